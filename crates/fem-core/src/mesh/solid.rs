//! What the 3D mesh has of its own: the names of its facets (faces, face sets), the nodal
//! areas of a face set, `to_tet10`, and the corner check of its elements.

use super::{ElementKind, Face, SolidMesh, TET_EDGES};
use crate::element::Element;
use crate::error::FemError;
use std::collections::BTreeMap;

/// Where the mid-edge node of an edge `(a, b)` goes ([`SolidMesh::to_tet10`]).
pub type MidpointFn<'a> = dyn Fn([f64; 3], [f64; 3]) -> [f64; 3] + 'a;

/// A quadrature point of a face ([`SolidMesh::face_points`]).
pub(crate) struct FacePoint {
    /// Position.
    pub(crate) x: [f64; 3],
    /// Unit normal, outward of the element (corners counter-clockwise seen from outside).
    pub(crate) normal: [f64; 3],
    /// Rule weight × surface Jacobian.
    pub(crate) weight: f64,
    /// The face nodes' shape values (the first 3, 4, 6 or 8).
    pub(crate) n: [f64; 8],
}

/// `(b − a) · ((c − a) × (d − a)) / 6`.
#[inline]
pub(crate) fn signed_volume(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) -> f64 {
    let u = sub(b, a);
    let v = sub(c, a);
    let w = sub(d, a);
    dot(u, cross(v, w)) / 6.0
}

#[inline]
pub(crate) fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[inline]
pub(crate) fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[inline]
pub(crate) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

impl SolidMesh {
    /// Adds (or replaces) a named face set ([`SolidMesh::add_facet_set`]), and the node set of
    /// the same name (every node of its faces) unless one exists already.
    ///
    /// # Errors
    /// [`FemError::InvalidSide`] for a face whose element or local index is out of range.
    pub fn add_face_set(&mut self, name: &str, faces: Vec<Face>) -> Result<(), FemError> {
        self.add_facet_set(name, faces)?;
        if !self.node_sets.contains_key(name) {
            let nodes = self.facet_set_nodes(name)?;
            self.node_sets.insert(name.to_string(), nodes);
        }
        Ok(())
    }

    /// The global nodes of a face, in [`ElementKind::facet_nodes`] order.
    ///
    /// # Panics
    /// If the face does not exist.
    #[track_caller]
    pub fn face_node_ids(&self, face: Face) -> impl Iterator<Item = usize> + '_ {
        self.facet_nodes(face)
    }

    /// A named face set ([`SolidMesh::facet_set`]).
    ///
    /// # Errors
    /// [`FemError::UnknownSet`] if there is none of that name.
    pub fn face_set(&self, name: &str) -> Result<&[Face], FemError> {
        self.facet_set(name)
    }

    /// Calls `f(nodes, point)` at each point of a rule on `face` (degree 4 on a 3- or 6-node
    /// triangle, curved P2 faces included; 3×3 Gauss on a 4- or 8-node quadrilateral), with the face's nodes in
    /// [`ElementKind::facet_nodes`] order; stops at the first error.
    pub(crate) fn face_points(
        &self,
        face: Face,
        mut f: impl FnMut(&[usize], &FacePoint) -> Result<(), FemError>,
    ) -> Result<(), FemError> {
        let mut nodes = [0usize; 8];
        let mut count = 0;
        for (slot, node) in nodes.iter_mut().zip(self.face_node_ids(face)) {
            *slot = node;
            count += 1;
        }
        let nodes = &nodes[..count];
        let quad = self.kind.facet_corner_count() == 4;
        let rule: &[([f64; 2], f64)] = if quad {
            crate::quadrature::tensor_rule(3)
        } else {
            &crate::quadrature::TRI_6
        };
        for &(xi, w) in rule {
            let (n, dn) = if quad {
                quadrilateral_shape(count, xi)
            } else {
                let (n6, dn6) = triangle_shape(count, xi);
                let (mut n, mut dn) = ([0.0; 8], [[0.0; 2]; 8]);
                n[..6].copy_from_slice(&n6);
                dn[..6].copy_from_slice(&dn6);
                (n, dn)
            };
            let mut x = [0.0; 3];
            let mut d = [[0.0; 3]; 2];
            for (i, &node) in nodes.iter().enumerate() {
                for (a, c) in self.nodes[node].iter().enumerate() {
                    x[a] += n[i] * c;
                    d[0][a] += dn[i][0] * c;
                    d[1][a] += dn[i][1] * c;
                }
            }
            let c = cross(d[0], d[1]);
            let jac = dot(c, c).sqrt();
            let point = FacePoint {
                x,
                normal: c.map(|v| v / jac),
                weight: w * jac,
                n,
            };
            f(nodes, &point)?;
        }
        Ok(())
    }

    /// The consistent nodal areas of a face set, `A_i = ∫ N_i dA` over its faces (a degree-4
    /// rule per face, curved P2 faces included): the weights that turn a uniform pressure into
    /// the nodal forces the elements feel. Returns the set's nodes (sorted, as its node set)
    /// and their areas. On P2 faces the corner nodes get `0` and the mid-edge nodes a third of
    /// each face (the P2 triangle's `∫ N_i`), so pressures read as `r_n / A_i` are exact for a
    /// uniform pressure, and a corner node carries no force of it.
    ///
    /// # Errors
    /// [`FemError::UnknownSet`] if there is no such face set.
    pub fn nodal_areas(&self, face_set: &str) -> Result<(Vec<usize>, Vec<f64>), FemError> {
        let faces = self.face_set(face_set)?;
        let mut area: BTreeMap<usize, f64> = BTreeMap::new();
        for &face in faces {
            self.face_points(face, |nodes, p| {
                for (i, node) in nodes.iter().enumerate() {
                    *area.entry(*node).or_insert(0.0) += p.n[i] * p.weight;
                }
                Ok(())
            })?;
        }
        // a flat P2 face gives its corners ∫ N_i = 0 up to round-off, a curved one a tiny
        // value of either sign: below 1e-9 of the largest area it is 0
        let largest = area.values().fold(0.0_f64, |m, a| m.max(*a));
        Ok(area
            .into_iter()
            .map(|(n, a)| (n, if a > 1e-9 * largest { a } else { 0.0 }))
            .unzip())
    }

    /// The same mesh with P2 (10-node) tetrahedra: a mid-edge node is added on every edge at
    /// `midpoint(a, b)`, where `a, b` are the edge's end nodes. A P2 mesh is returned as is.
    /// Node and face sets carry over (a face set's node set gains its faces' new nodes).
    ///
    /// `midpoint` places curved edges on the geometry (e.g. on a sphere); `None` puts the node
    /// at the middle of the straight edge.
    ///
    /// # Errors
    /// As [`SolidMesh::new`] (an inverted curved element shows up when assembled).
    pub fn to_tet10(&self, midpoint: Option<&MidpointFn<'_>>) -> Result<Self, FemError> {
        match self.kind {
            ElementKind::Tet10 => return Ok(self.clone()),
            ElementKind::Tet4 => {}
            other => {
                return Err(FemError::Unsupported {
                    what: format!("making 10-node tetrahedra of a {other:?} mesh"),
                });
            }
        }
        let mut nodes = self.nodes.clone();
        let mut index: std::collections::HashMap<(usize, usize), usize> =
            std::collections::HashMap::new();
        let mut connectivity = Vec::with_capacity(10 * self.element_count());
        for e in 0..self.element_count() {
            let cell = self.element(e);
            connectivity.extend_from_slice(cell);
            for [i, j] in TET_EDGES {
                let (a, b) = (cell[i].min(cell[j]), cell[i].max(cell[j]));
                let id = *index.entry((a, b)).or_insert_with(|| {
                    let (pa, pb) = (self.nodes[a], self.nodes[b]);
                    nodes.push(match midpoint {
                        Some(f) => f(pa, pb),
                        None => [
                            0.5 * (pa[0] + pb[0]),
                            0.5 * (pa[1] + pb[1]),
                            0.5 * (pa[2] + pb[2]),
                        ],
                    });
                    nodes.len() - 1
                });
                connectivity.push(id);
            }
        }
        let mut out = Self::new(
            nodes,
            ElementKind::Tet10,
            connectivity,
            self.regions.clone(),
        )?;
        for (name, set) in &self.node_sets {
            let mut set = set.clone();
            if let Some(faces) = self.facet_sets.get(name) {
                for f in faces {
                    set.extend(out.face_node_ids(*f));
                }
            }
            out.add_node_set(name, set)?;
        }
        for (name, faces) in &self.facet_sets {
            out.add_face_set(name, faces.clone())?;
        }
        Ok(out)
    }
}

/// Shape values and reference derivatives of a 4- or 8-node quadrilateral face at `(ξ, η)`
/// on `[−1, 1]²` (corners, then the mid-edge nodes), padded to 8.
pub(crate) fn quadrilateral_shape(nodes: usize, xi: [f64; 2]) -> ([f64; 8], [[f64; 2]; 8]) {
    let (mut n, mut dn) = ([0.0; 8], [[0.0; 2]; 8]);
    if nodes == 4 {
        crate::element::Quad4.shape(xi, &mut n, &mut dn);
    } else {
        crate::element::Quad8.shape(xi, &mut n, &mut dn);
    }
    (n, dn)
}

/// The corner tetrahedra of a tetrahedron (itself) or a hexahedron (at each corner, the corner
/// and its three neighbours as a right-handed triad) ([`SolidMesh::new`]).
pub(super) fn corner_simplices(corners: usize) -> Vec<[usize; 4]> {
    if corners == 4 {
        return vec![[0, 1, 2, 3]];
    }
    let corners = &crate::element::hex8::CORNERS;
    let mut tets = Vec::with_capacity(8);
    for (i, c) in corners.iter().enumerate() {
        let flip = |a: usize| {
            let mut d = *c;
            d[a] = -d[a];
            corners.iter().position(|q| *q == d).unwrap_or(i)
        };
        let (jx, jy, jz) = (flip(0), flip(1), flip(2));
        // the triad (x, y, z) of neighbours is right-handed where c_x c_y c_z < 0
        tets.push(if c[0] * c[1] * c[2] < 0.0 {
            [i, jx, jy, jz]
        } else {
            [i, jy, jx, jz]
        });
    }
    tets
}

/// Shape values and reference derivatives `(∂/∂ξ, ∂/∂η)` of a 3- or 6-node triangle at
/// `(ξ, η)`, in the node order of [`ElementKind::facet_nodes`] (corners, then the mid-edge nodes
/// of edges 0–1, 1–2, 2–0); the first `nodes` entries are set (`nodes` is 3 for the linear
/// triangle, anything else means 6).
///
/// ```
/// use fem_core::solid::triangle_shape;
/// let (n, _) = triangle_shape(6, [0.5, 0.0]); // the mid-edge node of edge 0–1
/// assert!((n[3] - 1.0).abs() < 1e-15 && n.iter().sum::<f64>() - 1.0 < 1e-15);
/// ```
pub fn triangle_shape(nodes: usize, xi: [f64; 2]) -> ([f64; 6], [[f64; 2]; 6]) {
    let l = [1.0 - xi[0] - xi[1], xi[0], xi[1]];
    let dl = [[-1.0, -1.0], [1.0, 0.0], [0.0, 1.0]];
    let (mut n, mut dn) = ([0.0; 6], [[0.0; 2]; 6]);
    if nodes == 3 {
        n[..3].copy_from_slice(&l);
        dn[..3].copy_from_slice(&dl);
        return (n, dn);
    }
    for i in 0..3 {
        n[i] = l[i] * (2.0 * l[i] - 1.0);
        dn[i] = dl[i].map(|d| (4.0 * l[i] - 1.0) * d);
    }
    for (k, (i, j)) in [(0, 1), (1, 2), (2, 0)].into_iter().enumerate() {
        n[3 + k] = 4.0 * l[i] * l[j];
        dn[3 + k] = [
            4.0 * (dl[i][0] * l[j] + l[i] * dl[j][0]),
            4.0 * (dl[i][1] * l[j] + l[i] * dl[j][1]),
        ];
    }
    (n, dn)
}
