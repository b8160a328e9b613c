//! A frictional block on a rigid line, its body assembled by fenris (through `Structure`) and by
//! fem-core (`LinearElasticModel`) on the same P2 mesh and material: the contact solver must
//! see the same structure and return the same reactions (issue 36).
//!
//! Reference: fem-core's own model of the same body. Both bilinear forms are integrated
//! exactly on straight-sided P2 triangles (fenris: triangle rule of strength 2; fem-core: its
//! element rules), so the stiffnesses and loads agree to rounding (checked to 1e-12 of their
//! largest entry), and the reactions to the contact solver's tolerance (`tol` = 1e-10,
//! relative: checked to `tol` times the largest reaction).

use contact_laws::Coulomb;
use contact_solver::{
    ContactSimulation, ContactZone, InterfaceStatus, RigidLine, SimulationSettings, StepResult,
};
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::{
    Component, ElementKind, Idealization, LinearElasticModel, Material, Mesh, Structure, Supports,
};
use fenris::connectivity::Tri6d2Connectivity;
use fenris::mesh::Tri6Mesh2d;
use fenris::nalgebra::Point2;
use fenris_body::{FenrisBody, FenrisBodyError, PlaneStrainElasticity};

const YOUNG: f64 = 1e3;
const POISSON: f64 = 0.3;
/// Gravity tilted along +x: the block presses on the line and pulls along it.
const BODY_FORCE: [f64; 2] = [0.25, -1.0];
const MU: f64 = 0.4;

/// A 2 × 1 block of 8 × 4 cells of P2 triangles (fem-core's generator).
fn mesh() -> Mesh {
    let spec = RectangleSpec {
        kind: ElementKind::Tri6,
        ..RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 8, 4)
    };
    rectangle(&spec).unwrap()
}

/// The same mesh for fenris (same node numbers, same local node order).
fn fenris_mesh(mesh: &Mesh) -> Tri6Mesh2d<f64> {
    let vertices = mesh
        .nodes()
        .iter()
        .map(|p| Point2::new(p[0], p[1]))
        .collect();
    let cells = (0..mesh.element_count())
        .map(|e| Tri6d2Connectivity(mesh.element(e).try_into().unwrap()))
        .collect();
    Tri6Mesh2d::from_vertices_and_connectivity(vertices, cells)
}

/// Both bodies, clamped along the top.
fn bodies() -> (LinearElasticModel, FenrisBody, Vec<usize>) {
    let mesh = mesh();
    let top = mesh.node_set("top").unwrap().to_vec();
    let bottom = mesh.node_set("bottom").unwrap().to_vec();
    let fixed: Vec<(usize, Component)> = top
        .iter()
        .flat_map(|&n| [(n, Component::X), (n, Component::Y)])
        .collect();
    let fenris = FenrisBody::plane_strain(
        &fenris_mesh(&mesh),
        PlaneStrainElasticity::new(YOUNG, POISSON).unwrap(),
        BODY_FORCE,
        &fixed,
    )
    .unwrap()
    .with_node_set("bottom", bottom.clone())
    .unwrap();
    let mut supports = Supports::new();
    supports.fix(&top, Component::X).fix(&top, Component::Y);
    let material = Material::new(YOUNG, POISSON, 0.0).unwrap();
    let mut model =
        LinearElasticModel::new(mesh, Idealization::PlaneStrain, &[(0, material)], supports)
            .unwrap();
    model.add_body_force(|_| BODY_FORCE).unwrap();
    (model, fenris, bottom)
}

/// The free-dof index pairs `(fem-core, fenris)` of every free component.
fn dof_pairs(a: &impl Structure, b: &impl Structure) -> Vec<(usize, usize)> {
    assert_eq!(a.node_count(), b.node_count());
    (0..a.node_count())
        .flat_map(|n| {
            let (da, db) = (a.node_dofs(n), b.node_dofs(n));
            (0..2).filter_map(move |c| match (da[c], db[c]) {
                (Some(i), Some(j)) => Some((i, j)),
                (None, None) => None,
                _ => panic!("node {n} component {c}: free in one body only"),
            })
        })
        .collect()
}

/// The full symmetric matrix from a lower triangle in CSC form.
fn dense(s: &impl Structure) -> Vec<Vec<f64>> {
    let k = s.stiffness_matrix().expect("an assembled stiffness");
    let n = s.dof_count();
    let mut m = vec![vec![0.0; n]; n];
    let entries = (0..n).flat_map(|j| {
        k.row_idx_of_col(j)
            .zip(k.val_of_col(j))
            .map(move |(i, &v)| (i, j, v))
    });
    for (i, j, v) in entries {
        m[i][j] = v;
        m[j][i] = v;
    }
    m
}

#[test]
fn issue_36_fenris_stiffness_and_load_match_fem_core() {
    let (model, fenris, _) = bodies();
    assert_eq!(model.dof_count(), fenris.dof_count());
    let pairs = dof_pairs(&model, &fenris);
    let (ka, kb) = (dense(&model), dense(&fenris));
    let scale = ka.iter().flatten().fold(0.0_f64, |m, v| m.max(v.abs()));
    let mut worst = 0.0_f64;
    for &(i, p) in &pairs {
        for &(j, q) in &pairs {
            worst = worst.max((ka[i][j] - kb[p][q]).abs());
        }
    }
    eprintln!("K: largest difference {worst:e}, largest entry {scale:e}");
    assert!(
        worst <= 1e-12 * scale,
        "K differs by {worst:e} (scale {scale:e})"
    );

    let mut fa = vec![0.0; model.dof_count()];
    model.rhs_into(1.0, &mut fa);
    let load_scale = fa.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let worst = pairs
        .iter()
        .map(|&(i, p)| (fa[i] - fenris.load()[p]).abs())
        .fold(0.0, f64::max);
    eprintln!("load: largest difference {worst:e}, largest entry {load_scale:e}");
    assert!(worst <= 1e-12 * load_scale, "load differs by {worst:e}");
}

fn solve<S: Structure>(body: S, bottom: &[usize]) -> StepResult {
    let ground = RigidLine::new([-1.0, 0.0], [3.0, 0.0]).unwrap(); // body above: left of a → b
    let zones = vec![ContactZone::rigid(
        "ground",
        bottom.to_vec(),
        ground,
        Coulomb::new(MU).unwrap(),
        0.01,
    )];
    let mut sim = ContactSimulation::new(body, zones, SimulationSettings::default()).unwrap();
    sim.step(1.0, 1.0).unwrap()
}

#[test]
fn issue_36_fenris_block_on_line_matches_fem_core() {
    let (model, fenris, bottom) = bodies();
    let tol = SimulationSettings::default().solver.tol;
    let a = solve(model, &bottom);
    let b = solve(fenris, &bottom);
    assert!(a.report.converged && b.report.converged);
    assert_eq!(a.contacts.len(), b.contacts.len());
    let scale = a
        .contacts
        .iter()
        .fold(0.0_f64, |m, c| m.max(c.r.n.abs()).max(c.r.t.norm()));
    let mut worst = 0.0_f64;
    for (ca, cb) in a.contacts.iter().zip(&b.contacts) {
        assert_eq!(ca.node, cb.node);
        assert_eq!(ca.status, cb.status, "node {}", ca.node);
        worst = worst
            .max((ca.r.n - cb.r.n).abs())
            .max((ca.r.t - cb.r.t).norm());
    }
    eprintln!("reactions: largest difference {worst:e}, largest reaction {scale:e}");
    assert!(
        worst <= tol * scale,
        "reactions differ by {worst:e} (scale {scale:e})"
    );
    // A real frictional problem: the base both sticks and slips, and carries load.
    let count = |s| a.contacts.iter().filter(|c| c.status == s).count();
    assert!(count(InterfaceStatus::Stick) > 0 && count(InterfaceStatus::Slip) > 0);
    assert!(a.contacts.iter().map(|c| c.r.n).sum::<f64>() > 0.0);
}

#[test]
fn issue_36_fenris_body_captures_errors() {
    let mesh = mesh();
    let fmesh = fenris_mesh(&mesh);
    let steel = PlaneStrainElasticity::new(YOUNG, POISSON).unwrap();
    assert!(matches!(
        PlaneStrainElasticity::new(YOUNG, 0.5),
        Err(FenrisBodyError::InvalidParameter {
            name: "poisson",
            ..
        })
    ));
    let count = mesh.node_count();
    assert!(matches!(
        FenrisBody::plane_strain(&fmesh, steel, BODY_FORCE, &[(count, Component::X)]),
        Err(FenrisBodyError::UnknownNode { node, .. }) if node == count
    ));
    // supports that leave a rigid-body motion: named, not factorised into nonsense
    assert!(matches!(
        FenrisBody::plane_strain(&fmesh, steel, BODY_FORCE, &[]),
        Err(FenrisBodyError::RigidBodyMotion {
            motion: "translation along x"
        })
    ));
    let top = mesh.node_set("top").unwrap();
    let top_y: Vec<_> = top.iter().map(|&n| (n, Component::Y)).collect();
    assert!(matches!(
        FenrisBody::plane_strain(&fmesh, steel, BODY_FORCE, &top_y),
        Err(FenrisBodyError::RigidBodyMotion {
            motion: "translation along x"
        })
    ));
    let one_node = [(top[0], Component::X), (top[0], Component::Y)];
    assert!(matches!(
        FenrisBody::plane_strain(&fmesh, steel, BODY_FORCE, &one_node),
        Err(FenrisBodyError::RigidBodyMotion { motion: "rotation" })
    ));
    let mut clamped = top_y.clone();
    clamped.push((top[0], Component::X));
    let body = FenrisBody::plane_strain(&fmesh, steel, BODY_FORCE, &clamped).unwrap();
    assert!(matches!(
        body.with_node_set("bottom", vec![count + 3]),
        Err(FenrisBodyError::UnknownNode { node, .. }) if node == count + 3
    ));
}
