//! Solves a host code's reduced problem with every algorithm of the local layer and prints
//! the iterations and the reactions.

use contact_solver::{Algorithm, UzawaSettings, solve_coulomb};
use standalone_local::spring_chain;

fn main() -> Result<(), contact_solver::SolverError> {
    let n = 8;
    let d: Vec<f64> = (0..n).map(|i| 1e-3 * (1.0 + 0.1 * i as f64)).collect();
    let problem = spring_chain(n, 1e-4, 50.0, &d, 2e-3, 0.3)?;
    for algorithm in [
        Algorithm::Newton,
        Algorithm::AndersonGaussSeidel,
        Algorithm::GaussSeidel,
        Algorithm::Uzawa,
        Algorithm::ClassicRccm,
    ] {
        let settings = UzawaSettings::default()
            .with_algorithm(algorithm)
            .with_tol(1e-10);
        let sol = solve_coulomb(&problem, &settings)?;
        let rn: f64 = sol.r.iter().step_by(2).sum();
        let rt: f64 = sol.r.iter().skip(1).step_by(2).sum();
        println!(
            "{algorithm:?}: {} iterations, Σr_n = {rn:.9}, Σr_t = {rt:.9}",
            sol.report.iterations
        );
    }
    Ok(())
}
