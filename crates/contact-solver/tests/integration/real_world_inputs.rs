//! Reduced problems as other codes export them (issue 14): round-off asymmetry, every gap
//! open, extreme magnitudes, huge friction coefficients. Each answer is checked against a
//! closed form or against the same problem at unit scale.

use contact_laws::{ContactLaw, Coulomb, LocalVec};
use contact_solver::local::generate::random_problem;
use contact_solver::{
    Algorithm, ReducedProblem, SolverError, UzawaSettings, UzawaSolver, solve_coulomb,
};
use proptest::prelude::*;

const ALL: [Algorithm; 6] = [
    Algorithm::Newton,
    Algorithm::AndersonGaussSeidel,
    Algorithm::GaussSeidel,
    Algorithm::Uzawa,
    Algorithm::AndersonUzawa,
    Algorithm::ClassicRccm,
];

fn settings(algorithm: Algorithm) -> UzawaSettings {
    UzawaSettings::default().with_algorithm(algorithm)
}

/// A mechanism's 2-contact problem exported with `W` symmetric to 3e-7 relative: repaired
/// (symmetrised, the report says by how much) and solved like its symmetric part; 1e-3 is
/// refused with the size of the asymmetry.
#[test]
fn round_off_asymmetry_is_repaired_and_reported() {
    let sym = [
        2.0, 0.3, 0.5, 0.1, //
        0.3, 1.0, 0.2, 0.0, //
        0.5, 0.2, 3.0, 0.4, //
        0.1, 0.0, 0.4, 1.5,
    ];
    let q = vec![-1.0, 0.4, -0.5, -0.2];
    let mu = vec![0.3, 0.5];
    let mut w = sym.to_vec();
    w[1] += 3e-7 * 3.0; // |W_01 − W_10| = 9e-7 = 3e-7 · max|W|
    w[4] -= 0.0;
    let p = ReducedProblem::new(w.clone(), q.clone(), mu.clone()).unwrap();
    assert!((p.asymmetry() - 3e-7).abs() < 1e-15, "{}", p.asymmetry());
    let reference = ReducedProblem::new(
        {
            let mut s = sym.to_vec();
            s[1] += 4.5e-7;
            s[4] += 4.5e-7;
            s
        },
        q.clone(),
        mu.clone(),
    )
    .unwrap();
    assert_eq!(reference.asymmetry(), 0.0);
    for algorithm in ALL {
        let a = solve_coulomb(&p, &settings(algorithm)).unwrap();
        let b = solve_coulomb(&reference, &settings(algorithm)).unwrap();
        assert_eq!(a.r, b.r, "{algorithm:?}");
        assert!((a.report.asymmetry - 3e-7).abs() < 1e-15);
    }
    let mut bad = sym.to_vec();
    bad[1] += 3e-3;
    match ReducedProblem::new(bad, q, mu) {
        Err(SolverError::NotSymmetric {
            row: 0,
            col: 1,
            difference,
            ..
        }) => assert!((difference - 3e-3).abs() < 1e-12),
        other => panic!("expected NotSymmetric, got {other:?}"),
    }
}

/// Every gap open (`q_n ≥ 0`): `r = 0` and `x = q` exactly, with no iteration, for every
/// algorithm — 667 contacts as in the granular problem of the issue.
#[test]
fn every_gap_open_is_answered_without_iterating() {
    let base = random_problem(667, 5);
    let q: Vec<f64> = base
        .q()
        .iter()
        .enumerate()
        .map(|(k, v)| if k % 2 == 0 { v.abs() + 1e-3 } else { *v })
        .collect();
    let p = ReducedProblem::new(
        base.w_dense().unwrap().to_vec(),
        q.clone(),
        base.mu().to_vec(),
    )
    .unwrap();
    for algorithm in ALL {
        let s = solve_coulomb(&p, &settings(algorithm)).unwrap();
        assert!(s.r.iter().all(|&v| v == 0.0));
        assert_eq!(s.x, q);
        assert_eq!(s.report.iterations, 0, "{algorithm:?}");
        assert!(s.report.converged);
    }
}

fn scaled(p: &ReducedProblem, sw: f64, sq: f64) -> ReducedProblem {
    ReducedProblem::new(
        p.w_dense().unwrap().iter().map(|v| v * sw).collect(),
        p.q().iter().map(|v| v * sq).collect(),
        p.mu().to_vec(),
    )
    .unwrap()
}

/// `W` and `q` scaled by powers of ten up to 1e±300: the reactions scale by `s_q/s_w` and `x`
/// by `s_q`. Below 1e±100 the solver runs on the data as given, so the agreement is to the
/// solver's tolerance (1e-8 relative, the residual's 1e-10 times the problem's condition);
/// beyond, it rescales by powers of two and agrees to the same.
#[test]
fn extreme_magnitudes_give_the_scaled_answer() {
    let p = random_problem(12, 3);
    for algorithm in ALL {
        let st = settings(algorithm).with_tol(1e-12);
        let unit = solve_coulomb(&p, &st).unwrap();
        let r_max = unit.r.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
        for (sw, sq) in [
            (1e300, 1e300),
            (1e-300, 1e-300),
            (1e300, 1.0),
            (1e-300, 1.0),
            (1.0, 1e-300),
            (1e150, 1e-150),
            (1e-120, 1e120),
        ] {
            let s = solve_coulomb(&scaled(&p, sw, sq), &st)
                .unwrap_or_else(|e| panic!("{algorithm:?} at W×{sw:e}, q×{sq:e}: {e}"));
            for (a, b) in s.r.iter().zip(&unit.r) {
                let back = a * (sw / sq);
                assert!(
                    (back - b).abs() <= 1e-8 * r_max,
                    "{algorithm:?} at W×{sw:e}, q×{sq:e}: {back} against {b}"
                );
            }
            assert!(s.report.converged);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    /// Scale invariance: `solve(s W, s q)` is `r` for `s = 10^k`, `k ∈ [−100, 100]`.
    #[test]
    fn scale_invariance_holds(k in -100i32..=100, seed in 0u64..1000) {
        let p = random_problem(6, seed);
        let st = UzawaSettings::default().with_tol(1e-12);
        let unit = solve_coulomb(&p, &st).unwrap();
        let s = 10f64.powi(k);
        let sol = solve_coulomb(&scaled(&p, s, s), &st).unwrap();
        let r_max = unit.r.iter().fold(0.0_f64, |a, v| a.max(v.abs())).max(1e-300);
        for (a, b) in sol.r.iter().zip(&unit.r) {
            prop_assert!((a - b).abs() <= 1e-8 * r_max, "s = {s:e}: {a} against {b}");
        }
    }
}

/// One contact pressed and pushed sideways, `W = [2 0.5; 0.5 1]`, `q = (−1, 0.5)`: it sticks
/// for `μ ≥ 1.2` with `r = −W⁻¹ q = (5/7, −6/7)`. From `μ = 100` on, the bipotential
/// iterations stall (the modified velocity `x_n + μ|x_t|` amplifies round-off by `μ`) or,
/// with `μ = 1e100`, absorb the penetration; the check of the Signorini–Coulomb conditions
/// catches both and the classical solver answers (`report.fallback_from`). Tolerance 1e-7:
/// the residual's 1e-10, amplified by `μ` (≤ 30 where a bipotential iteration answers) and
/// the condition of `W` (≈ 3).
#[test]
fn huge_friction_coefficients_stick_with_every_algorithm() {
    let w = vec![2.0, 0.5, 0.5, 1.0];
    let q = vec![-1.0, 0.5];
    for mu in [1.2, 30.0, 100.0, 1e6, 1e100] {
        let p = ReducedProblem::new(w.clone(), q.clone(), vec![mu]).unwrap();
        for algorithm in ALL {
            let s = solve_coulomb(&p, &settings(algorithm))
                .unwrap_or_else(|e| panic!("{algorithm:?}, μ = {mu:e}: {e}"));
            assert!(
                (s.r[0] - 5.0 / 7.0).abs() < 1e-7 && (s.r[1] + 6.0 / 7.0).abs() < 1e-7,
                "{algorithm:?}, μ = {mu:e}: {:?}",
                s.r
            );
        }
    }
    // μ = 1e100 through the default algorithm: the answer comes from the fallback
    let p = ReducedProblem::new(w, q, vec![1e100]).unwrap();
    let s = solve_coulomb(&p, &UzawaSettings::default()).unwrap();
    assert_eq!(s.report.fallback_from, Some(Algorithm::AndersonGaussSeidel));
    assert_eq!(s.report.algorithm, Algorithm::ClassicRccm);
    // without the fallback, the failure is an error, never a wrong "converged"
    let e = solve_coulomb(&p, &UzawaSettings::default().with_fallback(false));
    assert!(matches!(e, Err(SolverError::NotConverged { .. })), "{e:?}");
}

/// A law that is not scale invariant (a Tresca threshold of its own) cannot be rescaled:
/// magnitudes beyond 1e±150 are refused with the name of the data, not answered wrongly.
#[derive(Clone, Copy, Debug)]
struct Tresca(f64);

impl ContactLaw for Tresca {
    type State = ();
    fn has_friction(&self) -> bool {
        true
    }
    fn project<const DT: usize>(&self, tau: &LocalVec<DT>, _: &()) -> LocalVec<DT> {
        let n = tau.n.max(0.0);
        let t = tau.t_norm();
        let k = if t > self.0 { self.0 / t } else { 1.0 };
        let mut r = *tau * k;
        r.n = n;
        r
    }
    fn modified_velocity<const DT: usize>(&self, du: &LocalVec<DT>, _: &()) -> LocalVec<DT> {
        -*du
    }
    fn bipotential<const DT: usize>(&self, _: &LocalVec<DT>, _: &LocalVec<DT>, _: &()) -> f64 {
        0.0
    }
}

#[test]
fn a_law_that_cannot_be_rescaled_refuses_extreme_magnitudes() {
    let p = ReducedProblem::new(
        vec![1e200, 0.0, 0.0, 1e200],
        vec![-1e200, 0.5e200],
        vec![0.3],
    )
    .unwrap();
    let e = UzawaSolver::new(UzawaSettings::default()).solve(&p, &[Tresca(1.0)]);
    assert!(
        matches!(e, Err(SolverError::InvalidSetting { what: "W", .. })),
        "{e:?}"
    );
    // Coulomb is scale invariant: the same problem is solved (slip: r = (1, −0.3))
    let s = UzawaSolver::new(UzawaSettings::default())
        .solve(&p, &[Coulomb::new(0.3).unwrap()])
        .unwrap();
    assert!(
        (s.r[0] - 1.0).abs() < 1e-12 && (s.r[1] + 0.3).abs() < 1e-12,
        "{:?}",
        s.r
    );
    assert!(s.report.rescaled);
}

/// `Algorithm::Auto` runs Newton on a Coulomb problem (friction coefficients known, few
/// contacts) and the accelerated Gauss–Seidel sweep for a law without a friction coefficient;
/// the report names the one that ran, and the answer is the one of that algorithm.
#[test]
fn auto_picks_newton_for_coulomb_and_the_sweep_for_other_laws() {
    let p = random_problem(12, 9);
    let auto = solve_coulomb(&p, &settings(Algorithm::Auto)).unwrap();
    assert_eq!(auto.report.algorithm, Algorithm::Newton);
    let newton = solve_coulomb(&p, &settings(Algorithm::Newton)).unwrap();
    assert_eq!(auto.r, newton.r);
    let laws = vec![Tresca(0.05); 12];
    let s = UzawaSolver::new(settings(Algorithm::Auto))
        .solve(&p, &laws)
        .unwrap();
    assert_eq!(s.report.algorithm, Algorithm::AndersonGaussSeidel);
}
