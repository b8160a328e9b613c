//! A dynamic scene (`[analysis] dynamic = true`, issue 39), 2D or 3D through the same passes:
//! the keys checked ([`crate::raw::DynamicSpec`], densities, initial velocities, restitutions),
//! what the dynamic path does not serve refused at its key ([`refuse_unserved`]), then the
//! mesh, the model, the zones and a [`ContactSimulation`] of a [`DynamicModel`] stepped by
//! [`MoreauJean`] (Jean 1999; Acary & Brogliato 2008 §10.1).
//!
//! The run is one phase from 0 to `end_time` in steps of `time_step`; each load is scaled by
//! its time function at `t_k + θ h` (the θ-point of the step, a second-order rule for
//! `θ = 1/2`).

use super::Loaded;
use super::checks::{fem, finite_all, node_set, solver_error};
use super::dim::SceneDim;
use super::mesh;
use super::model::{self, MaterialPlan};
use super::phases::{Phase, TimeFunction, time_functions};
use super::study::{LoadRt, StudyDim, SupportRt};
use super::{contact, validate};
use crate::error::{CliError, CliResult, KeyPath, bail};
use crate::raw::{DynamicSpec, MassSpec, RawAnalysis, vector};
use crate::scene::{OutputSpec, Scene, Units};
use contact_laws::StandardLaw;
use contact_solver::ContactSimulation;
use contact_solver::coupling::simulation::MoreauJean;
use fem_core::dynamic::{DynamicModel, MassKind, Rayleigh};
use fem_core::{Dim, Idealization, Mesh, Structure};
use std::collections::BTreeMap;
use std::path::Path;

/// The simulation of a dynamic scene.
pub type DynamicSim<const D: usize> =
    ContactSimulation<DynamicModel<D>, StandardLaw, D, MoreauJean>;

/// A dynamic scene, built and ready to step.
pub struct DynamicStudy<const D: usize>
where
    Dim<D>: StudyDim<D>,
{
    /// The scene's title (or its file's stem).
    pub title: String,
    pub units: Units,
    pub sim: DynamicSim<D>,
    pub supports: Vec<SupportRt>,
    pub loads: Vec<LoadRt<D>>,
    pub functions: BTreeMap<String, TimeFunction>,
    /// The one phase, 0 to `end_time`.
    pub phase: Phase,
    /// Step, end time, θ, mass, damping.
    pub spec: DynamicSpec,
    pub zone_names: Vec<String>,
    /// Each zone's law name.
    pub zone_laws: Vec<String>,
    /// Each zone's restitution.
    pub restitution: Vec<f64>,
    /// `output.velocity_sets`: each set's name and nodes.
    pub velocity_sets: Vec<(String, Vec<usize>)>,
    pub output: OutputSpec,
    pub warnings: Vec<String>,
}

impl<const D: usize> DynamicStudy<D>
where
    Dim<D>: StudyDim<D>,
{
    /// The files a run writes: `summary.json`, `dynamics.csv`, the plots, and the VTK series.
    pub fn output_files(&self) -> usize {
        let plots = 2 + usize::from(!self.velocity_sets.is_empty());
        let vtk = if self.output.vtk {
            let every = self.output.every.max(1);
            // the .pvd, t = 0, every `every`-th step and the last
            2 + self.spec.steps.div_ceil(every)
        } else {
            0
        };
        2 + plots + vtk
    }
}

/// What a dimension builds a dynamic model in, from `[analysis]`: 2D, the idealisation (and a
/// body that may float: its inertia holds its rigid-body modes); 3D, a body that may float.
pub(crate) trait DynamicDim<const D: usize>: StudyDim<D>
where
    Dim<D>: StudyDim<D>,
{
    /// The model's options and the idealisation.
    fn options(
        analysis: &RawAnalysis,
    ) -> CliResult<(<Dim<D> as SceneDim<D>>::Options, Option<Idealization>)>;
}

impl DynamicDim<2> for Dim<2> {
    fn options(analysis: &RawAnalysis) -> CliResult<((Idealization, bool), Option<Idealization>)> {
        let i = validate::idealization(analysis.resolve(&KeyPath::root().key("analysis"))?)?;
        Ok(((i, true), Some(i)))
    }
}

impl DynamicDim<3> for Dim<3> {
    fn options(analysis: &RawAnalysis) -> CliResult<(bool, Option<Idealization>)> {
        analysis.resolve(&KeyPath::root().key("analysis"))?;
        Ok((true, None))
    }
}

/// Refuses, at its key, what a dynamic scene asks for that the dynamic path does not serve
/// (one place: lift a refusal here when the library serves it).
fn refuse_unserved(scene: &Scene) -> CliResult<()> {
    let root = KeyPath::root();
    let not = |p: KeyPath, what: &str| -> CliResult<()> {
        bail!(p, "`{p}`: {what} is not served by a dynamic scene yet");
    };
    if scene.preset.is_some() {
        not(root.key("preset"), "a library preset")?;
    }
    if scene.steps.is_some() {
        bail!(
            root.key("steps"),
            "`steps`: a dynamic scene steps with [analysis] `time_step` and `end_time`"
        );
    }
    if !scene.phases.is_empty() {
        not(root.key("phases"), "a sequence of phases")?;
    }
    if scene.initial_stress.is_some() {
        not(root.key("initial_stress"), "an initial stress")?;
    }
    if !scene.plots.is_empty() {
        not(
            root.key("plots"),
            "a plot of chosen quantities (the run plots its energies, contact forces and \
             velocities)",
        )?;
    }
    if scene.hertz.is_some() {
        not(root.key("hertz"), "the Hertz pressure plot")?;
    }
    let o = root.key("output");
    if scene.output.steps.is_some() {
        not(o.key("steps"), "a list of written steps (give `every`)")?;
    }
    if scene.output.profile_steps.is_some() {
        not(o.key("profile_steps"), "a pile's shaft profiles")?;
    }
    if scene.output.nodes.is_some() {
        not(o.key("nodes"), "a contact history by node")?;
    }
    for (i, s) in scene.supports.iter().enumerate() {
        if s.value != 0.0 {
            // the scheme's velocity lives on the free dofs: a prescribed component stays put
            not(
                root.key("supports").index(i).key("value"),
                "a prescribed displacement other than 0 (a moving support)",
            )?;
        }
    }
    // every law is served: `MoreauJean` takes RCCM's adhesion at velocity level (its springs
    // of the step's start state at u_θ, β updated once per step: `AdhesionUpdate::Lagged`)
    Ok(())
}

/// Refuses the keys of a dynamic scene in a static one (the materials' `density` is read by
/// both, `initial_velocity` is refused where materials are read).
pub(super) fn refuse_in_static(scene: &Scene) -> CliResult<()> {
    let root = KeyPath::root();
    let hint = "is a key of a dynamic scene (set `dynamic = true` in [analysis])";
    if let Some(a) = &scene.analysis {
        a.dynamic(&root.key("analysis"))?;
    }
    for (i, z) in scene.contact.iter().enumerate() {
        if z.law.restitution().is_some() {
            let p = root.key("contact").index(i).key("law").key("restitution");
            bail!(p, "`{p}` {hint}");
        }
    }
    if scene.output.velocity_sets.is_some() {
        let p = root.key("output").key("velocity_sets");
        bail!(p, "`{p}` {hint}");
    }
    Ok(())
}

/// The velocity of each node at t = 0 from the materials' `initial_velocity` on their regions
/// (at rest where none is given); a node shared by regions of two different velocities is
/// refused at the second one's key.
fn initial_velocities<const D: usize>(
    mesh: &Mesh<D>,
    materials: &[MaterialPlan],
) -> CliResult<Vec<[f64; D]>>
where
    Dim<D>: SceneDim<D>,
{
    let mut by_region: BTreeMap<u32, (Option<KeyPath>, [f64; D])> = BTreeMap::new();
    for m in materials {
        let v = match &m.initial_velocity {
            Some((p, c)) => (Some(p.clone()), finite_all(p, vector::<D>(p, c)?)?),
            None => (None, [0.0; D]),
        };
        for (_, r) in &m.regions {
            by_region.insert(*r, v.clone());
        }
    }
    let mut out: Vec<Option<([f64; D], Option<KeyPath>)>> = vec![None; mesh.node_count()];
    for (e, region) in mesh.regions().iter().enumerate() {
        let Some((key, v)) = by_region.get(region) else {
            continue; // the model's build names a region without a material
        };
        for &n in mesh.element(e) {
            match &out[n] {
                Some((w, wk)) if w != v => {
                    let p = key
                        .clone()
                        .or_else(|| wk.clone())
                        .unwrap_or_else(KeyPath::root);
                    bail!(
                        p,
                        "`{p}`: node {n} is shared by regions of different initial velocities \
                             ({w:?} and {v:?}); give the bodies their own nodes, or one velocity"
                    );
                }
                Some(_) => {}
                None => out[n] = Some((*v, key.clone())),
            }
        }
    }
    Ok(out
        .into_iter()
        .map(|v| v.map_or([0.0; D], |(v, _)| v))
        .collect())
}

/// Validates and builds a dynamic scene of dimension `D`.
pub(super) fn build<const D: usize>(loaded: &Loaded) -> CliResult<DynamicStudy<D>>
where
    Dim<D>: DynamicDim<D>,
{
    let scene = &loaded.scene;
    let root = KeyPath::root();
    let ap = root.key("analysis");
    let Some(analysis) = &scene.analysis else {
        return Err(CliError::at(
            &ap,
            "a dynamic scene without [analysis] (routing error)",
        ));
    };
    let Some(spec) = analysis.dynamic(&ap)? else {
        return Err(CliError::at(
            &ap,
            "a static scene reached the dynamic builder (routing)",
        ));
    };
    let (options, idealization) = Dim::<D>::options(analysis)?;
    refuse_unserved(scene)?;
    let base_dir = loaded
        .path
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_default();
    let functions = time_functions(scene)?;
    let phase = Phase {
        name: "dynamic".into(),
        steps: spec.steps,
        t0: 0.0,
        t1: spec.end_time,
        overrides: BTreeMap::new(),
        reset_displacements: false,
    };
    let phases = vec![phase.clone()];
    let mp = root.key("mesh");
    let mesh_raw = scene.mesh.as_ref().ok_or_else(|| {
        CliError::at(
            &root,
            "the scene has no [mesh] (a dynamic scene describes its mesh: a generator or gmsh)",
        )
    })?;
    let mesh_plan = mesh::validate(&mp, &mesh_raw.resolve::<D>(&mp)?, idealization, &base_dir)?;
    let mut plan = model::validate::<D>(scene, &functions, &phases, options)?;
    let contact_plan = contact::validate::<D>(scene)?;
    let restitution = scene
        .contact
        .iter()
        .enumerate()
        .map(|(i, z)| {
            let p = root.key("contact").index(i).key("law").key("restitution");
            z.law
                .restitution()
                .map_or(Ok(0.0), |e| crate::raw::restitution(&p, e))
        })
        .collect::<CliResult<Vec<f64>>>()?;
    if scene.output.every == 0 {
        let p = root.key("output").key("every");
        bail!(
            p,
            "`{p}` = 0: expected a stride ≥ 1 (every k-th step is written)"
        );
    }

    let mesh = mesh::build(&mp, mesh_plan, idealization)?;
    let velocity_sets = scene
        .output
        .velocity_sets
        .iter()
        .flatten()
        .enumerate()
        .map(|(i, s)| {
            let p = root.key("output").key("velocity_sets").index(i);
            Ok((s.clone(), node_set(&p, &mesh, s)?))
        })
        .collect::<CliResult<Vec<_>>>()?;
    let v0 = initial_velocities(&mesh, &plan.materials)?;
    // the materials' checked velocities are read: the plan keeps only what the model needs
    plan.materials
        .iter_mut()
        .for_each(|m| m.initial_velocity = None);
    let (model, supports, loads) = model::build(mesh, plan, &functions, &phases)?;
    let settings = contact_plan.settings;
    let contact_key = root.key("contact");
    let (sim, zone_laws, warnings) = contact::build_with(
        model,
        &contact_plan.zones,
        |model, zones| {
            let mass = match spec.mass {
                MassSpec::Consistent => MassKind::Consistent,
                MassSpec::Lumped => MassKind::Lumped,
            };
            let damping = Rayleigh {
                alpha: spec.alpha,
                beta: spec.beta,
            };
            let body = DynamicModel::new(model, mass, damping).map_err(|e| fem(&ap, e))?;
            let mut scheme =
                MoreauJean::new(spec.theta).map_err(|e| solver_error(&ap.key("theta"), e))?;
            for (z, &e) in restitution.iter().enumerate() {
                let p = contact_key.index(z).key("law").key("restitution");
                scheme = scheme
                    .with_zone_restitution(z, e)
                    .map_err(|err| solver_error(&p, err))?;
            }
            let mut velocity = vec![0.0; body.dof_count()];
            for (node, v) in v0.iter().enumerate() {
                for (c, dof) in body.node_dofs(node).into_iter().enumerate() {
                    if let Some(i) = dof {
                        velocity[i] = v[c];
                    }
                }
            }
            let scheme = scheme
                .with_velocity(velocity)
                .map_err(|e| solver_error(&root.key("materials"), e))?;
            ContactSimulation::with_scheme(body, zones, settings, scheme)
                .map_err(|e| solver_error(&contact_key, e))
        },
        |s: &DynamicModel<D>| s.model(),
    )?;
    let title = scene.title.clone().unwrap_or_else(|| {
        loaded
            .path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default()
    });
    Ok(DynamicStudy {
        title,
        units: scene.units.clone().unwrap_or_default(),
        zone_names: sim.zones().iter().map(|z| z.name.clone()).collect(),
        sim,
        supports,
        loads,
        functions,
        phase,
        spec,
        zone_laws,
        restitution,
        velocity_sets,
        output: scene.output.clone(),
        warnings,
    })
}
