//! A 3D sector from a 2D axisymmetric mesh: [`revolve`] turns the `(r, z)` triangles of a
//! [`Mesh`] about the z axis, so that a 3D model and the axisymmetric one can be compared on
//! the same meridian grid (Hertz, the pile), node by node.
//!
//! Each triangle swept through one angular sector is a prism, split into three tetrahedra by
//! a global order of the triangle's corners (corners `a < b < c`, `'` the next layer):
//! `(a, b, c, a')`, `(b, c, a', b')`, `(c, a', b', c')`. The diagonal of each quad face then
//! depends only on its edge's two corners, so neighbouring prisms share it and the mesh is
//! conforming. The order is by position (`z`, then `r`, then the index): two bodies whose
//! meridian meshes have coincident nodes on an interface (node pairs) get the same diagonals
//! there, so their interface faces match node for node. A corner on the axis (`r = 0`) is one node for every layer: the tetrahedra that
//! collapse are dropped (the prism becomes a pyramid of two tetrahedra, or one tetrahedron).
//!
//! P2: the corners are revolved, and every mid-edge node is placed at the cylindrical midpoint
//! of its edge (the mean of `r`, `θ` and `z`), so the mesh's faces of constant `r` lie on the
//! cylinder and its meridian edges are the 2D ones (straight in `(r, z)`: a 2D mesh with curved
//! mid-side nodes is revolved with straight ones).

use super::generate::oriented;
use super::mesh::{Face, SolidMesh, TET_EDGES};
use crate::error::FemError;
use crate::mesh::{ElementKind, Mesh};
use std::collections::HashMap;

/// A revolved mesh and where each 2D node went.
#[derive(Clone, Debug)]
pub struct Revolved {
    /// The 3D mesh: regions of the 2D elements, and for each 2D node set and edge set a node
    /// set and a face set of the same name; plus the node sets `theta0` and `theta1` (the
    /// planes `θ = 0` and `θ = angle`, axis included), `axis`, and the face sets `theta0` and
    /// `theta1`.
    pub mesh: SolidMesh,
    /// The angle of each node layer: `sectors + 1` layers for P1, `2 sectors + 1` for P2 (the
    /// mid-sector layers carry the mid-edge nodes).
    pub angles: Vec<f64>,
    /// `layers[n][l]`: the 3D node of 2D node `n` at layer `l` (the same node at every layer
    /// for a node on the axis).
    pub layers: Vec<Vec<usize>>,
}

/// Revolves `mesh` (coordinates `(r, z)`, `r ≥ 0`) through `angle` (radians, `0 < angle <
/// 2π`) in `sectors` equal sectors, from the plane `y = 0` (θ = 0, `x = r`) towards `+y`. The
/// 3D coordinates are `(r cos θ, r sin θ, z)`; P1 triangles give P1 tetrahedra, P2 give P2.
///
/// # Errors
/// [`FemError::InvalidParameter`] for an angle outside `(0, 2π)`, no sector, sectors wider
/// than 90°, or a node with `r < 0`; the errors of [`SolidMesh::new`] (a triangle with a
/// side on the axis gives a single tetrahedron per sector, never a flat one).
pub fn revolve(mesh: &Mesh, angle: f64, sectors: usize) -> Result<Revolved, FemError> {
    use std::f64::consts::{FRAC_PI_2, TAU};
    if !matches!(mesh.kind(), ElementKind::Tri3 | ElementKind::Tri6) {
        return Err(FemError::Unsupported {
            what: format!(
                "revolving a {:?} mesh (revolve takes triangles into tetrahedra)",
                mesh.kind()
            ),
        });
    }
    if !(angle > 0.0 && angle < TAU) {
        return Err(FemError::InvalidParameter {
            name: "angle",
            value: angle,
            expected: "an angle in (0, 2π) radians",
        });
    }
    if sectors == 0 || angle / sectors as f64 > FRAC_PI_2 + 1e-12 {
        return Err(FemError::InvalidParameter {
            name: "sectors",
            value: sectors as f64,
            expected: "at least one sector, each at most 90°",
        });
    }
    let nodes2 = mesh.nodes();
    let size = nodes2
        .iter()
        .flat_map(|p| p.iter())
        .fold(0.0_f64, |m, v| m.max(v.abs()));
    if let Some(p) = nodes2.iter().find(|p| p[0] < -1e-12 * size) {
        return Err(FemError::InvalidParameter {
            name: "r",
            value: p[0],
            expected: "a meridian mesh with r >= 0 (x is the radius)",
        });
    }
    let on_axis = |n: usize| nodes2[n][0].abs() <= 1e-12 * size;
    let npe = mesh.kind().node_count();
    let mut corner = vec![false; nodes2.len()];
    for e in 0..mesh.element_count() {
        for &n in &mesh.element(e)[..3] {
            corner[n] = true;
        }
    }
    // the corner nodes of every layer
    let theta = |k: usize| angle * k as f64 / sectors as f64;
    let mut nodes3: Vec<[f64; 3]> = Vec::new();
    let mut at: Vec<Vec<usize>> = vec![Vec::new(); nodes2.len()];
    for n in (0..nodes2.len()).filter(|&n| corner[n]) {
        let [r, z] = nodes2[n];
        if on_axis(n) {
            nodes3.push([0.0, 0.0, z]);
            at[n] = vec![nodes3.len() - 1; sectors + 1];
        } else {
            for k in 0..=sectors {
                let t = theta(k);
                nodes3.push([r * t.cos(), r * t.sin(), z]);
                at[n].push(nodes3.len() - 1);
            }
        }
    }
    // three tetrahedra per prism, the collapsed ones dropped
    let mut connectivity = Vec::new();
    let mut regions = Vec::new();
    let mut source = Vec::new();
    for e in 0..mesh.element_count() {
        let mut c = [mesh.element(e)[0], mesh.element(e)[1], mesh.element(e)[2]];
        c.sort_unstable_by(|&p, &q| order(nodes2, p, q));
        let [a, b, cc] = c;
        for k in 0..sectors {
            let (l, u) = (k, k + 1);
            for t in [
                [at[a][l], at[b][l], at[cc][l], at[a][u]],
                [at[b][l], at[cc][l], at[a][u], at[b][u]],
                [at[cc][l], at[a][u], at[b][u], at[cc][u]],
            ] {
                let distinct = (0..4).all(|i| (i + 1..4).all(|j| t[i] != t[j]));
                if !distinct {
                    continue;
                }
                let t = oriented(&nodes3, t);
                connectivity.extend_from_slice(&t);
                regions.push(mesh.regions()[e]);
                source.push(e);
            }
        }
    }
    let mut p1 = SolidMesh::new(nodes3, ElementKind::Tet4, connectivity, regions)?;
    // face sets from the 2D edge sets, and the two planes
    let mut faces_of: HashMap<[usize; 3], Vec<Face>> = HashMap::new();
    for element in 0..p1.element_count() {
        for face in 0..4u8 {
            let mut k: Vec<usize> = p1
                .face_node_ids(Face {
                    element,
                    side: face,
                })
                .collect();
            k.sort_unstable();
            faces_of.entry([k[0], k[1], k[2]]).or_default().push(Face {
                element,
                side: face,
            });
        }
    }
    let names: Vec<String> = mesh.edge_set_names().map(str::to_string).collect();
    for name in &names {
        let mut faces = Vec::new();
        for side in mesh.edge_set(name)? {
            let s: Vec<usize> = mesh.side_nodes(*side).collect();
            let (i, j) = if order(nodes2, s[0], s[1]).is_lt() {
                (s[0], s[1])
            } else {
                (s[1], s[0])
            };
            for k in 0..sectors {
                // the quad (i, j, j', i') split along j – i'
                for tri in [
                    [at[i][k], at[j][k], at[i][k + 1]],
                    [at[j][k], at[j][k + 1], at[i][k + 1]],
                ] {
                    let mut key = tri;
                    key.sort_unstable();
                    if key[0] == key[1] || key[1] == key[2] {
                        continue;
                    }
                    if let Some(list) = faces_of.get(&key) {
                        let pick = list
                            .iter()
                            .find(|f| source[f.element] == side.element)
                            .unwrap_or(&list[0]);
                        faces.push(*pick);
                    }
                }
            }
        }
        p1.add_face_set(name, faces)?;
    }
    let boundary = p1.boundary_facets();
    for (plane, layer) in [("theta0", 0), ("theta1", sectors)] {
        let mut in_layer = vec![false; p1.node_count()];
        for list in &at {
            if let Some(&n) = list.get(layer) {
                in_layer[n] = true;
            }
        }
        let faces = boundary
            .iter()
            .copied()
            .filter(|f| p1.face_node_ids(*f).all(|n| in_layer[n]))
            .collect();
        p1.add_face_set(plane, faces)?;
    }
    // P2: mid-edge nodes at the cylindrical midpoints
    let (mut solid, angles) = match mesh.kind() {
        ElementKind::Tri3 => (p1, (0..=sectors).map(theta).collect::<Vec<_>>()),
        _ => {
            let mid = |a: [f64; 3], b: [f64; 3]| cylindrical_midpoint(a, b);
            let p2 = p1.to_tet10(Some(&mid))?;
            (
                p2,
                (0..=2 * sectors)
                    .map(|h| 0.5 * theta(1) * h as f64)
                    .collect(),
            )
        }
    };
    let layers = node_layers(mesh, &solid, &at, sectors, npe);
    // node sets: the 2D ones at every layer, the planes and the axis
    let node_set_names: Vec<String> = mesh.node_set_names().map(str::to_string).collect();
    for name in &node_set_names {
        let set = mesh
            .node_set(name)?
            .iter()
            .flat_map(|&n| layers[n].clone())
            .collect();
        solid.add_node_set(name, set)?;
    }
    let last = angles.len() - 1;
    for (plane, layer) in [("theta0", 0), ("theta1", last)] {
        let set = layers
            .iter()
            .filter_map(|l| l.get(layer).copied())
            .collect();
        solid.add_node_set(plane, set)?;
    }
    let axis = (0..nodes2.len())
        .filter(|&n| on_axis(n))
        .filter_map(|n| layers[n].first().copied())
        .collect();
    solid.add_node_set("axis", axis)?;
    Ok(Revolved {
        mesh: solid,
        angles,
        layers,
    })
}

/// The node of every 2D node at every layer (module docs): P1 corners directly; P2 corners at
/// the mid layers and 2D mid-side nodes from the 3D mid-edge nodes of the right edges.
fn node_layers(
    mesh: &Mesh,
    solid: &SolidMesh,
    at: &[Vec<usize>],
    sectors: usize,
    npe: usize,
) -> Vec<Vec<usize>> {
    if npe == 3 {
        return at.to_vec();
    }
    let mut mid: HashMap<(usize, usize), usize> = HashMap::new();
    for e in 0..solid.element_count() {
        let cell = solid.element(e);
        for (k, [i, j]) in TET_EDGES.iter().enumerate() {
            mid.insert(
                (cell[*i].min(cell[*j]), cell[*i].max(cell[*j])),
                cell[4 + k],
            );
        }
    }
    let edge = |a: usize, b: usize| {
        if a == b {
            Some(a) // an axis node between two layers is itself
        } else {
            mid.get(&(a.min(b), a.max(b))).copied()
        }
    };
    let mut layers = vec![Vec::new(); at.len()];
    for (n, list) in at.iter().enumerate() {
        if list.is_empty() {
            continue;
        }
        for k in 0..sectors {
            layers[n].push(list[k]);
            layers[n].extend(edge(list[k], list[k + 1]));
        }
        layers[n].push(list[sectors]);
    }
    // the 2D mid-side nodes: mid nodes of the layer edges (i, j) and of the diagonals j – i'
    for e in 0..mesh.element_count() {
        let cell = mesh.element(e);
        for side in 0..3 {
            let s = ElementKind::Tri6.facet_nodes(side);
            let (a, b, m) = (cell[s[0]], cell[s[1]], cell[s[2]]);
            if !layers[m].is_empty() {
                continue;
            }
            let (i, j) = if order(mesh.nodes(), a, b).is_lt() {
                (a, b)
            } else {
                (b, a)
            };
            for k in 0..sectors {
                layers[m].extend(edge(at[i][k], at[j][k]));
                layers[m].extend(edge(at[j][k], at[i][k + 1]));
            }
            layers[m].extend(edge(at[i][sectors], at[j][sectors]));
        }
    }
    layers
}

/// The corner order of the prism split: by `z`, then `r`, then index.
fn order(nodes: &[[f64; 2]], p: usize, q: usize) -> std::cmp::Ordering {
    let (a, b) = (nodes[p], nodes[q]);
    a[1].total_cmp(&b[1])
        .then(a[0].total_cmp(&b[0]))
        .then(p.cmp(&q))
}

/// The midpoint in cylindrical coordinates (mean `r`, `θ`, `z`); an end on the axis takes the
/// other end's angle.
fn cylindrical_midpoint(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    let polar = |p: [f64; 3]| {
        let r = p[0].hypot(p[1]);
        let t = p[1].atan2(p[0]);
        (
            r,
            if t < 0.0 {
                t + std::f64::consts::TAU
            } else {
                t
            },
        )
    };
    let ((ra, ta), (rb, tb)) = (polar(a), polar(b));
    let scale = ra
        .max(rb)
        .max(a[2].abs())
        .max(b[2].abs())
        .max(f64::MIN_POSITIVE);
    let t = if ra <= 1e-12 * scale {
        tb
    } else if rb <= 1e-12 * scale {
        ta
    } else {
        0.5 * (ta + tb)
    };
    let r = 0.5 * (ra + rb);
    [r * t.cos(), r * t.sin(), 0.5 * (a[2] + b[2])]
}
