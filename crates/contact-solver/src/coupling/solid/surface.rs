//! Target surfaces of deformable bodies in 3D: the 3- or 6-node triangles of another body's
//! boundary, for node-to-face zones and for the normals of node-pair zones.
//!
//! # Projection and frame
//! A contactor node `p` is projected on each face by Gauss–Newton on the face's map
//! `X(ξ, η) = Σ N_i(ξ, η) x_i` (exact in one step on a flat 3-node face, a few steps on a
//! curved 6-node one). Among the faces whose projection falls inside (barycentric coordinates
//! `≥ −1e-9`) the one of smallest `|gap|` is kept; faces that contain the node itself are
//! skipped. The normal is the face's unit normal `∂X/∂ξ × ∂X/∂η` at the point: outward of the
//! target body when the face's corners turn counter-clockwise seen from outside, as the faces of
//! [`SolidMesh`] do, so it points from the target towards the contactor. The tangents follow
//! [`tangent_frame`](super::tangent_frame). The gap is `n·(p − X)`, and the weights of the
//! target nodes are the shape values `N_i` at the point.
//!
//! A node above a convex edge or vertex of a faceted surface projects inside no face: it takes
//! the closest point of the closest face, and the mean normal of the faces around that edge or
//! vertex, when that edge or vertex is inside the surface (shared by two faces, or not on the
//! surface's border). A node beyond the surface's border is not a candidate, as a node beyond
//! a rigid obstacle's end is not.

use crate::coupling::space::{cross, dot, sub};
use crate::coupling::zone::{MAX_TARGETS, Projection, TargetSurface, check_node};
use crate::error::SolverError;
use fem_core::ElementKind;
use fem_core::Structure;
use fem_core::solid::{SolidMesh, triangle_shape};
use std::collections::{HashMap, HashSet};

/// Barycentric tolerance of "inside a face".
const INSIDE: f64 = 1e-9;

/// A target surface: 3- or 6-node triangles (corners counter-clockwise seen from outside the
/// target body, then for 6 nodes the mid-edge nodes of edges 0–1, 1–2, 2–0).
#[derive(Clone, Debug, PartialEq)]
pub struct TriSurface {
    nodes_per_face: usize,
    connectivity: Vec<usize>,
}

impl TriSurface {
    /// A surface from a flat connectivity, `nodes_per_face` (3 or 6) entries per face.
    ///
    /// # Errors
    /// [`SolverError::InvalidGeometry`] for another face size, an empty surface, a length
    /// that is not a multiple of the face size, or a face that repeats a node.
    pub fn new(nodes_per_face: usize, connectivity: Vec<usize>) -> Result<Self, SolverError> {
        if nodes_per_face != 3 && nodes_per_face != 6 {
            return Err(SolverError::InvalidGeometry(format!(
                "a target surface has 3- or 6-node triangles, not {nodes_per_face}-node faces"
            )));
        }
        if connectivity.is_empty() || !connectivity.len().is_multiple_of(nodes_per_face) {
            return Err(SolverError::InvalidGeometry(format!(
                "a target surface of {nodes_per_face}-node triangles needs a non-empty \
                 connectivity whose length is a multiple of {nodes_per_face}, got {}",
                connectivity.len()
            )));
        }
        for (face, f) in connectivity.chunks_exact(nodes_per_face).enumerate() {
            let mut sorted = f.to_vec();
            sorted.sort_unstable();
            sorted.dedup();
            if sorted.len() != nodes_per_face {
                return Err(SolverError::InvalidGeometry(format!(
                    "target face {face} repeats a node: {f:?}"
                )));
            }
        }
        Ok(Self {
            nodes_per_face,
            connectivity,
        })
    }

    /// The faces of `mesh`'s face set `set` (a physical surface), oriented outward.
    ///
    /// # Errors
    /// [`SolverError::Structure`] for an unknown set; [`SolverError::InvalidGeometry`] for an
    /// empty one.
    pub fn from_face_set(mesh: &SolidMesh, set: &str) -> Result<Self, SolverError> {
        let faces = mesh.face_set(set)?;
        let npf = match mesh.kind() {
            ElementKind::Tet4 => 3,
            ElementKind::Tet10 => 6,
            // a bilinear face split into two triangles would carry the target's reactions by
            // linear, not bilinear, shape functions: not the element's surface
            other => {
                return Err(SolverError::InvalidGeometry(format!(
                    "face set `{set}` of a {other:?} mesh: node-to-face targets are triangle \
                     surfaces (tetrahedral meshes); use a rigid obstacle or a tetrahedral \
                     target body"
                )));
            }
        };
        let connectivity: Vec<usize> = faces
            .iter()
            .flat_map(|&f| mesh.face_node_ids(f).collect::<Vec<_>>())
            .collect();
        if connectivity.is_empty() {
            return Err(SolverError::InvalidGeometry(format!(
                "face set `{set}` has no face"
            )));
        }
        Self::new(npf, connectivity)
    }

    /// Nodes per face (3 or 6).
    pub fn nodes_per_face(&self) -> usize {
        self.nodes_per_face
    }

    /// Number of faces.
    pub fn face_count(&self) -> usize {
        self.connectivity.len() / self.nodes_per_face
    }

    /// The nodes of face `k`.
    ///
    /// # Panics
    /// If `k >= face_count()`.
    #[track_caller]
    pub fn face(&self, k: usize) -> &[usize] {
        &self.connectivity[k * self.nodes_per_face..(k + 1) * self.nodes_per_face]
    }

    /// Every node of the surface (sorted, without repeats).
    pub fn nodes(&self) -> Vec<usize> {
        let mut n = self.connectivity.clone();
        n.sort_unstable();
        n.dedup();
        n
    }
}

impl TargetSurface<3> for TriSurface {
    fn check<S: Structure<3> + ?Sized>(&self, s: &S, zone: &str) -> Result<(), SolverError> {
        self.connectivity
            .iter()
            .try_for_each(|&n| check_node(s, zone, n))
    }

    fn project_all<S: Structure<3> + ?Sized>(
        &self,
        s: &S,
        _zone: &str,
        nodes: &[usize],
    ) -> Result<Vec<Option<Projection<3>>>, SolverError> {
        let topo = Topology::new(s, self);
        Ok(nodes
            .iter()
            .map(|&node| project_on_surface(s, self, &topo, node))
            .collect())
    }

    fn node_normals<S: Structure<3> + ?Sized>(&self, s: &S) -> HashMap<usize, [f64; 3]> {
        node_normals(s, self)
    }
}

/// A point of a face: position, unit normal, surface Jacobian and shape values.
#[derive(Clone, Copy, Debug)]
struct FaceEval {
    x: [f64; 3],
    normal: [f64; 3],
    jac: f64,
    n: [f64; 6],
}

/// The face's map at `xi`: shape values, position and the two tangent vectors `∂X/∂ξ`,
/// `∂X/∂η`.
fn map_at<S: Structure<3> + ?Sized>(
    s: &S,
    face: &[usize],
    xi: [f64; 2],
) -> ([f64; 6], [f64; 3], [[f64; 3]; 2]) {
    let (n, dn) = triangle_shape(face.len(), xi);
    let mut x = [0.0; 3];
    let mut d = [[0.0; 3]; 2];
    for (i, &node) in face.iter().enumerate() {
        let p = s.node_position(node);
        for a in 0..3 {
            x[a] += n[i] * p[a];
            d[0][a] += dn[i][0] * p[a];
            d[1][a] += dn[i][1] * p[a];
        }
    }
    (n, x, d)
}

fn eval<S: Structure<3> + ?Sized>(s: &S, face: &[usize], xi: [f64; 2]) -> FaceEval {
    let (n, x, d) = map_at(s, face, xi);
    let c = cross(d[0], d[1]);
    let jac = dot(c, c).sqrt();
    FaceEval {
        x,
        normal: if jac > 0.0 { c.map(|v| v / jac) } else { c },
        jac,
        n,
    }
}

/// `(ξ, η)` of the point of `face` closest to `p` (Gauss–Newton on the face's map; the
/// parameters may fall outside the triangle).
fn project_params<S: Structure<3> + ?Sized>(s: &S, face: &[usize], p: [f64; 3]) -> [f64; 2] {
    let mut xi = [1.0 / 3.0, 1.0 / 3.0];
    let iterations = if face.len() == 3 { 1 } else { 25 };
    for _ in 0..iterations {
        let (_, x, d) = map_at(s, face, xi);
        let r = sub(p, x);
        let (a11, a12, a22) = (dot(d[0], d[0]), dot(d[0], d[1]), dot(d[1], d[1]));
        let (b1, b2) = (dot(d[0], r), dot(d[1], r));
        let det = a11 * a22 - a12 * a12;
        if !(det > 0.0 && det.is_finite()) {
            break;
        }
        let step = [(a22 * b1 - a12 * b2) / det, (a11 * b2 - a12 * b1) / det];
        // keep the iterate near the triangle (a curved face's map is only meaningful there)
        xi = [
            (xi[0] + step[0]).clamp(-0.5, 1.5),
            (xi[1] + step[1]).clamp(-0.5, 1.5),
        ];
        if step[0].abs() + step[1].abs() < 1e-14 {
            break;
        }
    }
    xi
}

/// The point of the reference triangle closest to `xi` in parameter space.
fn clamp_to_triangle(xi: [f64; 2]) -> [f64; 2] {
    let (mut a, mut b) = (xi[0].max(0.0), xi[1].max(0.0));
    let excess = a + b - 1.0;
    if excess > 0.0 {
        a -= 0.5 * excess;
        b -= 0.5 * excess;
        if a < 0.0 {
            (a, b) = (0.0, 1.0);
        } else if b < 0.0 {
            (a, b) = (1.0, 0.0);
        }
    }
    [a, b]
}

/// The surface's topology for the convex-edge fallback: how many faces share each corner
/// edge, and which corners lie on the border.
struct Topology {
    edges: HashMap<(usize, usize), Vec<usize>>,
    corner_faces: HashMap<usize, Vec<usize>>,
    border_corners: HashSet<usize>,
    boxes: Vec<([f64; 3], [f64; 3])>,
}

fn key(a: usize, b: usize) -> (usize, usize) {
    (a.min(b), a.max(b))
}

impl Topology {
    fn new<S: Structure<3> + ?Sized>(s: &S, surface: &TriSurface) -> Self {
        let mut edges: HashMap<(usize, usize), Vec<usize>> = HashMap::new();
        let mut corner_faces: HashMap<usize, Vec<usize>> = HashMap::new();
        let mut boxes = Vec::with_capacity(surface.face_count());
        for k in 0..surface.face_count() {
            let f = surface.face(k);
            for (i, j) in [(0, 1), (1, 2), (2, 0)] {
                edges.entry(key(f[i], f[j])).or_default().push(k);
            }
            for &c in &f[..3] {
                corner_faces.entry(c).or_default().push(k);
            }
            let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
            for &node in f {
                let x = s.node_position(node);
                for a in 0..3 {
                    lo[a] = lo[a].min(x[a]);
                    hi[a] = hi[a].max(x[a]);
                }
            }
            boxes.push((lo, hi));
        }
        let border_corners = edges
            .iter()
            .filter(|(_, f)| f.len() == 1)
            .flat_map(|(&(a, b), _)| [a, b])
            .collect();
        Self {
            edges,
            corner_faces,
            border_corners,
            boxes,
        }
    }
}

/// Distance from `p` to the box `(lo, hi)`.
fn box_distance(p: [f64; 3], (lo, hi): &([f64; 3], [f64; 3])) -> f64 {
    let mut d2 = 0.0;
    for a in 0..3 {
        let d = (lo[a] - p[a]).max(p[a] - hi[a]).max(0.0);
        d2 += d * d;
    }
    d2.sqrt()
}

/// The target of `node` on `surface` (module docs), or `None`.
fn project_on_surface<S: Structure<3> + ?Sized>(
    s: &S,
    surface: &TriSurface,
    topo: &Topology,
    node: usize,
) -> Option<Projection<3>> {
    let p = s.node_position(node);
    // the inside projection of smallest |gap|, and the closest clamped point of the others
    let mut best: Option<(f64, usize, [f64; 2])> = None;
    let mut nearest: Option<(f64, usize, [f64; 2])> = None;
    for k in 0..surface.face_count() {
        let face = surface.face(k);
        if face.contains(&node) {
            continue;
        }
        let bound = best
            .map_or(f64::INFINITY, |b| b.0)
            .min(nearest.map_or(f64::INFINITY, |n| n.0));
        if box_distance(p, &topo.boxes[k]) > bound * (1.0 + 1e-9) {
            continue;
        }
        let xi = project_params(s, face, p);
        let l = [1.0 - xi[0] - xi[1], xi[0], xi[1]];
        if l.iter().all(|&v| v >= -INSIDE) {
            let e = eval(s, face, xi);
            let gap = dot(e.normal, sub(p, e.x)).abs();
            if best.is_none_or(|(g, ..)| gap < g) {
                best = Some((gap, k, xi));
            }
        } else {
            let c = clamp_to_triangle(xi);
            let e = eval(s, face, c);
            let d = norm(sub(p, e.x));
            if nearest.is_none_or(|(n, ..)| d < n) {
                nearest = Some((d, k, c));
            }
        }
    }
    let inside = best.map(|(_, k, xi)| {
        let face = surface.face(k);
        let e = eval(s, face, xi);
        hit(face, &e, e.normal, p)
    });
    match (best, nearest) {
        // a closer edge or corner than every inside projection: the node is above it
        (Some((g, ..)), Some((d, k, xi))) if d < g * (1.0 - 1e-9) => {
            edge_hit(s, surface, topo, p, k, xi).or(inside)
        }
        (None, Some((_, k, xi))) => edge_hit(s, surface, topo, p, k, xi),
        _ => inside,
    }
}

/// The target on the edge or corner of face `k` where its clamped point `xi` lies, with the
/// mean normal of the faces around it; `None` on the surface's border.
fn edge_hit<S: Structure<3> + ?Sized>(
    s: &S,
    surface: &TriSurface,
    topo: &Topology,
    p: [f64; 3],
    k: usize,
    xi: [f64; 2],
) -> Option<Projection<3>> {
    let face = surface.face(k);
    let e = eval(s, face, xi);
    let l = [1.0 - xi[0] - xi[1], xi[0], xi[1]];
    let zero: Vec<usize> = (0..3).filter(|&i| l[i] <= 1e-12).collect();
    let around: &[usize] = match zero.as_slice() {
        [i] => {
            // on the edge opposite corner i
            let (a, b) = (face[(i + 1) % 3], face[(i + 2) % 3]);
            let faces = topo.edges.get(&key(a, b))?;
            if faces.len() < 2 {
                return None; // the surface's border
            }
            faces
        }
        [i, j] => {
            let c = face[3 - i - j];
            if topo.border_corners.contains(&c) {
                return None;
            }
            topo.corner_faces.get(&c)?
        }
        _ => return None,
    };
    let mut n = [0.0; 3];
    for &f in around {
        let fe = eval(s, surface.face(f), [1.0 / 3.0, 1.0 / 3.0]);
        for (v, c) in n.iter_mut().zip(fe.normal) {
            *v += c * fe.jac;
        }
    }
    let len = norm(n);
    if !(len > 0.0 && len.is_finite()) {
        return None;
    }
    Some(hit(face, &e, n.map(|v| v / len), p))
}

fn hit(face: &[usize], e: &FaceEval, normal: [f64; 3], p: [f64; 3]) -> Projection<3> {
    let mut targets = [None; MAX_TARGETS];
    for (i, &node) in face.iter().enumerate() {
        targets[i] = Some((node, e.n[i]));
    }
    Projection {
        targets,
        point: e.x,
        normal,
        gap: dot(normal, sub(p, e.x)),
    }
}

/// The unit normal of `surface` at each of its nodes: the mean of the normals of the faces
/// around the node, at the node, weighted by their surface Jacobians there. A node whose
/// normals cancel (a knife edge) has none.
fn node_normals<S: Structure<3> + ?Sized>(s: &S, surface: &TriSurface) -> HashMap<usize, [f64; 3]> {
    // reference coordinates of the six nodes of a triangle
    const AT: [[f64; 2]; 6] = [
        [0.0, 0.0],
        [1.0, 0.0],
        [0.0, 1.0],
        [0.5, 0.0],
        [0.5, 0.5],
        [0.0, 0.5],
    ];
    let mut sum: HashMap<usize, [f64; 3]> = HashMap::new();
    for k in 0..surface.face_count() {
        let face = surface.face(k);
        for (i, &node) in face.iter().enumerate() {
            let e = eval(s, face, AT[i]);
            let n = sum.entry(node).or_insert([0.0; 3]);
            for (v, c) in n.iter_mut().zip(e.normal) {
                *v += c * e.jac;
            }
        }
    }
    sum.into_iter()
        .filter_map(|(node, n)| {
            let len = norm(n);
            (len > 0.0 && len.is_finite()).then(|| (node, n.map(|v| v / len)))
        })
        .collect()
}

#[inline]
fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}
