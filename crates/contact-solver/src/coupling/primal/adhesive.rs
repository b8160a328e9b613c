//! The primal active set with adhesive (RCCM) springs: the seed's fixed point on the states,
//! each iteration one primal solve with the springs of the current states in the stiffness.
//!
//! With the springs `r_adh = −b (x + o)` (`b` the law's per-area stiffness times the tributary
//! area, `o` the tangential jump at the start of the step), the total reaction is
//! `r = r̄ + r_adh` and `K̃ w = r` becomes `(K̃ + b) w = r̄ − b (q + o)`: the springs are a
//! diagonal stiffness on the contact dofs and a known load, and `r̄` obeys the contact law
//! (Signorini and Coulomb with `μ̄` of the states) on the jumps `x = q + w`, which is the
//! primal solve of [`super::solve_primal`]. The states are then updated from the jumps, with
//! the same damped Anderson step as the dense path's fixed point
//! ([`crate::local::adhesion`]), until the largest state change is below the tolerance.
//!
//! The factor keeps the springs `b₀` it was formed with (the last step's, while the active
//! list is the same): a change of the springs is lagged as a load, and once the states have
//! converged the springs go into the factor for one exact solve if the lag's force still
//! matters (`docs/theory.md` §13). Each solve starts from the last one's guess and jumps, to a
//! tolerance that follows the last state change, down to a tenth of the solver's (the states
//! amplify the jumps' error), and at that tenth for the rest of the step once the state change
//! stops falling (loose solves can leave a contact flipping between stick and slip). Newton
//! with the states eliminated, the dense path's default, would need the springs' tangent,
//! which is not symmetric positive definite once the glue softens.

use super::{PrimalCache, PrimalStep, solve_primal};
use crate::error::SolverError;
use crate::local::adhesion::{
    AdhesionOptions, Anderson, largest_state_change, start_offset, states_from_jumps,
};
use contact_laws::{ContactLaw, ContactStatus};
use fem_core::Structure;

/// Most iterations with the springs' change lagged before they are put in the factor.
const MAX_LAGGED_ITERATIONS: usize = 100;

/// The inexact fixed point: each primal solve's relative tolerance is this fraction of the
/// last state change, at most [`LOOSEST`] and at least the solver's (which the answer's last
/// solve always meets).
const FORCING: f64 = 1e-2;
const LOOSEST: f64 = 1e-3;

/// The primal solves of an adhesive step run at this fraction of the solver's tolerance. The
/// state update amplifies the jumps' error where the jumps are small (`β = w/(C u²)`:
/// `δβ/β = 2 δu/u`); at the solver's own tolerance the state change of the 3D pile stalled
/// at 3e-8–1.4e-7, above the adhesion tolerance 1e-8.
const TIGHTER: f64 = 0.1;

/// After this many iterations without a new smallest state change, every solve of the step
/// runs at the tight tolerance. Loose solves can leave a contact or two flipping between stick
/// and slip from one iteration to the next, and the fixed point then cycles (the 3D pile,
/// once the shaft slides: changes of 8e-4–1.9e-3, period about 30).
const STALL: usize = 20;

/// What an adhesive step adds to a [`PrimalStep`] (whose `states` are the start states, and
/// whose `mu`, `springs` and `spring_load` are recomputed from the iterated states).
pub(crate) struct AdhesiveData<'a, const D: usize> {
    /// Jumps `(u_n, u_t…)` at the start of the step.
    pub u_start: &'a [[f64; D]],
    /// Tributary area of each contact.
    pub areas: &'a [f64],
    pub dt: f64,
}

/// The answer of an adhesive primal step, on the active list.
pub(crate) struct AdhesivePrimal<S> {
    /// Total reactions `r̄ + r_adh`.
    pub r: Vec<f64>,
    pub r_bar: Vec<f64>,
    pub x: Vec<f64>,
    pub states: Vec<S>,
    pub statuses: Vec<ContactStatus>,
    pub adhesion_iterations: usize,
    /// Primal iterations summed over the fixed point, and of them the inner ones.
    pub iterations: usize,
    pub inner_iterations: usize,
    pub solves: usize,
    pub residual: f64,
    pub converged: bool,
}

/// The fixed point on the states around [`solve_primal`] (module docs). `D = T + 1`.
pub(crate) fn solve_primal_adhesive<
    S: Structure<N> + ?Sized,
    const N: usize,
    L: ContactLaw,
    const T: usize,
    const D: usize,
>(
    structure: &S,
    cache: &mut PrimalCache,
    step: &PrimalStep<'_, L>,
    data: &AdhesiveData<'_, D>,
    options: &AdhesionOptions,
) -> Result<AdhesivePrimal<L::State>, SolverError> {
    let na = step.active.len();
    if D != T + 1 || step.q.len() != D * na || data.u_start.len() != na || data.areas.len() != na {
        return Err(SolverError::SizeMismatch {
            what: "adhesive primal step (D values per contact)",
            expected: D * na,
            found: step.q.len(),
        });
    }
    let m = D * na;
    // the springs act on the total tangential jump: x + o
    let offset = start_offset(data.u_start);
    let mut states = step.states.to_vec();
    let mut r_bar = step.r0.to_vec();
    let mut anderson = Anderson::new(options.anderson_window);
    let mut history = Vec::new();
    let (mut springs, mut load, mut mu) = (vec![0.0; m], vec![0.0; m], vec![0.0; na]);
    let mut out = AdhesivePrimal {
        r: Vec::new(),
        r_bar: Vec::new(),
        x: Vec::new(),
        states: Vec::new(),
        statuses: Vec::new(),
        adhesion_iterations: 0,
        iterations: 0,
        inner_iterations: 0,
        solves: 0,
        residual: 0.0,
        converged: true,
    };
    let update = |u: &[f64]| states_from_jumps(step.laws, step.states, data.u_start, u, data.dt);
    // the springs in the factorised stiffness, `b₀`: the last step's while the active list
    // is the same (a change of the springs is then lagged, below), else the start states'
    let mut b0 = cache.springs_for(step.active).to_vec();
    // the jumps the lag is taken at: the start of the step's, then the iterate's
    let mut u_iter: Vec<f64> = data.u_start.iter().flatten().copied().collect();
    let mut since_exact = 0;
    let mut x0 = vec![0.0; m];
    // the smallest state change so far, the iterations since, and whether every solve is now
    // at the tight tolerance
    let (mut best_change, mut since_best, mut exact) = (f64::INFINITY, 0, false);
    let (mut last_change, mut force_full) = (f64::INFINITY, false);
    loop {
        for (k, (law, s)) in step.laws.iter().zip(&states).enumerate() {
            let [kn, kt] = law.adhesive_stiffness(s);
            mu[k] = law.friction_coefficient(s).unwrap_or(0.0);
            for c in 0..D {
                let b = data.areas[k] * if c == 0 { kn } else { kt };
                springs[D * k + c] = if c == 0 || step.tangent[k] { b } else { 0.0 };
            }
        }
        if b0.len() != m || since_exact >= MAX_LAGGED_ITERATIONS {
            b0.clone_from(&springs);
            since_exact = 0;
        }
        // the springs' load at w = 0, with the change of the springs since the factorisation
        // lagged: (K̃ + b₀) w = r̄ − b (q + o) − (b − b₀) w_iter
        for j in 0..m {
            let w_iter = u_iter[j] - offset[j] - step.q[j];
            load[j] = -springs[j] * (step.q[j] + offset[j]) - (springs[j] - b0[j]) * w_iter;
        }
        let lagged = springs != b0;
        // the jumps to start from: the start of the step's (no slip yet), then the iterate's
        for j in 0..m {
            x0[j] = u_iter[j] - offset[j];
        }
        // an inexact fixed point: the solve's tolerance follows the last state change, down to
        // a tenth of the solver's; all at that once the states stall
        let tight = step.tol * TIGHTER;
        let tol = if force_full || exact {
            tight
        } else {
            tight.max((FORCING * last_change).min(LOOSEST))
        };
        let inner = PrimalStep {
            states: &states,
            mu: &mu,
            r0: &r_bar,
            x0: &x0,
            springs: &b0,
            spring_load: &load,
            tol,
            ..*step
        };
        let sol = solve_primal::<S, N, L, T>(structure, cache, &inner)?;
        out.iterations += sol.iterations;
        out.inner_iterations += sol.inner_iterations;
        out.solves += sol.solves;
        out.residual = sol.residual;
        out.converged &= sol.converged;
        out.adhesion_iterations += 1;
        since_exact += 1;
        r_bar.clone_from(&sol.r);
        let jumps: Vec<f64> = sol.x.iter().zip(&offset).map(|(x, o)| x + o).collect();
        // the fixed-point residual: the states the solve's own jumps imply, against the
        // states it used
        let implied = update(&jumps);
        let change = largest_state_change(step.laws, &implied, &states);
        history.push(change);
        let done = change <= options.tol;
        // the equilibrium error of the lag, (b − b₀)(w − w_iter), against the reactions: as
        // small as a state change within the tolerance would make it
        let lag_error = (0..m).fold(0.0_f64, |e, j| {
            e.max(((springs[j] - b0[j]) * (jumps[j] - u_iter[j])).abs())
        });
        let scale = (0..m).fold(0.0_f64, |e, j| {
            e.max(sol.r[j].abs()).max((springs[j] * jumps[j]).abs())
        });
        let lag_large = lagged && lag_error > options.tol * scale;
        if done && (lag_large || tol > step.tol) {
            // the states have converged with the springs' change lagged, or from a loose
            // solve: solve once more at the tolerance, with the springs in the factor if
            // the lag matters, from the jumps found
            if lag_large {
                b0.clone_from(&springs);
                since_exact = 0;
            }
            u_iter = jumps;
            force_full = true;
            continue;
        }
        last_change = change;
        if change < best_change {
            (best_change, since_best) = (change, 0);
        } else {
            since_best += 1;
            if since_best >= STALL && !exact {
                // from here every solve is tight, and the secant step starts afresh: the
                // damping the loose solves' noise put on it slowed the rest (the coarse 3D
                // pile: up to 148 iterations in a step, and the cap of 200 reached in one of
                // four runs, against at most 87–113 with the restart)
                exact = true;
                anderson = Anderson::new(options.anderson_window);
            }
        }
        if done || out.adhesion_iterations >= options.max_iterations {
            if !done && !options.accept_non_converged {
                return Err(SolverError::AdhesionNotConverged {
                    iterations: out.adhesion_iterations,
                    change,
                    history,
                });
            }
            out.converged &= done;
            // the total reaction with the springs the solve used
            out.r = (0..m).map(|j| sol.r[j] - springs[j] * jumps[j]).collect();
            out.r_bar = sol.r;
            out.x = sol.x;
            out.statuses = sol.statuses;
            // the states of the answer: those its jumps imply (within the tolerance of those
            // it was solved with)
            out.states = implied;
            return Ok(out);
        }
        u_iter = anderson.next(&jumps);
        states = update(&u_iter);
    }
}
