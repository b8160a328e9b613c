//! A scene with a plastic material (`[[materials]] type = "drucker-prager"` or
//! `"von-mises"`, issue 40), 2D (plane strain, axisymmetric) or 3D through the same passes:
//! the keys checked ([`plastic_law`], [`RawAnalysis::newton`]), what the plastic
//! path does not serve refused at its key ([`refuse_unserved`]), then the mesh, the elastic
//! model (loads at their reference values, the geostatic stress of `[initial_stress]`), a
//! [`PlasticModel`] on it with one law per region (elastic regions keep a
//! [`LinearElasticPoint`]) and a [`ContactSimulation`] stepped by the global Newton
//! ([`ContactSimulation::with_newton`]).
//!
//! The loads are scaled by one force factor (the simulation's): every load takes the same
//! function (or none) in every phase. Supports keep their dofs through every phase (a plastic
//! body's dof numbering is fixed); their values follow their functions.

use super::Loaded;
use super::checks::{fem, node_set, solver_error};
use super::dim::SceneDim;
use super::mesh;
use super::model;
use super::outputs::{QUANTITIES_3D, check_plot_file};
use super::phases::{Phase, TimeFunction, phases_of, time_functions};
use super::study::{LoadKind, LoadRt, StudyDim, SupportRt};
use super::{contact, validate};
use crate::error::err;
use crate::error::{CliError, CliResult, KeyPath, bail};
use crate::raw::{MaterialKind, NewtonSpec, RawAnalysis};
use crate::scene::MaterialSpec;
use crate::scene::{OutputSpec, PlotSpec, Scene, Units};
use contact_laws::StandardLaw;
use contact_solver::{ContactSimulation, NewtonSettings};
use fem_core::plastic::{ConstitutivePoint, LinearElasticPoint, PlasticModel};
use fem_core::plastic::{DruckerPrager, DruckerPragerParameters};
use fem_core::{Dim, ElasticModel, FemError, Idealization};
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;
use std::sync::Arc;

/// The simulation of a plastic scene.
pub type PlasticSim<const D: usize> = ContactSimulation<PlasticModel<D>, StandardLaw, D>;

/// A plastic scene, built and ready to step.
pub struct PlasticStudy<const D: usize>
where
    Dim<D>: StudyDim<D>,
{
    /// The scene's title (or its file's stem).
    pub title: String,
    pub units: Units,
    pub sim: PlasticSim<D>,
    pub supports: Vec<SupportRt>,
    /// The function of the loads' force factor (`None`: the constant 1), and the name of the
    /// first load (for a phase's override of it).
    pub load_function: (Option<String>, Option<String>),
    pub functions: BTreeMap<String, TimeFunction>,
    pub phases: Vec<Phase>,
    pub newton: NewtonSpec,
    /// Each region's material type (`drucker-prager`, `von-mises`, `elastic`).
    pub materials: Vec<(u32, &'static str)>,
    pub zone_names: Vec<String>,
    /// Each zone's law name.
    pub zone_laws: Vec<String>,
    pub plots: Vec<PlotSpec>,
    pub output: OutputSpec,
    pub warnings: Vec<String>,
}

impl<const D: usize> PlasticStudy<D>
where
    Dim<D>: StudyDim<D>,
{
    /// The steps of every phase.
    pub fn total_steps(&self) -> usize {
        self.phases.iter().map(|p| p.steps).sum()
    }

    /// The files a run writes: `summary.json`, `steps.csv`, the plots with `curves.csv`, and
    /// the mesh's VTK series (the `.pvd`, t = 0, every `every`-th step and the last).
    pub fn output_files(&self) -> usize {
        let plots = if self.plots.is_empty() {
            0
        } else {
            1 + self.plots.len()
        };
        let vtk = if self.output.vtk {
            2 + self.total_steps().div_ceil(self.output.every.max(1))
        } else {
            0
        };
        2 + plots + vtk
    }

    /// The elastic model the plastic body is built on (mesh, supports, loads).
    pub fn model(&self) -> &ElasticModel<D> {
        self.sim.structure().elastic()
    }
}

/// Whether `scene` has a plastic material (it then takes the plastic path).
pub(super) fn is_plastic(scene: &Scene) -> bool {
    scene
        .materials
        .iter()
        .any(|m| m.kind != MaterialKind::Elastic)
}

/// Refuses `[analysis.newton]` in a scene without a plastic material, and the plastic keys
/// of its (elastic) materials.
pub(super) fn refuse_in_elastic(scene: &Scene) -> CliResult<()> {
    for (i, m) in scene.materials.iter().enumerate() {
        plastic_law(&KeyPath::root().key("materials").index(i), m)?;
    }
    if scene.analysis.as_ref().is_some_and(RawAnalysis::has_newton) {
        let p = KeyPath::root().key("analysis").key("newton");
        bail!(
            p,
            "`{p}` is a key of a scene with a plastic material (a [[materials]] of type \
             \"drucker-prager\" or \"von-mises\")"
        );
    }
    Ok(())
}

/// What a dimension builds a plastic model in, from `[analysis]`: 2D, the idealisation (plane
/// strain or axisymmetric); 3D, nothing. Never floating.
pub(crate) trait PlasticDim<const D: usize>: StudyDim<D>
where
    Dim<D>: StudyDim<D>,
{
    /// The model's options and the idealisation.
    fn options(
        analysis: &RawAnalysis,
    ) -> CliResult<(<Dim<D> as SceneDim<D>>::Options, Option<Idealization>)>;
}

impl PlasticDim<2> for Dim<2> {
    fn options(analysis: &RawAnalysis) -> CliResult<((Idealization, bool), Option<Idealization>)> {
        let ap = KeyPath::root().key("analysis");
        let i = validate::idealization(analysis.resolve(&ap)?)?;
        if let Idealization::PlaneStress { .. } = i {
            let p = ap.key("type");
            bail!(
                p,
                "`{p}` = \"plane_stress\": a plastic material is served in plane strain, \
                 axisymmetry and 3D"
            );
        }
        Ok(((i, false), Some(i)))
    }
}

impl PlasticDim<3> for Dim<3> {
    fn options(analysis: &RawAnalysis) -> CliResult<(bool, Option<Idealization>)> {
        analysis.resolve(&KeyPath::root().key("analysis"))?;
        Ok((false, None))
    }
}

/// Refuses, at its key, what a plastic scene asks for that the plastic path does not serve.
fn refuse_unserved(scene: &Scene) -> CliResult<()> {
    let root = KeyPath::root();
    let not = |p: KeyPath, what: &str| -> CliResult<()> {
        bail!(
            p,
            "`{p}`: {what} is not served by a scene with a plastic material"
        );
    };
    if scene.analysis.as_ref().is_some_and(|a| a.floating()) {
        not(
            root.key("analysis").key("floating"),
            "a floating body (the global Newton needs supports that hold the body)",
        )?;
    }
    if scene.hertz.is_some() {
        not(root.key("hertz"), "the Hertz pressure plot")?;
    }
    for (i, p) in scene.phases.iter().enumerate() {
        if p.reset_displacements {
            not(
                root.key("phases").index(i).key("reset_displacements"),
                "resetting the displacements (the plastic strains would stay)",
            )?;
        }
    }
    Ok(())
}

/// The plastic law of material `m` (at `p`, `materials[i]`), or `None` for an elastic one
/// (which refuses the plastic keys, naming them).
///
/// # Errors
/// A message at the key: a plastic key on another type, `friction_angle` outside `[0, 90)`,
/// `dilatancy_angle` outside `[0, φ]`, a negative `cohesion` (zero with `φ = 0`), a
/// `yield_stress` not > 0, or a missing required key.
pub(crate) fn plastic_law(p: &KeyPath, m: &MaterialSpec) -> CliResult<Option<DruckerPrager>> {
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
    only(p, &what, &present, accepted)?;
    let (young, poisson) = (m.young, m.poisson);
    let law = match m.kind {
        MaterialKind::Elastic => return Ok(None),
        MaterialKind::VonMises => {
            let sp = p.key("yield_stress");
            let sigma_y = need(p, &m.yield_stress, "yield_stress", &what)?;
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
            let phi = need(p, &m.friction_angle, "friction_angle", &what)?;
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
            let c = need(p, &m.cohesion, "cohesion", &what)?;
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
                cone: m.cone.unwrap_or_default().cone_match(),
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

/// `need(path, &opt, "key", "what")`: the value, or "`path`: what needs `key`".
fn need(path: &KeyPath, v: &Option<f64>, key: &str, what: &str) -> CliResult<f64> {
    v.ok_or_else(|| err!(path, "`{path}`: {what} needs `{key}`"))
}

/// Refuses the keys present that `what` does not read (`accepted`, separated by spaces).
fn only(path: &KeyPath, what: &str, present: &[(&str, bool)], accepted: &str) -> CliResult<()> {
    let accepted: Vec<&str> = accepted.split_whitespace().collect();
    if let Some((k, _)) = present.iter().find(|(k, p)| *p && !accepted.contains(k)) {
        let p = path.key(k);
        bail!(p, "`{p}` is not a key of {what}");
    }
    Ok(())
}

/// Each region's law: the plastic materials' and a [`LinearElasticPoint`] for the elastic
/// ones; with each region's type name.
type Laws = (
    Vec<(u32, Arc<dyn ConstitutivePoint>)>,
    Vec<(u32, &'static str)>,
);

fn laws(scene: &Scene) -> CliResult<Laws> {
    let root = KeyPath::root();
    let (mut laws, mut kinds) = (Vec::new(), Vec::new());
    for (i, m) in scene.materials.iter().enumerate() {
        let p = root.key("materials").index(i);
        let law: Arc<dyn ConstitutivePoint> = match plastic_law(&p, m)? {
            Some(dp) => Arc::new(dp),
            None => Arc::new(LinearElasticPoint::new(m.young, m.poisson).map_err(|e| fem(&p, e))?),
        };
        let regions = m.regions.clone().unwrap_or_default();
        for r in m.region.into_iter().chain(regions) {
            laws.push((r, law.clone()));
            kinds.push((r, m.kind.name()));
        }
    }
    Ok((laws, kinds))
}

/// The loads' one function and phases (every load the same, no phase overriding a load's
/// function), at their keys.
fn load_function<const D: usize>(
    loads: &[LoadRt<D>],
    phases: &[Phase],
) -> CliResult<(Option<String>, Option<String>)> {
    for (i, p) in phases.iter().enumerate() {
        let named = |n: &String| loads.iter().any(|l| l.name.as_ref() == Some(n));
        if let Some(name) = p.overrides.keys().find(|n| named(n)) {
            let p = KeyPath::root()
                .key("phases")
                .index(i)
                .key("functions")
                .key(name);
            bail!(
                p,
                "`{p}`: a phase's function for a load is not served by a scene with a plastic \
                 material (the loads follow one force factor: give the load's own `function`)"
            );
        }
    }
    let phases = phases.len();
    let root = KeyPath::root().key("loads");
    let Some(first) = loads.first() else {
        return Ok((None, None));
    };
    for (i, l) in loads.iter().enumerate() {
        if l.function != first.function {
            let p = root.index(i).key("function");
            bail!(
                p,
                "`{p}`: the loads of a scene with a plastic material follow one force factor: \
                 give every load the same function (the first's is {:?})",
                first.function
            );
        }
        if l.phases.iter().take(phases).any(|on| !on) {
            let p = root.index(i).key("phases");
            bail!(
                p,
                "`{p}`: the loads of a scene with a plastic material act in every phase \
                 (scale them by their function)"
            );
        }
    }
    Ok((first.function.clone(), first.name.clone()))
}

/// Adds each load at its reference value (scaled by `factor`) to `model`: the one place that
/// turns a [`LoadKind`] into the model's loads (the static and dynamic runs scale them per
/// step, the plastic run once).
pub(crate) fn add_load<const D: usize>(
    model: &mut ElasticModel<D>,
    kind: &LoadKind<D>,
    factor: f64,
) -> Result<(), FemError>
where
    Dim<D>: SceneDim<D>,
{
    let scaled = |v: &[f64; D]| v.map(|x| x * factor);
    match kind {
        LoadKind::Traction(set, v) => Dim::<D>::traction(model, set, scaled(v)),
        LoadKind::Pressure(set, p) => Dim::<D>::pressure(model, set, p * factor),
        LoadKind::Nodal(nodes, v) => nodes
            .iter()
            .try_for_each(|&n| model.add_nodal_force(n, scaled(v))),
        LoadKind::Resultant(node, v) => model.add_nodal_force(*node, scaled(v)),
        LoadKind::Body(v) => {
            let v = scaled(v);
            model.add_body_force(|_| v)
        }
        LoadKind::Gravity => model.add_self_weight(),
    }
}

/// Checks the plots of a plastic scene: the zone and step quantities of a 3D scene (and
/// `force_t` in 2D: the zone's tangential force), and
/// `u_x`, `u_y`, `u_z` (mean over a node `set` or one `node`) and `reaction_x`, `reaction_y`,
/// `reaction_z` (sum over a supported node `set`: the load–displacement curve).
pub(super) fn check_plots<const D: usize>(
    plots: &[PlotSpec],
    zone_names: &[String],
    model: &ElasticModel<D>,
) -> CliResult<()>
where
    Dim<D>: SceneDim<D>,
{
    let axes = ["x", "y", "z"];
    let mut files = BTreeSet::new();
    for (i, plot) in plots.iter().enumerate() {
        let pp = KeyPath::root().key("plots").index(i);
        check_plot_file(&pp, plot, &mut files)?;
        let curves = plot
            .curves
            .iter()
            .enumerate()
            .map(|(k, c)| (pp.key("curves").index(k), c));
        for (cp, c) in curves.chain(plot.x_quantity.iter().map(|c| (pp.key("x_quantity"), c))) {
            let q = c.quantity.as_str();
            let axis = |prefix: &str| {
                q.strip_prefix(prefix)
                    .is_some_and(|a| axes[..D].contains(&a))
            };
            if axis("u_") || axis("reaction_") {
                match (&c.set, c.node) {
                    (Some(set), _) => {
                        node_set(&cp.key("set"), model.mesh(), set)?;
                    }
                    (None, Some(n)) if q.starts_with("u_") && n < model.mesh().node_count() => {}
                    _ => bail!(
                        cp,
                        "`{cp}`: `{q}` needs a node `set`{}",
                        if q.starts_with("u_") {
                            " or a `node` of the mesh"
                        } else {
                            ""
                        }
                    ),
                }
            } else if QUANTITIES_3D.contains(&q) || (D == 2 && q == "force_t") {
                if let Some(z) = &c.zone
                    && !zone_names.contains(z)
                {
                    let p = cp.key("zone");
                    bail!(p, "`{p}` = \"{z}\": no [[contact]] zone has that name");
                }
            } else {
                let p = cp.key("quantity");
                bail!(
                    p,
                    "`{p}` = \"{q}\": a scene with a plastic material plots {}{}, `u_*` and \
                     `reaction_*` (with a `set`)",
                    QUANTITIES_3D.join(", "),
                    if D == 2 { ", force_t" } else { "" }
                );
            }
        }
    }
    Ok(())
}

/// Validates and builds a plastic scene of dimension `D`.
pub(super) fn build<const D: usize>(loaded: &Loaded) -> CliResult<PlasticStudy<D>>
where
    Dim<D>: PlasticDim<D>,
{
    let scene = &loaded.scene;
    let root = KeyPath::root();
    let ap = root.key("analysis");
    refuse_unserved(scene)?;
    let Some(analysis) = &scene.analysis else {
        bail!(
            root,
            "the scene has no [analysis] (type = \"plane_strain\", \"axisymmetric\" or \"3d\")"
        );
    };
    let (options, idealization) = Dim::<D>::options(analysis)?;
    let newton = analysis.newton(&ap)?;
    let functions = time_functions(scene)?;
    let phases = phases_of(scene, None)?;
    let (laws, materials) = laws(scene)?;
    let base_dir = loaded
        .path
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_default();
    let mp = root.key("mesh");
    let mesh_raw = scene.mesh.as_ref().ok_or_else(|| {
        CliError::at(
            &root,
            "the scene has no [mesh] (a plastic scene describes its mesh: a generator or gmsh)",
        )
    })?;
    let mesh_plan = mesh::validate(&mp, &mesh_raw.resolve::<D>(&mp)?, idealization, &base_dir)?;
    let plan = model::validate::<D>(scene, &functions, &phases, options)?;
    let contact_plan = contact::validate::<D>(scene)?;
    let mesh = mesh::build(&mp, mesh_plan, idealization)?;
    let (mut model, supports, loads) = model::build(mesh, plan, &functions, &phases)?;
    for (i, s) in supports.iter().enumerate() {
        if s.phases.iter().take(phases.len()).any(|on| !on) {
            let p = root.key("supports").index(i).key("phases");
            bail!(
                p,
                "`{p}`: a plastic body keeps its supports in every phase (its dofs are \
                 numbered once); give the support a function instead"
            );
        }
    }
    let load_function = load_function(&loads, &phases)?;
    for (i, l) in loads.iter().enumerate() {
        add_load(&mut model, &l.kind, 1.0).map_err(|e| fem(&root.key("loads").index(i), e))?;
    }
    let settings = contact_plan.settings;
    let contact_key = root.key("contact");
    let (sim, zone_laws, warnings) = contact::build_with(
        model,
        &contact_plan.zones,
        |model, zones| {
            let mut body = PlasticModel::new(model, &laws).map_err(|e| plastic_error(scene, e))?;
            if let Some(kind) = newton.tangent {
                body.set_tangent_kind(kind)
                    .map_err(|e| fem(&ap.key("newton").key("tangent"), e))?;
            }
            // the run cuts a step itself (its time, hence its prescribed values and force
            // factor): the library's own cuts keep the prescribed values whole
            let settings_n = NewtonSettings::default()
                .with_tol(newton.tol)
                .with_max_iterations(newton.max_iterations)
                .with_max_cuts(0);
            ContactSimulation::new(body, zones, settings)
                .and_then(|s| s.with_newton(settings_n))
                .map_err(|e| solver_error(&contact_key, e))
        },
        |s: &PlasticModel<D>| s.elastic(),
    )?;
    let zone_names: Vec<String> = sim.zones().iter().map(|z| z.name.clone()).collect();
    check_plots(&scene.plots, &zone_names, sim.structure().elastic())?;
    if scene.output.every == 0 {
        let p = root.key("output").key("every");
        bail!(
            p,
            "`{p}` = 0: expected a stride ≥ 1 (every k-th step is written)"
        );
    }
    let title = scene.title.clone().unwrap_or_else(|| {
        loaded
            .path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default()
    });
    Ok(PlasticStudy {
        title,
        units: scene.units.clone().unwrap_or_default(),
        zone_names,
        sim,
        supports,
        load_function,
        functions,
        phases,
        newton,
        materials,
        zone_laws,
        plots: scene.plots.clone(),
        output: scene.output.clone(),
        warnings,
    })
}

/// A [`PlasticModel::new`] error at its key: an initial stress outside the yield surface at
/// `initial_stress` (naming the region, element and point), a region without a material at
/// `materials`.
fn plastic_error(scene: &Scene, e: FemError) -> CliError {
    let root = KeyPath::root();
    match e {
        FemError::OutsideYieldSurface {
            region,
            element,
            point,
            yield_function,
        } => {
            let p = root.key("initial_stress");
            let material = scene
                .materials
                .iter()
                .position(|m| {
                    m.region == Some(region) || m.regions.iter().flatten().any(|r| *r == region)
                })
                .map(|i| format!(" (`materials[{i}]`)"))
                .unwrap_or_default();
            CliError::at(
                &p,
                format!(
                    "`{p}`: the geostatic stress is outside the yield surface of region \
                     {region}{material} at element {element}, point {point} (yield function \
                     {yield_function:.3e} > 0): raise the cohesion or bring `k0` closer to 1"
                ),
            )
        }
        other => fem(&root.key("materials"), other),
    }
}
