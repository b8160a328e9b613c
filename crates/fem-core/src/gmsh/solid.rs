//! The 3D tables of the Gmsh reader: tetrahedra and hexahedra in our node order (Gmsh's Tet10
//! and Hex20 mid-edge nodes mapped), right-handed; physical surfaces matched to element faces,
//! physical curves and points to nodes.

use super::build::{Groups, Reader, Shape};
use crate::element::hex20::GMSH_TO_LOCAL;
use crate::error::FemError;
use crate::mesh::{ElementKind, Face, SolidMesh, signed_volume};
use std::collections::{BTreeMap, BTreeSet, HashMap};

/// What the reader takes, for the error on any other element type.
const READ: &str = "tetrahedra (types 4, 11), hexahedra (5, 17), triangles (2, 9), \
                    quadrangles (3, 16), lines (1, 8) and points (15)";

/// `ours[k] = gmsh[FROM_GMSH_TET10[k]]`: Gmsh's mid-edge nodes 8 (edge 2–3) and 9 (edge 1–3)
/// are our 9 and 8.
const FROM_GMSH_TET10: [usize; 10] = [0, 1, 2, 3, 4, 5, 6, 7, 9, 8];

/// `right[k] = left[MIRROR[k]]`: corners 2 ↔ 3, so the mid-edge nodes of edges 1–2 ↔ 1–3
/// (5 ↔ 8) and 2–0 ↔ 0–3 (6 ↔ 7); those of 0–1 (4) and 2–3 (9) stay.
const MIRROR: [usize; 10] = [0, 1, 3, 2, 4, 8, 7, 6, 5, 9];

/// `right[k] = left[HEX_MIRROR[k]]` for a hexahedron: bottom ↔ top (corners 0..4 ↔ 4..8, the
/// mid-edge nodes of the bottom edges ↔ those of the top edges; the vertical ones stay).
const HEX_MIRROR: [usize; 20] = [
    4, 5, 6, 7, 0, 1, 2, 3, 12, 13, 14, 15, 8, 9, 10, 11, 16, 17, 18, 19,
];

/// The 3D reader's tables.
pub(super) static SOLID: Reader<3> = Reader {
    read: READ,
    none: "tetrahedra or hexahedra (Gmsh types 4, 11, 5, 17)",
    orient,
    sets: add_physical_sets,
};

/// A 3D element in our node order (Gmsh's Tet10 and Hex20 mid-edge nodes mapped), right-handed:
/// the triad at corner 0, `(1, 2, 3)` of a tetrahedron or `(1, 3, 4)` of a hexahedron, has a
/// positive volume, else the element is mirrored.
fn orient(kind: ElementKind, t: Vec<usize>, nodes: &[[f64; 3]]) -> Vec<usize> {
    let cell: Vec<usize> = match kind {
        ElementKind::Tet10 => FROM_GMSH_TET10.iter().map(|&k| t[k]).collect(),
        ElementKind::Hex20 => {
            let mut cell = vec![0; 20];
            for (k, &local) in GMSH_TO_LOCAL.iter().enumerate() {
                cell[local] = t[k];
            }
            cell
        }
        _ => t,
    };
    let hex = kind.corner_count() == 8;
    let [i, j, k] = if hex { [1, 3, 4] } else { [1, 2, 3] };
    let volume = signed_volume(
        nodes[cell[0]],
        nodes[cell[i]],
        nodes[cell[j]],
        nodes[cell[k]],
    );
    if volume < 0.0 {
        let mirror: &[usize] = if hex { &HEX_MIRROR } else { &MIRROR };
        mirror[..kind.node_count()]
            .iter()
            .map(|&k| cell[k])
            .collect()
    } else {
        cell
    }
}

/// The physical surfaces, curves and points as face and node sets of `mesh`.
fn add_physical_sets(mesh: &mut SolidMesh, groups: &Groups) -> Result<(), FemError> {
    let (lower, index, origin) = (groups.lower, groups.index, groups.origin);
    // The faces of every tetrahedron, by their sorted corners (two for an interior face).
    let mut faces: HashMap<[usize; 4], Vec<Face>> = HashMap::new();
    if lower
        .iter()
        .any(|l| matches!(l.shape, Shape::Triangle | Shape::Quadrangle))
    {
        faces.reserve(mesh.kind().facet_count() * mesh.element_count());
        for f in mesh.all_facets() {
            faces.entry(mesh.facet_key(f)).or_default().push(f);
        }
    }
    let mut face_sets: BTreeMap<String, BTreeSet<Face>> = BTreeMap::new();
    let mut node_sets: BTreeMap<String, Vec<usize>> = BTreeMap::new();
    for l in lower {
        let entity = l.entity.1;
        let names = l.groups(groups);
        if matches!(l.shape, Shape::Triangle | Shape::Quadrangle) {
            let (what, of) = match l.shape {
                Shape::Triangle => ("triangle", "a tetrahedron"),
                _ => ("quadrangle", "a hexahedron"),
            };
            let face =
                match_face(mesh, &faces, index, &l.nodes).ok_or_else(|| FemError::Unsupported {
                    what: format!(
                        "{what} {} (nodes {:?}) of physical surface {} (entity {entity}) in \
                         {origin} is not a face of {of}",
                        l.element_tag,
                        l.nodes,
                        names.join(", ")
                    ),
                })?;
            for name in names {
                face_sets.entry(name).or_default().insert(face);
            }
            continue;
        }
        let ids = l
            .nodes
            .iter()
            .map(|t| index.get(t).copied().ok_or(*t))
            .collect::<Result<Vec<usize>, u64>>()
            .map_err(|t| FemError::Unsupported {
                what: format!(
                    "node {t} of physical {} {} (element {}) in {origin} is not a node of a \
                     tetrahedron",
                    l.shape.prefix(),
                    names.join(", "),
                    l.element_tag
                ),
            })?;
        for name in names {
            node_sets.entry(name).or_default().extend(&ids);
        }
    }
    for (name, set) in face_sets {
        mesh.add_face_set(&name, set.into_iter().collect())?;
    }
    for (name, mut set) in node_sets {
        if let Ok(of_faces) = mesh.node_set(&name) {
            set.extend_from_slice(of_faces);
        }
        mesh.add_node_set(&name, set)?;
    }
    Ok(())
}

/// The element face of a triangle or quadrangle element (node tags), if there is one.
fn match_face(
    mesh: &SolidMesh,
    faces: &HashMap<[usize; 4], Vec<Face>>,
    index: &HashMap<u64, usize>,
    nodes: &[u64],
) -> Option<Face> {
    let nc = mesh.kind().facet_corner_count();
    // a triangle on a hexahedral mesh (or a quadrangle on a tetrahedral one) is no face
    let element_corners = if matches!(nodes.len(), 3 | 6) { 3 } else { 4 };
    if element_corners != nc {
        return None;
    }
    let mut corners = [usize::MAX; 4];
    for (c, tag) in corners.iter_mut().zip(nodes).take(nc) {
        *c = *index.get(tag)?;
    }
    let mut key = corners;
    key.sort_unstable();
    let candidates = faces.get(&key)?;
    // An interior face: the tetrahedron whose face turns like the triangle.
    let face = candidates
        .iter()
        .copied()
        .find(|&f| {
            let ids: Vec<usize> = mesh.face_node_ids(f).take(nc).collect();
            let i = ids.iter().position(|&n| n == corners[0]).unwrap_or(0);
            ids[(i + 1) % nc] == corners[1]
        })
        .unwrap_or(candidates[0]);
    if nodes.len() == 6 && mesh.kind() == ElementKind::Tet10 {
        // each mid-side node of the triangle must be the face's on the same edge
        let ids: Vec<usize> = mesh.face_node_ids(face).collect();
        let edge = |a: usize, b: usize| (a.min(b), a.max(b));
        let face_mids: HashMap<(usize, usize), usize> = (0..3)
            .map(|k| (edge(ids[k], ids[(k + 1) % 3]), ids[3 + k]))
            .collect();
        for k in 0..3 {
            let mid = *index.get(&nodes[3 + k])?;
            if face_mids.get(&edge(corners[k], corners[(k + 1) % 3])) != Some(&mid) {
                return None;
            }
        }
    }
    Some(face)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solid::TET_EDGES;

    /// The edge (as a sorted pair of corners) that each node `4..10` of a P2 numbering sits on.
    fn edge_of(k: usize) -> [usize; 2] {
        TET_EDGES[k - 4]
    }

    #[test]
    fn mirror_works() {
        // Applying MIRROR to a left-handed numbering: the new node k must sit on the edge of
        // the new corners, i.e. new mid k on edge (a, b) is old mid on edge (MIRROR[a], MIRROR[b]).
        for (k, &from) in MIRROR.iter().enumerate().skip(4) {
            let [a, b] = edge_of(k);
            let mut old = [MIRROR[a], MIRROR[b]];
            old.sort_unstable();
            let mut at = edge_of(from);
            at.sort_unstable();
            assert_eq!(old, at, "node {k}");
        }
        for k in 0..10 {
            assert_eq!(MIRROR[MIRROR[k]], k, "MIRROR is an involution");
        }
    }

    #[test]
    fn from_gmsh_tet10_works() {
        // Gmsh's 10-node tetrahedron (`MSH_TET_10`, Gmsh reference manual, node ordering):
        // 4: 0–1, 5: 1–2, 6: 2–0, 7: 3–0, 8: 3–2, 9: 3–1.
        let gmsh_edges = [[0, 1], [1, 2], [2, 0], [3, 0], [3, 2], [3, 1]];
        for k in 4..10 {
            let mut ours = edge_of(k);
            let mut theirs = gmsh_edges[FROM_GMSH_TET10[k] - 4];
            ours.sort_unstable();
            theirs.sort_unstable();
            assert_eq!(ours, theirs, "node {k}");
        }
    }

    #[test]
    fn parse_msh_3d_rejects_a_file_without_tetrahedra() {
        let msh = "$MeshFormat\n4.1 0 8\n$EndMeshFormat
$Nodes\n1 3 1 3\n2 1 0 3\n1\n2\n3\n0 0 0\n1 0 0\n0 1 0\n$EndNodes
$Elements\n1 1 1 1\n2 1 2 1\n1 1 2 3\n$EndElements\n";
        assert!(matches!(
            crate::gmsh::parse_msh_3d(msh.as_bytes()),
            Err(FemError::Unsupported { what }) if what.contains("no tetrahedra")
        ));
    }
}
