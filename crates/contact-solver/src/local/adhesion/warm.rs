//! When a sequence of adhesive steps tries Newton from the previous step's reactions
//! ([`AdhesionOptions::warm_start`](super::AdhesionOptions::warm_start)).

use super::AdhesiveSolution;

/// Longest pause, in steps, after failed warm starts.
const MAX_PAUSE: usize = 32;

/// Paces the warm start over a sequence of steps: tried on every step while it works; after a
/// failure it pauses for 1, 2, 4, … (at most 32) steps, doubling while the retries fail. A
/// scene where it works (the seed's 5.6.2 and pile: 1–3 Newton iterations per step, no
/// condensation) keeps it; one where it never does (5.6.1, whose steps move the reactions too
/// far) pays for it on a few steps only.
///
/// ```
/// use contact_solver::local::adhesion::WarmStartPacing;
/// let mut pacing = WarmStartPacing::default();
/// assert!(pacing.enabled());
/// pacing.record_outcome(false, true); // failed: paused for one step
/// assert!(!pacing.enabled());
/// assert!(pacing.enabled());
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct WarmStartPacing {
    pause: usize,
    next_pause: usize,
}

impl WarmStartPacing {
    /// Whether this step tries the warm start (call once per step).
    pub fn enabled(&mut self) -> bool {
        if self.pause > 0 {
            self.pause -= 1;
            false
        } else {
            true
        }
    }

    /// Records a step's outcome: whether the warm start solved it, and whether it failed.
    pub fn record_outcome(&mut self, warm_started: bool, failed: bool) {
        if failed {
            self.next_pause = (2 * self.next_pause).clamp(1, MAX_PAUSE);
            self.pause = self.next_pause;
        } else if warm_started {
            self.next_pause = 0;
        }
    }

    /// [`record_outcome`](Self::record_outcome) of a solution.
    pub fn record<S>(&mut self, sol: &AdhesiveSolution<S>) {
        self.record_outcome(sol.warm_started, sol.warm_start_failed);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pauses_double_while_retries_fail_and_reset_on_success() {
        let mut p = WarmStartPacing::default();
        let mut tried = Vec::new();
        // fails on every try for 20 steps
        for _ in 0..20 {
            let on = p.enabled();
            tried.push(on);
            if on {
                p.record_outcome(false, true);
            }
        }
        let steps: Vec<usize> = (0..20).filter(|&k| tried[k]).collect();
        // tried at 0, then after pauses of 1, 2, 4, 8 steps
        assert_eq!(steps, vec![0, 2, 5, 10, 19]);
        // a success resets the pause
        while !p.enabled() {}
        p.record_outcome(true, false);
        p.record_outcome(false, true);
        assert!(!p.enabled());
        assert!(p.enabled());
    }
}
