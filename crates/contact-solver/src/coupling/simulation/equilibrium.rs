//! Stage 4, equilibrium and report: `u = u_free + K⁻¹ Hᵀ r` (one back-substitution), the jumps
//! of every candidate, and, once no inactive candidate penetrates, the accepted state and the
//! [`StepResult`].

use super::detection::FreeResponse;
use super::parts::nodal;
use super::report::{ContactRecord, InterfaceStatus, StepReport, StepResult};
use super::scheme::{AcceptedContact, TimeScheme};
use super::solve::Solved;
use super::{Clock, ContactSimulation};
use crate::coupling::space::ContactSpace;
use crate::error::SolverError;
use contact_laws::{ContactLaw, ContactStatus};
use fem_core::{Dim, Structure};
use std::borrow::Cow;
use std::time::Instant;

/// What the equilibrium of a pass produces.
pub(super) struct Equilibrium<const D: usize> {
    /// `y = y_free + A⁻¹ Hᵀ r` (`+ R Δα`), the step's solution in the scheme's unknown.
    pub(super) solution: Vec<f64>,
    /// The displacement it stands for ([`TimeScheme::displacement`]) when it is not
    /// `solution` itself.
    displacement: Option<Vec<f64>>,
    /// Every candidate's jump `[gap, u_t…]` at the end of the step.
    pub(super) jumps: Vec<[f64; D]>,
}

impl<const D: usize> Equilibrium<D> {
    /// The displacement at the end of the step.
    pub(super) fn displacement(&self) -> &[f64] {
        self.displacement.as_deref().unwrap_or(&self.solution)
    }
}

impl<S: Structure<D>, L: ContactLaw + Clone, const D: usize, T: TimeScheme<S, D>>
    ContactSimulation<S, L, D, T>
where
    Dim<D>: ContactSpace<D>,
{
    /// `y = y_free + K⁻¹ Hᵀ r` from the pass's `solved` reactions (one back-substitution), the
    /// displacement the scheme reads in it, and the local jumps of every candidate under that
    /// displacement (the active contacts keep the reduced solution's own jumps,
    /// [`TimeScheme::jump`]).
    pub(super) fn equilibrium(
        &mut self,
        clock: Clock,
        free: &FreeResponse<D>,
        solved: &Solved<L::State>,
    ) -> Result<Equilibrium<D>, SolverError> {
        let mut y = vec![0.0; self.structure.dof_count()];
        for (k, &i) in solved.active.iter().enumerate() {
            for d in 0..D {
                let r = solved.r[D * k + d];
                for &(dof, a) in &self.interface.h_rows[D * i + d] {
                    y[dof] += a * r;
                }
            }
        }
        self.structure.solve_in_place(&mut y)?;
        self.counters.structure_solves += 1;
        for (a, b) in y.iter_mut().zip(&free.y) {
            *a += b;
        }
        // a floating structure's rigid motion of the step, R Δα
        if let Some(modes) = self.structure.floating().map(|f| f.rigid_body_modes()) {
            for (j, &a) in solved.alpha.iter().enumerate() {
                for (u, r) in y.iter_mut().zip(modes.column(j)) {
                    *u += a * r;
                }
            }
        }
        let step = clock.scheme_step(&self.accepted);
        let displacement = match self.scheme.displacement(&step, &y) {
            Cow::Borrowed(_) => None,
            Cow::Owned(u) => Some(u),
        };
        let mut jumps = self
            .interface
            .local_jumps_of(&self.structure, displacement.as_deref().unwrap_or(&y));
        // active contacts: the reduced solution's own jumps. Recomputing them from `u` adds
        // the rounding of `u` (an ulp of the load) times the stiffness contrast, which is
        // large for stiff glue (C h / E ≫ 1); the next step starts from these jumps.
        for (k, &i) in solved.active.iter().enumerate() {
            let x: [f64; D] = core::array::from_fn(|d| solved.x[D * k + d]);
            let jump = self.scheme.jump(i, &x, &self.accepted.jumps[i]);
            jumps[i][0] = jump[0];
            for (d, value) in jumps[i].iter_mut().enumerate().skip(1) {
                if self.tangent_solved(i, d) {
                    *value = jump[d];
                }
            }
        }
        Ok(Equilibrium {
            solution: y,
            displacement,
            jumps,
        })
    }

    /// Accepts the pass (the scheme first, [`TimeScheme::accept`]): the carried state from
    /// the `equilibrium` and the `solved` reduced problem, the counters, and the step's result.
    pub(super) fn accept(
        &mut self,
        clock: Clock,
        equilibrium: Equilibrium<D>,
        solved: Solved<L::State>,
        mut report: StepReport,
        start: Instant,
    ) -> StepResult<D> {
        let contacts = self.accepted_contacts(&equilibrium.jumps, &solved);
        self.scheme.accept_contacts(&contacts);
        let step = clock.scheme_step(&self.accepted);
        self.scheme.accept(
            &self.structure,
            &step,
            &equilibrium.solution,
            equilibrium.displacement(),
        );
        let records = self.records(&equilibrium.jumps, &solved);
        let accepted = &mut self.accepted;
        for r in accepted.r_bar.iter_mut() {
            *r = [0.0; D];
        }
        for (k, &i) in solved.active.iter().enumerate() {
            accepted.states[i] = solved.states[k];
            accepted.r_bar[i] = core::array::from_fn(|d| solved.r_bar[D * k + d]);
        }
        for (a, d) in accepted.alpha.iter_mut().zip(&solved.alpha) {
            *a += d;
        }
        self.counters.equilibrium_iterations += report.equilibrium_iterations;
        self.counters.equilibrium_solves += report.equilibrium_solves;
        let Equilibrium {
            solution,
            displacement,
            jumps,
        } = equilibrium;
        accepted.jumps = jumps;
        let u = displacement.unwrap_or(solution);
        accepted.nodal_u = (0..self.structure.node_count())
            .map(|n| nodal(&self.structure, &u, n))
            .collect();
        accepted.u = u;
        accepted.time = clock.time;
        self.counters.steps += 1;
        self.counters.adhesion_iterations += report.adhesion_iterations;
        self.counters.contact_iterations += report.contact_iterations;
        report.active_contacts = solved.active.len();
        report.closed_contacts = records.iter().filter(|r| r.status.is_closed()).count();
        report.wall_time = start.elapsed();
        StepResult {
            report,
            contacts: records,
        }
    }

    /// What the scheme is told of each contact of the `solved` problem
    /// ([`TimeScheme::accept_contacts`]), with the step's `jumps`.
    fn accepted_contacts(
        &self,
        jumps: &[[f64; D]],
        solved: &Solved<L::State>,
    ) -> Vec<AcceptedContact<D>> {
        solved
            .active
            .iter()
            .enumerate()
            .map(|(k, &i)| {
                let law = self.interface.law(i);
                let area = self.interface.candidates[i].area;
                AcceptedContact {
                    index: i,
                    r: core::array::from_fn(|d| solved.r[D * k + d]),
                    r_bar: core::array::from_fn(|d| solved.r_bar[D * k + d]),
                    start: self.accepted.jumps[i],
                    jump: jumps[i],
                    springs_start: law
                        .adhesive_stiffness(&self.accepted.states[i])
                        .map(|v| v * area),
                    springs_end: law.adhesive_stiffness(&solved.states[k]).map(|v| v * area),
                }
            })
            .collect()
    }

    /// The records of every candidate at the end of the step, from the step's `jumps` and the
    /// `solved` reduced problem (before the accepted state is updated: the slip increment is
    /// taken from the last accepted jumps).
    fn records(&self, jumps: &[[f64; D]], solved: &Solved<L::State>) -> Vec<ContactRecord<D>> {
        let zero = <Dim<D> as ContactSpace<D>>::local_of(&[0.0; D]);
        let accepted = &self.accepted;
        let mut records: Vec<ContactRecord<D>> = self
            .interface
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
                    &core::array::from_fn::<f64, D, _>(|d| jumps[i][d] - accepted.jumps[i][d]),
                ),
                beta: self
                    .interface
                    .law(i)
                    .adhesion_intensity(&accepted.states[i]),
                normal: c.normal(),
                tangent: <Dim<D> as ContactSpace<D>>::tangents_of(c.frame()),
                r: zero,
                r_bar: zero,
                r_adh: zero,
            })
            .collect();
        for (k, &i) in solved.active.iter().enumerate() {
            let law = self.interface.law(i);
            let rb: [f64; D] = core::array::from_fn(|d| solved.r_bar[D * k + d]);
            let r: [f64; D] = core::array::from_fn(|d| solved.r[D * k + d]);
            let rec = &mut records[i];
            rec.beta = law.adhesion_intensity(&solved.states[k]);
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
        records
    }
}
