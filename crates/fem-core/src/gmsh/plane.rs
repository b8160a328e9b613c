//! The 2D tables of the Gmsh reader: triangles and quadrangles, oriented counter-clockwise;
//! physical curves matched to element sides, physical points to nodes.

use super::build::{Groups, Lower, Reader, Shape};
use crate::error::FemError;
use crate::mesh::{ElementKind, Mesh, Side};
use std::collections::{BTreeMap, HashMap};

/// The 2D reader's tables.
pub(super) static PLANE: Reader<2> = Reader {
    read: "triangles (types 2, 9), quadrangles (3, 16, 10), lines (1, 8) and points (15) \
           (volume meshes: `solid::gmsh`)",
    none: "triangles or quadrangles (Gmsh types 2, 9, 3, 16, 10)",
    orient,
    sets: add_physical_sets,
};

/// A 2D element counter-clockwise: the shoelace area of the corners; a clockwise element is
/// mirrored: triangles 1 ↔ 2 (mid-sides 3 ↔ 5), quadrangles 1 ↔ 3 (mid-sides 4 ↔ 7, 5 ↔ 6;
/// the centre stays).
fn orient(kind: ElementKind, mut cell: Vec<usize>, nodes: &[[f64; 2]]) -> Vec<usize> {
    let nc = kind.corner_count();
    let area: f64 = (0..nc)
        .map(|k| {
            let (p, q) = (nodes[cell[k]], nodes[cell[(k + 1) % nc]]);
            p[0] * q[1] - q[0] * p[1]
        })
        .sum();
    if area < 0.0 {
        let swaps: &[(usize, usize)] = match (nc, kind.is_quadratic()) {
            (3, false) => &[(1, 2)],
            (3, true) => &[(1, 2), (3, 5)],
            (_, false) => &[(1, 3)],
            (_, true) => &[(1, 3), (4, 7), (5, 6)],
        };
        swaps.iter().for_each(|&(a, b)| cell.swap(a, b));
    }
    cell
}

/// The physical curves and points as edge and node sets of `mesh`: line elements matched to
/// triangle sides (directed corner pairs), point elements to nodes; named by `names` or
/// `curve_N` / `point_N`.
fn add_physical_sets(mesh: &mut Mesh, groups: &Groups) -> Result<(), FemError> {
    let (lower, index, origin) = (groups.lower, groups.index, groups.origin);
    let of = |shape: Shape| lower.iter().filter(move |l| l.shape == shape);
    // Physical curves: match lines to triangle sides (directed corner pairs).
    let mut sides: HashMap<(usize, usize), Side> = HashMap::new();
    for side in mesh.all_facets() {
        let mut it = mesh.side_nodes(side);
        if let (Some(a), Some(b)) = (it.next(), it.next()) {
            sides.insert((a, b), side);
        }
    }
    let mut edge_sets: BTreeMap<String, Vec<Side>> = BTreeMap::new();
    for line in of(Shape::Line) {
        let side = match_side(mesh, &sides, index, line).ok_or_else(|| FemError::Unsupported {
            what: format!(
                "a line element of curve {} (nodes {:?}) in {origin} is not a triangle side",
                line.entity.1, line.nodes
            ),
        })?;
        for name in line.groups(groups) {
            let set = edge_sets.entry(name).or_default();
            if !set.contains(&side) {
                set.push(side);
            }
        }
    }
    let curves: Vec<String> = edge_sets.keys().cloned().collect();
    for (name, set) in edge_sets {
        mesh.add_edge_set(&name, set)?;
    }
    let mut node_sets: BTreeMap<String, Vec<usize>> = BTreeMap::new();
    for point in of(Shape::Point) {
        let node = point
            .nodes
            .first()
            .and_then(|t| index.get(t))
            .copied()
            .ok_or_else(|| FemError::Unsupported {
                what: format!(
                    "physical point entity {} (nodes {:?}) in {origin} is not a node of a triangle",
                    point.entity.1, point.nodes
                ),
            })?;
        for name in point.groups(groups) {
            node_sets.entry(name).or_default().push(node);
        }
    }
    for name in &curves {
        match node_sets.remove(name) {
            // a point group of the same name: one sorted set of both
            Some(points) => {
                let mut all = mesh.facet_set_nodes(name)?;
                all.extend(points);
                mesh.add_node_set(name, all)?;
            }
            None => {
                mesh.add_curve_node_set(name)?;
            }
        }
    }
    for (name, set) in node_sets {
        mesh.add_node_set(&name, set)?;
    }
    Ok(())
}

/// The triangle side of a line element: to the left of the line if two triangles share it.
/// For a 3-node line in a P2 mesh the middle node must be the side's.
fn match_side(
    mesh: &Mesh,
    sides: &HashMap<(usize, usize), Side>,
    index: &HashMap<u64, usize>,
    line: &Lower,
) -> Option<Side> {
    let a = *index.get(line.nodes.first()?)?;
    let b = *index.get(line.nodes.get(1)?)?;
    let side = sides.get(&(a, b)).or_else(|| sides.get(&(b, a))).copied()?;
    match (line.nodes.get(2), mesh.kind().is_quadratic()) {
        (Some(mid), true) => {
            let m = *index.get(mid)?;
            (mesh.side_nodes(side).nth(2) == Some(m)).then_some(side)
        }
        _ => Some(side),
    }
}
