//! Issue 35: a step whose penetration check runs out is an error in 2D and 3D alike. Before the
//! fix, the 2D step returned `Ok` with contacts still penetrating when
//! `max_detection_passes` ran out; the 3D step returned `NotConverged` without saying why.
//!
//! The scene (Poisson's effect, any elasticity text, e.g. Timoshenko & Goodier §6): a block
//! pushed sideways against a rigid wall by a prescribed displacement of its far side, its top
//! held vertically, a rigid floor just below its bottom. Without contact the block translates
//! and its bottom stays clear of the floor, so the floor's candidates are outside the first
//! reduced problem; the wall's reaction compresses the block, which bulges downwards by
//! `≈ ν/(1 − ν) ε H` (plane strain) — here ≈ 0.02, twenty times the floor's clearance — so
//! the floor's candidates penetrate after the first pass and need a second one.
//!
//! ```text
//!   wall   ┌──────────┐ ← top: u_y = 0
//!   x=-.05 │  block   │ ← u_x = -0.1 on the right side
//!          └──────────┘
//!   ══════════════════════ floor y = -0.001
//! ```

#![cfg(feature = "fe")]

use contact_laws::Signorini;
use contact_solver::coupling::solid::{ContactZone3, RigidPlane, SolidContactSimulation};
use contact_solver::{ContactSimulation, ContactZone, RigidLine, SimulationSettings, SolverError};
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::solid::generate::{box_mesh, lines};
use fem_core::solid::{SolidKind, SolidModel};
use fem_core::{Component, Idealization, LinearElasticModel, Material, Supports};

/// The floor's clearance below the block.
const CLEARANCE: f64 = 1e-3;

fn block_2d(passes: usize) -> ContactSimulation<LinearElasticModel, Signorini> {
    let mesh = rectangle(&RectangleSpec::new([0.0, 1.0], [0.0, 1.0], 4, 4)).unwrap();
    let set = |n: &str| mesh.node_set(n).unwrap().to_vec();
    let (top, bottom, left, right) = (set("top"), set("bottom"), set("left"), set("right"));
    let mut supports = Supports::new();
    supports.fix(&top, Component::Y);
    supports.prescribe(&right, Component::X, -0.1).unwrap();
    let model = LinearElasticModel::new(
        mesh,
        Idealization::PlaneStrain,
        &[(0, Material::new(100.0, 0.3, 0.0).unwrap())],
        supports,
    )
    .unwrap();
    let wall = RigidLine::new([-0.05, 2.0], [-0.05, -1.0]).unwrap();
    let floor = RigidLine::new([-1.0, -CLEARANCE], [2.0, -CLEARANCE]).unwrap();
    let zones = vec![
        ContactZone::rigid("wall", left, wall, Signorini, 0.06),
        ContactZone::rigid("floor", bottom, floor, Signorini, 1e-4),
    ];
    let settings = SimulationSettings::default().with_max_detection_passes(passes);
    ContactSimulation::new(model, zones, settings).unwrap()
}

fn block_3d(passes: usize) -> SolidContactSimulation<SolidModel, Signorini> {
    let l = lines(0.0, 1.0, 2);
    let mesh = box_mesh(&l, &l, &l, SolidKind::Tet4).unwrap();
    let set = |n: &str| mesh.node_set(n).unwrap().to_vec();
    let (top, right, left, bottom) = (set("z1"), set("x1"), set("x0"), set("z0"));
    let mut supports = Supports::new();
    supports.fix(&top, Component::Z);
    supports.prescribe(&right, Component::X, -0.1).unwrap();
    supports.fix(&right, Component::Y);
    let model = SolidModel::new(
        mesh,
        &[(0, Material::new(100.0, 0.3, 0.0).unwrap())],
        supports,
    )
    .unwrap();
    let wall = RigidPlane::new([-0.05, 0.0, 0.0], [1.0, 0.0, 0.0]).unwrap();
    let floor = RigidPlane::new([0.0, 0.0, -CLEARANCE], [0.0, 0.0, 1.0]).unwrap();
    let zones = vec![
        ContactZone3::rigid("wall", left, wall, Signorini, 0.06),
        ContactZone3::rigid("floor", bottom, floor, Signorini, 1e-4),
    ];
    let settings = SimulationSettings::for_dimension::<3>().with_max_detection_passes(passes);
    SolidContactSimulation::new(model, zones, settings).unwrap()
}

/// The refusal names the floor, a penetrating node of it and the setting to raise.
fn check_refusal(e: &SolverError, setting: &str) {
    match e {
        SolverError::StillPenetrating {
            passes,
            count,
            zone,
            gap,
            setting: s,
            ..
        } => {
            assert_eq!(*passes, 1);
            assert!(*count > 0);
            assert_eq!(zone, "floor");
            assert!(*gap < 0.0, "gap {gap}");
            assert_eq!(*s, setting);
        }
        other => panic!("expected StillPenetrating, got {other:?}"),
    }
    let text = e.to_string();
    assert!(text.contains("`floor`") && text.contains(setting), "{text}");
}

#[test]
fn issue_35_a_2d_step_that_still_penetrates_is_an_error() {
    let e = block_2d(1).step(1.0, 1.0).unwrap_err();
    check_refusal(&e, "max_detection_passes");
    // with the default passes the floor joins the reduced problem and nothing penetrates
    // (tolerance: the local solver's 1e-9 relative to the 0.05 push, with margin)
    let mut sim = block_2d(SimulationSettings::default().tuning.max_detection_passes);
    let res = sim.step(1.0, 1.0).unwrap();
    assert!(
        res.contacts.iter().all(|c| c.gap > -1e-9),
        "penetration left"
    );
    let floor_force: f64 = res
        .contacts
        .iter()
        .filter(|c| c.zone == 1)
        .map(|c| c.r.n)
        .sum();
    assert!(
        floor_force > 0.0,
        "the bulge presses on the floor: {floor_force}"
    );
}

#[test]
fn issue_35_a_3d_step_that_still_penetrates_is_the_same_error() {
    let e = block_3d(1).step(1.0, 1.0).unwrap_err();
    // one setting, one name, in both dimensions
    check_refusal(&e, "max_detection_passes");
    let mut sim = block_3d(
        SimulationSettings::for_dimension::<3>()
            .tuning
            .max_detection_passes,
    );
    let res = sim.step(1.0, 1.0).unwrap();
    assert!(
        res.contacts.iter().all(|c| c.gap > -1e-9),
        "penetration left"
    );
    let floor_force: f64 = res
        .contacts
        .iter()
        .filter(|c| c.zone == 1)
        .map(|c| c.r.n)
        .sum();
    assert!(
        floor_force > 0.0,
        "the bulge presses on the floor: {floor_force}"
    );
}
