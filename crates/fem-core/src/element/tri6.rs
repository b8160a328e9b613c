//! The 6-node quadratic isoparametric triangle (P2).
//!
//! With barycentric coordinates `L0 = 1 − ξ − η`, `L1 = ξ`, `L2 = η`:
//! ```text
//! corners  N_i = L_i (2 L_i − 1),       i = 0, 1, 2
//! mid-side N_3 = 4 L0 L1, N_4 = 4 L1 L2, N_5 = 4 L2 L0
//! ```

/// Shape functions of the 6-node triangle at `(ξ, η)`.
#[inline]
pub fn shape(xi: [f64; 2], n: &mut [f64]) {
    let (l1, l2) = (xi[0], xi[1]);
    let l0 = 1.0 - l1 - l2;
    n[0] = l0 * (2.0 * l0 - 1.0);
    n[1] = l1 * (2.0 * l1 - 1.0);
    n[2] = l2 * (2.0 * l2 - 1.0);
    n[3] = 4.0 * l0 * l1;
    n[4] = 4.0 * l1 * l2;
    n[5] = 4.0 * l2 * l0;
}

/// Derivatives `(∂N/∂ξ, ∂N/∂η)` of the shape functions at `(ξ, η)`.
#[inline]
pub fn shape_derivatives(xi: [f64; 2], dn: &mut [[f64; 2]]) {
    let (l1, l2) = (xi[0], xi[1]);
    let l0 = 1.0 - l1 - l2;
    // ∂L0 = (−1, −1), ∂L1 = (1, 0), ∂L2 = (0, 1)
    dn[0] = [-(4.0 * l0 - 1.0), -(4.0 * l0 - 1.0)];
    dn[1] = [4.0 * l1 - 1.0, 0.0];
    dn[2] = [0.0, 4.0 * l2 - 1.0];
    dn[3] = [4.0 * (l0 - l1), -4.0 * l1];
    dn[4] = [4.0 * l2, 4.0 * l1];
    dn[5] = [-4.0 * l2, 4.0 * (l0 - l2)];
}

use super::{Element, QuadPoint, Topology};
use crate::idealization::Idealization;
use crate::quadrature::{TRI_3, TRI_6, TRI_7};

/// The 6-node quadratic isoparametric triangle: corners `0, 1, 2` counter-clockwise, then the
/// mid-side nodes `3` (0–1), `4` (1–2), `5` (2–0) — Gmsh's and VTK's order. Stiffness with 3
/// points (6 in axisymmetry), loads with 6, mass with 7 (degree 5).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Tri6;

/// The sides of a 6-node triangle (corners, then the mid-side node).
pub const SIDES: [&[usize]; 3] = [&[0, 1, 3], &[1, 2, 4], &[2, 0, 5]];

impl Element<2> for Tri6 {
    #[inline]
    fn node_count(&self) -> usize {
        6
    }
    #[inline]
    fn shape(&self, xi: [f64; 2], n: &mut [f64], dn: &mut [[f64; 2]]) {
        shape(xi, n);
        shape_derivatives(xi, dn);
    }
    fn stiffness_rule(&self, setting: &Idealization, _: &[[f64; 2]]) -> &[QuadPoint<2>] {
        match setting {
            Idealization::Axisymmetric => &TRI_6,
            _ => &TRI_3,
        }
    }
    fn load_rule(&self, _: &Idealization) -> &[QuadPoint<2>] {
        &TRI_6
    }
    fn mass_rule(&self, _: &Idealization) -> &[QuadPoint<2>] {
        &TRI_7
    }
    fn topology(&self) -> Topology {
        Topology {
            corners: 3,
            sides: &SIDES,
            vtk_cell: 22,
            gmsh_type: 9,
        }
    }
}
