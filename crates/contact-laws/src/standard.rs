//! [`StandardLaw`]: the built-in laws behind one type, so that contact zones with different
//! laws (a frictionless zone beside an adhesive one) can live in one problem.

use crate::coulomb::{Coulomb, Signorini};
use crate::law::ContactLaw;
use crate::local::LocalVec;
use crate::rccm::{Rccm, RccmState};

/// One of the built-in laws. Its state is an [`RccmState`] for every variant; the
/// non-adhesive variants carry `β = 0` and ignore it.
///
/// # Examples
/// ```
/// use contact_laws::{Coulomb, ContactLaw, LocalVec2, StandardLaw};
/// let law = StandardLaw::from(Coulomb::new(0.3)?);
/// let s = law.initial_state();
/// assert_eq!(s.beta(), 0.0);
/// assert_eq!(law.friction_coefficient(&s), Some(0.3));
/// let r = law.project(&LocalVec2::planar(1.0, 2.0), &s); // slip: on the cone's surface
/// assert!((r.t[0] - 0.3 * r.n).abs() < 1e-15);
/// # Ok::<(), contact_laws::LawError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StandardLaw {
    /// Frictionless unilateral contact.
    Signorini(Signorini),
    /// Unilateral contact with Coulomb friction.
    Coulomb(Coulomb),
    /// RCCM adhesion with friction.
    Rccm(Rccm),
}

impl From<Signorini> for StandardLaw {
    fn from(l: Signorini) -> Self {
        Self::Signorini(l)
    }
}

impl From<Coulomb> for StandardLaw {
    fn from(l: Coulomb) -> Self {
        Self::Coulomb(l)
    }
}

impl From<Rccm> for StandardLaw {
    fn from(l: Rccm) -> Self {
        Self::Rccm(l)
    }
}

const NO_ADHESION: RccmState = RccmState::ZERO;

impl ContactLaw for StandardLaw {
    type State = RccmState;

    #[inline]
    fn initial_state(&self) -> RccmState {
        match self {
            Self::Rccm(l) => l.initial_state(),
            _ => NO_ADHESION,
        }
    }

    #[inline]
    fn has_friction(&self) -> bool {
        match self {
            Self::Signorini(l) => l.has_friction(),
            Self::Coulomb(l) => l.has_friction(),
            Self::Rccm(l) => l.has_friction(),
        }
    }

    #[inline]
    fn has_adhesion(&self) -> bool {
        match self {
            Self::Rccm(l) => l.has_adhesion(),
            _ => false,
        }
    }

    #[inline]
    fn adhesion_active(&self, state: &RccmState) -> bool {
        match self {
            Self::Rccm(l) => l.adhesion_active(state),
            _ => false,
        }
    }

    #[inline]
    fn project<const DT: usize>(&self, tau: &LocalVec<DT>, state: &RccmState) -> LocalVec<DT> {
        match self {
            Self::Signorini(l) => l.project(tau, &()),
            Self::Coulomb(l) => l.project(tau, &()),
            Self::Rccm(l) => l.project(tau, state),
        }
    }

    #[inline]
    fn modified_velocity<const DT: usize>(
        &self,
        du: &LocalVec<DT>,
        state: &RccmState,
    ) -> LocalVec<DT> {
        match self {
            Self::Signorini(l) => l.modified_velocity(du, &()),
            Self::Coulomb(l) => l.modified_velocity(du, &()),
            Self::Rccm(l) => l.modified_velocity(du, state),
        }
    }

    #[inline]
    fn adhesive_stiffness(&self, state: &RccmState) -> [f64; 2] {
        match self {
            Self::Rccm(l) => l.adhesive_stiffness(state),
            _ => [0.0, 0.0],
        }
    }

    #[inline]
    fn adhesion_intensity(&self, state: &RccmState) -> f64 {
        match self {
            Self::Rccm(l) => l.adhesion_intensity(state),
            _ => 0.0,
        }
    }

    #[inline]
    fn is_scale_invariant(&self) -> bool {
        true
    }

    #[inline]
    fn friction_coefficient(&self, state: &RccmState) -> Option<f64> {
        match self {
            Self::Signorini(l) => l.friction_coefficient(&()),
            Self::Coulomb(l) => l.friction_coefficient(&()),
            Self::Rccm(l) => l.friction_coefficient(state),
        }
    }

    #[inline]
    fn bipotential<const DT: usize>(
        &self,
        du: &LocalVec<DT>,
        r_bar: &LocalVec<DT>,
        state: &RccmState,
    ) -> f64 {
        match self {
            Self::Signorini(l) => l.bipotential(du, r_bar, &()),
            Self::Coulomb(l) => l.bipotential(du, r_bar, &()),
            Self::Rccm(l) => l.bipotential(du, r_bar, state),
        }
    }

    #[inline]
    fn update_state<const DT: usize>(
        &self,
        start: &RccmState,
        u_start: &LocalVec<DT>,
        u: &LocalVec<DT>,
        dt: f64,
    ) -> RccmState {
        match self {
            Self::Rccm(l) => l.update_state(start, u_start, u, dt),
            _ => *start,
        }
    }

    #[inline]
    fn state_change(&self, a: &RccmState, b: &RccmState) -> f64 {
        match self {
            Self::Rccm(l) => l.state_change(a, b),
            _ => 0.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::local::LocalVec2;
    use crate::rccm::{BetaScheme, RccmParams};

    fn rccm() -> Rccm {
        Rccm::new(RccmParams {
            c_n: 2e5,
            c_t: 1e5,
            w: 1e-6,
            alpha: 1.0,
            mu: 0.2,
            m: 2,
            beta_0: 1.0,
            scheme: BetaScheme::ImplicitEuler,
        })
        .unwrap()
    }

    #[test]
    fn standard_law_delegates_to_each_variant() {
        let law = rccm();
        let s = RccmState::new(0.5).unwrap();
        let any = StandardLaw::from(law);
        let u = LocalVec2::planar(1e-6, -2e-6);
        let tau = LocalVec2::planar(1.0, 0.7);
        assert_eq!(any.project(&tau, &s), law.project(&tau, &s));
        assert_eq!(any.modified_velocity(&u, &s), law.modified_velocity(&u, &s));
        assert_eq!(any.adhesive_reaction(&u, &s), law.adhesive_reaction(&u, &s));
        assert_eq!(any.friction_coefficient(&s), law.friction_coefficient(&s));
        assert_eq!(
            any.update_state(&s, &u, &(u * 3.0), 0.1),
            law.update_state(&s, &u, &(u * 3.0), 0.1)
        );
        assert!(any.has_adhesion() && any.adhesion_active(&s));
        assert_eq!(any.adhesion_intensity(&s), 0.5);

        let c = StandardLaw::from(Coulomb::new(0.4).unwrap());
        let s0 = c.initial_state();
        assert!(!c.has_adhesion() && !c.adhesion_active(&s0));
        assert_eq!(c.adhesive_stiffness(&s0), [0.0, 0.0]);
        assert_eq!(
            c.project(&tau, &s0),
            Coulomb::new(0.4).unwrap().project(&tau, &())
        );
        let f = StandardLaw::from(Signorini);
        assert!(!f.has_friction());
        assert_eq!(f.friction_coefficient(&s0), Some(0.0));
        assert_eq!(f.project(&tau, &s0), LocalVec2::planar(1.0, 0.0));
    }

    #[test]
    fn adhesive_reaction_is_minus_stiffness_times_jump() {
        let law = rccm();
        let s = RccmState::new(0.5).unwrap();
        let [k_n, k_t] = law.adhesive_stiffness(&s);
        assert_eq!([k_n, k_t], [0.25 * 2e5, 0.25 * 1e5]);
        let u = LocalVec2::planar(3e-6, 1e-6);
        let r = law.adhesive_reaction(&u, &s);
        assert_eq!(r.n, -k_n * u.n);
        assert_eq!(r.t[0], -k_t * u.t[0]);
    }
}
