//! Stage 1, detection: the step's inputs checked, the structure's renumbering followed, the
//! free response (the [`TimeScheme`]'s) and the jumps it predicts, the active set (candidates
//! within their alert distance at the start of the step or under the free response, plus every
//! adhesive one), and after the solve the inactive candidates that penetrate.

use super::parts::{Accepted, Interface, nodal};
use super::scheme::{SchemeStep, TimeScheme};
use super::settings::SimulationSettings;
use super::{Clock, ContactSimulation};
use crate::coupling::space::ContactSpace;
use crate::error::SolverError;
use contact_laws::ContactLaw;
use fem_core::{Dim, Structure};

/// The free response of a step: what the scheme predicts without contact.
pub(super) struct FreeResponse<const D: usize> {
    /// `y_free` on the free dofs, in the scheme's unknown (the displacement `u_free` when
    /// quasi-static).
    pub(super) y: Vec<f64>,
    /// Per candidate, the jump `[gap, u_t…]` it predicts ([`TimeScheme::free_jump`]).
    pub(super) jumps: Vec<[f64; D]>,
    /// Floating structures: the load along every mode at the step's force factor, `Rᵀ f`
    /// (empty otherwise).
    pub(super) mode_load: Vec<f64>,
}

/// Checks the step's `time` (not before `now`, the time of the last step) and `force_factor`.
///
/// # Errors
/// [`SolverError::InvalidSetting`] naming `time` or `force_factor`.
pub(super) fn check_step(time: f64, force_factor: f64, now: f64) -> Result<(), SolverError> {
    if !(time.is_finite() && time >= now) {
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
    Ok(())
}

impl<S: Structure<D>, L: ContactLaw + Clone, const D: usize, T: TimeScheme<S, D>>
    ContactSimulation<S, L, D, T>
where
    Dim<D>: ContactSpace<D>,
{
    /// Follows a renumbering of the structure's dofs ([`Interface::follow_numbering`]) with
    /// `u` and the cached operators, counting the change. Returns the step's stiffness version.
    pub(super) fn follow_structure(&mut self) -> Result<u64, SolverError> {
        if self.interface.follow_numbering(&self.structure)? {
            self.accepted.renumber(&self.structure);
            self.cache.invalidate();
            self.counters.stiffness_changes += 1;
        }
        Ok(self.interface.rows_version)
    }

    /// The scheme's free response at `clock` ([`TimeScheme::free_response`], one structure
    /// solve), the load along a floating structure's modes, and the jumps the response
    /// predicts for every candidate ([`TimeScheme::free_jump`]).
    pub(super) fn free_response(&mut self, clock: Clock) -> Result<FreeResponse<D>, SolverError> {
        let mut y = vec![0.0; self.structure.dof_count()];
        // a floating structure: its modes' amplitudes (reset when their number changed)
        let count = self
            .structure
            .floating()
            .map_or(0, |f| f.rigid_body_modes().len());
        let reset = self.accepted.alpha.len() != count;
        let fresh = if reset { vec![0.0; count] } else { Vec::new() };
        let alpha = if reset { &fresh } else { &self.accepted.alpha };
        let step = SchemeStep::new(
            clock.time,
            clock.dt,
            clock.force_factor,
            &self.accepted.u,
            alpha,
        );
        self.scheme.free_response(&self.structure, &step, &mut y)?;
        self.counters.structure_solves += 1;
        if reset {
            self.accepted.alpha = fresh;
        }
        let mut mode_load = vec![0.0; count];
        if let Some(floating) = self.structure.floating() {
            floating.rigid_body_load_into(clock.force_factor, &mut mode_load)?;
        }
        Ok(self.free_of(y, mode_load))
    }

    /// The free response `y` (with the load `mode_load` along a floating structure's modes)
    /// and the jumps it predicts for every candidate ([`TimeScheme::free_jump`]).
    pub(super) fn free_of(&mut self, y: Vec<f64>, mode_load: Vec<f64>) -> FreeResponse<D> {
        let jumps = self
            .interface
            .candidates
            .iter()
            .enumerate()
            .map(|(i, c)| {
                let u_rel = c.relative(|n| nodal(&self.structure, &y, n));
                self.scheme.free_jump(i, c, u_rel, &self.accepted.jumps[i])
            })
            .collect();
        FreeResponse {
            y,
            jumps,
            mode_load,
        }
    }
}

impl<L: ContactLaw, const D: usize> Interface<L, D>
where
    Dim<D>: ContactSpace<D>,
{
    /// The candidates of the reduced problem: within the alert distance at the start of the
    /// step (`accepted`) or under the free response (`free`), or adhesive; all of them without
    /// the alert-distance skip rule.
    pub(super) fn initial_active_set(
        &self,
        settings: &SimulationSettings,
        accepted: &Accepted<L::State, D>,
        free: &[[f64; D]],
        enters: impl Fn(usize, &[f64; D], &[f64; D], f64, bool) -> bool,
    ) -> Vec<usize> {
        let all = !settings.tuning.skip.alert_distance;
        (0..self.candidates.len())
            .filter(|&i| {
                let c = &self.candidates[i];
                let zone = &self.zones[c.zone];
                zone.law.adhesion_active(&accepted.states[i])
                    || enters(i, &accepted.jumps[i], &free[i], zone.alert_distance, all)
            })
            .collect()
    }

    /// The candidates outside the solved active set `active` (sorted) that penetrate under
    /// `jumps` as the scheme's `penetrates` says ([`TimeScheme::penetrates`], quasi-static: a
    /// gap below `−penetration_tol`, [`ContactSpace::PENETRATION_TOL`]: 0 in 2D).
    pub(super) fn penetrating(
        &self,
        active: &[usize],
        jumps: &[[f64; D]],
        penetrates: impl Fn(usize, &[f64; D], f64) -> bool,
    ) -> Vec<usize> {
        (0..self.candidates.len())
            .filter(|&i| {
                active.binary_search(&i).is_err() && penetrates(i, &jumps[i], self.penetration_tol)
            })
            .collect()
    }

    /// The error of a step whose `penetrating` candidates still penetrate after `passes`
    /// passes: it names the deepest one.
    pub(super) fn still_penetrating(
        &self,
        penetrating: &[usize],
        jumps: &[[f64; D]],
        passes: usize,
    ) -> SolverError {
        let deepest = penetrating
            .iter()
            .copied()
            .min_by(|&a, &b| jumps[a][0].total_cmp(&jumps[b][0]))
            .unwrap_or(penetrating[0]);
        let c = &self.candidates[deepest];
        SolverError::StillPenetrating {
            passes,
            count: penetrating.len(),
            zone: self.zones[c.zone].name.clone(),
            node: c.node,
            gap: jumps[deepest][0],
            setting: "max_detection_passes",
        }
    }
}
