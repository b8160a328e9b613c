//! De Saxcé's modified velocity and the contact bipotential `b_c`.
//!
//! ```text
//! v = −(u̇_t + (u̇_n + μ‖u̇_t‖) n)                        (seed 4.26, 4.39)
//! the law:  v ∈ ∂I_Kμ(r)                                  (seed 4.26, 4.38)
//! b_c(−u̇, r) = I_Kμ(r) + I_ℝ⁻(−u̇_n) + μ r_n ‖u̇_t‖        (seed 4.28, 4.62–4.63)
//! Fenchel:  b_c(−u̇, r) ≥ −u̇ · r, with equality iff (u̇, r) obeys the law  (4.8, 4.9)
//! ```
//!
//! With adhesion the same functions act on the auxiliary reaction `r̄ = r − r_adh` and on the
//! effective friction `μ̄ = μ f(β)` (seed 4.63): pass `CoulombCone::scaled`.

use crate::cone::{CoulombCone, FEASIBILITY_TOL};
use crate::local::LocalVec;

/// De Saxcé's modified velocity `v = −(u̇_t + (u̇_n + μ‖u̇_t‖) n)` (seed 4.26, 4.39).
///
/// `du` is the relative velocity `u̇` (or the increment `Δu` of a step); `v` has its units.
/// The contact law is `v ∈ ∂I_Kμ(r)`, so the Uzawa prediction of seed 5.26a reads
/// `τ = r + ρ v`, and `r = P_Kμ(τ)` is a fixed point exactly when `(u̇, r)` obeys the law.
#[inline]
pub fn modified_velocity<const DT: usize>(cone: &CoulombCone, du: &LocalVec<DT>) -> LocalVec<DT> {
    LocalVec {
        n: -(du.n + cone.mu() * du.t_norm()),
        t: -du.t,
    }
}

/// The contact bipotential `b_c(−u̇, r) = I_Kμ(r) + I_ℝ⁻(−u̇_n) + μ r_n ‖u̇_t‖`
/// (seed 4.28; with `r̄` and `μ̄`, 4.62–4.63).
///
/// Returns `f64::INFINITY` when an indicator is active (`r ∉ K_μ` or `u̇_n < 0`), tested with
/// the relative tolerance [`FEASIBILITY_TOL`]. Units: power per unit area (reaction times
/// velocity), or work per unit area when `du` is an increment.
#[inline]
pub fn contact_bipotential<const DT: usize>(
    cone: &CoulombCone,
    du: &LocalVec<DT>,
    r: &LocalVec<DT>,
) -> f64 {
    let du_t = du.t_norm();
    if !cone.contains(r) || du.n < -FEASIBILITY_TOL * (du.n.abs() + cone.mu() * du_t) {
        return f64::INFINITY;
    }
    // On K_μ, r_n ≥ 0 up to rounding: clamp so the coupling term is never negative.
    cone.mu() * r.n.max(0.0) * du_t
}

/// The Fenchel gap `b_c(−u̇, r) − (−u̇ · r) ≥ 0` (seed 4.8, 4.69).
///
/// It is `0` exactly on the extremal pairs — the pairs that obey the law (seed 4.9, 4.71) —
/// and `f64::INFINITY` when `b_c` is; it is never NaN for finite arguments.
#[inline]
pub fn contact_fenchel_gap<const DT: usize>(
    cone: &CoulombCone,
    du: &LocalVec<DT>,
    r: &LocalVec<DT>,
) -> f64 {
    let b = contact_bipotential(cone, du, r);
    if b.is_infinite() { b } else { b + du.dot(r) }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::local::LocalVec2;
    use approx::assert_relative_eq;

    #[test]
    fn modified_velocity_works() {
        let cone = CoulombCone::new(0.5).unwrap();
        // u̇ = (1, −2): v = −(−2 t + (1 + 0.5·2) n) = (−2, 2).
        let v = modified_velocity(&cone, &LocalVec2::planar(1.0, -2.0));
        assert_eq!(v, LocalVec2::planar(-2.0, 2.0));
    }

    #[test]
    fn slip_pair_is_extremal() {
        // r on the cone's surface, u̇_t opposite to r_t, u̇_n = 0 (seed 4.70, case 2).
        let cone = CoulombCone::new(0.5).unwrap();
        let r = LocalVec2::planar(2.0, 1.0);
        let du = LocalVec2::planar(0.0, -3.0);
        assert_relative_eq!(contact_bipotential(&cone, &du, &r), 3.0);
        assert_eq!(contact_fenchel_gap(&cone, &du, &r), 0.0);
        // The normality rule holds: v ∈ N_K(r), so P(r + ρ v) = r for any ρ > 0.
        let v = modified_velocity(&cone, &du);
        let back = cone.project(&(r + v * 0.7));
        assert_relative_eq!(back.n, r.n, epsilon = 1e-14);
        assert_relative_eq!(back.t[0], r.t[0], epsilon = 1e-14);
    }

    #[test]
    fn stick_and_separation_pairs_are_extremal() {
        let cone = CoulombCone::new(0.5).unwrap();
        // Stick: u̇ = 0, r inside.
        assert_eq!(
            contact_fenchel_gap(&cone, &LocalVec2::zeros(), &LocalVec2::planar(2.0, 0.3)),
            0.0
        );
        // Separation: r = 0, u̇_n ≥ 0, any u̇_t.
        assert_eq!(
            contact_fenchel_gap(&cone, &LocalVec2::planar(1.0, 5.0), &LocalVec2::zeros()),
            0.0
        );
    }

    #[test]
    fn non_extremal_pairs_have_a_positive_gap() {
        let cone = CoulombCone::new(0.5).unwrap();
        // Sliding in the direction of r_t: gap = μ r_n ‖u̇_t‖ + u̇_t r_t = 1·2 + 2·1 = 4.
        let gap = contact_fenchel_gap(
            &cone,
            &LocalVec2::planar(0.0, 2.0),
            &LocalVec2::planar(2.0, 1.0),
        );
        assert_relative_eq!(gap, 4.0);
        // Interpenetrating velocity: indicator of ℝ⁻ is active.
        assert_eq!(
            contact_bipotential(&cone, &LocalVec2::planar(-1.0, 0.0), &LocalVec2::zeros()),
            f64::INFINITY
        );
        // Reaction outside the cone.
        assert_eq!(
            contact_fenchel_gap(&cone, &LocalVec2::zeros(), &LocalVec2::planar(1.0, 1.0)),
            f64::INFINITY
        );
    }
}
