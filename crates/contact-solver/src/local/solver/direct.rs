//! The answers found without iterating: `r = 0` when every contact stays open, and (for
//! [`Algorithm::Auto`]) the exact answer of a one-contact Coulomb problem
//! ([`one_contact`](super::super::one_contact), issue 37).

use super::super::one_contact::candidates;
use super::super::problem::ReducedProblem;
use super::super::residual::{contact_statuses, natural_residual};
use super::super::settings::{Algorithm, Solution, UzawaReport};
use super::UzawaSolver;
use contact_laws::ContactLaw;

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
        let report = UzawaReport {
            algorithm,
            iterations: 0,
            outer_iterations: 0,
            tangential_sweeps: 0,
            converged: true,
            stalled: false,
            residual: 0.0,
            change: 0.0,
            history: Vec::new(),
            rho_min: rho.iter().fold(f64::INFINITY, |a, &b| a.min(b)),
            rho_max: rho.iter().fold(0.0, |a, &b| a.max(b)),
            statuses,
            fallback_from: None,
            asymmetry: problem.asymmetry(),
            rescaled: false,
            solved_contacts: 0,
        };
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
        // the block from the rows of W, whatever its storage (a kept non-symmetric W too)
        let mut w = [[0.0; 3]; 3];
        let (mut unit, mut col) = (vec![0.0; d], vec![0.0; d]);
        for l in 0..d {
            unit.fill(0.0);
            unit[l] = 1.0;
            problem.displacement_into(&unit, &mut col);
            for (k, row) in w.iter_mut().enumerate().take(d) {
                row[l] = col[k] - q[k];
            }
        }
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
            let report = UzawaReport {
                algorithm: Algorithm::Auto,
                iterations: 1,
                outer_iterations: 1,
                tangential_sweeps: 0,
                converged: true,
                stalled: false,
                residual,
                change: 0.0,
                history: vec![residual],
                rho_min: rho0[0],
                rho_max: rho0[0],
                statuses,
                fallback_from: None,
                asymmetry: problem.asymmetry(),
                rescaled: false,
                solved_contacts: 1,
            };
            let mut sol = Solution { r, x, report };
            self.check::<L, DT>(problem, laws, states, &mut sol, Some(mu));
            if sol.report.converged {
                return Some(sol);
            }
        }
        None
    }
}
