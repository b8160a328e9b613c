//! Issue 35: one contact geometry layer for 2D and 3D. The same generic function (recognition,
//! the rigid-target checks, the supported contactors and the frames) runs on a 2D block above
//! a rigid LINE and on a 3D block above a rigid plane, each also paired node to node with a
//! fixed normal.
//!
//! The scene (closed form, no mechanics): a unit block whose bottom face lies `GAP` above a
//! flat rigid obstacle; every bottom node projects on it with the gap `GAP`, the normal `e_y`
//! (2D) or `e_z` (3D), the tangents `t = (n_y, −n_x) = e_x` (2D) or `t₁ = e_x`, `t₂ = e_y`
//! (3D), and its own position minus `GAP` along the normal as its target point.
//!
//! ```text
//!   ┌──────┐  block, bottom at 0
//!   └──────┘
//!   ════════  obstacle at −GAP
//! ```

#![cfg(feature = "fe")]

use contact_laws::Signorini;
use contact_solver::coupling::solid::{PairNormals3, RigidPlane};
use contact_solver::coupling::space::ContactSpace;
use contact_solver::coupling::zone::PairNormals;
use contact_solver::{
    Candidate, ContactZone, RigidLine, SolverError, check_rigid_targets, recognize,
    supported_contactors,
};
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::solid::generate::{box_mesh, lines};
use fem_core::solid::{SolidKind, SolidModel};
use fem_core::{Component, Dim, Idealization, LinearElasticModel, Material, Structure, Supports};

/// The clearance of the bottom face above the obstacle.
const GAP: f64 = 0.01;

/// Recognition, the rigid checks and the supported contactors of any dimension, with the
/// closed-form checks of the module docs on every candidate; the candidates.
fn recognize_and_check<S, const D: usize>(
    s: &S,
    zones: &[ContactZone<Signorini, D>],
) -> Result<Vec<Candidate<D>>, SolverError>
where
    S: Structure<D>,
    Dim<D>: ContactSpace<D>,
{
    let candidates = recognize(s, zones)?;
    check_rigid_targets(s, zones, &candidates)?;
    assert!(supported_contactors(s, zones)?.is_empty());
    let up: [f64; D] = core::array::from_fn(|a| if a == D - 1 { 1.0 } else { 0.0 });
    for c in &candidates {
        let frame = c.frame();
        assert_eq!(c.normal(), up, "node {}", c.node);
        // the tangents are the other axes in order: e_x (2D); e_x, e_y (3D)
        for (k, t) in frame.iter().enumerate().skip(1) {
            let e: [f64; D] = core::array::from_fn(|a| if a == k - 1 { 1.0 } else { 0.0 });
            assert_eq!(*t, e, "node {} tangent {k}", c.node);
        }
        // positions and GAP are exact in binary up to one rounding of x − GAP
        assert!(
            (c.gap0 - GAP).abs() <= 1e-15,
            "node {}: gap {}",
            c.node,
            c.gap0
        );
        let x = s.node_position(c.node);
        for (a, (&p, &xa)) in c.point.iter().zip(&x).enumerate() {
            let want = if a == D - 1 { xa - GAP } else { xa };
            assert!((p - want).abs() <= 1e-15, "node {}", c.node);
        }
        // the local jump of a rigid translation along the normal: x_n = g₀ + 1, u_t = 0
        let local = c.local(c.relative(|n| if n == c.node { up } else { [0.0; D] }));
        assert!((local[0] - (c.gap0 + 1.0)).abs() <= 1e-15);
        assert!(local[1..].iter().all(|&v| v == 0.0));
    }
    Ok(candidates)
}

#[test]
fn issue_35_one_recognition_for_2d_and_3d() {
    let m = Material::new(100.0, 0.3, 0.0).unwrap();
    // 2D: a 4 × 4 block above the LINE y = −GAP (from left to right: the block on its left)
    let mesh = rectangle(&RectangleSpec::new([0.0, 1.0], [0.0, 1.0], 4, 4)).unwrap();
    let bottom = mesh.node_set("bottom").unwrap().to_vec();
    let top = mesh.node_set("top").unwrap().to_vec();
    let mut supports = Supports::new();
    supports.fix(&top, Component::Y).fix(&top, Component::X);
    let plane =
        LinearElasticModel::new(mesh, Idealization::PlaneStrain, &[(0, m)], supports).unwrap();
    let line = RigidLine::new([-1.0, -GAP], [2.0, -GAP]).unwrap();
    let zone = ContactZone::rigid("floor", bottom.clone(), line, Signorini, 0.1);
    let c2 = recognize_and_check(&plane, &[zone]).unwrap();
    assert_eq!(c2.len(), bottom.len());
    // 2D areas lumped along the bottom (plane strain: its length, 1)
    let sum: f64 = c2.iter().map(|c| c.area).sum();
    assert!((sum - 1.0).abs() < 1e-14, "{sum}");

    // 3D: a 2 × 2 × 1 block above the plane z = −GAP
    let l = lines(0.0, 1.0, 2);
    let mesh = box_mesh(&l, &l, &lines(0.0, 0.5, 1), SolidKind::Tet4).unwrap();
    let bottom3 = mesh.node_set("z0").unwrap().to_vec();
    let top3 = mesh.node_set("z1").unwrap().to_vec();
    let mut s = Supports::new();
    s.fix(&top3, Component::Z)
        .fix(&top3, Component::X)
        .fix(&top3, Component::Y);
    let solid = SolidModel::new(mesh, &[(0, m)], s).unwrap();
    let floor = RigidPlane::new([0.0, 0.0, -GAP], [0.0, 0.0, 1.0]).unwrap();
    let zone = ContactZone::rigid("floor", bottom3.clone(), floor, Signorini, 0.1);
    let c3 = recognize_and_check(&solid, &[zone]).unwrap();
    assert_eq!(c3.len(), bottom3.len());
    // 3D areas without `with_areas`: 1 per node
    assert!(c3.iter().all(|c| c.area == 1.0));

    // node pairs with a fixed normal, in both dimensions: the same generic code; a zero
    // normal is refused in both with the same message
    let targets2: Vec<usize> = bottom.iter().map(|_| top[0]).collect();
    let pairs = |n: [f64; 2]| {
        ContactZone::node_pairs(
            "pairs",
            bottom.clone(),
            targets2.clone(),
            Some(n),
            Signorini,
            1.0,
        )
    };
    let err = recognize(&plane, &[pairs([0.0, 0.0])]).unwrap_err();
    assert!(
        matches!(&err, SolverError::InvalidGeometry(m) if m.contains("unit normal")),
        "{err}"
    );
    assert_eq!(
        recognize(&plane, &[pairs([0.0, 2.0])]).unwrap().len(),
        bottom.len()
    );
    let targets3: Vec<usize> = bottom3.iter().map(|_| top3[0]).collect();
    let pairs3 = |n: [f64; 3]| {
        ContactZone::node_pairs(
            "pairs",
            bottom3.clone(),
            targets3.clone(),
            PairNormals3::Fixed(n),
            Signorini,
            1.0,
        )
    };
    let err = recognize(&solid, &[pairs3([0.0; 3])]).unwrap_err();
    assert!(
        matches!(&err, SolverError::InvalidGeometry(m) if m.contains("unit normal")),
        "{err}"
    );
    assert_eq!(
        recognize(&solid, &[pairs3([0.0, 0.0, 2.0])]).unwrap().len(),
        bottom3.len()
    );
    // the 2D default (normals from the target nodes) has no meaning in 3D: refused
    let from_targets = ContactZone::node_pairs(
        "pairs",
        bottom3.clone(),
        targets3.clone(),
        PairNormals::FromTargets,
        Signorini,
        1.0,
    );
    assert!(matches!(
        recognize(&solid, &[from_targets]),
        Err(SolverError::InvalidGeometry(m)) if m.contains("3D node pairs")
    ));
}
