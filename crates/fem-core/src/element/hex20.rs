//! The 20-node serendipity hexahedron.
//!
//! Corners as [`super::Hex8`], then the mid-edge nodes in VTK's order (cell type 25): `8..12`
//! on the edges 0–1, 1–2, 2–3, 3–0 of the bottom, `12..16` on 4–5, 5–6, 6–7, 7–4 of the top,
//! `16..20` on the vertical edges 0–4, 1–5, 2–6, 3–7. Gmsh (type 17) numbers the mid-edge
//! nodes by edge 0–1, 0–3, 0–4, 1–2, 1–5, 2–3, 2–6, 3–7, 4–5, 4–7, 5–6, 6–7; the reader maps
//! them with [`GMSH_TO_LOCAL`].
//! ```text
//! corners   N_i = ⅛ (1 + ξ ξ_i)(1 + η η_i)(1 + ζ ζ_i)(ξ ξ_i + η η_i + ζ ζ_i − 2)
//! ξ_i = 0   N_i = ¼ (1 − ξ²)(1 + η η_i)(1 + ζ ζ_i)   (and likewise for η_i = 0, ζ_i = 0)
//! ```

use super::hex8::CORNERS;
use super::{Element, QuadPoint, Topology};
use crate::quadrature::tensor_rule;

/// The 20-node hexahedron: stiffness and stresses with the full 3×3×3 Gauss rule, loads and
/// mass with 4×4×4.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Hex20;

/// The corner pairs of the mid-edge nodes `8..20`.
pub const EDGES: [[usize; 2]; 12] = [
    [0, 1],
    [1, 2],
    [2, 3],
    [3, 0],
    [4, 5],
    [5, 6],
    [6, 7],
    [7, 4],
    [0, 4],
    [1, 5],
    [2, 6],
    [3, 7],
];

/// `GMSH_TO_LOCAL[k]` is the local (VTK) index of Gmsh's node `k` of a 20-node hexahedron.
pub const GMSH_TO_LOCAL: [usize; 20] = [
    0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 16, 9, 17, 10, 18, 19, 12, 15, 13, 14,
];

/// The faces of a 20-node hexahedron: the corners of [`super::hex8::FACES`], then the
/// mid-edge nodes of the face's edges (c0–c1, c1–c2, c2–c3, c3–c0).
pub const FACES: [&[usize]; 6] = [
    &[0, 3, 2, 1, 11, 10, 9, 8],
    &[0, 1, 5, 4, 8, 17, 12, 16],
    &[1, 2, 6, 5, 9, 18, 13, 17],
    &[2, 3, 7, 6, 10, 19, 14, 18],
    &[3, 0, 4, 7, 11, 16, 15, 19],
    &[4, 5, 6, 7, 12, 13, 14, 15],
];

/// The reference position of node `i`.
fn node(i: usize) -> [f64; 3] {
    if i < 8 {
        CORNERS[i]
    } else {
        let [a, b] = EDGES[i - 8];
        core::array::from_fn(|c| 0.5 * (CORNERS[a][c] + CORNERS[b][c]))
    }
}

impl Element<3> for Hex20 {
    #[inline]
    fn node_count(&self) -> usize {
        20
    }
    fn shape(&self, xi: [f64; 3], n: &mut [f64], dn: &mut [[f64; 3]]) {
        for i in 0..20 {
            let c = node(i);
            let f: [f64; 3] = core::array::from_fn(|a| 1.0 + xi[a] * c[a]);
            if i < 8 {
                let s = xi[0] * c[0] + xi[1] * c[1] + xi[2] * c[2] - 2.0;
                let p = f[0] * f[1] * f[2];
                n[i] = 0.125 * p * s;
                // ∂/∂ξ_a = ⅛ c_a (Π_{b≠a} f_b · s + p)
                dn[i] = core::array::from_fn(|a| {
                    let others = f[(a + 1) % 3] * f[(a + 2) % 3];
                    0.125 * c[a] * (others * s + p)
                });
            } else {
                // the zero coordinate of the node is the bubble direction
                let z = (0..3).find(|&a| c[a] == 0.0).unwrap_or(0);
                let (o1, o2) = ((z + 1) % 3, (z + 2) % 3);
                let bubble = 1.0 - xi[z] * xi[z];
                n[i] = 0.25 * bubble * f[o1] * f[o2];
                let mut d = [0.0; 3];
                d[z] = -0.5 * xi[z] * f[o1] * f[o2];
                d[o1] = 0.25 * bubble * c[o1] * f[o2];
                d[o2] = 0.25 * bubble * f[o1] * c[o2];
                dn[i] = d;
            }
        }
    }
    fn stiffness_rule(&self, _: &(), _: &[[f64; 3]]) -> &[QuadPoint<3>] {
        tensor_rule(3)
    }
    fn load_rule(&self, _: &()) -> &[QuadPoint<3>] {
        tensor_rule(4)
    }
    fn topology(&self) -> Topology {
        Topology {
            corners: 8,
            sides: &FACES,
            vtk_cell: 25,
            gmsh_type: 17,
        }
    }
}
