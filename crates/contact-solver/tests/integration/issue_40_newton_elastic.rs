//! Issue 40: the global Newton around contact on a linear-elastic structure gives the linear
//! path's answer in one correction per step, for a frictionless (Signorini), a frictional
//! (Coulomb) and an adhesive (RCCM) interface.
//!
//! For `ElasticModel`, `f_int(u) = K u` and the tangent is `K`: the Newton's free response
//! `u_k + K⁻¹(f_ext − K u_k)` is the linear step's `K⁻¹ f_ext` up to round-off, so the contact
//! problem, the reactions and the displacement are the linear step's, and the residual after
//! one correction is round-off (below the default `1e-9`).
//!
//! Sketch: a block (P1, plane strain, E = 1000, ν = 0.3, 2 × 1, 8 × 4 cells) on a rigid
//! line, its top pressed down by `δ` and moved sideways (Coulomb, μ = 0.3) or pulled up (RCCM,
//! glued, `C_n = C_t = 100`, `w = 0.01`) over a few steps.

#![cfg(feature = "fe")]

use contact_laws::{BetaScheme, ContactLaw, Coulomb, Rccm, RccmParams, Signorini};
use contact_solver::{
    ContactSimulation, ContactZone, NewtonSettings, RigidLine, SimulationSettings, StepResult,
};
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::{Component, Idealization, LinearElasticModel, Material, Supports};

/// The block and its zone on the base, with `law`; the top node set.
fn block<L: ContactLaw + Clone>(law: L) -> (ContactSimulation<LinearElasticModel, L>, Vec<usize>) {
    let mesh = rectangle(&RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 8, 4)).unwrap();
    let top = mesh.node_set("top").unwrap().to_vec();
    let bottom = mesh.node_set("bottom").unwrap().to_vec();
    let mut supports = Supports::new();
    supports.prescribe(&top, Component::Y, 0.0).unwrap();
    supports.prescribe(&top, Component::X, 0.0).unwrap();
    let model = LinearElasticModel::new(
        mesh,
        Idealization::PlaneStrain,
        &[(0, Material::new(1000.0, 0.3, 0.0).unwrap())],
        supports,
    )
    .unwrap();
    let ground = RigidLine::new([-1.0, 0.0], [3.0, 0.0]).unwrap();
    let zone = ContactZone::rigid("base", bottom, ground, law, 0.1);
    let sim = ContactSimulation::new(model, vec![zone], SimulationSettings::default()).unwrap();
    (sim, top)
}

/// Runs the `path` of top displacements `(u_x, u_y)` on the linear path and through the
/// Newton, and checks that every step agrees.
fn linear_and_newton_agree<L: ContactLaw + Clone>(law: L, path: &[(f64, f64)]) {
    let (mut linear, top) = block(law.clone());
    let (newton, _) = block(law);
    let mut newton = newton.with_newton(NewtonSettings::default()).unwrap();
    for (k, &(ux, uy)) in path.iter().enumerate() {
        let time = (k + 1) as f64;
        let mut results: Vec<StepResult> = Vec::new();
        for sim in [&mut linear, &mut newton] {
            let model = sim.structure_mut();
            model.set_prescribed(&top, Component::X, ux).unwrap();
            model.set_prescribed(&top, Component::Y, uy).unwrap();
            results.push(sim.step(time, 1.0).unwrap());
        }
        let report = results[1].report.newton.as_ref().expect("a Newton step");
        assert!(results[0].report.newton.is_none());
        assert_eq!(report.iterations, 1, "step {k}: {:?}", report.residuals);
        assert_eq!((report.cuts, report.substeps), (0, 1));
        assert!(report.residuals[1] <= 1e-9, "{:?}", report.residuals);
        // 1e-10 of the largest value: both solve the same reduced problem from free
        // responses that differ by round-off (the Newton's is u + K⁻¹(f − K u))
        let scale = linear
            .displacement()
            .iter()
            .fold(0.0_f64, |m, v| m.max(v.abs()));
        for (a, b) in linear.displacement().iter().zip(newton.displacement()) {
            assert!((a - b).abs() <= 1e-10 * scale, "step {k}: u {a} vs {b}");
        }
        let r_scale = results[0]
            .contacts
            .iter()
            .fold(1e-300_f64, |m, c| m.max(c.r.n.abs()).max(c.r.t[0].abs()));
        for (a, b) in results[0].contacts.iter().zip(&results[1].contacts) {
            assert_eq!(a.status, b.status, "step {k}, node {}", a.node);
            for (x, y) in [(a.r.n, b.r.n), (a.r.t[0], b.r.t[0]), (a.gap, b.gap)] {
                assert!(
                    (x - y).abs() <= 1e-10 * r_scale.max(scale),
                    "step {k}: {x} vs {y}"
                );
            }
            assert!(
                (a.beta - b.beta).abs() <= 1e-10,
                "beta {} vs {}",
                a.beta,
                b.beta
            );
        }
    }
    assert_eq!(linear.counters().steps, newton.counters().steps);
}

#[test]
fn issue_40_newton_on_elastic_is_the_linear_step_signorini() {
    linear_and_newton_agree(Signorini, &[(0.0, -0.005), (0.0, -0.01), (0.002, -0.01)]);
}

#[test]
fn issue_40_newton_on_elastic_is_the_linear_step_coulomb() {
    // pressed, then pushed past the threshold: stick, then slip
    let path = [(0.0, -0.01), (1e-4, -0.01), (2e-3, -0.01), (4e-3, -0.01)];
    linear_and_newton_agree(Coulomb::new(0.3).unwrap(), &path);
}

#[test]
fn issue_40_newton_on_elastic_is_the_linear_step_rccm() {
    let law = Rccm::new(RccmParams {
        c_n: 100.0,
        c_t: 100.0,
        w: 0.01,
        alpha: 0.0,
        mu: 0.2,
        m: 1,
        beta_0: 1.0,
        scheme: BetaScheme::ImplicitEuler,
    })
    .unwrap();
    // pulled open through the peak (u₀ = √(w/C_n) = 0.01) into decohesion, sheared on the way
    let path = [(0.0, 0.004), (0.001, 0.008), (0.001, 0.012), (0.002, 0.02)];
    linear_and_newton_agree(law, &path);
}

#[test]
fn issue_40_newton_refuses_bad_settings() {
    let (sim, _) = block(Signorini);
    let e = sim
        .with_newton(NewtonSettings::default().with_tol(f64::NAN))
        .err()
        .expect("a NaN tolerance is refused");
    assert!(e.to_string().contains("NewtonSettings::tol"), "{e}");
    let (sim, _) = block(Signorini);
    let e = sim
        .with_newton(NewtonSettings::default().with_max_iterations(0))
        .err()
        .expect("no correction is refused");
    assert!(e.to_string().contains("max_iterations"), "{e}");
}

#[test]
fn issue_40_newton_refuses_a_floating_structure() {
    // the block held by contact only (no support): its rigid-body modes are solved on the
    // linear path only
    let mesh = rectangle(&RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 4, 2)).unwrap();
    let bottom = mesh.node_set("bottom").unwrap().to_vec();
    let model = LinearElasticModel::floating(
        mesh,
        Idealization::PlaneStrain,
        &[(0, Material::new(1000.0, 0.3, 1.0).unwrap())],
        Supports::new(),
    )
    .unwrap();
    let ground = RigidLine::new([-1.0, 0.0], [3.0, 0.0]).unwrap();
    let zone = ContactZone::rigid("base", bottom, ground, Coulomb::new(0.3).unwrap(), 0.1);
    let sim = ContactSimulation::new(model, vec![zone], SimulationSettings::default()).unwrap();
    let e = sim
        .with_newton(NewtonSettings::default())
        .err()
        .expect("a floating structure is refused");
    assert!(
        matches!(e, contact_solver::SolverError::Unsupported(_)),
        "{e:?}"
    );
    assert!(e.to_string().contains("floating"), "{e}");
}
