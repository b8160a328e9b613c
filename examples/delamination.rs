//! Seed 5.6.1: delamination of a thin aluminium layer glued on a rigid support and lifted at
//! point A (top right corner) by `u_y = 0.3 mm` in 10 s (and in 1 s for the rate study).
//!
//! Writes under `out/delamination/`: deformed shapes, β / opening / slip along the interface
//! at t = 3.571 s and 5.143 s for both algorithms, β(t) at interface points 1 and 2, β and the
//! adhesive normal reaction at point B against the imposed displacement for both loading
//! rates (seed figs 5.7–5.13), as CSV and SVG; and `table_5_1.md`, the seed's iteration table
//! measured on this machine.
//!
//! Both algorithms run in the seed's fixed point on β (`bipo::presets::seed::table_settings`),
//! and their answers must agree (max |Δr| / max |r| and max |Δβ| at most 1e-6, else an error).
//!
//! `cargo run --release --example delamination [steps]` (default 210, the seed's; 21 with
//! `BIPO_QUICK=1`).

#[path = "common/mod.rs"]
mod common;

use bipo::presets::seed::table_settings;
use bipo::presets::{DelaminationSpec, Scene};
use bipotential::contact_solver::{Algorithm, StepResult};
use common::{Series, check, line_plot, max_difference, write_series_csv};
use std::error::Error;
use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

struct Run {
    results: Vec<StepResult>,
    /// Nodal displacements at the snapshot steps.
    shapes: Vec<(usize, Vec<[f64; 2]>)>,
    total_seconds: f64,
}

fn run(
    spec: &DelaminationSpec,
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

/// Interface records of a step sorted by x.
fn along(res: &StepResult) -> Vec<&bipotential::contact_solver::ContactRecord> {
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
    let out = PathBuf::from("out/delamination");
    std::fs::create_dir_all(&out)?;
    let spec = DelaminationSpec {
        steps,
        ..DelaminationSpec::default()
    };
    let step_at = |t: f64| ((t / spec.duration * steps as f64).round() as usize).clamp(1, steps);
    let (k1, k2) = (step_at(3.571), step_at(5.143));

    let (bip, scene) = run(&spec, Algorithm::GaussSeidel, &[k1, k2, steps])?;
    let (cla, _) = run(&spec, Algorithm::ClassicRccm, &[])?;
    // The two algorithms solve the same steps: their answers agree to the fixed point's β
    // tolerance (1e-8, `SimulationSettings::adhesion_tol`) with a margin.
    let (dr, db) = max_difference(&bip.results, &cla.results);
    check("max |Δr| / max |r|, bipotential against classic", dr, 1e-6)?;
    check("max |Δβ|, bipotential against classic", db, 1e-6)?;
    let fast_spec = DelaminationSpec {
        duration: 1.0,
        ..spec.clone()
    };
    let (fast, _) = run(&fast_spec, Algorithm::GaussSeidel, &[])?;

    // Interface points: 1 and 2 are the first two interface nodes from the lifted end, B the
    // third (our reading of seed fig. 5.6).
    let first = along(&bip.results[0]);
    let n_if = first.len();
    let (p1, p2, pb) = (
        first[n_if - 1].node,
        first[n_if - 2].node,
        first[n_if - 3].node,
    );

    // Deformed shapes (fig 5.7): top and bottom lines of the layer, displacements × 1.
    let mesh = scene.simulation.structure().mesh();
    let mut shape_series = Vec::new();
    for (k, u) in &bip.shapes {
        for set in ["bottom", "top"] {
            let mut nodes = mesh.node_set(set)?.to_vec();
            nodes.sort_by(|a, b| mesh.nodes()[*a][0].total_cmp(&mesh.nodes()[*b][0]));
            let pts = nodes
                .iter()
                .map(|&n| (mesh.nodes()[n][0] + u[n][0], mesh.nodes()[n][1] + u[n][1]))
                .collect();
            shape_series.push(Series::new(
                format!(
                    "{set}, t = {:.3} s",
                    spec.duration * *k as f64 / steps as f64
                ),
                pts,
            ));
        }
    }
    write_series_csv(&out.join("deformed.csv"), "x_mm", "y_mm", &shape_series)?;
    line_plot(
        &out.join("deformed.svg"),
        "Deformed layer (fig. 5.7)",
        "x (mm)",
        "y (mm)",
        &shape_series,
    )?;

    // Along the interface at t1, t2 for both algorithms (figs 5.8–5.10).
    type Field = fn(&bipotential::contact_solver::ContactRecord) -> f64;
    let fields: [(&str, &str, Field); 3] = [
        ("beta", "β", |c| c.beta),
        ("opening", "u_n (mm)", |c| c.gap),
        ("slip", "u_t (mm)", |c| c.u_t),
    ];
    for (file, label, f) in fields {
        let mut series = Vec::new();
        for (name, r) in [("bipotential", &bip), ("classic RCCM", &cla)] {
            for k in [k1, k2] {
                let t = spec.duration * k as f64 / steps as f64;
                let pts = along(&r.results[k - 1])
                    .iter()
                    .map(|c| (c.position[0], f(c)))
                    .collect();
                series.push(Series::new(format!("{name}, t = {t:.3} s"), pts));
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

    // β(t) at points 1 and 2 (fig 5.11).
    let history =
        |r: &Run, node: usize, f: Field, x_of: &dyn Fn(&StepResult) -> f64| -> Vec<(f64, f64)> {
            r.results
                .iter()
                .map(|s| {
                    (
                        x_of(s),
                        f(s.contacts.iter().find(|c| c.node == node).unwrap()),
                    )
                })
                .collect()
        };
    let time = |s: &StepResult| s.report.time;
    let beta12 = vec![
        Series::new("point 1", history(&bip, p1, |c| c.beta, &time)),
        Series::new("point 2", history(&bip, p2, |c| c.beta, &time)),
    ];
    write_series_csv(&out.join("beta_points_1_2.csv"), "t_s", "beta", &beta12)?;
    line_plot(
        &out.join("beta_points_1_2.svg"),
        "β at interface points 1 and 2 (fig. 5.11)",
        "t (s)",
        "β",
        &beta12,
    )?;

    // Rate effect at point B (figs 5.12–5.13): against the imposed displacement.
    let imposed = |spec: &DelaminationSpec| {
        let (lift, duration) = (spec.lift, spec.duration);
        move |s: &StepResult| lift * s.report.time / duration
    };
    let (d_slow, d_fast) = (imposed(&spec), imposed(&fast_spec));
    let beta_b = vec![
        Series::new("0.3 mm in 10 s", history(&bip, pb, |c| c.beta, &d_slow)),
        Series::new("0.3 mm in 1 s", history(&fast, pb, |c| c.beta, &d_fast)),
    ];
    let radh_b = vec![
        Series::new("0.3 mm in 10 s", history(&bip, pb, |c| -c.r_adh.n, &d_slow)),
        Series::new("0.3 mm in 1 s", history(&fast, pb, |c| -c.r_adh.n, &d_fast)),
    ];
    write_series_csv(&out.join("beta_point_b.csv"), "u_y_mm", "beta", &beta_b)?;
    write_series_csv(
        &out.join("adhesive_reaction_point_b.csv"),
        "u_y_mm",
        "minus_r_adh_n_N",
        &radh_b,
    )?;
    line_plot(
        &out.join("beta_point_b.svg"),
        "β at point B (fig. 5.12)",
        "imposed u_y (mm)",
        "β",
        &beta_b,
    )?;
    line_plot(
        &out.join("adhesive_reaction_point_b.svg"),
        "Adhesive normal reaction at B (fig. 5.13)",
        "imposed u_y (mm)",
        "−r_adh,n (N per mm)",
        &radh_b,
    )?;

    // Table 5.1 on this machine.
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
        let (a, b) = (&bip.results[k - 1].report, &cla.results[k - 1].report);
        writeln!(
            md,
            "| {k} | {} | {} | {:.2} | {} | {} | {:.2} |",
            a.adhesion_iterations,
            a.contact_iterations,
            a.wall_time.as_secs_f64() * 1e3,
            b.adhesion_iterations,
            b.contact_iterations,
            b.wall_time.as_secs_f64() * 1e3
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
    std::fs::write(out.join("table_5_1.md"), &md)?;
    print!("{md}");
    let last = along(bip.results.last().unwrap());
    let debonded = last.iter().filter(|c| c.beta < 1e-3).count();
    println!(
        "\n{steps} steps; at the end {debonded} of {n_if} interface nodes debonded (β < 1e-3); \
         bipotential against classic: max |Δr| / max |r| = {dr:.1e}, max |Δβ| = {db:.1e}; \
         outputs in {}",
        out.display()
    );
    Ok(())
}
