//! Stage 3, the local solve on the active set: the reduced problem on the dense `F*` inside the
//! adhesion loop ([`crate::local::adhesion`]), the matrix-free sweep
//! ([`crate::local::matrix_free`]), or the primal active-set iteration
//! ([`crate::coupling::primal`]). Each gathers the active contacts' laws, states and free
//! gaps, solves, and returns the reactions on the active set.

use super::ContactSimulation;
use super::dispatch;
use super::last_problem::{AdhesiveInputs, LastProblem};
use super::report::StepReport;
use super::scheme::TimeScheme;
use crate::coupling::primal::adhesive::AdhesiveData;
use crate::coupling::primal::{LocalFrame, PrimalStep};
use crate::coupling::space::ContactSpace;
use crate::error::SolverError;
use crate::local::ReducedProblem;
use crate::local::adhesion::{
    AdhesionOptions, AdhesiveSolution, AdhesiveStep, any_adhesion_active, solve_adhesive_shared,
};
use contact_laws::{ContactLaw, ContactStatus};
use fem_core::{Dim, Structure};

/// What a pass of the local solve produces: the solution on its active set, or the candidates
/// to add to the active set before solving again (a floating body's rigid motion closes them).
pub(super) enum Pass<T> {
    Solved(Solved<T>),
    Extend(Vec<usize>),
}

/// The solution of the reduced problem of a step, on the active set.
pub(super) struct Solved<T> {
    /// The active set solved (candidate indices, sorted).
    pub(super) active: Vec<usize>,
    pub(super) r: Vec<f64>,
    pub(super) r_bar: Vec<f64>,
    /// `x = (gap, slip increment)` of the reduced solution.
    pub(super) x: Vec<f64>,
    pub(super) statuses: Vec<ContactStatus>,
    pub(super) states: Vec<T>,
    /// Floating structures: the change `Δα` of the rigid-body amplitudes (empty otherwise).
    pub(super) alpha: Vec<f64>,
}

impl<T> Solved<T> {
    /// The pass's answer on `active` from the adhesive solve, and the condensed problem it
    /// solved (`None` after Newton: formed when asked, [`LastProblem`]).
    pub(super) fn from_adhesive(
        active: &[usize],
        sol: AdhesiveSolution<T>,
        alpha: Vec<f64>,
    ) -> (Self, Option<ReducedProblem>) {
        let solved = Self {
            active: active.to_vec(),
            r: sol.r,
            r_bar: sol.r_bar,
            x: sol.x,
            statuses: sol.report.statuses,
            states: sol.states,
            alpha,
        };
        (solved, sol.condensed)
    }
}

impl<S: Structure<D>, L: ContactLaw + Clone, const D: usize, T: TimeScheme<S, D>>
    ContactSimulation<S, L, D, T>
where
    Dim<D>: ContactSpace<D>,
{
    /// The primal active-set solve of the step (no `F*`), with the adhesion fixed point
    /// around it when a law is adhesive ([`crate::coupling::primal::adhesive`]).
    ///
    /// In 3D ([`ContactSpace::ONE_FACTOR`]) the structure's factor of `K` is freed while the
    /// active set holds its own, and refactored after it, once the active set's is dropped:
    /// one factor at a time, whether the solve succeeded or not (a failed step may go on
    /// with a dense `F*`, which solves with `K`).
    pub(super) fn solve_active_set(
        &mut self,
        active: &[usize],
        free: &[[f64; D]],
        frames: &[LocalFrame],
        dt: f64,
        report: &mut StepReport,
    ) -> Result<Solved<L::State>, SolverError> {
        let released = <Dim<D> as ContactSpace<D>>::ONE_FACTOR && self.structure.release_factor();
        let solved = self.solve_active_set_with(active, free, frames, dt, report);
        if released {
            self.cache.primal.drop_factor();
            self.structure.restore_factor()?;
            self.counters.structure_refactorizations += 1;
        }
        solved
    }

    /// [`Self::solve_active_set`] once the structure's factor is settled.
    fn solve_active_set_with(
        &mut self,
        active: &[usize],
        free: &[[f64; D]],
        frames: &[LocalFrame],
        dt: f64,
        report: &mut StepReport,
    ) -> Result<Solved<L::State>, SolverError> {
        if self.velocity_springs_of(active).is_some() {
            return Err(SolverError::Unsupported(
                "adhesion at velocity level on the active-set path (use a dense F*)".into(),
            ));
        }
        let laws = self.laws_of(active);
        let states = self.states_of(active);
        let tangent: Vec<bool> = active.iter().map(|&i| self.tangent_needed(i)).collect();
        let mu: Vec<f64> = laws
            .iter()
            .zip(&states)
            .map(|(l, s)| l.friction_coefficient(s).unwrap_or(0.0))
            .collect();
        let q = self.q_of(active, free);
        let r0 = self.r_bar_of(active);
        let step = PrimalStep {
            active,
            frames,
            laws: &laws,
            states: &states,
            mu: &mu,
            tangent: &tangent,
            q: &q,
            r0: &r0,
            x0: &[],
            springs: &[],
            spring_load: &[],
            tol: self.settings.solver.tol,
            max_iterations: self
                .settings
                .solver
                .max_iterations
                .min(crate::coupling::primal::PRIMAL_MAX_ITERATIONS),
            accept_non_converged: self.settings.solver.accept_non_converged,
        };
        let before = self.cache.primal.factorizations;
        if any_adhesion_active(&laws, &states) {
            let u_start = self.jumps_of(active);
            let areas = self.areas_of(active);
            let data = AdhesiveData {
                u_start: &u_start,
                areas: &areas,
                dt,
            };
            let options = self.adhesion_options();
            let (structure, cache) = (&self.structure, &mut self.cache.primal);
            let sol = dispatch::primal_adhesive(structure, cache, &step, &data, &options)?;
            self.counters.active_set_steps += 1;
            self.counters.active_set_factorizations += self.cache.primal.factorizations - before;
            self.counters.active_set_solves += sol.solves;
            self.counters.active_set_inner_iterations += sol.inner_iterations;
            report.contact_iterations += sol.iterations;
            report.adhesion_iterations += sol.adhesion_iterations;
            report.residual = sol.residual;
            report.converged &= sol.converged;
            return Ok(Solved {
                active: active.to_vec(),
                r: sol.r,
                r_bar: sol.r_bar,
                x: sol.x,
                statuses: sol.statuses,
                states: sol.states,
                alpha: Vec::new(),
            });
        }
        let sol = dispatch::primal(&self.structure, &mut self.cache.primal, &step)?;
        self.counters.active_set_steps += 1;
        self.counters.active_set_factorizations += self.cache.primal.factorizations - before;
        self.counters.active_set_solves += sol.solves;
        self.counters.active_set_inner_iterations += sol.inner_iterations;
        report.contact_iterations += sol.iterations;
        report.residual = sol.residual;
        report.converged &= sol.converged;
        Ok(Solved {
            active: active.to_vec(),
            r: sol.r.clone(),
            r_bar: sol.r,
            x: sol.x,
            statuses: sol.statuses,
            states,
            alpha: Vec::new(),
        })
    }

    /// The reduced solve without `F*`: one structure solve per product `F* r`.
    pub(super) fn solve_matrix_free_active(
        &mut self,
        active: &[usize],
        free: &[[f64; D]],
        report: &mut StepReport,
    ) -> Result<Solved<L::State>, SolverError> {
        let na = active.len();
        let m = D * na;
        let laws = self.laws_of(active);
        let states = self.states_of(active);
        let q = self.q_of(active, free);
        let rho0 = self.estimate_rho0(active)?;
        let mut r = self.r_bar_of(active);
        let mut x = vec![0.0; m];
        let rows: Vec<usize> = active
            .iter()
            .flat_map(|&i| (0..D).map(move |d| D * i + d))
            .collect();
        // rows that carry the contact's response: in 3D a decoupled tangential row is
        // `x = q + r/ρ⁰` (its `r_t` stays 0); 2D applies every row
        let this = &*self;
        let applied: Vec<bool> = active
            .iter()
            .flat_map(|&i| {
                (0..D).map(move |d| {
                    d == 0
                        || !<Dim<D> as ContactSpace<D>>::DECOUPLE_HELD_TANGENTS
                        || this.tangent_solved(i, d)
                })
            })
            .collect();
        let (structure, h_rows) = (&self.structure, &self.interface.h_rows);
        let mut scratch = vec![0.0; structure.dof_count()];
        let mut applications = 0;
        let apply = |r: &[f64], x: &mut [f64]| -> Result<(), SolverError> {
            scratch.fill(0.0);
            for (j, &row) in rows.iter().enumerate() {
                if applied[j] && r[j] != 0.0 {
                    for &(dof, a) in &h_rows[row] {
                        scratch[dof] += a * r[j];
                    }
                }
            }
            structure.solve_in_place(&mut scratch)?;
            applications += 1;
            for (j, &row) in rows.iter().enumerate() {
                x[j] = q[j]
                    + if applied[j] {
                        h_rows[row]
                            .iter()
                            .map(|&(dof, a)| a * scratch[dof])
                            .sum::<f64>()
                    } else {
                        r[j] / rho0[j / D]
                    };
            }
            Ok(())
        };
        let mf = dispatch::matrix_free::<_, D>(
            apply,
            &laws,
            &states,
            &rho0,
            self.settings.tuning.matrix_free_window,
            &self.settings.solver,
            &mut r,
            &mut x,
        )?;
        self.counters.operator_applications += applications;
        self.counters.structure_solves += applications;
        self.counters.matrix_free_steps += 1;
        report.contact_iterations += mf.iterations;
        report.residual = mf.residual;
        report.converged &= mf.converged;
        let statuses = dispatch::statuses::<_, D>(&laws, &states, &rho0, &r, &x);
        Ok(Solved {
            active: active.to_vec(),
            r: r.clone(),
            r_bar: r,
            x,
            statuses,
            states,
            alpha: Vec::new(),
        })
    }

    /// The adhesion fixed point around the reduced solve, on the cached active set.
    pub(super) fn solve_active(
        &mut self,
        active: &[usize],
        free: &[[f64; D]],
        dt: f64,
        report: &mut StepReport,
    ) -> Result<Solved<L::State>, SolverError> {
        if let Some(springs) = self.velocity_springs_of(active) {
            return self.solve_velocity_adhesive(active, free, &springs, dt, report);
        }
        let laws = self.laws_of(active);
        let start_states = self.states_of(active);
        let u_start = self.jumps_of(active);
        let areas = self.areas_of(active);
        let q = self.q_of(active, free);
        let r_bar = self.r_bar_of(active);
        let step = AdhesiveStep {
            w: &self.cache.w,
            q: &q,
            laws: &laws,
            start_states: &start_states,
            u_start: &u_start,
            areas: &areas,
            dt,
        };
        let mut options = self.adhesion_options();
        options.warm_start = options.warm_start && self.warm.enabled();
        let shared = Some(&self.cache.w);
        let sol = solve_adhesive_shared(&mut self.solver, &step, shared, Some(&r_bar), &options)?;
        report.contact_iterations += sol.contact_iterations;
        report.adhesion_iterations += sol.adhesion_iterations;
        let inputs = AdhesiveInputs {
            q,
            laws,
            u_start,
            areas,
        };
        Ok(self.finish_adhesive(active, sol, Vec::new(), inputs, report, false))
    }

    /// `q` of the reduced problem on `active`, per contact the scheme's
    /// ([`TimeScheme::rhs`]) from the jumps `free` the free response predicts and the accepted
    /// ones: quasi-static, `q = (g₀ + n·u_rel(u_free), t·u_rel(u_free) − u_t,start)`; `0` on the
    /// decoupled tangential rows.
    pub(super) fn q_of(&self, active: &[usize], free: &[[f64; D]]) -> Vec<f64> {
        let mut q = vec![0.0; D * active.len()];
        for (k, &i) in active.iter().enumerate() {
            let qi = self.scheme.rhs(i, &free[i], &self.accepted.jumps[i]);
            q[D * k] = qi[0];
            for d in 1..D {
                if self.tangent_solved(i, d) {
                    q[D * k + d] = qi[d];
                }
            }
        }
        q
    }

    /// The laws of the contacts of `active`.
    pub(super) fn laws_of(&self, active: &[usize]) -> Vec<L> {
        active
            .iter()
            .map(|&i| self.interface.law(i).clone())
            .collect()
    }

    /// The accepted law states of the contacts of `active`.
    pub(super) fn states_of(&self, active: &[usize]) -> Vec<L::State> {
        active.iter().map(|&i| self.accepted.states[i]).collect()
    }

    /// The accepted jumps of the contacts of `active`.
    pub(super) fn jumps_of(&self, active: &[usize]) -> Vec<[f64; D]> {
        active.iter().map(|&i| self.accepted.jumps[i]).collect()
    }

    /// The accepted reactions `r̄` of the contacts of `active`, flat.
    pub(super) fn r_bar_of(&self, active: &[usize]) -> Vec<f64> {
        active
            .iter()
            .flat_map(|&i| self.accepted.r_bar[i])
            .collect()
    }

    /// The tributary areas of the contacts of `active`.
    pub(super) fn areas_of(&self, active: &[usize]) -> Vec<f64> {
        active
            .iter()
            .map(|&i| self.interface.candidates[i].area)
            .collect()
    }

    /// The adhesion loop's options from the settings (the primal path reads its tolerance,
    /// cap and Anderson window; the warm start and the method are the dense path's, which
    /// also asks its pacing, [`WarmStartPacing`](crate::local::adhesion::WarmStartPacing)).
    fn adhesion_options(&self) -> AdhesionOptions {
        AdhesionOptions {
            tol: self.settings.adhesion_tol,
            max_iterations: self.settings.max_adhesion_iterations,
            accept_non_converged: self.settings.solver.accept_non_converged,
            always_iterate: !self.settings.tuning.skip.adhesion_loop_only_when_adhesive,
            anderson_window: self.settings.tuning.adhesion_anderson_window,
            method: self.settings.tuning.adhesion_method,
            warm_start: self.settings.tuning.adhesion_warm_start,
        }
    }

    /// An adhesive pass's answer: paces the warm start, counts Newton's outcomes (unless
    /// `counted`: the floating stage counts every one of its solves as it goes), reports the
    /// residual, and keeps the reduced problem for export (the solve's, or, after Newton, one
    /// formed on request from `F*`, `inputs` and the final states).
    pub(super) fn finish_adhesive(
        &mut self,
        active: &[usize],
        sol: AdhesiveSolution<L::State>,
        alpha: Vec<f64>,
        inputs: AdhesiveInputs<L, D>,
        report: &mut StepReport,
        counted: bool,
    ) -> Solved<L::State> {
        self.warm.record(&sol);
        if !counted {
            self.counters.record_adhesive(&sol);
        }
        report.residual = sol.report.residual;
        report.converged &= sol.converged;
        let (solved, condensed) = Solved::from_adhesive(active, sol, alpha);
        self.cache.last_problem = match condensed {
            Some(p) => LastProblem::Formed(p),
            None => LastProblem::pending(inputs, solved.states.clone()),
        };
        solved
    }
}
