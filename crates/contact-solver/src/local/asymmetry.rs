//! What a [`ReducedProblem`](super::ReducedProblem) does with a `W` that is not symmetric: the
//! [`Asymmetry`] policy of its constructors and readers (documented on the type).

/// Asymmetry below which `W` is taken as given: `|W_ij − W_ji| ≤ 1e-12 · max|W|` (round-off
/// of a symmetric assembly).
pub(crate) const SYMMETRY_TOL: f64 = 1e-12;

/// Default relative asymmetry [`Asymmetry::Symmetrise`] repairs: up to
/// `|W_ij − W_ji| ≤ 1e-6 · max|W|` (round-off of the exporting code).
pub(crate) const DEFAULT_ASYMMETRY_TOL: f64 = 1e-6;

/// What a reduced problem's constructor does with a `W` whose relative asymmetry
/// `max|W_ij − W_ji| / max|W|` exceeds round-off (`1e-12`).
///
/// ```text
/// a = max|W_ij − W_ji| / max|W|          (relative asymmetry of the W given)
/// a ≤ 1e-12 (SYMMETRY_TOL)               taken as given, as symmetric (round-off), every policy
/// Refuse                                 a > 1e-12: SolverError::NotSymmetric
/// Symmetrise { tolerance }               a ≤ tolerance: W ← (W + Wᵀ)/2, reported by asymmetry();
///                                        beyond: NotSymmetric            (the default, 1e-6)
/// Keep                                   W kept as given; the algorithms solve x = W r + q on it
/// ```
///
/// Multibody codes (joints, bilateral constraints, some integrators) export Delassus operators
/// whose asymmetry is a property of the model, not round-off: symmetrising changes the answer
/// (on the issue-37 problems, asymmetry 9e-6 to 1.7e-3 of the scale, the answers of the
/// symmetrised problems miss by 6.7e-6 to 2.7e-5 on the real `W`). [`Asymmetry::Keep`] solves
/// the problem as given: the algorithms whose steps need only the diagonal blocks and the
/// columns of `W` (the Gauss–Seidel sweeps and their Anderson acceleration, the classical
/// split, the semismooth Newton, whose Newton system is non-symmetric anyway) accept it — their
/// fixed point is the zero of the natural map on the real `W`, though no energy guarantees
/// their convergence as for a symmetric `W`, hence the check below; the Uzawa
/// variants, whose step is a projected gradient of the symmetric energy, refuse it
/// ([`SolverError::NeedsSymmetricW`](crate::SolverError::NeedsSymmetricW)); `Auto` chooses among
/// the first. Every answer on a kept `W` is checked by the natural-map residual recomputed
/// from `x = W r + q` with the rows of the real `W`.
///
/// The default stays [`Symmetrise`](Asymmetry::Symmetrise) with `1e-6`, the behaviour before
/// this policy existed (no answer changes); FCLIB files, written by other codes, are read with
/// [`Keep`](Asymmetry::Keep).
///
/// # Examples
/// ```
/// use contact_solver::{Asymmetry, ReducedProblem, SolverError};
/// // asymmetry 1e-3 of the scale: refused by default, kept on request
/// let w = vec![2.0, 0.3, 0.3 + 2e-3, 1.0];
/// let (q, mu) = (vec![-1.0, 0.5], vec![0.3]);
/// let e = ReducedProblem::new(w.clone(), q.clone(), mu.clone());
/// assert!(matches!(e, Err(SolverError::NotSymmetric { .. })));
/// let p = ReducedProblem::with_asymmetry(2, w, q, mu, Asymmetry::Keep)?;
/// assert!(!p.is_symmetric() && (p.kept_asymmetry() - 1e-3).abs() < 1e-12);
/// # Ok::<(), SolverError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Asymmetry {
    /// Refuse any asymmetry beyond round-off (`1e-12`):
    /// [`SolverError::NotSymmetric`](crate::SolverError::NotSymmetric).
    Refuse,
    /// Replace `W` by `(W + Wᵀ)/2` when the relative asymmetry is at most `tolerance` (and
    /// report it, [`ReducedProblem::asymmetry`](super::ReducedProblem::asymmetry)); refuse it
    /// beyond. The default, with `tolerance = 1e-6`.
    Symmetrise {
        /// Largest relative asymmetry repaired (finite, `≥ 0`).
        tolerance: f64,
    },
    /// Keep `W` as given, whatever its asymmetry (each diagonal block's symmetric part must
    /// still be positive definite); the algorithms that need symmetry refuse it.
    Keep,
}

impl Default for Asymmetry {
    /// `Symmetrise { tolerance: 1e-6 }`: the behaviour of [`ReducedProblem::new`](super::ReducedProblem::new).
    fn default() -> Self {
        Self::Symmetrise {
            tolerance: DEFAULT_ASYMMETRY_TOL,
        }
    }
}

impl Asymmetry {
    /// The relative asymmetry up to which `W` is symmetrised (`None`: kept at any size).
    pub(crate) fn symmetrise_up_to(self) -> Option<f64> {
        match self {
            Self::Refuse => Some(0.0),
            Self::Symmetrise { tolerance } => Some(tolerance),
            Self::Keep => None,
        }
    }
}
