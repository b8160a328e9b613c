//! [`Floating`]: the capability of a structure that only contact holds.

use crate::error::FemError;
use crate::rigid_modes::RigidBodyModes;
#[cfg(doc)]
use crate::structure::Structure;

/// The capability of a [`Structure`] that only contact holds: the rigid-body modes its
/// supports leave and the load along them, reached through [`Structure::floating`] (the trait
/// docs say how the solves treat such a body and why the pair is one capability).
///
/// The modes live on the free dofs, so the trait is the same in 2D and 3D.
///
/// # Examples
/// A block with no support at all floats with three modes (two translations, one rotation):
/// ```
/// use fem_core::generate::{RectangleSpec, rectangle};
/// use fem_core::{Idealization, LinearElasticModel, Material, Structure, Supports};
/// let mesh = rectangle(&RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 2, 1))?;
/// let model = LinearElasticModel::floating(mesh, Idealization::PlaneStrain,
///     &[(0, Material::new(100.0, 0.3, 0.0)?)], Supports::new())?;
/// let floating = model.floating().expect("no support: rigid-body modes");
/// let mut load = vec![1.0; floating.rigid_body_modes().len()];
/// floating.rigid_body_load_into(1.0, &mut load)?;
/// assert_eq!(load, [0.0; 3]); // no load: nothing for contact to balance
/// # Ok::<(), fem_core::FemError>(())
/// ```
pub trait Floating {
    /// The rigid-body modes the supports leave (the kernel of `K` over the free dofs), at least
    /// one.
    fn rigid_body_modes(&self) -> &RigidBodyModes;

    /// The generalized load along each rigid-body mode, `Rᵀ f` (`f` the right-hand side of
    /// [`Structure::free_response_into`] at `load_factor`), written into `out` (one entry per
    /// mode). Contact must balance it.
    ///
    /// # Errors
    /// As the structure's own load assembly (e.g. a non-finite load).
    ///
    /// # Panics
    /// If `out.len()` is not the number of modes.
    fn rigid_body_load_into(&self, load_factor: f64, out: &mut [f64]) -> Result<(), FemError>;
}
