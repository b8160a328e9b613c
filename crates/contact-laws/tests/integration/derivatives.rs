//! Finite-difference checks that the laws derive from their bipotentials (seed 4.29, 4.73,
//! 4.80): on extremal pairs, `r ∈ ∂_{−u̇} b_c(−u̇, r)` and `G ∈ ∂_{β̇} b_β(β̇, G)`, where the
//! bipotentials are differentiable (slip with `‖u̇_t‖ > 0`; damaging with `α > 0`).
//!
//! Method: central differences along random directions (GetFEM's check of projections and
//! tangents), step `h = 1e-6` relative, tolerance `1e-6` relative (truncation error is zero for
//! these piecewise linear/quadratic functions away from kinks; rounding dominates).

use contact_laws::strategies::{magnitude, non_negative};
use contact_laws::{CoulombCone, LocalVec2, adhesion_bipotential, contact_bipotential};
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(10_000))]

    #[test]
    fn slip_reaction_is_the_gradient_of_b_c(
        mu in magnitude(), r_n in magnitude(), lambda in magnitude(), sign in prop_oneof![Just(1.0), Just(-1.0)],
    ) {
        // Slip pair: r = (r_n, s μ r_n), u̇ = (0, −s λ). Along y = −u̇_t, b_c = μ r_n |y|, whose
        // derivative is μ r_n sign(y) = r_t.
        let cone = CoulombCone::new(mu).unwrap();
        let r = LocalVec2::planar(r_n, sign * mu * r_n);
        let y = sign * lambda; // −u̇_t
        let h = 1e-6 * lambda;
        let b = |y: f64| contact_bipotential(&cone, &LocalVec2::planar(0.0, -y), &r);
        let fd = (b(y + h) - b(y - h)) / (2.0 * h);
        prop_assert!((fd - r.t[0]).abs() <= 1e-6 * r.t[0].abs(), "∂b/∂(−u̇_t) = {fd}, r_t = {}", r.t[0]);
    }

    #[test]
    fn normal_reaction_is_the_gradient_of_b_c_in_the_normal_opening(
        mu in non_negative(), r_n in magnitude(), un in magnitude(), ut in magnitude(),
    ) {
        // While the contact opens (u̇_n > 0), b_c does not depend on −u̇_n: its derivative
        // there is 0, so the only reaction it can derive is r_n = 0 (separation). A compressive
        // r_n comes from the indicator I_ℝ⁻(−u̇_n), whose subgradient at u̇_n = 0 is ℝ⁺.
        let cone = CoulombCone::new(mu).unwrap();
        let r = LocalVec2::planar(r_n, 0.0);
        let h = 1e-6 * un;
        let b = |y: f64| contact_bipotential(&cone, &LocalVec2::planar(-y, ut), &r);
        let fd = (b(-un + h) - b(-un - h)) / (2.0 * h);
        prop_assert_eq!(fd, 0.0, "∂b/∂(−u̇_n) = {}", fd);
    }

    #[test]
    fn thermodynamic_force_is_the_gradient_of_b_beta(alpha in magnitude(), g in magnitude()) {
        // Damaging pair β̇ = G/α with G < 0: ∂b_β/∂β̇ = αβ̇ = G (the law, 4.80), and
        // ∂b_β/∂G = ∂(G²/2α)/∂G = G/α = β̇ (the inverse law, 4.83c).
        let g = -g;
        let beta_dot = g / alpha;
        let h = 1e-6 * beta_dot.abs();
        let d_beta_dot = (adhesion_bipotential(alpha, beta_dot + h, g) - adhesion_bipotential(alpha, beta_dot - h, g)) / (2.0 * h);
        prop_assert!((d_beta_dot - g).abs() <= 1e-6 * g.abs(), "∂b_β/∂β̇ = {d_beta_dot}, G = {g}");
        let k = 1e-6 * g.abs();
        let d_g = (adhesion_bipotential(alpha, beta_dot, g + k) - adhesion_bipotential(alpha, beta_dot, g - k)) / (2.0 * k);
        prop_assert!((d_g - beta_dot).abs() <= 1e-6 * beta_dot.abs(), "∂b_β/∂G = {d_g}, β̇ = {beta_dot}");
    }
}
