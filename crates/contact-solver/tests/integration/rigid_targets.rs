//! Physical checks of rigid targets (issue 15, "silent wrong answers"): a LINE that faces away
//! from the body touching it, and a degenerate LINE, are refused when the simulation is built
//! instead of letting the body fall through or leaving its nodes unconstrained.

#![cfg(feature = "fe")]

use contact_laws::Signorini;
use contact_solver::{
    ArcSide, ContactSimulation, ContactZone, Obstacle, RigidArc, RigidLine, SimulationSettings,
    SolverError,
};
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::{Component, Idealization, LinearElasticModel, Material, Supports};

/// A 2 × 1 block resting at gap 0 on `target` with its bottom nodes as contactors.
fn block_on(target: impl Obstacle + 'static) -> Result<(), SolverError> {
    let mesh = rectangle(&RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 8, 4)).unwrap();
    let top = mesh.node_set("top").unwrap().to_vec();
    let bottom = mesh.node_set("bottom").unwrap().to_vec();
    let left = mesh.node_set("left").unwrap().to_vec();
    let mut supports = Supports::new();
    supports.prescribe(&top, Component::Y, -0.01).unwrap();
    supports.fix(&left, Component::X);
    let model = LinearElasticModel::new(
        mesh,
        Idealization::PlaneStrain,
        &[(0, Material::new(200.0, 0.3, 0.0).unwrap())],
        supports,
    )
    .unwrap();
    let zone = ContactZone::rigid("ground", bottom, target, Signorini, 0.1);
    let mut sim = ContactSimulation::new(model, vec![zone], SimulationSettings::default())?;
    // the right way round, the block is held: a compressive total reaction
    let res = sim.step(1.0, 1.0)?;
    let total: f64 = res.contacts.iter().map(|c| c.r.n).sum();
    assert!(total > 0.0, "Σr_n = {total}");
    Ok(())
}

fn message(e: SolverError) -> String {
    match e {
        SolverError::InvalidGeometry(m) => m,
        other => panic!("expected InvalidGeometry, got {other:?}"),
    }
}

#[test]
fn a_line_facing_the_body_holds_it() {
    block_on(RigidLine::new([-1.0, 0.0], [3.0, 0.0]).unwrap()).unwrap();
}

/// The same LINE given from b to a: the contactor side is below it, every bottom node has a
/// gap of exactly 0 (so no "starts inside" test can see it), and the block would fall through.
#[test]
fn a_line_facing_away_at_gap_zero_is_refused() {
    let e = block_on(RigidLine::new([3.0, 0.0], [-1.0, 0.0]).unwrap()).unwrap_err();
    let m = message(e);
    assert!(
        m.contains("zone `ground`") && m.contains("faces away"),
        "{m}"
    );
}

/// A LINE of length 1e-300 under the block: degenerate against the contactor's extent (2).
#[test]
fn a_degenerate_line_is_refused() {
    for length in [1e-300, 1e-12] {
        let e = block_on(RigidLine::new([0.0, 0.0], [length, 0.0]).unwrap()).unwrap_err();
        let m = message(e);
        assert!(m.contains("degenerate"), "{length:e}: {m}");
    }
}

/// An ARC under the block with the contactor on the wrong side (inside a large circle whose
/// top touches the block's bottom: the normal points down, away from the block).
#[test]
fn an_arc_facing_away_is_refused() {
    let r = 100.0;
    let arc =
        |side| RigidArc::new([1.0, -r], r, std::f64::consts::FRAC_PI_2 - 0.1, 0.2, side).unwrap();
    block_on(arc(ArcSide::Outside)).unwrap();
    let m = message(block_on(arc(ArcSide::Inside)).unwrap_err());
    assert!(m.contains("faces away"), "{m}");
}
