//! The convergence history of a Newton load path: what [`crate::plastic::newton::solve`]
//! returns and what [`crate::FemError::NotConverged`] carries (kept below `error` so that the
//! error can carry it).

/// One load step tried: its load factor and the relative residual before each solve and
/// after the last (so `residuals.len() − 1` solves when it converged).
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct NewtonStep {
    /// The load factor at the end of the step.
    pub load_factor: f64,
    /// The relative residual of every iterate ([`crate::plastic::newton`] states the norm).
    pub residuals: Vec<f64>,
    /// Whether the step converged (else it was cut, or the path failed).
    pub converged: bool,
}

/// The history of a Newton load path ([`crate::plastic::newton::solve`]).
#[derive(Clone, Debug, Default, PartialEq)]
#[non_exhaustive]
pub struct NewtonReport {
    /// Every step tried, in order (the cut ones included, with `converged: false`).
    pub steps: Vec<NewtonStep>,
    /// The step halvings made.
    pub cuts: usize,
    /// The load factor of the last converged state.
    pub load_factor: f64,
}

impl NewtonReport {
    /// The converged steps.
    pub fn converged_steps(&self) -> impl Iterator<Item = &NewtonStep> {
        self.steps.iter().filter(|s| s.converged)
    }
}
