//! The consistent boundary mass recovers a traction exactly from its consistent nodal forces
//! (issue 36: the contact pressure field).
//!
//! Source: O. C. Zienkiewicz, R. L. Taylor, *The Finite Element Method*, vol. 1, § 14.2 (the
//! consistent mass) and the `L²` projection: `M p = f` with `f_i = ∫ N_i p̂ w dΓ` gives back
//! `p = p̂` at the nodes for every `p̂` in the span of the boundary's shape functions — a
//! uniform and a linear field on P1 and P2 sides and faces (curved P2 ones included: the
//! isoparametric span holds every linear function of `x`), and a quadratic one on straight P2
//! sides and flat P2 faces.
//!
//! The forces come from an independent path: the model's own traction integration
//! (`add_edge_traction`, `add_face_traction`) read back as support reactions `R = K u − f`
//! with every loaded node held at `u = 0` (so `f = −R` there).

use fem_core::boundary_mass::BoundaryMass;
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::solid::generate::{box_mesh, lines, sphere_shell_octant};
use fem_core::solid::{SolidKind, SolidMesh, SolidModel};
use fem_core::{
    Component, ElementKind, Idealization, LinearElasticModel, Material, Mesh, Supports,
};

/// `f_i = −R_i` (component `comp`) at the boundary's nodes.
fn forces(reactions: &[fem_core::Reaction], mass: &BoundaryMass, comp: Component) -> Vec<f64> {
    let mut f = vec![0.0; mass.nodes().len()];
    for ((node, c), r) in reactions {
        if *c == comp
            && let Some(i) = mass.index_of(*node)
        {
            f[i] = -r;
        }
    }
    f
}

/// The largest nodal error of the field recovered from the consistent forces of `p`, relative
/// to the largest `|p|`.
fn error_2d(kind: ElementKind, ideal: Idealization, p: &dyn Fn([f64; 2]) -> f64) -> f64 {
    // a rectangle [1, 4] x [0, 2], graded so that the sides differ; the bottom y = 0 loaded
    let mut spec = RectangleSpec::new([1.0, 4.0], [0.0, 2.0], 5, 2);
    spec.grading_x = fem_core::generate::Grading::fine_at_start(3.0);
    spec.kind = kind;
    let mesh: Mesh = rectangle(&spec).unwrap();
    let bottom = mesh.node_set("bottom").unwrap().to_vec();
    let top = mesh.node_set("top").unwrap().to_vec();
    let sides = mesh.edge_set("bottom").unwrap().to_vec();
    let mass = BoundaryMass::from_sides(&mesh, &sides, ideal).unwrap();
    let mut s = Supports::new();
    s.fix(&bottom, Component::X)
        .fix(&bottom, Component::Y)
        .fix(&top, Component::X)
        .fix(&top, Component::Y);
    let nodes = mesh.nodes().to_vec();
    let material = Material::new(1000.0, 0.3, 0.0).unwrap();
    let mut model = LinearElasticModel::new(mesh, ideal, &[(0, material)], s).unwrap();
    // a pressure p on the face y = 0 (outward normal −y): traction (0, p)
    model.add_edge_traction("bottom", |x| [0.0, p(x)]).unwrap();
    let zero = vec![[0.0; 2]; nodes.len()];
    let r = model.reactions(&zero, 1.0).unwrap();
    let got = mass.solve(&forces(&r, &mass, Component::Y));
    let scale = mass
        .nodes()
        .iter()
        .fold(0.0_f64, |m, &n| m.max(p(nodes[n]).abs()));
    mass.nodes()
        .iter()
        .zip(&got)
        .map(|(&n, g)| (g - p(nodes[n])).abs() / scale)
        .fold(0.0, f64::max)
}

#[test]
fn issue_36_boundary_mass_recovers_uniform_linear_and_quadratic_tractions_2d() {
    let uniform = |_: [f64; 2]| 2.5;
    let linear = |x: [f64; 2]| 1.0 + 0.7 * x[0];
    let quadratic = |x: [f64; 2]| 1.0 + 0.7 * x[0] - 0.3 * x[0] * x[0];
    for ideal in [
        Idealization::PlaneStrain,
        Idealization::PlaneStress { thickness: 0.2 },
        Idealization::Axisymmetric,
    ] {
        for kind in [ElementKind::Tri3, ElementKind::Tri6] {
            // round-off of a few sums and a Cholesky solve of a well-conditioned system
            let tol = 1e-12;
            for (name, p) in [
                ("uniform", &uniform as &dyn Fn([f64; 2]) -> f64),
                ("linear", &linear),
            ] {
                let e = error_2d(kind, ideal, p);
                assert!(e < tol, "{kind:?} {ideal:?} {name}: relative error {e:e}");
            }
            if kind == ElementKind::Tri6 {
                let e = error_2d(kind, ideal, &quadratic);
                assert!(e < tol, "{ideal:?} quadratic: relative error {e:e}");
            } else {
                // P1 sides cannot carry a quadratic: the projection differs (the check fails)
                assert!(error_2d(kind, ideal, &quadratic) > 1e-4);
            }
        }
    }
}

/// The same in 3D on the face set `set` of `mesh`, for a pressure `p(x)` along the face's
/// outward normal; the other face sets named in `held` are held too.
fn error_3d(mesh: SolidMesh, set: &str, held: &[&str], p: &dyn Fn([f64; 3]) -> f64) -> f64 {
    let faces = mesh.face_set(set).unwrap().to_vec();
    let mass = BoundaryMass::from_faces(&mesh, &faces).unwrap();
    let mut s = Supports::new();
    for name in std::iter::once(&set).chain(held) {
        let nodes = mesh.node_set(name).unwrap().to_vec();
        for c in [Component::X, Component::Y, Component::Z] {
            s.fix(&nodes, c);
        }
    }
    let nodes = mesh.nodes().to_vec();
    let material = Material::new(1000.0, 0.3, 0.0).unwrap();
    let mut model = SolidModel::new(mesh, &[(0, material)], s).unwrap();
    // a traction p(x) e_z: compare the z forces with a field p
    model
        .add_face_traction(set, |x, _| [0.0, 0.0, p(x)])
        .unwrap();
    let zero = vec![[0.0; 3]; nodes.len()];
    let r = model.reactions(&zero, 1.0).unwrap();
    let got = mass.solve(&forces(&r, &mass, Component::Z));
    let scale = mass
        .nodes()
        .iter()
        .fold(0.0_f64, |m, &n| m.max(p(nodes[n]).abs()));
    mass.nodes()
        .iter()
        .zip(&got)
        .map(|(&n, g)| (g - p(nodes[n])).abs() / scale)
        .fold(0.0, f64::max)
}

#[test]
fn issue_36_boundary_mass_recovers_uniform_linear_and_quadratic_tractions_3d() {
    let uniform = |_: [f64; 3]| 2.5;
    let linear = |x: [f64; 3]| 1.0 + 0.7 * x[0] - 0.4 * x[1] + 0.2 * x[2];
    let quadratic = |x: [f64; 3]| 1.0 + 0.7 * x[0] * x[1] - 0.3 * x[1] * x[1];
    for kind in [SolidKind::Tet4, SolidKind::Tet10] {
        // a graded box, its top face z = 1 (flat)
        let xs = [0.0, 0.3, 1.0, 2.0];
        let mesh = box_mesh(&xs, &[0.0, 0.5, 1.5], &lines(0.0, 1.0, 2), kind).unwrap();
        // the curved outer face of a sphere octant (P2 faces on the sphere)
        let shell = sphere_shell_octant(1.0, 2.0, 3, 1, kind).unwrap();
        // round-off of a few sums and a Cholesky solve of a well-conditioned system
        let tol = 1e-12;
        for (name, p) in [
            ("uniform", &uniform as &dyn Fn([f64; 3]) -> f64),
            ("linear", &linear),
        ] {
            let e = error_3d(mesh.clone(), "z1", &["z0"], p);
            assert!(e < tol, "{kind:?} box {name}: relative error {e:e}");
            let e = error_3d(shell.clone(), "outer", &["inner"], p);
            assert!(e < tol, "{kind:?} sphere {name}: relative error {e:e}");
        }
        let e = error_3d(mesh.clone(), "z1", &["z0"], &quadratic);
        if kind == SolidKind::Tet10 {
            assert!(e < tol, "box quadratic: relative error {e:e}");
        } else {
            // P1 faces cannot carry a quadratic (the check can fail)
            assert!(e > 1e-4, "P1 quadratic: {e:e}");
        }
    }
}

#[test]
fn issue_36_p2_corner_areas_are_zero_but_the_recovered_field_is_not() {
    // the trap of issue 36: on 6-node faces the corners' consistent area is 0, so r_n / A is
    // 0 / 0 there; the mass recovers the uniform pressure at every node, corners included
    let mesh = box_mesh(
        &lines(0.0, 1.0, 2),
        &lines(0.0, 1.0, 2),
        &lines(0.0, 1.0, 1),
        SolidKind::Tet10,
    )
    .unwrap();
    let (nodes, areas) = mesh.nodal_areas("z1").unwrap();
    let faces = mesh.face_set("z1").unwrap().to_vec();
    let mass = BoundaryMass::from_faces(&mesh, &faces).unwrap();
    assert_eq!(mass.nodes(), nodes.as_slice());
    let corners = areas.iter().filter(|a| **a == 0.0).count();
    assert_eq!(corners, 9, "the 3 x 3 corner nodes of the face");
    // areas are the consistent forces of p = 1: the field is 1 everywhere
    let p = mass.solve(&areas);
    for v in p {
        // round-off of the solve
        assert!((v - 1.0).abs() < 1e-12, "{v}");
    }
}
