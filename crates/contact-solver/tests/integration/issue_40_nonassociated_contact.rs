//! Issue 40: the global Newton around contact on a non-associated body keeps its quadratic
//! rate: under `FlexibilityMode::Auto` it solves the contact problem with the exact
//! (non-symmetric) tangent, not with the symmetric part that the primal active set
//! factorises (`Nonlinear::symmetric_tangent`).
//!
//! Sketch: a Drucker–Prager block `2 × 1` (P1, 32 × 4 cells, plane strain, E = 1000,
//! ν = 0.3, φ = 30°, θ = 0°, c = 1) on a rigid line with Coulomb friction μ = 0.5 (33
//! contacts, beyond the Newton's dense limit of 24, where Auto took the active set), its left
//! side on rollers, its top lowered by 1e-2 in 4 steps (uniaxial plane-strain yield near
//! 3e-3). Measured against an explicit `FlexibilityMode::ActiveSet` (the inexact Newton).

#![cfg(feature = "fe")]

use contact_laws::Coulomb;
use contact_solver::{
    ContactSimulation, ContactZone, FlexibilityMode, NewtonSettings, RigidLine,
    SimulationSettings,
};
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::plastic::{ConeMatch, DruckerPrager, DruckerPragerParameters, PlasticModel};
use fem_core::{Component, Idealization, LinearElasticModel, Material, Supports};
use std::sync::Arc;

/// Newton corrections per step, or `None` from the first step that fails.
fn run(flexibility: FlexibilityMode) -> Vec<Option<(usize, Vec<f64>)>> {
    let mesh = rectangle(&RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 32, 4)).unwrap();
    let top = mesh.node_set("top").unwrap().to_vec();
    let bottom = mesh.node_set("bottom").unwrap().to_vec();
    let left = mesh.node_set("left").unwrap().to_vec();
    let mut supports = Supports::new();
    supports.prescribe(&top, Component::Y, 0.0).unwrap();
    supports.fix(&left, Component::X);
    let elastic = LinearElasticModel::new(
        mesh,
        Idealization::PlaneStrain,
        &[(0, Material::new(1000.0, 0.3, 0.0).unwrap())],
        supports,
    )
    .unwrap();
    let point = Arc::new(
        DruckerPrager::new(DruckerPragerParameters {
            young: 1000.0,
            poisson: 0.3,
            friction_angle: 30.0,
            dilatancy_angle: 0.0,
            cohesion: 1.0,
            cone: ConeMatch::PlaneStrain,
        })
        .unwrap(),
    );
    let body = PlasticModel::new(elastic, &[(0, point)]).unwrap();
    let ground = RigidLine::new([-1.0, 0.0], [3.0, 0.0]).unwrap();
    let zone = ContactZone::rigid("base", bottom, ground, Coulomb::new(0.5).unwrap(), 0.1);
    let settings = SimulationSettings::default().with_flexibility(flexibility);
    let mut sim = ContactSimulation::new(body, vec![zone], settings)
        .unwrap()
        .with_newton(
            NewtonSettings::default()
                .with_max_iterations(30)
                .with_max_cuts(0),
        )
        .unwrap();
    let mut out = Vec::new();
    for k in 1..=4 {
        sim.structure_mut()
            .set_prescribed(&top, Component::Y, -2.5e-3 * k as f64)
            .unwrap();
        match sim.step(k as f64, 1.0) {
            Ok(res) => {
                let newton = res.report.newton.unwrap();
                out.push(Some((newton.iterations, newton.residuals)));
            }
            Err(_) => {
                out.push(None);
                break;
            }
        }
    }
    out
}

#[test]
fn issue_40_nonassociated_contact_newton_stays_quadratic() {
    let exact = run(FlexibilityMode::default());
    let inexact = run(FlexibilityMode::ActiveSet);
    println!("Auto (exact tangent): {exact:?}");
    println!("ActiveSet (symmetric part): {inexact:?}");
    let mut total = 0;
    for step in &exact {
        let (iterations, residuals) = step.as_ref().expect("Auto converges every step");
        // issue 40: at most 8 corrections per step
        assert!(*iterations <= 8, "{residuals:?}");
        total += iterations;
        // quadratic at the end: r_k+1 ≤ C r_k² (C = 1e3) for the last correction above
        // round-off (1e-13) once r_k < 1e-3
        if let Some(w) = residuals.windows(2).rfind(|w| w[1] > 1e-13 && w[0] < 1e-3) {
            assert!(w[1] <= 1e3 * w[0] * w[0], "{residuals:?}");
        }
    }
    // the inexact Newton needs more corrections (or fails within 30)
    let inexact_total: usize = inexact
        .iter()
        .map(|s| s.as_ref().map_or(31, |(i, _)| *i))
        .sum();
    assert!(
        total < inexact_total || inexact.len() < exact.len(),
        "{total} vs {inexact_total}"
    );
}
