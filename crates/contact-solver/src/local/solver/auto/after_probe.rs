//! What [`Algorithm::Auto`] runs after its Newton under the progress probe gave up (issue 37,
//! ninth part: a sparse `W` kept non-symmetric, Siconos' capsules): a trial of the plain
//! Gauss–Seidel sweep from Newton's iterate, then, where it neither converged nor promises the
//! tolerance at its rate, Newton again from the sweep's iterate with `ρ` raised
//! (`newton/rho_raise.rs`), stopping at the first confirmed residual `≤ tol`
//! ([`NewtonProbe::Finish`]).
//!
//! ```text
//! sweeps ≤ AFTER_PROBE_TRIAL from Newton's iterate
//! converged                                        → its answer
//! ρ = (h_k / h_{k−S})^{1/S}, S = AFTER_PROBE_SPAN,
//!   k + ln(tol / h_k) / ln ρ ≤ AFTER_PROBE_PREDICTED  → the sweep goes on (the solver's chain)
//! otherwise                                        → Newton, ρ raised, from the sweep's iterate,
//!                                                    at most AFTER_PROBE_NEWTON iterations
//! not converged                                    → the sweep goes on from the trial's iterate
//! ```
//!
//! Measured (`docs/benchmarks.md`, "The capsules' plateau (issue 37, ninth part)"): Newton
//! plateaus on three capsule files (`Capsules-i122-1617` at 1.2e-6, `-i101-404` at 6e-7,
//! FCLIB's `-i125-1213` at 2.5e-7; given up at iteration 40–45), and the plain sweep from its
//! iterate plateaus too, then drops when its active set settles: after 1 413 sweeps on
//! `-i101-404`, 2 214 on `-i125-1213`, never on `-i122-1617` (at 1e-7 for 5 000 sweeps, to
//! its stall; the old chain then ran the last Newton from the start: 5 972 iterations in
//! all). Nothing in the sweep's first hundreds of sweeps tells the three apart (flat on each),
//! so the trial is long: `AFTER_PROBE_TRIAL` = 3 000 sweeps, 1.35× the slowest drop measured,
//! about what the raised Newton costs where it converges (27–75 iterations there, a sparse LU
//! each, about 50–70 sweeps an iteration). On `-i122-1617` Newton with `ρ` raised from the
//! trial's iterate then reaches `tol` in about 75 iterations. A first version with a trial of
//! 200 sweeps read by its rate sent `-i101-404` and `-i125-1213` to the raised Newton, 1.4–1.6×
//! slower than the sweep. Where the raised Newton fails (a loose sphere pile with a one-way
//! coupling of `δ = 5·10⁻²`, `tests/integration/issue_37_auto_multibody.rs`'s family: it
//! oscillates between 1e-6 and 5e-4) `AFTER_PROBE_NEWTON` bounds the detour and the sweep
//! resumes from its own iterate.

use super::super::super::newton::NewtonProbe;
use super::super::super::problem::ReducedProblem;
use super::super::super::settings::{Algorithm, Solution, UzawaSettings};
use super::super::UzawaSolver;
use super::last_newton;
use crate::error::{BestIterate, SolverError};
use contact_laws::ContactLaw;

/// Sweeps of the plain Gauss–Seidel trial from Newton's iterate (module docs).
const AFTER_PROBE_TRIAL: usize = 3000;
/// Sweeps over which the trial's rate is read (the sweep's residual on a plateau wanders by
/// a few per cent from sweep to sweep; four sweeps, as in `sweep_promises`, read noise).
const AFTER_PROBE_SPAN: usize = 50;
/// Sweeps in all (the trial's included) within which the trial's rate must promise `tol`
/// for the sweep to go on rather than the raised Newton (whose cost is about 2 000–5 000
/// sweeps where it converges, module docs).
const AFTER_PROBE_PREDICTED: f64 = 5000.0;
/// Iterations of the raised Newton (the converging runs measured took 3–75).
const AFTER_PROBE_NEWTON: usize = 150;

/// What [`UzawaSolver::after_progress_probe`] leaves to the solver's chain.
pub(in crate::local::solver) struct AfterProbe {
    /// The answer so far, converged or not.
    pub(in crate::local::solver) sol: Solution,
    /// Where the chain's sweep goes on from: the sweep trial's iterate.
    pub(in crate::local::solver) resume: Vec<f64>,
    /// Whether the raised Newton ran (the chain then skips its own last Newton).
    pub(in crate::local::solver) raised: bool,
}

/// Whether the sweep whose relative residuals are `history` (one a sweep) promises `tol`
/// within `within` sweeps in all at the rate of its last `span` sweeps (module docs). A
/// history at `tol` promises it; one of at most `span` sweeps, or not contracting (`ρ ≥ 1`,
/// a NaN), does not.
fn promises_over(history: &[f64], tol: f64, span: usize, within: f64) -> bool {
    let k = history.len();
    let Some(&last) = history.last() else {
        return false;
    };
    if last <= tol {
        return true;
    }
    if k <= span {
        return false;
    }
    let rate = (last / history[k - 1 - span]).powf(1.0 / span as f64);
    if rate.is_nan() || rate >= 1.0 || rate <= 0.0 {
        return false;
    }
    k as f64 + (tol / last).ln() / rate.ln() <= within
}

impl UzawaSolver {
    /// The runs after `Auto`'s Newton under the progress probe gave up (`sol`, its iterate):
    /// the sweep's trial, then Newton with `ρ` raised where the trial does not promise `tol`
    /// ([module docs](self)).
    #[allow(clippy::too_many_arguments)]
    pub(in crate::local::solver) fn after_progress_probe<L: ContactLaw, const DT: usize>(
        &mut self,
        st: UzawaSettings,
        sol: Solution,
        problem: &ReducedProblem,
        laws: &[L],
        states: &[L::State],
        mu: Option<&[f64]>,
        best_iterate: &mut Option<Box<BestIterate>>,
    ) -> Result<AfterProbe, SolverError> {
        let trial = UzawaSettings {
            algorithm: Algorithm::GaussSeidel,
            max_iterations: st.max_iterations.min(AFTER_PROBE_TRIAL),
            ..st
        };
        let (start, previous) = (sol.r.clone(), sol.report.history.len());
        let sol = self.run_after::<L, DT>(
            trial,
            st.algorithm,
            sol,
            problem,
            laws,
            states,
            &start,
            mu,
            best_iterate,
        )?;
        let sweeps = &sol.report.history[previous..];
        if sol.report.converged
            || promises_over(sweeps, st.tol, AFTER_PROBE_SPAN, AFTER_PROBE_PREDICTED)
        {
            let resume = sol.r.clone();
            return Ok(AfterProbe {
                sol,
                resume,
                raised: false,
            });
        }
        let resume = sol.r.clone();
        let newton = UzawaSettings {
            max_iterations: st.max_iterations.min(AFTER_PROBE_NEWTON),
            ..last_newton(st)
        };
        (self.newton.raise_rho, self.newton.probe) = (true, NewtonProbe::Finish);
        let after = self.run_after::<L, DT>(
            newton,
            st.algorithm,
            sol,
            problem,
            laws,
            states,
            &resume,
            mu,
            best_iterate,
        );
        (self.newton.raise_rho, self.newton.probe) = (false, NewtonProbe::Off);
        Ok(AfterProbe {
            sol: after?,
            resume,
            raised: true,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sweep contracting by 0.9877 a sweep from 7.5e-6 at sweep 200 promises 1e-8 near
    /// sweep 735, one by 0.99875 from 3.1e-7 near 2 947 (both within 5 000); one by 0.9995
    /// (near 7 000) does not; a plateau, a rising or NaN history, or one of at most `span`
    /// sweeps never; a history at `tol` always.
    #[test]
    fn promises_over_works() {
        let from = |h0: f64, rate: f64| {
            (0..200)
                .map(|k| h0 * rate.powi(k - 199))
                .collect::<Vec<_>>()
        };
        let (tol, span, within) = (1e-8, AFTER_PROBE_SPAN, AFTER_PROBE_PREDICTED);
        assert!(promises_over(&from(7.5e-6, 0.9877), tol, span, within));
        assert!(promises_over(&from(3.1e-7, 0.99875), tol, span, within));
        assert!(!promises_over(&from(3.1e-7, 0.9995), tol, span, within));
        assert!(!promises_over(&from(1.1e-6, 1.0), tol, span, within));
        assert!(!promises_over(&from(1.1e-6, 1.01), tol, span, within));
        assert!(!promises_over(&from(1e-3, 0.5)[..span], tol, span, within));
        assert!(promises_over(&[1.0, 1e-9], tol, span, within));
        assert!(!promises_over(&[], tol, span, within));
        let mut nan = from(7.5e-6, 0.9877);
        nan.push(f64::NAN);
        assert!(!promises_over(&nan, tol, span, within));
    }
}
