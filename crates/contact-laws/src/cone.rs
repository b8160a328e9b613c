//! The Coulomb cone `K_μ`, its polar cone `K*_μ` and the projections onto them.
//!
//! ```text
//! K_μ  = { r  : ‖r_t‖ ≤ μ r_n }              (seed 4.24)
//! K*_μ = { v  : μ ‖v_t‖ + v_n ≤ 0 }          (seed 4.27, 4.49)
//! ```
//!
//! Signs follow the [crate conventions](crate#sign-conventions): `r_n ≥ 0` is compression.

use crate::error::{LawError, non_negative};
use crate::local::LocalVec;

/// Relative tolerance of the membership tests [`CoulombCone::contains`] and
/// [`CoulombCone::polar_contains`] and of the indicator functions of the bipotentials.
///
/// A point built on the boundary of a cone in floating point (a projection in the slip case,
/// a slip pair of the bipotential) can miss the exact inequality by a few ulps; the tests
/// accept a violation up to `FEASIBILITY_TOL` times the magnitude of the terms compared.
pub const FEASIBILITY_TOL: f64 = 64.0 * f64::EPSILON;

/// Which of the three cases of the projection (seed eq. 5.38) applied.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ContactStatus {
    /// `τ ∈ K*_μ`: the projection is the cone's apex, `r = 0` (seed 5.35).
    Separation,
    /// `τ ∈ K_μ`: the projection is `τ` itself (seed 5.37).
    Stick,
    /// Otherwise: `τ` is projected onto the cone's surface (seed 5.32–5.34).
    Slip,
}

/// A Coulomb cone `K_μ = {‖r_t‖ ≤ μ r_n}` (seed 4.24) with a validated friction
/// coefficient `μ ≥ 0` (dimensionless). `μ = 0` is the frictionless half-line
/// `{r_t = 0, r_n ≥ 0}` of Signorini's law.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CoulombCone {
    mu: f64,
}

impl CoulombCone {
    /// The frictionless cone (`μ = 0`): the half-line of Signorini's law.
    pub const FRICTIONLESS: Self = Self { mu: 0.0 };

    /// Builds the cone of friction coefficient `mu` (seed 4.24).
    ///
    /// # Errors
    /// [`LawError::InvalidParameter`] if `mu` is NaN, infinite or negative.
    ///
    /// # Examples
    /// ```
    /// use contact_laws::{CoulombCone, LocalVec2};
    /// let cone = CoulombCone::new(0.5)?;
    /// assert!(cone.contains(&LocalVec2::planar(2.0, 1.0)));
    /// assert!(CoulombCone::new(-0.1).is_err());
    /// # Ok::<(), contact_laws::LawError>(())
    /// ```
    pub fn new(mu: f64) -> Result<Self, LawError> {
        Ok(Self {
            mu: non_negative("mu", mu)?,
        })
    }

    /// The friction coefficient `μ`.
    #[inline]
    pub fn mu(&self) -> f64 {
        self.mu
    }

    /// The cone of friction `μ · factor`, with `factor` clamped to `[0, 1]` (NaN gives 0).
    ///
    /// This is how the RCCM law builds `K_μ̄` with `μ̄ = μ f(β)` (seed 4.32–4.34) without a
    /// fallible constructor on the hot path.
    #[inline]
    pub fn scaled(&self, factor: f64) -> Self {
        // `max` returns the other operand when one is NaN, so NaN maps to 0 (`clamp` would
        // keep the NaN).
        #[allow(clippy::manual_clamp)]
        let f = factor.max(0.0).min(1.0);
        Self { mu: self.mu * f }
    }

    /// Membership `r ∈ K_μ`, with the relative tolerance [`FEASIBILITY_TOL`].
    #[inline]
    pub fn contains<const DT: usize>(&self, r: &LocalVec<DT>) -> bool {
        let rt = r.t_norm();
        let scale = FEASIBILITY_TOL * (rt + (1.0 + self.mu) * r.n.abs());
        r.n >= -scale && rt - self.mu * r.n <= scale
    }

    /// Membership `v ∈ K*_μ = {μ‖v_t‖ + v_n ≤ 0}` (seed 4.27), with the relative tolerance
    /// [`FEASIBILITY_TOL`].
    #[inline]
    pub fn polar_contains<const DT: usize>(&self, v: &LocalVec<DT>) -> bool {
        let a = self.mu * v.t_norm();
        a + v.n <= FEASIBILITY_TOL * (a + v.n.abs())
    }

    /// Orthogonal projection of `tau` onto `K_μ`, in closed form (seed 5.38).
    ///
    /// ```text
    /// μ‖τ_t‖ ≤ −τ_n         → r = 0                                   (separation, 5.35)
    /// ‖τ_t‖ ≤ μ τ_n         → r = τ                                   (stick, 5.37)
    /// otherwise             → r_n = (τ_n + μ‖τ_t‖)/(1 + μ²),
    ///                         r_t = μ r_n τ_t/‖τ_t‖                   (slip, 5.32–5.34)
    /// ```
    /// The separation test comes first, so that `μ = 0` and `τ_t = 0` are exact: the slip
    /// branch is reached only with `‖τ_t‖ > 0`, and never produces NaN for finite `τ`. For
    /// `μ > 1` the slip branch is evaluated with `1/μ` (the same formula divided through by
    /// `μ²`), so that it stays exact up to `μ = f64::MAX` (`1 + μ²` overflows beyond 1e154).
    #[inline]
    pub fn project<const DT: usize>(&self, tau: &LocalVec<DT>) -> LocalVec<DT> {
        self.project_with_status(tau).0
    }

    /// Like [`project`](Self::project), and also reports which case of seed eq. 5.38 applied.
    #[inline]
    pub fn project_with_status<const DT: usize>(
        &self,
        tau: &LocalVec<DT>,
    ) -> (LocalVec<DT>, ContactStatus) {
        let mu = self.mu;
        let tt = tau.t_norm();
        if mu * tt <= -tau.n {
            (LocalVec::zeros(), ContactStatus::Separation)
        } else if tt <= mu * tau.n {
            (*tau, ContactStatus::Stick)
        } else {
            // Here ‖τ_t‖ > 0: with ‖τ_t‖ = 0 one of the two tests above holds for μ ≥ 0.
            let (r_n, mu_r_n) = if mu <= 1.0 {
                let r_n = (tau.n + mu * tt) / (1.0 + mu * mu);
                (r_n, mu * r_n)
            } else {
                // the same with a = 1/μ, so that μ² cannot overflow (μ up to f64::MAX):
                // μ r_n = (a τ_n + ‖τ_t‖)/(1 + a²), r_n = a · μ r_n
                let a = 1.0 / mu;
                let mu_r_n = (a * tau.n + tt) / (1.0 + a * a);
                (a * mu_r_n, mu_r_n)
            };
            let r_t = tau.t * (mu_r_n / tt);
            (LocalVec { n: r_n, t: r_t }, ContactStatus::Slip)
        }
    }

    /// Orthogonal projection onto the polar cone `K*_μ`, the remainder of Moreau's
    /// decomposition `τ = P_K(τ) + P_K*(τ)` with `P_K(τ) · P_K*(τ) = 0`.
    ///
    /// Computed in closed form rather than as `τ − P_K(τ)`, which loses all its digits to
    /// cancellation when `τ` is close to the cone (e.g. `μ ≫ 1` and `τ_n ≈ 0`):
    ///
    /// ```text
    /// separation → τ;   stick → 0;
    /// slip       → s (−μ n + τ_t/‖τ_t‖),   s = (‖τ_t‖ − μ τ_n)/(1 + μ²) > 0
    /// ```
    #[inline]
    pub fn project_polar<const DT: usize>(&self, tau: &LocalVec<DT>) -> LocalVec<DT> {
        let mu = self.mu;
        let tt = tau.t_norm();
        if mu * tt <= -tau.n {
            *tau
        } else if tt <= mu * tau.n {
            LocalVec::zeros()
        } else {
            // μ s and s, with a = 1/μ when μ > 1 so that μ² cannot overflow
            let (mu_s, s) = if mu <= 1.0 {
                let s = (tt - mu * tau.n) / (1.0 + mu * mu);
                (mu * s, s)
            } else {
                let a = 1.0 / mu;
                let mu_s = (a * tt - tau.n) / (1.0 + a * a);
                (mu_s, a * mu_s)
            };
            LocalVec {
                n: -mu_s,
                t: tau.t * (s / tt),
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::local::{LocalVec2, LocalVec3};
    use approx::assert_relative_eq;

    #[test]
    fn new_rejects_negative_and_nan() {
        for mu in [-1.0, f64::NAN, f64::INFINITY] {
            assert!(matches!(
                CoulombCone::new(mu),
                Err(LawError::InvalidParameter { name: "mu", .. })
            ));
        }
    }

    #[test]
    fn project_separation_case_works() {
        // μ = 0.5, τ = (−2, 1): μ‖τ_t‖ = 0.5 ≤ 2 → r = 0.
        let cone = CoulombCone::new(0.5).unwrap();
        let (r, s) = cone.project_with_status(&LocalVec2::planar(-2.0, 1.0));
        assert_eq!(s, ContactStatus::Separation);
        assert_eq!(r, LocalVec2::zeros());
    }

    #[test]
    fn project_stick_case_works() {
        // μ = 0.5, τ = (4, −1.5): ‖τ_t‖ = 1.5 ≤ 2 → r = τ.
        let cone = CoulombCone::new(0.5).unwrap();
        let tau = LocalVec2::planar(4.0, -1.5);
        let (r, s) = cone.project_with_status(&tau);
        assert_eq!(s, ContactStatus::Stick);
        assert_eq!(r, tau);
    }

    #[test]
    fn project_slip_case_works() {
        // μ = 0.5, τ = (2, −3): r_n = (2 + 1.5)/1.25 = 2.8, r_t = −0.5·2.8 = −1.4.
        let cone = CoulombCone::new(0.5).unwrap();
        let (r, s) = cone.project_with_status(&LocalVec2::planar(2.0, -3.0));
        assert_eq!(s, ContactStatus::Slip);
        assert_relative_eq!(r.n, 2.8, epsilon = 1e-15);
        assert_relative_eq!(r.t[0], -1.4, epsilon = 1e-15);
        // 3D: τ = (1, 3, 4), μ = 1: r_n = (1 + 5)/2 = 3, r_t = 3·(3, 4)/5.
        let cone = CoulombCone::new(1.0).unwrap();
        let r = cone.project(&LocalVec3::spatial(1.0, 3.0, 4.0));
        assert_relative_eq!(r.n, 3.0, epsilon = 1e-15);
        assert_relative_eq!(r.t[0], 1.8, epsilon = 1e-15);
        assert_relative_eq!(r.t[1], 2.4, epsilon = 1e-15);
    }

    #[test]
    fn project_slip_with_huge_mu_is_exact() {
        // μ = 1e300, τ = (−1, 2): μ r_n = (τ_n/μ + ‖τ_t‖)/(1 + 1/μ²) = 2 to round-off, so
        // r = (2e-300, 2) (1 + μ² overflows: the plain formula gave r = 0); the polar part is
        // τ − r = (−1 − 2e-300, 0), Moreau's decomposition.
        let cone = CoulombCone::new(1e300).unwrap();
        let tau = LocalVec2::planar(-1.0, 2.0);
        let (r, s) = cone.project_with_status(&tau);
        assert_eq!(s, ContactStatus::Slip);
        assert_relative_eq!(r.n, 2e-300, max_relative = 1e-15);
        assert_relative_eq!(r.t[0], 2.0, max_relative = 1e-15);
        let p = cone.project_polar(&tau);
        assert_relative_eq!(p.n, -1.0, max_relative = 1e-15);
        assert!(p.t[0].abs() < 1e-15);
        // the largest finite μ
        let r = CoulombCone::new(f64::MAX)
            .unwrap()
            .project(&LocalVec3::spatial(-1.0, 3.0, 4.0));
        assert!(r.n > 0.0 && r.n.is_finite());
        assert_relative_eq!(r.t[0], 3.0, max_relative = 1e-15);
        assert_relative_eq!(r.t[1], 4.0, max_relative = 1e-15);
    }

    #[test]
    fn project_frictionless_is_exact() {
        let cone = CoulombCone::FRICTIONLESS;
        // Compression: the tangential part is dropped, the normal part kept.
        assert_eq!(
            cone.project(&LocalVec2::planar(3.0, 7.0)),
            LocalVec2::planar(3.0, 0.0)
        );
        // Tension with zero tangent: separation, not "stick" with r_n < 0.
        assert_eq!(
            cone.project(&LocalVec2::planar(-3.0, 0.0)),
            LocalVec2::zeros()
        );
        assert_eq!(
            cone.project(&LocalVec3::spatial(0.0, 0.0, 0.0)),
            LocalVec3::zeros()
        );
    }

    #[test]
    fn project_zero_tangent_is_exact() {
        let cone = CoulombCone::new(0.3).unwrap();
        assert_eq!(
            cone.project(&LocalVec3::spatial(2.0, 0.0, 0.0)),
            LocalVec3::spatial(2.0, 0.0, 0.0)
        );
        assert_eq!(
            cone.project(&LocalVec3::spatial(-2.0, 0.0, 0.0)),
            LocalVec3::zeros()
        );
        assert_eq!(
            cone.project(&LocalVec3::spatial(0.0, 0.0, 0.0)),
            LocalVec3::zeros()
        );
    }

    #[test]
    fn moreau_decomposition_works_in_each_case() {
        let cone = CoulombCone::new(0.4).unwrap();
        for tau in [
            LocalVec2::planar(-2.0, 0.5),
            LocalVec2::planar(2.0, 0.5),
            LocalVec2::planar(1.0, -5.0),
        ] {
            let p = cone.project(&tau);
            let q = cone.project_polar(&tau);
            assert!(cone.contains(&p));
            assert!(cone.polar_contains(&q));
            assert!(p.dot(&q).abs() <= 1e-14 * tau.norm() * tau.norm());
            let sum = p + q;
            assert!((sum - tau).norm() <= 1e-15 * tau.norm());
        }
    }

    #[test]
    fn scaled_clamps_the_factor() {
        let cone = CoulombCone::new(0.4).unwrap();
        assert_eq!(cone.scaled(0.5).mu(), 0.2);
        assert_eq!(cone.scaled(2.0).mu(), 0.4);
        assert_eq!(cone.scaled(-1.0).mu(), 0.0);
        assert_eq!(cone.scaled(f64::NAN).mu(), 0.0);
    }
}
