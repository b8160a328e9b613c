//! Errors of the contact solver.
//!
//! Problems are validated once, when a [`ReducedProblem`](crate::ReducedProblem) is built;
//! the solver's loop then only fails by not converging.

use contact_laws::LawError;

/// Error of `contact-solver`.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SolverError {
    /// An array does not have the length the problem needs.
    #[error("invalid size of `{what}`: expected {expected}, found {found}")]
    SizeMismatch {
        /// Which array (`"W"`, `"q"`, `"mu"`, `"laws"`, …).
        what: &'static str,
        /// The expected length.
        expected: usize,
        /// The length found.
        found: usize,
    },
    /// An entry is NaN or infinite.
    #[error("`{what}[{index}]` = {value} is not finite")]
    NonFinite {
        /// Which array.
        what: &'static str,
        /// Flat index of the entry.
        index: usize,
        /// The rejected value.
        value: f64,
    },
    /// The flexibility matrix `W` is not symmetric to the relative tolerance `1e-12·max|W|`.
    #[error(
        "W is not symmetric: |W[{row}][{col}] - W[{col}][{row}]| = {difference:e} exceeds {tolerance:e}"
    )]
    NotSymmetric {
        /// Row of the worst entry.
        row: usize,
        /// Column of the worst entry.
        col: usize,
        /// `|W_ij − W_ji|`.
        difference: f64,
        /// The tolerance it exceeds.
        tolerance: f64,
    },
    /// A 2×2 diagonal block of `W` is not positive definite, so `W` is not SPD (a contact with
    /// no flexibility, or a rigid-body mode).
    #[error("the 2x2 diagonal block of W at contact {contact} is not positive definite")]
    NotPositiveDefinite {
        /// Index of the contact.
        contact: usize,
    },
    /// A friction coefficient was rejected by the local law.
    #[error("invalid friction coefficient at contact {contact}: {source}")]
    InvalidLaw {
        /// Index of the contact.
        contact: usize,
        /// The law's own error.
        #[source]
        source: LawError,
    },
    /// The law at a contact has no friction coefficient
    /// ([`ContactLaw::friction_coefficient`](contact_laws::ContactLaw::friction_coefficient)
    /// returned `None`), which [`Algorithm::ClassicRccm`](crate::Algorithm::ClassicRccm)
    /// needs for its threshold `s = μ̄ r_n` and [`Algorithm::Newton`](crate::Algorithm::Newton)
    /// for its generalized Jacobian.
    #[error(
        "the law at contact {contact} has no friction coefficient: the classical RCCM solver and the Newton solver need a Coulomb-type law (use a bipotential sweep for this law)"
    )]
    NoFrictionCoefficient {
        /// Index of the contact.
        contact: usize,
    },
    /// A local law was rejected (without a contact index).
    #[error("invalid contact law: {0}")]
    Law(#[from] LawError),
    /// The JSON text is not a reduced problem.
    #[error("cannot read the reduced problem from JSON: {0}")]
    Json(String),
    /// Writing an output file or stream failed ([`output`](crate::output)).
    #[error("I/O error: {0}")]
    Io(String),
    /// The iteration reached `max_iterations` before meeting the stopping rule.
    #[error(
        "the contact iteration did not converge in {iterations} iterations (residual {residual:e})"
    )]
    NotConverged {
        /// Iterations done.
        iterations: usize,
        /// Natural-map residual at the last iterate.
        residual: f64,
        /// Natural-map residual of every iteration.
        history: Vec<f64>,
    },
    /// A contact zone or obstacle whose geometry makes no sense (zero-length LINE, node out of
    /// range, empty node set, …).
    #[error("invalid contact geometry: {0}")]
    InvalidGeometry(String),
    /// The requested solution path does not apply to this step (e.g.
    /// `FlexibilityMode::ActiveSet` on a node-to-segment zone); the message says why.
    #[error("unsupported for this step: {0}")]
    Unsupported(String),
    /// An invalid setting (tolerance, alert distance, time step, …).
    #[error("invalid setting `{what}` = {value}: {expected}")]
    InvalidSetting {
        /// The setting.
        what: &'static str,
        /// Its value.
        value: f64,
        /// What was expected.
        expected: &'static str,
    },
    /// The structure failed (factorisation, solve, unknown node set).
    #[cfg(feature = "fe")]
    #[error("structure: {0}")]
    Structure(#[from] fem_core::FemError),
    /// The fixed point between the contact solve and the adhesion update did not converge.
    #[error(
        "the adhesion fixed point did not converge in {iterations} iterations (last change of beta {change:e})"
    )]
    AdhesionNotConverged {
        /// Fixed-point iterations done.
        iterations: usize,
        /// Largest change of the state in the last iteration.
        change: f64,
        /// The largest state change of every iteration.
        history: Vec<f64>,
    },
}

#[cfg(feature = "serde")]
impl From<serde_json::Error> for SolverError {
    fn from(e: serde_json::Error) -> Self {
        Self::Json(e.to_string())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn errors_display_a_sentence() {
        let e = SolverError::SizeMismatch {
            what: "q",
            expected: 4,
            found: 3,
        };
        assert_eq!(e.to_string(), "invalid size of `q`: expected 4, found 3");
        let law = contact_laws::Coulomb::new(-1.0).unwrap_err();
        let e: SolverError = law.into();
        assert!(
            e.to_string()
                .starts_with("invalid contact law: invalid parameter `mu`")
        );
    }
}
