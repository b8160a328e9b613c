//! Stage 2, the dense operator: `F* = H K⁻¹ Hᵀ` on the active set, built with chunks of
//! right-hand sides of the factorised structure, and the base penalties `ρ⁰` of the
//! matrix-free path from a few exact diagonal blocks.

use super::ContactSimulation;
use crate::coupling::flexibility::{
    flexibility_into, from_nearest_sample, sampled_diagonal_blocks,
};
use crate::error::SolverError;
use crate::local::symmetrize;
use contact_laws::ContactLaw;
use fem_core::Structure;

/// Contacts whose diagonal block of `F*` is computed exactly to set `ρ⁰` in matrix-free steps.
const RHO_SAMPLES: usize = 16;

impl<S: Structure, L: ContactLaw + Clone> ContactSimulation<S, L> {
    /// `F* = H K⁻¹ Hᵀ` on `active`, in chunks of right-hand sides.
    pub(super) fn build_flexibility(&mut self, active: &[usize]) -> Result<(), SolverError> {
        let m = 2 * active.len();
        self.w.clear();
        self.w.resize(m * m, 0.0);
        // local rows of W (index into 0..m) whose columns are solved for
        let solved: Vec<usize> = (0..m)
            .filter(|&j| j % 2 == 0 || self.tangent_needed(active[j / 2]))
            .collect();
        let rows: Vec<usize> = active.iter().flat_map(|&i| [2 * i, 2 * i + 1]).collect();
        flexibility_into(
            &self.structure,
            &self.h_rows,
            &rows,
            &solved,
            self.settings.columns_per_solve,
            &mut self.w,
        )?;
        symmetrize(&mut self.w, m);
        // decoupled tangential unknowns of frictionless contacts: W_tt = W_nn, nothing else
        for (k, &i) in active.iter().enumerate() {
            if !self.tangent_needed(i) {
                self.w[(2 * k + 1) * m + 2 * k + 1] = self.w[2 * k * m + 2 * k];
            }
        }
        self.w_active.clear();
        self.w_active.extend_from_slice(active);
        self.counters.flexibility_builds += 1;
        self.counters.flexibility_columns += solved.len();
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
