//! The seed's studies run by name (`[preset]`): the overrides checked into the specs of the
//! library's presets (`bipo::presets`), then the preset built and made a study.

use super::checks::{
    count, expect, finite, kind, law_error, non_negative, poisson, positive, set, solver_error,
};
use super::contact::{scheme, settings, theta};
use super::mesh::pile_sizes;
use super::outputs::check_outputs;
use super::phases::{Phase, phase};
use super::study::{Body, Library, PresetStudy, Study};
use crate::error::{CliResult, KeyPath, bail};
use crate::presets::{DelaminationSpec, Installation, PulloutSpec, ShearSpec};
use crate::scene::{OutputSpec, Scene};
use crate::spec::{InstallationSpec, PileOverride, Preset, RccmOverride, Site};
use contact_laws::{BetaScheme, ContactLaw, Rccm, RccmParams};
use contact_solver::SimulationSettings;

enum PresetSpec {
    Delamination(DelaminationSpec),
    Shear(ShearSpec),
    Pile(Box<PulloutSpec>),
}

/// A preset with its overrides checked.
pub(super) struct PresetPlan {
    spec: PresetSpec,
    settings: SimulationSettings,
}

/// A preset builds its own mesh, supports, loads, zones and steps: the scene may not give them.
fn preset_only(scene: &Scene) -> CliResult<()> {
    let present = [
        ("mesh", scene.mesh.is_some()),
        ("analysis", scene.analysis.is_some()),
        ("materials", !scene.materials.is_empty()),
        ("initial_stress", scene.initial_stress.is_some()),
        ("functions", !scene.functions.is_empty()),
        ("supports", !scene.supports.is_empty()),
        ("ties", !scene.ties.is_empty()),
        ("loads", !scene.loads.is_empty()),
        ("contact", !scene.contact.is_empty()),
        ("steps", scene.steps.is_some()),
        ("phases", !scene.phases.is_empty()),
    ];
    if let Some((k, _)) = present.iter().find(|(_, p)| *p) {
        bail!(
            KeyPath::root().key(k),
            "`{k}` cannot be combined with [preset]: the preset builds its own mesh, \
                 supports, loads, contact zone and steps (override them inside [preset])"
        );
    }
    Ok(())
}

/// The preset's RCCM parameters with the scene's overrides, checked.
fn override_rccm(
    path: &KeyPath,
    base: RccmParams,
    o: &Option<RccmOverride>,
) -> CliResult<RccmParams> {
    let Some(o) = o else { return Ok(base) };
    let scheme = match (o.scheme, o.theta) {
        (None, None) => base.scheme,
        (Some(s), t) => scheme(path, s, t)?,
        (None, Some(t)) => {
            let p = path.key("theta");
            if let BetaScheme::Theta(_) = base.scheme {
                BetaScheme::Theta(theta(&p, t)?)
            } else {
                bail!(p, "`{p}` is only read with scheme = \"theta\"");
            }
        }
    };
    let p = RccmParams {
        c_n: o.c_n.unwrap_or(base.c_n),
        c_t: o.c_t.unwrap_or(base.c_t),
        w: o.w.unwrap_or(base.w),
        alpha: o.alpha.unwrap_or(base.alpha),
        mu: o.mu.unwrap_or(base.mu),
        m: o.m.unwrap_or(base.m),
        beta_0: o.beta_0.unwrap_or(base.beta_0),
        scheme,
    };
    Rccm::new(p).map_err(|e| law_error(path, e))?;
    Ok(p)
}

/// Checks the preset's overrides (the scene may give nothing else but the title, units, solver,
/// outputs and plots).
pub(super) fn validate(scene: &Scene, preset: &Preset) -> CliResult<PresetPlan> {
    preset_only(scene)?;
    let settings = settings::<2>(&scene.solver)?;
    let p = KeyPath::root().key("preset");
    // the keys both plates have, checked in the order of the table, around the plate's own
    macro_rules! plate {
        ($spec:ident, $o:ident, $own:block) => {
            set!(p, $spec, length = $o.length, positive);
            set!(p, $spec, height = $o.height, positive);
            set!(p, $spec, young = $o.young, positive);
            set!(p, $spec, poisson = $o.poisson, poisson);
            set!(p, $spec, nx = $o.nx, count);
            set!(p, $spec, ny = $o.ny, count);
            if let Some(e) = $o.element {
                $spec.kind = kind(e);
            }
            $own
            set!(p, $spec, duration = $o.duration, positive);
            set!(p, $spec, steps = $o.steps, count);
            $spec.interface = override_rccm(&p.key("interface"), $spec.interface, &$o.interface)?;
        };
    }
    let spec = match preset {
        Preset::Delamination { plate, lift } => {
            let mut spec = DelaminationSpec::default();
            plate!(spec, plate, { set!(p, spec, lift = *lift, finite) });
            PresetSpec::Delamination(spec)
        }
        Preset::Shear { plate, press, push } => {
            let mut spec = ShearSpec::default();
            plate!(spec, plate, {
                set!(p, spec, press = *press, finite);
                set!(p, spec, push = *push, finite);
            });
            PresetSpec::Shear(spec)
        }
        Preset::Pile(o) => {
            if o.sectors.is_some() {
                let sp = p.key("sectors");
                bail!(
                    sp,
                    "`{sp}`: the 3D pile preset is served in a scene with a plastic soil (a \
                     [[materials]] of type \"drucker-prager\" and [analysis] type = \"3d\"); \
                     examples/pile_3d.rs runs the elastic one"
                );
            }
            PresetSpec::Pile(Box::new(pile(&p, o)?))
        }
    };
    Ok(PresetPlan { spec, settings })
}

/// The pile preset's spec with the overrides `o` (at `p`), checked (`sectors` is the plastic
/// scene's, [`super::plastic_preset`], and is left to its caller).
pub(super) fn pile(p: &KeyPath, o: &PileOverride) -> CliResult<PulloutSpec> {
    let mut spec = match o.site {
        Some(Site::Cran) => PulloutSpec::cran(),
        _ => PulloutSpec::plancoet(),
    };
    if o.coulomb {
        spec = spec.with_coulomb_interface();
    }
    set!(p, spec, pile_young = o.pile_young, positive);
    set!(p, spec, pile_poisson = o.pile_poisson, poisson);
    set!(p, spec, pile_unit_weight = o.pile_unit_weight, non_negative);
    set!(p, spec, soil_young = o.soil_young, positive);
    set!(p, spec, soil_poisson = o.soil_poisson, poisson);
    set!(p, spec, soil_unit_weight = o.soil_unit_weight, non_negative);
    set!(p, spec, k0 = o.k0, non_negative);
    set!(p, spec, head_displacement = o.head_displacement, finite);
    if let Some(v) = o.head_force {
        if o.head_displacement.is_some() {
            bail!(
                p.key("head_force"),
                "give either `head_displacement` (the head's u_z prescribed) or `head_force` \
                 (a jack force on the head, the pile held by the soil alone), not both"
            );
        }
        spec.head_force = Some(finite(&p.key("head_force"), v)?);
    }
    set!(p, spec, steps = o.steps, count);
    set!(p, spec, alert_distance = o.alert_distance, non_negative);
    if let Some(i) = o.installation {
        let ip = p.key("installation").key("value");
        spec.installation = match i {
            InstallationSpec::None {} => Installation::None,
            InstallationSpec::RadialDisplacement { value } => {
                Installation::RadialDisplacement(non_negative(&ip, value)?)
            }
            InstallationSpec::NormalForceRatio { value } => {
                let ok = value.is_finite() && value >= 1.0;
                Installation::NormalForceRatio(expect(&ip, value, ok, "a finite ratio >= 1")?)
            }
        };
    }
    if let Some(m) = &o.mesh {
        pile_sizes(&p.key("mesh"), &mut spec.mesh, m)?;
    }
    spec.interface = override_rccm(&p.key("interface"), spec.interface, &o.interface)?;
    Ok(spec)
}

/// Builds the preset of `plan` (`[preset]` in the error) and makes it a study of `scene`.
pub(super) fn build(scene: &Scene, plan: PresetPlan) -> CliResult<Study> {
    let p = KeyPath::root().key("preset");
    let settings = plan.settings;
    match plan.spec {
        PresetSpec::Delamination(spec) => {
            let built = spec.build(settings).map_err(|e| solver_error(&p, e))?;
            finish(scene, "delamination", Library::Seed(Box::new(built)), None)
        }
        PresetSpec::Shear(spec) => {
            let built = spec.build(settings).map_err(|e| solver_error(&p, e))?;
            finish(scene, "shear", Library::Seed(Box::new(built)), None)
        }
        PresetSpec::Pile(spec) => {
            let steps = spec.steps;
            let built = spec.build(settings).map_err(|e| solver_error(&p, e))?;
            let phases = vec![
                phase("geostatic", 1, 0.0, 1.0),
                phase("installation", 1, 1.0, 2.0),
                phase("pullout", steps, 2.0, 2.0 + steps as f64),
            ];
            finish(scene, "pile", Library::Pile(Box::new(built)), Some(phases))
        }
    }
}

/// The study of a built preset: its zones, laws and phases, with the outputs checked.
fn finish(
    scene: &Scene,
    kind: &'static str,
    lib: Library,
    phases: Option<Vec<Phase>>,
) -> CliResult<Study> {
    let phases = match (phases, &lib) {
        (Some(p), _) => p,
        (None, Library::Seed(s)) => vec![phase("loading", s.steps, 0.0, s.duration)],
        (None, Library::Pile(_)) => unreachable!("pile phases are given"),
    };
    let study_preset = PresetStudy { kind, scene: lib };
    let sim = study_preset.sim();
    let zone_names: Vec<String> = sim.zones().iter().map(|z| z.name.clone()).collect();
    let adhesive_zones = sim.zones().iter().filter(|z| z.law.has_adhesion()).count();
    let friction_zones = sim.zones().iter().filter(|z| z.law.has_friction()).count();
    let zone_laws = sim
        .zones()
        .iter()
        .map(|z| {
            if z.law.has_adhesion() {
                "rccm"
            } else if z.law.has_friction() {
                "rccm (coulomb)"
            } else {
                "rccm (signorini)"
            }
            .to_string()
        })
        .collect();
    let mut study = Study {
        title: scene
            .title
            .clone()
            .unwrap_or_else(|| format!("preset {kind}")),
        units: scene.units.clone().unwrap_or_default(),
        body: Body::Preset(Box::new(study_preset)),
        phases,
        output: OutputSpec {
            // the pile writes its soil mesh unless told not to
            mesh_vtk: scene.output.mesh_vtk.or(Some(kind == "pile")),
            ..scene.output.clone()
        },
        plots: Vec::new(),
        zone_names,
        zone_laws,
        adhesive_zones,
        friction_zones,
        warnings: Vec::new(),
        hertz: None,
    };
    check_outputs(scene, &mut study)?;
    Ok(study)
}
