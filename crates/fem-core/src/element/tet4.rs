//! The 4-node linear tetrahedron (P1).
//!
//! Corners `0, 1, 2, 3` with `(x₁ − x₀, x₂ − x₀, x₃ − x₀)` a right-handed triad; shape
//! functions the barycentric coordinates `N = (1 − ξ − η − ζ, ξ, η, ζ)`.

use super::{Element, QuadPoint, Topology};
use crate::quadrature::{TET_1, conical_rule};
use std::sync::OnceLock;

/// The 4-node linear tetrahedron: stiffness at the centroid (its strain is constant); loads
/// and mass with the 64-point conical rule (degree 5).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Tet4;

/// The faces of a 4-node tetrahedron, corners counter-clockwise seen from outside:
///
/// ```text
/// face 0: 0 2 1 (opposite corner 3)    face 2: 1 2 3 (opposite corner 0)
/// face 1: 0 1 3 (opposite corner 2)    face 3: 0 3 2 (opposite corner 1)
/// ```
pub const FACES: [&[usize]; 4] = [&[0, 2, 1], &[0, 1, 3], &[1, 2, 3], &[0, 3, 2]];

/// The 64-point conical rule (degree 5) for the loads and error norms of tetrahedra, built
/// once.
pub(crate) fn tet_load_rule() -> &'static [QuadPoint<3>] {
    static RULE: OnceLock<Vec<QuadPoint<3>>> = OnceLock::new();
    RULE.get_or_init(|| conical_rule(4))
}

/// The barycentric coordinates and their (constant) derivatives.
pub(crate) const DL: [[f64; 3]; 4] = [
    [-1.0, -1.0, -1.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
];

impl Element<3> for Tet4 {
    #[inline]
    fn node_count(&self) -> usize {
        4
    }
    #[inline]
    fn shape(&self, xi: [f64; 3], n: &mut [f64], dn: &mut [[f64; 3]]) {
        n[..4].copy_from_slice(&[1.0 - xi[0] - xi[1] - xi[2], xi[0], xi[1], xi[2]]);
        dn[..4].copy_from_slice(&DL);
    }
    fn stiffness_rule(&self, _: &(), _: &[[f64; 3]]) -> &[QuadPoint<3>] {
        &TET_1
    }
    fn load_rule(&self, _: &()) -> &[QuadPoint<3>] {
        tet_load_rule()
    }
    fn topology(&self) -> Topology {
        Topology {
            corners: 4,
            sides: &FACES,
            vtk_cell: 10,
            gmsh_type: 4,
        }
    }
}
