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
