//! Reading quadrangles and hexahedra from Gmsh and writing them to VTK (issue 35).
//!
//! Sources: the Gmsh reference manual, "Node ordering" (MSH_QUA_4/8/9 = types 3, 16, 10;
//! MSH_HEX_8/20 = 5, 17: the 20-node hexahedron numbers its mid-edge nodes by edge 0–1, 0–3,
//! 0–4, 1–2, 1–5, 2–3, 2–6, 3–7, 4–5, 4–7, 5–6, 6–7) and the VTK file-format manual (cell types
//! 9, 23, 28, 12, 25; VTK_QUADRATIC_HEXAHEDRON's mid-edge nodes by edge 0–1, 1–2, 2–3, 3–0,
//! 4–5, 5–6, 6–7, 7–4, 0–4, 1–5, 2–6, 3–7). A 20-node hexahedron written in Gmsh's order with
//! every mid-edge node at the middle of its edge must come out with each of our mid-edge nodes
//! at the middle of the edge our numbering gives it; a left-handed one is mirrored.

use fem_core::element::hex20::EDGES;
use fem_core::gmsh::parse_msh;
use fem_core::solid::SolidKind;
use fem_core::solid::gmsh::parse_msh_3d;
use fem_core::vtk::write_vtu_3d;
use fem_core::{ElementKind, vtk::write_vtu};

const CORNERS: [[f64; 3]; 8] = [
    [0.0, 0.0, 0.0],
    [2.0, 0.0, 0.0],
    [2.0, 1.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 3.0],
    [2.0, 0.0, 3.0],
    [2.0, 1.0, 3.0],
    [0.0, 1.0, 3.0],
];

/// Gmsh's mid-edge order of the 20-node hexahedron.
const GMSH_EDGES: [[usize; 2]; 12] = [
    [0, 1],
    [0, 3],
    [0, 4],
    [1, 2],
    [1, 5],
    [2, 3],
    [2, 6],
    [3, 7],
    [4, 5],
    [4, 7],
    [5, 6],
    [6, 7],
];

/// One 20-node hexahedron in Gmsh's node order (corners permuted by `perm` first), MSH 4.1.
fn hex20_msh(perm: [usize; 8]) -> String {
    let corners: Vec<[f64; 3]> = perm.iter().map(|&k| CORNERS[k]).collect();
    let mut nodes = corners.clone();
    for [a, b] in GMSH_EDGES {
        nodes.push(core::array::from_fn(|d| {
            0.5 * (corners[a][d] + corners[b][d])
        }));
    }
    let mut s = String::from("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 20 1 20\n3 1 0 20\n");
    for k in 1..=20 {
        s += &format!("{k}\n");
    }
    for p in &nodes {
        s += &format!("{} {} {}\n", p[0], p[1], p[2]);
    }
    s += "$EndNodes\n$Elements\n1 1 1 1\n3 1 17 1\n1";
    for k in 1..=20 {
        s += &format!(" {k}");
    }
    s + "\n$EndElements\n"
}

#[test]
fn issue_35_gmsh_hex20_node_order_works() {
    // right-handed as written, and mirrored (top and bottom swapped: left-handed)
    for perm in [[0, 1, 2, 3, 4, 5, 6, 7], [4, 5, 6, 7, 0, 1, 2, 3]] {
        let mesh = parse_msh_3d(hex20_msh(perm).as_bytes()).unwrap();
        assert_eq!(mesh.kind(), SolidKind::Hex20);
        let cell = mesh.element(0);
        let x = mesh.nodes();
        for (k, [a, b]) in EDGES.iter().enumerate() {
            let mid: [f64; 3] = core::array::from_fn(|d| 0.5 * (x[cell[*a]][d] + x[cell[*b]][d]));
            // exact: halves of small integers
            assert_eq!(
                x[cell[8 + k]],
                mid,
                "{perm:?}: node {} is not on edge {a}–{b}",
                8 + k
            );
        }
    }
}

#[test]
fn issue_35_quadrangles_and_hexahedra_to_vtk_works() {
    let dir = std::env::temp_dir().join(format!("fem_core_issue_35_vtk_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let hex = parse_msh_3d(hex20_msh([0, 1, 2, 3, 4, 5, 6, 7]).as_bytes()).unwrap();
    let path = dir.join("hex20.vtu");
    write_vtu_3d(&path, &hex, &[], &[]).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(
        text.contains(r#"RangeMin="25" RangeMax="25""#),
        "VTK_QUADRATIC_HEXAHEDRON"
    );
    // a 9-node quadrangle (type 10), written back as VTK_BIQUADRATIC_QUAD
    let quad =
        "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 9 1 9\n2 1 0 9\n1\n2\n3\n4\n5\n6\n7\n8\n9
0 0 0\n2 0 0\n2 1 0\n0 1 0\n1 0 0\n2 0.5 0\n1 1 0\n0 0.5 0\n1 0.5 0\n$EndNodes
$Elements\n1 1 1 1\n2 1 10 1\n1 1 2 3 4 5 6 7 8 9\n$EndElements\n";
    let mesh = parse_msh(quad.as_bytes()).unwrap();
    assert_eq!(mesh.kind(), ElementKind::Quad9);
    let path = dir.join("quad9.vtu");
    write_vtu(&path, &mesh, &[], &[]).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(
        text.contains(r#"RangeMin="28" RangeMax="28""#),
        "VTK_BIQUADRATIC_QUAD"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Boundaries of quadrilateral and hexahedral meshes: the boundary sides and faces, the
/// outward normals, the edge sets' nodes, and the consistent nodal areas of quadrangle faces
/// (`∫ N_i dA`: a quarter of each face at a Hex8 face's corners; on Hex20 faces the corners'
/// `−A/12` are clipped to 0 as the P2 triangles' 0 are, the mid-edge nodes keep `A/3`).
#[test]
fn issue_35_boundaries_of_quadrilateral_and_hexahedral_meshes_works() {
    use fem_core::generate::{RectangleSpec, rectangle};
    use fem_core::solid::generate::{box_mesh, lines};
    for kind in [ElementKind::Quad4, ElementKind::Quad8, ElementKind::Quad9] {
        let spec = RectangleSpec {
            kind,
            ..RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 4, 2)
        };
        let mesh = rectangle(&spec).unwrap();
        assert_eq!(mesh.element_count(), 8);
        assert_eq!(mesh.boundary_facets().len(), 12, "{kind:?}");
        let per = if kind == ElementKind::Quad4 { 1 } else { 2 };
        assert_eq!(mesh.node_set("bottom").unwrap().len(), 4 * per + 1);
        let normals = mesh.outward_normals();
        let corner = mesh.node_set("top_right").unwrap()[0];
        let n = normals[corner].unwrap();
        // the bisector of +x and +y; round-off
        let h = std::f64::consts::FRAC_1_SQRT_2;
        assert!(
            (n[0] - h).abs() < 1e-15 && (n[1] - h).abs() < 1e-15,
            "{kind:?}: {n:?}"
        );
        let inside = (0..mesh.node_count())
            .filter(|&k| normals[k].is_none())
            .count();
        let interior = if per == 1 {
            3
        } else {
            7 * 3 - if kind == ElementKind::Quad8 { 8 } else { 0 }
        };
        assert_eq!(inside, interior, "{kind:?}: interior nodes");
    }
    for (kind, corner_area, mid_area) in [
        (SolidKind::Hex8, 0.25, None),
        (SolidKind::Hex20, 0.0, Some(1.0 / 3.0)),
    ] {
        let mesh = box_mesh(
            &lines(0.0, 2.0, 2),
            &lines(0.0, 1.0, 1),
            &lines(0.0, 1.0, 1),
            kind,
        )
        .unwrap();
        assert_eq!(mesh.boundary_facets().len(), 2 * (2 + 2 + 1), "{kind:?}");
        assert_eq!(mesh.face_set("z0").unwrap().len(), 2);
        let (nodes, areas) = mesh.nodal_areas("z0").unwrap();
        let total: f64 = areas.iter().sum();
        let x = mesh.nodes();
        // the face z = 0 is 2 × 1: two unit squares
        let at = |p: [f64; 3]| areas[nodes.iter().position(|&n| x[n] == p).unwrap()];
        // round-off of a 3×3 rule
        assert!(
            (at([0.0, 0.0, 0.0]) - corner_area).abs() < 1e-14,
            "{kind:?}"
        );
        if let Some(mid) = mid_area {
            assert!((at([0.5, 0.0, 0.0]) - mid).abs() < 1e-14, "{kind:?}");
            assert!((total - 2.0 * 4.0 / 3.0).abs() < 1e-13, "{kind:?}: {total}");
        } else {
            assert!((total - 2.0).abs() < 1e-13, "{kind:?}: {total}");
        }
    }
}
