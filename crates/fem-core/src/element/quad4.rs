//! The 4-node bilinear quadrilateral (Q1).
//!
//! Reference square `[−1, 1]²`, corners `0 (−1,−1), 1 (1,−1), 2 (1,1), 3 (−1,1)`
//! counter-clockwise (Gmsh's and VTK's order):
//! ```text
//! N_i = ¼ (1 + ξ ξ_i)(1 + η η_i)
//! ```

use super::{Element, QuadPoint, Topology};
use crate::idealization::Idealization;
use crate::quadrature::tensor_rule;

/// The 4-node quadrilateral (plane strain, plane stress, axisymmetry): stiffness and stresses
/// with the full 2×2 Gauss rule, loads and mass with 3×3.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Quad4;

/// The reference corners of a quadrilateral.
pub(crate) const CORNERS: [[f64; 2]; 4] = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];

/// The sides of a 4-node quadrilateral.
pub const SIDES: [&[usize]; 4] = [&[0, 1], &[1, 2], &[2, 3], &[3, 0]];

impl Element<2> for Quad4 {
    #[inline]
    fn node_count(&self) -> usize {
        4
    }
    fn shape(&self, xi: [f64; 2], n: &mut [f64], dn: &mut [[f64; 2]]) {
        for (i, c) in CORNERS.iter().enumerate() {
            let (a, b) = (1.0 + xi[0] * c[0], 1.0 + xi[1] * c[1]);
            n[i] = 0.25 * a * b;
            dn[i] = [0.25 * c[0] * b, 0.25 * a * c[1]];
        }
    }
    fn stiffness_rule(&self, _: &Idealization, _: &[[f64; 2]]) -> &[QuadPoint<2>] {
        tensor_rule(2)
    }
    fn load_rule(&self, _: &Idealization) -> &[QuadPoint<2>] {
        tensor_rule(3)
    }
    fn topology(&self) -> Topology {
        Topology {
            corners: 4,
            sides: &SIDES,
            vtk_cell: 9,
            gmsh_type: 3,
        }
    }
}
