//! Which path solved a step's reduced problem, and why ([`PathChoice`]): the settings asked
//! for it, or [`FlexibilityMode::Auto`](super::FlexibilityMode::Auto)'s rule chose it.
//!
//! `Auto`'s rule (per dimension, measured: `docs/benchmarks.md`):
//! ```text
//! floating structure or an adhesive contact active   -> dense F*
//! active contacts ≤ dense_limit (500 in 2D, 3000 in 3D), and in 3D also
//!   ≤ max(DOF_RULE_FLOOR, DOF_RULE_COEFFICIENT · DOF^(2/3)) (500, 0.5)  -> dense F*
//! 3D, within dense_limit but above that, the active set applies  -> primal active set
//! 3D, within dense_limit but above that, it does not            -> matrix-free
//! above dense_limit, the laws are Coulomb cones and K is known -> primal active set
//! otherwise (above dense_limit)                       -> matrix-free
//! active set not converged: ≤ FALLBACK_DENSE_LIMIT contacts (8000 in 2D, 3000 in 3D)
//!                                                      -> dense F*, else matrix-free
//! ```
//! The 3D rule on contacts and DOF together (issue 38): the dense path pays one solve with
//! the factor of `K` per column of `F*` (`n_c` to `3 n_c` of them, each `~ nnz(L) ~ N^(4/3)`
//! for a nested-dissection factor of `N` DOF) and sweeps over its `(3 n_c)²` entries; the
//! active set pays about six factorisations (`~ N²`) whatever `n_c`. Their ratio goes as
//! `n_c / N^(2/3)`. Measured (`docs/benchmarks.md`, "Issue 38: the dense limit on contacts
//! and DOF"): dense wins at `n_c / N^(2/3)` = 0.15–0.38 (the 3D Hertz, 121–852 contacts at
//! 2e4–1.6e5 DOF, 2–3×), the active set at 0.77–2.0 (the P1 block and the thin pad, 625–2 401
//! contacts, 1.8–37×); the crossover, interpolated, is at 0.5. Below `DOF_RULE_FLOOR`
//! contacts the dense path stays (the measured gaps there are within 2×, and every scene
//! captured before keeps its path). Where the active set does not apply (a law without a
//! Coulomb cone, a structure that does not expose `K`), the same line separates the dense path
//! from the matrix-free one (Anderson window 20: 57–252 products on the 3D cases measured):
//! matrix-free measured 2× faster at 0.77 (the P1 block, 1 089 contacts), 3–8× on the pad
//! (1.3–1.7), dense 2–4× faster at 0.15–0.16 (the Hertz).

use std::fmt;

/// Active contacts up to which `Auto` keeps the dense `F*` in 3D whatever the DOF (within
/// `dense_limit`).
pub(crate) const DOF_RULE_FLOOR: usize = 500;

/// `c` of the 3D rule `n_c ≤ c · DOF^(2/3)`: the measured crossover of the dense path and the
/// active set (module docs).
pub(crate) const DOF_RULE_COEFFICIENT: f64 = 0.5;

/// The most active contacts `Auto` solves on a dense `F*` in 3D for a model of `dofs` free
/// DOF (before `dense_limit`): `max(DOF_RULE_FLOOR, ⌊0.5 · dofs^(2/3)⌋)`.
pub(crate) fn dense_contacts_for_dofs(dofs: usize) -> usize {
    let by_dofs = DOF_RULE_COEFFICIENT * (dofs as f64).powf(2.0 / 3.0);
    // (a float of at most ~1e12 for any model that fits in memory: the cast is exact enough)
    DOF_RULE_FLOOR.max(by_dofs.floor() as usize)
}

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
    /// `Auto` in 3D: the active contacts are within the dense limit and above
    /// `DOF_RULE_FLOOR` (500), and at most `0.5 · DOF^(2/3)`: the dense columns cost less
    /// than the active set's factorisations.
    WithinDofRule {
        /// Active contacts.
        active: usize,
        /// Free DOF of the structure.
        dofs: usize,
        /// `0.5 · DOF^(2/3)`, the most contacts solved dense at this size.
        limit: usize,
    },
    /// `Auto` in 3D: the active contacts are within the dense limit but above
    /// `max(500, 0.5 · DOF^(2/3))`, and the active set applies: its factorisations cost less
    /// than the dense columns.
    AboveDofRule {
        /// Active contacts.
        active: usize,
        /// Free DOF of the structure.
        dofs: usize,
        /// `max(500, 0.5 · DOF^(2/3))`, the most contacts solved dense at this size.
        limit: usize,
    },
    /// `Auto` in 3D: the active contacts are within the dense limit but above
    /// `max(500, 0.5 · DOF^(2/3))`, and the active set does not apply (a law without a Coulomb
    /// cone, or a structure that does not expose its stiffness): matrix-free, whose products
    /// cost less than the dense columns there (measured, issue 38).
    AboveDofRuleMatrixFree {
        /// Active contacts.
        active: usize,
        /// Free DOF of the structure.
        dofs: usize,
        /// `max(500, 0.5 · DOF^(2/3))`, the most contacts solved dense at this size.
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
            Self::WithinDofRule {
                active,
                dofs,
                limit,
            } => write!(
                f,
                "auto: {active} active contacts ≤ {limit} = 0.5 DOF^(2/3) at {dofs} DOF: F*'s columns cost less than the active set's factorisations"
            ),
            Self::AboveDofRule {
                active,
                dofs,
                limit,
            } => write!(
                f,
                "auto: {active} active contacts > {limit} = max(500, 0.5 DOF^(2/3)) at {dofs} DOF: the active set's factorisations cost less than F*'s columns"
            ),
            Self::AboveDofRuleMatrixFree {
                active,
                dofs,
                limit,
            } => write!(
                f,
                "auto: {active} active contacts > {limit} = max(500, 0.5 DOF^(2/3)) at {dofs} DOF, the active set does not apply: matrix-free products cost less than F*'s columns"
            ),
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn issue_38_dense_contacts_for_dofs_works() {
        // the floor below ~1.5e4 DOF, then 0.5 DOF^(2/3): 1e6 DOF -> 5000 contacts
        assert_eq!(dense_contacts_for_dofs(0), DOF_RULE_FLOOR);
        assert_eq!(dense_contacts_for_dofs(10_325), DOF_RULE_FLOOR);
        // 0.5 · 1e6^(2/3) = 5000 up to the rounding of powf: 4999 or 5000
        assert!((4999..=5000).contains(&dense_contacts_for_dofs(1_000_000)));
        // the measured cases of the module docs land on the side that won
        for (contacts, dofs, dense_won) in [
            (121, 21_336, true),     // Hertz level 0
            (329, 103_320, true),    // Hertz --fine 10
            (469, 162_032, true),    // Hertz level 1
            (852, 104_916, true),    // the issue's GetFEM mesh
            (1_089, 53_328, false),  // P1 block, 32 cells
            (2_401, 175_224, false), // P1 block, 48 cells
            (625, 10_325, false),    // thin pad, 24 cells
            (1_369, 22_829, false),  // thin pad, 36 cells
            (2_401, 40_229, false),  // thin pad, 48 cells
        ] {
            assert_eq!(
                contacts <= dense_contacts_for_dofs(dofs),
                dense_won,
                "{contacts} contacts at {dofs} DOF"
            );
        }
    }

    #[test]
    fn issue_38_dof_rule_reasons_display() {
        let within = PathReason::WithinDofRule {
            active: 600,
            dofs: 103_320,
            limit: 1_101,
        };
        assert!(
            within
                .to_string()
                .starts_with("auto: 600 active contacts ≤ 1101")
        );
        let above = PathReason::AboveDofRule {
            active: 625,
            dofs: 10_325,
            limit: 500,
        };
        let c = PathChoice::new(SolvePath::ActiveSet, above);
        assert!(c.to_string().starts_with(
            "active set (auto: 625 active contacts > 500 = max(500, 0.5 DOF^(2/3)) at 10325 DOF"
        ));
    }
}
