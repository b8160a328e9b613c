//! A block resting under its own weight on an **elastic** foundation (issue 16): the block has
//! no support at all, the foundation is fixed at its base, and a node-to-segment zone on
//! non-matching P2 meshes joins them. Contact alone holds the block; its three rigid-body
//! modes are solved for exactly.
//!
//! Source: statics of a rigid body and Coulomb's law (Coulomb 1785; e.g. J. L. Meriam,
//! L. G. Kraige, *Engineering Mechanics: Statics*, ch. 6): the interface balances the block's
//! load, `Σ f_y = W`, `Σ f_x = −T`; the block sticks while `T ≤ μ W` and has no equilibrium
//! when `T > μ W`. The elastic foundation changes how the load spreads, not the resultants.
//!
//! ```text
//!        T →      ┌────────┐  y = 1     block: P2 8 × 4, E = 1000, ν = 0.3, unit weight 1
//!                 │  ↓ W   │            (W = 2 per unit thickness); T a uniform top traction
//!                 └────────┘  y = 0     node-to-segment, Coulomb μ = 0.3
//!      ┌──────────────────────────┐ y = 0   foundation: P2 15 × 5, E = 200, ν = 0.25,
//!      │                          │         weightless, x ∈ [−2, 4]
//!      └▨▨▨▨▨▨▨▨▨▨▨▨▨▨▨▨▨▨▨▨▨▨▨▨▨▨┘ y = −2  fixed
//! ```
//! What is asserted, and why:
//! - `T = 0`: the interface carries `W` to `1e-10` relative in the global frame (the
//!   equilibrium is solved to `equilibrium_tol = 1e-11` of the forces; the rest is round-off),
//!   and no net tangential force (`1e-10 W`);
//! - `T = 0.2 W < μ W`: the block sticks, `Σ f_x = −T` and `Σ f_y = W` to `1e-10` relative;
//! - `T = 0.4 W > μ W`: [`SolverError::Unbalanced`] on the block's x translation (body 0),
//!   out of balance by `T − μ W` to `1e-9 W` (the slip reactions are exactly `μ r_n`).

#![cfg(feature = "fe")]

use crate::support::hertz_scene::with_region;
use contact_laws::{Coulomb, StandardLaw};
use contact_solver::{ContactSimulation, ContactZone, SimulationSettings, SolverError, StepResult};
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::{
    Component, ElementKind, Idealization, LinearElasticModel, Material, Mesh, RigidMotion, Supports,
};

const WEIGHT: f64 = 2.0;
const MU: f64 = 0.3;

fn scene(push: f64) -> ContactSimulation<LinearElasticModel, StandardLaw> {
    let p2 = |x: [f64; 2], y: [f64; 2], nx, ny| {
        rectangle(&RectangleSpec {
            kind: ElementKind::Tri6,
            ..RectangleSpec::new(x, y, nx, ny)
        })
        .unwrap()
    };
    let block = p2([0.0, 2.0], [0.0, 1.0], 8, 4);
    let ground = p2([-2.0, 4.0], [-2.0, 0.0], 15, 5);
    // the two parts as regions 0 (block) and 1 (foundation)
    let mesh = Mesh::join(&[("blk.", &block), ("fnd.", &with_region(&ground, 1))]).unwrap();
    let sorted = |set: &str| {
        let mut v = mesh.node_set(set).unwrap().to_vec();
        v.sort_by(|&a, &b| mesh.nodes()[a][0].total_cmp(&mesh.nodes()[b][0]));
        v
    };
    let (contactor, surface) = (sorted("blk.bottom"), sorted("fnd.top"));
    let base = mesh.node_set("fnd.bottom").unwrap().to_vec();
    let mut supports = Supports::new();
    supports.fix(&base, Component::X).fix(&base, Component::Y);
    let mut model = LinearElasticModel::floating(
        mesh,
        Idealization::PlaneStrain,
        &[
            (0, Material::new(1000.0, 0.3, 1.0).unwrap()),
            (1, Material::new(200.0, 0.25, 0.0).unwrap()),
        ],
        supports,
    )
    .unwrap();
    assert_eq!(model.rigid_body_modes().map(|m| m.len()), Some(3));
    model.add_self_weight().unwrap();
    model
        .add_edge_traction("blk.top", |_| [push / 2.0, 0.0])
        .unwrap();
    let law: StandardLaw = Coulomb::new(MU).unwrap().into();
    let zone = ContactZone::node_to_segment("base", contactor, surface, law, 0.01);
    ContactSimulation::new(model, vec![zone], SimulationSettings::default()).unwrap()
}

/// `(Σ f_x, Σ f_y)` of the reactions on the block, in the global frame.
fn resultant(
    sim: &ContactSimulation<LinearElasticModel, StandardLaw>,
    res: &StepResult,
) -> [f64; 2] {
    res.contacts.iter().fold([0.0; 2], |s, c| {
        let k = sim.candidates().iter().find(|k| k.node == c.node).unwrap();
        [
            s[0] + c.r.n * k.normal()[0] + c.r.t[0] * k.tangent()[0],
            s[1] + c.r.n * k.normal()[1] + c.r.t[0] * k.tangent()[1],
        ]
    })
}

#[test]
fn block_on_elastic_foundation_works() {
    for push in [0.0, 0.2 * WEIGHT] {
        let mut sim = scene(push);
        let res = sim
            .step(1.0, 1.0)
            .expect("the block rests on the foundation");
        let [fx, fy] = resultant(&sim, &res);
        eprintln!(
            "T = {push}: Σ f_y = {fy:.14} (W = {WEIGHT}), Σ f_x = {fx:+.3e}, {} closed, α = {:?}",
            res.contacts.iter().filter(|c| c.r.n > 0.0).count(),
            sim.rigid_body_amplitudes()
        );
        assert!(((fy - WEIGHT) / WEIGHT).abs() <= 1e-10, "Σ f_y = {fy}");
        assert!((fx + push).abs() <= 1e-10 * WEIGHT, "Σ f_x = {fx}");
        assert!(res.contacts.iter().all(|c| c.gap >= -1e-9));
    }
}

#[test]
fn block_sliding_off_an_elastic_foundation_is_unbalanced() {
    let push = 0.4 * WEIGHT;
    let mut sim = scene(push);
    let err = sim.step(1.0, 1.0).unwrap_err();
    eprintln!("{err}");
    let SolverError::Unbalanced {
        body,
        motion,
        imbalance,
        ..
    } = err
    else {
        panic!("expected Unbalanced, got {err:?}");
    };
    assert_eq!(body, 0);
    assert_eq!(
        motion,
        RigidMotion::Translation {
            direction: [1.0, 0.0]
        }
    );
    let expected = push - MU * WEIGHT;
    assert!(
        (imbalance - expected).abs() <= 1e-9 * WEIGHT,
        "imbalance {imbalance} vs {expected}"
    );
}
