//! One run of one algorithm from a starting point, with its report.

use super::UzawaSolver;
use crate::error::SolverError;
use crate::local::anderson::BaseMap;
use crate::local::plain;
use crate::local::problem::ReducedProblem;
use crate::local::residual::{contact_statuses, norm};
use crate::local::settings::{Algorithm, Solution, UzawaReport, UzawaSettings};
use contact_laws::ContactLaw;

impl UzawaSolver {
    /// One run of `st.algorithm` from `r` (the sweeps' `ρ⁰` already set for `problem` by
    /// `solve_checked`, and kept: [`Sweeps::restart`](crate::local::sweep::Sweeps::restart)),
    /// with its report; `converged` is the algorithm's own stopping rule.
    pub(super) fn attempt<L: ContactLaw, const DT: usize>(
        &mut self,
        st: UzawaSettings,
        problem: &ReducedProblem,
        laws: &[L],
        states: &[L::State],
        mut r: Vec<f64>,
    ) -> Result<Solution, SolverError> {
        let m = problem.size();
        self.sweeps.restart(problem, st.tuning.rho_scale);
        self.sweeps
            .exact_contacts::<L, DT>(&st, problem, laws, states);
        let mut x = vec![0.0; m];
        problem.displacement_into(&r, &mut x);
        if st.algorithm == Algorithm::Uzawa {
            self.sweeps.set_velocity::<L, DT>(laws, states, &x);
        }
        let mut history = Vec::with_capacity(st.max_iterations.min(100_000));
        let denom_q = self.sweeps.rho0.iter().fold(0.0_f64, |a, &b| a.max(b)) * norm(problem.q());
        // Uzawa's global scale factor of ρ⁰ (Gauss–Seidel adapts `sweeps.rho` per contact).
        let mut theta = st.tuning.rho_scale;
        let (r_, x_, h_) = (&mut r, &mut x, &mut history);
        // (iterations, outer iterations, tangential sweeps, converged, residual, change)
        let stalled;
        let (iterations, outer_iterations, tangential_sweeps, converged, residual, change) =
            match st.algorithm {
                Algorithm::Uzawa | Algorithm::GaussSeidel => {
                    let run = plain::run::<L, DT>(
                        &mut self.sweeps,
                        problem,
                        laws,
                        states,
                        &st,
                        denom_q,
                        &mut theta,
                        r_,
                        x_,
                        h_,
                    );
                    let (n, c) = (run.iterations, run.converged);
                    stalled = run.stalled;
                    (n, n, 0, c, run.residual, run.change)
                }
                Algorithm::ClassicRccm => {
                    let run = self.classic.solve::<L, DT>(
                        problem,
                        laws,
                        states,
                        &self.sweeps.rho0,
                        &st,
                        r_,
                        x_,
                        h_,
                    )?;
                    self.sweeps.rho.copy_from_slice(&self.sweeps.rho0);
                    stalled = run.stalled;
                    let (n, o, t) = (run.iterations, run.outer_iterations, run.tangential_sweeps);
                    (n, o, t, run.converged, run.residual, run.change)
                }
                Algorithm::AndersonGaussSeidel | Algorithm::AndersonUzawa => {
                    let base = if st.algorithm == Algorithm::AndersonUzawa {
                        BaseMap::Uzawa
                    } else {
                        BaseMap::GaussSeidel
                    };
                    let run = self.anderson.solve::<L, DT>(
                        &mut self.sweeps,
                        base,
                        problem,
                        laws,
                        states,
                        &st,
                        denom_q,
                        &mut theta,
                        r_,
                        x_,
                        h_,
                    );
                    let n = run.iterations;
                    stalled = run.stalled;
                    (n, n, 0, run.converged, run.residual, run.change)
                }
                // resolved in solve_with_states
                Algorithm::Newton | Algorithm::Auto => {
                    let run = self.newton.solve::<L, DT>(
                        &mut self.sweeps,
                        problem,
                        laws,
                        states,
                        &st,
                        denom_q,
                        r_,
                        x_,
                        h_,
                    )?;
                    let (n, o) = (run.iterations, run.newton_steps);
                    stalled = run.stalled;
                    (n, o, 0, run.converged, run.residual, run.change)
                }
            };
        problem.displacement_into(&r, &mut x);
        if matches!(st.algorithm, Algorithm::Uzawa | Algorithm::AndersonUzawa) {
            for (rho, rho0) in self.sweeps.rho.iter_mut().zip(&self.sweeps.rho0) {
                *rho = theta * rho0;
            }
        }
        let statuses = contact_statuses::<L, DT>(laws, states, &self.sweeps.rho0, &r, &x);
        let report = UzawaReport {
            algorithm: st.algorithm,
            iterations,
            outer_iterations,
            tangential_sweeps,
            converged,
            stalled,
            residual,
            change,
            history,
            rho_min: self.sweeps.rho.iter().fold(f64::INFINITY, |a, &b| a.min(b)),
            rho_max: self.sweeps.rho.iter().fold(0.0, |a, &b| a.max(b)),
            statuses,
            fallback_from: None,
            asymmetry: 0.0,
            rescaled: false,
            solved_contacts: problem.contact_count(),
        };
        Ok(Solution { r, x, report })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::local::generate::random_sparse_problem;

    /// Issue 37, ninth part: `ρ⁰` (one eigenvalue problem a contact) is computed once a solve,
    /// by `solve_checked`, however many runs follow (`Auto`'s first runs and probes, Newton,
    /// the sweep, the fallbacks); main computed it again in every run (at least twice a
    /// solve, 3 times for `Auto`'s classical first run then Newton on Siconos'
    /// `NESpheres_10_1`). A second solve on the same solver computes it again (a new problem
    /// may have other diagonal blocks).
    #[test]
    fn issue_37_rho0_computed_once_a_solve() {
        let p = random_sparse_problem(3, 40, 4, 5);
        let laws = p.coulomb_laws();
        for algorithm in [Algorithm::Auto, Algorithm::Newton, Algorithm::ClassicRccm] {
            let st = UzawaSettings::default()
                .with_algorithm(algorithm)
                .with_tol(1e-10);
            let mut solver = UzawaSolver::new(st);
            let sol = solver.solve(&p, &laws).unwrap();
            assert!(sol.report.converged);
            assert_eq!(solver.sweeps.rho0_computed, 1, "{algorithm:?}");
            solver.solve(&p, &laws).unwrap();
            assert_eq!(solver.sweeps.rho0_computed, 2, "{algorithm:?}");
        }
    }
}
