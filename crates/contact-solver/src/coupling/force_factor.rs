//! The force factor of a step (`step(time, force_factor)`, 2D and 3D): it scales the
//! structure's applied forces only (point, edge or face tractions, body forces), through
//! [`Structure::free_response_into`]; prescribed displacements and initial stresses enter at
//! their current values whatever the factor. Prescribed values move with time through the
//! structure (`structure_mut()` between steps), as `bipo`'s time tables do.
//!
//! A factor other than 1 that changes nothing is the trap of issue 36 (a user ramped the factor
//! of a displacement-driven 3D run and got four identical steps): it is refused.

use crate::error::SolverError;
use fem_core::Structure;

/// The check of `step`'s force factor, kept by a simulation: a `force_factor` other than 1
/// under which the free response `u_free` is the one at factor 1 (to `1e-12` of its size) is
/// refused, the structure having no applied force for the factor to scale. The check costs one
/// extra structure solve; once a step has shown applied forces it is not repeated (a ramp of
/// forces pays it once per simulation, not once per step).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct ForceFactorCheck {
    /// A step with a factor other than 1 has shown the structure's applied forces.
    forces_seen: bool,
}

impl ForceFactorCheck {
    /// Checks `force_factor` against the step's free response `u_free` (module docs).
    ///
    /// # Errors
    /// [`SolverError::InvalidSetting`] naming `force_factor`; the structure's solve errors.
    pub(crate) fn check<S: Structure<D> + ?Sized, const D: usize>(
        &mut self,
        structure: &S,
        force_factor: f64,
        u_free: &[f64],
    ) -> Result<(), SolverError> {
        if force_factor == 1.0 || self.forces_seen {
            return Ok(());
        }
        let mut at_one = vec![0.0; u_free.len()];
        structure.free_response_into(1.0, &mut at_one)?;
        let mut same = same_to_round_off(u_free, &at_one);
        // a floating structure: the load along its rigid-body modes scales too
        if let Some(floating) = structure.floating() {
            let count = floating.rigid_body_modes().len();
            let (mut here, mut one) = (vec![0.0; count], vec![0.0; count]);
            floating.rigid_body_load_into(force_factor, &mut here)?;
            floating.rigid_body_load_into(1.0, &mut one)?;
            same &= same_to_round_off(&here, &one);
        }
        if same {
            return Err(SolverError::InvalidSetting {
                what: "force_factor",
                value: force_factor,
                expected: "1 for a structure without applied forces: the factor of `step` \
                           scales the applied forces only (not prescribed displacements or \
                           initial stresses), and this structure has none, so the step would \
                           be the one at factor 1; change prescribed displacements between \
                           steps with `structure_mut()` instead",
            });
        }
        self.forces_seen = true;
        Ok(())
    }
}

/// Whether `a` and `b` agree to `1e-12` of their largest entry: two solves that differ by the
/// forces' share alone differ by far more, and the round-off of one solve is ~1e-15 of it.
fn same_to_round_off(a: &[f64], b: &[f64]) -> bool {
    let size = a.iter().chain(b).fold(0.0_f64, |m, v| m.max(v.abs()));
    a.iter().zip(b).all(|(x, y)| (x - y).abs() <= 1e-12 * size)
}
