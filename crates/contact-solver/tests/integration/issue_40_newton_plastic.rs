//! Issue 40: a von Mises block (fem-core's `PlasticModel`) pressed onto a rigid flat base
//! through the global Newton around contact.
//!
//! Sketch: a square `1 × 1` (P1, plane strain, E = 1000, ν = 0.3, shear yield k = 1) on a
//! frictionless rigid line (Signorini), its left side on rollers, its top lowered by `δ`
//! (the top free to slide). The state is homogeneous uniaxial plane-strain compression
//! (`σ_xx = 0`): elastic, `σ_yy = −E δ / (1 − ν²)`, until `√J₂ = k`, i.e.
//! `|σ_yy| = k / √((1 + (1 − ν)² + ν²) / 6) = 1.949 k` (`δ = 1.77e-3`); then every point
//! flows and `|σ_yy|` rises towards the plane-strain limit `2k` as `σ_zz` tends to
//! `σ_yy / 2` (Hill 1950, ch. VII). The contact force is the reaction, `−σ_yy` times the
//! width.

#![cfg(feature = "fe")]

use contact_laws::Signorini;
use contact_solver::{
    ContactSimulation, ContactZone, NewtonSettings, RigidLine, SimulationSettings,
};
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::plastic::{DruckerPrager, PlasticModel};
use fem_core::{Component, Idealization, LinearElasticModel, Material, Supports};
use std::sync::Arc;

const E: f64 = 1000.0;
const NU: f64 = 0.3;
const K: f64 = 1.0;

#[test]
fn issue_40_von_mises_block_pressed_on_a_rigid_base() {
    let mesh = rectangle(&RectangleSpec::new([0.0, 1.0], [0.0, 1.0], 4, 4)).unwrap();
    let top = mesh.node_set("top").unwrap().to_vec();
    let bottom = mesh.node_set("bottom").unwrap().to_vec();
    let left = mesh.node_set("left").unwrap().to_vec();
    let mut supports = Supports::new();
    supports.prescribe(&top, Component::Y, 0.0).unwrap();
    supports.fix(&left, Component::X);
    let elastic = LinearElasticModel::new(
        mesh,
        Idealization::PlaneStrain,
        &[(0, Material::new(E, NU, 0.0).unwrap())],
        supports,
    )
    .unwrap();
    let point = Arc::new(DruckerPrager::von_mises(E, NU, K).unwrap());
    let body = PlasticModel::new(elastic, &[(0, point)]).unwrap();
    let ground = RigidLine::new([-1.0, 0.0], [2.0, 0.0]).unwrap();
    let zone = ContactZone::rigid("base", bottom, ground, Signorini, 0.1);
    let mut sim = ContactSimulation::new(body, vec![zone], SimulationSettings::default())
        .unwrap()
        // 1e-12: past yield the tangent is soft (σ_zz flows), and a residual of 1e-9 of the
        // forces would leave stress differences of 1e-8 between elements
        .with_newton(NewtonSettings::default().with_tol(1e-12))
        .unwrap();
    let first_yield = K / ((1.0 + (1.0 - NU).powi(2) + NU * NU) / 6.0).sqrt();
    let mut last = 0.0;
    for k in 1..=8 {
        let delta = 6e-4 * k as f64;
        sim.structure_mut()
            .set_prescribed(&top, Component::Y, -delta)
            .unwrap();
        let res = sim.step(k as f64, 1.0).unwrap();
        let newton = res.report.newton.as_ref().unwrap();
        // issue 40: at most 8 iterations per load step, no cut
        assert!(newton.iterations <= 8 && newton.cuts == 0, "{newton:?}");
        let force: f64 = res.contacts.iter().map(|c| c.r.n).sum();
        let out = sim.structure().element_outputs();
        let s_yy = out.stress[0][1];
        // homogeneous: every element has the same stress (1e-8 of k: the Newton's 1e-12 of
        // the forces over the soft plastic tangent)
        for s in &out.stress {
            assert!(
                (s[1] - s_yy).abs() <= 1e-8 * K && s[0].abs() <= 1e-8 * K,
                "{s:?}"
            );
        }
        // the contact force is the reaction −σ_yy × 1 (1e-8: the Newton's and the reduced
        // solver's tolerances)
        assert!((force + s_yy).abs() <= 1e-8 * force, "{force} vs {s_yy}");
        let elastic = E * delta / (1.0 - NU * NU);
        if elastic < first_yield {
            assert!(
                (force - elastic).abs() <= 1e-8 * elastic,
                "{force} vs {elastic}"
            );
            assert!(out.yielding.iter().all(|&y| y == 0.0));
        } else {
            // plastic: between the first yield and the limit 2k, rising
            assert!(out.yielding.iter().all(|&y| y == 1.0), "{:?}", out.yielding);
            assert!(
                force > first_yield * (1.0 - 1e-9) && force < 2.0 * K,
                "{force}"
            );
            assert!(force > last, "{force} after {last}");
            // quadratic at the end (the consistent tangent): the last correction above
            // round-off (1e-13) meets r_k+1 ≤ C r_k² with C = 100 (measured ~30; earlier
            // iterations, before the asymptotic regime, up to ~400); a linear rate would
            // leave r_k+1 ~ ρ r_k, far above
            let r = &newton.residuals;
            if let Some(w) = r.windows(2).rfind(|w| w[1] > 1e-13) {
                assert!(w[1] <= 100.0 * w[0] * w[0], "{r:?}");
            }
        }
        last = force;
    }
    assert!(last > first_yield, "the block yielded");
}
