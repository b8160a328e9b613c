//! A 3D scene (`[analysis] type = "3d"`): validated and built into a [`SolidStudy`], a
//! [`SolidContactSimulation`] of a [`SolidModel`] with its supports, loads, time functions and
//! phases.
//!
//! The passes are those of the 2D scene ([`super::validate`], then the build): what does not
//! depend on the dimension is the 2D code (time functions, phases, materials, supports' values
//! and names, the law of a zone, `[solver]`'s local keys, `[output]`); the model (loads with
//! three components, pressures on face sets) is built by the one generic
//! [`super::model::build`], the mesh, the zones and the plots by the generic [`mesh`],
//! [`contact`] and [`super::outputs::check_plots`] (what 3D reads differently, the box
//! generator and Gmsh volume files, rigid planes, spheres and cylinders, is
//! [`super::SceneDim`]'s). What 3D scenes do not have yet (floating bodies, shaft profiles) is
//! refused with its key path.

use super::Loaded;
use super::outputs::{MAX_OUTPUT_FILES, check_output_table, check_plots};
use super::phases::{Phase, TimeFunction, phases_of, time_functions};
use super::study::{LoadRt, SupportRt, written_steps};
use super::{contact, mesh, model};
use crate::error::{CliError, CliResult, KeyPath};
use crate::scene::{OutputSpec, PlotSpec, Scene, Units};
use contact_laws::StandardLaw;
use contact_solver::coupling::solid::SolidContactSimulation;
use fem_core::solid::SolidModel;
use std::collections::BTreeMap;
use std::path::Path;

/// A 3D scene ready to run.
pub struct SolidStudy {
    /// Title.
    pub title: String,
    /// Units.
    pub units: Units,
    /// The simulation.
    pub sim: SolidContactSimulation<SolidModel, StandardLaw>,
    /// Supports (each in its phases).
    pub supports: Vec<SupportRt>,
    /// Loads.
    pub loads: Vec<LoadRt<3>>,
    /// Time functions.
    pub functions: BTreeMap<String, TimeFunction>,
    /// Phases.
    pub phases: Vec<Phase>,
    /// Outputs.
    pub output: OutputSpec,
    /// Zone names.
    pub zone_names: Vec<String>,
    /// Zone law names.
    pub zone_laws: Vec<String>,
    /// Per phase (in order), the laws it sets: `(zone, law)`.
    pub phase_laws: Vec<Vec<(String, StandardLaw)>>,
    /// What the scene's checks let pass but the user should know (e.g. contactor nodes held
    /// by a support, left out): printed by `bipo check` and `bipo run`, and in `summary.json`.
    pub warnings: Vec<String>,
    /// `[hertz]`: the pressure plot against Hertz.
    pub hertz: Option<super::HertzPlan>,
    /// `[[plots]]`: curves against time, step or load factor (`curves.csv` and one SVG each).
    pub plots: Vec<PlotSpec>,
}

impl SolidStudy {
    /// Total steps.
    pub fn total_steps(&self) -> usize {
        self.phases.iter().map(|p| p.steps).sum()
    }

    /// The steps whose contacts and VTK files are written.
    pub fn written_steps(&self) -> usize {
        written_steps(&self.output, &self.phases)
    }

    /// Whether the body's `.vtu` series is written (`output.vtk` or `output.mesh_vtk`).
    pub fn writes_vtk(&self) -> bool {
        self.output.vtk || self.output.writes_mesh_vtk()
    }

    /// The files a run writes: `summary.json`, the CSV histories, and per `.vtu` series (the
    /// body's, the interface's with `output.vtk`) one file per written step and the `.pvd`.
    pub fn output_files(&self) -> usize {
        let o = &self.output;
        let fixed = 1
            + usize::from(o.history)
            + usize::from(o.report)
            + usize::from(o.pressure)
            + usize::from(self.hertz.is_some())
            + if self.plots.is_empty() {
                0
            } else {
                self.plots.len() + 1
            };
        let series = usize::from(self.writes_vtk()) + usize::from(o.vtk);
        self.written_steps()
            .saturating_add(1)
            .saturating_mul(series)
            .saturating_add(fixed)
    }
}

/// Refuses, with its key path, what a 3D scene cannot do yet.
fn refuse_unsupported(scene: &Scene) -> CliResult<()> {
    let root = KeyPath::root();
    if scene.output.profile_steps.is_some() {
        let p = root.key("output").key("profile_steps");
        return Err(CliError::at(
            &p,
            format!("`{p}`: shaft profiles are written by the 2D pile preset only"),
        ));
    }
    Ok(())
}

/// Validates and builds a 3D scene.
pub(super) fn build(loaded: &Loaded) -> CliResult<SolidStudy> {
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
    let plan = model::validate(scene, &functions, &phases, ())?;
    let contact = contact::validate::<3>(scene)?;
    refuse_unsupported(scene)?;

    let mesh = mesh::build(&mp, mesh_plan, None)?;
    let (model, supports, loads) = model::build(mesh, plan, &functions, &phases)?;
    let (sim, _, warnings) = contact::build(model, &contact.zones, contact.settings)?;
    let zone_names: Vec<String> = sim.zones().iter().map(|z| z.name.clone()).collect();
    let hertz = super::hertz::check(scene, &zone_names, 3, |e, nu| e / (1.0 - nu * nu))?;
    let plots = check_plots(&scene.plots, &zone_names, None)?;
    let study = SolidStudy {
        title: scene.title.clone().unwrap_or_else(|| {
            loaded
                .path
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default()
        }),
        units: scene.units.clone().unwrap_or_default(),
        sim,
        supports,
        loads,
        functions,
        phases,
        output: scene.output.clone(),
        zone_names,
        zone_laws: contact.zones.iter().map(|z| z.law_name.into()).collect(),
        phase_laws: contact.phase_laws,
        warnings,
        hertz,
        plots,
    };
    let candidates = study.sim.candidates();
    check_output_table(
        &study.output,
        study.total_steps(),
        &study.zone_names,
        &|n| candidates.iter().any(|c| c.node == n),
        study.sim.structure().mesh().node_count(),
    )?;
    let files = study.output_files();
    if files > MAX_OUTPUT_FILES {
        let key = if study.output.steps.is_some() {
            "steps"
        } else {
            "every"
        };
        let p = root.key("output").key(key);
        return Err(CliError::at(
            &p,
            format!(
                "`{p}`: the run would write {files} files: more than the limit of \
                 {MAX_OUTPUT_FILES}; raise `output.every`, list `output.steps`, or set \
                 `output.vtk` and `output.mesh_vtk` = false"
            ),
        ));
    }
    Ok(study)
}
