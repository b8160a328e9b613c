//! From a parsed [`Scene`] to a ready-to-step [`Study`], in two passes.
//!
//! 1. [`validate`] checks every value with its key path and gives a validated scene: the
//!    generator's spec of the mesh, the materials, supports, loads, laws and targets, the solver
//!    settings and phases (or a preset's checked overrides).
//! 2. The build makes, from it, through the library's public API: the mesh ([`mesh`]), the model
//!    ([`model`]), the contact zones, their recognition and the simulation ([`contact`]), or the
//!    preset ([`presets`]); then [`outputs`] checks `[output]` and the plots against the study.
//!    The checks that need the mesh or the study (node and edge sets, regions, candidates within
//!    the alert distance, contactor nodes of the plots) are made there, still with key paths.
//!
//! [`checks`] holds the value checks and error conversions, [`phases`] the time functions and
//! phases, [`study`] what a build gives: one [`Study`] type for both dimensions (`Study<3>` for
//! a 3D scene, `[analysis] type = "3d"`, whose two passes [`solid`] lists: it reuses the checks
//! that do not depend on the dimension).

mod checks;
mod contact;
mod curves;
mod dim;
mod dynamic;
mod hertz;
mod mesh;
mod model;
mod outputs;
mod phases;
mod plastic;
mod plastic_preset;
mod presets;
mod solid;
mod study;
mod supported;
mod validate;

pub use checks::kind_name;
pub(crate) use dim::SceneDim;
pub use dynamic::{DynamicSim, DynamicStudy};
pub use hertz::{HertzPlan, HertzShape};
pub use phases::{
    Phase, PhaseLaw, TimeFunction, describe_laws, final_law, function_value, laws_by_phase,
    phase_law_names,
};
pub(crate) use plastic::add_load;
pub use plastic::{PlasticSim, PlasticStudy};
pub(crate) use study::on_sim;
pub use study::{
    Body, Custom, Library, LoadRt, NoPreset, PresetStudy, Study, StudyDim, SupportRt, released_at,
};

use crate::error::{CliError, CliResult, KeyPath};
use crate::scene::Scene;
use std::path::PathBuf;
use validate::{Plan, Validated};

/// A scene file read from disk.
pub struct Loaded {
    pub path: PathBuf,
    /// Its text.
    pub source: String,
    /// Its content.
    pub scene: Scene,
}

/// Parses scene text.
pub fn parse(source: &str) -> CliResult<Scene> {
    let de = toml::Deserializer::parse(source).map_err(|e| CliError {
        span: e.span(),
        ..CliError::input(format!("invalid TOML: {}", e.message()))
    })?;
    serde_path_to_error::deserialize(de).map_err(|e| {
        let path = e.path().to_string();
        let inner = e.into_inner();
        let message = inner.message().trim_end().to_string();
        let message = if path.is_empty() || path == "." {
            message
        } else {
            format!("`{path}`: {message}")
        };
        CliError {
            span: inner.span(),
            ..CliError::input(message)
        }
    })
}

/// A built scene: 2D (a scene described key by key or a preset) or 3D: the one place where
/// the dimension is chosen.
pub enum Built {
    /// A 2D study.
    Plane(Box<Study>),
    /// A 3D study (`[analysis] type = "3d"`).
    Solid(Box<Study<3>>),
    /// A 2D dynamic study (`[analysis] dynamic = true`).
    PlaneDynamic(Box<DynamicStudy<2>>),
    /// A 3D dynamic study.
    SolidDynamic(Box<DynamicStudy<3>>),
    /// A 2D study with a plastic material (plane strain or axisymmetric).
    PlanePlastic(Box<PlasticStudy<2>>),
    /// A 3D study with a plastic material.
    SolidPlastic(Box<PlasticStudy<3>>),
}

/// The study's title: the scene's `title`, else the file's stem.
fn title(loaded: &Loaded) -> String {
    loaded.scene.title.clone().unwrap_or_else(|| {
        loaded
            .path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default()
    })
}

/// Validates the scene and builds the study (mesh, model, zones, recognition, simulation).
pub fn build(loaded: &Loaded) -> CliResult<Built> {
    let scene = &loaded.scene;
    // `[analysis] linear_solver` (how bipo was built and launched is the command's to check)
    if let Some(a) = &scene.analysis {
        a.linear_solver(&KeyPath::root().key("analysis"))?;
    }
    if !plastic::is_plastic(scene) {
        plastic::refuse_in_elastic(scene)?;
    }
    if let Some(a) = scene.analysis.as_ref().filter(|a| a.is_dynamic()) {
        if let Some(i) = scene
            .materials
            .iter()
            .position(|m| m.kind != crate::raw::MaterialKind::Elastic)
        {
            let p = KeyPath::root().key("materials").index(i).key("type");
            crate::error::bail!(
                p,
                "`{p}`: a plastic material is not served by a dynamic scene"
            );
        }
        return Ok(if a.is_solid() {
            Built::SolidDynamic(Box::new(dynamic::build::<3>(loaded)?))
        } else {
            Built::PlaneDynamic(Box::new(dynamic::build::<2>(loaded)?))
        });
    }
    dynamic::refuse_in_static(scene)?;
    if plastic::is_plastic(scene) {
        let solid = scene.analysis.as_ref().is_some_and(|a| a.is_solid());
        if scene.preset.is_some() {
            return Ok(if solid {
                Built::SolidPlastic(Box::new(plastic_preset::build::<3>(loaded)?))
            } else {
                Built::PlanePlastic(Box::new(plastic_preset::build::<2>(loaded)?))
            });
        }
        return Ok(if solid {
            Built::SolidPlastic(Box::new(plastic::build::<3>(loaded)?))
        } else {
            Built::PlanePlastic(Box::new(plastic::build::<2>(loaded)?))
        });
    }
    if scene.preset.is_none() && scene.analysis.as_ref().is_some_and(|a| a.is_solid()) {
        return Ok(Built::Solid(Box::new(solid::build(loaded)?)));
    }
    let study = match validate::validate(scene, &loaded.path)? {
        Validated::Preset(plan) => presets::build(scene, *plan)?,
        Validated::Custom(plan) => build_custom(loaded, *plan)?,
    };
    Ok(Built::Plane(Box::new(study)))
}

/// Builds a scene described key by key from its validated form.
fn build_custom(loaded: &Loaded, plan: Plan) -> CliResult<Study> {
    let scene = &loaded.scene;
    let Plan {
        functions,
        phases,
        mesh,
        model,
        contact,
    } = plan;
    let (idealization, _) = model.options;
    let mesh = mesh::build(&KeyPath::root().key("mesh"), mesh, Some(idealization))?;
    let mut study = custom_study(loaded, mesh, model, functions, phases, contact)?;
    outputs::check_outputs(scene, &mut study)?;
    Ok(study)
}

/// The study of a scene described key by key from its mesh and validated plans (the model,
/// the zones and the simulation built), before its `[output]` and plots are checked.
fn custom_study<const D: usize>(
    loaded: &Loaded,
    mesh: fem_core::Mesh<D>,
    model: model::ModelPlan<D>,
    functions: std::collections::BTreeMap<String, TimeFunction>,
    phases: Vec<Phase>,
    contact: contact::ContactPlan<D>,
) -> CliResult<Study<D>>
where
    fem_core::Dim<D>: StudyDim<D> + SceneDim<D>,
{
    let mut model = model;
    // a run whose solves are PETSc's holds no factor (`app_mpi` sets the solver)
    if let Some(a) = &loaded.scene.analysis
        && let Ok(crate::raw::LinearSolverSpec::Petsc(_)) = a.linear_solver(&KeyPath::root())
    {
        model.solves = model::Solves::External;
    }
    let (model, supports, loads) = model::build(mesh, model, &functions, &phases)?;
    let (sim, zone_laws, warnings) = contact::build(model, &contact.zones, contact.settings)?;
    let custom = Custom {
        sim,
        supports,
        loads,
        functions,
        phase_laws: contact.phase_laws,
    };
    Ok(Study {
        title: title(loaded),
        units: loaded.scene.units.clone().unwrap_or_default(),
        zone_names: custom.sim.zones().iter().map(|z| z.name.clone()).collect(),
        body: Body::Custom(Box::new(custom)),
        phases,
        output: loaded.scene.output.clone(),
        plots: Vec::new(),
        zone_laws,
        adhesive_zones: contact.adhesive,
        friction_zones: contact.friction,
        warnings,
        hertz: None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parse_rejects_unknown_keys_with_a_span() {
        let e = parse("title = \"x\"\ncolour = 1\n").unwrap_err();
        assert!(
            e.message.contains("unknown field `colour`"),
            "{}",
            e.message
        );
        assert_eq!(e.span.map(|s| s.start), Some(12));
    }
}
