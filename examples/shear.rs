//! Seed 5.6.2: shear of a compressed aluminium block adhering to a rigid plane: the top face
//! is pressed by `u_y = −0.5 mm` and the left face pushed by `u_x = 20 mm`, both linearly in
//! 10 s.
//!
//! Writes under `out/shear/`: deformed shapes; opening, slip and β along the interface at
//! t = 2.143, 3.143 and 3.571 s for both algorithms; adhesive, contact and total reactions at
//! point A over the loading (seed figs 5.15–5.21), as CSV and SVG; and `table_5_2.md`.
//!
//! Both algorithms run in the seed's fixed point on β (`bipo::presets::seed::table_settings`),
//! and their answers must agree (max |Δr| / max |r| and max |Δβ| at most 1e-6, else an error).
//!
//! `cargo run --release --example shear [steps]` (default 210, the seed's; 21 with
//! `BIPO_QUICK=1`).

#[path = "common/mod.rs"]
mod common;

use bipo::presets::seed::table_settings;
use bipo::presets::{Scene, ShearSpec};
use bipotential::contact_solver::{Algorithm, ContactRecord, StepResult};
use common::{Series, check, line_plot, max_difference, write_series_csv};
use std::error::Error;
use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

struct Run {
    results: Vec<StepResult>,
    shapes: Vec<(usize, Vec<[f64; 2]>)>,
    total_seconds: f64,
}

fn run(
    spec: &ShearSpec,
    algorithm: Algorithm,
    snapshots: &[usize],
) -> Result<(Run, Scene), Box<dyn Error>> {
    let mut scene = spec.build(table_settings(algorithm))?;
    let mut results = Vec::with_capacity(spec.steps);
    let mut shapes = Vec::new();
    let start = Instant::now();
    for k in 1..=spec.steps {
        results.push(scene.step(k)?);
        if snapshots.contains(&k) {
            shapes.push((k, scene.simulation.nodal_displacements()));
        }
    }
    let total_seconds = start.elapsed().as_secs_f64();
    Ok((
        Run {
            results,
            shapes,
            total_seconds,
        },
        scene,
    ))
}

fn along(res: &StepResult) -> Vec<&ContactRecord> {
    let mut v: Vec<_> = res.contacts.iter().collect();
    v.sort_by(|a, b| a.position[0].total_cmp(&b.position[0]));
    v
}

fn main() -> Result<(), Box<dyn Error>> {
    let steps: usize = std::env::args()
        .nth(1)
        .map(|s| s.parse())
        .transpose()?
        .unwrap_or(if common::quick() { 21 } else { 210 });
    let out = PathBuf::from("out/shear");
    std::fs::create_dir_all(&out)?;
    let spec = ShearSpec {
        steps,
        ..ShearSpec::default()
    };
    let step_at = |t: f64| ((t / spec.duration * steps as f64).round() as usize).clamp(1, steps);
    let snaps: Vec<usize> = [2.143, 3.143, 3.571].iter().map(|&t| step_at(t)).collect();

    let (bip, scene) = run(&spec, Algorithm::GaussSeidel, &snaps)?;
    let (cla, _) = run(&spec, Algorithm::ClassicRccm, &[])?;
    // The two algorithms solve the same steps: their answers agree to the fixed point's β
    // tolerance (1e-8, `SimulationSettings::adhesion_tol`) with a margin (measured: ~1e-9).
    let (dr, db) = max_difference(&bip.results, &cla.results);
    check("max |Δr| / max |r|, bipotential against classic", dr, 1e-6)?;
    check("max |Δβ|, bipotential against classic", db, 1e-6)?;
    let t_of = |k: usize| spec.duration * k as f64 / steps as f64;

    // Deformed outline (fig 5.15): the four sides, displacements × 1.
    let mesh = scene.simulation.structure().mesh();
    let mut shape_series = Vec::new();
    for (k, u) in &bip.shapes {
        let mut pts = Vec::new();
        for (set, sort_x, reverse) in [
            ("bottom", true, false),
            ("right", false, false),
            ("top", true, true),
            ("left", false, true),
        ] {
            let mut nodes = mesh.node_set(set)?.to_vec();
            let c = if sort_x { 0 } else { 1 };
            nodes.sort_by(|a, b| mesh.nodes()[*a][c].total_cmp(&mesh.nodes()[*b][c]));
            if reverse {
                nodes.reverse();
            }
            pts.extend(
                nodes
                    .iter()
                    .map(|&n| (mesh.nodes()[n][0] + u[n][0], mesh.nodes()[n][1] + u[n][1])),
            );
        }
        shape_series.push(Series::new(format!("t = {:.3} s", t_of(*k)), pts));
    }
    write_series_csv(&out.join("deformed.csv"), "x_mm", "y_mm", &shape_series)?;
    line_plot(
        &out.join("deformed.svg"),
        "Deformed block (fig. 5.15)",
        "x (mm)",
        "y (mm)",
        &shape_series,
    )?;

    // Along the interface (figs 5.16–5.18).
    type Field = fn(&ContactRecord) -> f64;
    let fields: [(&str, &str, Field); 3] = [
        ("opening", "u_n (mm)", |c| c.gap),
        ("slip", "u_t (mm)", |c| c.u_t),
        ("beta", "β", |c| c.beta),
    ];
    for (file, label, f) in fields {
        let mut series = Vec::new();
        for (name, r) in [("bipotential", &bip), ("classic RCCM", &cla)] {
            for &k in &snaps {
                let pts = along(&r.results[k - 1])
                    .iter()
                    .map(|c| (c.position[0], f(c)))
                    .collect();
                series.push(Series::new(format!("{name}, t = {:.3} s", t_of(k)), pts));
            }
        }
        write_series_csv(
            &out.join(format!("interface_{file}.csv")),
            "x_mm",
            file,
            &series,
        )?;
        line_plot(
            &out.join(format!("interface_{file}.svg")),
            &format!("{label} along the interface"),
            "x (mm)",
            label,
            &series,
        )?;
    }

    // Reactions at point A (figs 5.19–5.21): adhesive, contact (r̄) and total, normal and
    // tangential, over time.
    let a = scene.point_a;
    let at_a = |s: &StepResult| *s.contacts.iter().find(|c| c.node == a).unwrap();
    let mut reactions = Vec::new();
    for (comp, label) in [(0, "normal"), (1, "tangential")] {
        for (what, f) in [("adhesive", 0), ("contact", 1), ("total", 2)] {
            let pts = bip
                .results
                .iter()
                .map(|s| {
                    let c = at_a(s);
                    let v = match f {
                        0 => [c.r_adh.n, c.r_adh.t[0]][comp],
                        1 => [c.r_bar.n, c.r_bar.t[0]][comp],
                        _ => [c.r.n, c.r.t[0]][comp],
                    };
                    (s.report.time, v)
                })
                .collect();
            reactions.push(Series::new(format!("{what} {label}"), pts));
        }
    }
    write_series_csv(
        &out.join("reactions_point_a.csv"),
        "t_s",
        "reaction_N_per_mm",
        &reactions,
    )?;
    line_plot(
        &out.join("reactions_point_a_normal.svg"),
        "Normal reactions at A (figs 5.19–5.21)",
        "t (s)",
        "r_n (N per mm)",
        &reactions[..3],
    )?;
    line_plot(
        &out.join("reactions_point_a_tangential.svg"),
        "Tangential reactions at A",
        "t (s)",
        "r_t (N per mm)",
        &reactions[3..],
    )?;

    // Table 5.2 on this machine.
    let mut md = String::new();
    writeln!(
        md,
        "| step | β iterations (bipotential) | contact iterations (bipotential) | time/step ms (bipotential) | β iterations (classic) | contact iterations (classic) | time/step ms (classic) |"
    )?;
    writeln!(md, "|---|---|---|---|---|---|---|")?;
    for k in [1, 10, 40, 60, 100, 150, 200]
        .into_iter()
        .filter(|&k| k <= steps)
    {
        let (x, y) = (&bip.results[k - 1].report, &cla.results[k - 1].report);
        writeln!(
            md,
            "| {k} | {} | {} | {:.2} | {} | {} | {:.2} |",
            x.adhesion_iterations,
            x.contact_iterations,
            x.wall_time.as_secs_f64() * 1e3,
            y.adhesion_iterations,
            y.contact_iterations,
            y.wall_time.as_secs_f64() * 1e3
        )?;
    }
    let sum = |r: &Run, f: fn(&StepResult) -> usize| r.results.iter().map(f).sum::<usize>();
    writeln!(
        md,
        "| total | {} | {} | {:.3} s | {} | {} | {:.3} s |",
        sum(&bip, |s| s.report.adhesion_iterations),
        sum(&bip, |s| s.report.contact_iterations),
        bip.total_seconds,
        sum(&cla, |s| s.report.adhesion_iterations),
        sum(&cla, |s| s.report.contact_iterations),
        cla.total_seconds
    )?;
    std::fs::write(out.join("table_5_2.md"), &md)?;
    print!("{md}");
    let last = along(bip.results.last().unwrap());
    let debonded = last.iter().filter(|c| c.beta < 1e-3).count();
    println!(
        "\n{steps} steps; at the end {debonded} of {} interface nodes debonded; bipotential \
         against classic: max |Δr| / max |r| = {dr:.1e}, max |Δβ| = {db:.1e}; outputs in {}",
        last.len(),
        out.display()
    );
    Ok(())
}
