//! [`Nonlinear`]: the capability of a structure whose internal forces and tangent depend on
//! its state (plasticity, large strain), for a global Newton around contact.
//!
//! ```text
//! equilibrium:   f_int(u) = f_ext(λ)               (on the free dofs)
//! Newton:        K_t(u_k) Δu = f_ext(λ) − f_int(u_k),   u_{k+1} = u_k + Δu
//! ```
//! For a linear-elastic body `f_int(u) = K u`, `K_t = K`, and one step from any `u_0` lands
//! on the solution.

use crate::error::FemError;
#[cfg(doc)]
use crate::structure::Structure;

/// The state-dependent side of a [`Structure`], reached through [`Structure::nonlinear`].
///
/// # Contract
/// - `u` is the **total** displacement of the free dofs from the reference configuration
///   (the prescribed values are the structure's own, as in [`Structure::free_response_into`]).
/// - [`internal_force_into`](Self::internal_force_into) evaluates a **trial** state from the
///   last **committed** one and `u`; it never changes the committed state, so a line search
///   or a rejected step costs nothing to undo.
/// - [`update_tangent`](Self::update_tangent) assembles and factorises the tangent at the last
///   trial state. From then on the structure's own solves
///   ([`Structure::solve_in_place`], [`Structure::solve_many_in_place`]) are solves with the
///   tangent, and [`Structure::stiffness_version`] changes whenever the tangent does: the
///   contact solver's `F* = H K_t⁻¹ Hᵀ` follows the current tangent with no other seam.
/// - [`commit`](Self::commit) accepts the trial state (an accepted step);
///   [`rollback`](Self::rollback) returns to the committed one (a step cut).
///
/// # How a plastic material implements it
/// A Drucker–Prager body keeps its history per quadrature point twice, `committed` and
/// `trial`. `internal_force_into` runs the return mapping from `committed` and the strain of
/// `u` into `trial` and returns `f_int = Σ_e ∫ Bᵀ σ_trial w dΩ`; `update_tangent` assembles
/// `Σ_e ∫ Bᵀ C_t B w dΩ` on the stiffness pattern, refactors it (numeric only: the symbolic
/// factorisation is per pattern) and bumps the version; `commit` and `rollback` copy one
/// history onto the other. fem-core's [`ElasticModel`] has no history: `K_t = K`.
///
/// [`ElasticModel`]: crate::ElasticModel
///
/// # Examples
/// One Newton step solves a linear-elastic body from any start:
/// ```
/// use fem_core::generate::{RectangleSpec, rectangle};
/// use fem_core::{Component, Idealization, LinearElasticModel, Material, Structure, Supports};
/// let mesh = rectangle(&RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 4, 2))?;
/// let left = mesh.node_set("left")?.to_vec();
/// let mut supports = Supports::new();
/// supports.fix(&left, Component::X).fix(&left, Component::Y);
/// let mut model = LinearElasticModel::new(mesh, Idealization::PlaneStrain,
///     &[(0, Material::new(100.0, 0.3, 1.0)?)], supports)?;
/// model.add_self_weight()?;
/// let n = model.dof_count();
/// let (mut u, mut f_ext, mut f_int) = (vec![0.1; n], vec![0.0; n], vec![0.0; n]);
/// let body = model.nonlinear().expect("the elastic model is its own tangent");
/// body.external_force_into(1.0, &mut f_ext)?;
/// body.internal_force_into(&u, &mut f_int)?;
/// body.update_tangent()?;
/// let mut du: Vec<f64> = f_ext.iter().zip(&f_int).map(|(e, i)| e - i).collect();
/// model.solve_in_place(&mut du)?; // with the tangent
/// u.iter_mut().zip(&du).for_each(|(u, d)| *u += d);
/// let body = model.nonlinear().unwrap();
/// body.internal_force_into(&u, &mut f_int)?;
/// body.commit();
/// let scale = f_ext.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
/// assert!(f_int.iter().zip(&f_ext).all(|(i, e)| (i - e).abs() < 1e-12 * scale));
/// # Ok::<(), fem_core::FemError>(())
/// ```
pub trait Nonlinear {
    /// The external forces `f_ext(λ)` on the free dofs at `load_factor`: the right-hand side
    /// of the equilibrium `f_int(u) = f_ext(λ)`, written into `f_ext`. What a structure
    /// counts on which side (the coupling `−K_fp ū` of prescribed values, initial stresses)
    /// is its own, provided that a linear-elastic body at equilibrium solves `K u = f_ext`,
    /// the system of [`Structure::free_response_into`].
    ///
    /// # Errors
    /// A non-finite load factor or load.
    ///
    /// # Panics
    /// If `f_ext.len()` is not the structure's `dof_count()`.
    fn external_force_into(&self, load_factor: f64, f_ext: &mut [f64]) -> Result<(), FemError>;

    /// The internal forces `f_int(u)` at the trial displacement `u`, from the committed state;
    /// the trial state is kept for [`update_tangent`](Self::update_tangent) and
    /// [`commit`](Self::commit).
    ///
    /// # Errors
    /// A non-finite displacement, or a material point whose update fails.
    ///
    /// # Panics
    /// If `u.len()` or `f_int.len()` is not the structure's `dof_count()`.
    fn internal_force_into(&mut self, u: &[f64], f_int: &mut [f64]) -> Result<(), FemError>;

    /// Assembles and factorises the tangent at the last trial state (the committed state if
    /// none was evaluated since); the structure's solves use it from then on.
    ///
    /// # Errors
    /// The factorisation's (a tangent that lost definiteness: a softening or a mechanism).
    fn update_tangent(&mut self) -> Result<(), FemError>;

    /// Accepts the trial state as the new committed state.
    fn commit(&mut self);

    /// Discards the trial state: the next evaluation starts from the committed state again.
    fn rollback(&mut self);

    /// Moves the prescribed displacements `fraction` of the way from their values at the
    /// last [`commit`](Self::commit) (`ū_c`) to the values set for the coming step (`ū_s`),
    /// `ū = ū_c + fraction (ū_s − ū_c)`, for a step cut into sub-steps: a displacement
    /// control is then followed as the loads are (`fraction = 1` restores `ū_s`). What
    /// [`external_force_into`](Self::external_force_into),
    /// [`internal_force_into`](Self::internal_force_into) and
    /// [`Structure::prescribed_displacement`] see from then on.
    ///
    /// The default does nothing: right for a structure whose prescribed values do not change
    /// between steps, or whose steps are never cut (a linear one, solved in one correction).
    ///
    /// # Errors
    /// [`FemError::InvalidParameter`] naming `fraction` outside `[0, 1]`.
    fn interpolate_prescribed(&mut self, fraction: f64) -> Result<(), FemError> {
        let _ = fraction;
        Ok(())
    }

    /// Sets springs that every later [`update_tangent`](Self::update_tangent) adds to the
    /// tangent it factorises, `K_t + S`, until they are set again (an empty slice removes
    /// them). `S` is symmetric, given by its lower triangle: `entries` are `(row, col, s)`
    /// with `row ≥ col` on the free dofs (duplicates add up). They change the matrix of the
    /// Newton's linear solves only, never `f_int` nor the equilibrium: a caller whose
    /// solutions keep `S Δu = 0` (springs on dofs that the contact holds still) solves the
    /// same corrections with a matrix that stays regular where `K_t` alone is singular (a
    /// perfectly plastic body at its limit load, a mechanism that only the contact stops).
    ///
    /// The default refuses them.
    ///
    /// # Errors
    /// [`FemError::Unsupported`] for a structure without them (the default) or an entry
    /// outside the tangent's sparsity pattern; [`FemError::InvalidParameter`] naming
    /// `springs` for a non-finite value or an entry above the diagonal or outside the free
    /// dofs.
    fn set_tangent_springs(&mut self, entries: &[(usize, usize, f64)]) -> Result<(), FemError> {
        if entries.is_empty() {
            return Ok(());
        }
        Err(FemError::Unsupported {
            what: "springs on the tangent of this structure".into(),
        })
    }
}
