//! μ has one owner, the law (issue 35).
//!
//! A [`ReducedProblem`] carries one friction coefficient `μ_i` per contact, because a problem
//! read from a file or written for another code (JSON, FCLIB, Siconos) is a Coulomb problem:
//! [`solve_coulomb`](crate::solve_coulomb) solves it with the laws `Coulomb::new(μ_i)`, and
//! [`ReducedProblem::new`] stays the entry point of a user who has no laws. A problem solved
//! with laws ([`UzawaSolver::solve`](crate::UzawaSolver::solve) and
//! [`solve_with_states`](crate::UzawaSolver::solve_with_states)) takes the friction from the
//! laws, in their states (`μ̄_i = law_i.friction_coefficient(state_i)`, which for RCCM
//! depends on the adhesion `β`), so the two must not disagree:
//!
//! ```text
//! for every contact i whose law has a coefficient μ̄_i (finite, ≥ 0):
//!     |μ_i − μ̄_i| ≤ 1e-12 · max(μ_i, μ̄_i)      (round-off), else SolverError::FrictionMismatch
//! ```
//! A law without a coefficient (not Coulomb-type) has no `μ̄_i` to disagree with: its
//! projection is its friction, and the problem's `μ_i` is only what an export writes.
//! [`ReducedProblem::with_friction_of`] builds a problem whose coefficients are the laws'.

use super::problem::ReducedProblem;
use super::residual::pick;
use crate::error::SolverError;
use contact_laws::{ContactLaw, Coulomb};

/// Relative round-off within which the problem's `μ_i` and the law's `μ̄_i` agree (the law's
/// value is the one used).
const MU_AGREEMENT_TOL: f64 = 1e-12;

impl ReducedProblem {
    /// This problem with each contact's friction coefficient replaced by its law's in its
    /// state (`μ̄_i = law_i.friction_coefficient(state_i)`), so that it can be solved with
    /// those laws and exported with the friction they apply; a contact whose law has no
    /// coefficient keeps its `μ_i`. `laws` and `states` hold one entry per contact, or one
    /// shared by all.
    ///
    /// # Errors
    /// [`SolverError::SizeMismatch`] if `laws` or `states` has neither 1 nor `n_c` entries;
    /// [`SolverError::InvalidLaw`] if a law's coefficient is negative or not finite.
    ///
    /// # Examples
    /// ```
    /// use contact_laws::Coulomb;
    /// use contact_solver::{ReducedProblem, UzawaSettings, UzawaSolver};
    /// let p = ReducedProblem::new(vec![1.0, 0.0, 0.0, 1.0], vec![-1.0, 0.5], vec![0.0])?;
    /// let laws = [Coulomb::new(0.2)?];
    /// let p = p.with_friction_of(&laws, &[()])?;
    /// assert_eq!(p.mu(), [0.2]);
    /// let sol = UzawaSolver::new(UzawaSettings::default()).solve(&p, &laws)?;
    /// assert!((sol.r[1] + 0.2).abs() < 1e-9); // slip: r_t = −μ r_n
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn with_friction_of<L: ContactLaw>(
        mut self,
        laws: &[L],
        states: &[L::State],
    ) -> Result<Self, SolverError> {
        let nc = self.contact_count();
        check_count("laws", nc, laws.len())?;
        check_count("states", nc, states.len())?;
        for (contact, mu) in self.mu_mut().iter_mut().enumerate() {
            if let Some(m) = pick(laws, contact).friction_coefficient(pick(states, contact)) {
                Coulomb::new(m).map_err(|source| SolverError::InvalidLaw { contact, source })?;
                *mu = m;
            }
        }
        Ok(self)
    }

    /// Checks that every Coulomb-type law agrees with the problem's `μ_i` (module docs);
    /// `laws` and `states` have been checked to hold 1 or `n_c` entries.
    ///
    /// # Errors
    /// [`SolverError::FrictionMismatch`] for the first contact that disagrees.
    pub(crate) fn check_friction_of<L: ContactLaw>(
        &self,
        laws: &[L],
        states: &[L::State],
    ) -> Result<(), SolverError> {
        for (contact, &problem) in self.mu().iter().enumerate() {
            let law = pick(laws, contact).friction_coefficient(pick(states, contact));
            // a coefficient the law itself gets wrong is the algorithms' error to report
            if let Some(law) = law.filter(|m| m.is_finite() && *m >= 0.0)
                && (problem - law).abs() > MU_AGREEMENT_TOL * problem.max(law)
            {
                return Err(SolverError::FrictionMismatch {
                    contact,
                    problem,
                    law,
                });
            }
        }
        Ok(())
    }
}

/// `len` must be `n_c`, or 1 (shared) when there are contacts.
fn check_count(what: &'static str, nc: usize, len: usize) -> Result<(), SolverError> {
    if len == nc || (len == 1 && nc > 0) {
        Ok(())
    } else {
        Err(SolverError::SizeMismatch {
            what,
            expected: nc,
            found: len,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Algorithm, SolverError, UzawaSettings, UzawaSolver};
    use contact_laws::{BetaScheme, Rccm, RccmParams, Signorini};

    /// One contact, `W = I`, pressed by `q_n = −1` and pushed by `q_t = 0.5`: it slips with
    /// `r_t = −μ r_n`, so the answer shows which μ was used.
    fn pushed(mu: f64) -> ReducedProblem {
        ReducedProblem::new(vec![1.0, 0.0, 0.0, 1.0], vec![-1.0, 0.5], vec![mu]).unwrap()
    }

    #[test]
    fn issue_35_a_problem_whose_mu_disagrees_with_its_laws_is_refused() {
        // before issue 35 the law's 0.4 silently won over the problem's 0.2 (r_t = −0.4)
        let p = pushed(0.2);
        let laws = [Coulomb::new(0.4).unwrap()];
        for algorithm in [
            Algorithm::AndersonGaussSeidel,
            Algorithm::Newton,
            Algorithm::Auto,
        ] {
            let err = UzawaSolver::new(UzawaSettings::default().with_algorithm(algorithm))
                .solve(&p, &laws)
                .unwrap_err();
            assert!(
                matches!(err, SolverError::FrictionMismatch { contact: 0, problem, law }
                    if problem == 0.2 && law == 0.4),
                "{algorithm:?}: {err:?}"
            );
            let text = err.to_string();
            assert!(text.contains("contact 0") && text.contains("0.2") && text.contains("0.4"));
        }
    }

    #[test]
    fn issue_35_agreeing_mu_solves_and_with_friction_of_makes_it_agree() {
        let laws = [Coulomb::new(0.4).unwrap()];
        let p = pushed(0.2).with_friction_of(&laws, &[()]).unwrap();
        assert_eq!(p.mu(), [0.4]);
        let sol = UzawaSolver::new(UzawaSettings::default())
            .solve(&p, &laws)
            .unwrap();
        // slip at the law's μ: r = (1, −0.4) to the solver's tolerance (1e-10 relative)
        assert!((sol.r[0] - 1.0).abs() < 1e-9 && (sol.r[1] + 0.4).abs() < 1e-9);
        // round-off is not a disagreement (0.1 + 0.2 is 0.30000000000000004)
        let p = pushed(0.3);
        let laws = [Coulomb::new(0.1 + 0.2).unwrap()];
        assert!(
            UzawaSolver::new(UzawaSettings::default())
                .solve(&p, &laws)
                .is_ok()
        );
    }

    #[test]
    fn laws_without_a_coefficient_are_not_compared() {
        // Signorini has μ̄ = 0 and agrees only with μ = 0; RCCM's μ̄ depends on its state
        // (β₀ = 0.5 here), and with_friction_of takes it from there
        let p = pushed(0.0);
        assert!(
            UzawaSolver::new(UzawaSettings::default())
                .solve(&p, &[Signorini])
                .is_ok()
        );
        assert!(matches!(
            UzawaSolver::new(UzawaSettings::default()).solve(&pushed(0.3), &[Signorini]),
            Err(SolverError::FrictionMismatch { .. })
        ));
        let rccm = Rccm::new(RccmParams {
            c_n: 1.0,
            c_t: 1.0,
            w: 1.0,
            alpha: 0.0,
            mu: 0.3,
            m: 1,
            beta_0: 0.5,
            scheme: BetaScheme::ImplicitEuler,
        })
        .unwrap();
        let state = rccm.initial_state();
        let p = pushed(0.0).with_friction_of(&[rccm], &[state]).unwrap();
        assert_eq!(p.mu()[0], rccm.friction_coefficient(&state).unwrap());
    }

    #[test]
    fn with_friction_of_rejects_wrong_counts() {
        let laws = [Coulomb::new(0.1).unwrap(); 2];
        assert!(matches!(
            pushed(0.1).with_friction_of(&laws, &[()]),
            Err(SolverError::SizeMismatch { what: "laws", .. })
        ));
    }
}
