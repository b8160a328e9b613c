//! The 2D idealisations of a 3D elastic body.

use crate::error::{FemError, positive};

/// How a 2D model stands for a 3D body.
///
/// Coordinates are `(x, y)` in plane strain and plane stress, `(r, z)` in axisymmetry (the axis
/// is `r = 0`). Loads and reactions are per unit thickness in plane strain, per the given
/// thickness in plane stress, and per radian in axisymmetry (multiply by 2π for a full ring).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Idealization {
    /// `ε_zz = 0` (long bodies: the delamination tests of seed 5.6.1 and 5.6.2).
    PlaneStrain,
    /// `σ_zz = 0` for a plate of the given thickness (length).
    PlaneStress {
        /// Out-of-plane thickness, `> 0`.
        thickness: f64,
    },
    /// Axisymmetric about the `z` axis, with hoop strain `ε_θθ = u_r / r` (the pile of
    /// seed chapter 6). Integrals carry the weight `r` (per radian).
    Axisymmetric,
}

impl Idealization {
    /// Plane stress of the given thickness.
    ///
    /// # Errors
    /// [`FemError::InvalidParameter`] if `thickness` is not finite and positive.
    pub fn plane_stress(thickness: f64) -> Result<Self, FemError> {
        Ok(Idealization::PlaneStress {
            thickness: positive("thickness", thickness)?,
        })
    }

    /// Number of strain components: 3 (`ε_xx, ε_yy, γ_xy`) or 4 in axisymmetry
    /// (`ε_rr, ε_zz, γ_rz, ε_θθ`).
    #[inline]
    pub fn strain_size(&self) -> usize {
        match self {
            Idealization::Axisymmetric => 4,
            _ => 3,
        }
    }

    /// Integration weight at a point of first coordinate `x` (the radius in axisymmetry):
    /// `1`, the thickness, or `r`.
    #[inline]
    pub fn weight(&self, x: f64) -> f64 {
        match *self {
            Idealization::PlaneStrain => 1.0,
            Idealization::PlaneStress { thickness } => thickness,
            Idealization::Axisymmetric => x,
        }
    }
}
