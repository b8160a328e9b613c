//! How a Newton that [`Algorithm::Auto`](crate::Algorithm::Auto) chose decides to give up
//! (issue 37): the *probe* of its run, one of three by the storage and symmetry of `W`
//! (`solver/auto.rs` picks it).
//!
//! - [`NewtonProbe::Steps`] (a symmetric `W`): the run gives up on its second short step after
//!   the first ([`creeps`]: the line search failed, or accepted only `t ≤`
//!   `AUTO_NEWTON_SHORT_STEP`), every try counted, the [proximal
//!   regularisation](super::proximal)'s retries too. (Judging an iteration by its last try
//!   instead lets Newton finish on Siconos' `KaplasTower-i1061-4`, 4 Newton steps, each a
//!   failed plain step and a full one with `η = 10⁻⁶`; but its sparse LU costs about 60 ms
//!   there, and that Newton took 511 ms against the sweep's 30: measured and not kept.)
//! - [`NewtonProbe::Progress`] (a sparse `W` kept non-symmetric): the run gives up when its
//!   residual has not halved over the last `AUTO_NEWTON_PROGRESS_WINDOW` iterations, and stops
//!   as converged at the first residual `≤ tol` confirmed on the exact `x = W r + q`, without
//!   waiting for the change of `r` (the sweep-polishing that follows took 100–170 iterations
//!   on Siconos' capsules, half of Newton's run). Measured on the capsules: Newton's first
//!   steps are short while the proximal `η` rises (`t = 2⁻¹⁷ … 2⁻⁹` at iterations 3–6), then
//!   it converges in 29–40 iterations (`Capsules-i100-1090`, `-i103-990`, `-i100-889`), which
//!   the step rule abandoned at iteration 4–5; where it plateaus (`-i101-404` from iteration 24
//!   at 6e-7, `-i122-1617` from 20 at 1.2e-6, for hundreds of iterations) the window ends it.
//! - [`NewtonProbe::Finish`] (the Newton with `ρ` raised that `Auto` runs after the progress
//!   probe gave up and the plain sweep's trial did not promise the tolerance,
//!   `solver/auto/after_probe.rs`): no give-up, the progress probe's stop at the first
//!   confirmed residual `≤ tol` (measured on Siconos' capsules: reached after 30–66
//!   iterations, then 100 more of polishing without it).
//! - [`NewtonProbe::Off`]: no probe (a dense `W` kept non-symmetric, bounded by
//!   `AUTO_NEWTON_UNPROBED_BUDGET`; every Newton a user chose).

use super::super::settings::{AUTO_NEWTON_PROGRESS_WINDOW, AUTO_NEWTON_SHORT_STEP};

/// The probe of a Newton run ([module docs](self)).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) enum NewtonProbe {
    /// No probe: the run ends on its own rules and budget.
    #[default]
    Off,
    /// Give up on the second short iteration after the first.
    Steps,
    /// Give up when the residual stops halving; stop at the first confirmed residual `≤ tol`.
    Progress,
    /// Never give up; stop at the first confirmed residual `≤ tol`.
    Finish,
}

/// A residual at most this fraction of the best before the window counts as progress.
const PROGRESS_FACTOR: f64 = 0.5;

impl NewtonProbe {
    /// Whether the run stops on its residual alone at `residual ≤ tol` (confirmed by the
    /// caller on the exact `x`).
    pub(crate) fn stops_on_residual(self, residual: f64, tol: f64) -> bool {
        matches!(self, Self::Progress | Self::Finish) && residual <= tol
    }

    /// Whether a run whose residuals are `history` (one an iteration) gives up for lack of
    /// progress: the smallest of the last `AUTO_NEWTON_PROGRESS_WINDOW` is not below
    /// `PROGRESS_FACTOR` times the smallest before them.
    ///
    /// ```text
    /// give up at k  ⇔  k > W + 5  and  min h[k−W..k] > ½ min h[..k−W]
    /// ```
    pub(crate) fn gives_up(self, history: &[f64]) -> bool {
        let (k, w) = (history.len(), AUTO_NEWTON_PROGRESS_WINDOW);
        if self != Self::Progress || k <= w + 5 {
            return false;
        }
        let min = |h: &[f64]| h.iter().copied().fold(f64::INFINITY, f64::min);
        let (before, recent) = (min(&history[..k - w]), min(&history[k - w..]));
        let progressed = recent <= PROGRESS_FACTOR * before;
        !progressed
    }

    /// Whether the iteration whose last try ended with `stepped` and step `t` counts as a
    /// short one for [`NewtonProbe::Steps`].
    pub(crate) fn counts_short(self, stepped: bool, t: f64) -> bool {
        self == Self::Steps && creeps(stepped, t)
    }
}

/// Whether a Newton step says that the semi-smooth Newton creeps: its line search failed
/// (`!stepped`) or accepted only a step `t ≤ AUTO_NEWTON_SHORT_STEP` (measured in
/// `docs/benchmarks.md` "Auto on multibody problems": after their first step, converging
/// runs take `t ≥ 2⁻⁴`, the runs that creep for thousands of iterations `t ≤ 2⁻⁶` on most
/// steps).
fn creeps(stepped: bool, t: f64) -> bool {
    !stepped || t <= AUTO_NEWTON_SHORT_STEP
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The progress rule: a residual halving every 10 iterations never gives up; a plateau
    /// gives up once it has lasted the window; short histories and the other probes never.
    #[test]
    fn gives_up_works() {
        let w = AUTO_NEWTON_PROGRESS_WINDOW;
        let halving: Vec<f64> = (0..200).map(|k| 0.5_f64.powf(k as f64 / 10.0)).collect();
        for k in 1..=halving.len() {
            assert!(!NewtonProbe::Progress.gives_up(&halving[..k]), "{k}");
        }
        let mut plateau = vec![1.0, 0.1, 0.01];
        plateau.extend(std::iter::repeat_n(0.009, w + 5));
        assert!(NewtonProbe::Progress.gives_up(&plateau));
        assert!(!NewtonProbe::Steps.gives_up(&plateau));
        assert!(!NewtonProbe::Off.gives_up(&plateau));
        assert!(!NewtonProbe::Finish.gives_up(&plateau));
        assert!(!NewtonProbe::Progress.gives_up(&plateau[..w + 5]));
        // a NaN residual is no progress
        let mut nan = plateau[..w + 5].to_vec();
        nan.push(f64::NAN);
        assert!(NewtonProbe::Progress.gives_up(&nan));
    }

    /// Only the step probe counts short steps, and only failed or short ones; only the
    /// progress probe stops on the residual alone.
    #[test]
    fn counts_short_and_stops_on_residual_work() {
        assert!(NewtonProbe::Steps.counts_short(false, 1.0));
        assert!(NewtonProbe::Steps.counts_short(true, AUTO_NEWTON_SHORT_STEP));
        assert!(!NewtonProbe::Steps.counts_short(true, 2.0 * AUTO_NEWTON_SHORT_STEP));
        assert!(!NewtonProbe::Progress.counts_short(false, 0.0));
        assert!(!NewtonProbe::Off.counts_short(false, 0.0));
        assert!(NewtonProbe::Progress.stops_on_residual(1e-9, 1e-8));
        assert!(!NewtonProbe::Progress.stops_on_residual(1e-7, 1e-8));
        assert!(!NewtonProbe::Steps.stops_on_residual(1e-9, 1e-8));
        assert!(NewtonProbe::Finish.stops_on_residual(1e-9, 1e-8));
        assert!(!NewtonProbe::Finish.stops_on_residual(1e-7, 1e-8));
        assert!(!NewtonProbe::Finish.counts_short(false, 0.0));
    }
}
