//! Sparse `W` (issue 14, "Storage"): a problem stored in compressed rows solves exactly as the
//! same problem stored dense, with every algorithm; bad triplets are typed errors; the JSON
//! triplets round-trip; a 7000-contact 3D granular-size problem is solved in memory far below
//! the dense `8 m²` bytes.
//!
//! Source: the seeded block-sparse generator `generate::random_sparse_problem`
//! (`W = Σ_e B_eᵀ B_e + δ I`, a multibody Delassus operator's structure, Acary–Brogliato 2008
//! §13.4), and its dense twin built entry by entry from the stored triplets.
//!
//! Tolerances: sparse and dense run the same algorithm with the same arithmetic in the same
//! order on the stored columns (the sparse rows are iterated with columns ascending, the d rows
//! of a contact share one column list, and the entries the dense loops add beyond the pattern
//! are exact zeros), so the iterations and the reactions are *bit-identical*; the test asserts
//! equal iteration counts, `‖r_sparse − r_dense‖ ≤ 1e-12 ‖r_dense‖` (the issue's bound) and,
//! stronger, equal bits (observed) — any change of order in a sparse loop that is not
//! round-off-neutral shows up as a different iteration count or a difference above 1e-12
//! after the hundreds of sweeps of the plain algorithms. The large solve runs to `tol = 1e-8`.

use contact_solver::local::generate::random_sparse_problem;
use contact_solver::{
    Algorithm, ReducedProblem, Solution, SolverError, UzawaSettings, UzawaSolver,
};

const ALGORITHMS: [Algorithm; 7] = [
    Algorithm::Uzawa,
    Algorithm::GaussSeidel,
    Algorithm::AndersonGaussSeidel,
    Algorithm::AndersonUzawa,
    Algorithm::ClassicRccm,
    Algorithm::Newton,
    Algorithm::Auto,
];

fn solve(p: &ReducedProblem, algorithm: Algorithm, tol: f64) -> Solution {
    let st = UzawaSettings::default()
        .with_algorithm(algorithm)
        .with_tol(tol)
        .with_max_iterations(100_000)
        .with_fallback(false);
    UzawaSolver::new(st)
        .solve(p, &p.coulomb_laws())
        .unwrap_or_else(|e| panic!("{algorithm:?}: {e}"))
}

/// The same problem with `W` stored dense (row-major), entry by entry from the stored triplets.
fn dense_twin(p: &ReducedProblem) -> ReducedProblem {
    let a = p.w_sparse().expect("a sparse problem");
    let m = p.size();
    let mut w = vec![0.0; m * m];
    for (i, j, v) in a.triplets() {
        w[i * m + j] = v;
    }
    ReducedProblem::with_dimension(p.dimension(), w, p.q().to_vec(), p.mu().to_vec()).unwrap()
}

fn relative_difference(a: &[f64], b: &[f64]) -> f64 {
    let d: f64 = a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum();
    let n: f64 = b.iter().map(|y| y * y).sum();
    (d / n).sqrt()
}

#[test]
fn sparse_and_dense_storage_give_the_same_reactions_with_every_algorithm() {
    for (dim, seed) in [(2, 11), (3, 12)] {
        let sparse = random_sparse_problem(dim, 60, 4, seed);
        let dense = dense_twin(&sparse);
        assert!(sparse.is_sparse() && !dense.is_sparse());
        assert_eq!(sparse.diagonal_block(7), dense.diagonal_block(7));
        for algorithm in ALGORITHMS {
            let (s, d) = (
                solve(&sparse, algorithm, 1e-10),
                solve(&dense, algorithm, 1e-10),
            );
            assert!(s.report.converged, "dim {dim} {algorithm:?}");
            assert_eq!(s.report.algorithm, d.report.algorithm);
            let diff = relative_difference(&s.r, &d.r);
            if s.report.algorithm == Algorithm::Newton {
                // faer's sparse LU against the dense LU: the same Newton steps up to round-off
                // in the directions, so the same answer to the tolerance's order (both stop at
                // a residual ≤ 1e-10; W is well conditioned)
                assert!(diff <= 1e-8, "dim {dim} {algorithm:?}: {diff:e}");
                assert!(relative_difference(&s.x, &d.x) <= 1e-8);
                continue;
            }
            assert_eq!(
                (s.report.iterations, s.report.outer_iterations),
                (d.report.iterations, d.report.outer_iterations),
                "dim {dim} {algorithm:?}: same iterations"
            );
            assert!(diff <= 1e-12, "dim {dim} {algorithm:?}: {diff:e}");
            // stronger, and observed: the same bits
            let bits = |v: &[f64]| v.iter().map(|a| a.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&s.r), bits(&d.r), "dim {dim} {algorithm:?}");
            assert!(relative_difference(&s.x, &d.x) <= 1e-12);
        }
    }
}

#[test]
fn sparse_rescaling_keeps_the_storage_and_the_answer() {
    // W of 1e120: solved on a copy scaled by a power of two, in the sparse storage
    let base = random_sparse_problem(3, 30, 3, 5);
    let a = base.w_sparse().unwrap();
    let (rows, cols, vals): (Vec<usize>, Vec<usize>, Vec<f64>) = a
        .triplets()
        .map(|(i, j, v)| (i, j, v * 1e120))
        .fold((vec![], vec![], vec![]), |mut t, (i, j, v)| {
            t.0.push(i);
            t.1.push(j);
            t.2.push(v);
            t
        });
    let big = ReducedProblem::from_triplets(
        3,
        &rows,
        &cols,
        &vals,
        base.q().to_vec(),
        base.mu().to_vec(),
    )
    .unwrap();
    let s = solve(&big, Algorithm::AndersonGaussSeidel, 1e-10);
    let d = solve(&dense_twin(&big), Algorithm::AndersonGaussSeidel, 1e-10);
    assert!(s.report.rescaled && d.report.rescaled);
    assert!(relative_difference(&s.r, &d.r) <= 1e-12);
}

#[test]
fn from_triplets_captures_errors() {
    let q = vec![-1.0, 0.0, -1.0, 0.0];
    let mu = vec![0.3, 0.3];
    let ok = |rows: &[usize], cols: &[usize], vals: &[f64]| {
        ReducedProblem::from_triplets(2, rows, cols, vals, q.clone(), mu.clone())
    };
    let diag = [0, 1, 2, 3];
    assert!(ok(&diag, &diag, &[1.0; 4]).is_ok());
    // an index out of range names the triplet
    assert_eq!(
        ok(&[0, 1, 2, 3], &[0, 1, 7, 3], &[1.0; 4]),
        Err(SolverError::IndexOutOfRange {
            what: "cols",
            index: 2,
            value: 7,
            bound: 4
        })
    );
    // lengths that disagree
    assert!(matches!(
        ok(&diag, &diag, &[1.0; 3]),
        Err(SolverError::SizeMismatch {
            what: "vals",
            expected: 4,
            found: 3
        })
    ));
    // a NaN names the triplet
    assert!(matches!(
        ok(&diag, &diag, &[1.0, 1.0, f64::NAN, 1.0]),
        Err(SolverError::NonFinite {
            what: "vals",
            index: 2,
            ..
        })
    ));
    // duplicates are summed: two halves make the diagonal
    let p = ok(
        &[0, 0, 1, 2, 3],
        &[0, 0, 1, 2, 3],
        &[0.5, 0.5, 1.0, 1.0, 1.0],
    )
    .unwrap();
    assert_eq!(p.diagonal_block(0)[0][0], 1.0);
    // asymmetry: 1e-3 relative is refused, saying where and by how much ...
    let rows = [0, 1, 2, 3, 0, 2];
    let cols = [0, 1, 2, 3, 2, 0];
    let e = ok(&rows, &cols, &[1.0, 1.0, 1.0, 1.0, 0.2, 0.201]).unwrap_err();
    let SolverError::NotSymmetric {
        row,
        col,
        difference,
        ..
    } = e
    else {
        panic!("{e:?}")
    };
    assert_eq!((row, col), (0, 2));
    assert!((difference - 1e-3).abs() < 1e-15);
    // ... 1e-7 is symmetrised and reported
    let p = ok(&rows, &cols, &[1.0, 1.0, 1.0, 1.0, 0.2, 0.2 + 2e-7]).unwrap();
    assert!((p.asymmetry() - 2e-7).abs() < 1e-15);
    let a = p.w_sparse().unwrap();
    assert_eq!(a.get(0, 2), a.get(2, 0));
    // a singular diagonal block, a missing one, a negative μ, a wrong dimension
    assert_eq!(
        ok(&[0, 0, 1, 1, 2, 3], &[0, 1, 0, 1, 2, 3], &[1.0; 6]),
        Err(SolverError::NotPositiveDefinite { contact: 0 })
    );
    assert_eq!(
        ok(&[0, 1], &[0, 1], &[1.0; 2]),
        Err(SolverError::NotPositiveDefinite { contact: 1 })
    );
    assert!(matches!(
        ReducedProblem::from_triplets(2, &diag, &diag, &[1.0; 4], q.clone(), vec![0.3, -0.1]),
        Err(SolverError::InvalidLaw { contact: 1, .. })
    ));
    assert!(matches!(
        ReducedProblem::from_triplets(4, &diag, &diag, &[1.0; 4], q.clone(), vec![0.3]),
        Err(SolverError::InvalidSetting { what: "dim", .. })
    ));
}

/// Newton on a sparse `W` factorises its system with faer's sparse LU, never densified: a
/// 2D problem of 1001 contacts and a 3D one of 2000 (a dense Newton matrix of up to 6000² =
/// 288 MB) converge in a few Newton steps, and agree with the accelerated sweep to 1e-7 (both
/// stop at a relative residual ≤ 1e-10; the random block-sparse `W` has a condition number of
/// about 1e3).
#[test]
fn newton_factorises_sparse_systems() {
    for (dim, n_c, seed) in [(2, 1001, 4), (3, 2000, 3)] {
        let p = random_sparse_problem(dim, n_c, 2, seed);
        let newton = solve(&p, Algorithm::Newton, 1e-10);
        let ags = solve(&p, Algorithm::AndersonGaussSeidel, 1e-10);
        assert!(newton.report.converged && ags.report.converged);
        let steps = newton.report.outer_iterations;
        assert!((1..=20).contains(&steps), "{steps} Newton steps");
        let diff = relative_difference(&newton.r, &ags.r);
        assert!(diff <= 1e-7, "dim {dim}: {diff:e}");
    }
}

/// Formerly a known limit of the semi-smooth Newton method, sparse and dense alike: on
/// `random_sparse_problem(2, 1001, 2, 3)` its steps shrank to `t ≈ 2⁻¹⁰` at a kink of the
/// projection and the residual stayed at 7e-5 (2 600 Newton steps of 3 000 iterations), and
/// the default fallback (the accelerated sweep) solved it. Since issue 37's proximal
/// regularisation of the Jacobian (`src/local/newton/proximal.rs`: a short step raises `ε` in
/// `W + εI`) Newton solves it itself, in 300 iterations at most (it used to spend 3 000 and
/// not converge: the assertion fails on the plain Newton), and its answer agrees with the
/// sweep's to 1e-6.
/// (A stall rule on Newton's steps, 50 without halving, was tried and cut issue 8's tipping
/// block, where Newton converges after a long slow stretch: not adopted.)
#[test]
fn where_newton_stalls_the_fallback_solves() {
    let p = random_sparse_problem(2, 1001, 2, 3);
    let st = UzawaSettings::default()
        .with_algorithm(Algorithm::Newton)
        .with_tol(1e-8)
        .with_max_iterations(3000);
    let sol = UzawaSolver::new(st)
        .solve(&p, &p.coulomb_laws())
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(sol.report.fallback_from, None);
    assert_eq!(sol.report.algorithm, Algorithm::Newton);
    assert!(sol.report.converged);
    // measured 128 iterations (17 Newton steps)
    assert!(sol.report.iterations <= 300, "{}", sol.report.iterations);
    let ags = solve(&p, Algorithm::AndersonGaussSeidel, 1e-10);
    let diff = relative_difference(&sol.r, &ags.r);
    assert!(diff <= 1e-6, "{diff:e}");
}

#[cfg(feature = "serde")]
#[test]
fn json_triplets_round_trip() {
    let p = random_sparse_problem(3, 20, 3, 9);
    let text = p.to_json().unwrap();
    assert!(text.contains(r#""W":{"m":60,"i":["#), "{}", &text[..80]);
    let back = ReducedProblem::from_json(&text).unwrap();
    assert_eq!(back, p);
    assert!(matches!(back.w(), contact_solver::WView::Sparse(_)));
}

/// A granular-size problem: 3D, 7000 contacts (m = 21 000, dense W: 3.5 GB), about 5 blocks
/// per block row. Solved by Auto (the accelerated Gauss–Seidel sweep) in the sparse storage.
#[test]
fn issue_14_large_sparse_problem_is_solved_in_little_memory() {
    let p = random_sparse_problem(3, 7000, 4, 2026);
    let m = p.size() as f64;
    let dense_bytes = 8.0 * m * m;
    let a = p.w_sparse().unwrap();
    assert_eq!(
        p.w_storage_bytes(),
        a.stored() * 12 + (p.size() + 1) * size_of::<usize>()
    );
    assert!(
        (p.w_storage_bytes() as f64) < dense_bytes / 100.0,
        "{} bytes against {dense_bytes:e} dense",
        p.w_storage_bytes()
    );
    let s = solve(&p, Algorithm::Auto, 1e-8);
    assert_eq!(s.report.algorithm, Algorithm::AndersonGaussSeidel);
    assert!(s.report.converged && s.report.residual <= 1e-8);
    // an independent check of the answer: x = W r + q recomputed, Signorini on the normals
    let mut x = vec![0.0; p.size()];
    p.displacement_into(&s.r, &mut x);
    assert!(relative_difference(&x, &s.x) <= 1e-10);
    let scale = s.r.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
    for i in 0..p.contact_count() {
        let (r_n, x_n) = (s.r[3 * i], x[3 * i]);
        assert!(r_n >= -1e-7 * scale && x_n >= -1e-6 && (r_n * x_n).abs() <= 1e-6 * scale);
    }
}
