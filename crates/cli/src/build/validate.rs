//! The validation pass: from the parsed [`Scene`] to a [`Validated`] one, every value checked
//! with its key path (types and keys of the tagged tables, numbers, names of functions, phases,
//! supports and loads, laws and target geometry, solver settings, a preset's overrides), before
//! anything is built. What only the mesh or the built study can tell (node and edge sets,
//! regions, candidates, the plots' nodes) is checked by the build that follows.

use super::checks::positive;
use super::contact::{self, ContactPlan};
use super::mesh::{self, MeshPlan};
use super::model::{self, ModelPlan};
use super::phases::{Phase, TimeFunction, phases_of, time_functions};
use super::presets::{self, PresetPlan};
use crate::error::{CliError, CliResult, KeyPath, bail};
use crate::scene::Scene;
use crate::spec::Analysis;
use fem_core::Idealization;
use std::collections::BTreeMap;
use std::path::Path;

/// A scene whose values are checked, ready to build.
pub(super) enum Validated {
    /// A scene described key by key.
    Custom(Box<Plan>),
    Preset(Box<PresetPlan>),
}

/// A scene described key by key, checked.
pub(super) struct Plan {
    pub(super) functions: BTreeMap<String, TimeFunction>,
    pub(super) phases: Vec<Phase>,
    /// The mesh to generate or read.
    pub(super) mesh: MeshPlan,
    /// Materials, supports, loads, initial stress.
    pub(super) model: ModelPlan<2>,
    /// Contact zones and solver settings.
    pub(super) contact: ContactPlan<2>,
}

/// The 2D idealisation of `[analysis]` (its thickness checked).
pub(super) fn idealization(analysis: Analysis) -> CliResult<Idealization> {
    let root = KeyPath::root();
    Ok(match analysis {
        Analysis::PlaneStrain {} => Idealization::PlaneStrain,
        Analysis::PlaneStress { thickness } => Idealization::PlaneStress {
            thickness: positive(&root.key("analysis").key("thickness"), thickness)?,
        },
        Analysis::Axisymmetric {} => Idealization::Axisymmetric,
        Analysis::Solid {} => {
            bail!(
                root.key("analysis"),
                "a 3D scene is built by the 3D builder (internal routing error)"
            );
        }
    })
}

/// Checks every value of the scene that does not need the mesh, in the order of the file's
/// sections (so that the first error reported is the first one met);
/// `path` is the scene file's (Gmsh files are relative to it).
pub(super) fn validate(scene: &Scene, path: &Path) -> CliResult<Validated> {
    let root = KeyPath::root();
    if let Some(preset) = &scene.preset {
        let preset = preset.resolve(&root.key("preset"))?;
        return Ok(Validated::Preset(Box::new(presets::validate(
            scene, &preset,
        )?)));
    }
    let base_dir = path.parent().map(Path::to_path_buf).unwrap_or_default();

    // time functions and phases first: supports and loads refer to them
    let functions = time_functions(scene)?;
    let phases = phases_of(scene, None)?;

    // mesh and analysis
    let mesh_raw = scene.mesh.as_ref().ok_or_else(|| {
        CliError::at(
            &root,
            "the scene has no [mesh] (give `generator = \"rectangle\"`, `\"pile\"` or `\"gmsh\"`) \
             and no [preset]",
        )
    })?;
    let mp = root.key("mesh");
    let mesh_spec = &mesh_raw.resolve::<2>(&mp)?;
    let analysis = scene.analysis.ok_or_else(|| {
        CliError::at(
            &root,
            "the scene has no [analysis] (type = \"plane_strain\", \"plane_stress\" or \"axisymmetric\")",
        )
    })?;
    let idealization = idealization(analysis.resolve(&root.key("analysis"))?)?;
    let mesh = mesh::validate(&mp, mesh_spec, Some(idealization), &base_dir)?;

    let floating = scene.analysis.as_ref().is_some_and(|a| a.floating());
    let model = model::validate(scene, &functions, &phases, (idealization, floating))?;

    // contact (the solver settings with it)
    let contact = contact::validate::<2>(scene)?;
    Ok(Validated::Custom(Box::new(Plan {
        functions,
        phases,
        mesh,
        model,
        contact,
    })))
}
