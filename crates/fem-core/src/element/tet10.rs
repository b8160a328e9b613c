//! The 10-node quadratic isoparametric tetrahedron (P2).
//!
//! Corners as [`super::Tet4`], then the mid-edge nodes `4` (edge 0–1), `5` (1–2), `6` (2–0),
//! `7` (0–3), `8` (1–3), `9` (2–3): VTK's order (Gmsh swaps the last two; the reader swaps
//! them back). With barycentric `L_i`:
//! ```text
//! corners N_i = L_i (2 L_i − 1),   mid-edge N_k = 4 L_i L_j
//! ```

use super::tet4::{DL, tet_load_rule};
use super::{Element, QuadPoint, Topology};
use crate::quadrature::{TET_4, conical_rule};
use std::sync::OnceLock;

/// The 10-node tetrahedron: stiffness with Keast's 4-point rule (exact for straight sides),
/// or a degree-3 conical rule when a mid-edge node is off its edge's midpoint (so that curved
/// meshes pass the patch test); stresses at the 4 points; loads and mass with the 64-point
/// conical rule (degree 5).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Tet10;

/// The faces of a 10-node tetrahedron: the corners of [`super::tet4::FACES`], then the
/// mid-edge nodes of the face's edges (c0–c1, c1–c2, c2–c0).
pub const FACES: [&[usize]; 4] = [
    &[0, 2, 1, 6, 5, 4],
    &[0, 1, 3, 4, 8, 7],
    &[1, 2, 3, 5, 9, 8],
    &[0, 3, 2, 7, 9, 6],
];

/// The edges of a tetrahedron, in the order of the P2 mid-edge nodes `4..10`.
pub const TET_EDGES: [[usize; 2]; 6] = [[0, 1], [1, 2], [2, 0], [0, 3], [1, 3], [2, 3]];

#[inline]
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[inline]
fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// Whether a 10-node element has a mid-edge node off the midpoint of its edge (by more than
/// `1e-12` of the edge's length).
fn is_curved(coords: &[[f64; 3]]) -> bool {
    TET_EDGES.iter().enumerate().any(|(k, &[i, j])| {
        let (a, b, m) = (coords[i], coords[j], coords[4 + k]);
        let d = sub(b, a);
        let off: [f64; 3] = core::array::from_fn(|c| m[c] - 0.5 * (a[c] + b[c]));
        dot(off, off) > 1e-24 * dot(d, d)
    })
}

impl Element<3> for Tet10 {
    #[inline]
    fn node_count(&self) -> usize {
        10
    }
    fn shape(&self, xi: [f64; 3], n: &mut [f64], dn: &mut [[f64; 3]]) {
        let l = [1.0 - xi[0] - xi[1] - xi[2], xi[0], xi[1], xi[2]];
        for i in 0..4 {
            n[i] = l[i] * (2.0 * l[i] - 1.0);
            dn[i] = DL[i].map(|d| (4.0 * l[i] - 1.0) * d);
        }
        for (k, [i, j]) in TET_EDGES.into_iter().enumerate() {
            n[4 + k] = 4.0 * l[i] * l[j];
            dn[4 + k] = core::array::from_fn(|c| 4.0 * (DL[i][c] * l[j] + l[i] * DL[j][c]));
        }
    }
    fn stiffness_rule(&self, _: &(), coords: &[[f64; 3]]) -> &[QuadPoint<3>] {
        if coords.len() == 10 && is_curved(coords) {
            static CURVED: OnceLock<Vec<QuadPoint<3>>> = OnceLock::new();
            CURVED.get_or_init(|| conical_rule(3))
        } else {
            &TET_4
        }
    }
    fn stress_rule(&self, _: &(), _: &[[f64; 3]]) -> &[QuadPoint<3>] {
        &TET_4
    }
    fn load_rule(&self, _: &()) -> &[QuadPoint<3>] {
        tet_load_rule()
    }
    fn topology(&self) -> Topology {
        Topology {
            corners: 4,
            sides: &FACES,
            vtk_cell: 24,
            gmsh_type: 11,
        }
    }
}
