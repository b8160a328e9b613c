//! Seed 5.6.1: delamination of a thin aluminium layer, with both algorithms; prints the
//! iteration table of seed table 5.1 (β iterations, contact iterations and time per step at
//! steps 1, 10, 40, 60, 100, 150, 200, and the total time).
//!
//! `cargo run --release --example delamination [steps]`

use bipotential::contact_solver::scenes::DelaminationSpec;
use bipotential::contact_solver::{Algorithm, SimulationSettings, StepReport};
use std::time::Instant;

fn run(algorithm: Algorithm, steps: usize) -> Result<(Vec<StepReport>, f64), Box<dyn std::error::Error>> {
    let mut settings = SimulationSettings::default();
    settings.solver.algorithm = algorithm;
    let spec = DelaminationSpec { steps, ..DelaminationSpec::default() };
    let mut scene = spec.build(settings)?;
    let start = Instant::now();
    let mut reports = Vec::with_capacity(steps);
    for k in 1..=steps {
        reports.push(scene.step(k)?.report);
    }
    Ok((reports, start.elapsed().as_secs_f64()))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let steps: usize = std::env::args().nth(1).map(|s| s.parse()).transpose()?.unwrap_or(210);
    println!("| algorithm | step | β iterations | contact iterations | time per step (ms) |");
    println!("|---|---|---|---|---|");
    for (name, algorithm) in [("bipotential (GS)", Algorithm::GaussSeidel), ("bipotential (Uzawa)", Algorithm::Uzawa), ("classic RCCM", Algorithm::ClassicRccm)] {
        let (reports, total) = run(algorithm, steps)?;
        for &k in &[1, 10, 40, 60, 100, 150, 200] {
            if let Some(r) = reports.get(k - 1) {
                println!(
                    "| {name} | {k} | {} | {} | {:.2} |",
                    r.adhesion_iterations,
                    r.contact_iterations,
                    r.wall_time.as_secs_f64() * 1e3
                );
            }
        }
        let adh: usize = reports.iter().map(|r| r.adhesion_iterations).sum();
        let con: usize = reports.iter().map(|r| r.contact_iterations).sum();
        println!("| {name} | total | {adh} | {con} | {:.1} (total {total:.3} s) |", total * 1e3 / steps as f64);
    }
    Ok(())
}
