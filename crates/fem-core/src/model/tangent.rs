//! Crate-private hooks through which a state-dependent body built on an [`ElasticModel`]
//! (`crate::plastic::PlasticModel`) reuses its dof map, pattern, prescribed couplings, loads
//! and factorisation with a tangent of its own, instead of a second copy of that machinery.

use super::{ElasticModel, ModelSpace, StressField};
use crate::assembly::Pattern;
use crate::error::FemError;
use crate::space::Dim;

impl<const D: usize> ElasticModel<D>
where
    Dim<D>: ModelSpace<D>,
{
    /// The sparsity pattern of the reduced stiffness (lower triangle, free dofs).
    pub(crate) fn pattern(&self) -> &Pattern {
        &self.pattern
    }

    /// The prescribed value of every prescribed dof, in [`crate::DofMap::prescribed`] order.
    pub(crate) fn prescribed_values(&self) -> Vec<f64> {
        self.dofs.prescribed_values(&self.supports)
    }

    /// Sets the value of every prescribed dof, in [`crate::DofMap::prescribed`] order (the
    /// order of [`Self::prescribed_values`]); no refactorisation.
    ///
    /// # Panics
    /// If `values.len()` is not the number of prescribed dofs.
    #[track_caller]
    pub(crate) fn set_prescribed_values(&mut self, values: &[f64]) -> Result<(), FemError> {
        let prescribed = self.dofs.prescribed();
        assert_eq!(values.len(), prescribed.len(), "prescribed values length");
        for (&(node, component), &v) in prescribed.iter().zip(values) {
            self.supports.update(&[node], component, v)?;
        }
        Ok(())
    }

    /// `v −= K_fp ū`: the coupling of the prescribed values `prescribed` with the free dofs,
    /// as the right-hand side of [`crate::Structure::free_response_into`] subtracts it.
    pub(crate) fn subtract_prescribed_coupling(&self, prescribed: &[f64], v: &mut [f64]) {
        self.coupling.subtract_into(prescribed, v);
    }

    /// Takes the initial stress fields out of the model (with their internal forces), for a
    /// body that carries them as the committed stress of its material points.
    pub(crate) fn take_initial_stress(&mut self) -> Vec<(u32, StressField<D>)> {
        self.initial_force.fill(0.0);
        std::mem::take(&mut self.initial_stress)
    }

    /// Factorises the matrix with these `values` on the model's pattern (numeric work only:
    /// the symbolic factorisation is the model's) in place of `K`, and bumps the stiffness
    /// version: the model's solves are with that matrix from then on. A floating model is
    /// refused (its pinned factorisation is for `K`).
    ///
    /// # Errors
    /// [`FemError::Unsupported`] for a floating model; [`FemError::NotPositiveDefinite`]
    /// naming the dof of a failed pivot.
    pub(crate) fn factor_values(&mut self, values: &[f64]) -> Result<(), FemError> {
        if !self.pinned.is_empty() {
            return Err(FemError::Unsupported {
                what: "a tangent of its own on a floating model".into(),
            });
        }
        self.refuse_with_external("a tangent of its own")?;
        let solver = match &mut self.solver {
            Some(solver) => solver,
            None => self.solver.insert(super::solver_for(
                &self.mesh,
                &self.dofs,
                &self.pattern,
                self.ordering,
            )?),
        };
        solver
            .factor(self.pattern.view(values))
            .map_err(|e| self.name_failed_dof(e))?;
        self.version += 1;
        Ok(())
    }
}
