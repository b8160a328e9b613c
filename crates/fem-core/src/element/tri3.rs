//! The 3-node linear triangle (P1).

/// Shape functions of the 3-node triangle at `(ξ, η)`: `N = (1 − ξ − η, ξ, η)`.
#[inline]
pub fn shape(xi: [f64; 2], n: &mut [f64]) {
    n[0] = 1.0 - xi[0] - xi[1];
    n[1] = xi[0];
    n[2] = xi[1];
}

/// Derivatives `(∂N/∂ξ, ∂N/∂η)` of the shape functions (constant).
#[inline]
pub fn shape_derivatives(_xi: [f64; 2], dn: &mut [[f64; 2]]) {
    dn[0] = [-1.0, -1.0];
    dn[1] = [1.0, 0.0];
    dn[2] = [0.0, 1.0];
}

use super::{Element, QuadPoint, Topology};
use crate::idealization::Idealization;
use crate::quadrature::{TRI_1, TRI_3, TRI_6};

/// The 3-node linear triangle: corners `0, 1, 2` counter-clockwise. Stiffness at the
/// centroid (its strain is constant), or with 3 points in axisymmetry (the hoop strain is
/// not); loads with 3 points; mass with 6.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Tri3;

/// The sides of a 3-node triangle.
pub const SIDES: [&[usize]; 3] = [&[0, 1], &[1, 2], &[2, 0]];

impl Element<2> for Tri3 {
    #[inline]
    fn node_count(&self) -> usize {
        3
    }
    #[inline]
    fn shape(&self, xi: [f64; 2], n: &mut [f64], dn: &mut [[f64; 2]]) {
        shape(xi, n);
        shape_derivatives(xi, dn);
    }
    fn stiffness_rule(&self, setting: &Idealization, _: &[[f64; 2]]) -> &[QuadPoint<2>] {
        match setting {
            Idealization::Axisymmetric => &TRI_3,
            _ => &TRI_1,
        }
    }
    fn load_rule(&self, _: &Idealization) -> &[QuadPoint<2>] {
        &TRI_3
    }
    fn mass_rule(&self, _: &Idealization) -> &[QuadPoint<2>] {
        &TRI_6
    }
    fn topology(&self) -> Topology {
        Topology {
            corners: 3,
            sides: &SIDES,
            vtk_cell: 5,
            gmsh_type: 2,
        }
    }
}
