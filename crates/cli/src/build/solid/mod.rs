//! A 3D scene (`[analysis] type = "3d"`) validated and built into a [`Study<3>`] by the passes
//! of the 2D scene ([`super::validate`], then the build), all generic over the dimension (what 3D
//! reads differently is [`super::SceneDim`]'s). What 3D scenes do not have yet (floating bodies,
//! shaft profiles) is refused with its key path.

use super::Loaded;
use super::outputs::{check_file_count, check_output_table, check_plots};
use super::phases::{phases_of, time_functions};
use super::study::Study;
use super::{contact, mesh, model};
use crate::error::{CliError, CliResult, KeyPath, bail};
use crate::scene::Scene;
use std::path::Path;

/// Refuses, with its key path, what a 3D scene cannot do yet.
fn refuse_unsupported(scene: &Scene) -> CliResult<()> {
    let root = KeyPath::root();
    if scene.output.profile_steps.is_some() {
        let p = root.key("output").key("profile_steps");
        bail!(
            p,
            "`{p}`: shaft profiles are written by the 2D pile preset only"
        );
    }
    Ok(())
}

/// Validates and builds a 3D scene.
pub(super) fn build(loaded: &Loaded) -> CliResult<Study<3>> {
    let scene = &loaded.scene;
    let root = KeyPath::root();
    let base_dir = loaded
        .path
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_default();
    let functions = time_functions(scene)?;
    let phases = phases_of(scene, None)?;
    let mp = root.key("mesh");
    let mesh_raw = scene.mesh.as_ref().ok_or_else(|| {
        CliError::at(
            &root,
            "the 3D scene has no [mesh] (give `generator = \"box\"` or `\"gmsh\"`)",
        )
    })?;
    let mesh_plan = mesh::validate(&mp, &mesh_raw.resolve::<3>(&mp)?, None, &base_dir)?;
    if let Some(a) = &scene.analysis {
        a.resolve(&root.key("analysis"))?;
    }
    let plan = model::validate(scene, &functions, &phases, false)?;
    let contact = contact::validate::<3>(scene)?;
    refuse_unsupported(scene)?;

    let mesh = mesh::build(&mp, mesh_plan, None)?;
    let mut study = super::custom_study(loaded, mesh, plan, functions, phases, contact)?;
    study.hertz = super::hertz::check(scene, &study.zone_names, 3, |e, nu| e / (1.0 - nu * nu))?;
    study.plots = check_plots(&scene.plots, &study.zone_names, None)?;
    let candidates = study.candidates();
    check_output_table(
        &study.output,
        study.total_steps(),
        &study.zone_names,
        &|n| candidates.iter().any(|c| c.node == n),
        study.model().mesh().node_count(),
    )?;
    check_file_count(&study)?;
    Ok(study)
}
