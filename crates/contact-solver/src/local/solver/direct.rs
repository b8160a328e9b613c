//! The answers found without iterating: `r = 0` when every contact stays open, and (for
//! [`Algorithm::Auto`]) the exact answer of a one-contact Coulomb problem
//! ([`one_contact`](super::super::one_contact), issue 37).

use super::super::one_contact::candidates;
use super::super::problem::ReducedProblem;
use super::super::residual::{contact_statuses, natural_residual};
use super::super::settings::{Algorithm, Solution, UzawaReport};
use super::UzawaSolver;
use contact_laws::{ContactLaw, ContactStatus};

impl UzawaSolver {
    /// `r = 0` when it is the exact solution, with no iteration: every `q_n ≥ 0` for
    /// Coulomb-type laws (`mu`), else a natural residual of exactly 0 at `r = 0`.
    pub(super) fn open_solution<L: ContactLaw, const DT: usize>(
        &self,
        algorithm: Algorithm,
        problem: &ReducedProblem,
        laws: &[L],
        states: &[L::State],
        mu: Option<&[f64]>,
    ) -> Option<Solution> {
        let (q, m) = (problem.q(), problem.size());
        let r = vec![0.0; m];
        let open = match mu {
            Some(_) => q.iter().step_by(DT + 1).all(|&qn| qn >= 0.0),
            None => natural_residual::<L, DT>(laws, states, &self.sweeps.rho0, &r, q) == 0.0,
        };
        if !open {
            return None;
        }
        let x = q.to_vec();
        let statuses = contact_statuses::<L, DT>(laws, states, &self.sweeps.rho0, &r, &x);
        let rho = &self.sweeps.rho;
        let rho_range = (
            rho.iter().fold(f64::INFINITY, |a, &b| a.min(b)),
            rho.iter().fold(0.0_f64, |a, &b| a.max(b)),
        );
        let report = direct_report(algorithm, 0, 0.0, rho_range, statuses, problem);
        Some(Solution { r, x, report })
    }

    /// [`Algorithm::Auto`] on one contact with a friction coefficient `mu`: the exact answer
    /// of its case (open, stick or slip, [`one_contact`](super::super::one_contact)), with no
    /// iteration, when its natural residual meets the tolerance and it passes the same check
    /// as an iterated answer; `None` otherwise (a law whose answer is not Coulomb's, a root
    /// the grid did not bracket), and the solver iterates as before. Measured on Siconos'
    /// one-contact problems (`docs/benchmarks.md`, "Auto's rule, the whole collection"): the
    /// iterations' set-up was most of `Auto`'s time there, and a block `diag(1e4, 1, 1e-4)`
    /// made the sweeps take 311 iterations.
    pub(super) fn one_contact_solution<L: ContactLaw, const DT: usize>(
        &self,
        problem: &ReducedProblem,
        laws: &[L],
        states: &[L::State],
        mu: &[f64],
    ) -> Option<Solution> {
        let d = problem.dimension();
        let q = problem.q();
        // with one contact its diagonal block is the whole `W` (as stored: a kept
        // non-symmetric `W` too)
        let w = problem.diagonal_block(0);
        for cand in candidates(&w, q, mu[0]) {
            let r = cand[..d].to_vec();
            let mut x = vec![0.0; d];
            problem.displacement_into(&r, &mut x);
            let rho0 = &self.sweeps.rho0;
            let residual = natural_residual::<L, DT>(laws, states, rho0, &r, &x)
                / self.residual_scale(problem, &r);
            if residual.is_nan() || residual > self.settings.tol {
                continue;
            }
            let statuses = contact_statuses::<L, DT>(laws, states, rho0, &r, &x);
            let mut report = direct_report(
                Algorithm::Auto,
                1,
                residual,
                (rho0[0], rho0[0]),
                statuses,
                problem,
            );
            report.outer_iterations = 1;
            report.history = vec![residual];
            report.solved_contacts = 1;
            let mut sol = Solution { r, x, report };
            self.check::<L, DT>(problem, laws, states, &mut sol, Some(mu));
            if sol.report.converged {
                return Some(sol);
            }
        }
        None
    }
}

/// The report of an answer found without iterating (`iterations` 0 for `r = 0`, 1 for the
/// one-contact solve): converged, with the final `residual`, the penalty range `rho` and the
/// contact statuses.
fn direct_report(
    algorithm: Algorithm,
    iterations: usize,
    residual: f64,
    (rho_min, rho_max): (f64, f64),
    statuses: Vec<ContactStatus>,
    problem: &ReducedProblem,
) -> UzawaReport {
    UzawaReport {
        algorithm,
        iterations,
        outer_iterations: 0,
        tangential_sweeps: 0,
        converged: true,
        stalled: false,
        residual,
        change: 0.0,
        history: Vec::new(),
        rho_min,
        rho_max,
        statuses,
        fallback_from: None,
        asymmetry: problem.asymmetry(),
        rescaled: false,
        solved_contacts: 0,
    }
}
