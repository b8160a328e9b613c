//! [`MoreauJean`]'s side of the [`TimeScheme`] seam: the free response, the right-hand side
//! `q`, the jumps, the index set, the adhesive springs at velocity level and the acceptance
//! of a step (the scheme's math: the parent module's docs).

use super::AdhesionUpdate;
use super::{ContactVelocities, MoreauJean};
use crate::coupling::simulation::energy::{ContactTerms, EnergyBalance, StepFields};
use crate::coupling::simulation::scheme::{
    AcceptedContact, SchemeStep, TimeScheme, VelocitySprings,
};
use crate::coupling::zone::Candidate;
use crate::error::SolverError;
use fem_core::dynamic::DynamicModel;
use fem_core::model::ModelSpace;
use fem_core::{Dim, FemError, Structure};
use std::borrow::Cow;

fn length(what: &'static str, expected: usize, got: usize) -> Result<(), SolverError> {
    if expected == got {
        Ok(())
    } else {
        Err(FemError::LengthMismatch {
            what,
            expected,
            got,
        }
        .into())
    }
}

impl<const D: usize> TimeScheme<DynamicModel<D>, D> for MoreauJean
where
    Dim<D>: ModelSpace<D>,
{
    /// `v_free = v_k + M̂⁻¹ h (f_θ − C v_k − K (u_k + hθ v_k))` (module docs).
    fn free_response(
        &mut self,
        structure: &DynamicModel<D>,
        step: &SchemeStep<'_>,
        free: &mut [f64],
    ) -> Result<(), SolverError> {
        let Some((h, theta)) = structure.step() else {
            return Err(FemError::InvalidParameter {
                name: "h",
                value: step.dt,
                expected: "a step set on the structure: `ContactSimulation::advance` sets it",
            }
            .into());
        };
        if (step.dt - h).abs() > 1e-9 * h {
            return Err(SolverError::InvalidSetting {
                what: "dt",
                value: step.dt,
                expected: "the step `h` the structure's M̂ is factorised for \
                           (`ContactSimulation::advance` sets both)",
            });
        }
        if theta != self.theta {
            return Err(SolverError::InvalidSetting {
                what: "theta",
                value: theta,
                expected: "the scheme's θ in the structure's M̂ (`advance` sets both)",
            });
        }
        let n = structure.dof_count();
        if self.velocity.is_empty() {
            self.velocity = vec![0.0; n];
        }
        length("velocity", n, self.velocity.len())?;
        self.u_start = match &self.initial_displacement {
            Some(u0) => u0.clone(),
            None => step.displacement.to_vec(),
        };
        length("displacement", n, self.u_start.len())?;
        self.h = h;
        let lambda = (1.0 - theta) * self.force_factor.unwrap_or(step.force_factor)
            + theta * step.force_factor;
        self.load.resize(n, 0.0);
        structure.load_into(lambda, &mut self.load)?;
        // h (f_θ − C v_k − K (u_k + hθ v_k))
        let predictor: Vec<f64> = self
            .u_start
            .iter()
            .zip(&self.velocity)
            .map(|(u, v)| u + h * theta * v)
            .collect();
        let (mut kx, mut cv) = (vec![0.0; n], vec![0.0; n]);
        structure.stiffness_mul_into(&predictor, &mut kx);
        structure.damping_mul_into(&self.velocity, &mut cv);
        for (((y, f), c), k) in free.iter_mut().zip(&self.load).zip(&cv).zip(&kx) {
            *y = h * (f - c - k);
        }
        structure.solve_in_place(free)?;
        for (f, v) in free.iter_mut().zip(&self.velocity) {
            *f += v;
        }
        self.v_free.clear();
        self.v_free.extend_from_slice(free);
        self.node_dofs = (0..structure.node_count())
            .flat_map(|node| structure.node_dofs(node))
            .collect();
        Ok(())
    }

    /// Keeps the candidate's relative velocities and returns the jump predicted at
    /// `u_k + h(1−θ) v_k`: `[g_k + h(1−θ) v_n,k, u_t,k + h(1−θ) v_t,k]`.
    fn free_jump(
        &mut self,
        index: usize,
        candidate: &Candidate<D>,
        _u_rel: [f64; D],
        start: &[f64; D],
    ) -> [f64; D] {
        if self.contacts.len() <= index {
            self.contacts
                .resize(index + 1, ContactVelocities::default());
        }
        let shift = match &self.initial_displacement {
            Some(u0) => self.local_of(candidate, u0),
            None => [0.0; 3],
        };
        let e = self
            .zone_restitution
            .get(candidate.zone)
            .copied()
            .flatten()
            .unwrap_or(self.restitution);
        let contact = ContactVelocities {
            v_k: self.local_of(candidate, &self.velocity),
            v_free: self.local_of(candidate, &self.v_free),
            shift,
            e,
        };
        self.contacts[index] = contact;
        let weight = self.h * (1.0 - self.theta);
        core::array::from_fn(|d| start[d] + contact.shift[d] + weight * contact.v_k[d])
    }

    /// `[v_free,n + e v_n,k, v_free,t…]`.
    fn rhs(&self, index: usize, _free: &[f64; D], _start: &[f64; D]) -> [f64; D] {
        let c = &self.contacts[index];
        core::array::from_fn(|d| {
            if d == 0 {
                c.v_free[0] + c.e * c.v_k[0]
            } else {
                c.v_free[d]
            }
        })
    }

    /// `u = u_k + h((1−θ) v_k + θ v)`.
    fn displacement<'y>(&self, _step: &SchemeStep<'_>, solution: &'y [f64]) -> Cow<'y, [f64]> {
        let (h, theta) = (self.h, self.theta);
        Cow::Owned(
            self.u_start
                .iter()
                .zip(&self.velocity)
                .zip(solution)
                .map(|((u, v_k), v)| u + h * ((1.0 - theta) * v_k + theta * v))
                .collect(),
        )
    }

    /// `v_n = x_n − e v_n,k`, `v_t = x_t`, and the jump `start + h((1−θ) v_k + θ v)`.
    fn jump(&self, index: usize, x: &[f64; D], start: &[f64; D]) -> [f64; D] {
        let c = &self.contacts[index];
        let (h, theta) = (self.h, self.theta);
        core::array::from_fn(|d| {
            let v = if d == 0 { x[0] - c.e * c.v_k[0] } else { x[d] };
            start[d] + c.shift[d] + h * ((1.0 - theta) * c.v_k[d] + theta * v)
        })
    }

    /// Keeps `v`, and adds the step's terms to the energy balance.
    fn accept(
        &mut self,
        structure: &DynamicModel<D>,
        step: &SchemeStep<'_>,
        solution: &[f64],
        displacement: &[f64],
    ) {
        let contacts = std::mem::take(&mut self.step_contacts);
        if self.accepted_steps == 0 {
            self.energy =
                EnergyBalance::initial(structure, &self.u_start, &self.velocity, &contacts);
        }
        self.energy.add_step(
            structure,
            StepFields {
                h: self.h,
                theta: self.theta,
                u_k: &self.u_start,
                u: displacement,
                v_k: &self.velocity,
                v: solution,
                v_free: &self.v_free,
                load: &self.load,
                contacts,
            },
        );
        self.history.push(self.energy);
        self.velocity.clear();
        self.velocity.extend_from_slice(solution);
        self.initial_displacement = None;
        self.force_factor = Some(step.force_factor);
        self.accepted_steps += 1;
    }

    /// Moreau's index set: the gap predicted at `u_k + h(1−θ) v_k` is closed (`≤ 0`); the
    /// alert distance and the skip rule do not widen it.
    fn enters(
        &self,
        _index: usize,
        _start: &[f64; D],
        free: &[f64; D],
        _alert_distance: f64,
        _all: bool,
    ) -> bool {
        free[0] <= 0.0
    }

    /// Never: the index set is the start of the step's (module docs).
    fn penetrates(&self, _index: usize, _jump: &[f64; D], _tolerance: f64) -> bool {
        false
    }

    /// The springs' impulse at `u_θ`: scale `h²θ²`, offset
    /// `(u_k + hθ(1−θ) v_k − hθ² e v_n,k n) / (hθ²)`; constrained in Moreau's index set
    /// (module docs).
    fn velocity_springs(&self, index: usize, start: &[f64; D]) -> Option<VelocitySprings<D>> {
        let c = &self.contacts[index];
        let (h, theta) = (self.h, self.theta);
        let slope = h * theta * theta;
        let offset = core::array::from_fn(|d| {
            let u_k = start[d] + c.shift[d];
            let restitution = if d == 0 { slope * c.e * c.v_k[0] } else { 0.0 };
            (u_k + h * theta * (1.0 - theta) * c.v_k[d] - restitution) / slope
        });
        let free_gap = start[0] + c.shift[0] + h * (1.0 - theta) * c.v_k[0];
        let implicit = self.adhesion == AdhesionUpdate::Implicit;
        Some(VelocitySprings::new(
            h * slope,
            offset,
            free_gap <= 0.0,
            implicit,
        ))
    }

    /// Keeps the contacts' impact, friction and damage terms for [`accept`](Self::accept).
    fn accept_contacts(&mut self, contacts: &[AcceptedContact<D>]) {
        let mut terms = ContactTerms::default();
        for a in contacts {
            let shift = self.contacts[a.index].shift;
            let start: [f64; D] = core::array::from_fn(|d| a.start[d] + shift[d]);
            terms.add(
                &a.r_bar,
                &start,
                &a.jump,
                a.springs_start,
                a.springs_end,
                self.adhesion == AdhesionUpdate::Implicit,
                self.h,
                self.theta,
            );
        }
        self.step_contacts = terms;
    }
}
