//! Materials whose stress depends on their history (issue 40): the material-point seam.
//!
//! A [`ConstitutivePoint`] is the law of one quadrature point. It is written in 3D, on Voigt
//! vectors ordered `[xx, yy, zz, xy, yz, zx]` with **engineering** shear strains
//! (`γ_xy = 2 ε_xy`) and tensor shear stresses, so that `σ · ε̇` is the power per volume.
//! The 2D idealisations map onto it:
//!
//! | idealisation | strain given to the point | stress used by the element |
//! |---|---|---|
//! | plane strain | `[ε_xx, ε_yy, 0, γ_xy, 0, 0]` | `[σ_xx, σ_yy, σ_xy]` (`σ_zz` kept in the state) |
//! | axisymmetric `(r, z)` | `[ε_rr, ε_zz, ε_θθ, γ_rz, 0, 0]` | `[σ_rr, σ_zz, σ_rz, σ_θθ]` |
//! | 3D | the full vector | the full vector |
//!
//! Plane stress is not served by the plastic seam.
//!
//! # Contract of an update
//! [`ConstitutivePoint::update`] evaluates a **trial** state from the last **committed** one
//! and the total strain; it never changes `committed` (a rejected Newton iterate or a cut step
//! costs nothing to undo). The elastic predictor is incremental,
//! `σ_trial = σ_committed + C (ε − ε_committed)`, so a committed state may carry an initial
//! (geostatic) stress with zero strain. The tangent it writes is the **consistent** one
//! (`dσ/dε` of the discrete update), which gives the global Newton its quadratic rate.

use crate::error::{FemError, non_negative, positive};

mod drucker_prager;
#[cfg(test)]
mod drucker_prager_tests;
mod model;
mod model_initial;
mod model_lu;
mod model_post;
mod model_reaction;
mod model_springs;
#[cfg(test)]
mod model_tangent_tests;
#[cfg(test)]
mod model_tests;
pub mod newton;

pub use drucker_prager::{ConeMatch, DruckerPrager, DruckerPragerParameters};
pub use model::PlasticModel;
pub use model_lu::TangentKind;
pub use model_post::PlasticOutputs;

/// A symmetric tensor in Voigt order `[xx, yy, zz, xy, yz, zx]` (module docs): engineering
/// shears for strains, tensor shears for stresses.
pub type Voigt = [f64; 6];

/// A 6×6 matrix on Voigt vectors, row-major: `tangent[i][j] = ∂σ_i/∂ε_j`.
pub type VoigtMatrix = [[f64; 6]; 6];

/// The state of one material point: what a plastic body keeps per quadrature point, twice
/// (committed and trial).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[non_exhaustive]
pub struct PointState {
    /// The total strain.
    pub strain: Voigt,
    /// The stress.
    pub stress: Voigt,
    /// The plastic strain (engineering shears, as `strain`).
    pub plastic_strain: Voigt,
    /// The accumulated equivalent plastic strain (a non-decreasing scalar; its definition is
    /// the law's).
    pub equivalent_plastic_strain: f64,
    /// Whether the last update that produced this state was plastic.
    pub yielding: bool,
}

impl PointState {
    /// A point at zero strain carrying the (initial, e.g. geostatic) `stress`.
    pub fn with_stress(stress: Voigt) -> Self {
        Self {
            stress,
            ..Self::default()
        }
    }
}

/// The constitutive law of one material point (module docs for the conventions and the
/// contract of an update).
pub trait ConstitutivePoint: Send + Sync + core::fmt::Debug {
    /// The elastic tangent `C` (`σ = C ε` while elastic).
    fn elastic_tangent(&self) -> VoigtMatrix;

    /// From `committed` and the total `strain`, writes the trial state into `trial` and the
    /// consistent tangent `dσ/dε` into `tangent`.
    ///
    /// # Errors
    /// [`FemError::InvalidParameter`] naming `strain` for a non-finite strain, or the law's own when
    /// the update cannot be made (named).
    fn update(
        &self,
        committed: &PointState,
        strain: &Voigt,
        trial: &mut PointState,
        tangent: &mut VoigtMatrix,
    ) -> Result<(), FemError>;

    /// The yield function at `stress`: `≤ 0` for an admissible stress (`0` on the surface),
    /// in units of stress. A law with no yield surface returns `f64::NEG_INFINITY`.
    fn yield_function(&self, stress: &Voigt) -> f64;

    /// Whether the consistent tangent [`ConstitutivePoint::update`] writes is always
    /// symmetric (an associated law): a body of such laws factorises it with a Cholesky
    /// ([`TangentKind`]). `true` unless the law says otherwise.
    fn symmetric_tangent(&self) -> bool {
        true
    }
}

/// Isotropic linear elasticity as a [`ConstitutivePoint`] (no yield surface): the plastic
/// seam's reference, which must reproduce the elastic model's answers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinearElasticPoint {
    young: f64,
    poisson: f64,
}

impl LinearElasticPoint {
    /// Young's modulus `young > 0` and Poisson's ratio `0 ≤ poisson < 1/2`.
    ///
    /// # Errors
    /// [`FemError::InvalidParameter`] naming `young` or `poisson`.
    pub fn new(young: f64, poisson: f64) -> Result<Self, FemError> {
        let young = positive("young", young)?;
        let poisson = non_negative("poisson", poisson)?;
        if poisson >= 0.5 {
            return Err(FemError::InvalidParameter {
                name: "poisson",
                value: poisson,
                expected: "a value in [0, 0.5)",
            });
        }
        Ok(Self { young, poisson })
    }
}

/// Refuses a strain with a non-finite component ([`FemError::InvalidParameter`] naming
/// `strain`): the first check of every update.
pub(crate) fn check_strain(strain: &Voigt) -> Result<(), FemError> {
    match strain.iter().find(|v| !v.is_finite()) {
        Some(bad) => Err(FemError::InvalidParameter {
            name: "strain",
            value: *bad,
            expected: "finite components",
        }),
        None => Ok(()),
    }
}

/// The isotropic elastic tangent of `young` and `poisson` on Voigt vectors (engineering shears).
pub fn isotropic_tangent(young: f64, poisson: f64) -> VoigtMatrix {
    let lambda = young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
    let g = young / (2.0 * (1.0 + poisson));
    let mut c = [[0.0; 6]; 6];
    for (i, row) in c.iter_mut().enumerate().take(3) {
        row[..3].fill(lambda);
        row[i] += 2.0 * g;
    }
    for (i, row) in c.iter_mut().enumerate().skip(3) {
        row[i] = g;
    }
    c
}

impl ConstitutivePoint for LinearElasticPoint {
    fn elastic_tangent(&self) -> VoigtMatrix {
        isotropic_tangent(self.young, self.poisson)
    }

    fn update(
        &self,
        committed: &PointState,
        strain: &Voigt,
        trial: &mut PointState,
        tangent: &mut VoigtMatrix,
    ) -> Result<(), FemError> {
        check_strain(strain)?;
        *tangent = self.elastic_tangent();
        *trial = *committed;
        trial.strain = *strain;
        for (i, row) in tangent.iter().enumerate() {
            let dot: f64 = (0..6)
                .map(|j| row[j] * (strain[j] - committed.strain[j]))
                .sum();
            trial.stress[i] = committed.stress[i] + dot;
        }
        trial.yielding = false;
        Ok(())
    }

    fn yield_function(&self, _stress: &Voigt) -> f64 {
        f64::NEG_INFINITY
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Uniaxial strain from a prestressed state adds `C ε` to the initial stress exactly
    /// (tolerance: round-off of one 6-term dot product).
    #[test]
    fn elastic_point_is_incremental_from_the_committed_stress() {
        let point = LinearElasticPoint::new(200.0, 0.25).unwrap();
        let committed = PointState::with_stress([-1.0, -1.0, -2.0, 0.0, 0.0, 0.0]);
        let (mut trial, mut tangent) = (PointState::default(), [[0.0; 6]; 6]);
        point
            .update(
                &committed,
                &[1e-3, 0.0, 0.0, 2e-3, 0.0, 0.0],
                &mut trial,
                &mut tangent,
            )
            .unwrap();
        // λ = 80, G = 80: σ_xx = −1 + 240e-3, σ_yy = −1 + 80e-3, σ_xy = 80·2e-3
        let expected = [-0.76, -0.92, -1.92, 0.16, 0.0, 0.0];
        for (s, e) in trial.stress.iter().zip(expected) {
            assert!((s - e).abs() < 1e-14, "{s} vs {e}");
        }
        assert_eq!(
            committed.strain, [0.0; 6],
            "the committed state is untouched"
        );
        assert!(
            point
                .update(&committed, &[f64::NAN; 6], &mut trial, &mut tangent)
                .is_err()
        );
        assert!(LinearElasticPoint::new(1.0, 0.5).is_err());
    }
}
