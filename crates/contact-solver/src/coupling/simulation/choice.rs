//! Which path solved a step's reduced problem, and why ([`PathChoice`]): the settings asked
//! for it, or [`FlexibilityMode::Auto`](super::FlexibilityMode::Auto)'s rule chose it.
//!
//! `Auto`'s rule (per dimension, measured: `docs/benchmarks.md`):
//! ```text
//! floating structure or an adhesive contact active   -> dense F*
//! active contacts ≤ dense_limit (500 in 2D, 3000 in 3D) -> dense F*
//! otherwise, the laws are Coulomb cones and K is known -> primal active set
//! otherwise                                            -> matrix-free
//! active set not converged: ≤ FALLBACK_DENSE_LIMIT contacts (8000 in 2D, 3000 in 3D)
//!                                                      -> dense F*, else matrix-free
//! ```

use std::fmt;

/// How a step's reduced problem was solved.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[non_exhaustive]
pub enum SolvePath {
    /// On a dense `F* = H K⁻¹ Hᵀ` (the default before any pass has run).
    #[default]
    Dense,
    /// By the primal active-set iteration on the constrained stiffness (no `F*`).
    ActiveSet,
    /// Matrix-free: each product `F* r` is a solve with the stiffness (no `F*`).
    MatrixFree,
}

impl SolvePath {
    /// A short lowercase name: `dense`, `active set`, `matrix-free`.
    ///
    /// # Examples
    /// ```
    /// use contact_solver::SolvePath;
    /// assert_eq!(SolvePath::ActiveSet.name(), "active set");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            Self::Dense => "dense",
            Self::ActiveSet => "active set",
            Self::MatrixFree => "matrix-free",
        }
    }
}

/// Why a step took its [`SolvePath`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[non_exhaustive]
pub enum PathReason {
    /// [`SimulationSettings::flexibility`](super::SimulationSettings::flexibility) named this
    /// path (the default before any pass has run).
    #[default]
    Requested,
    /// The settings named a path without `F*` but no contact was active: nothing to solve.
    NoActiveContacts,
    /// The structure floats: its rigid-body amplitudes are solved on a dense `F*` only.
    Floating,
    /// `Auto`: an active law is adhesive (its springs live in the dense `F*`).
    Adhesive,
    /// `Auto`: the active contacts are at most the dense limit.
    WithinDenseLimit {
        /// Active contacts.
        active: usize,
        /// [`FlexibilityMode::Auto`](super::FlexibilityMode::Auto)'s `dense_limit`.
        limit: usize,
    },
    /// `Auto`: more active contacts than the dense limit, and the active set applies.
    AboveDenseLimit {
        /// Active contacts.
        active: usize,
        /// [`FlexibilityMode::Auto`](super::FlexibilityMode::Auto)'s `dense_limit`.
        limit: usize,
    },
    /// `Auto`: more active contacts than the dense limit, but the active set does not apply
    /// (a law without a Coulomb cone, or a structure that does not expose its stiffness).
    ActiveSetUnavailable {
        /// Active contacts.
        active: usize,
        /// [`FlexibilityMode::Auto`](super::FlexibilityMode::Auto)'s `dense_limit`.
        limit: usize,
    },
    /// `Auto`: the active-set iteration did not converge; the step was solved again on this
    /// path (dense up to the dimension's fallback limit, matrix-free beyond).
    ActiveSetFallback {
        /// Active contacts.
        active: usize,
        /// The dimension's `FALLBACK_DENSE_LIMIT`.
        limit: usize,
    },
}

/// The path a step's reduced problem took and why ([`StepReport::path`](super::StepReport::path)).
///
/// # Examples
/// ```
/// use contact_solver::{PathChoice, PathReason, SolvePath};
/// let c = PathChoice {
///     path: SolvePath::ActiveSet,
///     reason: PathReason::AboveDenseLimit { active: 3200, limit: 3000 },
/// };
/// assert_eq!(
///     c.to_string(),
///     "active set (auto: 3200 active contacts > dense limit 3000)"
/// );
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct PathChoice {
    /// The path.
    pub path: SolvePath,
    /// Why.
    pub reason: PathReason,
}

impl PathChoice {
    /// The choice of `path` for `reason`.
    pub(crate) fn new(path: SolvePath, reason: PathReason) -> Self {
        Self { path, reason }
    }
}

impl fmt::Display for PathReason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::Requested => write!(f, "requested by the settings"),
            Self::NoActiveContacts => write!(f, "no active contact"),
            Self::Floating => write!(f, "the structure floats: rigid modes need the dense F*"),
            Self::Adhesive => write!(f, "auto: an adhesive contact is active"),
            Self::WithinDenseLimit { active, limit } => {
                write!(f, "auto: {active} active contacts ≤ dense limit {limit}")
            }
            Self::AboveDenseLimit { active, limit } => {
                write!(f, "auto: {active} active contacts > dense limit {limit}")
            }
            Self::ActiveSetUnavailable { active, limit } => write!(
                f,
                "auto: {active} active contacts > dense limit {limit}, the active set does not apply"
            ),
            Self::ActiveSetFallback { active, limit } => write!(
                f,
                "auto: the active set did not converge; {active} active contacts against the fallback limit {limit}"
            ),
        }
    }
}

impl fmt::Display for PathChoice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} ({})", self.path.name(), self.reason)
    }
}
