//! Springs on the closed contacts for the global Newton around contact (issue 40): the
//! Newton's matrix where the body's tangent is singular but for the contact.
//!
//! A perfectly plastic body at its limit load has a singular consistent tangent `K_t`: a
//! homogeneous von Mises block pressed onto a frictionless base flows uniaxially
//! (`dε ∝ dev σ`, `dσ = 0`), a mechanism of the free dofs that only the contact stops. Then
//! `F* = H K_t⁻¹ Hᵀ` does not exist and the free response `K_t⁻¹ R` neither, although the
//! constrained system (the closed contacts held) is regular. The Newton's linear problem
//!
//! ```text
//! K_t Δu = R + Hᵀ r,    the contact law on x = H (u_k + Δu) − g
//! ```
//! is unchanged by springs `p` on the normals of the contacts closed at `u_k`,
//! `(K_t + H_nᵀ P H_n) Δu = R + Hᵀ r + H_nᵀ P H_n Δu`, where a contact that stays closed has
//! `H_n Δu = 0` (its gap is 0 at both iterates): the corrections are the Newton's own
//! (quadratic), solved with a regular matrix, and the equilibrium residual is the true one.
//! A contact that opens in the iteration makes that iteration a quasi-Newton one.
//!
//! The springs are a fallback, so that every step that converges without them is solved as
//! before: once a sub-step fails after at least one correction because a tangent failed (its
//! factorisation, or a contact solve on it; not a Newton that ran out of iterations), it is
//! tried again with springs before it is cut ([`super::newton`]), and every later tangent of
//! the simulation carries
//! them, on the contacts closed at each iterate (`r_n > 0`). Each spring is the tangent's
//! own stiffness along the normal row when they were switched on, `p = Σ_d a_d² K_dd` (a
//! stiffness of the body's scale, so that `K_t + P` is as well conditioned as the elastic
//! body).

use super::ContactSimulation;
use super::scheme::TimeScheme;
use crate::coupling::space::ContactSpace;
use crate::error::SolverError;
use contact_laws::ContactLaw;
use fem_core::{Dim, Structure};

impl<S: Structure<D>, L: ContactLaw + Clone, const D: usize, T: TimeScheme<S, D>>
    ContactSimulation<S, L, D, T>
where
    Dim<D>: ContactSpace<D>,
{
    /// Whether the Newton's tangents carry springs on the closed contacts (module docs of
    /// `newton_springs`): switched on by the first sub-step that failed without them.
    pub fn newton_springs(&self) -> bool {
        self.newton.as_ref().is_some_and(|n| !n.springs.is_empty())
    }

    /// The candidates closed under per-candidate reactions `(i, [r_n, r_t…])` (`r_n > 0`).
    pub(super) fn closed_of<'a>(
        &self,
        reactions: impl Iterator<Item = (usize, &'a [f64])>,
    ) -> Vec<usize> {
        reactions
            .filter(|(_, r)| r[0] > 0.0)
            .map(|(i, _)| i)
            .collect()
    }

    /// The springs' entries `(row, col, p a_row a_col)` (`row ≥ col`) on the normal rows of
    /// the `closed` candidates.
    fn spring_entries(&self, closed: &[usize], p: &[f64]) -> Vec<(usize, usize, f64)> {
        let mut entries = Vec::new();
        for &i in closed {
            let row = &self.interface.h_rows[D * i];
            for &(a, va) in row {
                for &(b, vb) in row {
                    if a >= b {
                        entries.push((a, b, p[i] * va * vb));
                    }
                }
            }
        }
        entries
    }

    /// Sets the springs of the `closed` candidates on the structure's next tangent, when they
    /// are on (nothing otherwise).
    ///
    /// # Errors
    /// The structure's ([`fem_core::Nonlinear::set_tangent_springs`]).
    pub(super) fn set_springs(&mut self, closed: &[usize]) -> Result<(), SolverError> {
        let Some(state) = self.newton.as_ref().filter(|n| !n.springs.is_empty()) else {
            return Ok(());
        };
        let entries = self.spring_entries(closed, &state.springs);
        if let Some(body) = self.structure.nonlinear() {
            body.set_tangent_springs(&entries)?;
        }
        Ok(())
    }

    /// Switches the springs on (module docs), if they are not yet and the structure takes
    /// them on every candidate's normal row: whether the failed sub-step is worth another
    /// attempt with them.
    pub(super) fn start_springs(&mut self) -> bool {
        if self.newton_springs() {
            return false;
        }
        let Some(k) = self.structure.stiffness_matrix() else {
            return false;
        };
        let (col_ptr, row_idx, values) = (k.col_ptr(), k.row_idx(), k.val());
        let diagonal = |j: usize| {
            (col_ptr[j]..col_ptr[j + 1])
                .find(|&q| row_idx[q] == j)
                .map_or(0.0, |q| values[q])
        };
        let stiffness: Vec<f64> = (0..self.interface.candidates.len())
            .map(|i| {
                self.interface.h_rows[D * i]
                    .iter()
                    .map(|&(dof, a)| a * a * diagonal(dof))
                    .sum::<f64>()
            })
            .collect();
        if stiffness.is_empty() || stiffness.iter().any(|p| !(p.is_finite() && *p > 0.0)) {
            return false;
        }
        // every candidate's spring must fit the tangent's pattern
        let all: Vec<usize> = (0..stiffness.len()).collect();
        let entries = self.spring_entries(&all, &stiffness);
        let Some(body) = self.structure.nonlinear() else {
            return false;
        };
        if body.set_tangent_springs(&entries).is_err() {
            return false;
        }
        match self.newton.as_mut() {
            Some(state) => {
                state.springs = stiffness;
                true
            }
            None => false,
        }
    }
}
