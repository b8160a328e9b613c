//! The bipotential Uzawa iteration on the reduced problem `x = W r + q` (seed 5.26, 5.52).
//!
//! ```text
//! prediction (5.26a):  τ_i = r_i + ρ_i v_i(x),   v_i = law_i.modified_velocity(x_i)
//! correction (5.26b):  r_i ← law_i.project(τ_i)
//! ```
//! Six algorithms are offered ([`Algorithm`]), all stopping on the rule below. Two are the
//! plain bipotential sweeps:
//! - [`Algorithm::Uzawa`]: all contacts from the same `x` (a projected-gradient / Jacobi
//!   step), then `x = W r + q` once per iteration — the seed's algorithm, kept as the
//!   reference;
//! - [`Algorithm::GaussSeidel`]: contact by contact, each using the current `x`, which is
//!   updated right after with the two columns of `W` that the contact touches (De Saxcé–Feng's
//!   projected Gauss–Seidel). On seeded random SPD problems
//!   ([`generate::random_problem`](crate::generate::random_problem), `n_c` = 10/100/300,
//!   release build) it takes 57–60 sweeps against 79–101 for Uzawa and is 1.5–9× faster
//!   (n_c = 300: 2.6 ms against 23 ms), because a sweep costs one pass over `W` while an
//!   Uzawa step costs one product `W r` per trial, and a few trials are redone.
//!
//! Two accelerate them ([`anderson`](crate::anderson)): [`Algorithm::AndersonGaussSeidel`] —
//! **the default** — and [`Algorithm::AndersonUzawa`], safeguarded Anderson mixing of the last
//! 5 iterates of the sweep. [`Algorithm::Newton`] ([`newton`](crate::newton)) is a semi-smooth
//! Newton method on the same projection equation, for Coulomb-type laws. And
//! [`Algorithm::ClassicRccm`] is the classical solver the seed compares the bipotential with
//! (GYPTIS, seed §5.6): Signorini and friction solved separately, with a fixed point on the
//! friction threshold ([`classic`](crate::classic)).
//!
//! # Which algorithm
//! Measured by `examples/work_precision_local.rs` (`docs/benchmarks.md`, "Local solver:
//! work–precision"): time to reach a residual of 1e-10 on random problems (`n_c` = 10 to 5000)
//! and on FE reduced problems of the Hertz scene (21 and 141 contacts, frictionless and with
//! partial slip).
//! - Newton is the fastest on every FE problem (5–8× faster than Gauss–Seidel) and on random
//!   problems up to `n_c` ≈ 1000, but its dense factorisation grows as `n_c³` (at `n_c` = 5000
//!   it is 4–5× slower than the accelerated sweep) and it needs
//!   [`ContactLaw::friction_coefficient`].
//! - The accelerated Gauss–Seidel sweep is 1.1–3× faster than Gauss–Seidel on every problem,
//!   needs nothing but `project` and `modified_velocity` (any law), and converges where
//!   Gauss–Seidel does not in 10 000 sweeps (issue 8's stress suite: a stiffness contrast of
//!   1e8, 40 sweeps). It is the default; choose Newton for Coulomb-type problems up to about a
//!   thousand contacts.
//!
//! # The penalty ρ
//! The base value is `ρ⁰_i = 1/λ_max(W_ii)`, where `W_ii` is contact `i`'s 2×2 diagonal block:
//! the largest step for which the local map `r_i ↦ r_i − ρ W_ii r_i` is non-expansive, i.e. the
//! local step never overshoots, whatever the block's anisotropy (`1/W_nn` can exceed it when
//! `W_tt > W_nn`). The user may scale it by [`UzawaSettings::rho_scale`]. It is then adapted
//! (Khobotov 1987, Solodov–Tseng 1996): after a trial step `r → r'`,
//!
//! ```text
//! ratio = ‖ρ (v(x(r')) − v(x(r)))‖ / ‖r' − r‖
//! ratio > ν = 1.5   → ρ ← ρ/2 and redo the step
//! ratio < 0.3       → ρ ← 1.5 ρ for the next step
//! ```
//! We use `ν = 1.5` rather than the extragradient's `ν < 1`: this is a plain projected
//! step, which for the associated (frictionless) part converges for `ρ L < 2`; and with
//! `ν < 1` the exact local step `ρ = 1/λ` of an isotropic block (ratio exactly 1) would be
//! rejected. Measured on the random problems, `ν = 0.9` costs Gauss–Seidel 89–96 sweeps
//! against 57–60 with `ν = 1.5` (Uzawa: 83–103 against 79–101).
//!
//! `ρ⁰ = 1/W_nn` was measured too: within ±15 % of the sweeps of `1/λ_max` on these nearly
//! isotropic blocks; `1/λ_max` is kept because it stays safe on anisotropic ones.
//! For Uzawa the norms are global and one factor scales every `ρ_i`; for Gauss–Seidel each
//! contact adapts its own `ρ_i` with its local step (`x_i` changes by `W_ii Δr_i`). So a `ρ`
//! that is `10³` times too large or too small still converges.
//!
//! # Stopping rule
//! Both must hold at the same iterate (so the rule does not depend on the adapted ρ):
//!
//! ```text
//! change   = ‖r_{k+1} − r_k‖ / max(‖r_{k+1}‖, tiny)                          ≤ tol
//! residual = ‖r − P_K(r + ρ⁰ v(W r + q))‖ / max(‖r‖, max_i ρ⁰_i ‖q‖, tiny)   ≤ tol
//! ```
//! with `ρ⁰` the *base* penalty (not the adapted one, nor the user's scale) and
//! `tiny = f64::MIN_POSITIVE`. The residual is the natural map of the fixed point (zero
//! exactly on solutions); [`UzawaReport::history`] records it at every iteration.

use crate::anderson::{AndersonScratch, BaseMap};
use crate::classic::ClassicScratch;
use crate::error::SolverError;
use crate::newton::NewtonScratch;
use crate::reduced::ReducedProblem;
use contact_laws::{ContactLaw, ContactStatus, LocalVec2};

/// Threshold ν of the self-adaptive rule: a step whose ratio exceeds it is redone with ρ/2.
pub const ADAPT_SHRINK_ABOVE: f64 = 1.5;
/// A step whose ratio is below this grows ρ by [`ADAPT_GROWTH`] for the next step.
pub const ADAPT_GROW_BELOW: f64 = 0.3;
/// Growth factor of ρ after an easy step.
pub const ADAPT_GROWTH: f64 = 1.5;
/// Maximum number of halvings of ρ within one step (`2⁻⁶⁰ ≈ 10⁻¹⁸`).
const MAX_SHRINKS: usize = 60;
/// Relative size of `‖P(τ) − τ‖/‖τ‖` under which a compressed contact is reported as stick.
const STATUS_TOL: f64 = 1e-8;

/// Which sweep the solver runs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Algorithm {
    /// Every contact from the same `x`, then `x = W r + q` (Jacobi / projected gradient).
    Uzawa,
    /// Contact by contact with the current `x` (projected Gauss–Seidel).
    GaussSeidel,
    /// The classical solver (seed §5.6, GYPTIS): contact and friction treated separately, by
    /// projected SOR sweeps on the normal then the tangential components, with a fixed point
    /// on the threshold `s_i = μ̄_i r_n,i`. Needs
    /// [`ContactLaw::friction_coefficient`]; see [`classic`](crate::classic).
    ClassicRccm,
    /// Anderson acceleration (memory [`ANDERSON_DEPTH`](crate::anderson::ANDERSON_DEPTH),
    /// safeguarded) of the projected Gauss–Seidel sweep; see [`anderson`](crate::anderson).
    /// The default (chosen by measurement, see the [module docs](self#which-algorithm)).
    #[default]
    AndersonGaussSeidel,
    /// Anderson acceleration (safeguarded) of the Uzawa step; see
    /// [`anderson`](crate::anderson).
    AndersonUzawa,
    /// Semi-smooth Newton on `r − P_K(r + ρ v(W r + q)) = 0` with a dense LU of the reduced
    /// Newton system, a line search and Gauss–Seidel fallback. Needs
    /// [`ContactLaw::friction_coefficient`]; see [`newton`](crate::newton).
    Newton,
}

/// Settings of the reduced solver.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UzawaSettings {
    /// Which sweep to run.
    pub algorithm: Algorithm,
    /// Tolerance of both tests of the stopping rule (see the [module docs](self)).
    pub tol: f64,
    /// Maximum number of iterations (sweeps).
    pub max_iterations: usize,
    /// Factor applied to the base `ρ⁰_i = 1/λ_max(W_ii)` at the start (adapted afterwards).
    /// Not used by [`Algorithm::ClassicRccm`].
    pub rho_scale: f64,
    /// Over-relaxation factor `ω ∈ (0, 2)` of the projected SOR sweeps of
    /// [`Algorithm::ClassicRccm`] (default [`DEFAULT_OMEGA`](crate::classic::DEFAULT_OMEGA));
    /// not used by the bipotential sweeps.
    pub omega: f64,
    /// Return `Ok` with `report.converged == false` instead of
    /// [`SolverError::NotConverged`].
    pub accept_non_converged: bool,
}

impl Default for UzawaSettings {
    fn default() -> Self {
        Self {
            algorithm: Algorithm::default(),
            tol: 1e-10,
            max_iterations: 10_000,
            rho_scale: 1.0,
            omega: crate::classic::DEFAULT_OMEGA,
            accept_non_converged: false,
        }
    }
}

/// What the solver did.
#[derive(Clone, Debug, PartialEq)]
pub struct UzawaReport {
    /// The algorithm that ran.
    pub algorithm: Algorithm,
    /// Iterations (sweeps) done: for [`Algorithm::ClassicRccm`], every normal and tangential
    /// sweep of every outer iteration (see [`classic`](crate::classic)); for the Anderson
    /// variants, base steps (rejected ones included); for [`Algorithm::Newton`], Newton steps
    /// plus Gauss–Seidel sweeps.
    pub iterations: usize,
    /// Outer iterations: threshold updates of [`Algorithm::ClassicRccm`], Newton steps (dense
    /// factorisations) of [`Algorithm::Newton`]; equal to `iterations` for the sweeps.
    pub outer_iterations: usize,
    /// Sweeps of the friction sub-problem of [`Algorithm::ClassicRccm`] (so
    /// `iterations − tangential_sweeps` are Signorini sweeps); 0 for the bipotential sweeps,
    /// which treat both components of a contact together.
    pub tangential_sweeps: usize,
    /// `true` when the stopping rule was met.
    pub converged: bool,
    /// Natural-map residual at the returned iterate (relative, see the [module docs](self)).
    pub residual: f64,
    /// Relative change `‖r_{k+1} − r_k‖/‖r_{k+1}‖` of the last iteration.
    pub change: f64,
    /// The natural-map residual of every iteration (of every outer iteration for
    /// [`Algorithm::ClassicRccm`]).
    pub history: Vec<f64>,
    /// Smallest adapted `ρ_i` at the end (the base `ρ⁰_i` for [`Algorithm::ClassicRccm`]).
    pub rho_min: f64,
    /// Largest adapted `ρ_i` at the end (the base `ρ⁰_i` for [`Algorithm::ClassicRccm`]).
    pub rho_max: f64,
    /// Status of each contact at the returned iterate (case of the projection with `ρ⁰`).
    pub statuses: Vec<ContactStatus>,
}

/// The solution of a reduced problem.
#[derive(Clone, Debug, PartialEq)]
pub struct Solution {
    /// Reactions, normal first per contact (`r_n ≥ 0` is compression).
    pub r: Vec<f64>,
    /// Displacements / gaps `x = W r + q` (`x_n ≥ 0` is an opening).
    pub x: Vec<f64>,
    /// How the solver got there.
    pub report: UzawaReport,
}

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
    r_trial: Vec<f64>,
    x_trial: Vec<f64>,
    v: Vec<f64>,
    v_trial: Vec<f64>,
    rho0: Vec<f64>,
    rho: Vec<f64>,
    classic: ClassicScratch,
    anderson: AndersonScratch,
    newton: NewtonScratch,
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

#[inline]
pub(crate) fn pick<T>(s: &[T], i: usize) -> &T {
    if s.len() == 1 { &s[0] } else { &s[i] }
}

#[inline]
pub(crate) fn local(v: &[f64], i: usize) -> LocalVec2 {
    LocalVec2::planar(v[2 * i], v[2 * i + 1])
}

#[inline]
pub(crate) fn set_local(v: &mut [f64], i: usize, a: &LocalVec2) {
    v[2 * i] = a.n;
    v[2 * i + 1] = a.t[0];
}

pub(crate) fn norm(v: &[f64]) -> f64 {
    v.iter().map(|a| a * a).sum::<f64>().sqrt()
}

/// `1/λ_max` of the SPD block `[a b; b d]`.
fn rho_of_block([a, b, _, d]: [f64; 4]) -> f64 {
    let h = 0.5 * (a - d);
    1.0 / (0.5 * (a + d) + (h * h + b * b).sqrt())
}

/// The status of each contact at `(r, x)`, from the projection `P(r + ρ v(x))`: separation
/// when it is zero, stick when it leaves `τ` unchanged (to [`STATUS_TOL`]), slip otherwise.
/// `laws` and `states` may hold one entry for every contact.
pub(crate) fn contact_statuses<L: ContactLaw>(
    laws: &[L],
    states: &[L::State],
    rho: &[f64],
    r: &[f64],
    x: &[f64],
) -> Vec<ContactStatus> {
    (0..rho.len())
        .map(|i| {
            let (law, s) = (pick(laws, i), pick(states, i));
            let tau = local(r, i) + law.modified_velocity(&local(x, i), s) * rho[i];
            let p = law.project(&tau, s);
            if p.n == 0.0 && p.t[0] == 0.0 {
                ContactStatus::Separation
            } else if (p - tau).norm() <= STATUS_TOL * tau.norm() {
                ContactStatus::Stick
            } else {
                ContactStatus::Slip
            }
        })
        .collect()
}

/// `‖r − P(r + ρ⁰ v(x))‖` (absolute), the natural map of the fixed point with the base `ρ⁰`.
pub(crate) fn natural_residual<L: ContactLaw>(
    laws: &[L],
    states: &[L::State],
    rho0: &[f64],
    r: &[f64],
    x: &[f64],
) -> f64 {
    let mut s2 = 0.0;
    for (i, &rho0) in rho0.iter().enumerate() {
        let (law, s) = (pick(laws, i), pick(states, i));
        let ri = local(r, i);
        let tau = ri + law.modified_velocity(&local(x, i), s) * rho0;
        let d = law.project(&tau, s) - ri;
        s2 += d.dot(&d);
    }
    s2.sqrt()
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

    /// Solves `problem` from `r = 0` with the laws' initial states.
    ///
    /// `laws` holds one law per contact, or a single law shared by all contacts.
    ///
    /// # Errors
    /// [`SolverError::SizeMismatch`] if `laws` has neither 1 nor `n_c` entries;
    /// [`SolverError::NotConverged`] unless `accept_non_converged`.
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
    /// [`SolverError::NonFinite`] if `r_start` is not finite, or `tol` or `rho_scale` is not
    /// finite and positive; [`SolverError::InvalidSetting`] if `omega` is not in `(0, 2)`;
    /// for [`Algorithm::ClassicRccm`], [`SolverError::NoFrictionCoefficient`] if a law's
    /// [`friction_coefficient`](ContactLaw::friction_coefficient) is `None` and
    /// [`SolverError::InvalidLaw`] if it is negative or not finite;
    /// [`SolverError::NotConverged`] unless `accept_non_converged`.
    pub fn solve_with_states<L: ContactLaw>(
        &mut self,
        problem: &ReducedProblem,
        laws: &[L],
        states: &[L::State],
        r_start: Option<&[f64]>,
    ) -> Result<Solution, SolverError> {
        let nc = problem.contact_count();
        let m = problem.size();
        let st = self.settings;
        for (what, len) in [("laws", laws.len()), ("states", states.len())] {
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
        if !(st.rho_scale.is_finite() && st.rho_scale > 0.0) {
            return Err(SolverError::NonFinite {
                what: "rho_scale",
                index: 0,
                value: st.rho_scale,
            });
        }
        if !(st.omega > 0.0 && st.omega < 2.0) {
            return Err(SolverError::InvalidSetting {
                what: "omega",
                value: st.omega,
                expected: "expected a value in (0, 2)",
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
        for buf in [
            &mut self.r_trial,
            &mut self.x_trial,
            &mut self.v,
            &mut self.v_trial,
        ] {
            buf.clear();
            buf.resize(m, 0.0);
        }
        self.rho0.clear();
        self.rho0
            .extend((0..nc).map(|i| rho_of_block(problem.diagonal_block(i))));
        self.rho.clear();
        self.rho.extend(self.rho0.iter().map(|a| a * st.rho_scale));
        let mut x = vec![0.0; m];
        problem.displacement_into(&r, &mut x);
        if st.algorithm == Algorithm::Uzawa {
            self.set_velocity(laws, states, &x);
        }
        let mut history = Vec::with_capacity(st.max_iterations.min(100_000));
        let denom_q = self.rho0.iter().fold(0.0_f64, |a, &b| a.max(b)) * norm(problem.q());

        let mut iterations = 0;
        let mut residual = f64::INFINITY;
        let mut change = f64::INFINITY;
        let mut converged = false;
        let mut outer_iterations = 0;
        let mut tangential_sweeps = 0;
        // Uzawa's global scale factor of ρ⁰ (Gauss–Seidel adapts `self.rho` per contact).
        let mut theta = st.rho_scale;
        if st.algorithm == Algorithm::ClassicRccm {
            let run = self.classic.solve(
                problem,
                laws,
                states,
                &self.rho0,
                &st,
                &mut r,
                &mut x,
                &mut history,
            )?;
            iterations = run.iterations;
            outer_iterations = run.outer_iterations;
            tangential_sweeps = run.tangential_sweeps;
            converged = run.converged;
            residual = run.residual;
            change = run.change;
            self.rho.copy_from_slice(&self.rho0);
        }
        if let Some(base) = match st.algorithm {
            Algorithm::AndersonGaussSeidel => Some(BaseMap::GaussSeidel),
            Algorithm::AndersonUzawa => Some(BaseMap::Uzawa),
            _ => None,
        } {
            let mut scratch = std::mem::take(&mut self.anderson);
            let run = scratch.solve(
                self,
                base,
                problem,
                laws,
                states,
                &st,
                denom_q,
                &mut theta,
                &mut r,
                &mut x,
                &mut history,
            );
            self.anderson = scratch;
            (iterations, outer_iterations) = (run.iterations, run.iterations);
            (converged, residual, change) = (run.converged, run.residual, run.change);
        }
        if st.algorithm == Algorithm::Newton {
            let mut scratch = std::mem::take(&mut self.newton);
            let run = scratch.solve(
                self,
                problem,
                laws,
                states,
                &st,
                denom_q,
                &mut r,
                &mut x,
                &mut history,
            );
            self.newton = scratch;
            let run = run?;
            (iterations, outer_iterations) = (run.iterations, run.newton_steps);
            (converged, residual, change) = (run.converged, run.residual, run.change);
        }
        let sweeps = matches!(st.algorithm, Algorithm::Uzawa | Algorithm::GaussSeidel);
        while sweeps && iterations < st.max_iterations {
            iterations += 1;
            let dr2 = match st.algorithm {
                Algorithm::Uzawa => {
                    self.uzawa_step(problem, laws, states, &mut r, &mut x, &mut theta)
                }
                // (The other algorithms ran above and never enter this loop.)
                _ => self.gauss_seidel_sweep(problem, laws, states, &mut r, &mut x),
            };
            outer_iterations = iterations;
            let r_norm = norm(&r);
            change = dr2.sqrt() / r_norm.max(f64::MIN_POSITIVE);
            let denom = r_norm.max(denom_q).max(f64::MIN_POSITIVE);
            residual = natural_residual(laws, states, &self.rho0, &r, &x) / denom;
            if change <= st.tol && residual <= st.tol && st.algorithm == Algorithm::GaussSeidel {
                // x was updated incrementally: confirm on the exact x = W r + q.
                problem.displacement_into(&r, &mut x);
                residual = natural_residual(laws, states, &self.rho0, &r, &x) / denom;
            }
            history.push(residual);
            if change <= st.tol && residual <= st.tol {
                converged = true;
                break;
            }
        }
        if !converged && !st.accept_non_converged {
            return Err(SolverError::NotConverged {
                iterations,
                residual,
                history,
            });
        }
        problem.displacement_into(&r, &mut x);
        if matches!(st.algorithm, Algorithm::Uzawa | Algorithm::AndersonUzawa) {
            for (rho, rho0) in self.rho.iter_mut().zip(&self.rho0) {
                *rho = theta * rho0;
            }
        }
        let statuses = contact_statuses(laws, states, &self.rho0, &r, &x);
        let report = UzawaReport {
            algorithm: st.algorithm,
            iterations,
            outer_iterations,
            tangential_sweeps,
            converged,
            residual,
            change,
            history,
            rho_min: self.rho.iter().fold(f64::INFINITY, |a, &b| a.min(b)),
            rho_max: self.rho.iter().fold(0.0, |a, &b| a.max(b)),
            statuses,
        };
        Ok(Solution { r, x, report })
    }

    /// The base penalties `ρ⁰_i = 1/λ_max(W_ii)` of the current solve.
    pub(crate) fn rho0(&self) -> &[f64] {
        &self.rho0
    }

    /// `self.v = v(x)`, the precondition of [`uzawa_step`](Self::uzawa_step).
    pub(crate) fn set_velocity<L: ContactLaw>(
        &mut self,
        laws: &[L],
        states: &[L::State],
        x: &[f64],
    ) {
        for i in 0..self.rho0.len() {
            let v = pick(laws, i).modified_velocity(&local(x, i), pick(states, i));
            set_local(&mut self.v, i, &v);
        }
    }

    /// One Jacobi step with the globally adapted factor `theta`; returns `‖Δr‖²`.
    /// `self.v` must hold `v(x)` on entry (it holds `v` of the new `x` on return).
    pub(crate) fn uzawa_step<L: ContactLaw>(
        &mut self,
        problem: &ReducedProblem,
        laws: &[L],
        states: &[L::State],
        r: &mut [f64],
        x: &mut [f64],
        theta: &mut f64,
    ) -> f64 {
        // `self.v` holds v(x) for the current iterate: set before the first step, then carried
        // over from the accepted trial below, so it is never evaluated twice.
        let nc = problem.contact_count();
        let mut shrinks = 0;
        loop {
            let mut dr2 = 0.0;
            for i in 0..nc {
                let (law, s) = (pick(laws, i), pick(states, i));
                let ri = local(r, i);
                let tau = ri + local(&self.v, i) * (*theta * self.rho0[i]);
                let rn = law.project(&tau, s);
                let d = rn - ri;
                dr2 += d.dot(&d);
                set_local(&mut self.r_trial, i, &rn);
            }
            if dr2 == 0.0 {
                return 0.0;
            }
            problem.displacement_into(&self.r_trial, &mut self.x_trial);
            let mut dv2 = 0.0;
            for i in 0..nc {
                let v = pick(laws, i).modified_velocity(&local(&self.x_trial, i), pick(states, i));
                set_local(&mut self.v_trial, i, &v);
                let d = (v - local(&self.v, i)) * (*theta * self.rho0[i]);
                dv2 += d.dot(&d);
            }
            let ratio = (dv2 / dr2).sqrt();
            if ratio > ADAPT_SHRINK_ABOVE && shrinks < MAX_SHRINKS {
                *theta *= 0.5;
                shrinks += 1;
                continue;
            }
            if ratio < ADAPT_GROW_BELOW {
                *theta *= ADAPT_GROWTH;
            }
            r.copy_from_slice(&self.r_trial);
            x.copy_from_slice(&self.x_trial);
            std::mem::swap(&mut self.v, &mut self.v_trial);
            return dr2;
        }
    }

    /// One projected Gauss–Seidel sweep with per-contact adapted `ρ_i`; returns `‖Δr‖²`.
    pub(crate) fn gauss_seidel_sweep<L: ContactLaw>(
        &mut self,
        problem: &ReducedProblem,
        laws: &[L],
        states: &[L::State],
        r: &mut [f64],
        x: &mut [f64],
    ) -> f64 {
        let m = problem.size();
        let w = problem.w();
        let mut dr2 = 0.0;
        for i in 0..problem.contact_count() {
            let (law, s) = (pick(laws, i), pick(states, i));
            let [b_nn, b_nt, b_tn, b_tt] = problem.diagonal_block(i);
            let ri = local(r, i);
            let xi = local(x, i);
            let v = law.modified_velocity(&xi, s);
            let mut shrinks = 0;
            let d = loop {
                let rho = self.rho[i];
                let d = law.project(&(ri + v * rho), s) - ri;
                let dd = d.dot(&d);
                if dd == 0.0 {
                    break d;
                }
                // x_i moves by W_ii Δr_i when only r_i changes.
                let xn = LocalVec2::planar(
                    xi.n + b_nn * d.n + b_nt * d.t[0],
                    xi.t[0] + b_tn * d.n + b_tt * d.t[0],
                );
                let dv = law.modified_velocity(&xn, s) - v;
                let ratio = rho * (dv.dot(&dv) / dd).sqrt();
                if ratio > ADAPT_SHRINK_ABOVE && shrinks < MAX_SHRINKS {
                    self.rho[i] *= 0.5;
                    shrinks += 1;
                    continue;
                }
                if ratio < ADAPT_GROW_BELOW {
                    self.rho[i] *= ADAPT_GROWTH;
                }
                break d;
            };
            if d.n == 0.0 && d.t[0] == 0.0 {
                continue;
            }
            dr2 += d.dot(&d);
            set_local(r, i, &(ri + d));
            // x += W[:, 2i] Δr_n + W[:, 2i+1] Δr_t, read as rows (W is symmetric).
            let row_n = &w[2 * i * m..(2 * i + 1) * m];
            let row_t = &w[(2 * i + 1) * m..(2 * i + 2) * m];
            for ((xk, a), b) in x.iter_mut().zip(row_n).zip(row_t) {
                *xk += a * d.n + b * d.t[0];
            }
        }
        dr2
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use contact_laws::{Coulomb, Signorini};

    #[test]
    fn rho_of_block_works() {
        // λ_max of [2 0; 0 1] is 2; of [1 1; 1 1] is 2.
        assert_eq!(rho_of_block([2.0, 0.0, 0.0, 1.0]), 0.5);
        assert!((rho_of_block([1.0, 1.0, 1.0, 1.0]) - 0.5).abs() < 1e-15);
    }

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
