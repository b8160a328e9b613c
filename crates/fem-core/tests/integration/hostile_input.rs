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

#[test]
fn an_empty_mesh_is_refused() {
    let e = Mesh::new(
        vec![[0.0, 0.0], [1.0, 0.0]],
        fem_core::ElementKind::Tri3,
        vec![],
        vec![],
    )
    .unwrap_err();
    assert_eq!(e, FemError::EmptyMesh { node_count: 2 });
    let e = Mesh::<2>::new(vec![], fem_core::ElementKind::Tri6, vec![], vec![]).unwrap_err();
    assert_eq!(e, FemError::EmptyMesh { node_count: 0 });
}

#[test]
fn a_dof_prescribed_twice_with_different_values_is_refused() {
    let mut s = Supports::new();
    s.prescribe(&[0, 1], Component::Y, -0.01).unwrap();
    // the same value again is no conflict
    s.prescribe(&[1, 2], Component::Y, -0.01).unwrap();
    // another component is another dof
    s.prescribe(&[1], Component::X, 0.5).unwrap();
    let e = s.prescribe(&[3, 1], Component::Y, 0.02).unwrap_err();
    assert_eq!(
        e,
        FemError::ConflictingPrescription {
            node: 1,
            component: Component::Y,
            first: -0.01,
            second: 0.02
        }
    );
    // nothing was changed by the refused call (node 3 stays free)
    assert_eq!(s.value(3, Component::Y), None);
    assert_eq!(s.value(1, Component::Y), Some(-0.01));
    // a fixed dof prescribed to a value is a conflict too
    s.fix(&[7], Component::X);
    assert!(matches!(
        s.prescribe(&[7], Component::X, 1.0),
        Err(FemError::ConflictingPrescription { node: 7, .. })
    ));
    assert!(s.to_owned().prescribe(&[7], Component::X, 0.0).is_ok());
}

#[test]
fn update_changes_a_prescribed_value_on_purpose() {
    let mut s = Supports::new();
    s.prescribe(&[0], Component::Y, -0.01).unwrap();
    s.update(&[0], Component::Y, -0.02).unwrap();
    assert_eq!(s.value(0, Component::Y), Some(-0.02));
    assert!(matches!(
        s.update(&[0], Component::Y, f64::NAN),
        Err(FemError::InvalidParameter { .. })
    ));
    // release then prescribe is no conflict either
    s.release(&[0], Component::Y);
    s.prescribe(&[0], Component::Y, 0.3).unwrap();
}

#[test]
fn a_model_changes_its_prescribed_values_between_steps() {
    let mesh = square();
    let top = mesh.node_set("top").unwrap().to_vec();
    let mut s = supported(&mesh);
    s.prescribe(&top, Component::Y, -0.01).unwrap();
    let mut model = LinearElasticModel::new(
        mesh,
        Idealization::PlaneStrain,
        &[(0, Material::new(1.0, 0.3, 0.0).unwrap())],
        s,
    )
    .unwrap();
    model.set_prescribed(&top, Component::Y, -0.02).unwrap();
    assert_eq!(model.supports().value(top[0], Component::Y), Some(-0.02));
}

/// Two triangles of the unit square, with node tags 11..14 and element tags 21, 22.
fn msh(nodes: &str, elements: &str) -> String {
    format!(
        "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 4 11 14\n2 1 0 4\n{nodes}$EndNodes\n\
         $Elements\n{elements}$EndElements\n"
    )
}

const NODES: &str = "11\n12\n13\n14\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n";

#[test]
fn gmsh_errors_name_the_files_own_tags() {
    let ok = msh(NODES, "1 2 21 22\n2 1 2 2\n21 11 12 14\n22 14 12 13\n");
    assert_eq!(
        fem_core::gmsh::parse_msh(ok.as_bytes())
            .unwrap()
            .element_count(),
        2
    );
    let cases = [
        // a node tag never defined, in a triangle and in a line of a physical curve
        (
            msh(NODES, "1 2 21 22\n2 1 2 2\n21 11 12 14\n22 14 12 19\n"),
            "element 22 refers to node tag 19, which $Nodes never defines",
        ),
        // a degenerate triangle: its Gmsh tag, not its index 1
        (
            msh(NODES, "1 2 21 22\n2 1 2 2\n21 11 12 14\n22 14 12 14\n"),
            "element 22 is degenerate",
        ),
        // an element tag used twice
        (
            msh(NODES, "1 2 21 22\n2 1 2 2\n21 11 12 14\n21 14 12 13\n"),
            "element tag 21 is used twice",
        ),
        // headers announcing more than the blocks hold
        (
            msh(
                NODES,
                "1 2000000000 21 22\n2 1 2 2\n21 11 12 14\n22 14 12 13\n",
            ),
            "the $Elements header announces 2000000000 elements, but its blocks hold 2",
        ),
        (
            msh(NODES, "1 2 21 22\n2 1 2 2\n21 11 12 14\n22 14 12 13\n")
                .replace("1 4 11 14\n", "1 9 11 14\n"),
            "the $Nodes header announces 9 nodes, but its blocks define 4",
        ),
        // a non-finite coordinate: node tag 13, not index 2
        (
            msh(
                &NODES.replace("1 1 0", "inf 1 0"),
                "1 2 21 22\n2 1 2 2\n21 11 12 14\n22 14 12 13\n",
            ),
            "node 13 has a non-finite coordinate (inf, 1.0)",
        ),
    ];
    for (text, expected) in cases {
        let e = fem_core::gmsh::parse_msh(text.as_bytes()).unwrap_err();
        assert!(
            e.to_string().contains(expected),
            "{e}\nexpected: {expected}"
        );
    }
}
