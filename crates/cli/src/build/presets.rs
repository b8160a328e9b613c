//! The seed's studies run by name (`[preset]`): the overrides checked into the specs of the
//! library's presets (`bipo::presets`), then the preset built and made a study.

use super::checks::{
    at_least, expect, finite, kind, law_error, non_negative, poisson, positive, solver_error,
};
use super::contact::{rccm_params, settings};
use super::outputs::check_outputs;
use super::phases::{Phase, phase};
use super::study::{Body, Library, PresetStudy, Study};
use crate::error::{CliResult, KeyPath, bail};
use crate::presets::{DelaminationSpec, Installation, PulloutSpec, ShearSpec};
use crate::scene::{OutputSpec, Scene};
use crate::spec::{InstallationSpec, Preset, RccmOverride, RccmSpec, Site};
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
        (Some(s), t) => {
            let spec = RccmSpec {
                c_n: 0.0,
                c_t: 0.0,
                w: 0.0,
                alpha: 0.0,
                mu: 0.0,
                m: 1,
                beta_0: 1.0,
                scheme: s,
                theta: t,
            };
            rccm_params(path, &spec)?.scheme
        }
        (None, Some(t)) => {
            let p = path.key("theta");
            if let BetaScheme::Theta(_) = base.scheme {
                BetaScheme::Theta(expect(
                    &p,
                    t,
                    (0.0..=1.0).contains(&t),
                    "a value in [0, 1]",
                )?)
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
    if let Preset::Pile { .. } = preset {
        return validate_pile(scene, preset);
    }
    let settings = settings::<2>(&scene.solver)?;
    let p = KeyPath::root().key("preset");
    macro_rules! set {
        ($spec:ident.$field:ident = $v:expr, $check:expr) => {
            if let Some(v) = $v {
                $spec.$field = $check(&p.key(stringify!($field)), v)?;
            }
        };
    }
    let count = |p: &KeyPath, v| at_least(p, v, 1);
    // the keys both plates have, checked in the order of the table, around the plate's own
    macro_rules! plate {
        ($spec:ident, $o:ident, $own:block) => {
            set!($spec.length = $o.length, positive);
            set!($spec.height = $o.height, positive);
            set!($spec.young = $o.young, positive);
            set!($spec.poisson = $o.poisson, poisson);
            set!($spec.nx = $o.nx, count);
            set!($spec.ny = $o.ny, count);
            if let Some(e) = $o.element {
                $spec.kind = kind(e);
            }
            $own
            set!($spec.duration = $o.duration, positive);
            set!($spec.steps = $o.steps, count);
            $spec.interface = override_rccm(&p.key("interface"), $spec.interface, &$o.interface)?;
        };
    }
    let spec = match preset {
        Preset::Delamination { plate, lift } => {
            let mut spec = DelaminationSpec::default();
            plate!(spec, plate, { set!(spec.lift = *lift, finite) });
            PresetSpec::Delamination(spec)
        }
        Preset::Shear { plate, press, push } => {
            let mut spec = ShearSpec::default();
            plate!(spec, plate, {
                set!(spec.press = *press, finite);
                set!(spec.push = *push, finite);
            });
            PresetSpec::Shear(spec)
        }
        Preset::Pile { .. } => unreachable!("handled above"),
    };
    Ok(PresetPlan { spec, settings })
}

/// Checks the pile preset's overrides.
// A flat list of optional overrides, each with its own check: clearer in one place than split.
fn validate_pile(scene: &Scene, preset: &Preset) -> CliResult<PresetPlan> {
    let Preset::Pile {
        site,
        coulomb,
        pile_young,
        pile_poisson,
        pile_unit_weight,
        soil_young,
        soil_poisson,
        soil_unit_weight,
        k0,
        installation,
        head_displacement,
        head_force,
        steps,
        alert_distance,
        interface,
        mesh,
    } = preset
    else {
        unreachable!("called for the pile preset")
    };
    let settings = settings::<2>(&scene.solver)?;
    let p = KeyPath::root().key("preset");
    let mut spec = match site {
        Some(Site::Cran) => PulloutSpec::cran(),
        _ => PulloutSpec::plancoet(),
    };
    if *coulomb {
        spec = spec.with_coulomb_interface();
    }
    for (name, value, slot, is_poisson) in [
        ("pile_young", pile_young, &mut spec.pile_young, false),
        ("pile_poisson", pile_poisson, &mut spec.pile_poisson, true),
        (
            "pile_unit_weight",
            pile_unit_weight,
            &mut spec.pile_unit_weight,
            false,
        ),
        ("soil_young", soil_young, &mut spec.soil_young, false),
        ("soil_poisson", soil_poisson, &mut spec.soil_poisson, true),
        (
            "soil_unit_weight",
            soil_unit_weight,
            &mut spec.soil_unit_weight,
            false,
        ),
    ] {
        if let Some(v) = value {
            *slot = if is_poisson {
                poisson(&p.key(name), *v)?
            } else if name.ends_with("unit_weight") {
                non_negative(&p.key(name), *v)?
            } else {
                positive(&p.key(name), *v)?
            };
        }
    }
    if let Some(v) = k0 {
        spec.k0 = non_negative(&p.key("k0"), *v)?;
    }
    if let Some(v) = head_displacement {
        spec.head_displacement = finite(&p.key("head_displacement"), *v)?;
    }
    if let Some(v) = head_force {
        if head_displacement.is_some() {
            bail!(
                p.key("head_force"),
                "give either `head_displacement` (the head's u_z prescribed) or `head_force` \
                 (a jack force on the head, the pile held by the soil alone), not both"
            );
        }
        spec.head_force = Some(finite(&p.key("head_force"), *v)?);
    }
    if let Some(v) = steps {
        spec.steps = at_least(&p.key("steps"), *v, 1)?;
    }
    if let Some(v) = alert_distance {
        spec.alert_distance = non_negative(&p.key("alert_distance"), *v)?;
    }
    if let Some(i) = installation {
        let ip = p.key("installation").key("value");
        spec.installation = match i {
            InstallationSpec::None {} => Installation::None,
            InstallationSpec::RadialDisplacement { value } => {
                Installation::RadialDisplacement(non_negative(&ip, *value)?)
            }
            InstallationSpec::NormalForceRatio { value } => Installation::NormalForceRatio(expect(
                &ip,
                *value,
                value.is_finite() && *value >= 1.0,
                "a finite ratio >= 1",
            )?),
        };
    }
    if let Some(m) = mesh {
        let mp = p.key("mesh");
        if let Some(e) = m.element {
            spec.mesh.kind = kind(e);
        }
        for (name, value, slot) in [
            ("diameter", m.diameter, &mut spec.mesh.diameter),
            ("length", m.length, &mut spec.mesh.length),
            ("width", m.width, &mut spec.mesh.width),
            ("depth", m.depth, &mut spec.mesh.depth),
        ] {
            if let Some(v) = value {
                *slot = positive(&mp.key(name), v)?;
            }
        }
        for (name, value, slot) in [
            ("cells_pile_r", m.cells_pile_r, &mut spec.mesh.cells_pile_r),
            ("cells_soil_r", m.cells_soil_r, &mut spec.mesh.cells_soil_r),
            ("cells_shaft", m.cells_shaft, &mut spec.mesh.cells_shaft),
            (
                "cells_below_tip",
                m.cells_below_tip,
                &mut spec.mesh.cells_below_tip,
            ),
        ] {
            if let Some(v) = value {
                *slot = at_least(&mp.key(name), v, 1)?;
            }
        }
    }
    spec.interface = override_rccm(&p.key("interface"), spec.interface, interface)?;
    Ok(PresetPlan {
        spec: PresetSpec::Pile(Box::new(spec)),
        settings,
    })
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
