//! The classical RCCM solver (`Algorithm::ClassicRccm`) against the bipotential Gauss–Seidel
//! sweep and closed forms.
//!
//! Reference: the classical treatment of contact with friction as two separate problems —
//! Signorini at fixed friction, friction (Tresca) at a fixed threshold `s = μ r_n`, with a
//! fixed point on `s` (Panagiotopoulos 1975; Raous, Chabrand & Lebon 1988; GYPTIS, Latil &
//! Raous 1991) — as compared with the bipotential in Terfaya 2019 §5.6, tables 5.1–5.2. Both
//! solvers stop on the same rule (relative change of `r` and natural-map residual ≤ tol), so
//! on the same problem they must reach the same (unique, for these SPD problems with the
//! random μ) solution.
//!
//! Cases:
//! - seeded random SPD problems (`generate::random_problem`, `n_c` = 10 and 50, three seeds,
//!   Coulomb with `μ ~ U(0, 1)`), and the same problems with RCCM laws at `β = 0.5`;
//! - the same `W`, `q` with `μ = 0` (Signorini only: the friction sub-problem never runs);
//! - one contact, `W = diag(f, f)`, `q = (−1, 0.5)`: Signorini `r = (1/f, 0)`, stick
//!   (μ = 0.8) `r = (1/f, −0.5/f)`, slip (μ = 0.2) `r_t = −μ r_n`, separation `r = 0`;
//! - typed errors: a Tresca law (no friction coefficient), a law with `μ̄ < 0`, `ω ∉ (0, 2)`,
//!   and a capped iteration.

use approx::assert_relative_eq;
use contact_solver::contact_laws::{
    BetaScheme, ContactLaw, ContactStatus, Coulomb, LawError, LocalVec, Rccm, RccmParams, RccmState,
};
use contact_solver::local::generate::random_problem;
use contact_solver::{
    Algorithm, ReducedProblem, Solution, SolverError, UzawaSettings, UzawaSolver,
};

fn settings(algorithm: Algorithm) -> UzawaSettings {
    UzawaSettings::default()
        .with_algorithm(algorithm)
        .with_max_iterations(100_000)
}

fn solve<L: ContactLaw>(p: &ReducedProblem, laws: &[L], algorithm: Algorithm) -> Solution {
    UzawaSolver::new(settings(algorithm))
        .solve(p, laws)
        .unwrap()
}

fn relative_distance(a: &[f64], b: &[f64]) -> f64 {
    let d: f64 = a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum();
    let n: f64 = b.iter().map(|y| y * y).sum();
    (d / n).sqrt()
}

/// The bookkeeping of the report: sweeps = normal + tangential, one residual per outer
/// iteration, at least one sweep of each kind per outer iteration.
fn check_counts(s: &Solution, frictional: bool) {
    let rep = &s.report;
    assert_eq!(rep.algorithm, Algorithm::ClassicRccm);
    assert!(rep.converged);
    assert_eq!(rep.history.len(), rep.outer_iterations);
    assert_eq!(rep.history.last(), Some(&rep.residual));
    assert!(rep.residual <= 1e-10 && rep.change <= 1e-10);
    let normal = rep.iterations - rep.tangential_sweeps;
    assert!(normal >= rep.outer_iterations);
    if frictional {
        assert!(rep.tangential_sweeps >= rep.outer_iterations);
    } else {
        assert_eq!(rep.tangential_sweeps, 0);
    }
}

#[test]
fn classic_matches_gauss_seidel_on_random_problems() {
    for nc in [10, 50] {
        for seed in [1, 2, 3] {
            let p = random_problem(nc, seed);
            let laws = p.coulomb_laws();
            let gs = solve(&p, &laws, Algorithm::GaussSeidel);
            let cl = solve(&p, &laws, Algorithm::ClassicRccm);
            check_counts(&cl, true);
            // Both stop at a relative residual of 1e-10 on problems of condition number ≈ 40:
            // the iterates are within ≈ 3e-10 of each other (measured); 1e-8 leaves margin.
            let d = relative_distance(&cl.r, &gs.r);
            assert!(d <= 1e-8, "n_c = {nc}, seed {seed}: |Δr|/|r| = {d:e}");
            assert_eq!(cl.report.statuses, gs.report.statuses);
            // x is returned as W r + q.
            let mut x = vec![0.0; p.size()];
            p.displacement_into(&cl.r, &mut x);
            assert_eq!(cl.x, x);
        }
    }
}

#[test]
fn classic_matches_gauss_seidel_with_rccm_states() {
    // RCCM with β = 0.5, m = 1: μ̄ = μ (1 − β) = 0.15 read through friction_coefficient.
    let law = Rccm::new(RccmParams {
        c_n: 1.0,
        c_t: 1.0,
        w: 1.0,
        alpha: 0.0,
        mu: 0.3,
        m: 1,
        beta_0: 1.0,
        scheme: BetaScheme::ImplicitEuler,
    })
    .unwrap();
    let state = RccmState::new(0.5).unwrap();
    assert_relative_eq!(
        law.friction_coefficient(&state).unwrap(),
        0.15,
        epsilon = 1e-15
    );
    // μ has one owner, the law (issue 35): the problem carries the laws' μ̄ = 0.15
    let p = random_problem(10, 4)
        .with_friction_of(&[law], &[state])
        .unwrap();
    let mut gs_solver = UzawaSolver::new(settings(Algorithm::GaussSeidel));
    let gs = gs_solver
        .solve_with_states(&p, &[law], &[state], None)
        .unwrap();
    let mut solver = UzawaSolver::new(settings(Algorithm::ClassicRccm));
    let cl = solver
        .solve_with_states(&p, &[law], &[state], None)
        .unwrap();
    check_counts(&cl, true);
    // Same argument as above: both within a few 1e-10 of the solution.
    assert!(relative_distance(&cl.r, &gs.r) <= 1e-8);
    // Slip contacts sit on the cone of μ̄ = 0.15, not of μ = 0.3.
    for (i, st) in cl.report.statuses.iter().enumerate() {
        if *st == ContactStatus::Slip {
            assert_relative_eq!(
                cl.r[2 * i + 1].abs(),
                0.15 * cl.r[2 * i],
                max_relative = 1e-8
            );
        }
    }
}

#[test]
fn frictionless_skips_the_friction_sub_problem() {
    for seed in [1, 2] {
        let p0 = random_problem(20, seed);
        let p = ReducedProblem::new(
            p0.w_dense().unwrap().to_vec(),
            p0.q().to_vec(),
            vec![0.0; 20],
        )
        .unwrap();
        let laws = p.coulomb_laws();
        let gs = solve(&p, &laws, Algorithm::GaussSeidel);
        // A warm start with r_t ≠ 0: the classic solver drops it.
        let r_start: Vec<f64> = (0..p.size()).map(|k| 0.1 * (k % 3) as f64).collect();
        let mut solver = UzawaSolver::new(settings(Algorithm::ClassicRccm));
        let states = [()];
        let cl = solver
            .solve_with_states(&p, &laws, &states, Some(&r_start))
            .unwrap();
        check_counts(&cl, false);
        // Every sweep was a Signorini sweep.
        assert_eq!(cl.report.tangential_sweeps, 0);
        assert!(cl.r.iter().skip(1).step_by(2).all(|&r_t| r_t == 0.0));
        // 1e-8: as in the frictional comparison.
        assert!(relative_distance(&cl.r, &gs.r) <= 1e-8);
    }
}

#[test]
fn sweep_counts_are_printed() {
    // `cargo test -p contact-solver --test integration -- --nocapture classic::sweep_counts`
    // prints the figures quoted in the docs of `contact_solver::local::classic`, and checks them.
    println!("n_c seed | GS sweeps | classic sweeps (tangential) outer");
    // (n_c, seed, classic sweeps quoted in the docs of `contact_solver::local::classic`)
    for (nc, seed, quoted) in [
        (10, 1, 486),
        (10, 2, 179),
        (10, 3, 233),
        (50, 1, 228),
        (50, 2, 268),
        (100, 3, 393),
    ] {
        let p = random_problem(nc, seed);
        let laws = p.coulomb_laws();
        let gs = solve(&p, &laws, Algorithm::GaussSeidel);
        let cl = solve(&p, &laws, Algorithm::ClassicRccm);
        check_counts(&cl, true);
        let rep = &cl.report;
        println!(
            "{nc:3} {seed:4} | {:9} | {:14} ({:3}) {:5}",
            gs.report.iterations, rep.iterations, rep.tangential_sweeps, rep.outer_iterations
        );
        // ±10 %: the counts are deterministic, but a change of rounding (another platform's
        // libm, a reordered sum) may move the last sweeps; a change of the algorithm moves more.
        let (lo, hi) = (quoted * 9 / 10, quoted * 11 / 10);
        assert!(
            (lo..=hi).contains(&rep.iterations),
            "n_c = {nc}, seed {seed}: {} sweeps, the docs quote {quoted}",
            rep.iterations
        );
    }
}

const F: f64 = 2.5e-3; // a flexibility in mm/N, as in tests/integration/single_contact.rs

fn single(q: [f64; 2], mu: f64) -> Solution {
    let p = ReducedProblem::new(vec![F, 0.0, 0.0, F], q.to_vec(), vec![mu]).unwrap();
    solve(&p, &p.coulomb_laws(), Algorithm::ClassicRccm)
}

#[test]
fn single_contact_signorini_works() {
    let s = single([-1.0, 0.5], 0.0);
    // One decoupled contact with ω = 1: the Signorini sweep is exact, 1e-12 is rounding.
    assert_relative_eq!(s.r[0], 1.0 / F, max_relative = 1e-12);
    assert_eq!(s.r[1], 0.0);
    assert_eq!(s.report.tangential_sweeps, 0);
    assert_eq!(s.report.statuses, vec![ContactStatus::Slip]);
}

#[test]
fn single_contact_stick_works() {
    let s = single([-1.0, 0.5], 0.8);
    // 1e-9 relative: ten times the solver's tolerance (as in tests/integration/single_contact.rs).
    assert_relative_eq!(s.r[0], 1.0 / F, max_relative = 1e-9);
    assert_relative_eq!(s.r[1], -0.5 / F, max_relative = 1e-9);
    assert_eq!(s.report.statuses, vec![ContactStatus::Stick]);
    check_counts(&s, true);
}

#[test]
fn single_contact_slip_works() {
    let s = single([-1.0, 0.5], 0.2);
    assert_relative_eq!(s.r[0], 1.0 / F, max_relative = 1e-9);
    assert_relative_eq!(s.r[1], -0.2 * s.r[0], max_relative = 1e-9);
    assert_eq!(s.report.statuses, vec![ContactStatus::Slip]);
    check_counts(&s, true);
}

#[test]
fn single_contact_separation_works() {
    let s = single([0.3, 0.5], 0.5);
    assert_eq!(s.r, vec![0.0, 0.0]);
    assert_eq!(s.x, vec![0.3, 0.5]);
    assert_eq!(s.report.statuses, vec![ContactStatus::Separation]);
    // Every gap open (q_n ≥ 0): r = 0 is the exact solution, answered before any sweep.
    assert_eq!(
        (
            s.report.iterations,
            s.report.tangential_sweeps,
            s.report.outer_iterations
        ),
        (0, 0, 0)
    );
}

/// Tresca friction (threshold `s` independent of `r_n`): not a Coulomb-type law, so
/// `friction_coefficient` keeps its default `None` (see contact-laws'
/// tests/integration/user_law.rs).
#[derive(Clone, Copy, Debug)]
struct Tresca {
    s: f64,
}

impl ContactLaw for Tresca {
    type State = ();

    fn has_friction(&self) -> bool {
        self.s > 0.0
    }

    fn project<const DT: usize>(&self, tau: &LocalVec<DT>, _: &()) -> LocalVec<DT> {
        let tt = tau.t_norm();
        let t = if tt > self.s {
            tau.t * (self.s / tt)
        } else {
            tau.t
        };
        LocalVec::new(tau.n.max(0.0), t)
    }

    fn modified_velocity<const DT: usize>(&self, du: &LocalVec<DT>, _: &()) -> LocalVec<DT> {
        -*du
    }

    fn bipotential<const DT: usize>(&self, du: &LocalVec<DT>, r: &LocalVec<DT>, _: &()) -> f64 {
        if r.n < 0.0 || r.t_norm() > self.s * (1.0 + 1e-14) || du.n < 0.0 {
            return f64::INFINITY;
        }
        self.s * du.t_norm()
    }
}

/// A Coulomb law that reports a negative friction coefficient (a buggy user law).
#[derive(Clone, Copy, Debug)]
struct BadMu(Coulomb);

impl ContactLaw for BadMu {
    type State = ();

    fn has_friction(&self) -> bool {
        true
    }

    fn friction_coefficient(&self, _: &()) -> Option<f64> {
        Some(-0.1)
    }

    fn project<const DT: usize>(&self, tau: &LocalVec<DT>, s: &()) -> LocalVec<DT> {
        self.0.project(tau, s)
    }

    fn modified_velocity<const DT: usize>(&self, du: &LocalVec<DT>, s: &()) -> LocalVec<DT> {
        self.0.modified_velocity(du, s)
    }

    fn bipotential<const DT: usize>(&self, du: &LocalVec<DT>, r: &LocalVec<DT>, s: &()) -> f64 {
        self.0.bipotential(du, r, s)
    }
}

#[test]
fn classic_captures_a_law_without_friction_coefficient() {
    let p = random_problem(5, 1);
    let mut laws = vec![Tresca { s: 0.2 }; 5];
    // The bipotential sweep does not need μ̄: it solves the Tresca problem.
    assert!(solve(&p, &laws, Algorithm::GaussSeidel).report.converged);
    let e = UzawaSolver::new(settings(Algorithm::ClassicRccm)).solve(&p, &laws);
    assert_eq!(e, Err(SolverError::NoFrictionCoefficient { contact: 0 }));
    assert!(e.unwrap_err().to_string().contains("contact 0"));
    // The first offending contact is named.
    laws[0] = Tresca { s: 0.0 };
    let e = UzawaSolver::new(settings(Algorithm::ClassicRccm)).solve(&p, &laws);
    assert_eq!(e, Err(SolverError::NoFrictionCoefficient { contact: 0 }));
}

#[test]
fn classic_captures_a_negative_friction_coefficient() {
    let p = random_problem(3, 1);
    let laws = [BadMu(Coulomb::new(0.3).unwrap())];
    let e = UzawaSolver::new(settings(Algorithm::ClassicRccm)).solve(&p, &laws);
    assert!(matches!(
        e,
        Err(SolverError::InvalidLaw {
            contact: 0,
            source: LawError::InvalidParameter { name: "mu_bar", .. }
        })
    ));
}

#[test]
fn solve_captures_invalid_omega() {
    let p = random_problem(3, 1);
    let laws = p.coulomb_laws();
    for omega in [0.0, 2.0, -1.0, f64::NAN, f64::INFINITY] {
        for algorithm in [Algorithm::ClassicRccm, Algorithm::GaussSeidel] {
            let st = settings(algorithm).with_omega(omega);
            let e = UzawaSolver::new(st).solve(&p, &laws).unwrap_err();
            match e {
                SolverError::InvalidSetting {
                    what: "omega",
                    value,
                    ..
                } => assert!(value.to_bits() == omega.to_bits()),
                other => panic!("omega = {omega}: expected InvalidSetting, got {other:?}"),
            }
        }
    }
    // Inside (0, 2) over-relaxation converges to the same solution.
    let reference = solve(&p, &laws, Algorithm::GaussSeidel);
    for omega in [0.5, 1.5, 1.9] {
        let st = settings(Algorithm::ClassicRccm).with_omega(omega);
        let s = UzawaSolver::new(st).solve(&p, &laws).unwrap();
        // As in the random comparison: both within a few 1e-10 of the solution.
        assert!(
            relative_distance(&s.r, &reference.r) <= 1e-8,
            "omega = {omega}"
        );
    }
}

#[test]
fn classic_captures_non_convergence() {
    let p = random_problem(10, 1);
    let laws = p.coulomb_laws();
    let st = settings(Algorithm::ClassicRccm).with_max_iterations(5);
    match UzawaSolver::new(st).solve(&p, &laws) {
        Err(SolverError::NotConverged {
            iterations,
            residual,
            history,
            ..
        }) => {
            assert_eq!(iterations, 5);
            assert!(!history.is_empty());
            assert_eq!(history.last(), Some(&residual));
            assert!(residual > 1e-10);
        }
        other => panic!("expected NotConverged, got {other:?}"),
    }
    let st = st.with_accept_non_converged(true);
    let s = UzawaSolver::new(st).solve(&p, &laws).unwrap();
    assert!(!s.report.converged);
    assert_eq!(s.report.iterations, 5);
}

#[test]
fn solver_reuse_across_algorithms_works() {
    // The scratch buffers are resized per solve: a solver that ran a large problem then a
    // small one, and the classic after the bipotential, gives the same answer as a fresh one.
    let big = random_problem(30, 9);
    let small = random_problem(4, 2);
    let mut solver = UzawaSolver::new(settings(Algorithm::ClassicRccm));
    solver.solve(&big, &big.coulomb_laws()).unwrap();
    let reused = solver.solve(&small, &small.coulomb_laws()).unwrap();
    let fresh = solve(&small, &small.coulomb_laws(), Algorithm::ClassicRccm);
    assert_eq!(reused, fresh);
}
