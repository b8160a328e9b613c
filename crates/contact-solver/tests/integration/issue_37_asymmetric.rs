//! Non-symmetric Delassus operators kept as given (issue 37): multibody codes with joints or
//! bilateral constraints export a `W` whose asymmetry is a property of the model, and its
//! symmetrised problem has another answer.
//!
//! Family: a symmetric positive definite `W` (`generate::random_problem_in`, 2D and 3D,
//! frictionless and Coulomb; a sparse block copy) plus a skew part `K = −Kᵀ` of relative size
//! `ε = 1e-5 … 1e-3` (`W' = W + ε max|W| (U − Uᵀ)`, `U` uniform in `[−1, 1]`): `rᵀ W' r = rᵀ W r`,
//! so the frictionless problem stays monotone with a unique answer, and the diagonal blocks'
//! symmetric parts are those of `W` (positive definite).
//!
//! Checks, on the real `W'`:
//! - every algorithm that does not need symmetry (Gauss–Seidel, Anderson on it, the classical
//!   split, Newton, `Auto`) returns an answer whose natural-map residual, computed here from
//!   `x = W' r + q` with our own cone projection, is within `10 × tol`;
//! - the answer of the symmetrised problem misses on `W'` by far more (`> 1e3 × tol`), and
//!   differs from the kept answer: the test fails if the library quietly symmetrises;
//! - Uzawa and Anderson–Uzawa refuse the kept `W'` with `NeedsSymmetricW` naming themselves.

use contact_solver::local::generate::random_problem_in;
use contact_solver::{
    Algorithm, Asymmetry, ReducedProblem, SolverError, UzawaSettings, solve_coulomb,
};

const TOL: f64 = 1e-10;

/// `W + ε max|W| (U − Uᵀ)` with `U` uniform in `[−1, 1]` (a skew part; seeded).
fn skewed(w: &[f64], m: usize, eps: f64, seed: u64) -> Vec<f64> {
    let s = w.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
    let mut g = contact_solver::local::generate::SplitMix64::new(seed);
    let mut out = w.to_vec();
    for i in 0..m {
        for j in (i + 1)..m {
            let k = eps * s * g.uniform(-1.0, 1.0);
            out[i * m + j] += k;
            out[j * m + i] -= k;
        }
    }
    out
}

/// The kept non-symmetric problem and `W'` itself (dense row-major).
fn family(
    dim: usize,
    nc: usize,
    eps: f64,
    frictionless: bool,
    seed: u64,
) -> (ReducedProblem, Vec<f64>) {
    let base = random_problem_in(dim, nc, seed);
    let m = base.size();
    let w = skewed(base.w_dense().unwrap(), m, eps, seed + 1);
    let mu = if frictionless {
        vec![0.0; nc]
    } else {
        base.mu().to_vec()
    };
    let p = ReducedProblem::with_asymmetry(dim, w.clone(), base.q().to_vec(), mu, Asymmetry::Keep)
        .unwrap();
    (p, w)
}

/// Projection onto the Coulomb cone `‖z_t‖ ≤ μ z_n` (here, independent of the library).
fn project(z: &[f64], mu: f64) -> Vec<f64> {
    let (zn, zt) = (z[0], &z[1..]);
    let nt = zt.iter().map(|a| a * a).sum::<f64>().sqrt();
    if nt <= mu * zn {
        return z.to_vec();
    }
    if mu * nt <= -zn {
        return vec![0.0; z.len()];
    }
    let a = (zn + mu * nt) / (1.0 + mu * mu);
    let mut out = vec![a];
    out.extend(zt.iter().map(|t| mu * a * t / nt));
    out
}

/// Natural-map residual `‖r − P_K(r − ρ û(x))‖ / max(‖r‖, ρ_max ‖q‖)` on the dense `w`, with
/// `x = w r + q` recomputed here, `û = (x_n + μ‖x_t‖, x_t)` (De Saxcé) and `ρ_i = 1/w_nn,i`.
fn residual(w: &[f64], q: &[f64], mu: &[f64], dim: usize, r: &[f64]) -> f64 {
    let m = q.len();
    let x: Vec<f64> = (0..m)
        .map(|i| q[i] + (0..m).map(|j| w[i * m + j] * r[j]).sum::<f64>())
        .collect();
    let (mut f2, mut rho_max) = (0.0, 0.0_f64);
    for (c, &mu_c) in mu.iter().enumerate() {
        let b = dim * c;
        let rho = 1.0 / w[b * m + b];
        rho_max = rho_max.max(rho);
        let xt = &x[b + 1..b + dim];
        let u_hat_n = x[b] + mu_c * xt.iter().map(|a| a * a).sum::<f64>().sqrt();
        let z: Vec<f64> = (0..dim)
            .map(|k| r[b + k] - rho * if k == 0 { u_hat_n } else { x[b + k] })
            .collect();
        let p = project(&z, mu_c);
        f2 += (0..dim).map(|k| (r[b + k] - p[k]).powi(2)).sum::<f64>();
    }
    let norm = |v: &[f64]| v.iter().map(|a| a * a).sum::<f64>().sqrt();
    f2.sqrt() / norm(r).max(rho_max * norm(q)).max(f64::MIN_POSITIVE)
}

/// `algorithm` alone (no fallback: each must solve the problem itself) to `TOL`.
fn settings(algorithm: Algorithm) -> UzawaSettings {
    UzawaSettings::default()
        .with_algorithm(algorithm)
        .with_tol(TOL)
        .with_max_iterations(100_000)
        .with_fallback(false)
}

const VALID: [Algorithm; 5] = [
    Algorithm::GaussSeidel,
    Algorithm::AndersonGaussSeidel,
    Algorithm::ClassicRccm,
    Algorithm::Newton,
    Algorithm::Auto,
];

/// The checks of the module docs on one problem of the family.
fn check_family(dim: usize, nc: usize, eps: f64, frictionless: bool, seed: u64) {
    let (p, w) = family(dim, nc, eps, frictionless, seed);
    let what = format!("dim {dim}, {nc} contacts, eps {eps:e}, frictionless {frictionless}");
    assert!(!p.is_symmetric(), "{what}");
    // the measured relative asymmetry is at most 2ε (two draws of [−1, 1]) and about 2ε
    assert!(
        p.kept_asymmetry() > 0.5 * eps && p.kept_asymmetry() <= 2.0 * eps,
        "{what}"
    );
    let (q, mu) = (p.q().to_vec(), p.mu().to_vec());
    // the symmetrised problem, solved to the same tolerance
    let sym = ReducedProblem::with_asymmetry(
        dim,
        w.clone(),
        q.clone(),
        mu.clone(),
        Asymmetry::Symmetrise { tolerance: 1.0 },
    )
    .unwrap();
    assert!(sym.is_symmetric() && sym.asymmetry() == p.kept_asymmetry());
    let r_sym = solve_coulomb(&sym, &settings(Algorithm::Newton)).unwrap().r;
    let miss = residual(&w, &q, &mu, dim, &r_sym);
    // the symmetrised answer misses on W' by about ε (relative): far above the tolerance
    assert!(
        miss > 1e3 * TOL,
        "{what}: the symmetrised answer misses by only {miss:e}"
    );
    for algorithm in VALID {
        let sol = solve_coulomb(&p, &settings(algorithm))
            .unwrap_or_else(|e| panic!("{what}, {algorithm:?}: {e}"));
        // ρ here (1/W_nn) differs from the library's (1/λ_max of the block) by a factor ≤ 3
        // (blocks of 2 or 3 rows, diagonally dominant); the natural residuals with two
        // penalties differ by at most about that factor: 10 × tol leaves room for it
        let res = residual(&w, &q, &mu, dim, &sol.r);
        assert!(
            res <= 10.0 * TOL,
            "{what}, {algorithm:?}: residual {res:e} on the real W"
        );
        assert!(sol.report.residual <= 2.0 * TOL, "{what}, {algorithm:?}");
        let scale = sol.r.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
        let diff = sol
            .r
            .iter()
            .zip(&r_sym)
            .fold(0.0_f64, |a, (x, y)| a.max((x - y).abs()));
        // the kept answer is another answer than the symmetrised one (by about ε · scale)
        assert!(
            diff > 1e-2 * eps * scale,
            "{what}, {algorithm:?}: differs by {diff:e}"
        );
    }
    for algorithm in [Algorithm::Uzawa, Algorithm::AndersonUzawa] {
        match solve_coulomb(&p, &settings(algorithm)) {
            Err(SolverError::NeedsSymmetricW {
                algorithm: name,
                asymmetry,
            }) => {
                assert_eq!(name, algorithm.name());
                assert_eq!(asymmetry, p.kept_asymmetry());
            }
            other => panic!("{what}, {algorithm:?}: expected NeedsSymmetricW, got {other:?}"),
        }
    }
}

#[test]
fn issue_37_kept_asymmetric_2d_coulomb_solves_on_the_real_w() {
    check_family(2, 12, 1e-3, false, 3);
    check_family(2, 12, 1e-5, false, 5);
}

#[test]
fn issue_37_kept_asymmetric_2d_frictionless_solves_on_the_real_w() {
    check_family(2, 12, 1e-4, true, 7);
}

#[test]
fn issue_37_kept_asymmetric_3d_coulomb_solves_on_the_real_w() {
    check_family(3, 10, 1e-3, false, 11);
    check_family(3, 10, 1e-5, false, 13);
}

#[test]
fn issue_37_kept_asymmetric_3d_frictionless_solves_on_the_real_w() {
    check_family(3, 10, 1e-4, true, 17);
}

/// The same `W'` stored sparse (triplets of every entry): the same checks on the residual, and
/// the same answer as the dense storage to the solver's accuracy.
#[test]
fn issue_37_kept_asymmetric_sparse_matches_dense() {
    let (p, w) = family(3, 8, 1e-3, false, 19);
    let m = p.size();
    let (mut rows, mut cols, mut vals) = (Vec::new(), Vec::new(), Vec::new());
    for i in 0..m {
        for j in 0..m {
            rows.push(i);
            cols.push(j);
            vals.push(w[i * m + j]);
        }
    }
    let (q, mu) = (p.q().to_vec(), p.mu().to_vec());
    let s = ReducedProblem::from_triplets_with_asymmetry(
        3,
        &rows,
        &cols,
        &vals,
        q.clone(),
        mu.clone(),
        Asymmetry::Keep,
    )
    .unwrap();
    assert!(s.is_sparse() && !s.is_symmetric());
    // the same pair measured (the sparse scan divides each entry by max|W| first: round-off)
    assert!((s.kept_asymmetry() - p.kept_asymmetry()).abs() <= 1e-15 * p.kept_asymmetry());
    // refused without the policy
    assert!(matches!(
        ReducedProblem::from_triplets(3, &rows, &cols, &vals, q.clone(), mu.clone()),
        Err(SolverError::NotSymmetric { .. })
    ));
    for algorithm in [Algorithm::AndersonGaussSeidel, Algorithm::Newton] {
        let a = solve_coulomb(&p, &settings(algorithm)).unwrap();
        let b = solve_coulomb(&s, &settings(algorithm)).unwrap();
        // as in check_family: 10 × tol for the other penalty of this residual
        assert!(
            residual(&w, &q, &mu, 3, &b.r) <= 10.0 * TOL,
            "{algorithm:?}"
        );
        let scale = a.r.iter().fold(0.0_f64, |x, v| x.max(v.abs()));
        // two answers within tol of the unique solution (monotone problem, well conditioned:
        // W = AAᵀ + 0.1 I) agree to a small multiple of tol, far below the skew's ε = 1e-3
        for (x, y) in a.r.iter().zip(&b.r) {
            assert!(
                (x - y).abs() <= 1e-6 * scale,
                "{algorithm:?}: {x} against {y}"
            );
        }
    }
}

/// JSON: refused by default (the behaviour of `from_json` is unchanged), read as given with
/// `Asymmetry::Keep`, written back unchanged.
#[cfg(feature = "serde")]
#[test]
fn issue_37_json_keeps_asymmetric_w_on_request() {
    let (p, _) = family(2, 4, 1e-3, false, 23);
    let text = p.to_json().unwrap();
    assert!(matches!(
        ReducedProblem::from_json(&text),
        Err(SolverError::NotSymmetric { .. })
    ));
    let back = ReducedProblem::from_json_with_asymmetry(&text, Asymmetry::Keep).unwrap();
    assert_eq!(back, p);
}

/// Below round-off nothing changes: a symmetric `W` under `Keep` is the same problem, with the
/// same answer bit for bit, and Uzawa runs on it.
#[test]
fn issue_37_keep_changes_nothing_on_a_symmetric_w() {
    let base = random_problem_in(3, 10, 29);
    let w = base.w_dense().unwrap().to_vec();
    let (q, mu) = (base.q().to_vec(), base.mu().to_vec());
    let kept = ReducedProblem::with_asymmetry(3, w, q, mu, Asymmetry::Keep).unwrap();
    assert!(kept.is_symmetric() && kept.kept_asymmetry() == 0.0);
    assert_eq!(kept, base);
    for algorithm in [
        Algorithm::Uzawa,
        Algorithm::AndersonGaussSeidel,
        Algorithm::Newton,
    ] {
        let a = solve_coulomb(&base, &settings(algorithm)).unwrap();
        let b = solve_coulomb(&kept, &settings(algorithm)).unwrap();
        assert_eq!(a.r, b.r, "{algorithm:?}");
    }
}

/// Against Siconos (`tests/data/issue_37_make_siconos.py`): a 3D problem of 20 contacts whose
/// `W` is SPD plus a skew part of `1e-3` of its scale, solved by Siconos'
/// `FRICTION_3D_NSGS` to `1e-12` (stored). Ours, on the kept `W`, agree to `1e-6` of the
/// largest reaction (both are within about `1e-10` of the unique answer of this well-conditioned
/// monotone problem, so the bound has four orders of room); the symmetrised problem's answer
/// does not (it differs by about the skew's `1e-3`).
#[cfg(feature = "serde")]
#[test]
fn issue_37_kept_asymmetric_agrees_with_siconos_nsgs() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/");
    let text = std::fs::read_to_string(format!("{dir}issue_37_skew_3d.json")).unwrap();
    let reference = std::fs::read_to_string(format!("{dir}issue_37_skew_3d_siconos.json")).unwrap();
    // the list after "r": (the file is written by the script above)
    let start = reference.find("\"r\": [").unwrap() + 6;
    let end = start + reference[start..].find(']').unwrap();
    let r_siconos: Vec<f64> = reference[start..end]
        .split(',')
        .map(|v| v.trim().parse().unwrap())
        .collect();
    let p = ReducedProblem::from_json_with_asymmetry(&text, Asymmetry::Keep).unwrap();
    assert!(!p.is_symmetric() && r_siconos.len() == p.size());
    let scale = r_siconos.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
    let gap = |r: &[f64]| {
        r.iter()
            .zip(&r_siconos)
            .fold(0.0_f64, |a, (x, y)| a.max((x - y).abs()))
    };
    for algorithm in [
        Algorithm::AndersonGaussSeidel,
        Algorithm::Newton,
        Algorithm::Auto,
    ] {
        let t = std::time::Instant::now();
        let sol = solve_coulomb(&p, &settings(algorithm)).unwrap();
        let ms = t.elapsed().as_secs_f64() * 1e3;
        let g = gap(&sol.r);
        eprintln!(
            "{algorithm:?}: {} iterations, {ms:.3} ms, max|r - r_siconos| = {g:.2e} (max|r| {scale:.3})",
            sol.report.iterations
        );
        assert!(g <= 1e-6 * scale, "{algorithm:?}: {g:e}");
    }
    let sym = ReducedProblem::with_asymmetry(
        3,
        p.w_dense().unwrap().to_vec(),
        p.q().to_vec(),
        p.mu().to_vec(),
        Asymmetry::Symmetrise { tolerance: 1.0 },
    )
    .unwrap();
    let g = gap(&solve_coulomb(&sym, &settings(Algorithm::Newton)).unwrap().r);
    assert!(
        g > 1e-5 * scale,
        "the symmetrised answer is {g:e} from Siconos'"
    );
}

/// A multibody Delassus operator (`generate::multibody::SpherePile`, 3 × 3 × 3 spheres in a
/// box, shaken: rank-deficient, semidefinite) made non-symmetric by a skew part of `1e-4` of
/// its scale, as joints would make it: the sweeps and Newton solve it on the real `W`
/// (residual as in [`check_family`]), and the symmetrised problem's answer misses there.
#[test]
fn issue_37_kept_asymmetric_sphere_pile_solves_on_the_real_w() {
    use contact_solver::local::generate::multibody::SpherePile;
    let pile = SpherePile {
        nx: 3,
        ny: 3,
        layers: 3,
        jitter: 0.2,
        initial_speed: 0.05,
        ..SpherePile::default()
    }
    .generate(3)
    .unwrap();
    let base = &pile.problem;
    let m = base.size();
    let w = skewed(base.w_dense().unwrap(), m, 1e-4, 41);
    let (q, mu) = (base.q().to_vec(), base.mu().to_vec());
    let p = ReducedProblem::with_asymmetry(3, w.clone(), q.clone(), mu.clone(), Asymmetry::Keep)
        .unwrap();
    let sym = ReducedProblem::with_asymmetry(
        3,
        w.clone(),
        q.clone(),
        mu.clone(),
        Asymmetry::Symmetrise { tolerance: 1.0 },
    )
    .unwrap();
    let r_sym = solve_coulomb(&sym, &settings(Algorithm::AndersonGaussSeidel))
        .unwrap()
        .r;
    let miss = residual(&w, &q, &mu, 3, &r_sym);
    assert!(
        miss > 1e3 * TOL,
        "the symmetrised answer misses by only {miss:e}"
    );
    for algorithm in [
        Algorithm::AndersonGaussSeidel,
        Algorithm::Newton,
        Algorithm::Auto,
    ] {
        let sol = solve_coulomb(&p, &settings(algorithm))
            .unwrap_or_else(|e| panic!("{algorithm:?}: {e}"));
        let res = residual(&w, &q, &mu, 3, &sol.r);
        eprintln!(
            "pile, {} contacts, {algorithm:?}: {} iterations, residual {res:.2e} (symmetrised: {miss:.2e})",
            p.contact_count(),
            sol.report.iterations
        );
        assert!(
            res <= 10.0 * TOL,
            "{algorithm:?}: residual {res:e} on the real W"
        );
    }
}
