//! The reduced problem of the last solve, kept for export: formed when the solve formed it
//! (the fixed point's last condensed problem, or `F*` with `q` and `μ`), or formed on first
//! request from what Newton's step needs (Newton never condenses the final springs, a dense
//! condensation per step that only an export would use).

use crate::error::SolverError;
use crate::local::ReducedProblem;
use crate::local::adhesion::{AdhesiveStep, condensed_problem};
use contact_laws::ContactLaw;
use std::sync::OnceLock;

/// What an adhesive pass solved with besides `F*` and its final states.
pub(super) struct AdhesiveInputs<L: ContactLaw, const D: usize> {
    pub(super) q: Vec<f64>,
    pub(super) laws: Vec<L>,
    pub(super) u_start: Vec<[f64; D]>,
    pub(super) areas: Vec<f64>,
}

/// What an adhesive step solved by Newton needs to form its condensed problem besides `F*`.
pub(super) struct Pending<L: ContactLaw, const D: usize> {
    inputs: AdhesiveInputs<L, D>,
    states: Vec<L::State>,
}

/// The last reduced problem, formed or pending.
pub(super) enum LastProblem<L: ContactLaw, const D: usize> {
    /// No dense reduced problem (matrix-free or active-set step, or no step yet).
    None,
    Formed(ReducedProblem),
    /// Formed from `F*` (the simulation's, unchanged until the next solve) on first request.
    Pending(Box<Pending<L, D>>, OnceLock<Option<ReducedProblem>>),
}

impl<L: ContactLaw, const D: usize> LastProblem<L, D> {
    /// A problem to form from `F*`, `inputs` and the final `states` when asked.
    pub(super) fn pending(inputs: AdhesiveInputs<L, D>, states: Vec<L::State>) -> Self {
        Self::Pending(Box::new(Pending { inputs, states }), OnceLock::new())
    }

    /// The problem, formed now if pending (`w` is `F*` of the last solve). `None` when the
    /// step had no dense problem, or when the condensation of a pending one fails (it cannot
    /// for a step that solved: the springs' system `I + S F* S` is positive definite).
    pub(super) fn get(&self, w: &[f64]) -> Option<&ReducedProblem> {
        match self {
            Self::None => None,
            Self::Formed(p) => Some(p),
            Self::Pending(p, cell) => cell.get_or_init(|| form(p, w).ok()).as_ref(),
        }
    }
}

fn form<L: ContactLaw, const D: usize>(
    p: &Pending<L, D>,
    w: &[f64],
) -> Result<ReducedProblem, SolverError> {
    let step = AdhesiveStep::<L, D> {
        w,
        q: &p.inputs.q,
        laws: &p.inputs.laws,
        start_states: &p.states,
        u_start: &p.inputs.u_start,
        areas: &p.inputs.areas,
        dt: 0.0,
    };
    condensed_problem(&step, &p.states)
}
