//! Writes seeded random reduced problems to JSON for the Siconos peer check, solves them with
//! both bipotential sweeps and several ρ scales (and with the classical RCCM solver), and prints
//! iterations and wall times.
//!
//! ```text
//! cargo run --release -p contact-solver --example export_random -- [OUT_DIR]
//! /usr/bin/python3 shared/peers/siconos_fc.py OUT_DIR/random_100.json --tol 1e-10
//! ```
//! For each problem it also writes `random_<n_c>.solution.json` with our `r` and `x`.

use contact_solver::local::generate::random_problem;
use contact_solver::{Algorithm, UzawaSettings, UzawaSolver};
use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "target/reduced_problems".to_string());
    std::fs::create_dir_all(&out)?;
    println!("n_c  algorithm    rho_scale  iters  residual   ms(median of 5)  |r|");
    for (nc, seed) in [(10, 1), (100, 3), (300, 5)] {
        let p = random_problem(nc, seed);
        std::fs::write(format!("{out}/random_{nc}.json"), p.to_json()?)?;
        let laws = p.coulomb_laws();
        for algorithm in [
            Algorithm::Uzawa,
            Algorithm::GaussSeidel,
            Algorithm::ClassicRccm,
        ] {
            // The classical solver has no ρ to scale: one run.
            let scales: &[f64] = if algorithm == Algorithm::ClassicRccm {
                &[1.0]
            } else {
                &[1e-3, 1.0, 1e3]
            };
            for &rho_scale in scales {
                let mut solver = UzawaSolver::new(
                    UzawaSettings::default()
                        .with_algorithm(algorithm)
                        .with_rho_scale(rho_scale)
                        .with_max_iterations(100_000),
                );
                let mut times = Vec::new();
                let mut last = None;
                for _ in 0..5 {
                    let t = Instant::now();
                    let s = solver.solve(&p, &laws)?;
                    times.push(t.elapsed().as_secs_f64() * 1e3);
                    last = Some(s);
                }
                times.sort_by(f64::total_cmp);
                let s = last.ok_or("no run")?;
                let r_norm = s.r.iter().map(|a| a * a).sum::<f64>().sqrt();
                println!(
                    "{nc:4} {algorithm:12?} {rho_scale:9.0e} {:6} {:9.2e} {:12.3} {r_norm:.12e}",
                    s.report.iterations, s.report.residual, times[2]
                );
                if algorithm == Algorithm::GaussSeidel && rho_scale == 1.0 {
                    let json = format!("{{\"r\":{:?},\"x\":{:?}}}", s.r, s.x);
                    std::fs::write(format!("{out}/random_{nc}.solution.json"), json)?;
                }
            }
        }
    }
    Ok(())
}
