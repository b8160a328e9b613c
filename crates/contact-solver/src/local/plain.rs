//! The plain bipotential iteration ([`Algorithm::Uzawa`] and [`Algorithm::GaussSeidel`]): base
//! steps until both tests of the [stopping rule](crate::local#stopping-rule) hold, or the
//! residual alone has stayed `≤ tol` for a long streak (`residual_stop`).

use super::problem::ReducedProblem;
use super::residual::{natural_residual, norm};
use super::residual_stop::ResidualStop;
use super::settings::{Algorithm, UzawaSettings};
use super::stall::StallDetector;
use super::sweep::Sweeps;
use contact_laws::ContactLaw;

/// What a plain run did.
pub(crate) struct PlainRun {
    pub(crate) iterations: usize,
    pub(crate) converged: bool,
    /// `true` when the [stall detector](super::stall) stopped the run.
    pub(crate) stalled: bool,
    pub(crate) residual: f64,
    pub(crate) change: f64,
}

/// Runs Uzawa steps (`algorithm == Uzawa`, with the global factor `theta`) or Gauss–Seidel
/// sweeps from `(r, x)` (`x = W r + q`; for Uzawa, `sweeps.v` must hold `v(x)`), pushing the
/// relative natural residual of every iteration to `history` (stopping early when the
/// [stall detector](super::stall) fires); `denom_q = max_i ρ⁰_i ‖q‖`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn run<L: ContactLaw, const DT: usize>(
    sweeps: &mut Sweeps,
    problem: &ReducedProblem,
    laws: &[L],
    states: &[L::State],
    st: &UzawaSettings,
    denom_q: f64,
    theta: &mut f64,
    r: &mut [f64],
    x: &mut [f64],
    history: &mut Vec<f64>,
) -> PlainRun {
    let mut run = PlainRun {
        iterations: 0,
        converged: false,
        stalled: false,
        residual: f64::INFINITY,
        change: f64::INFINITY,
    };
    let mut stall = StallDetector::new(st.tuning.stall_window);
    let mut streak = ResidualStop::default();
    while run.iterations < st.max_iterations {
        run.iterations += 1;
        let dr2 = match st.algorithm {
            Algorithm::Uzawa => sweeps.uzawa_step::<L, DT>(problem, laws, states, r, x, theta),
            _ => sweeps.gauss_seidel_sweep::<L, DT>(problem, laws, states, r, x),
        };
        let r_norm = norm(r);
        run.change = dr2.sqrt() / r_norm.max(f64::MIN_POSITIVE);
        let denom = r_norm.max(denom_q).max(f64::MIN_POSITIVE);
        run.residual = natural_residual::<L, DT>(laws, states, &sweeps.rho0, r, x) / denom;
        // the second way to stop: a long streak of residuals ≤ tol (`residual_stop`)
        let on_residual = streak.met(run.iterations, run.residual, run.change, st.tol);
        let both = run.change <= st.tol && run.residual <= st.tol;
        if (both || on_residual) && st.algorithm != Algorithm::Uzawa {
            // x was updated incrementally: confirm on the exact x = W r + q.
            problem.displacement_into(r, x);
            run.residual = natural_residual::<L, DT>(laws, states, &sweeps.rho0, r, x) / denom;
        }
        history.push(run.residual);
        if run.residual <= st.tol && (run.change <= st.tol || on_residual) {
            run.converged = true;
            break;
        }
        if on_residual {
            streak.reset();
        }
        if stall.stalled(run.iterations, run.residual) {
            run.stalled = true;
            break;
        }
    }
    run
}
