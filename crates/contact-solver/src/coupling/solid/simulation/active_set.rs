//! The primal active-set path of a 3D step ([`FlexibilityMode::ActiveSet`], and `Auto` past its
//! dense limit): no `F*`, the contact conditions imposed on the factorised stiffness, as in 2D
//! ([`crate::coupling::primal`]) with two tangents per contact and the friction force's
//! direction in the tangent plane as a lagged unknown.

use super::{SolidContactSimulation, Solved};
use crate::coupling::primal::adhesive::{AdhesiveData, solve_primal_adhesive};
use crate::coupling::primal::{
    LocalFrame, PRIMAL_MAX_ITERATIONS, PrimalStep, frames, solve_primal,
};
use crate::error::SolverError;
use crate::local::adhesion::{AdhesionOptions, any_adhesion_active};
use contact_laws::ContactLaw;
use fem_core::Structure;

impl<S: Structure<3>, L: ContactLaw + Clone> SolidContactSimulation<S, L> {
    /// The local frames of the active-set path on `active`, or why it does not apply: each
    /// contact's rows of `H` a rotation of its node's free dofs, minus a combination of target
    /// nodes' (rigid obstacles, node pairs, node-to-face), laws with a friction coefficient, a
    /// structure that exposes its stiffness.
    pub(super) fn active_set_frames(&self, active: &[usize]) -> Result<Vec<LocalFrame>, String> {
        if self.structure.stiffness_matrix().is_none() {
            return Err("the structure does not expose its stiffness matrix".into());
        }
        for &i in active {
            let zone = &self.zones[self.candidates[i].zone];
            if zone.law.friction_coefficient(&self.states[i]).is_none() {
                return Err(format!(
                    "zone `{}`: its law has no friction coefficient (not a Coulomb-cone law)",
                    zone.name
                ));
            }
        }
        let node_of = |i: usize| self.candidates[i].node;
        frames(&self.structure, &self.h_rows, active, &node_of)
    }

    /// The adhesion loop's options from the settings (the primal path reads its tolerance,
    /// cap and Anderson window; the warm start and the method are the dense path's, which
    /// also asks its pacing, [`WarmStartPacing`](crate::local::adhesion::WarmStartPacing)).
    pub(super) fn adhesion_options(&self) -> AdhesionOptions {
        AdhesionOptions {
            accept_non_converged: self.settings.adhesion.accept_non_converged
                || self.settings.solver.accept_non_converged,
            warm_start: self.settings.adhesion.warm_start,
            ..self.settings.adhesion
        }
    }

    /// The primal active-set solve of the reduced problem on `active`, with the adhesion
    /// fixed point around it when a law is adhesive ([`crate::coupling::primal::adhesive`]).
    pub(super) fn solve_active_set(
        &mut self,
        active: &[usize],
        frames: &[LocalFrame],
        free: &[[f64; 3]],
        dt: f64,
    ) -> Result<Solved<L::State>, SolverError> {
        let laws: Vec<L> = active
            .iter()
            .map(|&i| self.zones[self.candidates[i].zone].law.clone())
            .collect();
        let states: Vec<L::State> = active.iter().map(|&i| self.states[i]).collect();
        let tangent: Vec<bool> = active.iter().map(|&i| self.tangent_needed(i)).collect();
        let mu: Vec<f64> = laws
            .iter()
            .zip(&states)
            .map(|(l, s)| l.friction_coefficient(s).unwrap_or(0.0))
            .collect();
        let mut q = vec![0.0; 3 * active.len()];
        for (k, &i) in active.iter().enumerate() {
            q[3 * k] = free[i][0];
            if tangent[k] {
                for d in 1..3 {
                    q[3 * k + d] = free[i][d] - self.jumps[i][d];
                }
            }
        }
        let r0: Vec<f64> = active.iter().flat_map(|&i| self.r_bar_last[i]).collect();
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
                .min(PRIMAL_MAX_ITERATIONS),
            accept_non_converged: self.settings.solver.accept_non_converged,
        };
        let before = self.primal.factorizations;
        if any_adhesion_active(&laws, &states) {
            let u_start: Vec<[f64; 3]> = active.iter().map(|&i| self.jumps[i]).collect();
            let areas: Vec<f64> = active.iter().map(|&i| self.candidates[i].area).collect();
            let data = AdhesiveData {
                u_start: &u_start,
                areas: &areas,
                dt,
            };
            let options = self.adhesion_options();
            let sol = solve_primal_adhesive::<_, 3, _, 2, 3>(
                &self.structure,
                &mut self.primal,
                &step,
                &data,
                &options,
            )?;
            return Ok(Solved {
                r: sol.r,
                r_bar: sol.r_bar,
                states: Some(sol.states),
                iterations: sol.iterations,
                adhesion_iterations: sol.adhesion_iterations,
                residual: sol.residual,
                matrix_free: false,
                active_set: true,
                factorizations: self.primal.factorizations - before,
            });
        }
        let sol = solve_primal::<_, 3, _, 2>(&self.structure, &mut self.primal, &step)?;
        Ok(Solved {
            r_bar: sol.r.clone(),
            r: sol.r,
            states: None,
            iterations: sol.iterations,
            adhesion_iterations: 0,
            residual: sol.residual,
            matrix_free: false,
            active_set: true,
            factorizations: self.primal.factorizations - before,
        })
    }
}
