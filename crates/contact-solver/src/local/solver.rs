//! The dispatcher of the reduced-problem solvers: [`UzawaSolver`] validates the settings and
//! the starting point, runs the chosen [`Algorithm`] (one file each, below it), and reports.

use super::anderson::AndersonScratch;
use super::classic::ClassicScratch;
use super::dense::KeptLu;
use super::newton::{NewtonProbe, NewtonScratch};
use super::problem::ReducedProblem;
use super::residual::{
    coulomb_residual, friction_coefficients, natural_residual, norm, penetration,
};
use super::settings::{Algorithm, Solution, UzawaSettings};
use super::stall::MIN_STALL_WINDOW;
use super::sweep::Sweeps;
use crate::error::{BestIterate, SolverError};
use contact_laws::ContactLaw;

mod attempt;
mod auto;
mod classic_first;
mod direct;
mod rescale;
mod skip_open;

use auto::{
    auto_contact_solve, auto_newton_budget, last_newton, newton_pays, newton_probe, pressed_most,
    sparse_twin_for_auto, sweep_after_newton, sweep_probe, sweep_promises,
};

/// A converged answer of a Coulomb-type problem must satisfy the Signorini–Coulomb conditions
/// checked without the modified velocity to this factor of the tolerance (relative), or it is
/// not accepted (see [`UzawaSettings::fallback`]). Near a solution both residuals are of the
/// same order; a penetration hidden by `x_n + μ̄|x_t|` (huge `μ̄`) is of order one. The
/// largest penetration `max(−x_n)⁺` must also be within this factor of the tolerance relative
/// to `max(‖q‖∞, ‖W r‖∞)`, or the run counts as stalled: an iteration whose reactions grow
/// without bound (no solution) brings the relative residual to 0 while `x_n` stays at the
/// scale of `q` (measured over the test suite: converged answers reach at most 74 × tol, the
/// unsolvable problem of `tests/integration/stall.rs` 1e10 × tol).
pub(crate) const CHECK_FACTOR: f64 = 1e3;

/// On a kept non-symmetric `W`, the natural residual recomputed from `x = W r + q` must be
/// within this factor of the tolerance: the algorithm stopped on its own `x`, updated column
/// by column, which differs from the recomputed one by round-off (`~1e-16 · cond`, far below
/// `tol`); the factor only keeps an answer stopped just under `tol` from being refused.
pub(crate) const KEPT_CHECK_FACTOR: f64 = 2.0;

/// `W`, `q` or the reactions' scale `max|q|/max|W|` with magnitudes beyond
/// `[1/RESCALE_ABOVE, RESCALE_ABOVE]` are rescaled internally (scale-invariant laws only).
pub(crate) const RESCALE_ABOVE: f64 = 1e100;

/// The reduced-problem solver: settings plus scratch buffers reused across solves.
///
/// # Examples
/// ```
/// use contact_solver::{ReducedProblem, UzawaSettings, UzawaSolver};
/// // One contact, W = I, pressed by q_n = −1 with a tangential push 0.5 and μ = 0.2: slip.
/// let p = ReducedProblem::new(vec![1.0, 0.0, 0.0, 1.0], vec![-1.0, 0.5], vec![0.2])?;
/// let sol = UzawaSolver::new(UzawaSettings::default()).solve(&p, &p.coulomb_laws())?;
/// assert!((sol.r[0] - 1.0).abs() < 1e-9 && (sol.r[1] + 0.2).abs() < 1e-9);
/// # Ok::<(), contact_solver::SolverError>(())
/// ```
#[derive(Clone, Debug, Default)]
pub struct UzawaSolver {
    settings: UzawaSettings,
    sweeps: Sweeps,
    classic: ClassicScratch,
    anderson: AndersonScratch,
    newton: NewtonScratch,
    /// The factors of the adhesive Newton's last Jacobian, for its chord steps.
    kept_lu: KeptLu,
    /// Whether [`Algorithm::Auto`]'s Newton on the problem being solved sweeps first
    /// ([`pressed_most`]), set where `Auto` chooses.
    sweep_first: bool,
}

/// Solves `problem` with one Coulomb law `Coulomb::new(μ_i)` per contact — the entry point for
/// a problem read from JSON or exported by another FE code.
///
/// # Errors
/// [`SolverError::NotConverged`] unless `settings.accept_non_converged`.
///
/// # Examples
/// ```
/// use contact_solver::{ReducedProblem, UzawaSettings, solve_coulomb};
/// let p = ReducedProblem::new(vec![2.0, 0.0, 0.0, 2.0], vec![-1.0, 0.5], vec![0.8])?;
/// let sol = solve_coulomb(&p, &UzawaSettings::default())?;
/// assert!((sol.r[1] + 0.25).abs() < 1e-9); // stick: r_t = −q_t/f
/// # Ok::<(), contact_solver::SolverError>(())
/// ```
pub fn solve_coulomb(
    problem: &ReducedProblem,
    settings: &UzawaSettings,
) -> Result<Solution, SolverError> {
    UzawaSolver::new(*settings).solve(problem, &problem.coulomb_laws())
}

impl UzawaSolver {
    /// A solver with these settings (buffers are sized at the first solve).
    pub fn new(settings: UzawaSettings) -> Self {
        Self {
            settings,
            ..Self::default()
        }
    }

    /// The settings.
    pub fn settings(&self) -> &UzawaSettings {
        &self.settings
    }

    /// The factors the adhesive Newton keeps between iterations and between steps.
    pub(crate) fn kept_lu(&mut self) -> &mut KeptLu {
        &mut self.kept_lu
    }

    /// The settings, to change for one solve.
    pub(crate) fn settings_mut(&mut self) -> &mut UzawaSettings {
        &mut self.settings
    }

    /// Solves `problem` from `r = 0` with the laws' initial states.
    ///
    /// `laws` holds one law per contact, or a single law shared by all contacts.
    ///
    /// # Errors
    /// [`SolverError::SizeMismatch`] if `laws` has neither 1 nor `n_c` entries;
    /// [`SolverError::FrictionMismatch`] if a law's friction coefficient disagrees with the
    /// problem's `μ_i`; [`SolverError::NotConverged`] unless `accept_non_converged`.
    pub fn solve<L: ContactLaw>(
        &mut self,
        problem: &ReducedProblem,
        laws: &[L],
    ) -> Result<Solution, SolverError> {
        let states: Vec<L::State> = laws.iter().map(|l| l.initial_state()).collect();
        self.solve_with_states(problem, laws, &states, None)
    }

    /// Solves `problem` with given per-contact states (1 shared or `n_c`) and an optional
    /// starting reaction `r_start` (warm start, `m` entries).
    ///
    /// # Errors
    /// [`SolverError::SizeMismatch`] if `laws`, `states` or `r_start` has the wrong length;
    /// [`SolverError::FrictionMismatch`] if a law's friction coefficient in its state
    /// disagrees with the problem's `μ_i` (μ has one owner, the law: build the problem with
    /// [`ReducedProblem::with_friction_of`]);
    /// [`SolverError::NonFinite`] if `r_start` is not finite, or `tol` or `rho_scale` is not
    /// finite and positive; [`SolverError::InvalidSetting`] if `omega` is not in `(0, 2)` or
    /// `stall_window` is neither 0 nor at least
    /// [`MIN_STALL_WINDOW`](crate::local::stall::MIN_STALL_WINDOW);
    /// for [`Algorithm::ClassicRccm`], [`SolverError::NoFrictionCoefficient`] if a law's
    /// [`friction_coefficient`](ContactLaw::friction_coefficient) is `None` and
    /// [`SolverError::InvalidLaw`] if it is negative or not finite;
    /// [`SolverError::Stalled`] when the [stall detector](crate::local::stall) stopped the
    /// (last) run, [`SolverError::NotConverged`] when it reached `max_iterations`, unless
    /// `accept_non_converged`.
    pub fn solve_with_states<L: ContactLaw>(
        &mut self,
        problem: &ReducedProblem,
        laws: &[L],
        states: &[L::State],
        r_start: Option<&[f64]>,
    ) -> Result<Solution, SolverError> {
        let mut st = self.settings;
        let r = starting_reactions(&st, problem, laws.len(), states.len(), r_start)?;
        // μ has one owner, the law: the problem's coefficients may not disagree (friction.rs)
        problem.check_friction_of(laws, states)?;
        let mu = friction_coefficients(laws, states, problem.contact_count());
        let auto = st.algorithm == Algorithm::Auto;
        // a multibody W stored dense is solved stored sparse, unless the restriction to the
        // contacts that may close pays (it needs the dense W)
        if auto
            && mu.is_some()
            && !skip_open::restriction_pays(&st, problem, &r)
            && let Some(sparse) = sparse_twin_for_auto(problem)
        {
            return self.solve_with_states(&sparse, laws, states, r_start);
        }
        if auto {
            st.algorithm = if mu.is_some() && newton_pays(problem) {
                Algorithm::Newton
            } else {
                Algorithm::AndersonGaussSeidel
            };
            self.sweep_first = st.algorithm == Algorithm::Newton && pressed_most(problem);
            st = auto_contact_solve(st, problem);
        }
        // the Uzawa step is a projected gradient of the energy ½ rᵀ W r + qᵀ r: it needs W
        // symmetric (the sweeps and Newton need only the diagonal blocks, see `asymmetry`)
        if !problem.is_symmetric()
            && matches!(st.algorithm, Algorithm::Uzawa | Algorithm::AndersonUzawa)
        {
            return Err(SolverError::NeedsSymmetricW {
                algorithm: st.algorithm.name(),
                asymmetry: problem.kept_asymmetry(),
            });
        }
        if let Some(sol) = self.solve_rescaled(problem, laws, states, &r)? {
            return Ok(sol);
        }
        match problem.dimension() {
            3 => self.solve_checked::<L, 2>(st, auto, problem, laws, states, r, mu.as_deref()),
            _ => self.solve_checked::<L, 1>(st, auto, problem, laws, states, r, mu.as_deref()),
        }
    }

    /// The rest of [`solve_with_states`](Self::solve_with_states) once the inputs are checked,
    /// the algorithm chosen (by [`Algorithm::Auto`] when `auto`) and the magnitudes in range,
    /// for tangent dimension `DT`: the open shortcut, the algorithm, the check of its answer
    /// and the fallback.
    #[allow(clippy::too_many_arguments)]
    fn solve_checked<L: ContactLaw, const DT: usize>(
        &mut self,
        st: UzawaSettings,
        auto: bool,
        problem: &ReducedProblem,
        laws: &[L],
        states: &[L::State],
        r: Vec<f64>,
        mu: Option<&[f64]>,
    ) -> Result<Solution, SolverError> {
        self.sweeps.reset(problem, st.tuning.rho_scale);
        if r.iter().all(|&v| v == 0.0)
            && let Some(sol) = self.open_solution::<L, DT>(st.algorithm, problem, laws, states, mu)
        {
            return Ok(sol);
        }
        if auto
            && let Some(mu) = mu
            && problem.contact_count() == 1
            && let Some(sol) = self.one_contact_solution::<L, DT>(problem, laws, states, mu)
        {
            return Ok(sol);
        }
        if let Some(mu) = mu
            && let Some(sol) =
                self.solve_skipping_open::<L, DT>(st, auto, problem, laws, states, &r, mu)?
        {
            return Ok(sol);
        }
        // a small sparse symmetric W: the classical solver first (issue 37, `classic_first`)
        let mut spent = classic_first::Spent::default();
        if auto && let Some(mu) = mu {
            match self.solve_classic_first::<L, DT>(st, problem, laws, states, &r, mu)? {
                Ok(sol) => return Ok(sol),
                Err(work) => spent = work,
            }
        }
        let auto_newton = auto && st.algorithm == Algorithm::Newton && mu.is_some();
        // sweep first (issue 37): the sweep goes on from the probe when its rate promises the
        // tolerance soon; else Newton runs from `r` as without the probe
        if auto_newton && self.sweep_first && problem.w_dense().is_some() {
            let probe = self.attempt::<L, DT>(sweep_probe(st), problem, laws, states, r.clone())?;
            if sweep_promises(&probe.report.history, st.tol) {
                let rest = UzawaSettings {
                    algorithm: Algorithm::AndersonGaussSeidel,
                    ..st
                };
                let mut sol =
                    self.solve_checked::<L, DT>(rest, false, problem, laws, states, probe.r, mu)?;
                let mut history = probe.report.history;
                history.append(&mut sol.report.history);
                sol.report.history = history;
                sol.report.iterations += probe.report.iterations;
                return Ok(sol);
            }
        }
        let first = if auto_newton {
            auto_newton_budget(st, problem)
        } else {
            st
        };
        let probe = if auto_newton {
            newton_probe(problem)
        } else {
            NewtonProbe::Off
        };
        self.newton.probe = probe;
        let first_run = self.attempt::<L, DT>(first, problem, laws, states, r.clone());
        self.newton.probe = NewtonProbe::Off;
        let mut sol = first_run?;
        let mut best_iterate = None;
        self.accept_on_residual::<L, DT>(problem, laws, states, &mut sol, &mut best_iterate);
        self.check::<L, DT>(problem, laws, states, &mut sol, mu);
        // the smallest residual of the last run, for the stalled error
        let mut best = best_of(&sol.report.history);
        // What runs next while the answer is not converged: the sweep when Auto's Newton ran
        // out of its budget (`sweep_after_newton`); then the fallback — Newton's is first the
        // accelerated sweep (it solves what Newton does, without a Jacobian), then the
        // classical split, like every other algorithm's.
        let switched = auto_newton && !sol.report.converged && !sol.report.stalled;
        let fallback = st.fallback
            && !st.accept_non_converged
            && st.algorithm != Algorithm::ClassicRccm
            && mu.is_some();
        let newton = st.algorithm == Algorithm::Newton;
        let sweep = sweep_after_newton(probe);
        let chain: &[Algorithm] = match (switched || (fallback && newton), fallback) {
            // issue 37: after a probe's switch, Newton again, unprobed, `ρ` raised (`last_newton`)
            (true, true) if switched => &[sweep, Algorithm::Newton, Algorithm::ClassicRccm],
            (true, false) => &[sweep, Algorithm::Newton],
            (true, true) => &[sweep, Algorithm::ClassicRccm],
            (false, true) => &[Algorithm::ClassicRccm],
            (false, false) => &[],
        };
        // an unprobed Newton (a dense W kept non-symmetric) and the progress probe's hand their
        // iterate to the sweep
        let mut from_newton = switched && probe != NewtonProbe::Steps;
        // issue 37, ninth part: after the progress probe, the sweep's trial (`auto/after_probe.rs`)
        let (mut raised, mut resume) = (false, None);
        if switched && probe == NewtonProbe::Progress {
            let after = self.after_progress_probe::<L, DT>(
                st,
                sol,
                problem,
                laws,
                states,
                mu,
                &mut best_iterate,
            )?;
            (sol, raised, resume) = (after.sol, after.raised, Some(after.resume));
            best = best_of(&sol.report.history);
        }
        for &next in chain {
            if sol.report.converged {
                break;
            }
            let again = next == Algorithm::Newton;
            if again && (raised || newton_probe(problem) == NewtonProbe::Off) {
                continue; // the unprobed Newton already ran
            }
            let start = if from_newton {
                resume.take().unwrap_or_else(|| sol.r.clone())
            } else {
                r.clone()
            };
            from_newton = false;
            let settings = UzawaSettings {
                algorithm: next,
                ..st
            };
            let settings = if again { last_newton(st) } else { settings };
            let previous = sol.report.history.len();
            self.newton.raise_rho = again;
            let after = self.run_after::<L, DT>(
                settings,
                st.algorithm,
                sol,
                problem,
                laws,
                states,
                &start,
                mu,
                &mut best_iterate,
            );
            self.newton.raise_rho = false;
            sol = after?;
            best = best_of(&sol.report.history[previous..]);
        }
        if !sol.report.converged && !st.accept_non_converged {
            let report = sol.report;
            if report.stalled {
                return Err(SolverError::Stalled {
                    algorithm: report.algorithm.name(),
                    fallback_from: report.fallback_from.map(Algorithm::name),
                    iterations: report.iterations,
                    residual: report.residual,
                    best_residual: best,
                    history: report.history,
                    best: best_iterate,
                });
            }
            return Err(SolverError::NotConverged {
                iterations: report.iterations,
                residual: report.residual,
                history: report.history,
                best: best_iterate,
            });
        }
        sol.report.asymmetry = problem.asymmetry();
        spent.add_to(&mut sol);
        Ok(sol)
    }

    /// The denominator of the relative natural residual of `r`: `max(‖r‖, ρ_max ‖q‖)` with the
    /// sweeps' largest `ρ⁰_i` (never 0).
    fn residual_scale(&self, problem: &ReducedProblem, r: &[f64]) -> f64 {
        let rho_max = self.sweeps.rho0.iter().fold(0.0_f64, |a, &b| a.max(b));
        norm(r)
            .max(rho_max * norm(problem.q()))
            .max(f64::MIN_POSITIVE)
    }

    /// Issue 37: a run that ended without meeting its rule (at `max_iterations`, or stalled)
    /// with a relative natural residual `≤ tol` at its returned iterate (on the exact
    /// `x = W r + q`, which [`attempt`](Self::attempt) recomputed) is converged: the rule's
    /// change need not vanish on a rank-deficient `W` (`residual_stop`). Otherwise the iterate
    /// becomes `best` when its residual is the smallest so far (the best-effort answer of
    /// [`SolverError::best_iterate`]); converging runs copy nothing.
    fn accept_on_residual<L: ContactLaw, const DT: usize>(
        &self,
        problem: &ReducedProblem,
        laws: &[L],
        states: &[L::State],
        sol: &mut Solution,
        best: &mut Option<Box<BestIterate>>,
    ) {
        if sol.report.converged {
            return;
        }
        let rho0 = &self.sweeps.rho0;
        let denom = self.residual_scale(problem, &sol.r);
        let residual = natural_residual::<L, DT>(laws, states, rho0, &sol.r, &sol.x) / denom;
        if residual <= self.settings.tol {
            sol.report.converged = true;
            sol.report.stalled = false;
            sol.report.residual = residual;
        } else if residual.is_finite() && best.as_ref().is_none_or(|b| residual < b.residual) {
            *best = Some(Box::new(BestIterate::new(
                sol.r.clone(),
                sol.x.clone(),
                residual,
            )));
        }
    }

    /// Runs `st.algorithm` from `r` after the run that ended in `before` (started as
    /// `first`), accepts it on its residual
    /// or keeps it as the best iterate, checks its answer, and reports both: the iterations and histories added, the
    /// first algorithm in [`fallback_from`](UzawaReport::fallback_from).
    #[allow(clippy::too_many_arguments)]
    fn run_after<L: ContactLaw, const DT: usize>(
        &mut self,
        st: UzawaSettings,
        first: Algorithm,
        before: Solution,
        problem: &ReducedProblem,
        laws: &[L],
        states: &[L::State],
        r: &[f64],
        mu: Option<&[f64]>,
        best_iterate: &mut Option<Box<BestIterate>>,
    ) -> Result<Solution, SolverError> {
        let mut sol = self.attempt::<L, DT>(st, problem, laws, states, r.to_vec())?;
        self.accept_on_residual::<L, DT>(problem, laws, states, &mut sol, best_iterate);
        self.check::<L, DT>(problem, laws, states, &mut sol, mu);
        let earlier = before.report;
        let report = &mut sol.report;
        report.fallback_from = Some(first);
        report.iterations += earlier.iterations;
        report.outer_iterations += earlier.outer_iterations;
        let mut history = earlier.history;
        history.append(&mut report.history);
        report.history = history;
        Ok(sol)
    }

    /// The independent check of a converged answer, for Coulomb-type laws (`mu`): the
    /// Signorini–Coulomb conditions without the modified velocity
    /// ([`coulomb_residual`](super::residual::coulomb_residual)), relative like the natural
    /// residual, must be within `CHECK_FACTOR`` × tol`; else the answer is not converged.
    /// On a kept non-symmetric `W` the natural residual itself is recomputed from
    /// `x = W r + q` (the rows of the real `W`; the algorithms updated `x` by columns read from
    /// the stored `Wᵀ`), reported, and must be within `KEPT_CHECK_FACTOR`` × tol`.
    fn check<L: ContactLaw, const DT: usize>(
        &self,
        problem: &ReducedProblem,
        laws: &[L],
        states: &[L::State],
        sol: &mut Solution,
        mu: Option<&[f64]>,
    ) {
        let Some(mu) = mu else { return };
        if !sol.report.converged {
            return;
        }
        let rho0 = &self.sweeps.rho0;
        let denom = self.residual_scale(problem, &sol.r);
        if !problem.is_symmetric() {
            problem.displacement_into(&sol.r, &mut sol.x);
            let residual = natural_residual::<L, DT>(laws, states, rho0, &sol.r, &sol.x) / denom;
            sol.report.residual = residual;
            if residual.is_nan() || residual > KEPT_CHECK_FACTOR * self.settings.tol {
                sol.report.converged = false;
                return;
            }
        }
        let error = coulomb_residual::<DT>(mu, rho0, &sol.r, &sol.x) / denom;
        if error.is_nan() || error > CHECK_FACTOR * self.settings.tol {
            sol.report.converged = false;
            return;
        }
        let (pen, scale) = penetration::<DT>(problem.q(), &sol.x);
        if pen > CHECK_FACTOR * self.settings.tol * scale {
            // r grew without bound: no solution (see `penetration`)
            sol.report.converged = false;
            sol.report.stalled = true;
        }
    }
}

/// The smallest entry of a residual history (`+∞` when empty; NaNs skipped).
fn best_of(history: &[f64]) -> f64 {
    history.iter().copied().fold(f64::INFINITY, f64::min)
}

/// Checks the sizes and the settings of a solve and returns the starting reactions (`r_start`,
/// or zero).
fn starting_reactions(
    st: &UzawaSettings,
    problem: &ReducedProblem,
    n_laws: usize,
    n_states: usize,
    r_start: Option<&[f64]>,
) -> Result<Vec<f64>, SolverError> {
    let nc = problem.contact_count();
    let m = problem.size();
    for (what, len) in [("laws", n_laws), ("states", n_states)] {
        if len != nc && !(len == 1 && nc > 0) {
            return Err(SolverError::SizeMismatch {
                what,
                expected: nc,
                found: len,
            });
        }
    }
    if !(st.tol.is_finite() && st.tol > 0.0) {
        return Err(SolverError::NonFinite {
            what: "tol",
            index: 0,
            value: st.tol,
        });
    }
    if !(st.tuning.rho_scale.is_finite() && st.tuning.rho_scale > 0.0) {
        return Err(SolverError::NonFinite {
            what: "rho_scale",
            index: 0,
            value: st.tuning.rho_scale,
        });
    }
    if !(st.tuning.omega > 0.0 && st.tuning.omega < 2.0) {
        return Err(SolverError::InvalidSetting {
            what: "omega",
            value: st.tuning.omega,
            expected: "expected a value in (0, 2)",
        });
    }
    if st.tuning.stall_window != 0 && st.tuning.stall_window < MIN_STALL_WINDOW {
        return Err(SolverError::InvalidSetting {
            what: "stall_window",
            value: st.tuning.stall_window as f64,
            expected: "expected 0 (detector off) or a window of at least 10 iterations",
        });
    }
    let mut r = vec![0.0; m];
    if let Some(r0) = r_start {
        if r0.len() != m {
            return Err(SolverError::SizeMismatch {
                what: "r_start",
                expected: m,
                found: r0.len(),
            });
        }
        if let Some((index, &value)) = r0.iter().enumerate().find(|(_, a)| !a.is_finite()) {
            return Err(SolverError::NonFinite {
                what: "r_start",
                index,
                value,
            });
        }
        r.copy_from_slice(r0);
    }
    Ok(r)
}

#[cfg(test)]
mod tests {
    use super::*;
    use contact_laws::{Coulomb, Signorini};

    #[test]
    fn shared_law_works() {
        let p = ReducedProblem::new(vec![1.0, 0.0, 0.0, 1.0], vec![-2.0, 1.0], vec![0.0]).unwrap();
        let sol = UzawaSolver::new(UzawaSettings::default())
            .solve(&p, &[Signorini])
            .unwrap();
        assert_eq!(sol.r, vec![2.0, 0.0]);
    }

    #[test]
    fn bipotential_report_counts_work() {
        // Every bipotential sweep is an outer iteration and none is a "tangential sweep".
        let p = ReducedProblem::new(vec![1.0, 0.0, 0.0, 1.0], vec![-2.0, 1.0], vec![0.3]).unwrap();
        for algorithm in [Algorithm::Uzawa, Algorithm::GaussSeidel] {
            let st = UzawaSettings {
                algorithm,
                ..UzawaSettings::default()
            };
            let rep = UzawaSolver::new(st)
                .solve(&p, &p.coulomb_laws())
                .unwrap()
                .report;
            assert_eq!(rep.outer_iterations, rep.iterations);
            assert_eq!(rep.history.len(), rep.iterations);
            assert_eq!(rep.tangential_sweeps, 0);
        }
    }

    #[test]
    fn solve_rejects_wrong_law_count() {
        let p = ReducedProblem::new(vec![1.0, 0.0, 0.0, 1.0], vec![-2.0, 1.0], vec![0.0]).unwrap();
        let laws = [Coulomb::new(0.1).unwrap(); 2];
        let e = UzawaSolver::new(UzawaSettings::default()).solve(&p, &laws);
        assert!(matches!(
            e,
            Err(SolverError::SizeMismatch {
                what: "laws",
                expected: 1,
                found: 2
            })
        ));
    }
}
