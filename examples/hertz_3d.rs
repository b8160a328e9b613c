//! A rigid ball pressed into an elastic block, in 3D (quarter model, P2 tetrahedra), against
//! Hertz: the contact radius and the force inside half of it, for the measured total force.
//! The same problem as `tools/peers/getfem_hertz3d.py` (GetFEM), grid for grid.
//!
//! Run: `cargo run --release --example hertz_3d -- 0 1` (refinement levels: each halves every
//! cell of the graded base grid); `--matrix-free`, `--active-set` or `--dense` chooses the
//! reduced problem's path (default: the settings' `Auto`). `BIPO_QUICK=1` runs level 0 alone.
//! Ends in an error when Hertz's radius is not between the farthest closed and the nearest
//! open node, or the force inside `a_H/2` misses Hertz's by more than 10 %.
//!
//! Block `[0, 4]² × [−4, 0]`, grid lines fine (0.15) up to 0.9 in x, y and 0.6 in depth, then
//! geometric to 4; ball R = 10 centred at (0, 0, R); E = 1000, ν = 0.3; bottom pushed up by
//! d = 0.04; symmetry on x = 0 and y = 0; frictionless.

use bipotential::contact_laws::Signorini;
use bipotential::contact_solver::FlexibilityMode;
use bipotential::contact_solver::coupling::solid::{
    ContactZone3, RigidSphere, Side3, SolidContactSimulation, SolidSettings,
};
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
    let mut settings = SolidSettings::default();
    if args.iter().any(|a| a == "--matrix-free") {
        settings.flexibility = FlexibilityMode::MatrixFree;
    } else if args.iter().any(|a| a == "--active-set") {
        settings.flexibility = FlexibilityMode::ActiveSet;
    } else if args.iter().any(|a| a == "--dense") {
        settings.flexibility = FlexibilityMode::Dense;
    }
    let levels: Vec<usize> = args
        .iter()
        .filter(|a| !a.starts_with("--"))
        .map(|a| a.parse())
        .collect::<Result<_, _>>()?;
    let levels = if !levels.is_empty() {
        levels
    } else if std::env::var_os("BIPO_QUICK").is_some_and(|v| v != "0") {
        vec![0]
    } else {
        vec![0, 1]
    };
    let mut misses = Vec::new();
    let (e, nu, radius, d) = (1000.0, 0.3, 10.0, 0.04);
    let e_star = e / (1.0 - nu * nu);
    println!(
        "| level | DOF | active contacts | P | a (farthest closed) | a (nearest open) | a_Hertz(P) | force inside a_H/2 / Hertz | build (s) | step (s) | iterations |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    for level in levels {
        let xy = refine(&graded(4.0, 6, 0.9, 4), level);
        let mut z: Vec<f64> = refine(&graded(4.0, 4, 0.6, 4), level)
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
        let p: f64 = 4.0 * res.contacts.iter().map(|c| c.r[0]).sum::<f64>();
        let a_h = (3.0 * p * radius / (4.0 * e_star)).cbrt();
        let (mut inside, mut outside) = (0.0_f64, f64::INFINITY);
        for (c, x) in res.contacts.iter().zip(&positions) {
            let r = x[0].hypot(x[1]);
            if c.r[0] > 1e-9 * p {
                inside = inside.max(r);
            } else if c.candidate.area > 0.0 && c.gap > 0.0 {
                outside = outside.min(r);
            }
        }
        let half: f64 = 4.0
            * res
                .contacts
                .iter()
                .zip(&positions)
                .filter(|(_, x)| x[0].hypot(x[1]) < 0.5 * a_h)
                .map(|(c, _)| c.r[0])
                .sum::<f64>();
        let hertz_half = p * (1.0 - 0.75_f64.powf(1.5));
        println!(
            "| {level} | {dofs} | {} | {p:.4} | {inside:.4} ({:+.2} %) | {outside:.4} | {a_h:.4} | {:.4} | {t_build:.2} | {t_step:.2} | {}{} |",
            res.active,
            100.0 * (inside / a_h - 1.0),
            half / hertz_half,
            res.contact_iterations,
            if res.matrix_free {
                " (matrix-free)".to_string()
            } else if res.active_set {
                format!(" (active set, {} factorisations)", res.factorizations)
            } else {
                String::new()
            }
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
