//! Signorini's unilateral contact and Coulomb friction as [`ContactLaw`]s.
//!
//! ```text
//! Signorini (4.20–4.22):  x_n ≥ 0,  r_n ≥ 0,  r_n x_n = 0
//! Coulomb (4.23):         ‖r_t‖ ≤ μ r_n;  slip ⇒ u̇_t = −λ r_t/‖r_t‖, λ ≥ 0
//! ```

use crate::cone::CoulombCone;
use crate::de_saxce::{contact_bipotential, modified_velocity};
use crate::error::LawError;
use crate::law::ContactLaw;
use crate::local::LocalVec;

/// Frictionless unilateral contact (Signorini, seed 4.20–4.22): the cone `K_0`, the half-line
/// `{r_t = 0, r_n ≥ 0}`. It has no parameters and no state.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Signorini;

/// Unilateral contact with Coulomb friction (seed 4.23–4.28) of coefficient `μ ≥ 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Coulomb {
    cone: CoulombCone,
}

impl Coulomb {
    /// Builds the law of friction coefficient `mu` (dimensionless).
    ///
    /// # Errors
    /// [`LawError::InvalidParameter`] if `mu` is negative, NaN or infinite.
    pub fn new(mu: f64) -> Result<Self, LawError> {
        Ok(Self {
            cone: CoulombCone::new(mu)?,
        })
    }

    /// The friction coefficient `μ`.
    #[inline]
    pub fn mu(&self) -> f64 {
        self.cone.mu()
    }

    /// The Coulomb cone `K_μ`.
    #[inline]
    pub fn cone(&self) -> CoulombCone {
        self.cone
    }
}

impl ContactLaw for Signorini {
    type State = ();

    #[inline]
    fn has_friction(&self) -> bool {
        false
    }

    #[inline]
    fn is_scale_invariant(&self) -> bool {
        true
    }

    #[inline]
    fn friction_coefficient(&self, _: &()) -> Option<f64> {
        Some(0.0)
    }

    #[inline]
    fn project<const DT: usize>(&self, tau: &LocalVec<DT>, _: &()) -> LocalVec<DT> {
        CoulombCone::FRICTIONLESS.project(tau)
    }

    #[inline]
    fn modified_velocity<const DT: usize>(&self, du: &LocalVec<DT>, _: &()) -> LocalVec<DT> {
        modified_velocity(&CoulombCone::FRICTIONLESS, du)
    }

    #[inline]
    fn bipotential<const DT: usize>(&self, du: &LocalVec<DT>, r: &LocalVec<DT>, _: &()) -> f64 {
        contact_bipotential(&CoulombCone::FRICTIONLESS, du, r)
    }
}

impl ContactLaw for Coulomb {
    type State = ();

    #[inline]
    fn has_friction(&self) -> bool {
        self.cone.mu() > 0.0
    }

    #[inline]
    fn is_scale_invariant(&self) -> bool {
        true
    }

    #[inline]
    fn friction_coefficient(&self, _: &()) -> Option<f64> {
        Some(self.cone.mu())
    }

    #[inline]
    fn project<const DT: usize>(&self, tau: &LocalVec<DT>, _: &()) -> LocalVec<DT> {
        self.cone.project(tau)
    }

    #[inline]
    fn modified_velocity<const DT: usize>(&self, du: &LocalVec<DT>, _: &()) -> LocalVec<DT> {
        modified_velocity(&self.cone, du)
    }

    #[inline]
    fn bipotential<const DT: usize>(&self, du: &LocalVec<DT>, r: &LocalVec<DT>, _: &()) -> f64 {
        contact_bipotential(&self.cone, du, r)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::local::LocalVec2;

    #[test]
    fn coulomb_new_rejects_negative_mu() {
        assert!(matches!(
            Coulomb::new(-0.1),
            Err(LawError::InvalidParameter { name: "mu", .. })
        ));
    }

    #[test]
    fn capability_queries_work() {
        assert!(!Signorini.has_friction());
        assert!(!Signorini.has_adhesion());
        assert!(Coulomb::new(0.3).unwrap().has_friction());
        assert!(!Coulomb::new(0.0).unwrap().has_friction());
    }

    #[test]
    fn coulomb_with_zero_friction_is_signorini() {
        let c = Coulomb::new(0.0).unwrap();
        for tau in [
            LocalVec2::planar(1.0, 2.0),
            LocalVec2::planar(-1.0, 2.0),
            LocalVec2::planar(0.0, 0.0),
        ] {
            assert_eq!(c.project(&tau, &()), Signorini.project(&tau, &()));
        }
    }

    #[test]
    fn default_fenchel_gap_is_zero_on_a_slip_pair() {
        let c = Coulomb::new(0.5).unwrap();
        let r = LocalVec2::planar(2.0, 1.0);
        let du = LocalVec2::planar(0.0, -4.0);
        assert_eq!(c.fenchel_gap(&du, &r, &()), 0.0);
        assert_eq!(c.update_state(&(), &du, &du, 1.0), ());
        assert_eq!(c.adhesive_reaction(&du, &()), LocalVec2::zeros());
    }
}
