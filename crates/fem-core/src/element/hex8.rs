//! The 8-node trilinear hexahedron (Q1).
//!
//! Reference cube `[−1, 1]³`; corners `0..4` on `ζ = −1` counter-clockwise seen from `+ζ`
//! (`(−1,−1), (1,−1), (1,1), (−1,1)`), then `4..8` above them on `ζ = 1` (Gmsh's and VTK's
//! order):
//! ```text
//! N_i = ⅛ (1 + ξ ξ_i)(1 + η η_i)(1 + ζ ζ_i)
//! ```

use super::{Element, QuadPoint, Topology};
use crate::quadrature::tensor_rule;

/// The 8-node hexahedron: stiffness and stresses with the full 2×2×2 Gauss rule, loads and
/// mass with 3×3×3.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Hex8;

/// The reference corners of a hexahedron.
pub(crate) const CORNERS: [[f64; 3]; 8] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
];

/// The faces of an 8-node hexahedron, corners counter-clockwise seen from outside:
/// `ζ = −1, η = −1, ξ = 1, η = 1, ξ = −1, ζ = 1`.
pub const FACES: [&[usize]; 6] = [
    &[0, 3, 2, 1],
    &[0, 1, 5, 4],
    &[1, 2, 6, 5],
    &[2, 3, 7, 6],
    &[3, 0, 4, 7],
    &[4, 5, 6, 7],
];

impl Element<3> for Hex8 {
    #[inline]
    fn node_count(&self) -> usize {
        8
    }
    fn shape(&self, xi: [f64; 3], n: &mut [f64], dn: &mut [[f64; 3]]) {
        for (i, c) in CORNERS.iter().enumerate() {
            let f: [f64; 3] = core::array::from_fn(|a| 1.0 + xi[a] * c[a]);
            n[i] = 0.125 * f[0] * f[1] * f[2];
            dn[i] = [
                0.125 * c[0] * f[1] * f[2],
                0.125 * f[0] * c[1] * f[2],
                0.125 * f[0] * f[1] * c[2],
            ];
        }
    }
    fn stiffness_rule(&self, _: &(), _: &[[f64; 3]]) -> &[QuadPoint<3>] {
        tensor_rule(2)
    }
    fn load_rule(&self, _: &()) -> &[QuadPoint<3>] {
        tensor_rule(3)
    }
    fn topology(&self) -> Topology {
        Topology {
            corners: 8,
            sides: &FACES,
            vtk_cell: 12,
            gmsh_type: 5,
        }
    }
}
