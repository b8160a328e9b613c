//! The matrix-free path of a 3D step ([`SolidSettings::flexibility`](super::SolidSettings)):
//! the reduced problem solved with one structure solve per product, without `F*`.

use super::{SolidContactSimulation, Solved};
use crate::coupling::flexibility::{from_nearest_sample, sampled_diagonal_blocks};
use crate::error::SolverError;
use crate::local::matrix_free::solve_matrix_free_3d;
use contact_laws::ContactLaw;
use fem_core::Structure;

impl<S: Structure<3>, L: ContactLaw + Clone> SolidContactSimulation<S, L> {
    /// The reduced problem on `active` without `F*`: each product `x = H K⁻¹ Hᵀ r + q` is one
    /// structure solve ([`solve_matrix_free_3d`]). A direction the contact cannot use
    /// (frictionless tangents, or held on both sides) answers `x = r / ρ⁰`, which the law's
    /// projection drives to `r = 0` there (the dense path's decoupling).
    pub(super) fn solve_matrix_free(
        &mut self,
        active: &[usize],
        free: &[[f64; 3]],
    ) -> Result<Solved<L::State>, SolverError> {
        let na = active.len();
        let laws: Vec<L> = active
            .iter()
            .map(|&i| self.zones[self.candidates[i].zone].law.clone())
            .collect();
        let states: Vec<L::State> = active.iter().map(|&i| self.states[i]).collect();
        let rho0 = self.estimate_rho0(active)?;
        // rows of H that carry the contact's response; the others are decoupled
        let used: Vec<bool> = active
            .iter()
            .flat_map(|&i| {
                let t = self.tangent_needed(i);
                (0..3).map(move |d| (i, d, t))
            })
            .map(|(i, d, t)| (d == 0 || t) && !self.h_rows[3 * i + d].is_empty())
            .collect();
        let rows: Vec<usize> = active
            .iter()
            .flat_map(|&i| [3 * i, 3 * i + 1, 3 * i + 2])
            .collect();
        let mut q = vec![0.0; 3 * na];
        for (k, &i) in active.iter().enumerate() {
            q[3 * k] = free[i][0];
            for d in 1..3 {
                if used[3 * k + d] {
                    q[3 * k + d] = free[i][d] - self.jumps[i][d];
                }
            }
        }
        let mut r: Vec<f64> = active.iter().flat_map(|&i| self.r_bar_last[i]).collect();
        let mut x = vec![0.0; 3 * na];
        let (structure, h_rows) = (&self.structure, &self.h_rows);
        let mut scratch = vec![0.0; structure.dof_count()];
        let apply = |r: &[f64], x: &mut [f64]| -> Result<(), SolverError> {
            scratch.fill(0.0);
            for (j, &row) in rows.iter().enumerate() {
                if used[j] && r[j] != 0.0 {
                    for &(dof, a) in &h_rows[row] {
                        scratch[dof] += a * r[j];
                    }
                }
            }
            structure.solve_in_place(&mut scratch)?;
            for (j, &row) in rows.iter().enumerate() {
                x[j] = q[j]
                    + if used[j] {
                        h_rows[row]
                            .iter()
                            .map(|&(dof, a)| a * scratch[dof])
                            .sum::<f64>()
                    } else {
                        r[j] / rho0[j / 3]
                    };
            }
            Ok(())
        };
        let report = solve_matrix_free_3d(
            apply,
            &laws,
            &states,
            &rho0,
            &self.settings.solver,
            &mut r,
            &mut x,
        )?;
        Ok(Solved {
            r_bar: r.clone(),
            r,
            states: None,
            iterations: report.iterations,
            adhesion_iterations: 0,
            residual: report.residual,
            matrix_free: true,
            active_set: false,
            factorizations: 0,
        })
    }

    /// `ρ⁰` per active contact for the matrix-free iteration: `1 / λ̄` of the 3 × 3 diagonal
    /// block of `F*` (`λ̄` its Gershgorin bound), computed exactly on up to 16 contacts spread
    /// over the active set and given to the others from the nearest sample.
    fn estimate_rho0(&self, active: &[usize]) -> Result<Vec<f64>, SolverError> {
        let (samples, blocks) =
            sampled_diagonal_blocks(&self.structure, &self.h_rows, active, 3, 16)?;
        let rho: Vec<f64> = blocks
            .iter()
            .map(|w| {
                let bound = (0..3)
                    .map(|a| (0..3).map(|b| w[3 * a + b].abs()).sum::<f64>())
                    .fold(0.0_f64, f64::max);
                if bound > 0.0 && bound.is_finite() {
                    1.0 / bound
                } else {
                    1.0
                }
            })
            .collect();
        Ok(from_nearest_sample(&samples, &rho, active.len()))
    }
}
