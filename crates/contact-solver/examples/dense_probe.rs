//! Dense-path timing probe (issue 14): median wall time of every algorithm on seeded dense
//! random problems (2D and 3D, `n_c` = 300), to check that routing `W` through the storage
//! abstraction costs nothing on dense problems.
//!
//! ```text
//! cargo run --release -p contact-solver --example dense_probe -- [RUNS]
//! ```

use contact_solver::local::generate::random_problem_in;
use contact_solver::{Algorithm, UzawaSettings, UzawaSolver};
use std::time::Instant;

fn main() {
    faer::set_global_parallelism(faer::Par::Seq);
    let runs: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(7);
    let algorithms = [
        Algorithm::Uzawa,
        Algorithm::GaussSeidel,
        Algorithm::AndersonGaussSeidel,
        Algorithm::AndersonUzawa,
        Algorithm::ClassicRccm,
        Algorithm::Newton,
    ];
    for dim in [2, 3] {
        let p = random_problem_in(dim, 300, 1);
        let laws = p.coulomb_laws();
        for algorithm in algorithms {
            let settings = UzawaSettings::default()
                .with_algorithm(algorithm)
                .with_tol(1e-10);
            let mut solver = UzawaSolver::new(settings);
            let mut times = Vec::new();
            let mut iterations = 0;
            for _ in 0..runs {
                let t = Instant::now();
                let sol = solver.solve(&p, &laws).expect("converges");
                times.push(t.elapsed().as_secs_f64() * 1e3);
                iterations = sol.report.iterations;
            }
            times.sort_by(f64::total_cmp);
            println!(
                "dim {dim} n_c 300 {algorithm:?}: median {:.3} ms (min {:.3}), {iterations} iterations",
                times[runs / 2],
                times[0]
            );
        }
    }
}
