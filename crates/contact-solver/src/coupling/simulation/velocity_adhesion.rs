//! Stage 3 for adhesive laws under a velocity-level scheme ([`TimeScheme::velocity_springs`],
//! Moreau–Jean): the springs of the states at the start of the step condensed into the
//! reduced problem, one solve of the law on the contacts of the scheme's index set, and the
//! states updated once from the step's jumps.
//!
//! ```text
//! x = W (r̄ + r_adh) + q,     r_adh = −B (x + o),   B = s A k(β_k)       (per contact)
//! ⇒  x = W̃ r̄ + q̃              (W̃, q̃: the exact condensation, local::adhesion::condense)
//! r̄ ∈ the law's cone on the constrained contacts, r̄ = 0 on the others
//! β_{k+1} = the law's update from the jumps at the start and the end of the step
//! ```
//! Moreau–Jean's `s` and `o` make `r_adh` the impulse `h r_adh(u_θ)` of the springs at
//! `u_θ = (1−θ) u_k + θ u_{k+1}` (`moreau_jean.rs`). By default the springs are those of the
//! start states `β_k` and the states are updated once (they lag a step, an `O(h)` error);
//! [`VelocitySprings::implicit`] iterates them to the end states instead (the quasi-static
//! loop's plain fixed point, to [`SimulationSettings::adhesion_tol`](super::SimulationSettings)).

use super::ContactSimulation;
use super::report::StepReport;
use super::scheme::{TimeScheme, VelocitySprings};
use super::solve::Solved;
use crate::coupling::space::ContactSpace;
use crate::error::SolverError;
use crate::local::ReducedProblem;
use crate::local::adhesion::{condense, largest_state_change, states_from_jumps};
use contact_laws::{ContactLaw, ContactStatus};
use fem_core::{Dim, Structure};

impl<S: Structure<D>, L: ContactLaw + Clone, const D: usize, T: TimeScheme<S, D>>
    ContactSimulation<S, L, D, T>
where
    Dim<D>: ContactSpace<D>,
{
    /// The scheme's springs of every contact of `active`, when it gives them and some law of
    /// `active` is adhesive in its accepted state; `None` otherwise (the usual paths).
    pub(super) fn velocity_springs_of(&self, active: &[usize]) -> Option<Vec<VelocitySprings<D>>> {
        let mut adhesive = false;
        let mut springs = Vec::with_capacity(active.len());
        for &i in active {
            springs.push(self.scheme.velocity_springs(i, &self.accepted.jumps[i])?);
            let law = self.interface.law(i);
            adhesive |= law.has_adhesion() && law.adhesion_active(&self.accepted.states[i]);
        }
        adhesive.then_some(springs)
    }

    /// The adhesive step at velocity level on the dense `F*` of `active` (module docs).
    pub(super) fn solve_velocity_adhesive(
        &mut self,
        active: &[usize],
        free: &[[f64; D]],
        springs: &[VelocitySprings<D>],
        dt: f64,
        report: &mut StepReport,
    ) -> Result<Solved<L::State>, SolverError> {
        let laws = self.laws_of(active);
        let start_states = self.states_of(active);
        let u_start = self.jumps_of(active);
        let implicit = springs.iter().any(|v| v.implicit);
        let mut states = start_states.clone();
        let mut history = Vec::new();
        loop {
            let sol = self.velocity_pass(active, free, springs, &laws, &states, report)?;
            // the states the step's jumps imply, once
            let jumps: Vec<f64> = active
                .iter()
                .enumerate()
                .flat_map(|(k, &i)| {
                    let xk: [f64; D] = core::array::from_fn(|d| sol.x[D * k + d]);
                    self.scheme.jump(i, &xk, &u_start[k])
                })
                .collect();
            let implied = states_from_jumps(&laws, &start_states, &u_start, &jumps, dt);
            report.adhesion_iterations += 1;
            if !implicit {
                return Ok(Solved {
                    states: implied,
                    ..sol
                });
            }
            // the fixed point: the springs' states are the end states, to the tolerance
            let change = largest_state_change(&laws, &implied, &states);
            history.push(change);
            if change <= self.settings.adhesion_tol {
                return Ok(sol);
            }
            if history.len() >= self.settings.max_adhesion_iterations {
                if self.settings.solver.accept_non_converged {
                    report.converged = false;
                    return Ok(sol);
                }
                return Err(SolverError::AdhesionNotConverged {
                    iterations: history.len(),
                    change,
                    history,
                });
            }
            states = implied;
        }
    }

    /// One solve with the springs of `states`: `r̄` on the constrained contacts, `x` and the
    /// total `r` on all; `states` in the answer.
    fn velocity_pass(
        &mut self,
        active: &[usize],
        free: &[[f64; D]],
        springs: &[VelocitySprings<D>],
        laws: &[L],
        states: &[L::State],
        report: &mut StepReport,
    ) -> Result<Solved<L::State>, SolverError> {
        let m = D * active.len();
        let areas = self.areas_of(active);
        let q = self.q_of(active, free);
        let stiff: Vec<[f64; 2]> = laws
            .iter()
            .zip(states)
            .zip(areas.iter().zip(springs))
            .map(|((l, s), (a, v))| l.adhesive_stiffness(s).map(|k| v.scale * a * k))
            .collect();
        let offset: Vec<f64> = springs.iter().flat_map(|v| v.offset).collect();
        let (w, q) = condense(&self.cache.w, &q, &offset, &stiff, m)?;
        // the law's solve on the constrained contacts (rows `rows`), `r̄ = 0` elsewhere
        let on: Vec<usize> = (0..active.len())
            .filter(|&k| springs[k].constrained)
            .collect();
        let rows: Vec<usize> = on
            .iter()
            .flat_map(|&k| (0..D).map(move |d| D * k + d))
            .collect();
        let mut r_bar = vec![0.0; m];
        let mut statuses = vec![ContactStatus::Separation; active.len()];
        if !on.is_empty() {
            let w_on: Vec<f64> = rows
                .iter()
                .flat_map(|&i| rows.iter().map(move |&j| (i, j)))
                .map(|(i, j)| w[i * m + j])
                .collect();
            let q_on: Vec<f64> = rows.iter().map(|&i| q[i]).collect();
            let (laws_on, states_on): (Vec<L>, Vec<L::State>) =
                on.iter().map(|&k| (laws[k].clone(), states[k])).unzip();
            let mu = laws_on
                .iter()
                .zip(&states_on)
                .map(|(l, s)| l.friction_coefficient(s).unwrap_or(0.0))
                .collect();
            let problem = ReducedProblem::with_dimension(D, w_on, q_on, mu)?;
            let start: Vec<f64> = rows
                .iter()
                .map(|&i| self.accepted.r_bar[active[i / D]][i % D])
                .collect();
            let sol =
                self.solver
                    .solve_with_states(&problem, &laws_on, &states_on, Some(&start))?;
            report.contact_iterations += sol.report.iterations;
            report.residual = sol.report.residual;
            report.converged &= sol.report.converged;
            for (j, &i) in rows.iter().enumerate() {
                r_bar[i] = sol.r[j];
            }
            for (j, &k) in on.iter().enumerate() {
                statuses[k] = sol.report.statuses[j];
            }
        }
        // x = W̃ r̄ + q̃ on every contact, then r = r̄ − B (x + o)
        let x: Vec<f64> = (0..m)
            .map(|i| q[i] + rows.iter().map(|&j| w[i * m + j] * r_bar[j]).sum::<f64>())
            .collect();
        let r: Vec<f64> = (0..m)
            .map(|i| {
                let [kn, kt] = stiff[i / D];
                r_bar[i] - if i % D == 0 { kn } else { kt } * (x[i] + offset[i])
            })
            .collect();
        Ok(Solved {
            active: active.to_vec(),
            r,
            r_bar,
            x,
            statuses,
            states: states.to_vec(),
            alpha: Vec::new(),
        })
    }
}
