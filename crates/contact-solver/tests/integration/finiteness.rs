//! Finiteness over random inputs (issue 15): any finite reduced problem, of any dimension and
//! magnitude, given to any algorithm, gives either an error of `SolverError` or an answer
//! whose every number is finite and that satisfies the Signorini–Coulomb conditions it claims
//! to have converged to. No panic, no NaN, no "converged" with a penetration.
//!
//! The problems are random SPD `W` (2D and 3D, 1–6 contacts) scaled by `10^a`, `a ∈ [−150,
//! 150]`, with `q` of mixed signs scaled by `10^b` (independently, so the answer's magnitude
//! ranges over 1e±300), `μ` from 0 to 1e6 (issue 14's range) and some `μ = 0` contacts; and raw
//! random matrices (most not SPD), which must be refused or solved. The check of a converged
//! answer is relative to `‖r‖∞` and `max(‖x‖∞, ‖q‖∞)`, with a tolerance of 1e-6: the stopping
//! tolerance 1e-10 amplified by `μ` (≤ 1e6 — the modified velocity multiplies the round-off of
//! `x_t` by `μ`) is the bound this suite may claim, not a sharper one.

use contact_solver::local::generate::random_problem_in;
use contact_solver::{Algorithm, ReducedProblem, UzawaSettings, UzawaSolver};
use proptest::prelude::*;

const ALGORITHMS: [Algorithm; 7] = [
    Algorithm::Auto,
    Algorithm::Newton,
    Algorithm::AndersonGaussSeidel,
    Algorithm::GaussSeidel,
    Algorithm::Uzawa,
    Algorithm::AndersonUzawa,
    Algorithm::ClassicRccm,
];

/// The largest violation of `r_n ≥ 0`, `x_n ≥ 0`, `‖r_t‖ ≤ μ r_n`, `r_n x_n = 0`, relative to
/// the answer's scales.
fn violation(p: &ReducedProblem, r: &[f64], x: &[f64]) -> f64 {
    let d = p.dimension();
    let max = |v: &[f64]| v.iter().fold(f64::MIN_POSITIVE, |a, b| a.max(b.abs()));
    let (rs, xs) = (max(r), max(x).max(max(p.q())));
    let mut worst = 0.0_f64;
    for (i, &mu) in p.mu().iter().enumerate() {
        let (rn, xn) = (r[d * i] / rs, x[d * i] / xs);
        let rt = r[d * i + 1..d * i + d]
            .iter()
            .map(|v| (v / rs) * (v / rs))
            .sum::<f64>()
            .sqrt();
        worst = worst
            .max(-rn)
            .max(-xn)
            .max(rn * xn)
            .max(rt - mu * rn.max(0.0));
    }
    worst
}

fn check(p: &ReducedProblem, algorithm: Algorithm) -> Result<(), TestCaseError> {
    let st = UzawaSettings::default()
        .with_algorithm(algorithm)
        .with_tol(1e-10)
        .with_max_iterations(5000);
    match UzawaSolver::new(st).solve(p, &p.coulomb_laws()) {
        Ok(sol) => {
            prop_assert!(
                sol.r.iter().chain(&sol.x).all(|v| v.is_finite()),
                "{algorithm:?}: non-finite answer {:?}",
                sol.r
            );
            prop_assert!(sol.report.converged, "{algorithm:?}: Ok but not converged");
            let v = violation(p, &sol.r, &sol.x);
            prop_assert!(v <= 1e-6, "{algorithm:?}: violation {v:e}");
        }
        // a typed error (not converged, stalled, refused magnitudes) is an allowed answer;
        // its message must say something
        Err(e) => prop_assert!(!e.to_string().is_empty()),
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn any_scaled_problem_gives_a_finite_answer_or_an_error(
        dim in 2usize..=3,
        nc in 1usize..=6,
        seed in 0u64..10_000,
        a in -150i32..=150,
        b in -150i32..=150,
        log_mu in proptest::collection::vec(-3.0f64..6.0, 6),
        frictionless in proptest::collection::vec(any::<bool>(), 6),
    ) {
        let base = random_problem_in(dim, nc, seed);
        let (sw, sq) = (10f64.powi(a), 10f64.powi(b));
        let w = base.w_dense().expect("a dense generator").iter().map(|v| v * sw).collect();
        let q = base.q().iter().map(|v| v * sq).collect();
        let mu = (0..nc)
            .map(|i| if frictionless[i] { 0.0 } else { 10f64.powf(log_mu[i]) })
            .collect();
        let p = ReducedProblem::with_dimension(dim, w, q, mu).unwrap();
        for algorithm in ALGORITHMS {
            check(&p, algorithm)?;
        }
    }

    #[test]
    fn any_finite_matrix_is_refused_or_solved(
        dim in 2usize..=3,
        nc in 1usize..=4,
        entries in proptest::collection::vec(-1e3f64..1e3, 144),
        q in proptest::collection::vec(-1e3f64..1e3, 12),
        mu in 0.0f64..10.0,
        symmetric in any::<bool>(),
    ) {
        let m = dim * nc;
        let mut w: Vec<f64> = entries[..m * m].to_vec();
        if symmetric {
            for i in 0..m {
                for j in 0..i {
                    w[i * m + j] = w[j * m + i];
                }
            }
        }
        if let Ok(p) = ReducedProblem::with_dimension(dim, w, q[..m].to_vec(), vec![mu; nc]) {
            for algorithm in ALGORITHMS {
                check(&p, algorithm)?;
            }
        }
    }
}
