//! 3D mesh input and output: Gmsh `.msh` 4.1 volume meshes read into a `SolidMesh`
//! (`solid::gmsh`), and `SolidMesh`es written as VTK `.vtu` (`vtk::write_vtu_3d`).
//!
//! Source of the fixtures: Gmsh 4.8.4 (Debian bookworm's `gmsh`), the unit cube `[0, 1]³`
//! with transfinite curves (2 nodes), surfaces and volume, so the cube is cut into six
//! tetrahedra, saved with `-format msh41` (`-order 2` for P2):
//!
//! ```text
//!        8 ──────── 7            physical groups: volume 7 "solid",
//!       ╱│         ╱│            surface 1 "bottom" (z = 0, triangles 1 2 4 and 4 2 3),
//!      5 ──────── 6 │            surface 2 (unnamed, z = 1, triangles 5 6 8 and 8 6 7),
//!      │ 4 ───────│─ 3           curve 3 "edge" (node 1 → node 5), point 4 (node 7)
//!      │╱         │╱             tetrahedra (1 2 4 5), (2 4 5 6), (5 6 4 8),
//!      1 ──────── 2              (2 4 6 3), (4 8 6 3), (6 8 7 3), all right-handed
//! ```
//!
//! P2 adds the mid-edge nodes 9–20 (edges of the cube), the face centres 21–24 (on the
//! diagonals of faces z = 0, z = 1, y = 0, x = 1) and the interior nodes 25–27. Gmsh's
//! 10-node tetrahedra put node 8 on edge 2–3 and node 9 on edge 1–3 (e.g. element 7:
//! `1 2 4 5 | 9 21 12 17 25 23`, node 25 = (0, 0.5, 0.5) on edge 4–5): the reader swaps them.
//! The other fixtures are these files edited by hand (each test says how). To regenerate:
//! `gmsh cube.geo -3 -format msh41 -o p1.msh` (and `-order 2 -o p2.msh`), with `cube.geo`:
//!
//! ```text
//! Point(1) = {0,0,0,1}; Point(2) = {1,0,0,1}; Point(3) = {1,1,0,1}; Point(4) = {0,1,0,1};
//! Point(5) = {0,0,1,1}; Point(6) = {1,0,1,1}; Point(7) = {1,1,1,1}; Point(8) = {0,1,1,1};
//! Line(1)={1,2}; Line(2)={2,3}; Line(3)={3,4}; Line(4)={4,1};
//! Line(5)={5,6}; Line(6)={6,7}; Line(7)={7,8}; Line(8)={8,5};
//! Line(9)={1,5}; Line(10)={2,6}; Line(11)={3,7}; Line(12)={4,8};
//! Curve Loop(1)={1,2,3,4}; Plane Surface(1)={1};    Curve Loop(2)={5,6,7,8}; Plane Surface(2)={2};
//! Curve Loop(3)={1,10,-5,-9}; Plane Surface(3)={3}; Curve Loop(4)={2,11,-6,-10}; Plane Surface(4)={4};
//! Curve Loop(5)={3,12,-7,-11}; Plane Surface(5)={5}; Curve Loop(6)={4,9,-8,-12}; Plane Surface(6)={6};
//! Transfinite Curve{:} = 2; Transfinite Surface{:};
//! Surface Loop(1)={1,2,3,4,5,6}; Volume(1)={1}; Transfinite Volume{1};
//! Physical Volume("solid", 7) = {1}; Physical Surface("bottom", 1) = {1};
//! Physical Surface(2) = {2}; Physical Curve("edge", 3) = {9}; Physical Point(4) = {7};
//! ```

use fem_core::FemError;
use fem_core::solid::generate::{box_mesh, lines};
use fem_core::solid::gmsh::{parse_msh_3d, read_msh_3d};
use fem_core::solid::{Face, SolidKind, SolidMesh, TET_EDGES};
use fem_core::vtk::{Field3, write_vtu_3d};
use std::path::PathBuf;
use vtkio::model::{Attribute, CellType, DataSet, IOBuffer, VertexNumbers, Vtk};

const P1_CUBE: &str = r#"$MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
3
1 3 "edge"
2 1 "bottom"
3 7 "solid"
$EndPhysicalNames
$Entities
8 12 6 1
1 0 0 0 0 
2 1 0 0 0 
3 1 1 0 0 
4 0 1 0 0 
5 0 0 1 0 
6 1 0 1 0 
7 1 1 1 1 4 
8 0 1 1 0 
1 0 0 0 1 0 0 0 2 1 -2 
2 1 0 0 1 1 0 0 2 2 -3 
3 0 1 0 1 1 0 0 2 3 -4 
4 0 0 0 0 1 0 0 2 4 -1 
5 0 0 1 1 0 1 0 2 5 -6 
6 1 0 1 1 1 1 0 2 6 -7 
7 0 1 1 1 1 1 0 2 7 -8 
8 0 0 1 0 1 1 0 2 8 -5 
9 0 0 0 0 0 1 1 3 2 1 -5 
10 1 0 0 1 0 1 0 2 2 -6 
11 1 1 0 1 1 1 0 2 3 -7 
12 0 1 0 0 1 1 0 2 4 -8 
1 0 0 0 1 1 0 1 1 4 1 2 3 4 
2 0 0 1 1 1 1 1 2 4 5 6 7 8 
3 0 0 0 1 0 1 0 4 1 10 -5 -9 
4 1 0 0 1 1 1 0 4 2 11 -6 -10 
5 0 1 0 1 1 1 0 4 3 12 -7 -11 
6 0 0 0 0 1 1 0 4 4 9 -8 -12 
1 0 0 0 1 1 1 1 7 6 1 2 3 4 5 6 
$EndEntities
$Nodes
12 8 1 8
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
0 5 0 1
5
0 0 1
0 6 0 1
6
1 0 1
0 7 0 1
7
1 1 1
0 8 0 1
8
0 1 1
1 9 0 0
2 1 0 0
2 2 0 0
3 1 0 0
$EndNodes
$Elements
5 12 1 12
0 7 15 1
1 7 
1 9 1 1
2 1 5 
2 1 2 2
3 1 2 4 
4 4 2 3 
2 2 2 2
5 5 6 8 
6 8 6 7 
3 1 4 6
7 1 2 4 5 
8 2 4 5 6 
9 5 6 4 8 
10 2 4 6 3 
11 4 8 6 3 
12 6 8 7 3 
$EndElements
"#;

const P2_CUBE: &str = r#"$MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
3
1 3 "edge"
2 1 "bottom"
3 7 "solid"
$EndPhysicalNames
$Entities
8 12 6 1
1 0 0 0 0 
2 1 0 0 0 
3 1 1 0 0 
4 0 1 0 0 
5 0 0 1 0 
6 1 0 1 0 
7 1 1 1 1 4 
8 0 1 1 0 
1 0 0 0 1 0 0 0 2 1 -2 
2 1 0 0 1 1 0 0 2 2 -3 
3 0 1 0 1 1 0 0 2 3 -4 
4 0 0 0 0 1 0 0 2 4 -1 
5 0 0 1 1 0 1 0 2 5 -6 
6 1 0 1 1 1 1 0 2 6 -7 
7 0 1 1 1 1 1 0 2 7 -8 
8 0 0 1 0 1 1 0 2 8 -5 
9 0 0 0 0 0 1 1 3 2 1 -5 
10 1 0 0 1 0 1 0 2 2 -6 
11 1 1 0 1 1 1 0 2 3 -7 
12 0 1 0 0 1 1 0 2 4 -8 
1 0 0 0 1 1 0 1 1 4 1 2 3 4 
2 0 0 1 1 1 1 1 2 4 5 6 7 8 
3 0 0 0 1 0 1 0 4 1 10 -5 -9 
4 1 0 0 1 1 1 0 4 2 11 -6 -10 
5 0 1 0 1 1 1 0 4 3 12 -7 -11 
6 0 0 0 0 1 1 0 4 4 9 -8 -12 
1 0 0 0 1 1 1 1 7 6 1 2 3 4 5 6 
$EndEntities
$Nodes
25 27 1 27
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
0 5 0 1
5
0 0 1
0 6 0 1
6
1 0 1
0 7 0 1
7
1 1 1
0 8 0 1
8
0 1 1
1 1 0 1
9
0.4999999999986718 0 0
1 2 0 1
10
1 0.4999999999986718 0
1 3 0 1
11
0.5000000000013305 1 0
1 4 0 1
12
0 0.5000000000013305 0
1 5 0 1
13
0.4999999999986718 0 1
1 6 0 1
14
1 0.4999999999986718 1
1 7 0 1
15
0.5000000000013305 1 1
1 8 0 1
16
0 0.5000000000013305 1
1 9 0 1
17
0 0 0.4999999999986718
1 10 0 1
18
1 0 0.4999999999986718
1 11 0 1
19
1 1 0.4999999999986718
1 12 0 1
20
0 1 0.4999999999986718
2 1 0 1
21
0.5 0.5 0
2 2 0 1
22
0.5 0.5 1
2 3 0 1
23
0.5 0 0.5
2 4 0 1
24
1 0.5 0.5
3 1 0 3
25
26
27
0 0.5 0.5
0.5 0.5 0.5
0.5 1 0.5
$EndNodes
$Elements
5 12 1 12
0 7 15 1
1 7 
1 9 8 1
2 1 5 17 
2 1 9 2
3 1 2 4 9 21 12 
4 4 2 3 21 10 11 
2 2 9 2
5 5 6 8 13 22 16 
6 8 6 7 22 14 15 
3 1 11 6
7 1 2 4 5 9 21 12 17 25 23 
8 2 4 5 6 21 25 23 18 13 26 
9 5 6 4 8 13 26 25 16 20 22 
10 2 4 6 3 21 26 18 10 24 11 
11 4 8 6 3 20 22 26 11 24 27 
12 6 8 7 3 22 15 14 24 19 27 
$EndElements
"#;

fn tmp(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name)
}

/// `text` with the first `old` replaced by `new` (which must be there).
fn edit(text: &str, old: &str, new: &str) -> String {
    assert!(text.contains(old), "the fixture has no `{old}`");
    text.replacen(old, new, 1)
}

fn assert_unsupported(result: Result<SolidMesh, FemError>, needle: &str) {
    match result {
        Err(FemError::Unsupported { what }) => {
            assert!(what.contains(needle), "`{what}` should mention `{needle}`")
        }
        other => panic!("expected Unsupported mentioning `{needle}`, got {other:?}"),
    }
}

fn assert_invalid(result: Result<SolidMesh, FemError>, needle: &str) {
    match result {
        Err(FemError::Io { detail, .. }) => {
            assert!(
                detail.contains(needle),
                "`{detail}` should mention `{needle}`"
            )
        }
        other => panic!("expected Io mentioning `{needle}`, got {other:?}"),
    }
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// The signed volume of element `e` (its corners).
fn volume(mesh: &SolidMesh, e: usize) -> f64 {
    let c: Vec<[f64; 3]> = mesh.element(e)[..4]
        .iter()
        .map(|&n| mesh.nodes()[n])
        .collect();
    let n = cross(sub(c[2], c[0]), sub(c[3], c[0]));
    let u = sub(c[1], c[0]);
    (u[0] * n[0] + u[1] * n[1] + u[2] * n[2]) / 6.0
}

/// `(b − a) × (c − a)` of a face's corners: outward, since they turn counter-clockwise seen
/// from outside.
fn face_normal(mesh: &SolidMesh, face: Face) -> [f64; 3] {
    let c: Vec<[f64; 3]> = mesh
        .face_node_ids(face)
        .take(3)
        .map(|n| mesh.nodes()[n])
        .collect();
    cross(sub(c[1], c[0]), sub(c[2], c[0]))
}

/// The nodes of `mesh` where `keep` holds, in order.
fn nodes_where(mesh: &SolidMesh, keep: impl Fn([f64; 3]) -> bool) -> Vec<usize> {
    (0..mesh.node_count())
        .filter(|&n| keep(mesh.nodes()[n]))
        .collect()
}

/// Checks what the P1 and P2 cubes share: six right-handed tetrahedra of region 7 filling the
/// unit cube, and the sets of the physical groups.
fn assert_cube(mesh: &SolidMesh) {
    assert_eq!(mesh.element_count(), 6);
    assert_eq!(mesh.regions(), &[7; 6]);
    // Gmsh's coordinates are exact for the corners: the sum is 1 up to rounding.
    let total: f64 = (0..6).map(|e| volume(mesh, e)).sum();
    assert!((total - 1.0).abs() < 1e-14, "volume {total}");
    assert!((0..6).all(|e| volume(mesh, e) > 0.0));
    // Sets: one face set per physical surface, one node set per group.
    let face_sets: Vec<&String> = mesh.facet_sets().keys().collect();
    assert_eq!(face_sets, ["bottom", "surface_2"]);
    let node_sets: Vec<&String> = mesh.node_sets().keys().collect();
    assert_eq!(node_sets, ["bottom", "edge", "point_4", "surface_2"]);
    for (name, z) in [("bottom", 0.0), ("surface_2", 1.0)] {
        let faces = mesh.face_set(name).unwrap();
        assert_eq!(faces.len(), 2, "{name}");
        for &f in faces {
            assert!(mesh.face_node_ids(f).all(|n| mesh.nodes()[n][2] == z));
            // outward: −z on the bottom, +z on the top (Gmsh's bottom triangles point inward)
            let normal = face_normal(mesh, f);
            assert_eq!(normal[2].signum(), 2.0 * z - 1.0, "{name}: {normal:?}");
        }
        assert_eq!(
            mesh.node_set(name).unwrap(),
            nodes_where(mesh, |p| p[2] == z)
        );
    }
    assert_eq!(
        mesh.node_set("edge").unwrap(),
        nodes_where(mesh, |p| p[0] == 0.0 && p[1] == 0.0)
    );
    assert_eq!(mesh.node_set("point_4").unwrap(), [6]);
    assert_eq!(mesh.nodes()[6], [1.0, 1.0, 1.0]);
}

#[test]
fn parse_msh_3d_p1_cube_works() {
    let mesh = parse_msh_3d(P1_CUBE.as_bytes()).unwrap();
    assert_eq!(mesh.kind(), SolidKind::Tet4);
    assert_eq!(mesh.node_count(), 8);
    // nodes in tag order (tags 1..8 become 0..7); element 7 is (1 2 4 5)
    assert_eq!(mesh.element(0), [0, 1, 3, 4]);
    assert_eq!(mesh.node_set("edge").unwrap(), [0, 4]);
    assert_cube(&mesh);
}

#[test]
fn parse_msh_3d_p2_cube_works() {
    let mesh = parse_msh_3d(P2_CUBE.as_bytes()).unwrap();
    assert_eq!(mesh.kind(), SolidKind::Tet10);
    assert_eq!(mesh.node_count(), 27);
    // element 7: Gmsh `1 2 4 5 | 9 21 12 17 25 23` → ours with 25 (edge 4–5) and 23 (edge 2–5)
    // swapped, as 0-based indices.
    assert_eq!(mesh.element(0), [0, 1, 3, 4, 8, 20, 11, 16, 22, 24]);
    // Every mid-edge node at the middle of its edge (VTK order, TET_EDGES). Gmsh writes the
    // middle of a cube edge as 0.4999999999986718: 1.3e-12 off.
    for e in 0..mesh.element_count() {
        let cell = mesh.element(e);
        for (k, [a, b]) in TET_EDGES.iter().enumerate() {
            let (pa, pb, pm) = (
                mesh.nodes()[cell[*a]],
                mesh.nodes()[cell[*b]],
                mesh.nodes()[cell[4 + k]],
            );
            for i in 0..3 {
                let mid = 0.5 * (pa[i] + pb[i]);
                assert!((pm[i] - mid).abs() < 1e-11, "element {e}, node {}", 4 + k);
            }
        }
    }
    // 6-node faces: 3 corners, 3 mid-edge nodes, 9 nodes per side of the cube.
    assert_eq!(mesh.node_set("bottom").unwrap().len(), 9);
    assert_eq!(mesh.node_set("edge").unwrap(), [0, 4, 16]);
    assert_cube(&mesh);
}

#[test]
fn read_msh_3d_works() {
    let path = tmp("solid_io_p2_cube.msh");
    std::fs::write(&path, P2_CUBE).unwrap();
    assert_eq!(
        read_msh_3d(&path).unwrap(),
        parse_msh_3d(P2_CUBE.as_bytes()).unwrap()
    );
    let missing = tmp("solid_io_no_such_file.msh");
    assert!(matches!(
        read_msh_3d(&missing),
        Err(FemError::Io { path, source: Some(_), .. }) if path.contains("solid_io_no_such_file")
    ));
}

#[test]
fn parse_msh_3d_reorients_left_handed_tetrahedra() {
    // Elements 7 and 12 with corners 2 and 3 swapped (and the mid-edge nodes with them, in
    // Gmsh's order 0–1, 1–2, 2–0, 3–0, 3–2, 3–1): the same mesh must come out.
    let p1 = edit(P1_CUBE, "\n7 1 2 4 5 \n", "\n7 1 2 5 4 \n");
    let p1 = edit(&p1, "\n12 6 8 7 3 \n", "\n12 6 8 3 7 \n");
    assert_eq!(
        parse_msh_3d(p1.as_bytes()).unwrap(),
        parse_msh_3d(P1_CUBE.as_bytes()).unwrap()
    );
    let p2 = edit(
        P2_CUBE,
        "\n7 1 2 4 5 9 21 12 17 25 23 \n",
        "\n7 1 2 5 4 9 23 17 12 25 21 \n",
    );
    let p2 = edit(
        &p2,
        "\n12 6 8 7 3 22 15 14 24 19 27 \n",
        "\n12 6 8 3 7 22 27 24 14 19 15 \n",
    );
    assert_eq!(
        parse_msh_3d(p2.as_bytes()).unwrap(),
        parse_msh_3d(P2_CUBE.as_bytes()).unwrap()
    );
}

/// The P1 cube with one more physical surface (tag 9, entity 7) holding the interior triangle
/// `corners`, shared by elements 7 (1 2 4 5) and 8 (2 4 5 6).
fn with_interior_surface(corners: &str) -> String {
    let text = edit(P1_CUBE, "\n8 12 6 1\n", "\n8 12 7 1\n");
    let text = edit(
        &text,
        "6 0 0 0 0 1 1 0 4 4 9 -8 -12 \n",
        "6 0 0 0 0 1 1 0 4 4 9 -8 -12 \n7 0 0 0 1 1 1 1 9 0 \n",
    );
    let text = edit(&text, "\n5 12 1 12\n", "\n6 13 1 13\n");
    edit(
        &text,
        "$EndElements",
        &format!("2 7 2 1\n13 {corners}\n$EndElements"),
    )
}

#[test]
fn parse_msh_3d_interior_surface_works() {
    // (2 4 5) turns counter-clockwise seen from (1, 1, 1): its normal points out of element 7
    // (index 0), which holds the origin; (2 5 4) points out of element 8 (index 1).
    for (corners, element) in [("2 4 5", 0), ("2 5 4", 1)] {
        let mesh = parse_msh_3d(with_interior_surface(corners).as_bytes()).unwrap();
        let faces = mesh.face_set("surface_9").unwrap();
        assert_eq!(faces.len(), 1);
        assert_eq!(faces[0].element, element, "triangle {corners}");
        let mut nodes: Vec<usize> = mesh.face_node_ids(faces[0]).collect();
        nodes.sort_unstable();
        assert_eq!(nodes, [1, 3, 4]);
        assert_eq!(mesh.node_set("surface_9").unwrap(), [1, 3, 4]);
    }
}

#[test]
fn parse_msh_3d_rejects_mixed_kinds() {
    // The last tetrahedron moved to a block of 10-node ones (its extra nodes are any tags).
    let text = edit(P1_CUBE, "\n5 12 1 12\n", "\n6 12 1 12\n");
    let text = edit(&text, "\n3 1 4 6\n", "\n3 1 4 5\n");
    let text = edit(
        &text,
        "\n12 6 8 7 3 \n",
        "\n3 1 11 1\n12 6 8 7 3 1 1 1 1 1 1\n",
    );
    assert_unsupported(parse_msh_3d(text.as_bytes()), "mixed 4-node and 10-node");
}

#[test]
fn parse_msh_3d_rejects_a_triangle_off_the_tetrahedra() {
    // Nodes 1, 2 and 7 are in no tetrahedron together.
    let text = edit(P1_CUBE, "\n3 1 2 4 \n", "\n3 1 2 7 \n");
    assert_unsupported(parse_msh_3d(text.as_bytes()), "physical surface bottom");
    // A 6-node triangle whose mid-side nodes are the face's, on the wrong edges.
    let text = edit(P2_CUBE, "\n3 1 2 4 9 21 12 \n", "\n3 1 2 4 9 12 21 \n");
    assert_unsupported(parse_msh_3d(text.as_bytes()), "is not a face");
}

#[test]
fn parse_msh_3d_rejects_other_element_types() {
    // An 8-node hexahedron (type 5) is read since issue 35, but not beside tetrahedra.
    let text = edit(P1_CUBE, "\n5 12 1 12\n", "\n6 13 1 13\n");
    let text = edit(
        &text,
        "$EndElements",
        "3 1 5 1\n13 1 2 3 4 5 6 7 8\n$EndElements",
    );
    assert_unsupported(parse_msh_3d(text.as_bytes()), "mixed 4-node and 8-node");
    // A 6-node prism (type 6), known to Gmsh but not read here.
    let text = edit(P1_CUBE, "\n5 12 1 12\n", "\n6 13 1 13\n");
    let text = edit(
        &text,
        "$EndElements",
        "3 1 6 1\n13 1 2 3 4 5 6\n$EndElements",
    );
    assert_unsupported(parse_msh_3d(text.as_bytes()), "MSH_PRI_6");
    // A type number that Gmsh does not have.
    let text = edit(P1_CUBE, "\n3 1 4 6\n", "\n3 1 200 6\n");
    assert_unsupported(parse_msh_3d(text.as_bytes()), "200");
    // A 2D mesh holds no tetrahedra; the 2D reader points to this one.
    let square = "$MeshFormat\n4.1 0 8\n$EndMeshFormat
$Nodes\n1 3 1 3\n2 1 0 3\n1\n2\n3\n0 0 0\n1 0 0\n0 1 0\n$EndNodes
$Elements\n1 1 1 1\n2 1 2 1\n1 1 2 3\n$EndElements\n";
    assert_unsupported(parse_msh_3d(square.as_bytes()), "no tetrahedra");
    match fem_core::gmsh::parse_msh(P1_CUBE.as_bytes()) {
        Err(FemError::Unsupported { what }) => assert!(what.contains("solid::gmsh"), "{what}"),
        other => panic!("expected Unsupported, got {other:?}"),
    }
}

#[test]
fn parse_msh_3d_rejects_bad_data() {
    assert_invalid(parse_msh_3d(b"\x00\xff\xfe garbage \x01"), "$MeshFormat");
    assert_invalid(parse_msh_3d(b""), "$MeshFormat");
    let old = edit(P1_CUBE, "4.1 0 8", "2.2 0 8");
    assert_unsupported(parse_msh_3d(old.as_bytes()), "version 2.2");
    // A flat tetrahedron: node 5 moved into the plane of nodes 1, 2, 4.
    let flat = edit(P1_CUBE, "\n5\n0 0 1\n", "\n5\n0.2 0.2 0\n");
    assert_invalid(parse_msh_3d(flat.as_bytes()), "element 7 is degenerate");
    // Every truncation of the P2 file: an error, never a panic (or a mesh).
    let end = P2_CUBE.find("$EndElements").unwrap();
    for k in 0..end {
        assert!(
            parse_msh_3d(&P2_CUBE.as_bytes()[..k]).is_err(),
            "the first {k} bytes gave a mesh"
        );
    }
    // Bytes flipped here and there: whatever comes out, no panic.
    let mut bytes = P2_CUBE.as_bytes().to_vec();
    for k in (0..bytes.len()).step_by(37) {
        let saved = bytes[k];
        bytes[k] = b'9';
        let _ = parse_msh_3d(&bytes);
        bytes[k] = saved;
    }
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
fn write_vtu_3d_p2_box_works() {
    let mesh = box_mesh(
        &lines(0.0, 2.0, 2),
        &lines(0.0, 1.0, 1),
        &lines(0.0, 1.0, 1),
        SolidKind::Tet10,
    )
    .unwrap();
    let (n, m) = (mesh.node_count(), mesh.element_count());
    let temperature: Vec<f64> = mesh.nodes().iter().map(|p| p[0] + 10.0 * p[2]).collect();
    let u: Vec<[f64; 3]> = mesh
        .nodes()
        .iter()
        .map(|p| [p[1], -p[0], 0.5 * p[2]])
        .collect();
    let sigma: Vec<[f64; 6]> = (0..m)
        .map(|e| [1.0, 2.0, 3.0, 4.0, 5.0, e as f64])
        .collect();
    let path = tmp("solid_io_p2_box.vtu");
    write_vtu_3d(
        &path,
        &mesh,
        &[
            ("T", Field3::Scalar(&temperature)),
            ("u", Field3::Vector(&u)),
        ],
        &[("sigma", Field3::SymTensor(&sigma))],
    )
    .unwrap();

    let piece = read_vtu(&path);
    assert_eq!(piece.num_points(), n);
    let points = as_f64(&piece.points);
    for (k, p) in mesh.nodes().iter().enumerate() {
        assert_eq!(&points[3 * k..3 * k + 3], p);
    }
    assert_eq!(piece.cells.types, vec![CellType::QuadraticTetra; m]);
    match &piece.cells.cell_verts {
        VertexNumbers::XML {
            connectivity,
            offsets,
        } => {
            let conn: Vec<usize> = connectivity.iter().map(|&c| c as usize).collect();
            assert_eq!(conn, mesh.connectivity());
            let expected: Vec<u64> = (1..=m as u64).map(|e| 10 * e).collect();
            assert_eq!(offsets, &expected);
        }
        other => panic!("expected XML cells, got {other:?}"),
    }
    assert_eq!(as_f64(array(&piece.data.point, "T")), temperature);
    let u_read = as_f64(array(&piece.data.point, "u"));
    assert_eq!(u_read, u.iter().flatten().copied().collect::<Vec<f64>>());
    let s = as_f64(array(&piece.data.cell, "sigma"));
    assert_eq!(s.len(), 9 * m);
    // (xx, yy, zz, xy, yz, zx) = (1, 2, 3, 4, 5, 1) as a full 3x3 tensor, row-major.
    assert_eq!(&s[9..18], &[1.0, 4.0, 1.0, 4.0, 2.0, 5.0, 1.0, 5.0, 3.0]);
    let region = array(&piece.data.cell, "region").clone();
    assert_eq!(region.cast_into::<u32>().unwrap(), vec![0; m]);
}

#[test]
fn write_vtu_3d_p1_from_gmsh_works() {
    let mesh = parse_msh_3d(P1_CUBE.as_bytes()).unwrap();
    let path = tmp("solid_io_p1_cube.vtu");
    write_vtu_3d(&path, &mesh, &[], &[]).unwrap();
    let piece = read_vtu(&path);
    assert_eq!(piece.num_points(), 8);
    assert_eq!(piece.cells.types, vec![CellType::Tetra; 6]);
    let region = array(&piece.data.cell, "region").clone();
    assert_eq!(region.cast_into::<u32>().unwrap(), vec![7; 6]);
}

#[test]
fn write_vtu_3d_rejects_length_mismatch() {
    let mesh = parse_msh_3d(P1_CUBE.as_bytes()).unwrap();
    let path = tmp("solid_io_mismatch.vtu");
    let _ = std::fs::remove_file(&path);
    let short = [[0.0; 3]; 7];
    assert!(matches!(
        write_vtu_3d(&path, &mesh, &[("u", Field3::Vector(&short))], &[]),
        Err(FemError::LengthMismatch {
            expected: 8,
            got: 7,
            ..
        })
    ));
    let long = [[0.0; 6]; 7];
    assert!(matches!(
        write_vtu_3d(&path, &mesh, &[], &[("s", Field3::SymTensor(&long))]),
        Err(FemError::LengthMismatch {
            expected: 6,
            got: 7,
            ..
        })
    ));
    assert!(!path.exists(), "nothing is written on error");
    let dir = tmp("solid_io_no_such_dir").join("x.vtu");
    assert!(matches!(
        write_vtu_3d(&dir, &mesh, &[], &[]),
        Err(FemError::Io { .. })
    ));
}
