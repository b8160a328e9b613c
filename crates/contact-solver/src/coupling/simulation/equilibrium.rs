//! Stage 4, equilibrium and report: `u = u_free + K⁻¹ Hᵀ r` (one back-substitution), the jumps
//! of every candidate, and, once no inactive candidate penetrates, the accepted state and the
//! [`StepResult`].

use super::ContactSimulation;
use super::report::{ContactRecord, InterfaceStatus, StepReport, StepResult};
use super::solve::Solved;
use crate::coupling::space::ContactSpace;
use crate::error::SolverError;
use contact_laws::{ContactLaw, ContactStatus};
use fem_core::{Dim, Structure};
use std::time::Instant;

impl<S: Structure<D>, L: ContactLaw + Clone, const D: usize> ContactSimulation<S, L, D>
where
    Dim<D>: ContactSpace<D>,
{
    /// `u = u_free + K⁻¹ Hᵀ r` and the local jumps of every candidate under it (the active
    /// contacts keep the reduced solution's own jumps).
    pub(super) fn equilibrium(
        &mut self,
        u_free: &[f64],
        solved: &Solved<L::State>,
    ) -> Result<(Vec<f64>, Vec<[f64; D]>), SolverError> {
        let mut u = vec![0.0; self.structure.dof_count()];
        for (k, &i) in self.w_active.iter().enumerate() {
            for d in 0..D {
                let r = solved.r[D * k + d];
                for &(dof, a) in &self.h_rows[D * i + d] {
                    u[dof] += a * r;
                }
            }
        }
        self.structure.solve_in_place(&mut u)?;
        self.counters.structure_solves += 1;
        for (a, b) in u.iter_mut().zip(u_free) {
            *a += b;
        }
        // a floating structure's rigid motion of the step, R Δα
        if let Some(modes) = self.structure.floating().map(|f| f.rigid_body_modes()) {
            for (j, &a) in solved.alpha.iter().enumerate() {
                for (u, r) in u.iter_mut().zip(modes.column(j)) {
                    *u += a * r;
                }
            }
        }
        let mut jumps = self.local_jumps_of(&u);
        // active contacts: the reduced solution's own jumps. Recomputing them from `u` adds
        // the rounding of `u` (an ulp of the load) times the stiffness contrast, which is
        // large for stiff glue (C h / E ≫ 1); the next step starts from these jumps.
        for (k, &i) in self.w_active.iter().enumerate() {
            jumps[i][0] = solved.x[D * k];
            let (start, x) = (self.jumps[i], &solved.x[D * k..D * (k + 1)]);
            for (d, jump) in jumps[i].iter_mut().enumerate().skip(1) {
                if self.tangent_solved(i, d) {
                    *jump = start[d] + x[d];
                }
            }
        }
        Ok((u, jumps))
    }

    pub(super) fn accept(
        &mut self,
        time: f64,
        u: Vec<f64>,
        jumps: Vec<[f64; D]>,
        solved: Solved<L::State>,
        mut report: StepReport,
        start: Instant,
    ) -> StepResult<D> {
        let zero = <Dim<D> as ContactSpace<D>>::local_of(&[0.0; D]);
        let mut records: Vec<ContactRecord<D>> = self
            .candidates
            .iter()
            .enumerate()
            .map(|(i, c)| ContactRecord {
                zone: c.zone,
                node: c.node,
                position: self.structure.node_position(c.node),
                area: c.area,
                status: InterfaceStatus::Inactive,
                gap: jumps[i][0],
                u_t: <Dim<D> as ContactSpace<D>>::tangential_of(&jumps[i]),
                slip_increment: <Dim<D> as ContactSpace<D>>::tangential_of(
                    &core::array::from_fn::<f64, D, _>(|d| jumps[i][d] - self.jumps[i][d]),
                ),
                beta: self.zones[c.zone].law.adhesion_intensity(&self.states[i]),
                normal: c.normal(),
                tangent: <Dim<D> as ContactSpace<D>>::tangents_of(c.frame()),
                r: zero,
                r_bar: zero,
                r_adh: zero,
            })
            .collect();
        for r in self.r_bar.iter_mut() {
            *r = [0.0; D];
        }
        for (k, &i) in self.w_active.iter().enumerate() {
            let law = &self.zones[self.candidates[i].zone].law;
            self.states[i] = solved.states[k];
            let rb: [f64; D] = core::array::from_fn(|d| solved.r_bar[D * k + d]);
            let r: [f64; D] = core::array::from_fn(|d| solved.r[D * k + d]);
            self.r_bar[i] = rb;
            let rec = &mut records[i];
            rec.beta = law.adhesion_intensity(&self.states[i]);
            rec.r_bar = <Dim<D> as ContactSpace<D>>::local_of(&rb);
            rec.r = <Dim<D> as ContactSpace<D>>::local_of(&r);
            rec.r_adh =
                <Dim<D> as ContactSpace<D>>::local_of(&core::array::from_fn::<f64, D, _>(|d| {
                    r[d] - rb[d]
                }));
            // named by what the law is: a frictionless law's closed contact neither sticks
            // nor slips
            rec.status = match solved.statuses[k] {
                ContactStatus::Separation => InterfaceStatus::Open,
                _ if !law.has_friction() => InterfaceStatus::Closed,
                ContactStatus::Stick => InterfaceStatus::Stick,
                ContactStatus::Slip => InterfaceStatus::Slip,
            };
        }
        for (a, d) in self.alpha.iter_mut().zip(&solved.alpha) {
            *a += d;
        }
        self.counters.equilibrium_iterations += report.equilibrium_iterations;
        self.counters.equilibrium_solves += report.equilibrium_solves;
        self.jumps = jumps;
        self.nodal_u = self.nodal_of(&u);
        self.u = u;
        self.time = time;
        self.counters.steps += 1;
        self.counters.adhesion_iterations += report.adhesion_iterations;
        self.counters.contact_iterations += report.contact_iterations;
        report.active_contacts = self.w_active.len();
        report.closed_contacts = records.iter().filter(|r| r.status.is_closed()).count();
        report.wall_time = start.elapsed();
        StepResult {
            report,
            contacts: records,
        }
    }
}
