//! Stage 2, the dense operator: `F* = H K⁻¹ Hᵀ` on the active set, built with chunks of
//! right-hand sides of the factorised structure, and the base penalties `ρ⁰` of the
//! matrix-free path from a few exact diagonal blocks.

use super::ContactSimulation;
use crate::coupling::flexibility::flexibility_into;
use crate::error::SolverError;
use crate::local::symmetrize;
use contact_laws::ContactLaw;
use faer::Mat;
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
        let na = active.len();
        let ns = na.min(RHO_SAMPLES);
        let samples: Vec<usize> = (0..ns).map(|k| (2 * k + 1) * na / (2 * ns)).collect();
        let mut x = Mat::<f64>::zeros(self.structure.dof_count(), 2 * ns);
        for (c, &k) in samples.iter().enumerate() {
            let i = active[k];
            for d in 0..2 {
                for &(dof, a) in &self.h_rows[2 * i + d] {
                    x[(dof, 2 * c + d)] += a;
                }
            }
        }
        self.structure.solve_many_in_place(x.as_mut())?;
        self.counters.flexibility_columns += 2 * ns;
        let rho: Vec<f64> = samples
            .iter()
            .enumerate()
            .map(|(c, &k)| {
                let i = active[k];
                let w = |row: usize, col: usize| -> f64 {
                    self.h_rows[2 * i + row]
                        .iter()
                        .map(|&(dof, a)| a * x[(dof, 2 * c + col)])
                        .sum()
                };
                let (a, b, d) = (w(0, 0), 0.5 * (w(0, 1) + w(1, 0)), w(1, 1));
                let h = 0.5 * (a - d);
                1.0 / (0.5 * (a + d) + (h * h + b * b).sqrt())
            })
            .collect();
        Ok((0..na)
            .map(|k| {
                let nearest = samples
                    .iter()
                    .enumerate()
                    .min_by_key(|(_, s)| s.abs_diff(k))
                    .map_or(0, |(c, _)| c);
                rho[nearest]
            })
            .collect())
    }
}
