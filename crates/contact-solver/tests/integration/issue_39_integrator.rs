//! Issue 39, the event-free smooth integrator check: without contact, [`MoreauJean`] is the
//! θ-method on `M ü + C u̇ + K u = f` (Hughes 1987 §9.3; Jean 1999 eq. 19).
//!
//! (a) The recurrence written out with dense matrices (no `v_free`, no `M̂⁻¹` of the
//!     library's; one dense LU per step):
//!     ```text
//!     (M + hθC + h²θ²K) v = M v_k − h(1−θ) C v_k − h K u_k − h²θ(1−θ) K v_k + h f_θ
//!     u = u_k + h((1−θ) v_k + θ v),      f_θ = f((1−θ) λ_k + θ λ)
//!     ```
//!     on a damped (Rayleigh), loaded (a ramp), P2 cantilever started from `(u0, v0) ≠ 0`,
//!     `θ = 0.7`: both give the same `(u, v)` to round-off (1e-12 relative).
//! (b) One mode: a P2 cantilever with the lumped mass released from its first eigenmode `φ`
//!     (`K φ = ω² M φ`), `θ = 1/2`, no damping. The trapezoidal rule keeps the motion in that
//!     mode, a rotation by `φ_h = 2 atan(ωh/2)` per step: `u_n = u0 cos(n φ_h) φ`, a period
//!     `2π h / φ_h` (longer than `2π/ω` by `(ωh)²/12` to leading order), and `T + V`
//!     conserved to round-off.
//!
//! Sketch: a cantilever `4 × 0.5`, clamped at `x = 0`; the contact zone is its tip against a
//! rigid line 10 beyond (never reached: no contact, the scheme is event-free).

#![cfg(feature = "fe")]

use contact_laws::Signorini;
use contact_solver::coupling::simulation::MoreauJean;
use contact_solver::{ContactSimulation, ContactZone, RigidLine, SimulationSettings};
use faer::linalg::solvers::Solve;
use faer::{Mat, Side};
use fem_core::dynamic::{DynamicModel, MassKind, Rayleigh};
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::{Component, ElementKind, Idealization, LinearElasticModel, Material, Structure};
use fem_core::{Mesh, Supports};

/// A P2 cantilever `4 × 0.5` (`nx × 1` cells), clamped at `x = 0`, unloaded; `E = 100`,
/// `ν = 0.3`, `ρ = 1`.
fn cantilever(nx: usize) -> (LinearElasticModel, Vec<usize>) {
    let spec = RectangleSpec {
        kind: ElementKind::Tri6,
        ..RectangleSpec::new([0.0, 4.0], [0.0, 0.5], nx, 1)
    };
    let mesh: Mesh = rectangle(&spec).unwrap();
    let left = mesh.node_set("left").unwrap().to_vec();
    let right = mesh.node_set("right").unwrap().to_vec();
    let mut supports = Supports::new();
    supports.fix(&left, Component::X).fix(&left, Component::Y);
    let m = Material::new(100.0, 0.3, 0.0)
        .unwrap()
        .with_density(1.0)
        .unwrap();
    let model =
        LinearElasticModel::new(mesh, Idealization::PlaneStrain, &[(0, m)], supports).unwrap();
    (model, right)
}

/// The simulation of `body` with `scheme`, its tip against a far rigid line (never reached).
fn simulation(
    body: DynamicModel<2>,
    right: Vec<usize>,
    scheme: MoreauJean,
) -> ContactSimulation<DynamicModel<2>, Signorini, 2, MoreauJean> {
    let far = RigidLine::new([14.0, -1.0], [14.0, 2.0]).unwrap(); // normal −x, 10 away
    let zone = ContactZone::rigid("far", right, far, Signorini, 0.1);
    ContactSimulation::with_scheme(body, vec![zone], SimulationSettings::default(), scheme).unwrap()
}

/// The dense `n × n` matrix of the product `mul` (column j = `mul(e_j)`).
fn dense(n: usize, mul: impl Fn(&[f64], &mut [f64])) -> Mat<f64> {
    let mut a = Mat::<f64>::zeros(n, n);
    let (mut e, mut y) = (vec![0.0; n], vec![0.0; n]);
    for j in 0..n {
        e[j] = 1.0;
        mul(&e, &mut y);
        e[j] = 0.0;
        for i in 0..n {
            a[(i, j)] = y[i];
        }
    }
    a
}

fn col(v: &[f64]) -> Mat<f64> {
    Mat::from_fn(v.len(), 1, |i, _| v[i])
}

fn max_rel(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    a.iter()
        .zip(b)
        .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()))
        / scale
}

#[test]
fn issue_39_theta_method_recurrence_matches_moreau_jean() {
    let (mut model, right) = cantilever(4);
    model.add_edge_traction("right", |_| [0.0, -1.0]).unwrap(); // unit downward, ramped
    let damping = Rayleigh {
        alpha: 0.2,
        beta: 0.01,
    };
    let body = DynamicModel::new(model, MassKind::Consistent, damping).unwrap();
    let n = body.dof_count();
    let m = dense(n, |x, y| body.mass_mul_into(x, y));
    let k = dense(n, |x, y| body.stiffness_mul_into(x, y));
    let c = dense(n, |x, y| body.damping_mul_into(x, y));
    let mut f1 = vec![0.0; n];
    body.load_into(1.0, &mut f1).unwrap();
    // a non-trivial start: u0 and v0 vary along the free dofs
    let u0: Vec<f64> = (0..n).map(|i| 1e-3 * (0.37 * i as f64).sin()).collect();
    let v0: Vec<f64> = (0..n).map(|i| 1e-2 * (0.91 * i as f64).cos()).collect();
    let (theta, h, steps) = (0.7, 0.05, 12);
    let scheme = MoreauJean::new(theta)
        .unwrap()
        .with_displacement(u0.clone())
        .unwrap()
        .with_velocity(v0.clone())
        .unwrap();
    let mut sim = simulation(body, right, scheme);
    sim.structure_mut().set_step(h, theta).unwrap();

    let a = &m + (h * theta) * &c + (h * h * theta * theta) * &k;
    let lu = a.partial_piv_lu();
    let (mut u, mut v) = (col(&u0), col(&v0));
    // the library takes the previous step's factor as λ_k, the first step's own before it
    let lambda = |s: usize| s as f64 / steps as f64;
    let mut lambda_k = lambda(1);
    let (mut worst_u, mut worst_v) = (0.0_f64, 0.0_f64);
    for s in 1..=steps {
        let res = sim.step(s as f64 * h, lambda(s)).unwrap();
        assert_eq!(res.report.active_contacts, 0); // event-free
        let f_theta = ((1.0 - theta) * lambda_k + theta * lambda(s)) * col(&f1);
        let rhs = &m * &v
            - (h * (1.0 - theta)) * (&c * &v)
            - h * (&k * &u)
            - (h * h * theta * (1.0 - theta)) * (&k * &v)
            + h * f_theta;
        let v_next = lu.solve(&rhs);
        u = &u + h * ((1.0 - theta) * &v + theta * &v_next);
        v = v_next;
        lambda_k = lambda(s);
        let (u_ref, v_ref): (Vec<f64>, Vec<f64>) = (0..n).map(|i| (u[(i, 0)], v[(i, 0)])).unzip();
        worst_u = worst_u.max(max_rel(sim.displacement(), &u_ref));
        worst_v = worst_v.max(max_rel(sim.scheme().velocity(), &v_ref));
    }
    eprintln!(
        "θ-method written out vs MoreauJean, {steps} steps (θ = {theta}, Rayleigh, ramp): \
         max |Δu|/|u| = {worst_u:.1e}, |Δv|/|v| = {worst_v:.1e}"
    );
    // two exact solutions of one linear recurrence, computed two ways (sparse Cholesky of
    // M̂ with v_free, dense LU): round-off of 12 steps on a matrix of condition ~1e4
    // (measured 4.0e-15 on u, 1.7e-14 on v)
    assert!(
        worst_u < 1e-12 && worst_v < 1e-12,
        "{worst_u:e} {worst_v:e}"
    );
}

#[test]
fn issue_39_one_mode_keeps_its_period_and_energy() {
    let (model, right) = cantilever(8);
    let body = DynamicModel::new(model, MassKind::Lumped, Rayleigh::default()).unwrap();
    let n = body.dof_count();
    // K φ = ω² M φ with M diagonal: the symmetric A = M^-1/2 K M^-1/2
    let mut m = vec![0.0; n];
    body.mass_mul_into(&vec![1.0; n], &mut m);
    let k = dense(n, |x, y| body.stiffness_mul_into(x, y));
    let a = Mat::from_fn(n, n, |i, j| k[(i, j)] / (m[i] * m[j]).sqrt());
    let eigen = a.self_adjoint_eigen(Side::Lower).unwrap();
    let omega = eigen.S()[0].sqrt();
    let y = eigen.U().col(0);
    let phi: Vec<f64> = (0..n).map(|i| y[i] / m[i].sqrt()).collect();
    let top = phi.iter().fold(0.0_f64, |s, p| s.max(p.abs()));
    let phi: Vec<f64> = phi.iter().map(|p| 1e-3 * p / top).collect(); // u0: tip ~1e-3
    let period = 2.0 * std::f64::consts::PI / omega;
    let h = period / 40.0; // ωh = 0.157: period elongation (ωh)²/12 = 0.2 %
    let scheme = MoreauJean::new(0.5)
        .unwrap()
        .with_displacement(phi.clone())
        .unwrap();
    let mut sim = simulation(body, right, scheme);
    let phi_h = 2.0 * (omega * h / 2.0).atan();
    let steps = 200; // five periods
    let mut worst = 0.0_f64;
    for s in 1..=steps {
        sim.advance(h).unwrap();
        let c = (s as f64 * phi_h).cos();
        let expected: Vec<f64> = phi.iter().map(|p| c * p).collect();
        let err = sim
            .displacement()
            .iter()
            .zip(&expected)
            .fold(0.0_f64, |m, (u, e)| m.max((u - e).abs()));
        worst = worst.max(err / 1e-3);
    }
    let history = sim.scheme().energy_history();
    let e0 = history[0].initial;
    let drift = history
        .iter()
        .map(|e| (e.mechanical() - e0).abs() / e0)
        .fold(0.0, f64::max);
    let elongation = omega * h / phi_h - 1.0;
    eprintln!(
        "one mode, ω = {omega:.5}, h = T/40: max |u − u0 cos(nφ_h) φ| / u0 = {worst:.1e}; \
         period 2πh/φ_h = {:.6} vs 2π/ω = {period:.6} (+{:.3} %, (ωh)²/12 = {:.3} %); \
         max |T + V − E0|/E0 = {drift:.1e}",
        2.0 * std::f64::consts::PI * h / phi_h,
        100.0 * elongation,
        100.0 * (omega * h).powi(2) / 12.0
    );
    // the dense eigenvector is exact to ~1e-13 of its norm; the other modes it carries at
    // that level rotate at their own φ_h but stay at that level (the map is an isometry in
    // the energy norm): 200 steps of round-off on top (measured 4.4e-11)
    assert!(worst < 2e-10, "{worst:e}");
    // the discrete period is the closed form's, not the ODE's (the test can tell them apart)
    assert!(elongation > 1e-3);
    // θ = 1/2: T + V is conserved by the trapezoidal rule; what is left is the round-off of
    // evaluating ½ uᵀ K u for a bending mode, ε ‖K‖ ‖u‖² / (uᵀ K u) ≈ 1e-12, as in
    // `issue_39_dynamics.rs` (measured 3.6e-12 over 200 steps)
    assert!(drift < 2e-11, "{drift:e}");
}
