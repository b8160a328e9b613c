//! [`ReducedSolver`]: a solver of the model's reduced system `K x = b` that takes the place of
//! its own Cholesky factorisation (a distributed one: `bipotential-petsc` under MPI), while the
//! model keeps everything else — the dof map, the loads, the prescribed couplings
//! (`b = λ f_ext + f_σ₀ − K_fp ū` is still the model's), the recovery of stresses and
//! reactions. A program that already runs on an [`ElasticModel`] (the `bipo` command) thus
//! runs distributed by handing the model such a solver, nothing else changed.
//!
//! The solver is for the model's numbering at the moment it is set: a change that renumbers
//! the dofs (constraining a free dof, releasing a support) or refactors `K` is refused from then
//! on, and so is a floating model (its pinned factorisation is `K⁺`, not `K⁻¹`).

use super::{ElasticModel, ModelSpace};
use crate::element::Setting;
use crate::error::FemError;
use crate::ordering::FillOrdering;
use crate::space::Dim;
use crate::{Material, Mesh, Supports};
use faer::MatMut;

/// Solves `K X = B` for the model's reduced stiffness `K` (free dofs, the model's numbering),
/// `B`'s columns overwritten by the solutions. Set with
/// [`ElasticModel::set_reduced_solver`].
///
/// # Examples
/// A solver that forwards to a second model built alike (a distributed solver is the real
/// use):
/// ```
/// use fem_core::faer::MatMut;
/// use fem_core::model::ReducedSolver;
/// use fem_core::solid::generate::{box_mesh, lines};
/// use fem_core::solid::{SolidKind, SolidModel};
/// use fem_core::{Component, FemError, Material, Structure, Supports};
/// struct Twin(SolidModel);
/// impl ReducedSolver for Twin {
///     fn solve_many_in_place(&self, rhs: MatMut<'_, f64>) -> Result<(), FemError> {
///         self.0.solve_many_in_place(rhs)
///     }
/// }
/// let build = || -> Result<SolidModel, FemError> {
///     let l = lines(0.0, 1.0, 2);
///     let mesh = box_mesh(&l, &l, &l, SolidKind::Tet4)?;
///     let mut s = Supports::new();
///     s.fix(mesh.node_set("z0")?, Component::Z)
///         .fix(mesh.node_set("x0")?, Component::X)
///         .fix(mesh.node_set("y0")?, Component::Y);
///     s.prescribe(mesh.node_set("z1")?, Component::Z, -1e-3)?;
///     SolidModel::new(mesh, &[(0, Material::new(1e3, 0.3, 0.0)?)], s)
/// };
/// let mut model = build()?;
/// let serial = model.solve(1.0)?;
/// model.set_reduced_solver(Box::new(Twin(build()?)))?;
/// assert!(model.has_reduced_solver());
/// assert_eq!(model.solve(1.0)?, serial);
/// # Ok::<(), FemError>(())
/// ```
pub trait ReducedSolver: Send + Sync {
    /// Overwrites each column `b` of `rhs` (`dof_count` rows) with `K⁻¹ b`.
    ///
    /// # Errors
    /// The solver's failure, as a [`FemError`] (a distributed solver's as
    /// [`FemError::LinearAlgebra`] with its sentence).
    fn solve_many_in_place(&self, rhs: MatMut<'_, f64>) -> Result<(), FemError>;
}

impl<const D: usize> ElasticModel<D>
where
    Dim<D>: ModelSpace<D>,
{
    /// Solves with `solver` in place of the model's factorisation from now on:
    /// [`Structure::solve_many_in_place`](crate::Structure::solve_many_in_place) and
    /// [`Structure::free_response_into`](crate::Structure::free_response_into) go through it.
    /// Changes that renumber the dofs or refactor `K` are refused afterwards
    /// ([`FemError::Unsupported`]); changing a prescribed *value* is not such a change.
    ///
    /// # Errors
    /// [`FemError::Unsupported`] for a floating model (its solves are `P K⁺ P`, with `K`
    /// pinned).
    pub fn set_reduced_solver(&mut self, solver: Box<dyn ReducedSolver>) -> Result<(), FemError> {
        if !self.pinned.is_empty() {
            return Err(FemError::Unsupported {
                what: "an external solver for a floating model (hold the body with supports)"
                    .into(),
            });
        }
        self.external = Some(solver);
        // never used again: the factor's memory goes back
        self.solver = None;
        Ok(())
    }

    /// Builds the model as the constructors do (the dofs numbered, `K` assembled, the loads
    /// empty) but does not factorise `K`, nor analyse its pattern for a factorisation: for a
    /// model whose solves go to a [`ReducedSolver`] ([`Self::set_reduced_solver`]), so that
    /// it never holds a Cholesky factor (a distributed run's rank holds `K` and its share of
    /// the distributed matrix). Until a solver is set, solves fail
    /// ([`FemError::LinearAlgebra`]); [`Self::refactor`] factorises it as
    /// [`LinearElasticModel::new`](crate::LinearElasticModel::new) (2D, minimum-degree
    /// ordering) or [`SolidModel::new`](crate::solid::SolidModel::new) (3D, nested
    /// dissection) would have.
    ///
    /// `setting` is the [`Idealization`](crate::Idealization) in 2D, `()` in 3D.
    ///
    /// # Errors
    /// As [`LinearElasticModel::new`](crate::LinearElasticModel::new), but for a stiffness
    /// that is singular otherwise than by a rigid-body mode (a node no element connects, a
    /// mechanism): no factorisation finds it (the external solver's does, or fails to
    /// converge).
    ///
    /// # Examples
    /// ```
    /// use fem_core::solid::generate::{box_mesh, lines};
    /// use fem_core::solid::{SolidKind, SolidModel};
    /// use fem_core::{Component, FemError, Material, Structure, Supports};
    /// let l = lines(0.0, 1.0, 2);
    /// let mesh = box_mesh(&l, &l, &l, SolidKind::Tet4)?;
    /// let mut s = Supports::new();
    /// s.fix(mesh.node_set("z0")?, Component::Z)
    ///     .fix(mesh.node_set("x0")?, Component::X)
    ///     .fix(mesh.node_set("y0")?, Component::Y);
    /// let materials = [(0, Material::new(1e3, 0.3, 0.0)?)];
    /// let mut model = SolidModel::unfactored(mesh, (), &materials, s)?;
    /// assert_eq!((model.factorizations(), model.factor_nnz()), (0, 0));
    /// assert!(model.solve(1.0).is_err());
    /// model.refactor()?;
    /// assert_eq!(model.factorizations(), 1);
    /// # Ok::<(), FemError>(())
    /// ```
    pub fn unfactored(
        mesh: Mesh<D>,
        setting: Setting<D>,
        materials: &[(u32, Material)],
        supports: Supports,
    ) -> Result<Self, FemError> {
        let ordering = if D == 2 {
            FillOrdering::Amd
        } else {
            FillOrdering::default()
        };
        Self::assembled(mesh, setting, materials, supports, false, ordering)
    }

    /// Whether the model solves with an external [`ReducedSolver`].
    pub fn has_reduced_solver(&self) -> bool {
        self.external.is_some()
    }

    /// [`FemError::Unsupported`] naming `what` when an external solver is set (it cannot
    /// follow a renumbering or a new `K`).
    pub(super) fn refuse_with_external(&self, what: &str) -> Result<(), FemError> {
        match self.external {
            None => Ok(()),
            Some(_) => Err(FemError::Unsupported {
                what: format!(
                    "{what} with an external solver of K (it solves the numbering and the \
                     stiffness it was set up with)"
                ),
            }),
        }
    }
}

/// The release and restore of the factor of `K` ([`Structure::release_factor`](crate::Structure::release_factor),
/// [`Structure::restore_factor`](crate::Structure::restore_factor)): the 3D active set frees it while it holds its own.
impl<const D: usize> ElasticModel<D>
where
    Dim<D>: ModelSpace<D>,
{
    pub(super) fn release_own_factor(&mut self) -> bool {
        match &mut self.solver {
            Some(solver) if solver.is_factored() => {
                solver.release();
                true
            }
            _ => false,
        }
    }

    pub(super) fn restore_own_factor(&mut self) -> Result<(), FemError> {
        // the values `assemble_and_factor` factorised; the version stays (same matrix)
        let values = if self.pinned.is_empty() {
            &self.values
        } else {
            &self.pinned_values
        };
        let result = match &mut self.solver {
            Some(solver) if solver.is_released() => solver.factor(self.pattern.view(values)),
            _ => return Ok(()),
        };
        result.map_err(|e| self.name_failed_dof(e))
    }
}

#[cfg(test)]
mod tests {
    use crate::solid::generate::{box_mesh, lines};
    use crate::solid::{SolidKind, SolidModel};
    use crate::{Component, FemError, Material, Structure, Supports};
    use faer::MatMut;

    /// Solves with a second model built alike, counting its calls.
    struct Twin(SolidModel, std::sync::atomic::AtomicUsize);

    impl super::ReducedSolver for Twin {
        fn solve_many_in_place(&self, rhs: MatMut<'_, f64>) -> Result<(), FemError> {
            self.1.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            self.0.solve_many_in_place(rhs)
        }
    }

    fn block() -> SolidModel {
        let l = lines(0.0, 1.0, 2);
        let mesh = box_mesh(&l, &l, &l, SolidKind::Tet4).unwrap();
        let mut s = Supports::new();
        s.fix(mesh.node_set("z0").unwrap(), Component::Z)
            .fix(mesh.node_set("x0").unwrap(), Component::X)
            .fix(mesh.node_set("y0").unwrap(), Component::Y);
        s.prescribe(mesh.node_set("z1").unwrap(), Component::Z, -1e-3)
            .unwrap();
        SolidModel::new(mesh, &[(0, Material::new(1e3, 0.3, 0.0).unwrap())], s).unwrap()
    }

    #[test]
    fn issue_41_external_solver_works_and_refuses_renumbering() {
        let mut model = block();
        let serial = model.solve(1.0).unwrap();
        model
            .set_reduced_solver(Box::new(Twin(block(), 0.into())))
            .unwrap();
        // the same K and right-hand side: the same bits
        assert_eq!(model.solve(1.0).unwrap(), serial);
        // a new prescribed value is not a renumbering
        let top = model.mesh().node_set("z1").unwrap().to_vec();
        model.set_prescribed(&top, Component::Z, -2e-3).unwrap();
        let doubled = model.solve(1.0).unwrap();
        for (a, b) in doubled.iter().zip(&serial) {
            for k in 0..3 {
                // linear in the prescribed value, to rounding
                assert!((a[k] - 2.0 * b[k]).abs() <= 1e-12 * (1e-3 + b[k].abs()));
            }
        }
        // constraining a free dof would renumber: refused, the supports unchanged
        let x1 = model.mesh().node_set("x1").unwrap().to_vec();
        let e = model.set_prescribed(&x1, Component::X, 0.0).unwrap_err();
        assert!(matches!(e, FemError::Unsupported { .. }), "{e}");
        assert!(model.supports().value(x1[0], Component::X).is_none());
        assert!(matches!(
            model.refactor(),
            Err(FemError::Unsupported { .. })
        ));
    }

    #[test]
    fn issue_41_unfactored_model_solves_by_its_external_solver_only() {
        let factored = block();
        let serial = factored.solve(1.0).unwrap();
        let l = lines(0.0, 1.0, 2);
        let mesh = box_mesh(&l, &l, &l, SolidKind::Tet4).unwrap();
        let mut model = SolidModel::unfactored(
            mesh,
            (),
            &[(0, Material::new(1e3, 0.3, 0.0).unwrap())],
            factored.supports().clone(),
        )
        .unwrap();
        // no factor, no symbolic analysis; K assembled all the same (the same bits)
        assert_eq!((model.factorizations(), model.factor_nnz()), (0, 0));
        assert_eq!(model.stiffness().val(), factored.stiffness().val());
        let e = model.solve(1.0).unwrap_err();
        assert!(e.to_string().contains("set_reduced_solver"), "{e}");
        model
            .set_reduced_solver(Box::new(Twin(block(), 0.into())))
            .unwrap();
        assert_eq!(model.solve(1.0).unwrap(), serial);
        // a factored model handed a solver lets its factor go
        let mut handed = block();
        assert!(handed.factor_nnz() > 0);
        handed
            .set_reduced_solver(Box::new(Twin(block(), 0.into())))
            .unwrap();
        assert_eq!(handed.factor_nnz(), 0);
        assert_eq!(handed.solve(1.0).unwrap(), serial);
    }
}
