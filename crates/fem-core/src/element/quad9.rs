//! The 9-node Lagrange (biquadratic) quadrilateral.
//!
//! Nodes as [`super::Quad8`], then the centre `8 (0, 0)` (Gmsh's and VTK's order). With the
//! 1D quadratics `l₋(s) = s(s − 1)/2`, `l₀(s) = 1 − s²`, `l₊(s) = s(s + 1)/2`:
//! ```text
//! N_i(ξ, η) = l_{ξ_i}(ξ) l_{η_i}(η)
//! ```

use super::quad4::CORNERS;
use super::quad8::{MIDS, SIDES};
use super::{Element, QuadPoint, Topology};
use crate::idealization::Idealization;
use crate::quadrature::tensor_rule;

/// The 9-node Lagrange quadrilateral (plane strain, plane stress, axisymmetry): stiffness and
/// stresses with the full 3×3 Gauss rule, loads and mass with 4×4.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Quad9;

/// The 1D quadratic Lagrange polynomial of node `c ∈ {−1, 0, 1}` and its derivative at `s`.
#[inline]
pub(crate) fn lagrange2(c: f64, s: f64) -> (f64, f64) {
    if c == 0.0 {
        (1.0 - s * s, -2.0 * s)
    } else {
        (0.5 * s * (s + c), s + 0.5 * c)
    }
}

impl Element<2> for Quad9 {
    #[inline]
    fn node_count(&self) -> usize {
        9
    }
    fn shape(&self, xi: [f64; 2], n: &mut [f64], dn: &mut [[f64; 2]]) {
        for (i, c) in CORNERS.iter().chain(&MIDS).chain(&[[0.0, 0.0]]).enumerate() {
            let (a, da) = lagrange2(c[0], xi[0]);
            let (b, db) = lagrange2(c[1], xi[1]);
            n[i] = a * b;
            dn[i] = [da * b, a * db];
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
            vtk_cell: 28,
            gmsh_type: 10,
        }
    }
}
