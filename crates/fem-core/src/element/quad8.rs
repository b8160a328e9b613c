//! The 8-node serendipity quadrilateral.
//!
//! Corners as [`super::Quad4`], then the mid-side nodes `4 (0,−1), 5 (1,0), 6 (0,1),
//! 7 (−1,0)` (Gmsh's and VTK's order):
//! ```text
//! corners  N_i = ¼ (1 + ξ ξ_i)(1 + η η_i)(ξ ξ_i + η η_i − 1)
//! ξ_i = 0  N_i = ½ (1 − ξ²)(1 + η η_i)        η_i = 0  N_i = ½ (1 + ξ ξ_i)(1 − η²)
//! ```

use super::quad4::CORNERS;
use super::{Element, QuadPoint, Topology};
use crate::idealization::Idealization;
use crate::quadrature::tensor_rule;

/// The 8-node serendipity quadrilateral (plane strain, plane stress, axisymmetry): stiffness
/// and stresses with the full 3×3 Gauss rule, loads and mass with 4×4.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Quad8;

/// The reference mid-side nodes of a quadratic quadrilateral.
pub(crate) const MIDS: [[f64; 2]; 4] = [[0.0, -1.0], [1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]];

/// The sides of an 8- or 9-node quadrilateral (corners, then the mid-side node).
pub const SIDES: [&[usize]; 4] = [&[0, 1, 4], &[1, 2, 5], &[2, 3, 6], &[3, 0, 7]];

impl Element<2> for Quad8 {
    #[inline]
    fn node_count(&self) -> usize {
        8
    }
    fn shape(&self, xi: [f64; 2], n: &mut [f64], dn: &mut [[f64; 2]]) {
        let [x, y] = xi;
        for (i, c) in CORNERS.iter().enumerate() {
            let (a, b, s) = (1.0 + x * c[0], 1.0 + y * c[1], x * c[0] + y * c[1] - 1.0);
            n[i] = 0.25 * a * b * s;
            dn[i] = [0.25 * c[0] * b * (s + a), 0.25 * c[1] * a * (s + b)];
        }
        for (k, m) in MIDS.iter().enumerate() {
            let i = 4 + k;
            if m[0] == 0.0 {
                n[i] = 0.5 * (1.0 - x * x) * (1.0 + y * m[1]);
                dn[i] = [-x * (1.0 + y * m[1]), 0.5 * (1.0 - x * x) * m[1]];
            } else {
                n[i] = 0.5 * (1.0 + x * m[0]) * (1.0 - y * y);
                dn[i] = [0.5 * m[0] * (1.0 - y * y), -y * (1.0 + x * m[0])];
            }
        }
    }
    fn stiffness_rule(&self, _: &Idealization, _: &[[f64; 2]]) -> &[QuadPoint<2>] {
        tensor_rule(3)
    }
    fn load_rule(&self, _: &Idealization) -> &[QuadPoint<2>] {
        tensor_rule(4)
    }
    fn topology(&self) -> Topology {
        Topology {
            corners: 4,
            sides: &SIDES,
            vtk_cell: 23,
            gmsh_type: 16,
        }
    }
}
