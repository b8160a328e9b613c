//! The reduced problem with adhesive springs: the entry point for an FE code that has its own
//! structure and wants the RCCM coupling of `docs/theory.md` §13 (seed 5.43–5.48).
//!
//! Given, on `n_c` contacts, the flexibility `W`, the free gap/slip `q` (`x = W r + q` with
//! `x = (gap, slip increment of the step)` per contact and `r` the **total** nodal reaction),
//! the laws with their states at the start of the step, the jumps `(u_n, u_t)` at the start of
//! the step and the tributary areas, [`solve_adhesive`] condenses the springs
//! `r_adh = −A k(β) (u_n, u_t)` exactly, solves `x = W̃ r̄ + q̃` with the bipotential (or the
//! classical) solver, updates the states and repeats until the largest state change is below
//! the tolerance. [`ContactSimulation`](crate::ContactSimulation) calls it every step.
//!
//! # Newton: adhesion and contact together
//! [`AdhesionMethod::Newton`] (the default) eliminates the states instead of iterating on them:
//! one reduced solve at the start states, to a loose tolerance, finds the contact set, then a
//! semi-smooth Newton iteration on the total reactions solves contact and the state update
//! together (module `newton`: `docs/theory.md`, "The coupling solved by Newton"). When it
//! cannot make progress the fixed point below finishes from Newton's last iterate if that is
//! close (relative residual ≤ 1e-6: a few steps of 5.6.1 stop at the rounding of the forces,
//! just above the tolerance), else runs from the start of the step
//! ([`AdhesiveSolution::newton_fallback`]). Measured on the seed's scenes
//! (`examples/seed_tables.rs`): median contact iterations per step 4 / 1 / 2 on 5.6.1 / 5.6.2 /
//! the pile against 33 / 54 / 59 for the fixed point (5.6.1: at most 5 on every step, the
//! seed's 7–8), in a sixth to a quarter of the time.
//!
//! # Accelerating the fixed point
//! The seed's fixed point (solve with β, update β from the jumps, repeat) converges linearly
//! and slowly where the damage front moves. [`AdhesionOptions::anderson_window`] applies
//! Anderson acceleration to the interface jumps `u` (the states are recomputed from the mixed
//! jumps, so any law works). Measured on the seed scenes, 210 steps each
//! (`cargo run --release --example adhesion_window`):
//!
//! | scene | window 0 (plain) | window 1 | window 2 | window 3–8 |
//! |---|---|---|---|---|
//! | 5.6.1 delamination, 10 s | 1934 β iterations, ≤ 52 per step | **1107, ≤ 20** | 1146, ≤ 18 | 1169–1172, ≤ 21 |
//! | 5.6.1, loaded in 1 s | 1527, ≤ 27 | **991, ≤ 8** | 1009, ≤ 8 | 1012–1013, ≤ 8 |
//! | 5.6.2 shear | 468, ≤ 4 | 468, ≤ 4 | 468, ≤ 4 | 468, ≤ 4 |
//! | pile pull-out, Plancoët, α = 0 (50 increments) | diverges (2-cycle) | 725 | — | — |
//!
//! The pile's interface (`f(β) = 1 − β`: friction grows as the glue breaks) makes the plain
//! fixed point cycle; the damping of the safeguard (halved whenever the residual reverses and
//! does not shrink) and the secant step make it converge.
//! Window 1 (a secant step) is the default.
//!
//! # Examples
//! One glued contact (RCCM, α = 0) whose free opening is larger than the critical one: the
//! springs soften (β < 1) and the total reaction is a tension.
//! ```
//! use contact_laws::{BetaScheme, ContactLaw, Rccm, RccmParams};
//! use contact_solver::local::adhesion::{AdhesionOptions, AdhesiveStep, solve_adhesive};
//! use contact_solver::{UzawaSettings, UzawaSolver};
//! let law = Rccm::new(RccmParams { c_n: 100.0, c_t: 100.0, w: 0.01, alpha: 0.0, mu: 0.2,
//!     m: 1, beta_0: 1.0, scheme: BetaScheme::ImplicitEuler })?;
//! let step = AdhesiveStep {
//!     w: &[1e-3, 0.0, 0.0, 1e-3], // a stiff body
//!     q: &[0.02, 0.0],            // free opening 0.02 > u₀ = √(w/C) = 0.01
//!     laws: &[law],
//!     start_states: &[law.initial_state()],
//!     u_start: &[[0.0, 0.0]],
//!     areas: &[1.0],
//!     dt: 1.0,
//! };
//! let mut solver = UzawaSolver::new(UzawaSettings::default());
//! let sol = solve_adhesive(&mut solver, &step, None, &AdhesionOptions::default())?;
//! let beta = sol.states[0].beta();
//! let u_n = sol.x[0];
//! assert!(beta < 1.0 && (beta - 0.01 / (100.0 * u_n * u_n)).abs() < 1e-7); // β = w/(C u²)
//! assert!((sol.r[0] + beta * beta * 100.0 * u_n).abs() < 1e-7);              // r = r_adh
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod condense;
mod newton;
mod warm;

pub use condense::{condense, condensed_problem};
pub use warm::WarmStartPacing;

use condense::condensed_with_springs;
pub(crate) use condense::start_offset;

use super::problem::ReducedProblem;
use super::settings::{Algorithm, UzawaReport};
use super::solver::UzawaSolver;
use crate::error::SolverError;
use contact_laws::{ContactLaw, LocalVec2, LocalVec3};
use faer::Mat;
use faer::linalg::solvers::Solve;
use std::sync::Arc;

/// One step of a reduced problem with adhesive laws, in 2D (`D = 2`, per contact `(n, t)`,
/// the default) or 3D (`D = 3`, per contact `(n, t₁, t₂)`).
#[derive(Clone, Copy, Debug)]
pub struct AdhesiveStep<'a, L: ContactLaw, const D: usize = 2> {
    /// `W`, dense row-major `m × m` (`m = D n_c`, normal first per contact).
    pub w: &'a [f64],
    /// `q`: the free gap and the free tangential displacement of the step.
    pub q: &'a [f64],
    /// One law per contact.
    pub laws: &'a [L],
    /// States at the start of the step.
    pub start_states: &'a [L::State],
    /// Jumps `(u_n, u_t)` (2D) or `(u_n, u_t1, u_t2)` (3D) at the start of the step.
    pub u_start: &'a [[f64; D]],
    /// Tributary area of each contact (turns the per-area spring stiffness into a nodal one).
    pub areas: &'a [f64],
    /// Time step (the viscous β update needs it).
    pub dt: f64,
}

/// Default [`AdhesionOptions::anderson_window`], chosen by measurement (module docs).
pub(crate) const DEFAULT_ANDERSON_WINDOW: usize = 1;

/// Tolerance of the first reduced solve of [`AdhesionMethod::Newton`]: it only has to find
/// the contact set Newton starts from.
const NEWTON_START_TOL: f64 = 1e-3;

/// Iteration cap of a warm-started Newton ([`AdhesionOptions::warm_start`]): from a good start
/// it converges in 1–3 iterations (the seed's 5.6.2 and pile); past this the loose start is
/// surer.
const WARM_MAX_ITERATIONS: usize = 6;

/// Largest [`ContactLaw::state_change`] of a contact a warm-started answer is accepted with.
/// From the previous step's reactions Newton can reach another solution of the implicit step:
/// a glued contact pulled from `r = 0` converges to its debonded branch (β = 0, the jump
/// free), where the start states' springs hold it elastic: a change of 1 (β from 1 to 0; the
/// stiff-glue stress cases, `tests/integration/stress.rs`). Past this change the loose start,
/// which carries those springs, decides. The seed's steps change β by at most 0.07 (5.6.2,
/// the pile) and 0.33 (5.6.1, where the front passes a node in a few steps: at 0.25, four of
/// its warm answers were dropped though the loose start gave the same reactions to 2e-10).
const WARM_MAX_STATE_CHANGE: f64 = 0.5;

/// Tolerance and cap of the adhesion fixed point.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct AdhesionOptions {
    /// Largest [`ContactLaw::state_change`] accepted between two iterations.
    pub tol: f64,
    /// Maximum fixed-point iterations.
    pub max_iterations: usize,
    /// Return the last iterate instead of [`SolverError::AdhesionNotConverged`].
    pub accept_non_converged: bool,
    /// Iterate (update the states and solve again) even when no law is adhesive — only to
    /// measure what skipping the loop saves.
    pub always_iterate: bool,
    /// Anderson acceleration of the fixed point on the interface jumps: how many past
    /// iterates to mix (`0`: the plain fixed point of the seed).
    pub anderson_window: usize,
    /// How adhesion and contact are solved together (ignored with
    /// [`Algorithm::ClassicRccm`], which is a fixed point by definition).
    pub method: AdhesionMethod,
    /// [`AdhesionMethod::Newton`] with a start `r̄` (the previous step's): first try Newton
    /// from the total reactions that start implies (`r̄` plus the start states' springs on
    /// the start jumps), at most 6 iterations, before the loose reduced solve and its
    /// condensation; its answer is kept only if no contact's state changed by more than 0.5
    /// ([`ContactLaw::state_change`]: a larger change may be another branch of the implicit
    /// step). Saves the condensation when the step changes little (the seed's 5.6.2: 1
    /// iteration per step); when it fails ([`AdhesiveSolution::warm_start_failed`]) the step
    /// goes on as without it. A sequence of steps can pause it after failures
    /// ([`WarmStartPacing`]).
    pub warm_start: bool,
}

/// How [`solve_adhesive`] couples the states to the contact problem.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[non_exhaustive]
pub enum AdhesionMethod {
    /// The seed's fixed point: the reduced problem with the springs condensed at frozen
    /// states, solved by the configured algorithm; the states updated from its jumps
    /// (Anderson-accelerated, [`AdhesionOptions::anderson_window`]); repeated.
    FixedPoint,
    /// One semi-smooth Newton iteration on the reactions with the states eliminated
    /// ([module docs](self#newton-adhesion-and-contact-together)); the fixed point when it
    /// cannot make progress.
    #[default]
    Newton,
}

impl Default for AdhesionOptions {
    fn default() -> Self {
        Self {
            tol: 1e-8,
            max_iterations: 200,
            accept_non_converged: false,
            always_iterate: false,
            anderson_window: DEFAULT_ANDERSON_WINDOW,
            method: AdhesionMethod::default(),
            warm_start: true,
        }
    }
}

/// The solution of an [`AdhesiveStep`].
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct AdhesiveSolution<S> {
    /// Total reactions `r = r̄ + r_adh` (nodal forces).
    pub r: Vec<f64>,
    /// Reactions of the contact law, `r̄ ∈ K_μ̄`.
    pub r_bar: Vec<f64>,
    /// `x = (gap, slip increment)` per contact.
    pub x: Vec<f64>,
    /// States at the end of the step.
    pub states: Vec<S>,
    /// Fixed-point iterations (0 when no law is adhesive: a single solve).
    pub adhesion_iterations: usize,
    /// Solver sweeps summed over the fixed point.
    pub contact_iterations: usize,
    /// Whether both the solver and the fixed point met their tolerances.
    pub converged: bool,
    /// [`AdhesionMethod::Newton`] was asked for but could not make progress, so the answer
    /// comes from the fixed point.
    pub newton_fallback: bool,
    /// Newton solved the step from the start `r̄` ([`AdhesionOptions::warm_start`]).
    pub warm_started: bool,
    /// The warm-started Newton was tried and did not converge within its cap, or its answer
    /// moved a state by more than the guard allows (its iterations are counted in
    /// [`contact_iterations`](Self::contact_iterations)).
    pub warm_start_failed: bool,
    /// Jacobians [`AdhesionMethod::Newton`] formed and factorised (dense LU, `2m³/3` flops
    /// each), the step's dominant cost on a large interface; its other iterations were chord
    /// steps with kept factors. 0 for the fixed point.
    pub jacobian_factorizations: usize,
    /// Report of the last reduced solve.
    pub report: UzawaReport,
    /// The last condensed problem `x = W̃ r̄ + q̃` with `μ̄` per contact (export it to compare
    /// with another solver): the fixed point's last solve. `None` after
    /// [`AdhesionMethod::Newton`], which never condenses the springs of the final states (it
    /// would cost a dense condensation per step); [`condensed_problem`] forms it from the step
    /// and [`states`](Self::states).
    pub condensed: Option<ReducedProblem>,
}

fn check_len(what: &'static str, expected: usize, found: usize) -> Result<(), SolverError> {
    if expected == found {
        Ok(())
    } else {
        Err(SolverError::SizeMismatch {
            what,
            expected,
            found,
        })
    }
}

/// Solves one step with adhesion: condensation, reduced solve, state update, repeated to a
/// fixed point (a single solve when no law is adhesive in its start state).
///
/// In 2D (`D = 2`, the seed's RCCM studies) or 3D (`D = 3`): the adhesive springs act on the
/// normal jump and, with one stiffness `k_t`, on both tangential components (the law is
/// isotropic in the tangent plane).
///
/// # Errors
/// [`SolverError::SizeMismatch`] for inconsistent lengths; [`SolverError::InvalidSetting`]
/// for a bad `dt` or tolerance; the reduced problem's validation errors;
/// [`SolverError::NotConverged`] and [`SolverError::AdhesionNotConverged`] unless accepted.
pub fn solve_adhesive<L: ContactLaw, const D: usize>(
    solver: &mut UzawaSolver,
    step: &AdhesiveStep<'_, L, D>,
    r_bar_start: Option<&[f64]>,
    options: &AdhesionOptions,
) -> Result<AdhesiveSolution<L::State>, SolverError> {
    solve_adhesive_shared(solver, step, None, r_bar_start, options)
}

/// [`solve_adhesive`] where `shared`, when given, holds `step.w` (the same slice): a step
/// without springs solves, and returns as its condensed problem, a problem on that allocation
/// instead of a copy of `W` (issue 38: the simulation's `F*` is held once).
pub(crate) fn solve_adhesive_shared<L: ContactLaw, const D: usize>(
    solver: &mut UzawaSolver,
    step: &AdhesiveStep<'_, L, D>,
    shared: Option<&Arc<Vec<f64>>>,
    r_bar_start: Option<&[f64]>,
    options: &AdhesionOptions,
) -> Result<AdhesiveSolution<L::State>, SolverError> {
    if D != 2 && D != 3 {
        return Err(SolverError::Unsupported(format!(
            "an adhesive step in dimension {D} (2 or 3)"
        )));
    }
    let m = step.q.len();
    let na = m / D;
    check_len("q", D * na, m)?;
    check_len("W", m * m, step.w.len())?;
    check_len("laws", na, step.laws.len())?;
    check_len("start_states", na, step.start_states.len())?;
    check_len("u_start", na, step.u_start.len())?;
    check_len("areas", na, step.areas.len())?;
    if !(step.dt.is_finite() && step.dt >= 0.0) {
        return Err(SolverError::InvalidSetting {
            what: "dt",
            value: step.dt,
            expected: "a finite time step >= 0",
        });
    }
    if !(options.tol.is_finite() && options.tol > 0.0) {
        return Err(SolverError::InvalidSetting {
            what: "adhesion tol",
            value: options.tol,
            expected: "a finite tolerance > 0",
        });
    }
    for (index, &value) in step.areas.iter().enumerate() {
        if !(value.is_finite() && value >= 0.0) {
            return Err(SolverError::NonFinite {
                what: "areas",
                index,
                value,
            });
        }
    }
    for (index, u) in step.u_start.iter().enumerate() {
        if let Some(&value) = u.iter().find(|v| !v.is_finite()) {
            return Err(SolverError::NonFinite {
                what: "u_start",
                index,
                value,
            });
        }
    }
    let offset = start_offset(step.u_start);
    let mut states = step.start_states.to_vec();
    let mut r_bar = match r_bar_start {
        Some(r) => {
            check_len("r_bar_start", m, r.len())?;
            r.to_vec()
        }
        None => vec![0.0; m],
    };
    let adhesion_active = any_adhesion_active(step.laws, &states);
    let adhesive = options.always_iterate || adhesion_active;
    let mut newton_fallback = false;
    let r_bar_initial = r_bar.clone();
    // Newton only where a law is adhesive (not when the loop is forced on for a measurement)
    let mut newton = adhesion_active
        && options.method == AdhesionMethod::Newton
        && solver.settings().algorithm != Algorithm::ClassicRccm;
    let mut history = Vec::new();
    let mut anderson = Anderson::new(options.anderson_window);
    let mut adhesion_iterations = 0;
    let mut contact_iterations = 0;
    let mut converged = true;
    let mut warm_start_failed = false;
    let mut factorizations = 0;
    if let Some(r_bar_start) = r_bar_start.filter(|_| newton && options.warm_start) {
        // the total reactions at the start: r̄ plus the start states' springs on the start
        // jumps (x + o at the start is u_start)
        let r_warm: Vec<f64> = (0..na)
            .flat_map(|k| {
                let [kn, kt] = step.laws[k].adhesive_stiffness(&step.start_states[k]);
                let (a, u, rb) = (step.areas[k], step.u_start[k], &r_bar_start[D * k..]);
                (0..D).map(move |d| rb[d] - a * if d == 0 { kn } else { kt } * u[d])
            })
            .collect();
        let mut settings = *solver.settings();
        settings.max_iterations = settings.max_iterations.min(WARM_MAX_ITERATIONS);
        match newton::solve(&settings, step, &r_warm, &offset, solver.kept_lu())? {
            newton::Outcome::Solved(mut sol) => {
                let change = step
                    .laws
                    .iter()
                    .zip(sol.states.iter().zip(step.start_states))
                    .fold(0.0_f64, |c, (l, (a, b))| c.max(l.state_change(a, b)));
                if change <= WARM_MAX_STATE_CHANGE {
                    sol.warm_started = true;
                    // the warm start solved the adhesion: at least one iteration, even when
                    // its start already met Newton's tolerance
                    sol.adhesion_iterations = sol.adhesion_iterations.max(1);
                    return Ok(*sol);
                }
                contact_iterations += sol.contact_iterations;
                factorizations += sol.jacobian_factorizations;
                warm_start_failed = true;
            }
            newton::Outcome::Failed(_, work) => {
                contact_iterations += work.iterations;
                factorizations += work.factorizations;
                warm_start_failed = true;
            }
        }
        // a dropped warm start's factors belong to the branch it went to (or to an iterate
        // far from any answer): no chord step from the loose start may use them
        solver.kept_lu().forget();
    }
    loop {
        let (problem, stiff) = condensed_with_springs(step, &states, &offset, shared)?;
        let sol = if newton && adhesion_iterations == 0 {
            // Newton's start only needs the contact set: a loose solve
            let saved = *solver.settings();
            let s = solver.settings_mut();
            s.tol = s.tol.max(NEWTON_START_TOL);
            s.accept_non_converged = true;
            let sol = solver.solve_with_states(&problem, step.laws, &states, Some(&r_bar));
            *solver.settings_mut() = saved;
            sol?
        } else {
            solver.solve_with_states(&problem, step.laws, &states, Some(&r_bar))?
        };
        contact_iterations += sol.report.iterations;
        converged &= sol.report.converged;
        r_bar.copy_from_slice(&sol.r);
        // the jumps: x plus the offset; the total reaction r = r̄ − k (jump)
        let jumps: Vec<f64> = sol.x.iter().zip(&offset).map(|(x, o)| x + o).collect();
        let mut r = vec![0.0; m];
        for (k, &[kn, kt]) in stiff.iter().enumerate() {
            for d in 0..D {
                let i = D * k + d;
                r[i] = sol.r[i] - if d == 0 { kn } else { kt } * jumps[i];
            }
        }
        if newton && adhesion_iterations == 0 {
            // the first solve found the contact set at the start states: Newton from there
            let start = r.clone();
            let settings = *solver.settings();
            match newton::solve(&settings, step, &start, &offset, solver.kept_lu())? {
                newton::Outcome::Solved(mut sol) => {
                    sol.contact_iterations += contact_iterations;
                    sol.jacobian_factorizations += factorizations;
                    sol.adhesion_iterations += 1;
                    sol.warm_start_failed = warm_start_failed;
                    return Ok(*sol);
                }
                // Newton stopped close to the answer (at the rounding of the forces): the
                // fixed point finishes from its iterate
                newton::Outcome::Failed(Some((r_bar_newton, states_newton)), work) => {
                    contact_iterations += work.iterations;
                    factorizations += work.factorizations;
                    r_bar.copy_from_slice(&r_bar_newton);
                    states = states_newton;
                }
                // Newton could not make progress: the seed's fixed point from the start of
                // the step, as if Newton had not run (its loose first solve is not reused)
                newton::Outcome::Failed(None, work) => {
                    contact_iterations += work.iterations;
                    factorizations += work.factorizations;
                    r_bar.copy_from_slice(&r_bar_initial);
                }
            }
            newton = false;
            newton_fallback = true;
            continue;
        }
        let finish = |states: Vec<L::State>, converged: bool| AdhesiveSolution {
            r,
            r_bar: sol.r,
            x: sol.x,
            states,
            adhesion_iterations: 0,
            contact_iterations,
            jacobian_factorizations: factorizations,
            converged,
            newton_fallback,
            warm_started: false,
            warm_start_failed,
            report: sol.report,
            condensed: Some(problem),
        };
        if !adhesive {
            return Ok(finish(states, converged));
        }
        adhesion_iterations += 1;
        // the next jumps the states are computed from: the solve's, or Anderson's mix of them
        let update =
            |u: &[f64]| states_from_jumps(step.laws, step.start_states, step.u_start, u, step.dt);
        // the fixed-point residual: the states the solve's own jumps imply, against the
        // states the solve used
        let g = jumps;
        let implied = update(&g);
        let change = largest_state_change(step.laws, &implied, &states);
        history.push(change);
        let done = change <= options.tol;
        // the states of the next solve: from the solve's jumps, or Anderson's mix of them
        let next = anderson.next(&g);
        states = if done { implied } else { update(&next) };
        if done || adhesion_iterations >= options.max_iterations {
            if !done && !options.accept_non_converged {
                return Err(SolverError::AdhesionNotConverged {
                    iterations: adhesion_iterations,
                    change,
                    history,
                });
            }
            let mut s = finish(states, converged && done);
            s.adhesion_iterations = adhesion_iterations;
            return Ok(s);
        }
    }
}

/// Whether any law is adhesive with its adhesion active in its state (else a step needs no
/// adhesion loop).
pub(crate) fn any_adhesion_active<L: ContactLaw>(laws: &[L], states: &[L::State]) -> bool {
    laws.iter()
        .zip(states)
        .any(|(l, s)| l.has_adhesion() && l.adhesion_active(s))
}

/// The states the jumps `u` (`D` per contact) imply from the start of the step; a negative
/// normal jump (an Anderson mix may give one) is clamped to zero, as an opening.
pub(crate) fn states_from_jumps<L: ContactLaw, const D: usize>(
    laws: &[L],
    start: &[L::State],
    u_start: &[[f64; D]],
    u: &[f64],
    dt: f64,
) -> Vec<L::State> {
    (0..laws.len())
        .map(|k| {
            let mut u1: [f64; D] = core::array::from_fn(|d| u[D * k + d]);
            u1[0] = u1[0].max(0.0);
            update_state(&laws[k], &start[k], &u_start[k], &u1, dt)
        })
        .collect()
}

/// The largest [`ContactLaw::state_change`] between two lists of states.
pub(crate) fn largest_state_change<L: ContactLaw>(
    laws: &[L],
    a: &[L::State],
    b: &[L::State],
) -> f64 {
    laws.iter()
        .zip(a.iter().zip(b))
        .fold(0.0_f64, |c, (law, (x, y))| c.max(law.state_change(x, y)))
}

/// The law's state update from the jumps `u0` (start of the step) and `u1`, in 2D or 3D.
fn update_state<L: ContactLaw, const D: usize>(
    law: &L,
    start: &L::State,
    u0: &[f64; D],
    u1: &[f64; D],
    dt: f64,
) -> L::State {
    if D == 3 {
        let a = LocalVec3::spatial(u0[0], u0[1], u0[2]);
        let b = LocalVec3::spatial(u1[0], u1[1], u1[2]);
        law.update_state(start, &a, &b, dt)
    } else {
        let a = LocalVec2::planar(u0[0], u0[1]);
        let b = LocalVec2::planar(u1[0], u1[1]);
        law.update_state(start, &a, &b, dt)
    }
}

/// Damped Anderson acceleration (type II) of a fixed point `u = g(u)`: with the last `window`
/// differences of iterates `ΔU` and residuals `ΔF` (`f = g(u) − u`),
/// `γ = argmin ‖f_k − ΔF γ‖`, `u⁺ = (u_k − ΔU γ) + ω (f_k − ΔF γ)`. `ω = 1` and `window = 0`
/// is the plain fixed point. Safeguard: when the residual grows, the history is dropped and the
/// damping `ω` halved (down to 1/64) — this is what makes a fixed point that would cycle (an
/// interface whose friction grows as it debonds, `f(β) = 1 − β`) converge.
pub(crate) struct Anderson {
    window: usize,
    omega: f64,
    u: Option<Vec<f64>>,
    u_prev: Option<Vec<f64>>,
    f_prev: Option<Vec<f64>>,
    du: Vec<Vec<f64>>,
    df: Vec<Vec<f64>>,
}

/// Smallest damping of the adhesion fixed point.
const MIN_DAMPING: f64 = 1.0 / 64.0;

impl Anderson {
    pub(crate) fn new(window: usize) -> Self {
        Self {
            window,
            omega: 1.0,
            u: None,
            u_prev: None,
            f_prev: None,
            du: Vec::new(),
            df: Vec::new(),
        }
    }

    /// The next iterate, given the image `g` of the current one.
    pub(crate) fn next(&mut self, g: &[f64]) -> Vec<f64> {
        let Some(u) = self.u.take() else {
            self.u = Some(g.to_vec());
            return g.to_vec();
        };
        let f: Vec<f64> = g.iter().zip(&u).map(|(a, b)| a - b).collect();
        let norm = |v: &[f64]| v.iter().map(|a| a * a).sum::<f64>().sqrt();
        if let (Some(fp), Some(up)) = (&self.f_prev, &self.u_prev) {
            let (nf, nfp) = (norm(&f), norm(fp));
            let cos = f.iter().zip(fp).map(|(a, b)| a * b).sum::<f64>()
                / (nf * nfp).max(f64::MIN_POSITIVE);
            if cos < -0.5 && nf > 0.5 * nfp {
                // the iterates swing back and forth (a cycle): forget the history, damp more
                self.du.clear();
                self.df.clear();
                self.omega = (0.5 * self.omega).max(MIN_DAMPING);
            } else if nf > nfp {
                // the residual grew: forget the history
                self.du.clear();
                self.df.clear();
            } else if self.window > 0 {
                self.du.push(u.iter().zip(up).map(|(a, b)| a - b).collect());
                self.df.push(f.iter().zip(fp).map(|(a, b)| a - b).collect());
                if self.du.len() > self.window {
                    self.du.remove(0);
                    self.df.remove(0);
                }
            }
        }
        let mut u_bar = u.clone();
        let mut f_bar = f.clone();
        let k = self.df.len();
        if k > 0 {
            // normal equations (ΔFᵀΔF + εI) γ = ΔFᵀ f, tiny and regularised
            let a = Mat::<f64>::from_fn(k, k, |i, j| {
                let d: f64 = self.df[i].iter().zip(&self.df[j]).map(|(x, y)| x * y).sum();
                if i == j {
                    d * (1.0 + 1e-10) + f64::MIN_POSITIVE
                } else {
                    d
                }
            });
            let b = Mat::<f64>::from_fn(k, 1, |i, _| {
                self.df[i].iter().zip(&f).map(|(x, y)| x * y).sum()
            });
            let gamma = a.partial_piv_lu().solve(&b);
            if (0..k).all(|i| gamma[(i, 0)].is_finite()) {
                for i in 0..k {
                    let c = gamma[(i, 0)];
                    for ((ub, fb), (du, df)) in u_bar
                        .iter_mut()
                        .zip(f_bar.iter_mut())
                        .zip(self.du[i].iter().zip(&self.df[i]))
                    {
                        *ub -= c * du;
                        *fb -= c * df;
                    }
                }
            }
        }
        let out: Vec<f64> = u_bar
            .iter()
            .zip(&f_bar)
            .map(|(a, b)| a + self.omega * b)
            .collect();
        self.f_prev = Some(f);
        self.u_prev = Some(u);
        self.u = Some(out.clone());
        out
    }
}
