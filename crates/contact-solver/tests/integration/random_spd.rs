//! Random SPD reduced problems (`contact_solver::local::generate::random_problem`, seeded).
//!
//! Reference: the optimality conditions themselves (seed 4.8–4.9, `docs/theory.md` §4): at a
//! solution, per contact, `r_i ∈ K_μi`, `x_n ≥ 0` and the Fenchel gap
//! `b_c(−x_i, r_i) + x_i·r_i` vanishes; and the two sweeps (Uzawa, Gauss–Seidel), which
//! share nothing but the laws, agree. Uniqueness holds for these μ ≤ 1 and well-conditioned W
//! in practice (not in general for Coulomb friction).

use contact_solver::contact_laws::{CoulombCone, LocalVec2, contact_fenchel_gap};
use contact_solver::local::generate::random_problem;
use contact_solver::{
    Algorithm, ReducedProblem, Solution, SolverError, UzawaSettings, solve_coulomb,
};

fn run(p: &ReducedProblem, algorithm: Algorithm, rho_scale: f64) -> Solution {
    let settings = UzawaSettings::default()
        .with_algorithm(algorithm)
        .with_rho_scale(rho_scale);
    solve_coulomb(p, &settings).unwrap()
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|a| a * a).sum::<f64>().sqrt()
}

/// Checks the optimality conditions. Tolerances: with a relative natural-map residual of 1e-10,
/// `r` and `x` are accurate to about `cond(W)·1e-10 ≈ 4e-9` relative (cond ≈ 40), so
/// feasibility and the gap are checked at 1e-7 of the problem's scales.
fn check_optimality(p: &ReducedProblem, s: &Solution) {
    let (r_scale, x_scale) = (norm(&s.r), norm(p.q()));
    let tol = 1e-7;
    for (i, &mu) in p.mu().iter().enumerate() {
        let cone = CoulombCone::new(mu).unwrap();
        let r = LocalVec2::planar(s.r[2 * i], s.r[2 * i + 1]);
        let x = LocalVec2::planar(s.x[2 * i], s.x[2 * i + 1]);
        assert!(r.n >= -tol * r_scale, "contact {i}: r_n = {}", r.n);
        assert!(
            r.t_norm() <= mu * r.n + tol * r_scale,
            "contact {i}: r outside K"
        );
        assert!(x.n >= -tol * x_scale, "contact {i}: x_n = {}", x.n);
        // Evaluate the gap at the nearest admissible pair, so rounding does not hit an indicator.
        let r_adm = cone.project(&r);
        let x_adm = LocalVec2::planar(x.n.max(0.0), x.t[0]);
        let gap = contact_fenchel_gap(&cone, &x_adm, &r_adm);
        assert!(
            gap.is_finite() && gap <= tol * r_scale * x_scale,
            "contact {i}: gap {gap}"
        );
    }
}

#[test]
fn random_10_and_100_contacts_satisfy_the_law_and_both_sweeps_agree() {
    for (nc, seed) in [(10, 1), (10, 2), (100, 3)] {
        let p = random_problem(nc, seed);
        let a = run(&p, Algorithm::Uzawa, 1.0);
        let b = run(&p, Algorithm::GaussSeidel, 1.0);
        check_optimality(&p, &a);
        check_optimality(&p, &b);
        let diff: Vec<f64> = a.r.iter().zip(&b.r).map(|(x, y)| x - y).collect();
        // 1e-8 relative: each is within ≈ cond(W)·tol ≈ 4e-9 of the solution.
        assert!(
            norm(&diff) <= 1e-8 * norm(&a.r),
            "nc = {nc}: {}",
            norm(&diff) / norm(&a.r)
        );
        assert_eq!(a.report.statuses, b.report.statuses);
    }
}

#[test]
fn bad_rho_still_converges() {
    let p = random_problem(100, 3);
    let reference = run(&p, Algorithm::GaussSeidel, 1.0);
    for alg in [Algorithm::Uzawa, Algorithm::GaussSeidel] {
        for scale in [1e-3, 1e3] {
            let s = run(&p, alg, scale);
            check_optimality(&p, &s);
            let diff: Vec<f64> = s.r.iter().zip(&reference.r).map(|(x, y)| x - y).collect();
            assert!(
                norm(&diff) <= 1e-8 * norm(&reference.r),
                "{alg:?} scale {scale}"
            );
        }
    }
}

#[test]
fn not_converged_carries_the_history() {
    let p = random_problem(10, 1);
    // with the fallback (default), the error carries both runs: 3 sweeps, then the classical
    // solver's iterations
    match solve_coulomb(&p, &UzawaSettings::default().with_max_iterations(3)) {
        Err(SolverError::NotConverged {
            iterations,
            residual,
            history,
            ..
        }) => {
            assert!(iterations > 3 && history.len() > 3);
            assert_eq!(history.last(), Some(&residual));
        }
        other => panic!("expected NotConverged, got {other:?}"),
    }
    let settings = UzawaSettings::default()
        .with_max_iterations(3)
        .with_fallback(false);
    match solve_coulomb(&p, &settings) {
        Err(SolverError::NotConverged {
            iterations,
            residual,
            history,
            ..
        }) => {
            assert_eq!(iterations, 3);
            assert_eq!(history.len(), 3);
            assert_eq!(history[2], residual);
        }
        other => panic!("expected NotConverged, got {other:?}"),
    }
    let settings = settings.with_accept_non_converged(true);
    let s = solve_coulomb(&p, &settings).unwrap();
    assert!(!s.report.converged);
    assert_eq!(s.report.history.len(), 3);
}

#[test]
fn warm_start_from_the_solution_converges_at_once() {
    use contact_solver::UzawaSolver;
    let p = random_problem(10, 2);
    let laws = p.coulomb_laws();
    let mut solver = UzawaSolver::new(UzawaSettings::default());
    let first = solver.solve(&p, &laws).unwrap();
    let again = solver
        .solve_with_states(&p, &laws, &[()], Some(&first.r))
        .unwrap();
    assert!(again.report.iterations <= 2);
}
