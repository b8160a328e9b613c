//! [`ElasticModel`] as a [`Nonlinear`] structure with no history: `f_int(u) = K u`, the
//! tangent is `K` (assembled and factorised when the model was built), and the equilibrium
//! `f_int(u) = f_ext(λ)` is the system of
//! [`Structure::free_response_into`](crate::Structure::free_response_into), with
//!
//! ```text
//! f_ext(λ) = λ f_ext,ref + f_σ₀ − K_fp ū          (free dofs; ū the prescribed values)
//! ```
//!
//! A plastic model keeps the same `f_ext` and replaces `K u` by `Σ_e ∫ Bᵀ σ(u) w dΩ`
//! (see [`Nonlinear`] for its history and tangent).

use super::{ElasticModel, ModelSpace};
use crate::error::FemError;
use crate::space::Dim;
use crate::structure::Nonlinear;

impl<const D: usize> Nonlinear for ElasticModel<D>
where
    Dim<D>: ModelSpace<D>,
{
    fn external_force_into(&self, load_factor: f64, f_ext: &mut [f64]) -> Result<(), FemError> {
        self.checked_rhs_into(load_factor, f_ext)
    }

    #[track_caller]
    fn internal_force_into(&mut self, u: &[f64], f_int: &mut [f64]) -> Result<(), FemError> {
        self.check_finite("displacement", u)?;
        // the true K, not the pinned matrix a floating model factorises
        self.pattern.symmetric_mul_into(&self.values, u, f_int);
        Ok(())
    }

    /// `K` is the tangent at every state and is factorised already: nothing to do, and
    /// [`stiffness_version`](crate::Structure::stiffness_version) stays (the contact solver
    /// keeps its `F*`).
    fn update_tangent(&mut self) -> Result<(), FemError> {
        Ok(())
    }

    /// No history to keep.
    fn commit(&mut self) {}

    /// No history to restore.
    fn rollback(&mut self) {}
}
