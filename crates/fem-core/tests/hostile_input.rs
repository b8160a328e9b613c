//! Hostile input to fem-core (issue 15): each class gets the error that names its cause, not a
//! symptom further down (a "missing support", a "degenerate element", NaN displacements).

use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::{Component, FemError, Idealization, LinearElasticModel, Material, Mesh, Supports};

fn supported(mesh: &Mesh) -> Supports {
    let mut s = Supports::new();
    s.fix(mesh.node_set("left").unwrap(), Component::X);
    s.fix(mesh.node_set("bottom").unwrap(), Component::Y);
    s
}

fn square() -> Mesh {
    rectangle(&RectangleSpec::new([0.0, 1.0], [0.0, 1.0], 2, 2)).unwrap()
}

#[test]
fn an_overflowing_young_modulus_is_named() {
    let mesh = square();
    let s = supported(&mesh);
    let e = LinearElasticModel::new(
        mesh,
        Idealization::PlaneStrain,
        &[(0, Material::new(1e308, 0.3, 0.0).unwrap())],
        s,
    )
    .unwrap_err();
    assert!(
        matches!(e, FemError::NonFiniteStiffness { region: 0, young, .. } if young == 1e308),
        "{e:?}"
    );
}

#[test]
fn a_subnormal_young_modulus_is_refused() {
    let e = Material::new(1e-310, 0.3, 0.0).unwrap_err();
    assert!(
        matches!(e, FemError::InvalidParameter { name: "young", .. }),
        "{e:?}"
    );
    assert!(Material::new(f64::MIN_POSITIVE, 0.3, 0.0).is_ok());
}

#[test]
fn overflowing_coordinates_are_named() {
    let e = rectangle(&RectangleSpec::new([0.0, 1e308], [0.0, 1e308], 2, 2)).unwrap_err();
    assert!(
        matches!(
            e,
            FemError::InvalidParameter {
                name: "node coordinates",
                ..
            }
        ),
        "{e:?}"
    );
}

#[test]
fn a_plane_stress_thickness_must_be_positive() {
    for thickness in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let mesh = square();
        let s = supported(&mesh);
        let e = LinearElasticModel::new(
            mesh,
            Idealization::PlaneStress { thickness },
            &[(0, Material::new(1.0, 0.3, 0.0).unwrap())],
            s,
        )
        .unwrap_err();
        assert!(
            matches!(
                e,
                FemError::InvalidParameter {
                    name: "thickness",
                    ..
                }
            ),
            "{thickness}: {e:?}"
        );
    }
}

#[test]
fn non_finite_loads_are_errors_not_nan_displacements() {
    let mesh = square();
    let s = supported(&mesh);
    let mut m = LinearElasticModel::new(
        mesh,
        Idealization::PlaneStrain,
        &[(0, Material::new(1.0, 0.3, 0.0).unwrap())],
        s,
    )
    .unwrap();
    for factor in [f64::NAN, f64::INFINITY] {
        let e = m.solve(factor).unwrap_err();
        assert!(
            matches!(
                e,
                FemError::NonFiniteSolve {
                    what: "load factor",
                    ..
                }
            ),
            "{e:?}"
        );
    }
    // finite forces whose scaled sum overflows: the right-hand side, at a named node
    let top_right = m.mesh().node_count() - 1;
    m.add_nodal_force(top_right, [1e308, 0.0]).unwrap();
    let e = m.solve(10.0).unwrap_err();
    match e {
        FemError::NonFiniteSolve {
            what: "right-hand side",
            node: Some((node, Component::X)),
            ..
        } => assert_eq!(node, top_right),
        other => panic!("{other:?}"),
    }
    // unscaled, the right-hand side is finite but the displacement of this soft square
    // (E = 1) overflows: named too
    let e = m.solve(1.0).unwrap_err();
    assert!(
        matches!(
            e,
            FemError::NonFiniteSolve {
                what: "displacement",
                node: Some(_),
                ..
            }
        ),
        "{e:?}"
    );
}

#[test]
fn unknown_nodes_are_named_without_a_fake_element() {
    let mut mesh = square();
    let e = mesh.add_node_set("top", vec![99]).unwrap_err();
    let text = e.to_string();
    assert!(text.contains("a node set refers to node 99"), "{text}");
    assert!(!text.contains(&usize::MAX.to_string()), "{text}");
}

/// Huge counts are refused before anything is allocated (an allocation failure would abort
/// the process; `usize::MAX` overflowed the capacity): `nx = 1e9`, `nx = usize::MAX`, a huge
/// layer, a huge pile mesh.
#[test]
fn huge_meshes_are_refused_before_allocation() {
    use fem_core::generate::{MAX_GENERATED_NODES, PileSpec, pile_in_soil};
    for nx in [1_000_000_000, usize::MAX, MAX_GENERATED_NODES] {
        let e = rectangle(&RectangleSpec::new([0.0, 1.0], [0.0, 1.0], nx, 2)).unwrap_err();
        assert!(matches!(e, FemError::TooLarge { .. }), "{nx}: {e:?}");
    }
    let e = rectangle(&RectangleSpec::new([0.0, 1.0], [0.0, 1.0], 2, usize::MAX)).unwrap_err();
    assert!(
        matches!(
            e,
            FemError::TooLarge {
                requested: None,
                ..
            }
        ),
        "{e:?}"
    );
    assert!(e.to_string().contains("more than usize::MAX"), "{e}");
    let pile = PileSpec {
        cells_soil_r: usize::MAX - 1,
        ..PileSpec::default()
    };
    assert!(matches!(
        pile_in_soil(&pile),
        Err(FemError::TooLarge { .. })
    ));
    // the limit itself is reachable: a 100 × 100 grid is far below it
    assert!(rectangle(&RectangleSpec::new([0.0, 1.0], [0.0, 1.0], 100, 100)).is_ok());
}
