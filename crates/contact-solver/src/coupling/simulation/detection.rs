//! Stage 1, detection: the step's inputs checked, the free response `u_free` of the structure
//! to the loads, the active set (candidates within their alert distance at the start of the
//! step or under `u_free`, plus every adhesive one), and after the solve the inactive
//! candidates that penetrate.

use super::ContactSimulation;
use crate::coupling::space::ContactSpace;
use crate::error::SolverError;
use contact_laws::ContactLaw;
use fem_core::{Dim, Structure};

impl<S: Structure<D>, L: ContactLaw + Clone, const D: usize> ContactSimulation<S, L, D>
where
    Dim<D>: ContactSpace<D>,
{
    /// Checks `time` and `force_factor` and counts a change of the stiffness; returns the
    /// stiffness version of the step.
    pub(super) fn begin_step(&mut self, time: f64, force_factor: f64) -> Result<u64, SolverError> {
        if !(time.is_finite() && time >= self.time) {
            return Err(SolverError::InvalidSetting {
                what: "time",
                value: time,
                expected: "a finite time not before the current time",
            });
        }
        if !force_factor.is_finite() {
            return Err(SolverError::InvalidSetting {
                what: "force_factor",
                value: force_factor,
                expected: "a finite number",
            });
        }
        self.follow_numbering()?;
        let version = self.structure.stiffness_version();
        if version != self.last_version {
            self.counters.stiffness_changes += 1;
            self.last_version = version;
        }
        Ok(version)
    }

    /// `u_free`, the response to the applied forces scaled by `force_factor` (prescribed
    /// displacements at their values) without contact, and the
    /// candidates' local jumps under it.
    pub(super) fn free_response(
        &mut self,
        force_factor: f64,
    ) -> Result<(Vec<f64>, Vec<[f64; D]>), SolverError> {
        let mut u_free = vec![0.0; self.structure.dof_count()];
        self.structure
            .free_response_into(force_factor, &mut u_free)?;
        self.counters.structure_solves += 1;
        // a floating structure: u_free = K⁺ f plus the rigid motion of the last step, and the
        // load along the modes that contact must balance
        let count = self
            .structure
            .floating()
            .map_or(0, |f| f.rigid_body_modes().len());
        if self.alpha.len() != count {
            self.alpha = vec![0.0; count];
        }
        self.mode_load.resize(count, 0.0);
        if let Some(floating) = self.structure.floating() {
            let modes = floating.rigid_body_modes();
            floating.rigid_body_load_into(force_factor, &mut self.mode_load)?;
            for (j, &a) in self.alpha.iter().enumerate() {
                if a != 0.0 {
                    for (u, r) in u_free.iter_mut().zip(modes.column(j)) {
                        *u += a * r;
                    }
                }
            }
        }
        let free = self.local_jumps_of(&u_free);
        Ok((u_free, free))
    }

    /// The candidates of the reduced problem: within the alert distance at the start of the
    /// step or under the free response (`free`), or adhesive; all of them without the
    /// alert-distance skip rule.
    pub(super) fn initial_active_set(&self, free: &[[f64; D]]) -> Vec<usize> {
        let all = !self.settings.tuning.skip.alert_distance;
        (0..self.candidates.len())
            .filter(|&i| {
                let c = &self.candidates[i];
                let zone = &self.zones[c.zone];
                all || zone.law.adhesion_active(&self.states[i])
                    || self.jumps[i][0] <= zone.alert_distance
                    || free[i][0] <= zone.alert_distance
            })
            .collect()
    }

    /// The candidates outside the solved active set whose gap under `jumps` is below
    /// `−penetration_tol` ([`ContactSpace::PENETRATION_TOL`]: 0 in 2D).
    pub(super) fn penetrating(&self, jumps: &[[f64; D]]) -> Vec<usize> {
        (0..self.candidates.len())
            .filter(|i| {
                self.w_active.binary_search(i).is_err() && jumps[*i][0] < -self.penetration_tol
            })
            .collect()
    }
}
