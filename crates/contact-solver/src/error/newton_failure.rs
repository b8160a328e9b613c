//! [`NewtonFailure`]: what [`SolverError::NewtonNotConverged`] carries.

use super::{HistoryTail, SolverError, tail_note};
use std::error::Error;
use std::fmt;

/// A step of the global Newton around contact that did not converge
/// ([`SolverError::NewtonNotConverged`]): the load the simulation reached (its last converged
/// state, accepted and committed, which the simulation keeps), the load asked for, and the
/// residuals of the last attempt, after [`cuts`](Self::cuts) halvings of the step.
///
/// # Examples
/// ```
/// use contact_solver::{NewtonFailure, SolverError};
/// let e = SolverError::NewtonNotConverged(Box::new(NewtonFailure {
///     load_factor: 0.5, time: 0.5, target_load_factor: 1.0, target_time: 1.0,
///     cuts: 4, iterations: 10, history: vec![1.0, 0.1, 0.09], cause: None,
/// }));
/// assert_eq!(e.history(), Some(&[1.0, 0.1, 0.09][..]));
/// assert!(e.to_string().contains("force factor 5e-1"));
/// ```
#[derive(Clone, PartialEq)]
pub struct NewtonFailure {
    /// The force factor of the last converged state.
    pub load_factor: f64,
    /// The time of the last converged state.
    pub time: f64,
    /// The force factor the step was asked to reach.
    pub target_load_factor: f64,
    /// The time the step was asked to reach.
    pub target_time: f64,
    /// Halvings of the step done.
    pub cuts: usize,
    /// Newton corrections of the last attempt.
    pub iterations: usize,
    /// The relative equilibrium residual at every evaluation of the last attempt (as
    /// [`NewtonReport::residuals`](crate::NewtonReport::residuals)).
    pub history: Vec<f64>,
    /// What stopped the last attempt when it was not the iteration budget (a contact solve
    /// that did not converge, a tangent that lost definiteness); its
    /// [`source`](Error::source).
    pub cause: Option<Box<SolverError>>,
}

impl fmt::Display for NewtonFailure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "the global Newton did not converge: the last converged state is at force factor \
             {:e}, time {:e}, of the step's {:e} at {:e}, after {} cut(s); the last attempt ran \
             {} iteration(s) ({}){}; raise `max_iterations` or `max_cuts` of NewtonSettings or \
             take smaller steps",
            self.load_factor,
            self.time,
            self.target_load_factor,
            self.target_time,
            self.cuts,
            self.iterations,
            tail_note("residuals", &self.history),
            if self.cause.is_some() {
                ", stopped by the error below"
            } else {
                ""
            }
        )
    }
}

impl fmt::Debug for NewtonFailure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("NewtonFailure")
            .field("load_factor", &self.load_factor)
            .field("time", &self.time)
            .field("target_load_factor", &self.target_load_factor)
            .field("target_time", &self.target_time)
            .field("cuts", &self.cuts)
            .field("iterations", &self.iterations)
            .field("history", &HistoryTail(&self.history))
            .field("cause", &self.cause)
            .finish()
    }
}

impl Error for NewtonFailure {
    fn source(&self) -> Option<&(dyn Error + 'static)> {
        self.cause.as_deref().map(|e| e as &(dyn Error + 'static))
    }
}
