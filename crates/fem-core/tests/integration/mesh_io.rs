//! Mesh input and output: Gmsh `.msh` 4.1 reading, VTK `.vtu` / `.pvd` writing, and the
//! structured generators feeding both.
//!
//! Source of the fixtures: Gmsh 4.15.2 (Python API), the unit square `[0, 1]²` meshed as two
//! triangles with the transfinite algorithm, saved with `Mesh.MshFileVersion = 4.1`:
//!
//! ```text
//!  4 ── curve 3 ── 3        physical groups: surface 5 "body",
//!  │             ╱ │        curve 1 "bottom" (1 → 2), curve 3 (unnamed, 3 → 4),
//!  │          ╱    │        point 7 "origin" (node 1)
//!  │       ╱       │
//!  │    ╱          │        triangles (1, 2, 4) and (4, 2, 3); P2 adds mid-side nodes 5–8
//!  1 ── bottom ─── 2        and the centre node 9
//! ```
//!
//! `CW_P1`/`CW_P2` are the same square with the surface's curve loop reversed, so Gmsh writes
//! clockwise triangles. The remaining fixtures are written by hand.

use approx::assert_relative_eq;
use fem_core::generate::{PileSpec, RectangleSpec, pile_in_soil, rectangle};
use fem_core::gmsh::{parse_msh, read_msh};
use fem_core::vtk::{Field, write_pvd, write_vtu};
use fem_core::{ElementKind, FemError, Mesh, Side};
use std::path::PathBuf;
use vtkio::model::{Attribute, CellType, DataSet, IOBuffer, VertexNumbers, Vtk};

const P1_SQUARE: &str = r#"$MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
3
0 7 "origin"
1 1 "bottom"
2 5 "body"
$EndPhysicalNames
$Entities
4 4 1 0
1 0 0 0 1 7 
2 1 0 0 0 
3 1 1 0 0 
4 0 1 0 0 
1 0 0 0 1 0 0 1 1 2 1 -2 
2 1 0 0 1 1 0 0 2 2 -3 
3 0 1 0 1 1 0 1 3 2 3 -4 
4 0 0 0 0 1 0 0 2 4 -1 
1 0 0 0 1 1 0 1 5 4 1 2 3 4 
$EndEntities
$Nodes
7 4 1 4
0 1 0 1
1
0 0 0
0 2 0 1
2
1 0 0
0 3 0 1
3
1 1 0
0 4 0 1
4
0 1 0
1 1 0 0
1 3 0 0
2 1 0 0
$EndNodes
$Elements
4 5 1 5
0 1 15 1
1 1 
1 1 1 1
2 1 2 
1 3 1 1
3 3 4 
2 1 2 2
4 1 2 4 
5 4 2 3 
$EndElements
"#;

const P2_SQUARE: &str = r#"$MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
3
0 7 "origin"
1 1 "bottom"
2 5 "body"
$EndPhysicalNames
$Entities
4 4 1 0
1 0 0 0 1 7 
2 1 0 0 0 
3 1 1 0 0 
4 0 1 0 0 
1 0 0 0 1 0 0 1 1 2 1 -2 
2 1 0 0 1 1 0 0 2 2 -3 
3 0 1 0 1 1 0 1 3 2 3 -4 
4 0 0 0 0 1 0 0 2 4 -1 
1 0 0 0 1 1 0 1 5 4 1 2 3 4 
$EndEntities
$Nodes
9 9 1 9
0 1 0 1
1
0 0 0
0 2 0 1
2
1 0 0
0 3 0 1
3
1 1 0
0 4 0 1
4
0 1 0
1 1 0 1
5
0.4999999999986718 0 0
1 2 0 1
6
1 0.4999999999986718 0
1 3 0 1
7
0.5000000000013304 1 0
1 4 0 1
8
0 0.5000000000013304 0
2 1 0 1
9
0.5 0.5 0
$EndNodes
$Elements
4 5 1 5
0 1 15 1
1 1 
1 1 8 1
2 1 2 5 
1 3 8 1
3 3 4 7 
2 1 9 2
4 1 2 4 5 9 8 
5 4 2 3 9 6 7 
$EndElements
"#;

const CW_P1: &str = r#"$MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
3
0 7 "origin"
1 1 "bottom"
2 5 "body"
$EndPhysicalNames
$Entities
4 4 1 0
1 0 0 0 1 7 
2 1 0 0 0 
3 1 1 0 0 
4 0 1 0 0 
1 0 0 0 1 0 0 1 1 2 1 -2 
2 1 0 0 1 1 0 0 2 2 -3 
3 0 1 0 1 1 0 1 3 2 3 -4 
4 0 0 0 0 1 0 0 2 4 -1 
1 0 0 0 1 1 0 1 5 4 -4 -3 -2 -1 
$EndEntities
$Nodes
7 4 1 4
0 1 0 1
1
0 0 0
0 2 0 1
2
1 0 0
0 3 0 1
3
1 1 0
0 4 0 1
4
0 1 0
1 1 0 0
1 3 0 0
2 1 0 0
$EndNodes
$Elements
4 5 1 5
0 1 15 1
1 1 
1 1 1 1
2 1 2 
1 3 1 1
3 3 4 
2 1 2 2
4 4 3 1 
5 3 2 1 
$EndElements
"#;

const CW_P2: &str = r#"$MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
3
0 7 "origin"
1 1 "bottom"
2 5 "body"
$EndPhysicalNames
$Entities
4 4 1 0
1 0 0 0 1 7 
2 1 0 0 0 
3 1 1 0 0 
4 0 1 0 0 
1 0 0 0 1 0 0 1 1 2 1 -2 
2 1 0 0 1 1 0 0 2 2 -3 
3 0 1 0 1 1 0 1 3 2 3 -4 
4 0 0 0 0 1 0 0 2 4 -1 
1 0 0 0 1 1 0 1 5 4 -4 -3 -2 -1 
$EndEntities
$Nodes
9 9 1 9
0 1 0 1
1
0 0 0
0 2 0 1
2
1 0 0
0 3 0 1
3
1 1 0
0 4 0 1
4
0 1 0
1 1 0 1
5
0.4999999999986718 0 0
1 2 0 1
6
1 0.4999999999986718 0
1 3 0 1
7
0.5000000000013304 1 0
1 4 0 1
8
0 0.5000000000013304 0
2 1 0 1
9
0.5 0.5 0
$EndNodes
$Elements
4 5 1 5
0 1 15 1
1 1 
1 1 8 1
2 1 2 5 
1 3 8 1
3 3 4 7 
2 1 9 2
4 4 3 1 7 9 8 
5 3 2 1 6 5 9 
$EndElements
"#;

/// `P1_SQUARE` saved as binary MSH 4.1 (`Mesh.Binary = 1`), hex-encoded.
const P1_SQUARE_BINARY_HEX: &[&str] = &[
    "244d657368466f726d61740a342e31203120380a010000000a24456e644d657368466f726d61740a2450687973696361",
    "6c4e616d65730a330a30203720226f726967696e220a3120312022626f74746f6d220a3220352022626f6479220a2445",
    "6e64506879736963616c4e616d65730a24456e7469746965730a04000000000000000400000000000000010000000000",
    "000000000000000000000100000000000000000000000000000000000000000000000000000001000000000000000700",
    "000002000000000000000000f03f00000000000000000000000000000000000000000000000003000000000000000000",
    "f03f000000000000f03f00000000000000000000000000000000040000000000000000000000000000000000f03f0000",
    "000000000000000000000000000001000000000000000000000000000000000000000000000000000000000000000000",
    "f03f00000000000000000000000000000000010000000000000001000000020000000000000001000000feffffff0200",
    "0000000000000000f03f00000000000000000000000000000000000000000000f03f000000000000f03f000000000000",
    "00000000000000000000020000000000000002000000fdffffff030000000000000000000000000000000000f03f0000",
    "000000000000000000000000f03f000000000000f03f0000000000000000010000000000000003000000020000000000",
    "000003000000fcffffff0400000000000000000000000000000000000000000000000000000000000000000000000000",
    "00000000f03f00000000000000000000000000000000020000000000000004000000ffffffff01000000000000000000",
    "000000000000000000000000000000000000000000000000f03f000000000000f03f0000000000000000010000000000",
    "0000050000000400000000000000010000000200000003000000040000000a24456e64456e7469746965730a244e6f64",
    "65730a070000000000000004000000000000000100000000000000040000000000000000000000010000000000000001",
    "000000000000000100000000000000000000000000000000000000000000000000000000000000000000000200000000",
    "00000001000000000000000200000000000000000000000000f03f000000000000000000000000000000000000000003",
    "0000000000000001000000000000000300000000000000000000000000f03f000000000000f03f000000000000000000",
    "0000000400000000000000010000000000000004000000000000000000000000000000000000000000f03f0000000000",
    "000000010000000100000000000000000000000000000001000000030000000000000000000000000000000200000001",
    "0000000000000000000000000000000a24456e644e6f6465730a24456c656d656e74730a040000000000000005000000",
    "000000000100000000000000050000000000000000000000010000000f00000001000000000000000100000000000000",
    "010000000000000001000000010000000100000001000000000000000200000000000000010000000000000002000000",
    "000000000100000003000000010000000100000000000000030000000000000003000000000000000400000000000000",
    "020000000100000002000000020000000000000004000000000000000100000000000000020000000000000004000000",
    "0000000005000000000000000400000000000000020000000000000003000000000000000a24456e64456c656d656e74",
    "730a",
];

/// Sparse, unordered node tags (10, 20, 30, 40 and an unused 99), sparse element tags, no
/// `$PhysicalNames`: surface 1 in physical group 2, curve 1 (bottom) in physical group 4.
const SPARSE_TAGS: &str = "$MeshFormat
4.1 0 8
$EndMeshFormat
$Entities
0 1 1 0
1 0 0 0 1 0 0 1 4 0
1 0 0 0 1 1 0 1 2 0
$EndEntities
$Nodes
1 5 10 99
2 1 0 5
40
30
20
10
99
0 1 0
1 1 0
1 0 0
0 0 0
5 5 0
$EndNodes
$Elements
2 3 5 100
1 1 1 1
5 10 20
2 1 2 2
7 10 20 30
100 10 30 40
$EndElements
";

fn binary_square() -> Vec<u8> {
    let hex: String = P1_SQUARE_BINARY_HEX.concat();
    (0..hex.len())
        .step_by(2)
        .map(|i| u8::from_str_radix(&hex[i..i + 2], 16).unwrap())
        .collect()
}

fn tmp(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name)
}

fn side_nodes(mesh: &Mesh, side: Side) -> Vec<usize> {
    mesh.side_nodes(side).collect()
}

fn assert_unsupported(result: Result<Mesh, FemError>, needle: &str) {
    match result {
        Err(FemError::Unsupported { what }) => {
            assert!(what.contains(needle), "`{what}` should mention `{needle}`")
        }
        other => panic!("expected Unsupported mentioning `{needle}`, got {other:?}"),
    }
}

/// Checks the P1 unit square read from any of the fixtures.
fn assert_p1_square(mesh: &Mesh) {
    assert_eq!(mesh.kind(), ElementKind::Tri3);
    assert_eq!(mesh.node_count(), 4);
    assert_eq!(
        mesh.nodes(),
        &[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
    );
    assert_eq!(mesh.element_count(), 2);
    assert_eq!(mesh.regions(), &[5, 5]);
    let names: Vec<&str> = mesh.edge_set_names().collect();
    assert_eq!(names, ["bottom", "curve_3"]);
    let names: Vec<&str> = mesh.node_set_names().collect();
    assert_eq!(names, ["bottom", "curve_3", "origin"]);
    let bottom = mesh.edge_set("bottom").unwrap();
    assert_eq!(bottom.len(), 1);
    assert_eq!(side_nodes(mesh, bottom[0]), [0, 1]);
    let top = mesh.edge_set("curve_3").unwrap();
    assert_eq!(top.len(), 1);
    assert_eq!(side_nodes(mesh, top[0]), [2, 3]);
    // along the curve, the body on the right (issue 36): against the sides' direction
    assert_eq!(mesh.node_set("bottom").unwrap(), &[1, 0]);
    assert_eq!(mesh.node_set("curve_3").unwrap(), &[3, 2]);
    assert_eq!(mesh.node_set("origin").unwrap(), &[0]);
}

#[test]
fn parse_msh_p1_square_works() {
    let mesh = parse_msh(P1_SQUARE.as_bytes()).unwrap();
    assert_p1_square(&mesh);
    assert_eq!(mesh.connectivity(), &[0, 1, 3, 3, 1, 2]);
}

#[test]
fn parse_msh_binary_works() {
    let mesh = parse_msh(&binary_square()).unwrap();
    assert_p1_square(&mesh);
    assert_eq!(mesh, parse_msh(P1_SQUARE.as_bytes()).unwrap());
}

#[test]
fn parse_msh_p2_square_works() {
    let mesh = parse_msh(P2_SQUARE.as_bytes()).unwrap();
    assert_eq!(mesh.kind(), ElementKind::Tri6);
    assert_eq!(mesh.node_count(), 9);
    assert_eq!(mesh.element_count(), 2);
    assert_eq!(mesh.regions(), &[5, 5]);
    // Gmsh's node order is ours: corners, then mid-sides 0-1, 1-2, 2-0.
    assert_eq!(mesh.element(0), &[0, 1, 3, 4, 8, 7]);
    for e in 0..mesh.element_count() {
        let c = mesh.element(e);
        for [a, b, m] in [[0, 1, 3], [1, 2, 4], [2, 0, 5]] {
            let [pa, pb, pm] = [c[a], c[b], c[m]].map(|n| mesh.nodes()[n]);
            for k in 0..2 {
                // Gmsh places the mid-side nodes by parametric interpolation (1e-12 off).
                assert_relative_eq!(pm[k], 0.5 * (pa[k] + pb[k]), epsilon = 1e-11);
            }
        }
    }
    let bottom = mesh.edge_set("bottom").unwrap();
    assert_eq!(side_nodes(&mesh, bottom[0]), [0, 1, 4]);
    // along the curve, mid-side node between the corners, the body on the right (issue 36)
    assert_eq!(mesh.node_set("bottom").unwrap(), &[1, 4, 0]);
    assert_eq!(mesh.node_set("curve_3").unwrap(), &[3, 6, 2]);
    assert_eq!(mesh.node_set("origin").unwrap(), &[0]);
}

#[test]
fn parse_msh_reorients_clockwise_triangles_works() {
    let mesh = parse_msh(CW_P1.as_bytes()).unwrap();
    assert_p1_square(&mesh);
    // Gmsh wrote (4, 3, 1) and (3, 2, 1): corners 1 and 2 are swapped.
    assert_eq!(mesh.connectivity(), &[3, 0, 2, 2, 0, 1]);

    let p2 = parse_msh(CW_P2.as_bytes()).unwrap();
    // Gmsh wrote (4, 3, 1 | 7, 9, 8): now (4, 1, 3 | 8, 9, 7), mid-sides following.
    assert_eq!(p2.element(0), &[3, 0, 2, 7, 8, 6]);
    assert_eq!(p2.element(1), &[2, 0, 1, 8, 4, 5]);
    for e in 0..p2.element_count() {
        let c = p2.element(e);
        for [a, b, m] in [[0, 1, 3], [1, 2, 4], [2, 0, 5]] {
            let [pa, pb, pm] = [c[a], c[b], c[m]].map(|n| p2.nodes()[n]);
            // As above: Gmsh's mid-side nodes are 1e-12 off the midpoints.
            assert_relative_eq!(pm[0], 0.5 * (pa[0] + pb[0]), epsilon = 1e-11);
            assert_relative_eq!(pm[1], 0.5 * (pa[1] + pb[1]), epsilon = 1e-11);
        }
    }
    assert_eq!(
        side_nodes(&p2, p2.edge_set("bottom").unwrap()[0]),
        [0, 1, 4]
    );
}

#[test]
fn parse_msh_sparse_tags_works() {
    let mesh = parse_msh(SPARSE_TAGS.as_bytes()).unwrap();
    // Unused node 99 is dropped; the others are numbered in tag order.
    assert_eq!(
        mesh.nodes(),
        &[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
    );
    assert_eq!(mesh.connectivity(), &[0, 1, 2, 0, 2, 3]);
    assert_eq!(mesh.regions(), &[2, 2]);
    assert_eq!(
        mesh.edge_set("curve_4").unwrap(),
        &[Side {
            element: 0,
            side: 0
        }]
    );
    assert_eq!(mesh.node_set("curve_4").unwrap(), &[1, 0]); // along the curve (issue 36)
}

#[test]
fn read_msh_works() {
    let path = tmp("mesh_io_square.msh");
    std::fs::write(&path, P2_SQUARE).unwrap();
    let mesh = read_msh(&path).unwrap();
    assert_eq!(mesh, parse_msh(P2_SQUARE.as_bytes()).unwrap());
}

#[test]
fn read_msh_rejects_missing_file() {
    let path = tmp("mesh_io_does_not_exist.msh");
    let e = read_msh(&path).unwrap_err();
    let FemError::Io {
        path: p, source, ..
    } = &e
    else {
        panic!("expected Io, got {e:?}");
    };
    assert!(p.ends_with("mesh_io_does_not_exist.msh"));
    // The I/O error is kept as the source, and printed by the chain, not by the message.
    let io = source
        .as_ref()
        .and_then(|c| c.get_ref().downcast_ref::<std::io::Error>())
        .expect("an std::io::Error source");
    assert_eq!(io.kind(), std::io::ErrorKind::NotFound);
    let os = io.to_string();
    assert!(!e.to_string().contains(&os), "{e}");
    let mut chain = e.to_string();
    let mut next = std::error::Error::source(&e);
    while let Some(s) = next {
        chain = format!("{chain}: {s}");
        next = s.source();
    }
    assert_eq!(chain.matches(&os).count(), 1, "{chain}");
    assert_eq!(e.clone(), e);
}

#[test]
fn parse_msh_rejects_other_element_types() {
    // A 4-node quadrangle (type 3) is read since issue 35 (it was rejected before).
    let quad = SPARSE_TAGS.replace("2 3 5 100", "2 2 5 100").replace(
        "2 1 2 2\n7 10 20 30\n100 10 30 40",
        "2 1 3 1\n7 10 20 30 40",
    );
    let mesh = parse_msh(quad.as_bytes()).unwrap();
    assert_eq!(mesh.kind(), fem_core::ElementKind::Quad4);
    assert_eq!(mesh.element(0), &[0, 1, 2, 3]);
    let tet = SPARSE_TAGS.replace("2 3 5 100", "2 2 5 100").replace(
        "2 1 2 2\n7 10 20 30\n100 10 30 40",
        "3 1 4 1\n7 10 20 30 40",
    );
    assert_unsupported(parse_msh(tet.as_bytes()), "type 4 (MSH_TET_4)");
    let unknown = SPARSE_TAGS.replace("2 1 2 2\n", "2 1 200 2\n");
    assert_unsupported(parse_msh(unknown.as_bytes()), "type 200");
}

#[test]
fn parse_msh_rejects_mixed_triangles() {
    let mixed = P2_SQUARE
        .replace("$Elements\n4 5 1 5\n", "$Elements\n5 5 1 5\n")
        .replace(
            "2 1 9 2\n4 1 2 4 5 9 8 \n5 4 2 3 9 6 7 \n",
            "2 1 9 1\n4 1 2 4 5 9 8 \n2 1 2 1\n5 4 2 3 \n",
        );
    assert_unsupported(parse_msh(mixed.as_bytes()), "mixed");
}

#[test]
fn parse_msh_rejects_lines_off_the_triangle_sides() {
    // The bottom line now runs along the diagonal 1-3, which no triangle has.
    let diagonal = P1_SQUARE.replace("1 1 1 1\n2 1 2 \n", "1 1 1 1\n2 1 3 \n");
    assert_unsupported(parse_msh(diagonal.as_bytes()), "not a triangle side");
}

#[test]
fn parse_msh_rejects_other_versions_and_empty_meshes() {
    let v22 = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
    assert_unsupported(parse_msh(v22.as_bytes()), "version 2.2");
    let lines_only = SPARSE_TAGS
        .replace("2 3 5 100", "1 1 5 5")
        .replace("2 1 2 2\n7 10 20 30\n100 10 30 40\n", "");
    assert_unsupported(parse_msh(lines_only.as_bytes()), "no triangles");
}

#[test]
fn parse_msh_rejects_garbage() {
    let truncated = &P1_SQUARE[..P1_SQUARE.len() / 2];
    let binary = binary_square();
    let cases: Vec<&[u8]> = vec![
        b"",
        b"\x00\xff\xfe garbage \x01",
        b"$MeshFormat\n",
        b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n",
        b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 1 1 1\n$EndNodes\n",
        // Empty blocks trip an unchecked subtraction inside the parser.
        b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n0 0 1 1\n$EndNodes\n",
        b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Elements\n0 0 1 1\n$EndElements\n",
        b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n1 1 \"a\"\n",
        truncated.as_bytes(),
        &binary[..binary.len() - 40],
        &binary[..200],
    ];
    for (i, bytes) in cases.into_iter().enumerate() {
        match parse_msh(bytes) {
            Err(FemError::Io { detail, .. }) => assert!(!detail.is_empty()),
            Err(FemError::Unsupported { .. }) => {}
            other => panic!("case {i}: expected an error, got {other:?}"),
        }
    }
    // A node that no element uses is dropped, but a triangle on an undefined node is an error.
    let undefined = SPARSE_TAGS.replace("100 10 30 40", "100 10 30 41");
    assert!(matches!(
        parse_msh(undefined.as_bytes()),
        Err(FemError::Io { detail, source: None, .. }) if detail.contains("41")
    ));
}

fn read_vtu(path: &std::path::Path) -> vtkio::model::UnstructuredGridPiece {
    let vtk = Vtk::import(path).unwrap();
    match vtk.data {
        DataSet::UnstructuredGrid { mut pieces, .. } => {
            assert_eq!(pieces.len(), 1);
            pieces.remove(0).into_loaded_piece_data(None).unwrap()
        }
        other => panic!("expected an unstructured grid, got {other:?}"),
    }
}

fn array<'a>(attributes: &'a [Attribute], name: &str) -> &'a IOBuffer {
    attributes
        .iter()
        .find_map(|a| match a {
            Attribute::DataArray(d) if d.name == name => Some(&d.data),
            _ => None,
        })
        .unwrap_or_else(|| panic!("no array `{name}`"))
}

fn as_f64(buffer: &IOBuffer) -> Vec<f64> {
    buffer.clone().cast_into::<f64>().unwrap()
}

#[test]
fn write_vtu_p2_works() {
    let spec = RectangleSpec {
        kind: ElementKind::Tri6,
        ..RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 2, 1)
    };
    let mesh = rectangle(&spec).unwrap();
    let (n, m) = (mesh.node_count(), mesh.element_count());
    let temperature: Vec<f64> = mesh.nodes().iter().map(|p| p[0] + 10.0 * p[1]).collect();
    let u: Vec<[f64; 2]> = mesh.nodes().iter().map(|p| [p[1], -p[0]]).collect();
    let sigma: Vec<[f64; 4]> = (0..m).map(|e| [1.0, 2.0, 3.0, e as f64]).collect();
    let path = tmp("mesh_io_p2.vtu");
    write_vtu(
        &path,
        &mesh,
        &[("T", Field::Scalar(&temperature)), ("u", Field::Vector(&u))],
        &[("sigma", Field::SymTensor(&sigma))],
    )
    .unwrap();

    let piece = read_vtu(&path);
    assert_eq!(piece.num_points(), n);
    let points = as_f64(&piece.points);
    for (k, p) in mesh.nodes().iter().enumerate() {
        assert_eq!(&points[3 * k..3 * k + 3], &[p[0], p[1], 0.0]);
    }
    assert_eq!(piece.cells.types, vec![CellType::QuadraticTriangle; m]);
    match &piece.cells.cell_verts {
        VertexNumbers::XML {
            connectivity,
            offsets,
        } => {
            let conn: Vec<usize> = connectivity.iter().map(|&c| c as usize).collect();
            assert_eq!(conn, mesh.connectivity());
            assert_eq!(offsets.len(), m);
            assert_eq!(offsets[m - 1] as usize, 6 * m);
        }
        other => panic!("expected XML cells, got {other:?}"),
    }
    assert_eq!(as_f64(array(&piece.data.point, "T")), temperature);
    let u_read = as_f64(array(&piece.data.point, "u"));
    assert_eq!(u_read.len(), 3 * n);
    assert_eq!(&u_read[3..6], &[u[1][0], u[1][1], 0.0]);
    let s = as_f64(array(&piece.data.cell, "sigma"));
    assert_eq!(s.len(), 9 * m);
    // (xx, yy, xy, zz) = (1, 2, 3, 1) as a full 3x3 tensor, row-major.
    assert_eq!(&s[9..18], &[1.0, 3.0, 0.0, 3.0, 2.0, 0.0, 0.0, 0.0, 1.0]);
    let region = array(&piece.data.cell, "region").clone();
    assert_eq!(region.cast_into::<u32>().unwrap(), vec![0; m]);
}

#[test]
fn write_vtu_p1_pile_works() {
    let spec = PileSpec {
        kind: ElementKind::Tri3,
        cells_shaft: 4,
        cells_below_tip: 3,
        cells_soil_r: 4,
        cells_pile_r: 1,
        ..PileSpec::default()
    };
    let mesh = pile_in_soil(&spec).unwrap();
    let path = tmp("mesh_io_pile.vtu");
    write_vtu(&path, &mesh, &[], &[]).unwrap();
    let piece = read_vtu(&path);
    assert_eq!(piece.num_points(), mesh.node_count());
    assert_eq!(
        piece.cells.types,
        vec![CellType::Triangle; mesh.element_count()]
    );
    let region = array(&piece.data.cell, "region").clone();
    assert_eq!(region.cast_into::<u32>().unwrap(), mesh.regions());
}

#[test]
fn write_vtu_rejects_length_mismatch() {
    let mesh = parse_msh(P1_SQUARE.as_bytes()).unwrap();
    let path = tmp("mesh_io_mismatch.vtu");
    let _ = std::fs::remove_file(&path);
    let short = [[0.0; 2]; 3];
    assert!(matches!(
        write_vtu(&path, &mesh, &[("u", Field::Vector(&short))], &[]),
        Err(FemError::LengthMismatch {
            expected: 4,
            got: 3,
            ..
        })
    ));
    let long = [[0.0; 4]; 3];
    assert!(matches!(
        write_vtu(&path, &mesh, &[], &[("s", Field::SymTensor(&long))]),
        Err(FemError::LengthMismatch {
            expected: 2,
            got: 3,
            ..
        })
    ));
    assert!(!path.exists(), "nothing is written on error");
    let dir = tmp("mesh_io_no_such_dir").join("x.vtu");
    assert!(matches!(
        write_vtu(&dir, &mesh, &[], &[]),
        Err(FemError::Io { .. })
    ));
}

#[test]
fn write_pvd_works() {
    let path = tmp("mesh_io_series.pvd");
    write_pvd(&path, &[(0.0, "step_0.vtu"), (0.25, "a&b/step_1.vtu")]).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains("type=\"Collection\""));
    assert_eq!(text.matches("<DataSet ").count(), 2);
    assert!(text.contains("timestep=\"0.25\""));
    assert!(text.contains("file=\"a&amp;b/step_1.vtu\""));
    assert!(matches!(
        write_pvd(&path, &[(f64::NAN, "x.vtu")]),
        Err(FemError::InvalidParameter { name: "time", .. })
    ));
}

/// Node tags that contradict the `$Nodes` header: `mshio` trusts a header that announces
/// contiguous tags and renumbers the nodes in file order, so a repeated tag, a tag outside
/// the announced range or tags out of order would silently move nodes. Each is refused.
#[test]
fn node_tags_that_contradict_the_header_are_refused() {
    let file = |tags: &str| {
        format!(
            "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 4 1 4\n2 1 0 4\n{tags}\n\
             0 0 0\n1 0 0\n1 1 0\n0 1 0\n$EndNodes\n$Elements\n1 2 1 2\n2 1 2 2\n1 1 2 3\n\
             2 1 3 4\n$EndElements\n"
        )
    };
    assert!(parse_msh(file("1\n2\n3\n4").as_bytes()).is_ok());
    for (tags, expected) in [
        ("1\n2\n2\n4", "node tag 2 is defined twice"),
        ("1\n2\n3\n5", "node tag 5 is outside the range 1…4"),
        ("1\n2\n4\n3", "node tag 4 where 3 was expected"),
    ] {
        let e = parse_msh(file(tags).as_bytes()).unwrap_err().to_string();
        assert!(e.contains(expected), "{tags:?}: {e}");
    }
}
