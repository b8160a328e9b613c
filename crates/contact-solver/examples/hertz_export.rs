//! Solves the plane-strain Hertz scene of `tests/integration/hertz.rs` (P2, fine zone of 8 × 8
//! cells, `a ≈ 1`) and writes its reduced problem and our reactions for the Siconos peer check.
//!
//! ```text
//! cargo run --release -p contact-solver --example hertz_export -- [OUT.json]
//! /usr/bin/python3 crates/contact-solver/examples/compare_siconos.py OUT.json OUT_ours.json
//! /usr/bin/python3 ../shared/peers/siconos_fc.py OUT.json --tol 1e-10     # every Siconos solver
//! ```
//! `OUT.json` (default `out/hertz_reduced.json`) is the reduced problem `x = W r + q` of the
//! step (`ContactSimulation::last_reduced_problem`), normal first per contact, `μ = 0`;
//! `OUT_ours.json` is `{"r": [...]}`, the law reactions `r̄` of the same contacts in the same
//! order (`ContactSimulation::last_active`). The example also re-solves the exported problem
//! with our Gauss–Seidel sweep and prints its iterations and wall time (median of 5) beside
//! Hertz's `a` and `p0`.

#[path = "../tests/support/hertz_scene.rs"]
mod hertz_scene;

use contact_solver::{SimulationSettings, UzawaSettings, UzawaSolver};
use fem_core::{ElementKind, Idealization};
use hertz_scene::HertzScene;
use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "out/hertz_reduced.json".to_string());
    let ours = match path.strip_suffix(".json") {
        Some(stem) => format!("{stem}_ours.json"),
        None => format!("{path}_ours.json"),
    };
    if let Some(dir) = std::path::Path::new(&path).parent()
        && !dir.as_os_str().is_empty()
    {
        std::fs::create_dir_all(dir)?;
    }

    let scene = HertzScene::new(Idealization::PlaneStrain, ElementKind::Tri6, 8);
    // the reduced problem is exported, so the step must build a dense F*
    let mut settings =
        SimulationSettings::default().with_flexibility(contact_solver::FlexibilityMode::Dense);
    settings.solver.tol = 1e-12; // so that our side of the comparison is well below 1e-8
    let start = Instant::now();
    let mut sim = scene.simulation(settings);
    let built = start.elapsed();
    let res = sim.step(1.0, 1.0)?;
    let stepped = start.elapsed() - built;
    let m = scene.measure(&sim, &res);
    println!(
        "Hertz plane strain, P2, {} nodes: P = {:.6e}, a = {:.5} (Hertz {:.5}, {:+.2e}), \
         p0 = {:.5} (Hertz {:.5}, {:+.2e})",
        sim.structure().mesh().node_count(),
        m.p_total,
        m.a_fe,
        m.a_hertz,
        m.a_error(),
        m.p0_fe,
        m.p0_hertz,
        m.p0_error()
    );
    println!(
        "model {:.1?}, step {:.1?} ({} active contacts, {} closed, {} sweeps, residual {:.1e})",
        built,
        stepped,
        res.report.active_contacts,
        m.closed,
        res.report.contact_iterations,
        res.report.residual
    );

    let problem = sim
        .last_reduced_problem()
        .ok_or("the step solved no reduced problem")?;
    std::fs::write(&path, problem.to_json()?)?;
    let r: Vec<f64> = sim
        .last_active()
        .iter()
        .flat_map(|&i| [res.contacts[i].r_bar.n, res.contacts[i].r_bar.t[0]])
        .collect();
    std::fs::write(
        &ours,
        serde_json::to_string(&serde_json::json!({ "r": r }))?,
    )?;
    println!(
        "wrote {path} ({} contacts) and {ours}",
        problem.contact_count()
    );

    // The same reduced problem alone, cold start, as Siconos sees it.
    let laws = problem.coulomb_laws();
    let mut solver = UzawaSolver::new(UzawaSettings::default().with_tol(1e-12));
    let mut times = Vec::new();
    let mut last = None;
    for _ in 0..5 {
        let t = Instant::now();
        let s = solver.solve(problem, &laws)?;
        times.push(t.elapsed().as_secs_f64() * 1e3);
        last = Some(s);
    }
    times.sort_by(f64::total_cmp);
    let s = last.ok_or("no run")?;
    let diff =
        s.r.iter()
            .zip(&r)
            .fold(0.0_f64, |a, (x, y)| a.max((x - y).abs()));
    println!(
        "reduced solve alone (Gauss-Seidel, tol 1e-12): {} sweeps, {:.3} ms (median of 5), \
         max |r - r_step| = {diff:.1e}",
        s.report.iterations, times[2]
    );
    Ok(())
}
