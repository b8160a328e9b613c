//! The second way every algorithm stops (issue 37): on the natural-map residual alone, when
//! the change of `r` does not vanish.
//!
//! The [stopping rule](crate::local#stopping-rule) asks for both a relative change of `r` and
//! a relative natural residual `≤ tol`. On a rank-deficient `W` (a hyperstatic stack: four
//! corners carry what three would) the solutions form a set, not a point, and an iteration
//! may keep moving `r` along that set while every iterate already solves the problem to
//! `tol`: the change need not vanish. So a run also stops as converged when its residual has
//! stayed `≤ tol` for a *streak* of iterations as long as the run before it (and at least
//! `MIN_RESIDUAL_STREAK`) over which its change has not halved either (a change still
//! decaying will meet the first test), the residual then confirmed on the exact
//! `x = W r + q`:
//!
//! ```text
//! stop at k   ⇔   res_i ≤ tol for every i in [s, k],   change_k > change_j / 2,
//!                 k − max(s, j) ≥ max(MIN_RESIDUAL_STREAK, s)
//! ```
//! (`j`: the last iteration at which the change halved, as the stall detector tracks the
//! residual.) The first test (both change and residual) is tried first and is unchanged, so
//! every run that met it before this one fires stops at the same iteration with the same
//! answer. Over `cargo test -p contact-solver --test integration` every printed number and
//! iteration count stays as it was (the seed's sweep table included) but one: the error of a
//! floating block pushed beyond its friction limit (no equilibrium; `issue_35_floating_3d`),
//! some of whose reduced solves now stop on their residual alone, and
//! whose reported direction moves by 2e-10. A run that ends (at `max_iterations` or
//! stalled) with a residual `≤ tol` on the exact `x` is converged too (the dispatcher's
//! [`UzawaSolver`](crate::UzawaSolver) tests it), and the independent check of the answer
//! stays.
//!
//! The residual is the one the loops compute anyway (every iteration; every
//! `RESIDUAL_CHECK_EVERY` sweeps inside the classical solver's sub-problems), so the rule costs
//! a comparison per iteration and one product `W r` per streak.

/// The shortest streak of iterations with a residual `≤ tol` that stops a run on the residual
/// alone.
pub(crate) const MIN_RESIDUAL_STREAK: usize = 100;

/// The classical solver's sub-problems compute the natural residual of the whole problem every
/// this many sweeps (one projection per contact: a fraction of a sweep's cost).
pub(crate) const RESIDUAL_CHECK_EVERY: usize = 4;

/// The state of the rule over one run.
#[derive(Clone, Debug, Default)]
pub(crate) struct ResidualStop {
    /// The first iteration of the current streak of residuals `≤ tol`.
    since: Option<usize>,
    /// The change of reference and the iteration it was set (when the change halved).
    change_ref: f64,
    change_since: usize,
}

impl ResidualStop {
    /// Records the residual of iteration `k`; `true` when the streak is long enough to stop
    /// (the caller confirms on the exact `x`, and calls [`reset`](Self::reset) if that fails).
    pub(crate) fn met(&mut self, k: usize, residual: f64, change: f64, tol: f64) -> bool {
        if self.change_since == 0 || change <= 0.5 * self.change_ref || change.is_nan() {
            (self.change_ref, self.change_since) = (change, k);
        }
        if residual.is_nan() || residual > tol {
            self.since = None;
            return false;
        }
        let since = *self.since.get_or_insert(k);
        k - since.max(self.change_since) >= MIN_RESIDUAL_STREAK.max(since)
    }

    /// Starts over (the exact residual did not confirm the streak).
    pub(crate) fn reset(&mut self) {
        self.since = None;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn residual_stop_works() {
        let mut s = ResidualStop::default();
        // above tol: never
        assert!(!(1..50).any(|k| s.met(k, 1e-3, 1e-6, 1e-8)));
        // a streak from 50 at a constant change: stops at 150 (max(100, 50) later), not before
        assert!(!(50..150).any(|k| s.met(k, 1e-9, 1e-6, 1e-8)));
        assert!(s.met(150, 1e-9, 1e-6, 1e-8));
        // a residual above tol (or NaN) restarts the streak; a streak from 300 needs 300 more
        assert!(!s.met(151, f64::NAN, 1e-6, 1e-8));
        s.reset();
        assert!(!(300..600).any(|k| s.met(k, 1e-9, 1e-6, 1e-8)));
        assert!(s.met(600, 1e-9, 1e-6, 1e-8));
        // a change that halves every 50 iterations (still converging) never stops it
        let mut s = ResidualStop::default();
        let halving = |k: usize| 1e-6 * 0.5f64.powf(k as f64 / 50.0);
        assert!(!(1..2000).any(|k| s.met(k, 1e-9, halving(k), 1e-8)));
    }
}
