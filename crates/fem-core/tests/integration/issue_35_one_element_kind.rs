//! One element kind for both dimensions (issue 35): `ElementKind` holds the triangles and
//! quadrilaterals of the plane and the tetrahedra and hexahedra of space, each with its
//! dimension; a mesh of the other dimension refuses a kind with `FemError::KindDimension`.
//!
//! Sources: the Gmsh reference manual, "MSH file format" (element types 2, 9, 3, 16, 10 in the
//! plane, 4, 11, 5, 17 in space) and the VTK file-format manual (cell types 5, 22, 9, 23, 28;
//! 10, 24, 12, 25): the numbers every kind had before the join.

use fem_core::generate::{PileSpec, RectangleSpec, pile_in_soil, rectangle};
use fem_core::gmsh::parse_mesh;
use fem_core::solid::generate::{box_mesh, lines};
use fem_core::solid::{SolidKind, SolidMesh};
use fem_core::vtk::write_vtu;
use fem_core::{Dim, ElementKind, FemError, Mesh, Space};

/// The error of a kind of dimension `kind_dimension` given to a mesh of `dimension`.
fn refused(kind: &str, kind_dimension: usize, dimension: usize) -> FemError {
    FemError::KindDimension {
        kind: kind.to_string(),
        kind_dimension,
        dimension,
    }
}

/// The mesh `mesh` as a Gmsh MSH 4.1 file: one entity of dimension `D` holding every node and
/// every element, of Gmsh type `gmsh_type`, nodes in the mesh's order.
fn msh<const D: usize>(mesh: &Mesh<D>, gmsh_type: u32) -> String
where
    Dim<D>: Space,
{
    let (n, e) = (mesh.node_count(), mesh.element_count());
    let mut s = format!("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 {n} 1 {n}\n{D} 1 0 {n}\n");
    for k in 1..=n {
        s += &format!("{k}\n");
    }
    for p in mesh.nodes() {
        let z = if D == 3 { p[D - 1] } else { 0.0 };
        s += &format!("{} {} {z}\n", p[0], p[1]);
    }
    s += &format!("$EndNodes\n$Elements\n1 {e} 1 {e}\n{D} 1 {gmsh_type} {e}\n");
    for k in 0..e {
        s += &format!("{}", k + 1);
        for node in mesh.element(k) {
            s += &format!(" {}", node + 1);
        }
        s += "\n";
    }
    s + "$EndElements\n"
}

/// Reads `mesh` back from Gmsh (its kind and node count again) and writes it to VTK (the cell
/// type `vtk_cell`).
fn round_trip<const D: usize>(mesh: &Mesh<D>, gmsh_type: u32, vtk_cell: u8)
where
    Dim<D>: Space,
{
    let kind = mesh.kind();
    let back: Mesh<D> = parse_mesh(msh(mesh, gmsh_type).as_bytes()).unwrap();
    assert_eq!(back.kind(), kind);
    assert_eq!(back.element(0).len(), kind.node_count(), "{kind:?}");
    assert_eq!(
        back.connectivity().len(),
        mesh.connectivity().len(),
        "{kind:?}"
    );
    let dir = std::env::temp_dir().join(format!("fem_core_issue_35_kind_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(format!("{kind:?}.vtu"));
    write_vtu(&path, mesh, &[], &[]).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    let range = format!(r#"RangeMin="{vtk_cell}" RangeMax="{vtk_cell}""#);
    assert!(text.contains(&range), "{kind:?}: no {range}");
    std::fs::remove_file(&path).unwrap();
}

#[test]
fn issue_35_one_element_kind() {
    // (a) one enum builds the meshes of both dimensions, through `Mesh::new` and the generators
    let square = Mesh::<2>::new(
        vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
        ElementKind::Quad4,
        vec![0, 1, 2, 3],
        vec![],
    )
    .unwrap();
    let tet = [[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let tetra = Mesh::<3>::new(tet.to_vec(), ElementKind::Tet4, vec![0, 1, 2, 3], vec![]).unwrap();
    assert_eq!(
        (square.kind().dimension(), tetra.kind().dimension()),
        (2, 3)
    );
    // the old name of the 3D kinds is the same type
    let old: SolidMesh =
        SolidMesh::new(tet.to_vec(), SolidKind::Tet4, vec![0, 1, 2, 3], vec![]).unwrap();
    assert_eq!(old, tetra);

    // (b) a kind of the other dimension is refused, naming the kind and both dimensions
    let err = Mesh::<2>::new(
        vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]],
        ElementKind::Tet4,
        vec![0, 1, 2, 3],
        vec![],
    )
    .unwrap_err();
    assert_eq!(err, refused("Tet4", 3, 2));
    assert_eq!(
        err.to_string(),
        "element kind Tet4 is 3D, but the mesh is 2D"
    );
    let err = Mesh::<3>::new(tet[..3].to_vec(), ElementKind::Tri3, vec![0, 1, 2], vec![]);
    assert_eq!(err.unwrap_err(), refused("Tri3", 2, 3));
    let spec = RectangleSpec {
        kind: ElementKind::Hex8,
        ..RectangleSpec::new([0.0, 1.0], [0.0, 1.0], 1, 1)
    };
    assert_eq!(rectangle(&spec).unwrap_err(), refused("Hex8", 3, 2));
    let spec = PileSpec {
        kind: ElementKind::Tet10,
        ..PileSpec::default()
    };
    assert_eq!(pile_in_soil(&spec).unwrap_err(), refused("Tet10", 3, 2));
    let l = lines(0.0, 1.0, 1);
    assert_eq!(
        box_mesh(&l, &l, &l, ElementKind::Quad9).unwrap_err(),
        refused("Quad9", 2, 3)
    );
    assert_eq!(
        ElementKind::Hex20.element::<2>().unwrap_err(),
        refused("Hex20", 3, 2)
    );
    assert_eq!(
        ElementKind::Tri6.element::<3>().unwrap_err(),
        refused("Tri6", 2, 3)
    );

    // (c) every kind keeps its node count, Gmsh type and VTK cell type, and a mesh of each
    // goes to Gmsh and back (the same kind) and to VTK (the same cell type)
    let table: [(ElementKind, usize, u32, u8); 9] = [
        (ElementKind::Tri3, 3, 2, 5),
        (ElementKind::Tri6, 6, 9, 22),
        (ElementKind::Quad4, 4, 3, 9),
        (ElementKind::Quad8, 8, 16, 23),
        (ElementKind::Quad9, 9, 10, 28),
        (ElementKind::Tet4, 4, 4, 10),
        (ElementKind::Tet10, 10, 11, 24),
        (ElementKind::Hex8, 8, 5, 12),
        (ElementKind::Hex20, 20, 17, 25),
    ];
    assert_eq!(table.map(|row| row.0), ElementKind::ALL);
    for (kind, nodes, gmsh, vtk) in table {
        let topology = kind.topology();
        assert_eq!(
            (kind.node_count(), topology.gmsh_type, topology.vtk_cell),
            (nodes, gmsh, vtk),
            "{kind:?}"
        );
        if kind.dimension() == 2 {
            assert_eq!(kind.element::<2>().unwrap().node_count(), nodes);
            let spec = RectangleSpec {
                kind,
                ..RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 2, 1)
            };
            round_trip(&rectangle(&spec).unwrap(), gmsh, vtk);
        } else {
            assert_eq!(kind.element::<3>().unwrap().node_count(), nodes);
            round_trip(
                &box_mesh(&l, &l, &lines(0.0, 2.0, 2), kind).unwrap(),
                gmsh,
                vtk,
            );
        }
    }
}
