//! Stage 2, the dense operator: `F* = H K⁻¹ Hᵀ` on the active set, built with chunks of
//! right-hand sides of the factorised structure, and the base penalties `ρ⁰` of the
//! matrix-free path from a few exact diagonal blocks.

use super::ContactSimulation;
use crate::coupling::flexibility::{
    Previous, build_dense, from_nearest_sample, sampled_diagonal_blocks,
};
use crate::error::SolverError;
use contact_laws::ContactLaw;
use fem_core::Structure;

/// Contacts whose diagonal block of `F*` is computed exactly to set `ρ⁰` in matrix-free steps.
const RHO_SAMPLES: usize = 16;

impl<S: Structure, L: ContactLaw + Clone> ContactSimulation<S, L> {
    /// `F* = H K⁻¹ Hᵀ` on `active`, in chunks of right-hand sides. With `reuse` (the
    /// stiffness unchanged since the last build) only the columns of contacts the last active
    /// set did not have are solved.
    pub(super) fn build_flexibility(
        &mut self,
        active: &[usize],
        reuse: bool,
    ) -> Result<(), SolverError> {
        let m = 2 * active.len();
        let old = std::mem::take(&mut self.w);
        let previous = reuse.then_some(Previous {
            w: &old,
            active: &self.w_active,
        });
        // the columns solved: normals, and tangents where a law needs them
        let (w, columns) = build_dense(
            &self.structure,
            &self.h_rows,
            active,
            |j| j % 2 == 0 || self.tangent_needed(active[j / 2]),
            previous,
            self.settings.columns_per_solve,
        )?;
        self.w = w;
        // decoupled tangential unknowns of frictionless contacts: W_tt = W_nn, nothing else
        for (k, &i) in active.iter().enumerate() {
            if !self.tangent_needed(i) {
                self.w[(2 * k + 1) * m + 2 * k + 1] = self.w[2 * k * m + 2 * k];
            }
        }
        self.w_active.clear();
        self.w_active.extend_from_slice(active);
        self.counters.flexibility_builds += 1;
        self.counters.flexibility_columns += columns;
        Ok(())
    }

    /// `ρ⁰_i = 1/λ_max` of the diagonal blocks of `F*`, computed exactly on up to
    /// [`RHO_SAMPLES`] contacts spread over the active list and carried to the others from the
    /// nearest sample in that order (interfaces are listed in order along them).
    pub(super) fn estimate_rho0(&mut self, active: &[usize]) -> Result<Vec<f64>, SolverError> {
        let (samples, blocks) =
            sampled_diagonal_blocks(&self.structure, &self.h_rows, active, 2, RHO_SAMPLES)?;
        self.counters.flexibility_columns += 2 * samples.len();
        let rho: Vec<f64> = blocks
            .iter()
            .map(|w| {
                let (a, b, d) = (w[0], 0.5 * (w[1] + w[2]), w[3]);
                let h = 0.5 * (a - d);
                1.0 / (0.5 * (a + d) + (h * h + b * b).sqrt())
            })
            .collect();
        Ok(from_nearest_sample(&samples, &rho, active.len()))
    }
}
