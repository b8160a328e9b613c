//! What [`Algorithm::Auto`] runs after its Newton under the progress probe gave up (issue 37,
//! ninth part: a sparse `W` kept non-symmetric, Siconos' capsules): a trial of the plain
//! Gauss–Seidel sweep from Newton's iterate, read by its rate; then either the sweep goes on,
//! or Newton again from the sweep's iterate with `ρ` raised (`newton/rho_raise.rs`), stopping
//! at the first confirmed residual `≤ tol` ([`NewtonProbe::Finish`]).
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
//! Measured (`docs/benchmarks.md`, "The capsules' plateau (issue 37, ninth part)"): where
//! Newton plateaus on the capsules (`Capsules-i122-1617` at 1.2e-6, `-i101-404` at 6e-7,
//! given up at iteration 44–45) the plain sweep from its iterate plateaus too: on
//! `-i122-1617` at 1.1e-6 for 450 sweeps, then at 1e-7 for 5 000 (the old chain ran it to
//! its stall, then the last Newton: 5 972 iterations in all), on `-i101-404` at 3e-7 for 550
//! sweeps before its active set settles (1 457 in all). Its rate over the last 50 of 200
//! sweeps promises `tol` after 2 947 sweeps on `-i101-404` (the sweep goes on: 1 457 in all,
//! where the raised Newton's 27 iterations cost more) and never on `-i122-1617`, where
//! Newton with `ρ` raised from the trial's iterate reaches `tol` in 75 iterations (320 in
//! all, 5 972 before). On a loose sphere pile with
//! a one-way coupling (`tests/integration/issue_37_auto_multibody.rs`'s family), where Newton
//! plateaus at 1.8e-5 and the raised Newton fails for 2 000 iterations, the sweep contracts
//! steadily after 100 sweeps and the same rate promises `tol` at about 735 sweeps: it goes on.
//! `AFTER_PROBE_PREDICTED` (the raised Newton's cost in sweeps) is 1.7× the first and 7× the
//! second; a first setting of 1 500 sent `-i101-404` to Newton, 1.4× slower. Where the rate misleads
//! (a pile of the same family with `δ = 5·10⁻²`, 134 contacts: the sweep plateaus at 3e-7
//! for 1 500 sweeps and then converges, the raised Newton oscillates between 1e-6 and 5e-4)
//! `AFTER_PROBE_NEWTON` bounds the detour, and the sweep resumes from its own iterate.

use super::super::super::newton::NewtonProbe;
use super::super::super::problem::ReducedProblem;
use super::super::super::settings::{Algorithm, Solution, UzawaSettings};
use super::super::UzawaSolver;
use super::last_newton;
use crate::error::{BestIterate, SolverError};
use contact_laws::ContactLaw;

/// Sweeps of the plain Gauss–Seidel trial from Newton's iterate.
const AFTER_PROBE_TRIAL: usize = 200;
/// Sweeps over which the trial's rate is read (the sweep's residual on a plateau wanders by
/// a few per cent from sweep to sweep; four sweeps, as in `sweep_promises`, read noise).
const AFTER_PROBE_SPAN: usize = 50;
/// Sweeps in all (the trial's included) within which the trial's rate must promise `tol`
/// for the sweep to go on: about what the raised Newton costs where it converges (27–75
/// iterations on the capsules, a sparse LU each, about 50–70 sweeps an iteration there).
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

    /// The measured shapes of the module docs: a sweep contracting by 0.9877 a sweep from
    /// 7.5e-6 at sweep 200 promises 1e-8 near sweep 735, one by 0.99875 from 3.1e-7 near
    /// 2 947 (both go on); one by 0.9995 (near 7 000) does not; a plateau, a rising or NaN
    /// history, or one of at most `span` sweeps never; a history at `tol` always.
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
