//! Stage 2, the dense operator: `F* = H K⁻¹ Hᵀ` on the active set, built with chunks of
//! right-hand sides of the factorised structure, and the base penalties `ρ⁰` of the
//! matrix-free path from a few exact diagonal blocks.

use super::ContactSimulation;
use super::dispatch;
use super::scheme::TimeScheme;
use crate::coupling::flexibility::{
    Previous, build_dense, from_nearest_sample, sampled_diagonal_blocks,
};
use crate::coupling::space::ContactSpace;
use crate::error::SolverError;
use contact_laws::ContactLaw;
use fem_core::{Dim, Structure};

/// Contacts whose diagonal block of `F*` is computed exactly to set `ρ⁰` in matrix-free steps.
const RHO_SAMPLES: usize = 16;

impl<S: Structure<D>, L: ContactLaw + Clone, const D: usize, T: TimeScheme<S, D>>
    ContactSimulation<S, L, D, T>
where
    Dim<D>: ContactSpace<D>,
{
    /// `F* = H K⁻¹ Hᵀ` on `active`, in chunks of right-hand sides, into the operator cache
    /// (with `active`). With `reuse` (the stiffness unchanged since the last build) only the
    /// columns of contacts the last active set did not have are solved.
    pub(super) fn build_flexibility(
        &mut self,
        active: &[usize],
        reuse: bool,
    ) -> Result<(), SolverError> {
        let m = D * active.len();
        let old = std::mem::take(&mut self.cache.w);
        let previous = reuse.then_some(Previous {
            w: &old,
            active: &self.cache.active,
        });
        // the columns solved: normals, and tangents where a law needs them
        let (mut w, columns) = build_dense(
            &self.structure,
            &self.interface.h_rows,
            active,
            |j| j % D == 0 || self.tangent_solved(active[j / D], j % D),
            previous,
            self.settings.columns_per_solve,
        )?;
        // the old F* is dropped here unless the last reduced problem still holds it
        drop(old);
        // decoupled tangential unknowns of frictionless contacts (and, in 3D, of held
        // directions): W_tt = W_nn, nothing else
        for (k, &i) in active.iter().enumerate() {
            let wnn = w[D * k * m + D * k];
            for d in 1..D {
                if !self.tangent_solved(i, d) {
                    w[(D * k + d) * m + D * k + d] = wnn;
                }
            }
        }
        self.cache.w = std::sync::Arc::new(w);
        self.cache.active.clear();
        self.cache.active.extend_from_slice(active);
        self.counters.flexibility_builds += 1;
        self.counters.flexibility_columns += columns;
        Ok(())
    }

    /// `ρ⁰_i = 1/λ_max` of the diagonal blocks of `F*`, computed exactly on up to
    /// [`RHO_SAMPLES`] contacts spread over the active list and carried to the others from the
    /// nearest sample in that order (interfaces are listed in order along them).
    pub(super) fn estimate_rho0(&mut self, active: &[usize]) -> Result<Vec<f64>, SolverError> {
        let (samples, blocks) = sampled_diagonal_blocks(
            &self.structure,
            &self.interface.h_rows,
            active,
            D,
            RHO_SAMPLES,
        )?;
        self.counters.flexibility_columns += D * samples.len();
        let rho: Vec<f64> = blocks.iter().map(|w| dispatch::rho0::<D>(w)).collect();
        Ok(from_nearest_sample(&samples, &rho, active.len()))
    }
}
