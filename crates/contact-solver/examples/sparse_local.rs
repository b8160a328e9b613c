//! Sparse `W` (issue 14): the same seeded block-sparse problem solved with `W` stored sparse
//! and dense (every algorithm), and a granular-size sparse problem (3D, 7000 contacts by
//! default) solved by `Algorithm::Auto`, with the memory of `W` in both storages. Median wall
//! time of `RUNS` solves (cold start, one thread).
//!
//! ```text
//! cargo run --release -p contact-solver --example sparse_local -- [RUNS] [N_C_LARGE]
//! ```

use contact_solver::local::generate::random_sparse_problem;
use contact_solver::{Algorithm, ReducedProblem, UzawaSettings, UzawaSolver};
use std::time::Instant;

/// Median time (ms) of `runs` solves, and the last report's iteration count.
fn time(p: &ReducedProblem, algorithm: Algorithm, tol: f64, runs: usize) -> (f64, usize, bool) {
    let settings = UzawaSettings::default()
        .with_algorithm(algorithm)
        .with_tol(tol);
    let mut solver = UzawaSolver::new(settings);
    let laws = p.coulomb_laws();
    let mut times = Vec::with_capacity(runs);
    let (mut iterations, mut converged) = (0, false);
    for _ in 0..runs {
        let t = Instant::now();
        let sol = solver.solve(p, &laws).expect("solves");
        times.push(t.elapsed().as_secs_f64() * 1e3);
        (iterations, converged) = (sol.report.iterations, sol.report.converged);
    }
    times.sort_by(f64::total_cmp);
    (times[runs / 2], iterations, converged)
}

fn main() {
    faer::set_global_parallelism(faer::Par::Seq);
    let mut args = std::env::args().skip(1);
    let runs: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(5);
    let n_large: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(7000);

    // 1. Same W, sparse and dense: 3D, 600 contacts (m = 1800), about 5 blocks per block row.
    let sparse = random_sparse_problem(3, 600, 4, 1);
    let a = sparse.w_sparse().expect("sparse");
    let m = sparse.size();
    let mut w = vec![0.0; m * m];
    for (i, j, v) in a.triplets() {
        w[i * m + j] = v;
    }
    let dense =
        ReducedProblem::with_dimension(3, w, sparse.q().to_vec(), sparse.mu().to_vec()).unwrap();
    println!(
        "same W, 3D n_c = 600 (m = {m}): {} stored entries ({:.1} % of m²); W: {:.2} MB sparse, {:.2} MB dense",
        a.stored(),
        100.0 * a.stored() as f64 / (m * m) as f64,
        sparse.w_storage_bytes() as f64 / 1e6,
        dense.w_storage_bytes() as f64 / 1e6
    );
    println!("| algorithm | iterations | dense (ms) | sparse (ms) | speed-up |");
    println!("|---|---|---|---|---|");
    for algorithm in [
        Algorithm::Uzawa,
        Algorithm::GaussSeidel,
        Algorithm::AndersonGaussSeidel,
        Algorithm::AndersonUzawa,
        Algorithm::ClassicRccm,
        Algorithm::Newton,
    ] {
        let (td, n, _) = time(&dense, algorithm, 1e-10, runs);
        let (ts, ns, _) = time(&sparse, algorithm, 1e-10, runs);
        assert_eq!(n, ns, "{algorithm:?}: same iterations");
        println!(
            "| {algorithm:?} | {n} | {td:.2} | {ts:.2} | {:.1}× |",
            td / ts
        );
    }

    // 2. Granular size: 3D, n_large contacts, Auto (the accelerated sweep).
    let t = Instant::now();
    let large = random_sparse_problem(3, n_large, 4, 2026);
    let build = t.elapsed().as_secs_f64() * 1e3;
    let m = large.size() as f64;
    let (tl, n, converged) = time(&large, Algorithm::Auto, 1e-8, runs);
    println!(
        "3D n_c = {n_large} (m = {m}): W {:.2} MB sparse ({} stored entries) against {:.0} MB dense; \
         built and validated in {build:.0} ms; Auto (AndersonGaussSeidel) to 1e-8: median {tl:.0} ms, \
         {n} iterations, converged {converged}",
        large.w_storage_bytes() as f64 / 1e6,
        large.w_sparse().unwrap().stored(),
        8.0 * m * m / 1e6
    );
}
