//! The keys of a plastic material and of the global Newton (issue 40), read; the Newton's
//! checked here, the material's by `build::plastic` (which reads the materials' table).
//!
//! ```text
//! [[materials]]
//! region = 0
//! type = "drucker-prager"      # or "elastic" (the default), "von-mises"
//! young = 1e4
//! poisson = 0.3
//! friction_angle = 20.0        # φ in degrees, 0 ≤ φ < 90
//! dilatancy_angle = 20.0       # θ in degrees, 0 ≤ θ ≤ φ (default φ: associated flow)
//! cohesion = 1.0               # c ≥ 0 (> 0 when φ = 0)
//! cone = "plane-strain"        # or "outer", "inner": how the cone matches Mohr–Coulomb
//! # type = "von-mises" takes `yield_stress` (uniaxial σ_y) instead of the four keys above
//!
//! [analysis.newton]            # only with a plastic material; every key optional
//! tol = 1e-9                   # relative equilibrium residual
//! max_iterations = 12          # Newton corrections per step
//! max_cuts = 8                 # halvings of a step that does not converge
//! tangent = "exact"            # or "symmetric" (default: symmetric for associated laws)
//! ```

use super::RawAnalysis;
use crate::error::{CliResult, KeyPath, bail};
use fem_core::plastic::ConeMatch;
use serde::Deserialize;

/// `[[materials]] type`.
#[derive(Debug, Deserialize, Clone, Copy, PartialEq, Eq, Default)]
#[serde(rename_all = "kebab-case")]
pub enum MaterialKind {
    /// Linear elastic (the default).
    #[default]
    Elastic,
    /// Non-associated Drucker–Prager with perfect plasticity
    /// ([`fem_core::plastic::DruckerPrager`]).
    DruckerPrager,
    /// Von Mises, as Drucker–Prager with `φ = θ = 0` ([`DruckerPrager::von_mises`]).
    VonMises,
}

impl MaterialKind {
    /// The name in a scene file.
    pub fn name(self) -> &'static str {
        match self {
            Self::Elastic => "elastic",
            Self::DruckerPrager => "drucker-prager",
            Self::VonMises => "von-mises",
        }
    }
}

/// `[[materials]] cone`: how the Drucker–Prager cone matches Mohr–Coulomb ([`ConeMatch`]).
#[derive(Debug, Deserialize, Clone, Copy, PartialEq, Eq, Default)]
#[serde(rename_all = "kebab-case")]
pub enum ConeSpec {
    /// [`ConeMatch::PlaneStrain`] (the seed's, the default).
    #[default]
    PlaneStrain,
    /// [`ConeMatch::Outer`].
    Outer,
    /// [`ConeMatch::Inner`].
    Inner,
}

impl ConeSpec {
    /// The library's match.
    pub fn cone_match(self) -> ConeMatch {
        match self {
            Self::PlaneStrain => ConeMatch::PlaneStrain,
            Self::Outer => ConeMatch::Outer,
            Self::Inner => ConeMatch::Inner,
        }
    }
}

/// `[analysis.newton] tangent`: which tangent the plastic body factorises
/// ([`fem_core::plastic::TangentKind`]).
#[derive(Debug, Deserialize, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum TangentSpec {
    /// The symmetric part, by Cholesky (the default for associated laws).
    Symmetric,
    /// The consistent tangent itself, by LU (the default for a non-associated law; it also
    /// factorises an indefinite tangent near collapse).
    Exact,
}

/// `[analysis.newton]`, as read.
#[derive(Debug, Deserialize, Clone, Copy, Default)]
#[serde(deny_unknown_fields)]
pub struct RawNewton {
    tol: Option<f64>,
    max_iterations: Option<usize>,
    max_cuts: Option<usize>,
    tangent: Option<TangentSpec>,
}

/// The Newton settings a plastic scene runs with, checked.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NewtonSpec {
    /// The relative equilibrium residual.
    pub tol: f64,
    /// Newton corrections per step.
    pub max_iterations: usize,
    /// Halvings of a step (the run's, over its time and its prescribed values).
    pub max_cuts: usize,
    /// The tangent asked for (`None`: the body's default).
    pub tangent: Option<fem_core::plastic::TangentKind>,
}

/// The most halvings of one step (a step of `2⁻⁴⁰` of its size is below any load's meaning).
const MAX_CUTS: usize = 40;

impl RawAnalysis {
    /// Whether `[analysis.newton]` is given.
    pub fn has_newton(&self) -> bool {
        self.newton.is_some()
    }

    /// The Newton settings of a plastic scene (`p` is `analysis`): the library's defaults
    /// (`contact_solver::NewtonSettings`) where a key is left out.
    pub fn newton(&self, p: &KeyPath) -> CliResult<NewtonSpec> {
        let d = contact_solver::NewtonSettings::default();
        let raw = self.newton.unwrap_or_default();
        let np = p.key("newton");
        let tol = raw.tol.unwrap_or(d.tol);
        if !(tol > 0.0 && tol < 1.0) {
            let kp = np.key("tol");
            bail!(
                kp,
                "`{kp}` = {tol:?}: expected a relative residual in (0, 1)"
            );
        }
        let max_iterations = raw.max_iterations.unwrap_or(d.max_iterations);
        if max_iterations == 0 {
            let kp = np.key("max_iterations");
            bail!(kp, "`{kp}` = 0: expected at least 1 correction per step");
        }
        let max_cuts = raw.max_cuts.unwrap_or(d.max_cuts);
        if max_cuts > MAX_CUTS {
            let kp = np.key("max_cuts");
            bail!(kp, "`{kp}` = {max_cuts}: expected at most {MAX_CUTS}");
        }
        Ok(NewtonSpec {
            tol,
            max_iterations,
            max_cuts,
            tangent: raw.tangent.map(|t| match t {
                TangentSpec::Symmetric => fem_core::plastic::TangentKind::Symmetric,
                TangentSpec::Exact => fem_core::plastic::TangentKind::Exact,
            }),
        })
    }
    /// `[analysis]` (at `p`) of a scene with the pile preset and a plastic soil: its `type`
    /// (`"axisymmetric"`, or `"3d"`: whether the quarter is built) and `newton`, no other key.
    pub fn pile_preset_is_solid(&self, p: &KeyPath) -> CliResult<bool> {
        let present = super::keys::present!(self; thickness, floating, dynamic, time_step,
            end_time, theta, mass, rayleigh_alpha, rayleigh_beta, newton);
        super::keys::only(
            p,
            "the [analysis] of a pile preset with a plastic soil",
            &present,
            "newton",
        )?;
        match self.kind {
            super::AnalysisKind::Axisymmetric => Ok(false),
            super::AnalysisKind::Solid => Ok(true),
            _ => {
                let tp = p.key("type");
                crate::error::bail!(
                    tp,
                    "`{tp}`: the pile preset with a plastic soil is \"axisymmetric\" or \"3d\" \
                     (a quarter of `[preset] sectors` sectors)"
                );
            }
        }
    }
}
