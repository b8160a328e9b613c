//! Issue 40: the global Newton around contact on a structure of the user's own with a
//! state-dependent tangent — a spring chain pressed onto a rigid line and pulled along it,
//! with Coulomb friction — against its closed form.
//!
//! ```text
//!   wall ──A── node 1 ──B── node 0  → λ F           A: elastic–plastic, linear hardening
//!                           │   ↓ P                   (k_a, yield force f_y, modulus h)
//!                           C                      B: hardening, N = k_b e + c e³
//!   ════════════════════ rigid line y = 0 ════      C: vertical, k_y; node 0 on the line
//! ```
//! Node 0 is pressed by the dead load `P` (`r_n = P`, C carries nothing) and pulled by `λ F`.
//! It sticks while `λ F ≤ μ P` (`u_0 = 0`, `r_t = −λ F`); past that it slides, and the springs
//! in series carry `N = λ F − μ P`: `u_1 = N / k_a + max(N − f_y, 0) / h` (A, monotonic
//! loading) and `u_0 = u_1 + e` with `k_b e + c e³ = N` (Cardano). With `h = 0` (perfectly
//! plastic) the chain holds at most `N = f_y`: no equilibrium exists past `λ F = f_y + μ P`.
//! The cubic spring makes the Newton's residuals shrink quadratically where A is elastic.

#![cfg(feature = "fe")]

use contact_laws::Coulomb;
use contact_solver::{
    ContactSimulation, ContactZone, FlexibilityMode, InterfaceStatus, NewtonSettings, RigidLine,
    SimulationSettings, SolverError, StepResult,
};
use fem_core::faer::MatMut;
use fem_core::faer::sparse::{SparseColMat, SparseColMatRef, Triplet};
use fem_core::{FemError, Nonlinear, Structure};

const K_A: f64 = 100.0;
const F_Y: f64 = 1.0;
const K_B: f64 = 50.0;
const C: f64 = 1.0e4;
const K_Y: f64 = 200.0;
const P: f64 = 10.0;
const F: f64 = 6.2;
const MU: f64 = 0.3;

/// Spring A's history: plastic displacement and accumulated plastic displacement.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Plastic {
    p: f64,
    alpha: f64,
}

/// The chain: dofs `0 = u_0x`, `1 = u_0y`, `2 = u_1x`.
struct Chain {
    /// Hardening modulus of A (0: perfectly plastic).
    h: f64,
    committed: Plastic,
    trial: Plastic,
    /// A's tangent at the trial state.
    k_a_t: f64,
    /// B's elongation at the trial state.
    e: f64,
    /// The factorised tangent (lower Cholesky factor, row-major 3 × 3).
    l: [[f64; 3]; 3],
    lower: SparseColMat<usize, f64>,
    version: u64,
}

impl Chain {
    fn new(h: f64) -> Self {
        let mut chain = Self {
            h,
            committed: Plastic::default(),
            trial: Plastic::default(),
            k_a_t: K_A,
            e: 0.0,
            l: [[0.0; 3]; 3],
            lower: SparseColMat::try_new_from_triplets(3, 3, &[Triplet::new(0, 0, 1.0)]).unwrap(),
            version: 0,
        };
        chain.factorise().unwrap();
        chain
    }

    /// A's force from the committed state at `u_1` (return mapping), into `trial`.
    fn spring_a(&mut self, u1: f64) -> f64 {
        let c = self.committed;
        let n_trial = K_A * (u1 - c.p);
        let phi = n_trial.abs() - (F_Y + self.h * c.alpha);
        if phi <= 0.0 {
            self.trial = c;
            self.k_a_t = K_A;
            return n_trial;
        }
        let dgamma = phi / (K_A + self.h);
        let sign = n_trial.signum();
        self.trial = Plastic {
            p: c.p + dgamma * sign,
            alpha: c.alpha + dgamma,
        };
        self.k_a_t = K_A * self.h / (K_A + self.h);
        n_trial - K_A * dgamma * sign
    }

    /// The tangent `K_t`, factorised (dense Cholesky) and as a lower CSC triangle.
    fn factorise(&mut self) -> Result<(), FemError> {
        let k_b = K_B + 3.0 * C * self.e * self.e;
        let k = [
            [k_b, 0.0, -k_b],
            [0.0, K_Y, 0.0],
            [-k_b, 0.0, k_b + self.k_a_t],
        ];
        let mut l = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..=i {
                let s = k[i][j] - (0..j).map(|m| l[i][m] * l[j][m]).sum::<f64>();
                if i == j {
                    // a pivot below 1e-12 of the diagonal: the tangent lost definiteness
                    if s <= 1e-12 * k[i][i] {
                        return Err(FemError::NonPositivePivot { row: Some(i) });
                    }
                    l[i][i] = s.sqrt();
                } else {
                    l[i][j] = s / l[j][j];
                }
            }
        }
        self.l = l;
        // the whole lower triangle: the active-set path needs a pattern that couples the
        // dofs of a contact node (0, 1) with every dof either is coupled to
        let t = [(0, 0), (1, 0), (2, 0), (1, 1), (2, 1), (2, 2)]
            .map(|(i, j)| Triplet::new(i, j, k[i][j]));
        self.lower = SparseColMat::try_new_from_triplets(3, 3, &t).unwrap();
        Ok(())
    }
}

impl Structure for Chain {
    fn dof_count(&self) -> usize {
        3
    }
    fn node_count(&self) -> usize {
        2
    }
    fn node_position(&self, node: usize) -> [f64; 2] {
        [[0.0, 0.0], [-1.0, 0.0]][node]
    }
    fn node_dofs(&self, node: usize) -> [Option<usize>; 2] {
        [[Some(0), Some(1)], [Some(2), None]][node]
    }
    fn prescribed_displacement(&self, _: usize) -> [f64; 2] {
        [0.0, 0.0]
    }
    fn solve_many_in_place(&self, mut rhs: MatMut<'_, f64>) -> Result<(), FemError> {
        let l = &self.l;
        for c in 0..rhs.ncols() {
            let mut y = [0.0; 3];
            for i in 0..3 {
                y[i] = (rhs[(i, c)] - (0..i).map(|m| l[i][m] * y[m]).sum::<f64>()) / l[i][i];
            }
            for i in (0..3).rev() {
                y[i] = (y[i] - (i + 1..3).map(|m| l[m][i] * y[m]).sum::<f64>()) / l[i][i];
            }
            for (i, v) in y.into_iter().enumerate() {
                rhs[(i, c)] = v;
            }
        }
        Ok(())
    }
    fn free_response_into(&self, factor: f64, u: &mut [f64]) -> Result<(), FemError> {
        u.copy_from_slice(&[factor * F, -P, 0.0]);
        self.solve_in_place(u)
    }
    fn stiffness_version(&self) -> u64 {
        self.version
    }
    fn stiffness_matrix(&self) -> Option<SparseColMatRef<'_, usize, f64>> {
        Some(self.lower.as_ref())
    }
    fn nonlinear(&mut self) -> Option<&mut dyn Nonlinear> {
        Some(self)
    }
}

impl Nonlinear for Chain {
    fn external_force_into(&self, factor: f64, f_ext: &mut [f64]) -> Result<(), FemError> {
        f_ext.copy_from_slice(&[factor * F, -P, 0.0]);
        Ok(())
    }
    fn internal_force_into(&mut self, u: &[f64], f_int: &mut [f64]) -> Result<(), FemError> {
        self.e = u[0] - u[2];
        let n_b = K_B * self.e + C * self.e.powi(3);
        let n_a = self.spring_a(u[2]);
        f_int.copy_from_slice(&[n_b, K_Y * u[1], n_a - n_b]);
        Ok(())
    }
    fn update_tangent(&mut self) -> Result<(), FemError> {
        self.factorise()?;
        self.version += 1;
        Ok(())
    }
    fn commit(&mut self) {
        self.committed = self.trial;
    }
    fn rollback(&mut self) {
        self.trial = self.committed;
    }
}

/// The closed form at `λ` (module docs): `(u_0x, u_1x, r_t)`.
fn closed_form(lambda: f64, h: f64) -> (f64, f64, f64) {
    let pull = lambda * F;
    if pull <= MU * P {
        return (0.0, 0.0, -pull);
    }
    let n = pull - MU * P;
    let u1 = n / K_A + if n > F_Y { (n - F_Y) / h } else { 0.0 };
    // Cardano: e³ + p e + q = 0, p = k_b / c > 0, one real root
    let (p, q) = (K_B / C, -n / C);
    let d = (0.25 * q * q + p * p * p / 27.0).sqrt();
    let e = (-0.5 * q + d).cbrt() + (-0.5 * q - d).cbrt();
    (u1 + e, u1, -MU * P)
}

fn chain_sim(
    h: f64,
    flexibility: FlexibilityMode,
    newton: NewtonSettings,
) -> ContactSimulation<Chain, Coulomb> {
    let ground = RigidLine::new([-5.0, 0.0], [5.0, 0.0]).unwrap();
    let zone = ContactZone::rigid("ground", vec![0], ground, Coulomb::new(MU).unwrap(), 0.1);
    let settings = SimulationSettings::default().with_flexibility(flexibility);
    ContactSimulation::new(Chain::new(h), vec![zone], settings)
        .unwrap()
        .with_newton(newton)
        .unwrap()
}

/// Checks a step's answer at `λ` against the closed form: 1e-8 of the pull's scale (the
/// Newton stops at 1e-12 of the forces, the reduced solver at 1e-10 of the reactions).
fn check_closed_form(
    sim: &ContactSimulation<Chain, Coulomb>,
    res: &StepResult,
    lambda: f64,
    h: f64,
) {
    let (u0, u1, r_t) = closed_form(lambda, h);
    let u = sim.displacement();
    let c = &res.contacts[0];
    assert!(
        (u[0] - u0).abs() <= 1e-8 * u0.abs().max(1e-3),
        "λ {lambda}: u_0 {} vs {u0}",
        u[0]
    );
    assert!(
        (u[2] - u1).abs() <= 1e-8 * u1.abs().max(1e-3),
        "λ {lambda}: u_1 {} vs {u1}",
        u[2]
    );
    assert!(
        u[1].abs() <= 1e-8 * P / K_Y,
        "the node stays on the line: {}",
        u[1]
    );
    assert!(
        (c.r.n - P).abs() <= 1e-8 * P,
        "λ {lambda}: r_n {} vs {P}",
        c.r.n
    );
    assert!(
        (c.r.t[0] - r_t).abs() <= 1e-8 * P,
        "λ {lambda}: r_t {} vs {r_t}",
        c.r.t[0]
    );
    let expected = if lambda * F < MU * P {
        InterfaceStatus::Stick
    } else {
        InterfaceStatus::Slip
    };
    assert_eq!(c.status, expected, "λ {lambda}");
}

#[test]
fn issue_40_chain_force_displacement_matches_the_closed_form() {
    for flexibility in [FlexibilityMode::Dense, FlexibilityMode::ActiveSet] {
        let newton = NewtonSettings::default().with_tol(1e-12);
        let mut sim = chain_sim(20.0, flexibility, newton);
        let mut yielded = false;
        for k in 1..=20 {
            let lambda = 0.05 * k as f64;
            let res = sim.step(lambda, lambda).unwrap();
            check_closed_form(&sim, &res, lambda, 20.0);
            assert_eq!(
                res.report.active_set,
                flexibility == FlexibilityMode::ActiveSet
            );
            let report = res.report.newton.as_ref().unwrap();
            assert_eq!(report.cuts, 0, "λ {lambda}: {:?}", report.residuals);
            // at most 8 iterations per load step (issue 40's "must show")
            assert!(report.iterations <= 8, "λ {lambda}: {:?}", report.residuals);
            yielded |= sim.structure().committed.alpha > 0.0;
        }
        assert!(yielded, "spring A yields on the way (N reaches 3 > f_y)");
    }
}

#[test]
fn issue_40_chain_newton_converges_quadratically_where_smooth() {
    // from λ = 0.5 (just sliding) to 0.6: A stays elastic (N ≤ 0.72 < f_y), B is the cubic
    let mut sim = chain_sim(
        20.0,
        FlexibilityMode::Dense,
        NewtonSettings::default().with_tol(1e-14),
    );
    sim.step(0.5, 0.5).unwrap();
    let res = sim.step(0.6, 0.6).unwrap();
    let r = &res.report.newton.as_ref().unwrap().residuals;
    println!("residuals {r:?}");
    assert!(
        r.len() >= 4,
        "a nonlinear step takes several corrections: {r:?}"
    );
    // quadratic: r_k+1 ≤ C r_k² while above round-off (1e-13 of the forces), with C = 10 (the
    // cubic's curvature over the tangent, 6 c e / k_b², about 1 here); linear convergence
    // would give r_k+1 ~ ρ r_k instead
    for w in r.windows(2).skip(1) {
        if w[1] > 1e-13 {
            assert!(w[1] <= 10.0 * w[0] * w[0], "not quadratic: {r:?}");
        }
    }
    check_closed_form(&sim, &res, 0.6, 20.0);
}

#[test]
fn issue_40_chain_step_too_large_is_cut_and_passes() {
    // from rest to λ = 1 in one step with 3 corrections at most: the cubic and A's yield take
    // more, so the step is halved until the sub-steps converge
    let newton = NewtonSettings::default()
        .with_tol(1e-12)
        .with_max_iterations(3);
    let mut sim = chain_sim(20.0, FlexibilityMode::Dense, newton);
    let res = sim.step(1.0, 1.0).unwrap();
    let report = res.report.newton.as_ref().unwrap();
    assert!(report.cuts >= 1 && report.substeps >= 2, "{report:?}");
    assert!(report.iterations <= 3);
    assert_eq!(sim.counters().steps, report.substeps);
    check_closed_form(&sim, &res, 1.0, 20.0);
    assert!((sim.time() - 1.0).abs() == 0.0);
}

#[test]
fn issue_40_chain_failure_keeps_the_last_converged_state() {
    // A perfectly plastic (h = 0): the chain holds at most λ F = f_y + μ P, λ_lim = 4 / 6.2
    let lambda_lim = (F_Y + MU * P) / F;
    let newton = NewtonSettings::default().with_tol(1e-12).with_max_cuts(6);
    let mut sim = chain_sim(0.0, FlexibilityMode::Dense, newton);
    sim.step(0.5, 0.5).unwrap();
    let e = sim.step(1.0, 1.0).unwrap_err();
    let SolverError::NewtonNotConverged(failure) = &e else {
        panic!("expected NewtonNotConverged, got {e:?}");
    };
    println!("{e}");
    assert_eq!(failure.cuts, 6);
    assert_eq!(
        (failure.target_load_factor, failure.target_time),
        (1.0, 1.0)
    );
    // the load reached is below the limit, within the last sub-step (0.5 / 2⁶) of it
    let reached = failure.load_factor;
    assert!(
        reached < lambda_lim && reached > lambda_lim - 0.5 / 64.0,
        "{reached} vs {lambda_lim}"
    );
    assert!(!failure.history.is_empty());
    assert_eq!(e.history(), Some(&failure.history[..]));
    assert!(e.to_string().contains("last converged state"), "{e}");
    // past the limit A's tangent vanishes and the chain's K_t is singular: the cause
    assert!(
        matches!(
            failure.cause.as_deref(),
            Some(SolverError::Structure(FemError::NonPositivePivot { .. }))
        ),
        "{:?}",
        failure.cause
    );
    assert!(contact_solver::error::chain(&e).contains("not positive definite"));
    // the simulation and the structure keep that state: the closed form at `reached`
    assert_eq!(sim.time(), failure.time);
    let (u0, u1, _) = closed_form(reached, 1.0);
    let u = sim.displacement();
    assert!(
        (u[0] - u0).abs() <= 1e-8 * u0 && (u[2] - u1).abs() <= 1e-8 * u1,
        "{u:?}"
    );
    assert_eq!(
        sim.structure().committed,
        Plastic::default(),
        "A never yielded below λ_lim"
    );
    assert_eq!(
        sim.structure().trial,
        sim.structure().committed,
        "rolled back"
    );
    // and it goes on from there: a step at the load reached converges where it stands
    // (its slip increment is 0: the contact sticks at the cone's edge)
    let res = sim.step(1.5, reached).unwrap();
    assert_eq!(res.report.newton.as_ref().unwrap().iterations, 1);
    let v = sim.displacement();
    assert!(
        (v[0] - u0).abs() <= 1e-8 * u0 && (v[2] - u1).abs() <= 1e-8 * u1,
        "{v:?}"
    );
    assert!((res.contacts[0].r.t[0] + MU * P).abs() <= 1e-8 * P);
}
