//! The stall detector shared by every algorithm loop (issue 14): an iteration that makes no
//! progress is stopped early, so the fallback starts sooner and the error says it stalled.
//!
//! After each iteration the loop hands the detector the iterations done `k` and the relative
//! natural residual `res_k` (the value it pushes to the history). The detector keeps a
//! *reference* residual `ref`, set at the first finite residual and reset to `res_k` whenever
//! `res_k ≤` `STALL_FACTOR`` · ref` (the residual has halved since the reference was set, at
//! iteration `j`):
//!
//! ```text
//! stalled at k   ⇔   window > 0   and   k − j ≥ max(window, ⌊k/2⌋)
//! ```
//! i.e. the residual has not halved over the last `window` iterations, nor over the second
//! half of the run. The `⌊k/2⌋` term lets slow but steady convergence through: a residual
//! that halves every `h` iterations is never cut once `k ≥ 2h`, however large `h`. What is cut
//! is a plateau, or a decay slower than geometric (a residual `~ 1/k` halves only when `k`
//! doubles, which is what an unsolvable problem gives as `r` grows without bound).
//! `window` is [`UzawaTuning::stall_window`](crate::UzawaTuning::stall_window), `0` to
//! switch the detector off.

/// A residual at most this fraction of the reference counts as progress.
pub(crate) const STALL_FACTOR: f64 = 0.5;

/// The smallest non-zero [`UzawaTuning::stall_window`](crate::UzawaTuning::stall_window)
/// accepted: a fixed-point iteration cannot be asked to halve its residual in fewer steps
/// (Anderson's safeguard alone wastes a step per rejection, Newton warms up with sweeps).
///
/// Public because a user who sets the window must know the least value the solver accepts
/// (a smaller one is [`SolverError::InvalidSetting`](crate::SolverError::InvalidSetting));
/// the CLI checks its `[solver] stall_window` key against it.
pub const MIN_STALL_WINDOW: usize = 10;

/// The default [`UzawaTuning::stall_window`](crate::UzawaTuning::stall_window).
///
/// Measured with the detector off over every solve of `cargo test -p contact-solver` (1620
/// algorithm runs, 1437 of them converging, and 11 457 sub-problems of the classical solver):
/// the smallest window that cuts no converging run is 2532 iterations (a run converging at
/// iteration 15 946 whose residual did not halve between about iterations 2530 and 5060); the
/// longest plateau of any converging run is 4754 iterations (at iteration 52 468, where the
/// `k/2` term covers it); the classical sub-problems need at most 12. 5000 is twice the worst
/// case. On a problem with no solution (residual `~ 1/k`) the detector then fires after about
/// 15 000 iterations (`tests/integration/stall.rs`), so it saves nothing under the default
/// `max_iterations` (10 000) but most of a larger one (hard problems are given 100 000).
pub(crate) const DEFAULT_STALL_WINDOW: usize = 5000;

/// The state of the detector over one run of an algorithm.
#[derive(Clone, Debug)]
pub(crate) struct StallDetector {
    window: usize,
    /// The reference residual and the iteration at which it was set.
    reference: f64,
    since: usize,
}

impl StallDetector {
    /// A detector with this window (`0`: never stalls).
    pub(crate) fn new(window: usize) -> Self {
        Self {
            window,
            reference: f64::INFINITY,
            since: 0,
        }
    }

    /// Records `residual` after `iterations` iterations; `true` when the run has stalled.
    pub(crate) fn stalled(&mut self, iterations: usize, residual: f64) -> bool {
        if residual <= STALL_FACTOR * self.reference {
            self.reference = residual;
            self.since = iterations;
        }
        let plateau = iterations - self.since;
        self.window > 0 && plateau >= self.window.max(iterations / 2)
    }
}
