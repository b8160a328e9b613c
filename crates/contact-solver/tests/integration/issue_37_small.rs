//! Issue 37, seventh part: `Auto` on Siconos' small problems (`docs/benchmarks.md`, "Auto on
//! small problems"). On a small sparse symmetric `W` `Auto` now runs the classical solver
//! first within a budget of sweeps (`src/local/solver/classic_first.rs`; it was Newton, 1.6–4.4×
//! the classical solver's time on `FC3D_Example1`, `FrictionContactProblem00031/00394/00374`,
//! `Confeti-ex13-Fc3D-SBM`); on a dense `W` kept non-symmetric of at most 32 rows it runs
//! Newton without the sweep first (it swept first on the slider crank, 1.4× Newton); Newton's small systems on a
//! sparse `W` go to the in-crate dense LU (faer's sparse LU ordered and factorised
//! symbolically at every step). Compared in iterations and answers, never in time.
//!
//! Known answers are built as in `issue_37_auto_rule.rs`: pick `r*`, `x*` that satisfy
//! Coulomb's law per contact, any `W`, and set `q = x* − W r*`.

use contact_solver::local::generate::random_sparse_problem;
use contact_solver::{Algorithm, Asymmetry, ReducedProblem, UzawaSettings, UzawaSolver};

fn solve(p: &ReducedProblem, algorithm: Algorithm) -> contact_solver::Solution {
    let st = UzawaSettings::default()
        .with_algorithm(algorithm)
        .with_tol(1e-10);
    UzawaSolver::new(st)
        .solve(p, &p.coulomb_laws())
        .unwrap_or_else(|e| panic!("{algorithm:?}: {e}"))
}

/// Three uncoupled 2D contacts (a block-diagonal `W` stored sparse, as Siconos'
/// `FC3D_Example1` and `FrictionContactProblem00394` are): a slip, a stick and an open one,
/// each on the block `diag(2, 1)` (`FC3D_Example1`'s `W` is diagonal), μ = 0.3. Returns
/// the problem and `r*`.
fn uncoupled() -> (ReducedProblem, Vec<f64>) {
    let block = [[2.0, 0.0], [0.0, 1.0]];
    let mu = 0.3;
    // (r*, x*) per contact: slip (x_t > 0 against r_t = −μ r_n), stick, open
    let known = [
        ([1.0, -mu], [0.0, 0.4]),
        ([0.5, 0.05], [0.0, 0.0]),
        ([0.0, 0.0], [0.7, -0.2]),
    ];
    let (mut rows, mut cols, mut vals, mut q, mut r_star) =
        (vec![], vec![], vec![], vec![], vec![]);
    for (i, (r, x)) in known.iter().enumerate() {
        for (k, row) in block.iter().enumerate() {
            for (l, &v) in row.iter().enumerate().filter(|(_, v)| **v != 0.0) {
                rows.push(2 * i + k);
                cols.push(2 * i + l);
                vals.push(v);
            }
            q.push(x[k] - row.iter().zip(r).map(|(w, r)| w * r).sum::<f64>());
        }
        r_star.extend_from_slice(r);
    }
    let p = ReducedProblem::from_triplets(2, &rows, &cols, &vals, q, vec![mu; 3]).unwrap();
    (p, r_star)
}

/// On the uncoupled sparse problem `Auto` runs the classical solver (the old rule ran Newton)
/// and its run is the classical solver's alone, bit for bit and sweep for sweep; the answer is
/// the known one to 1e-9 (tolerance 1e-10 relative on answers of order 1, with margin).
#[test]
fn issue_37_auto_runs_the_classical_solver_first_on_small_sparse_problems() {
    let (p, r_star) = uncoupled();
    assert!(p.is_sparse() && p.is_symmetric());
    let auto = solve(&p, Algorithm::Auto);
    let classic = solve(&p, Algorithm::ClassicRccm);
    assert_eq!(auto.report.algorithm, Algorithm::ClassicRccm);
    assert_eq!(auto.report.fallback_from, None);
    assert_eq!(auto.report.iterations, classic.report.iterations);
    assert_eq!(auto.r, classic.r);
    for (got, want) in auto.r.iter().zip(&r_star) {
        assert!(
            (got - want).abs() <= 1e-9,
            "{:?} against {r_star:?}",
            auto.r
        );
    }
}

/// Where the classical solver does not converge within its budget (a strongly coupled random
/// sparse problem, 40 contacts in 3D) `Auto` runs Newton from the start as before: the same
/// answer as Newton alone, bit for bit, and Newton's iterations plus the classical sweeps
/// spent (at most `AUTO_CLASSIC_PROBE` = 200, at least 16), reported.
#[test]
fn issue_37_auto_runs_newton_after_a_slow_classical_start() {
    let p = random_sparse_problem(3, 40, 4, 5);
    assert!(p.is_sparse() && p.is_symmetric());
    let auto = solve(&p, Algorithm::Auto);
    let newton = solve(&p, Algorithm::Newton);
    assert_eq!(auto.report.algorithm, Algorithm::Newton);
    assert_eq!(auto.r, newton.r);
    let spent = auto.report.iterations - newton.report.iterations;
    assert!((16..=200).contains(&spent), "{spent}");
}

/// A dense 2-contact problem kept non-symmetric (like Siconos' slider crank and rovers), both
/// pressed, weakly coupled: the old rule swept first (8 accelerated sweeps) and, the sweep
/// having converged, returned the sweep; on a non-symmetric `W` of at most 32 rows `Auto` now
/// runs Newton at once, the same run as Newton alone bit for bit.
#[test]
fn issue_37_auto_runs_newton_at_once_on_a_tiny_non_symmetric_w() {
    let w = vec![
        2.0, 0.01, 0.02, 0.0, //
        0.0, 2.0, 0.0, 0.01, //
        0.01, 0.0, 2.0, 0.0, //
        0.0, 0.0, 0.01, 2.0,
    ];
    let (q, mu) = (vec![-1.0, 0.05, -0.5, -0.02], vec![0.3, 0.5]);
    let p = ReducedProblem::with_asymmetry(2, w, q, mu, Asymmetry::Keep).unwrap();
    assert!(!p.is_symmetric());
    let sweep = solve(&p, Algorithm::AndersonGaussSeidel);
    // the sweep converges within the old probe's 8 sweeps: the old rule kept it
    assert!(sweep.report.iterations <= 8, "{}", sweep.report.iterations);
    let auto = solve(&p, Algorithm::Auto);
    let newton = solve(&p, Algorithm::Newton);
    assert_eq!(auto.report.algorithm, Algorithm::Newton);
    assert_eq!(auto.report.iterations, newton.report.iterations);
    assert_eq!(auto.r, newton.r);
}

/// Newton on a small sparse `W` (its systems now solved dense) takes the iterations it takes
/// on the same `W` stored dense, and the answers agree to 1e-12 relative (the two LUs pivot
/// alike; round-off of a 24-row system, with margin).
#[test]
fn issue_37_small_sparse_newton_matches_dense_newton() {
    let sparse = random_sparse_problem(3, 8, 3, 11);
    let m = sparse.size();
    let mut w = vec![0.0; m * m];
    for (i, j, v) in sparse.w_sparse().unwrap().triplets() {
        w[i * m + j] = v;
    }
    let dense =
        ReducedProblem::with_dimension(3, w, sparse.q().to_vec(), sparse.mu().to_vec()).unwrap();
    let a = solve(&sparse, Algorithm::Newton);
    let b = solve(&dense, Algorithm::Newton);
    assert_eq!(a.report.iterations, b.report.iterations);
    let scale = b.r.iter().fold(0.0_f64, |s, v| s.max(v.abs()));
    for (x, y) in a.r.iter().zip(&b.r) {
        assert!((x - y).abs() <= 1e-12 * scale, "{x} against {y}");
    }
}
