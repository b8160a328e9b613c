//! The keys of a plastic material and of the global Newton (issue 40), read and checked.
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
//! ```

use super::RawAnalysis;
use crate::error::{CliResult, KeyPath, bail, err};
use crate::scene::MaterialSpec;
use fem_core::FemError;
use fem_core::plastic::{ConeMatch, DruckerPrager, DruckerPragerParameters};
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

/// `[analysis.newton]`, as read.
#[derive(Debug, Deserialize, Clone, Copy, Default)]
#[serde(deny_unknown_fields)]
pub struct RawNewton {
    tol: Option<f64>,
    max_iterations: Option<usize>,
    max_cuts: Option<usize>,
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
        })
    }
}

/// The plastic law of material `m` (at `p`, `materials[i]`), or `None` for an elastic one
/// (which refuses the plastic keys, naming them).
///
/// # Errors
/// A message at the key: a plastic key on another type, `friction_angle` outside `[0, 90)`,
/// `dilatancy_angle` outside `[0, φ]`, a negative `cohesion` (zero with `φ = 0`), a
/// `yield_stress` not > 0, or a missing required key.
pub fn plastic_law(p: &KeyPath, m: &MaterialSpec) -> CliResult<Option<DruckerPrager>> {
    let present = [
        ("friction_angle", m.friction_angle.is_some()),
        ("dilatancy_angle", m.dilatancy_angle.is_some()),
        ("cohesion", m.cohesion.is_some()),
        ("cone", m.cone.is_some()),
        ("yield_stress", m.yield_stress.is_some()),
    ];
    let accepted = match m.kind {
        MaterialKind::Elastic => "",
        MaterialKind::DruckerPrager => "friction_angle dilatancy_angle cohesion cone",
        MaterialKind::VonMises => "yield_stress",
    };
    let what = format!("a material of type \"{}\"", m.kind.name());
    super::keys::only(p, &what, &present, accepted)?;
    let (young, poisson) = (m.young, m.poisson);
    let law = match m.kind {
        MaterialKind::Elastic => return Ok(None),
        MaterialKind::VonMises => {
            let sp = p.key("yield_stress");
            let sigma_y = super::keys::need(p, &m.yield_stress, "yield_stress", &what)?;
            if !(sigma_y.is_finite() && sigma_y > 0.0) {
                bail!(sp, "`{sp}` = {sigma_y:?}: expected a finite stress > 0");
            }
            // the shear yield stress k = σ_y / √3
            DruckerPrager::von_mises(young, poisson, sigma_y / 3f64.sqrt())
        }
        MaterialKind::DruckerPrager => {
            let (fp, dp, cp) = (
                p.key("friction_angle"),
                p.key("dilatancy_angle"),
                p.key("cohesion"),
            );
            let phi = super::keys::need(p, &m.friction_angle, "friction_angle", &what)?;
            if !(phi.is_finite() && (0.0..90.0).contains(&phi)) {
                bail!(
                    fp,
                    "`{fp}` = {phi:?}: expected a friction angle φ in [0, 90) degrees"
                );
            }
            let theta = m.dilatancy_angle.unwrap_or(phi);
            if !(theta.is_finite() && theta >= 0.0) {
                bail!(
                    dp,
                    "`{dp}` = {theta:?}: expected a dilatancy angle θ ≥ 0 degrees"
                );
            }
            if theta > phi {
                bail!(
                    dp,
                    "`{dp}` = {theta:?}: the dilatancy angle θ must not exceed the friction \
                     angle φ = `{fp}` = {phi:?} (θ = φ is associated flow)"
                );
            }
            let c = super::keys::need(p, &m.cohesion, "cohesion", &what)?;
            if !(c.is_finite() && c >= 0.0) {
                bail!(cp, "`{cp}` = {c:?}: expected a finite cohesion c ≥ 0");
            }
            if c == 0.0 && phi == 0.0 {
                bail!(
                    cp,
                    "`{cp}` = 0 with `{fp}` = 0: a soil without friction needs a cohesion > 0"
                );
            }
            DruckerPrager::new(DruckerPragerParameters {
                young,
                poisson,
                friction_angle: phi,
                dilatancy_angle: theta,
                cohesion: c,
                cone: match m.cone.unwrap_or_default() {
                    ConeSpec::PlaneStrain => ConeMatch::PlaneStrain,
                    ConeSpec::Outer => ConeMatch::Outer,
                    ConeSpec::Inner => ConeMatch::Inner,
                },
            })
        }
    };
    law.map(Some).map_err(|e| match e {
        FemError::InvalidParameter {
            name,
            value,
            expected,
        } => {
            let kp = p.key(name);
            err!(kp, "`{kp}` = {value:?}: expected {expected}")
        }
        other => err!(p, "`{p}`: {other}"),
    })
}
