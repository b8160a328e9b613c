//! A change of supports between steps renumbers the structure's dofs (`release`, or
//! `set_prescribed` on a free dof): the simulations must follow the new numbering. Checked
//! against a simulation built with the final supports from the start: a block pressed on a
//! rigid floor (frictionless: the answer does not depend on the history); in 2D its
//! bottom-left node is held along x, then released; in 3D a contact node is then also held
//! along y. Before the fix the 2D step answered with the old rows of `H` (a contact force of 0
//! against 0.079) and the 3D one panicked on an index.

#![cfg(feature = "fe")]

use contact_laws::Signorini;
use contact_solver::coupling::solid::{ContactZone3, RigidPlane, SolidContactSimulation};
use contact_solver::{ContactSimulation, ContactZone, RigidLine, SimulationSettings};
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::solid::generate::{box_mesh, lines};
use fem_core::solid::{SolidKind, SolidModel};
use fem_core::{
    Component, ElementKind, Idealization, LinearElasticModel, Material, Structure, Supports,
};

#[test]
fn renumbered_supports_are_followed_in_2d() {
    let mesh = rectangle(&RectangleSpec {
        kind: ElementKind::Tri6,
        ..RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 4, 2)
    })
    .unwrap();
    let m = Material::new(1000.0, 0.3, 0.0).unwrap();
    let top = mesh.node_set("top").unwrap().to_vec();
    let bottom = mesh.node_set("bottom").unwrap().to_vec();
    let corner = mesh.node_set("bottom_left").unwrap().to_vec();
    let build = |hold_corner: bool| {
        let mut s = Supports::new();
        s.prescribe(&top, Component::Y, -1e-3)
            .unwrap()
            .fix(&top, Component::X);
        if hold_corner {
            s.fix(&corner, Component::X);
        }
        let model =
            LinearElasticModel::new(mesh.clone(), Idealization::PlaneStrain, &[(0, m)], s).unwrap();
        let line = RigidLine::new([-1.0, 0.0], [3.0, 0.0]).unwrap();
        let zone = ContactZone::rigid("floor", bottom.clone(), line, Signorini, 0.1);
        ContactSimulation::new(model, vec![zone], SimulationSettings::default()).unwrap()
    };
    let mut a = build(true);
    a.step(1.0, 1.0).unwrap();
    a.structure_mut().release(&corner, Component::X).unwrap();
    let ra = a.step(2.0, 1.0).unwrap();
    let mut b = build(false);
    let rb = b.step(1.0, 1.0).unwrap();
    for (x, y) in ra.contacts.iter().zip(&rb.contacts) {
        assert!((x.r.n - y.r.n).abs() < 1e-8 * 0.5, "{} vs {}", x.r.n, y.r.n);
    }
    let (ua, ub) = (a.nodal_displacements(), b.nodal_displacements());
    for (x, y) in ua.iter().zip(&ub) {
        assert!(
            (x[0] - y[0]).abs() < 1e-12 && (x[1] - y[1]).abs() < 1e-12,
            "{x:?} {y:?}"
        );
    }
}

#[test]
fn renumbered_supports_are_followed_in_3d() {
    let mesh = box_mesh(
        &lines(0.0, 1.0, 2),
        &lines(0.0, 1.0, 2),
        &lines(0.0, 0.5, 1),
        SolidKind::Tet10,
    )
    .unwrap();
    let m = Material::new(1000.0, 0.3, 0.0).unwrap();
    let top = mesh.node_set("z1").unwrap().to_vec();
    let (nodes, areas) = mesh.nodal_areas("z0").unwrap();
    let corner = vec![nodes[0]];
    let build = || {
        let mut s = Supports::new();
        s.prescribe(&top, Component::Z, -1e-3)
            .unwrap()
            .fix(&top, Component::X)
            .fix(&top, Component::Y);
        s.fix(&corner, Component::X);
        let model = SolidModel::new(mesh.clone(), &[(0, m)], s).unwrap();
        let floor = RigidPlane::new([0.0; 3], [0.0, 0.0, 1.0]).unwrap();
        let zone = ContactZone3::rigid("floor", nodes.clone(), floor, Signorini, 0.1)
            .with_areas(areas.clone());
        SolidContactSimulation::new(model, vec![zone], SimulationSettings::for_dimension::<3>())
            .unwrap()
    };
    let mut a = build();
    a.step(1.0, 1.0).unwrap();
    // constrain a free dof: the dofs are renumbered
    a.structure_mut()
        .set_prescribed(&corner, Component::Y, 0.0)
        .unwrap();
    let ra = a.step(2.0, 1.0).unwrap();
    let mut fresh = {
        let mut s = Supports::new();
        s.prescribe(&top, Component::Z, -1e-3)
            .unwrap()
            .fix(&top, Component::X)
            .fix(&top, Component::Y);
        s.fix(&corner, Component::X).fix(&corner, Component::Y);
        let model = SolidModel::new(mesh.clone(), &[(0, m)], s).unwrap();
        let floor = RigidPlane::new([0.0; 3], [0.0, 0.0, 1.0]).unwrap();
        let zone = ContactZone3::rigid("floor", nodes.clone(), floor, Signorini, 0.1)
            .with_areas(areas.clone());
        SolidContactSimulation::new(model, vec![zone], SimulationSettings::for_dimension::<3>())
            .unwrap()
    };
    let rf = fresh.step(1.0, 1.0).unwrap();
    for (x, y) in ra.contacts.iter().zip(&rf.contacts) {
        assert!((x.r.n - y.r.n).abs() < 1e-8, "{:?} vs {:?}", x.r, y.r);
    }
    for n in 0..mesh.node_count() {
        let (x, y) = (a.nodal_displacement(n), fresh.nodal_displacement(n));
        for c in 0..3 {
            assert!((x[c] - y[c]).abs() < 1e-12, "node {n}: {x:?} {y:?}");
        }
    }
}

/// `SolidModel::release` between steps: the corner's x support removed, against a simulation
/// built without it; releasing every support along z of a body held only by them is refused
/// and leaves the model as it was.
#[test]
fn released_supports_are_followed_in_3d() {
    let mesh = box_mesh(
        &lines(0.0, 1.0, 2),
        &lines(0.0, 1.0, 2),
        &lines(0.0, 0.5, 1),
        SolidKind::Tet10,
    )
    .unwrap();
    let m = Material::new(1000.0, 0.3, 0.0).unwrap();
    let top = mesh.node_set("z1").unwrap().to_vec();
    let (nodes, areas) = mesh.nodal_areas("z0").unwrap();
    let corner = vec![nodes[0]];
    let build = |hold_corner: bool| {
        let mut s = Supports::new();
        s.prescribe(&top, Component::Z, -1e-3)
            .unwrap()
            .fix(&top, Component::X)
            .fix(&top, Component::Y);
        if hold_corner {
            s.fix(&corner, Component::X);
        }
        let model = SolidModel::new(mesh.clone(), &[(0, m)], s).unwrap();
        let floor = RigidPlane::new([0.0; 3], [0.0, 0.0, 1.0]).unwrap();
        let zone = ContactZone3::rigid("floor", nodes.clone(), floor, Signorini, 0.1)
            .with_areas(areas.clone());
        SolidContactSimulation::new(model, vec![zone], SimulationSettings::for_dimension::<3>())
            .unwrap()
    };
    let mut a = build(true);
    a.step(1.0, 1.0).unwrap();
    a.structure_mut().release(&corner, Component::X).unwrap();
    let ra = a.step(2.0, 1.0).unwrap();
    let mut fresh = build(false);
    let rf = fresh.step(1.0, 1.0).unwrap();
    for (x, y) in ra.contacts.iter().zip(&rf.contacts) {
        assert!((x.r.n - y.r.n).abs() < 1e-8, "{:?} vs {:?}", x.r, y.r);
    }
    for n in 0..mesh.node_count() {
        let (x, y) = (a.nodal_displacement(n), fresh.nodal_displacement(n));
        for c in 0..3 {
            assert!((x[c] - y[c]).abs() < 1e-12, "node {n}: {x:?} {y:?}");
        }
    }
    // the top's z support is all that holds the body along z: releasing it is refused
    let dofs = a.structure().dof_count();
    assert!(a.structure_mut().release(&top, Component::Z).is_err());
    assert_eq!(a.structure().dof_count(), dofs);
    assert!(
        a.structure_mut()
            .release(&[usize::MAX], Component::Z)
            .is_err()
    );
    a.step(3.0, 1.0).unwrap();
}
