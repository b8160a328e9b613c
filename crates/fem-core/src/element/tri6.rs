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
