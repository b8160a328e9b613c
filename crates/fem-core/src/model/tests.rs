//! Unit tests of `LinearElasticModel`.

use super::*;
use crate::generate::{RectangleSpec, rectangle};
use crate::mesh::{ElementKind, Side};

/// Unit square, two P1 triangles; right side loaded by a uniform traction.
fn square_model(idealization: Idealization) -> LinearElasticModel {
    let nodes = vec![[1.0, 0.0], [2.0, 0.0], [2.0, 1.0], [1.0, 1.0]];
    let mut mesh = Mesh::new(nodes, ElementKind::Tri3, vec![0, 1, 2, 0, 2, 3], vec![]).unwrap();
    mesh.add_edge_set(
        "right",
        vec![Side {
            element: 0,
            side: 1,
        }],
    )
    .unwrap();
    let mut supports = Supports::new();
    supports.fix(&[0, 3], Component::X).fix(&[0], Component::Y);
    let m = Material::new(100.0, 0.25, 0.0).unwrap();
    LinearElasticModel::new(mesh, idealization, &[(0, m)], supports).unwrap()
}

#[test]
fn prescribed_displacement_reports_imposed_values_only() {
    let mut m = square_model(Idealization::PlaneStrain);
    m.set_prescribed(&[3], Component::Y, 0.25).unwrap();
    assert_eq!(m.prescribed_displacement(3), [0.0, 0.25]); // x fixed at 0, y imposed
    assert_eq!(m.prescribed_displacement(2), [0.0, 0.0]); // free node
    let u = m.solve(1.0).unwrap();
    assert_eq!(u[3][1], 0.25);
}

#[test]
fn uniaxial_tension_works() {
    let mut model = square_model(Idealization::PlaneStress { thickness: 1.0 });
    model.add_edge_traction("right", |_| [2.0, 0.0]).unwrap();
    let u = model.solve(1.0).unwrap();
    // ε_xx = σ/E = 0.02 over a length 1; ε_yy = −ν ε_xx.
    assert!((u[1][0] - 0.02).abs() < 1e-12 && (u[2][0] - 0.02).abs() < 1e-12);
    assert!((u[3][1] + 0.005).abs() < 1e-12);
    for pts in model.stresses(&u).unwrap() {
        for (_, s) in pts {
            assert!((s[0] - 2.0).abs() < 1e-12 && s[1].abs() < 1e-12 && s[2].abs() < 1e-12);
        }
    }
    // Strains: ε_xx = 0.02, ε_yy = −0.005, ε_zz = −ν/(1−ν)(ε_xx + ε_yy) = −0.005.
    for pts in model.strains(&u).unwrap() {
        for (_, e) in pts {
            assert!((e[0] - 0.02).abs() < 1e-12 && (e[1] + 0.005).abs() < 1e-12);
            assert!(e[2].abs() < 1e-12 && (e[3] + 0.005).abs() < 1e-12);
        }
    }
    // Reactions balance the applied load: Σ R_x = −2 (length 1 × traction 2).
    let r = model.reactions(&u, 1.0).unwrap();
    let rx: f64 = r
        .iter()
        .filter(|((_, c), _)| *c == Component::X)
        .map(|(_, v)| v)
        .sum();
    assert!((rx + 2.0).abs() < 1e-12, "Σ R_x = {rx}");
}

#[test]
fn missing_supports_are_reported_not_nan() {
    let nodes = vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
    let mesh = Mesh::new(nodes, ElementKind::Tri3, vec![0, 1, 2], vec![]).unwrap();
    let m = Material::new(1.0, 0.3, 0.0).unwrap();
    let err = LinearElasticModel::new(mesh, Idealization::PlaneStrain, &[(0, m)], Supports::new())
        .unwrap_err();
    assert!(
        matches!(err, FemError::NotPositiveDefinite { .. }),
        "{err:?}"
    );
}

#[test]
fn changing_a_prescribed_value_does_not_refactor() {
    let mut model = square_model(Idealization::PlaneStrain);
    assert_eq!(model.factorizations(), 1);
    model.set_prescribed(&[1, 2], Component::X, 0.01).unwrap(); // new constraint
    assert_eq!(model.factorizations(), 2);
    let v = model.stiffness_version();
    model.set_prescribed(&[1, 2], Component::X, 0.02).unwrap(); // value only
    assert_eq!(model.factorizations(), 2);
    assert_eq!(model.stiffness_version(), v);
    let u = model.solve(0.0).unwrap();
    assert!((u[1][0] - 0.02).abs() < 1e-15);
    assert!((u[3][0]).abs() < 1e-15);
}

#[test]
fn missing_material_is_reported() {
    let nodes = vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
    let mesh = Mesh::new(nodes, ElementKind::Tri3, vec![0, 1, 2], vec![3]).unwrap();
    let m = Material::new(1.0, 0.3, 0.0).unwrap();
    let err = LinearElasticModel::new(mesh, Idealization::PlaneStrain, &[(0, m)], Supports::new())
        .unwrap_err();
    assert_eq!(
        err,
        FemError::MissingMaterial {
            region: 3,
            element: 0
        }
    );
}

/// Issue 13: a stiffness that is not positive definite names a node and a component of
/// the model, not faer's pivot in its permuted order.
#[test]
fn issue_13_not_positive_definite_names_node() {
    let m = Material::new(210e9, 0.3, 0.0).unwrap();

    // A supported 3 × 2 rectangle plus one node (inserted as node 5) that no element
    // connects. Its two rows and columns of K are zero but for the structural diagonal
    // (0). Every leading block of P K Pᵀ without its dofs is a principal submatrix of the
    // supported rectangle's stiffness (SPD), and the first block that holds one of its
    // dofs has the pivot 0 − 0 = 0 exactly: the factorisation must stop at node 5,
    // whichever of its components the ordering puts first.
    let rect = rectangle(&RectangleSpec::new([0.0, 3.0], [0.0, 2.0], 3, 2)).unwrap();
    let extra = 5;
    let shift = |n: usize| if n >= extra { n + 1 } else { n };
    let mut nodes = rect.nodes().to_vec();
    nodes.insert(extra, [10.0, 10.0]);
    let connectivity = rect.connectivity().iter().map(|&n| shift(n)).collect();
    let mesh = Mesh::new(nodes, ElementKind::Tri3, connectivity, vec![]).unwrap();
    let bottom: Vec<usize> = rect
        .node_set("bottom")
        .unwrap()
        .iter()
        .map(|&n| shift(n))
        .collect();
    let mut supports = Supports::new();
    supports
        .fix(&bottom, Component::X)
        .fix(&bottom, Component::Y);
    let dofs = DofMap::new(mesh.node_count(), &supports).unwrap();
    let err =
        LinearElasticModel::new(mesh, Idealization::PlaneStrain, &[(0, m)], supports).unwrap_err();
    let FemError::NotPositiveDefinite {
        node,
        component,
        row,
    } = err
    else {
        panic!("expected NotPositiveDefinite, got {err:?}");
    };
    assert_eq!(node, extra);
    assert_eq!(dofs.free_dofs(node)[component as usize], Some(row));
    assert!(
        err.to_string()
            .contains(&format!("node {extra}, component {component}"))
    );

    // Rectangles fixed in y only along the bottom: the one rigid-body mode is the
    // translation along x, u = (1, 0) at every node. Its leading block first becomes
    // singular at the last x dof eliminated, so a failure must name an x dof. (Round-off
    // can instead leave that pivot tiny and positive, and the factorisation succeeds: so
    // only the meshes that fail are checked, and at least one must.)
    let mut failures = 0;
    for kind in [ElementKind::Tri3, ElementKind::Tri6] {
        for (nx, ny) in [(1, 1), (2, 3), (4, 4), (10, 7)] {
            let spec = RectangleSpec {
                kind,
                ..RectangleSpec::new([0.0, 2.0], [0.0, 1.0], nx, ny)
            };
            let mesh = rectangle(&spec).unwrap();
            let mut supports = Supports::new();
            supports.fix(mesh.node_set("bottom").unwrap(), Component::Y);
            match LinearElasticModel::new(mesh, Idealization::PlaneStrain, &[(0, m)], supports) {
                Ok(_) => {}
                Err(FemError::NotPositiveDefinite { component, .. }) => {
                    assert_eq!(component, Component::X, "{kind:?} {nx}×{ny}");
                    failures += 1;
                }
                Err(e) => panic!("{kind:?} {nx}×{ny}: {e:?}"),
            }
        }
    }
    assert!(failures > 0);
}

/// A rigid cap (the top of a block tied along `y`) pressed by one resultant force: the
/// uniaxial stress field is exact for P1, so the cap's displacement is `−P H / (E w)` to
/// round-off (plane stress, the sides free, the bottom on rollers).
#[test]
fn tied_cap_under_a_resultant_force_works() {
    let mesh = rectangle(&RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 4, 3)).unwrap();
    let top = mesh.node_set("top").unwrap().to_vec();
    let bottom = mesh.node_set("bottom").unwrap().to_vec();
    let mut supports = Supports::new();
    supports
        .fix(&bottom, Component::Y)
        .fix(&bottom[..1], Component::X)
        .tie(&top, Component::Y)
        .unwrap();
    let e = 100.0;
    let mut model = LinearElasticModel::new(
        mesh,
        Idealization::PlaneStress { thickness: 1.0 },
        &[(0, Material::new(e, 0.3, 0.0).unwrap())],
        supports,
    )
    .unwrap();
    assert_eq!(model.dof_count(), 2 * 20 - 5 - 1 - (top.len() - 1));
    let p = 3.0;
    // the resultant on any one node of the cap
    model.add_nodal_force(top[2], [0.0, -p]).unwrap();
    let u = model.solve(1.0).unwrap();
    let expected = -p * 1.0 / (e * 2.0);
    for &n in &top {
        assert!(
            (u[n][1] - expected).abs() < 1e-13,
            "{} vs {expected}",
            u[n][1]
        );
    }
    let reactions = model.reactions(&u, 1.0).unwrap();
    let total: f64 = reactions
        .iter()
        .filter(|((_, c), _)| *c == Component::Y)
        .map(|(_, r)| r)
        .sum();
    assert!((total - p).abs() < 1e-12, "{total}");
}

#[test]
fn ties_that_contradict_the_supports_are_refused() {
    let mesh = rectangle(&RectangleSpec::new([0.0, 1.0], [0.0, 1.0], 2, 2)).unwrap();
    let top = mesh.node_set("top").unwrap().to_vec();
    let bottom = mesh.node_set("bottom").unwrap().to_vec();
    let m = [(0, Material::new(1.0, 0.3, 0.0).unwrap())];
    // prescribed at one node of the cap, free at the others
    let mut s = Supports::new();
    s.fix(&bottom, Component::X).fix(&bottom, Component::Y);
    s.tie(&top, Component::Y).unwrap();
    s.prescribe(&top[..1], Component::Y, -0.1).unwrap();
    let e = LinearElasticModel::new(mesh.clone(), Idealization::PlaneStrain, &m, s).unwrap_err();
    assert!(
        matches!(e, FemError::InvalidTie { node: Some(_), .. }),
        "{e}"
    );
    // the whole cap prescribed: a displacement-controlled cap
    let mut s = Supports::new();
    s.fix(&bottom, Component::X).fix(&bottom, Component::Y);
    s.tie(&top, Component::Y).unwrap();
    s.prescribe(&top, Component::Y, -0.1).unwrap();
    let model = LinearElasticModel::new(mesh, Idealization::PlaneStrain, &m, s).unwrap();
    let u = model.solve(1.0).unwrap();
    assert!(top.iter().all(|&n| u[n][1] == -0.1));
}

/// One generic function run on a 2D and a 3D model: a nodal force is balanced by the support
/// reactions, component by component.
fn reactions_balance<const D: usize>(mut model: ElasticModel<D>, node: usize)
where
    Dim<D>: ModelSpace<D>,
{
    let force: [f64; D] = std::array::from_fn(|c| 1.0 + c as f64);
    model.add_nodal_force(node, force).unwrap();
    let u = model.solve(1.0).unwrap();
    let reactions = model.reactions(&u, 1.0).unwrap();
    for (c, f) in force.iter().enumerate() {
        let sum: f64 = reactions
            .iter()
            .filter(|((_, component), _)| *component as usize == c)
            .map(|(_, r)| r)
            .sum();
        // equilibrium, to the round-off of a solve with entries of size E = 100
        assert!(
            (sum + f).abs() < 1e-10,
            "{}: Σ R_{c} = {sum}",
            <Dim<D> as Space>::NAME
        );
    }
}

#[test]
fn issue_35_one_model_for_both_dimensions_works() {
    use crate::solid::generate::{box_mesh, lines};
    reactions_balance(square_model(Idealization::PlaneStrain), 2);
    let unit = lines(0.0, 1.0, 1);
    let mesh = box_mesh(&unit, &unit, &unit, ElementKind::Tet4).unwrap();
    let top = mesh.nodes().iter().position(|p| *p == [1.0; 3]).unwrap();
    let mut supports = Supports::new();
    let bottom = mesh.node_set("z0").unwrap().to_vec();
    for c in Component::all::<3>() {
        supports.fix(&bottom, c);
    }
    let m = Material::new(100.0, 0.25, 0.0).unwrap();
    reactions_balance(SolidModel::new(mesh, &[(0, m)], supports).unwrap(), top);
}

/// A solve after a failed factorisation (a non-positive-definite tangent) is an error naming
/// the cause, never the solver's panic: the Newton around contact solves again after a failed
/// step (issue 40, found by the CLI's plastic scenes).
#[test]
fn solve_after_failed_factorisation_is_an_error() {
    let mut m = square_model(Idealization::PlaneStrain);
    let negated: Vec<f64> = m.values.iter().map(|v| -v).collect();
    assert!(m.factor_values(&negated).is_err());
    let mut u = vec![0.0; m.dof_map().free_count()];
    let e = Structure::free_response_into(&m, 1.0, &mut u).unwrap_err();
    assert!(e.to_string().contains("last factorisation failed"), "{e}");
    let mut b = vec![1.0; u.len()];
    assert!(Structure::solve_in_place(&m, &mut b).is_err());
    // a successful factorisation makes it solvable again
    m.refactor().unwrap();
    assert!(Structure::free_response_into(&m, 1.0, &mut u).is_ok());
}

/// Issue 38: a released factor refuses solves (naming the release, never a panic), and the
/// restored one gives the free response bit for bit as before, at the same stiffness version.
#[test]
fn issue_38_release_and_restore_factor_works() {
    let mut model = square_model(Idealization::PlaneStress { thickness: 1.0 });
    model.add_edge_traction("right", |_| [2.0, 0.5]).unwrap();
    let before = model.solve(1.0).unwrap();
    let version = model.stiffness_version();
    // nothing to restore while the factor is held
    model.restore_factor().unwrap();
    assert!(model.release_factor());
    assert!(!model.release_factor(), "released already");
    match model.solve(1.0) {
        Err(FemError::LinearAlgebra { detail }) => assert!(detail.contains("released")),
        other => panic!("expected a refused solve, got {other:?}"),
    }
    model.restore_factor().unwrap();
    assert_eq!(model.solve(1.0).unwrap(), before);
    assert_eq!(model.stiffness_version(), version);
}
