//! Isotropic linear elasticity.

use crate::error::{FemError, non_negative, positive};
use crate::idealization::Idealization;
use nalgebra::Matrix4;

/// An isotropic linear-elastic material with a unit weight and, optionally, a mass density.
///
/// Build it with [`Material::new`] (positional) or [`Material::from_params`] (or `try_from`,
/// named); both validate the same way. The mass density is separate
/// ([`Material::with_density`]): the unit weight is a load, not a mass, so that a weightless
/// body can have inertia and a quasi-static body needs no density.
///
/// Strain and stress vectors are ordered `(xx, yy, xy)` in the plane and
/// `(rr, zz, rz, θθ)` in axisymmetry, with engineering shear strain `γ = 2ε`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material {
    young: f64,
    poisson: f64,
    unit_weight: f64,
    density: Option<f64>,
}

/// The parameters of a [`Material`], by name: the input of [`Material::from_params`].
///
/// # Examples
/// ```
/// use fem_core::{Material, MaterialParams};
/// let steel = Material::from_params(MaterialParams {
///     young: 210e9,
///     poisson: 0.3,
///     unit_weight: 78.5e3,
/// })?;
/// assert_eq!(steel, Material::new(210e9, 0.3, 78.5e3)?);
/// # Ok::<(), fem_core::FemError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MaterialParams {
    /// Young's modulus `E > 0` (stress).
    pub young: f64,
    /// Poisson's ratio `−1 < ν < 0.5`.
    pub poisson: f64,
    /// Unit weight `γ ≥ 0` (force per volume, acting along `−y` / `−z`).
    pub unit_weight: f64,
}

impl Material {
    /// Builds a material from Young's modulus `young > 0` (stress), Poisson's ratio
    /// `−1 < poisson < 0.5` and unit weight `unit_weight ≥ 0` (force per volume, acting along
    /// `−y` / `−z`; seed table 6.2 gives γ in kN/m³).
    ///
    /// # Errors
    /// [`FemError::InvalidParameter`] naming the offending parameter.
    ///
    /// # Examples
    /// ```
    /// use fem_core::Material;
    /// let soil = Material::new(30e3, 0.3, 18.0)?; // kPa, -, kN/m³
    /// assert_eq!(soil.poisson(), 0.3);
    /// # Ok::<(), fem_core::FemError>(())
    /// ```
    pub fn new(young: f64, poisson: f64, unit_weight: f64) -> Result<Self, FemError> {
        let young = positive("young", young)?;
        if young < f64::MIN_POSITIVE {
            // subnormal: its inverse overflows and the stiffness loses every digit
            return Err(FemError::InvalidParameter {
                name: "young",
                value: young,
                expected: "a finite value > 0 that is not subnormal (>= 2.2e-308)",
            });
        }
        if !(poisson > -1.0 && poisson < 0.5) {
            return Err(FemError::InvalidParameter {
                name: "poisson",
                value: poisson,
                expected: "a value in (-1, 0.5)",
            });
        }
        let unit_weight = non_negative("unit_weight", unit_weight)?;
        Ok(Self {
            young,
            poisson,
            unit_weight,
            density: None,
        })
    }

    /// The material with the mass density `density > 0` (mass per volume), which the mass of
    /// a model ([`crate::Mass`]) integrates.
    ///
    /// # Errors
    /// [`FemError::InvalidParameter`] named `density` for a value that is not finite and
    /// positive.
    ///
    /// # Examples
    /// ```
    /// use fem_core::Material;
    /// let steel = Material::new(210e9, 0.3, 78.5e3)?.with_density(7850.0)?;
    /// assert_eq!(steel.density(), Some(7850.0));
    /// assert_eq!(Material::new(210e9, 0.3, 0.0)?.density(), None);
    /// assert!(steel.with_density(0.0).is_err());
    /// # Ok::<(), fem_core::FemError>(())
    /// ```
    pub fn with_density(self, density: f64) -> Result<Self, FemError> {
        let density = positive("density", density)?;
        Ok(Self {
            density: Some(density),
            ..self
        })
    }

    /// [`Material::new`] with the parameters named (example at [`MaterialParams`]).
    ///
    /// # Errors
    /// As [`Material::new`].
    pub fn from_params(params: MaterialParams) -> Result<Self, FemError> {
        let MaterialParams {
            young,
            poisson,
            unit_weight,
        } = params;
        Self::new(young, poisson, unit_weight)
    }

    /// Young's modulus `E`.
    #[inline]
    pub fn young(&self) -> f64 {
        self.young
    }

    /// Poisson's ratio `ν`.
    #[inline]
    pub fn poisson(&self) -> f64 {
        self.poisson
    }

    /// Unit weight `γ` (force per volume).
    #[inline]
    pub fn unit_weight(&self) -> f64 {
        self.unit_weight
    }

    /// The mass density `ρ` (mass per volume), if one was given
    /// ([`Material::with_density`]).
    #[inline]
    pub fn density(&self) -> Option<f64> {
        self.density
    }

    /// The elasticity matrix `D` (σ = D ε) for `idealization`, in the top-left
    /// `strain_size × strain_size` block of a 4×4 matrix (the rest is zero).
    ///
    /// ```text
    /// plane strain, axisymmetry: λ = Eν/((1+ν)(1−2ν)), G = E/(2(1+ν)),
    ///   D = [λ+2G λ 0 (λ); λ λ+2G 0 (λ); 0 0 G (0); (λ λ 0 λ+2G)]
    /// plane stress: D = E/(1−ν²) [1 ν 0; ν 1 0; 0 0 (1−ν)/2]
    /// ```
    pub fn elasticity(&self, idealization: &Idealization) -> Matrix4<f64> {
        let (e, nu) = (self.young, self.poisson);
        let mut d = Matrix4::zeros();
        match idealization {
            Idealization::PlaneStress { .. } => {
                let c = e / (1.0 - nu * nu);
                d[(0, 0)] = c;
                d[(1, 1)] = c;
                d[(0, 1)] = c * nu;
                d[(1, 0)] = c * nu;
                d[(2, 2)] = c * (1.0 - nu) / 2.0;
            }
            _ => {
                let lambda = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
                let g = e / (2.0 * (1.0 + nu));
                let n = idealization.strain_size();
                for (i, j) in [(0, 1), (1, 0)] {
                    d[(i, j)] = lambda;
                }
                d[(0, 0)] = lambda + 2.0 * g;
                d[(1, 1)] = lambda + 2.0 * g;
                d[(2, 2)] = g;
                if n == 4 {
                    d[(3, 3)] = lambda + 2.0 * g;
                    for (i, j) in [(0, 3), (3, 0), (1, 3), (3, 1)] {
                        d[(i, j)] = lambda;
                    }
                }
            }
        }
        d
    }
}

impl TryFrom<MaterialParams> for Material {
    type Error = FemError;

    /// As [`Material::from_params`].
    fn try_from(params: MaterialParams) -> Result<Self, FemError> {
        Self::from_params(params)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn new_rejects_invalid_parameters() {
        for (e, nu, g, name) in [
            (0.0, 0.3, 0.0, "young"),
            (-1.0, 0.3, 0.0, "young"),
            (f64::NAN, 0.3, 0.0, "young"),
            (1.0, 0.5, 0.0, "poisson"),
            (1.0, -1.0, 0.0, "poisson"),
            (1.0, f64::NAN, 0.0, "poisson"),
            (1.0, 0.3, -1.0, "unit_weight"),
        ] {
            match Material::new(e, nu, g) {
                Err(FemError::InvalidParameter { name: n, .. }) => assert_eq!(n, name),
                other => panic!("expected InvalidParameter({name}), got {other:?}"),
            }
        }
    }

    #[test]
    fn with_density_rejects_invalid_densities() {
        let m = Material::new(1.0, 0.3, 0.0).unwrap();
        for rho in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            match m.with_density(rho) {
                Err(FemError::InvalidParameter { name, .. }) => assert_eq!(name, "density"),
                other => panic!("expected InvalidParameter(density), got {other:?}"),
            }
        }
        let dense = m.with_density(3.0).unwrap();
        assert_eq!((dense.density(), m.density()), (Some(3.0), None));
        assert_eq!(dense.young(), m.young());
    }

    #[test]
    fn from_params_agrees_with_new() {
        for (young, poisson, unit_weight) in [
            (210e9, 0.3, 78.5e3),
            (1.0, -0.5, 0.0),
            (30e3, 0.499, 18.0),
            // rejected, with the same error
            (0.0, 0.3, 0.0),
            (f64::NAN, 0.3, 0.0),
            (1.0, 0.5, 0.0),
            (1.0, f64::NAN, 0.0),
            (1.0, 0.3, -1.0),
            (1.0, 0.3, f64::INFINITY),
        ] {
            let params = MaterialParams {
                young,
                poisson,
                unit_weight,
            };
            let named = Material::from_params(params);
            let positional = Material::new(young, poisson, unit_weight);
            // `InvalidParameter` holds the value, so compare NaN errors by Debug.
            assert_eq!(format!("{named:?}"), format!("{positional:?}"));
            assert_eq!(
                format!("{:?}", Material::try_from(params)),
                format!("{positional:?}")
            );
            if let Ok(m) = named {
                assert_eq!(
                    (m.young(), m.poisson(), m.unit_weight()),
                    (young, poisson, unit_weight)
                );
            }
        }
    }

    #[test]
    fn elasticity_works() {
        let m = Material::new(1.0, 0.25, 0.0).unwrap();
        // Uniaxial stress in plane stress: ε = (1, −ν, 0) gives σ = (E, 0, 0).
        let d = m.elasticity(&Idealization::PlaneStress { thickness: 1.0 });
        let s = d * nalgebra::Vector4::new(1.0, -0.25, 0.0, 0.0);
        assert!((s[0] - 1.0).abs() < 1e-15 && s[1].abs() < 1e-15);
        // Axisymmetric D is the 3D isotropic law restricted to (rr, zz, rz, θθ): hydrostatic
        // strain (1, 1, 0, 1) gives 3K = E/(1−2ν) on each normal component.
        let d = m.elasticity(&Idealization::Axisymmetric);
        let s = d * nalgebra::Vector4::new(1.0, 1.0, 0.0, 1.0);
        for i in [0, 1, 3] {
            assert!((s[i] - 1.0 / (1.0 - 0.5)).abs() < 1e-14);
        }
    }
}
