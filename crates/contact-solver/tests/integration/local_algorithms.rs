//! The accelerated and Newton local solvers (`Algorithm::AndersonGaussSeidel`,
//! `Algorithm::AndersonUzawa`, `Algorithm::Newton`) against the projected Gauss–Seidel sweep
//! and closed forms.
//!
//! Reference: every algorithm solves the same fixed point `r = P_K(r + ρ v(W r + q))`
//! (De Saxcé, Feng 1998; seed 5.26) and stops on the same rule (relative change of `r` and
//! natural-map residual ≤ tol, `docs/theory.md` §13), so on problems with a unique solution
//! they reach the same `r`. Anderson acceleration: Walker, Ni 2011; semi-smooth Newton on the
//! projection equation: Alart, Curnier 1991, Qi, Sun 1993 (Siconos' NSN-AC is the same idea on
//! the Alart–Curnier form).
//!
//! Cases:
//! - seeded random SPD problems (`generate::random_problem`, `n_c` = 10, 50, 100, `μ ~ U(0, 1)`),
//!   and the same with RCCM laws at `β = 0.5` (μ̄ read through `friction_coefficient`);
//! - the FE-like reduced problem exported by the Hertz scene (`tests/support/hertz_scene.rs`,
//!   P2, plane strain, 8 × 8 fine cells), frictionless as exported, and with `μ = 0.3` and a
//!   tangential shift `q_t + 10⁻⁴` of the flat (partial slip: stick, slip and separation at
//!   once);
//! - a tangentially supported contact (`W = [1 0; 0 0]`, a corner on a support), where the
//!   Newton system has no tangential equation;
//! - one contact with `W = diag(f, f)`: Signorini, stick, slip and separation closed forms;
//! - issue 8's hardest friction case: a block (E = 1000, ν = 0, P1 8 × 4) pressed by 0.01 and
//!   pushed sideways by 0.05 on a rigid flat with `μ = 10`: it tips, three nodes lift off, two
//!   slip and four stick, and Gauss–Seidel needs 54 000 sweeps;
//! - typed errors: a law without friction coefficient and a negative one for Newton, a capped
//!   iteration for every algorithm.

#![cfg(feature = "fe")]

use crate::support::hertz_scene::HertzScene;
use contact_solver::contact_laws::{
    BetaScheme, ContactLaw, ContactStatus, Coulomb, LawError, LocalVec, Rccm, RccmParams, RccmState,
};
use contact_solver::local::generate::random_problem;
use contact_solver::{
    Algorithm, ReducedProblem, SimulationSettings, Solution, SolverError, UzawaSettings,
    UzawaSolver,
};
use contact_solver::{ContactSimulation, ContactZone, RigidLine};
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::{Component, ElementKind, Idealization, LinearElasticModel, Material, Supports};

const NEW: [Algorithm; 3] = [
    Algorithm::AndersonGaussSeidel,
    Algorithm::AndersonUzawa,
    Algorithm::Newton,
];

fn settings(algorithm: Algorithm) -> UzawaSettings {
    UzawaSettings::default()
        .with_algorithm(algorithm)
        .with_max_iterations(100_000)
}

fn solve<L: ContactLaw>(p: &ReducedProblem, laws: &[L], algorithm: Algorithm) -> Solution {
    UzawaSolver::new(settings(algorithm))
        .solve(p, laws)
        .unwrap_or_else(|e| panic!("{algorithm:?}: {e}"))
}

fn relative_distance(a: &[f64], b: &[f64]) -> f64 {
    let d: f64 = a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum();
    let n: f64 = b.iter().map(|y| y * y).sum();
    (d / n).sqrt()
}

/// The report's bookkeeping: one residual per iteration, the rule met at the returned
/// iterate, and `x` returned as `W r + q` exactly.
fn check_report(p: &ReducedProblem, s: &Solution, algorithm: Algorithm) {
    let rep = &s.report;
    assert_eq!(rep.algorithm, algorithm);
    assert!(rep.converged);
    assert_eq!(rep.history.len(), rep.iterations, "{algorithm:?}");
    if rep.iterations > 0 {
        assert_eq!(rep.history.last(), Some(&rep.residual));
    } else {
        // every gap open: r = 0 answered without iterating
        assert!(s.r.iter().all(|&v| v == 0.0) && rep.residual == 0.0);
    }
    assert!(
        rep.residual <= 1e-10 && rep.change <= 1e-10,
        "{algorithm:?}: {rep:?}"
    );
    assert!(rep.outer_iterations <= rep.iterations);
    let mut x = vec![0.0; p.size()];
    p.displacement_into(&s.r, &mut x);
    assert_eq!(s.x, x);
}

/// The Hertz scene's reduced problem (P2, plane strain, 8 × 8 fine cells, frictionless).
fn hertz_problem() -> ReducedProblem {
    let scene = HertzScene::new(Idealization::PlaneStrain, ElementKind::Tri6, 8);
    let mut sim = scene.simulation(SimulationSettings::default());
    sim.step(1.0, 1.0).expect("the Hertz step converges");
    sim.last_reduced_problem()
        .expect("the step solved a reduced problem")
        .clone()
}

#[test]
fn local_algorithms_match_gauss_seidel_on_random_problems() {
    for (nc, seed) in [(10, 1), (10, 2), (50, 3), (100, 4)] {
        let p = random_problem(nc, seed);
        let laws = p.coulomb_laws();
        let gs = solve(&p, &laws, Algorithm::GaussSeidel);
        for algorithm in NEW {
            let s = solve(&p, &laws, algorithm);
            check_report(&p, &s, algorithm);
            // Both stop at a relative residual of 1e-10 on problems of condition number ≈ 40,
            // so both are within ≈ 4e-9 of the solution; 1e-8 leaves margin.
            let d = relative_distance(&s.r, &gs.r);
            assert!(d <= 1e-8, "{algorithm:?}, n_c = {nc}: |Δr|/|r| = {d:e}");
            assert_eq!(s.report.statuses, gs.report.statuses, "{algorithm:?}");
        }
    }
}

#[test]
fn local_algorithms_match_gauss_seidel_on_the_hertz_problem() {
    let frictionless = hertz_problem();
    let nc = frictionless.contact_count();
    let q: Vec<f64> = (frictionless.q().iter().enumerate())
        .map(|(k, &a)| if k % 2 == 1 { a + 1e-4 } else { a })
        .collect();
    let frictional =
        ReducedProblem::new(frictionless.w_dense().unwrap().to_vec(), q, vec![0.3; nc]).unwrap();
    for (name, p) in [("frictionless", frictionless), ("shifted", frictional)] {
        let laws = p.coulomb_laws();
        let gs = solve(&p, &laws, Algorithm::GaussSeidel);
        if name == "shifted" {
            let count = |k| gs.report.statuses.iter().filter(|&&s| s == k).count();
            let statuses = [
                ContactStatus::Separation,
                ContactStatus::Stick,
                ContactStatus::Slip,
            ];
            assert!(
                statuses.iter().all(|&k| count(k) > 0),
                "{:?}",
                gs.report.statuses
            );
        }
        for algorithm in NEW {
            let s = solve(&p, &laws, algorithm);
            check_report(&p, &s, algorithm);
            // This W is far worse conditioned than the random ones (the flexibility of a
            // refined mesh; cond of the active block ≈ 1e3): at a residual of 1e-10 the
            // iterates differ by up to ≈ 2e-9 (measured); 1e-7 leaves margin.
            let d = relative_distance(&s.r, &gs.r);
            assert!(d <= 1e-7, "{name}, {algorithm:?}: |Δr|/|r| = {d:e}");
        }
        // Newton converges in a handful of factorisations on this FE-like problem, where the
        // sweeps need about a hundred.
        let newton = solve(&p, &laws, Algorithm::Newton);
        assert!(
            newton.report.outer_iterations <= 15 && gs.report.iterations >= 50,
            "{name}: Newton {} steps, Gauss–Seidel {} sweeps",
            newton.report.outer_iterations,
            gs.report.iterations
        );
    }
}

#[test]
fn local_algorithms_match_gauss_seidel_with_rccm_states() {
    // RCCM with β = 0.5, m = 1: μ̄ = μ (1 − β) = 0.15 through friction_coefficient.
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
    // μ has one owner, the law (issue 35): the problem carries the laws' μ̄ = 0.15
    let p = random_problem(10, 4)
        .with_friction_of(&[law], &[state])
        .unwrap();
    let gs = UzawaSolver::new(settings(Algorithm::GaussSeidel))
        .solve_with_states(&p, &[law], &[state], None)
        .unwrap();
    for algorithm in NEW {
        let s = UzawaSolver::new(settings(algorithm))
            .solve_with_states(&p, &[law], &[state], None)
            .unwrap();
        check_report(&p, &s, algorithm);
        // As on the random problems: both within a few 1e-9 of the solution.
        assert!(relative_distance(&s.r, &gs.r) <= 1e-8, "{algorithm:?}");
        assert_eq!(s.report.statuses, gs.report.statuses);
    }
}

#[test]
fn single_contact_closed_forms_work() {
    // W = diag(f, f), q = (−1, q_t): Signorini r = (1/f, 0); stick (μ = 0.8) r = −q/f;
    // slip (μ = 0.2) r = (1/f, −μ/f); separation (q_n = +1) r = 0.
    let f = 2.0;
    let cases = [
        ([-1.0, 0.5], 0.0, [0.5, 0.0]),
        ([-1.0, 0.5], 0.8, [0.5, -0.25]),
        ([-1.0, 0.5], 0.2, [0.5, -0.1]),
        ([1.0, 0.5], 0.2, [0.0, 0.0]),
    ];
    for (q, mu, r) in cases {
        let p = ReducedProblem::new(vec![f, 0.0, 0.0, f], q.to_vec(), vec![mu]).unwrap();
        for algorithm in NEW {
            let s = solve(&p, &p.coulomb_laws(), algorithm);
            check_report(&p, &s, algorithm);
            // A 2×2 problem solved to a relative residual of 1e-10: exact to rounding.
            for (got, want) in s.r.iter().zip(r) {
                assert!(
                    (got - want).abs() <= 1e-9,
                    "{algorithm:?}, q = {q:?}, μ = {mu}: r = {:?}",
                    s.r
                );
            }
        }
    }
}

#[test]
fn newton_handles_a_tangentially_supported_contact() {
    // W = [1 0; 0 0]: x_t = q_t whatever r_t. With q_t = 0 every r_t in the cone solves the
    // tangential part; from r = 0 the solution r = (1, 0) is reached. With q_t ≠ 0 the
    // contact must slip: r_t = −μ r_n sign(q_t).
    for (q_t, r_t) in [(0.0, 0.0), (0.5, -0.3)] {
        let p = ReducedProblem::new(vec![1.0, 0.0, 0.0, 0.0], vec![-1.0, q_t], vec![0.3]).unwrap();
        let s = solve(&p, &p.coulomb_laws(), Algorithm::Newton);
        check_report(&p, &s, Algorithm::Newton);
        // Exact to rounding (see above).
        assert!(
            (s.r[0] - 1.0).abs() <= 1e-9 && (s.r[1] - r_t).abs() <= 1e-9,
            "{:?}",
            s.r
        );
    }
}

#[test]
fn local_algorithms_are_robust_to_rho_scale() {
    let p = random_problem(20, 5);
    let laws = p.coulomb_laws();
    let reference = solve(&p, &laws, Algorithm::GaussSeidel);
    for algorithm in NEW {
        for rho_scale in [1e-3, 1e3] {
            let st = settings(algorithm).with_rho_scale(rho_scale);
            let s = UzawaSolver::new(st).solve(&p, &laws).unwrap();
            // Same argument as on the random problems.
            let d = relative_distance(&s.r, &reference.r);
            assert!(d <= 1e-8, "{algorithm:?}, rho_scale = {rho_scale}: {d:e}");
        }
    }
}

#[test]
fn newton_warm_started_at_the_solution_stops_at_once() {
    let p = random_problem(30, 6);
    let laws = p.coulomb_laws();
    let gs = solve(&p, &laws, Algorithm::GaussSeidel);
    let states = vec![(); 1];
    let s = UzawaSolver::new(settings(Algorithm::Newton))
        .solve_with_states(&p, &laws, &states, Some(&gs.r))
        .unwrap();
    check_report(&p, &s, Algorithm::Newton);
    assert!(s.report.iterations <= 3, "{:?}", s.report);
}

/// Tresca friction: not a Coulomb-type law (`friction_coefficient` is `None`).
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
fn newton_captures_a_law_without_friction_coefficient() {
    let p = random_problem(5, 1);
    let laws = [Tresca { s: 0.2 }];
    // The accelerated sweeps need no μ̄: they solve the Tresca problem.
    for algorithm in [Algorithm::AndersonGaussSeidel, Algorithm::AndersonUzawa] {
        assert!(solve(&p, &laws, algorithm).report.converged);
    }
    let e = UzawaSolver::new(settings(Algorithm::Newton)).solve(&p, &laws);
    assert_eq!(e, Err(SolverError::NoFrictionCoefficient { contact: 0 }));
    let e = UzawaSolver::new(settings(Algorithm::Newton))
        .solve(&p, &[BadMu(Coulomb::new(0.3).unwrap())]);
    assert!(matches!(
        e,
        Err(SolverError::InvalidLaw {
            contact: 0,
            source: LawError::InvalidParameter { name: "mu_bar", .. }
        })
    ));
}

#[test]
fn local_algorithms_capture_non_convergence() {
    let p = random_problem(20, 1);
    let laws = p.coulomb_laws();
    for algorithm in NEW {
        // the algorithm's own capture, without the fallback to the classical solver
        let st = settings(algorithm)
            .with_max_iterations(2)
            .with_fallback(false);
        match UzawaSolver::new(st).solve(&p, &laws) {
            Err(SolverError::NotConverged {
                iterations,
                residual,
                history,
                ..
            }) => {
                assert_eq!(iterations, 2, "{algorithm:?}");
                assert_eq!(history.len(), 2);
                assert_eq!(history.last(), Some(&residual));
                assert!(residual > 1e-10 && residual.is_finite());
            }
            other => panic!("{algorithm:?}: expected NotConverged, got {other:?}"),
        }
        let st = settings(algorithm)
            .with_accept_non_converged(true)
            .with_max_iterations(2);
        let s = UzawaSolver::new(st).solve(&p, &laws).unwrap();
        assert!(!s.report.converged && s.r.iter().all(|a| a.is_finite()));
    }
}

#[test]
fn solver_reuse_across_algorithms_works() {
    // Scratch buffers are resized per solve: a solver that ran a large problem, then a small
    // one, gives the answer of a fresh solver.
    let big = random_problem(30, 9);
    let small = random_problem(4, 2);
    for algorithm in NEW {
        let mut solver = UzawaSolver::new(settings(algorithm));
        solver.solve(&big, &big.coulomb_laws()).unwrap();
        let reused = solver.solve(&small, &small.coulomb_laws()).unwrap();
        assert_eq!(reused, solve(&small, &small.coulomb_laws(), algorithm));
    }
}

/// The reduced problem of the push step of issue 8's tipping block (see the file header).
fn tipping_block_problem() -> ReducedProblem {
    let mut spec = RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 8, 4);
    spec.kind = ElementKind::Tri3;
    let mesh = rectangle(&spec).unwrap();
    let top = mesh.node_set("top").unwrap().to_vec();
    let bottom = mesh.node_set("bottom").unwrap().to_vec();
    let mut supports = Supports::new();
    supports.prescribe(&top, Component::Y, -0.01).unwrap();
    supports.prescribe(&top, Component::X, 0.0).unwrap();
    let material = Material::new(1000.0, 0.0, 0.0).unwrap();
    let model =
        LinearElasticModel::new(mesh, Idealization::PlaneStrain, &[(0, material)], supports)
            .unwrap();
    let ground = RigidLine::new([-1.0, 0.0], [3.0, 0.0]).unwrap();
    let zone = ContactZone::rigid("base", bottom, ground, Coulomb::new(10.0).unwrap(), 0.1);
    let mut settings = SimulationSettings::default();
    settings.solver.algorithm = Algorithm::Newton;
    let mut sim = ContactSimulation::new(model, vec![zone], settings).unwrap();
    sim.step(1.0, 1.0).unwrap();
    sim.structure_mut()
        .set_prescribed(&top, Component::X, 0.05)
        .unwrap();
    sim.step(2.0, 1.0).unwrap();
    sim.last_reduced_problem().unwrap().clone()
}

#[test]
fn issue_8_tipping_block_with_mu_10_converges() {
    let p = tipping_block_problem();
    let laws = p.coulomb_laws();
    let newton = solve(&p, &laws, Algorithm::Newton);
    check_report(&p, &newton, Algorithm::Newton);
    let count = |s: &Solution, k| s.report.statuses.iter().filter(|&&a| a == k).count();
    assert_eq!(count(&newton, ContactStatus::Separation), 3);
    assert_eq!(count(&newton, ContactStatus::Slip), 2);
    assert_eq!(count(&newton, ContactStatus::Stick), 4);
    for algorithm in [
        Algorithm::GaussSeidel,
        Algorithm::AndersonGaussSeidel,
        Algorithm::AndersonUzawa,
    ] {
        let s = solve(&p, &laws, algorithm);
        check_report(&p, &s, algorithm);
        eprintln!(
            "{algorithm:?}: {} iterations, |r − r_Newton|/|r| = {:e}",
            s.report.iterations,
            relative_distance(&s.r, &newton.r)
        );
        // The sweeps contract by about 1 − 2e-4 per iteration here (50 000 sweeps), so
        // stopping at a change of 1e-10 leaves an error up to ≈ 1e-10/2e-4 = 5e-7 (measured
        // 3e-8 to 1e-7 against Newton, whose residual is 1e-15); 1e-6 leaves margin.
        let d = relative_distance(&s.r, &newton.r);
        assert!(d <= 1e-6, "{algorithm:?}: |Δr|/|r| = {d:e}");
        assert_eq!(s.report.statuses, newton.report.statuses, "{algorithm:?}");
    }
}
