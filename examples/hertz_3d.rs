//! A rigid ball pressed into an elastic block, in 3D (quarter model, P2 tetrahedra), against
//! Hertz: the contact radius and the force inside half of it, for the measured total force, and
//! the continuous pressure recovered from the reactions by the consistent mass of the top face
//! (`TractionField`): at the centre against `p0`, and its relative `L²` distance to the Hertz
//! ellipse over the contact disc `r < a`.
//! The same problem as `tools/peers/getfem_hertz3d.py` (GetFEM), grid for grid.
//!
//! Run: `cargo run --release --example hertz_3d -- 0 1` (refinement levels: each halves every
//! cell of the graded base grid); `--matrix-free`, `--active-set` or `--dense` chooses the
//! reduced problem's path (default: the settings' `Auto`; with `--matrix-free`, `--mf-window d`
//! sets the depth of its Anderson mixing, default 20, 0 for the momentum iteration); `--svg DIR` draws each level's
//! recovered pressure against the ellipse into `DIR/hertz_3d_pressure_<level>.svg`.
//! `--fine N` grades the base grid with `N` fine cells across the contact (6 by default; 10
//! gives ~1e5 DOF, the size of issue 38's check against GetFEM) and runs level 0 alone unless
//! levels are given. `BIPO_QUICK=1` runs level 0 alone. Ends in an error when Hertz's radius is not between the
//! farthest closed and the nearest open node, or the force inside `a_H/2` misses Hertz's by
//! more than 10 %.
//!
//! Block `[0, 4]² × [−4, 0]`, grid lines fine (0.15) up to 0.9 in x, y and 0.6 in depth, then
//! geometric to 4; ball R = 10 centred at (0, 0, R); E = 1000, ν = 0.3; bottom pushed up by
//! d = 0.04; symmetry on x = 0 and y = 0; frictionless.

use bipotential::contact_laws::Signorini;
use bipotential::contact_solver::coupling::solid::{
    ContactZone3, RigidSphere, Side3, SolidContactSimulation,
};
use bipotential::contact_solver::coupling::traction::TractionField;
use bipotential::contact_solver::{FlexibilityMode, SimulationSettings};
use bipotential::fem_core::boundary_mass::BoundaryMass;
use bipotential::fem_core::solid::generate::{box_mesh, lines};
use bipotential::fem_core::solid::{SolidKind, SolidModel};
use bipotential::fem_core::{Component, Material, Structure, Supports};
use std::error::Error;
use std::time::Instant;

fn graded(l: f64, n_fine: usize, fine: f64, n_coarse: usize) -> Vec<f64> {
    let mut v = lines(0.0, fine, n_fine);
    let r = (l / fine).powf(1.0 / n_coarse as f64);
    for k in 1..=n_coarse {
        v.push(fine * r.powi(k as i32));
    }
    v
}

/// Inserts the midpoint of every interval, `times` times.
fn refine(v: &[f64], times: usize) -> Vec<f64> {
    let mut v = v.to_vec();
    for _ in 0..times {
        let mut out = vec![v[0]];
        for w in v.windows(2) {
            out.push(0.5 * (w[0] + w[1]));
            out.push(w[1]);
        }
        v = out;
    }
    v
}

fn main() -> Result<(), Box<dyn Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut settings = SimulationSettings::for_dimension::<3>();
    if args.iter().any(|a| a == "--matrix-free") {
        settings.flexibility = FlexibilityMode::MatrixFree;
        if let Some(i) = args.iter().position(|a| a == "--mf-window") {
            let depth = args.get(i + 1).ok_or("--mf-window needs a depth")?;
            settings = settings.with_matrix_free_window(depth.parse()?);
        }
    } else if args.iter().any(|a| a == "--active-set") {
        settings.flexibility = FlexibilityMode::ActiveSet;
    } else if args.iter().any(|a| a == "--dense") {
        settings.flexibility = FlexibilityMode::Dense;
    }
    let svg_dir = args
        .iter()
        .position(|a| a == "--svg")
        .and_then(|i| args.get(i + 1))
        .map(std::path::PathBuf::from);
    let fine: Option<usize> = args
        .iter()
        .position(|a| a == "--fine")
        .map(|i| {
            args.get(i + 1)
                .ok_or("--fine needs a cell count")
                .map(|v| v.parse())
        })
        .transpose()?
        .transpose()?;
    if fine.is_some_and(|n| n < 2) {
        return Err("--fine needs at least 2 fine cells".into());
    }
    let values: Vec<usize> = args
        .iter()
        .enumerate()
        .filter(|(i, a)| {
            !a.starts_with("--")
                && Some(std::path::Path::new(a)) != svg_dir.as_deref()
                && (*i == 0 || (args[i - 1] != "--fine" && args[i - 1] != "--mf-window"))
        })
        .map(|(_, a)| a.parse())
        .collect::<Result<_, _>>()?;
    let levels = if !values.is_empty() {
        values
    } else if fine.is_some() || std::env::var_os("BIPO_QUICK").is_some_and(|v| v != "0") {
        vec![0]
    } else {
        vec![0, 1]
    };
    let mut misses = Vec::new();
    let (e, nu, radius, d) = (1000.0, 0.3, 10.0, 0.04);
    let e_star = e / (1.0 - nu * nu);
    println!(
        "| level | DOF | active contacts | P | a (farthest closed) | a (nearest open) | a_Hertz(P) | force inside a_H/2 / Hertz | build (s) | step (s) | iterations | p(0) / p0 | L2 distance (r < a) |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for level in levels {
        // the base grid: `n` fine cells up to 0.9 in x, y, and `2n/3` fine cells to 0.6 in
        // depth and geometric ones beyond (n = 6 by default)
        let n = fine.unwrap_or(6);
        let m = (2 * n + 1) / 3;
        let xy = refine(&graded(4.0, n, 0.9, m), level);
        let mut z: Vec<f64> = refine(&graded(4.0, m, 0.6, m), level)
            .iter()
            .map(|v| -v)
            .collect();
        z.reverse();
        let t = Instant::now();
        let mesh = box_mesh(&xy, &xy, &z, SolidKind::Tet10)?;
        let mut s = Supports::new();
        s.fix(mesh.node_set("x0")?, Component::X)
            .fix(mesh.node_set("y0")?, Component::Y)
            .prescribe(mesh.node_set("z0")?, Component::Z, d)?;
        let (nodes, areas) = mesh.nodal_areas("z1")?;
        let positions: Vec<[f64; 3]> = nodes.iter().map(|&n| mesh.nodes()[n]).collect();
        let model = SolidModel::new(mesh, &[(0, Material::new(e, nu, 0.0)?)], s)?;
        let dofs = model.dof_count();
        let ball = RigidSphere::new([0.0, 0.0, radius], radius, Side3::Outside)?;
        let zone = ContactZone3::rigid("top", nodes, ball, Signorini, 0.0).with_areas(areas);
        let mut sim = SolidContactSimulation::new(model, vec![zone], settings)?;
        let t_build = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let res = sim.step(1.0, 1.0)?;
        let t_step = t.elapsed().as_secs_f64();
        // the path on stderr, so that the table on stdout stays as it was
        eprintln!(
            "level {level}: path {}; K {} stored entries, its factor {}",
            res.report.path,
            sim.structure().nnz(),
            sim.structure().factor_nnz()
        );
        let p: f64 = 4.0 * res.contacts.iter().map(|c| c.r.n).sum::<f64>();
        let a_h = (3.0 * p * radius / (4.0 * e_star)).cbrt();
        let (mut inside, mut outside) = (0.0_f64, f64::INFINITY);
        for (c, x) in res.contacts.iter().zip(&positions) {
            let r = x[0].hypot(x[1]);
            if c.r.n > 1e-9 * p {
                inside = inside.max(r);
            } else if c.area > 0.0 && c.gap > 0.0 {
                outside = outside.min(r);
            }
        }
        let half: f64 = 4.0
            * res
                .contacts
                .iter()
                .zip(&positions)
                .filter(|(_, x)| x[0].hypot(x[1]) < 0.5 * a_h)
                .map(|(c, _)| c.r.n)
                .sum::<f64>();
        let hertz_half = p * (1.0 - 0.75_f64.powf(1.5));
        // the pressure field: M p = r_n on the top face, against p0 √(1 − r²/a²)
        let mesh = sim.structure().mesh();
        let mass = BoundaryMass::from_faces(mesh, mesh.face_set("z1")?)?;
        let field = TractionField::from_records(&mass, 0, &res.contacts)?;
        let p0 = 3.0 * p / (2.0 * std::f64::consts::PI * a_h * a_h);
        let ellipse = |r: f64| p0 * (1.0 - (r / a_h).powi(2)).max(0.0).sqrt();
        // the node at the first point of contact, the origin
        let at_origin = |n: &usize| mesh.nodes()[*n].iter().map(|c| c * c).sum::<f64>();
        let origin = field
            .nodes
            .iter()
            .min_by(|a, b| at_origin(a).total_cmp(&at_origin(b)));
        let centre = origin.and_then(|&n| field.at(n)).map_or(f64::NAN, |v| v.0) / p0;
        let disc = |x: [f64; 3]| x[0].hypot(x[1]) < a_h;
        let err = mass.integrate(&field.pressure, |x, v| {
            if disc(x) {
                (v - ellipse(x[0].hypot(x[1]))).powi(2)
            } else {
                0.0
            }
        });
        let norm = mass.integrate(&field.pressure, |x, _| {
            if disc(x) {
                ellipse(x[0].hypot(x[1])).powi(2)
            } else {
                0.0
            }
        });
        let l2 = (err / norm).sqrt();
        if let Some(dir) = &svg_dir {
            let profile: Vec<(f64, f64)> = field
                .nodes
                .iter()
                .zip(&field.pressure)
                .map(|(&n, &v)| (mesh.nodes()[n][0].hypot(mesh.nodes()[n][1]), v))
                .filter(|(r, _)| *r < 2.0 * a_h)
                .collect();
            let path = dir.join(format!("hertz_3d_pressure_{level}.svg"));
            plot_pressure(&path, level, a_h, &ellipse, &profile)?;
        }
        println!(
            "| {level} | {dofs} | {} | {p:.4} | {inside:.4} ({:+.2} %) | {outside:.4} | {a_h:.4} | {:.4} | {t_build:.2} | {t_step:.2} | {}{} | {centre:.4} | {:.2} % |",
            res.report.active_contacts,
            100.0 * (inside / a_h - 1.0),
            half / hertz_half,
            res.report.contact_iterations,
            if res.report.matrix_free {
                let products = sim.counters().operator_applications;
                format!(" (matrix-free, {products} products)")
            } else if res.report.active_set {
                let factorizations = sim.counters().active_set_factorizations;
                format!(" (active set, {factorizations} factorisations)")
            } else {
                String::new()
            },
            100.0 * l2
        );
        // Hertz's radius lies between the farthest closed node and the nearest open one (1 %
        // slack for the force's own discretisation); the force inside a_H/2 within 10 % of
        // Hertz's (measured +5.6 % on level 0, the coarsest: 4-5 nodes across a_H/2)
        if a_h < 0.99 * inside || a_h > 1.01 * outside || (half / hertz_half - 1.0).abs() > 0.1 {
            misses.push(format!(
                "level {level}: a_H {a_h:.4} outside [{inside:.4}, {outside:.4}] or force                  inside a_H/2 {:.4} of Hertz's",
                half / hertz_half
            ));
        }
    }
    if !misses.is_empty() {
        return Err(misses.join("; ").into());
    }
    Ok(())
}

/// The recovered pressure at the top face's nodes (dots) against the Hertz ellipse (line).
fn plot_pressure(
    path: &std::path::Path,
    level: usize,
    a: f64,
    ellipse: &dyn Fn(f64) -> f64,
    nodes: &[(f64, f64)],
) -> Result<(), Box<dyn Error>> {
    use plotters::prelude::*;
    let root = SVGBackend::new(path, (800, 500)).into_drawing_area();
    root.fill(&WHITE)?;
    let top = nodes.iter().map(|p| p.1).fold(ellipse(0.0), f64::max) * 1.1;
    let low = nodes.iter().map(|p| p.1).fold(0.0, f64::min) * 1.1;
    let mut chart = ChartBuilder::on(&root)
        .caption(
            format!("hertz_3d level {level}: recovered pressure against Hertz"),
            ("sans-serif", 20),
        )
        .margin(15)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(0.0..2.0 * a, low..top)?;
    chart
        .configure_mesh()
        .x_desc("r = √(x² + y²)")
        .y_desc("p")
        .draw()?;
    let blue = RGBColor(31, 119, 180);
    let red = RGBColor(214, 39, 40);
    chart
        .draw_series(nodes.iter().map(|&p| Circle::new(p, 3, blue.filled())))?
        .label("M p = r_n (nodes)")
        .legend(move |(x, y)| Circle::new((x + 10, y), 3, blue.filled()));
    let curve = (0..=200).map(|k| {
        let r = 2.0 * a * f64::from(k) / 200.0;
        (r, ellipse(r))
    });
    chart
        .draw_series(LineSeries::new(curve, red.stroke_width(2)))?
        .label("Hertz p0 √(1 − r²/a²)")
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], red.stroke_width(2)));
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()?;
    root.present()?;
    Ok(())
}
