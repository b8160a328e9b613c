//! `[preset] kind = "pile"` in a scene with a plastic soil (issue 40): the preset's mesh,
//! supports, self-weight, geostatic K0 stress and interface
//! ([`PulloutSpec::build_plastic`], [`PulloutSpec::build_plastic_3d`]), the soil's law from
//! the one `[[materials]]` (its `young`, `poisson` and `unit_weight` are the soil's), made a
//! [`PlasticStudy`] that the plastic run steps like a scene written key by key.
//!
//! ```text
//! [preset]
//! kind = "pile"
//! installation = { type = "none" }  # the only one served (the default here)
//! sectors = 2                       # with [analysis] type = "3d": the quarter's sectors
//!
//! [analysis]
//! type = "axisymmetric"             # or "3d"
//! [analysis.newton]                 # optional
//!
//! [[materials]]                     # the soil (region 0); the pile stays linear elastic
//! type = "drucker-prager"
//! young = 3e4
//! poisson = 0.33
//! unit_weight = 20.0
//! friction_angle = 35.0
//! cohesion = 1.0
//! ```
//!
//! Two phases: `geostatic` (1 step, t = 0 → 1, the head held) and `pullout` (`steps` steps,
//! t = 1 → 1 + steps, the head's `u_z` ramped to `head_displacement` by the function
//! `lift`). The head's support is named `head` (its reaction is `reaction_y` over
//! `pile_head` in 2D, `reaction_z` in 3D, per radian or per quarter). Refused at their keys:
//! an installation other than `none` (calibrated on the elastic soil), `head_force` (a
//! floating pile), the preset's `soil_young`, `soil_poisson`, `soil_unit_weight` (the
//! material's), and every key that describes a mesh, supports, loads, contact or steps.

use super::Loaded;
use super::checks::solver_error;
use super::contact::settings;
use super::phases::{TimeFunction, phase};
use super::plastic::{PlasticStudy, check_plots, plastic_law};
use super::presets::pile;
use super::study::{StudyDim, SupportRt};
use crate::error::{CliError, CliResult, KeyPath, bail};
use crate::presets::{Installation, PileSpace, PlasticPullout, PulloutSpec};
use crate::raw::MaterialKind;
use crate::scene::Scene;
use crate::spec::{InstallationSpec, PileOverride, Preset};
use contact_laws::{ContactLaw, StandardLaw};
use contact_solver::{NewtonSettings, SimulationSettings, SolverError};
use fem_core::generate::{PILE, SOIL};
use fem_core::plastic::DruckerPrager;
use fem_core::{Component, Dim, FemError};
use std::collections::BTreeMap;

/// The most sectors of the quarter (16 make 5.6° sectors, the faceting far below the
/// mesh's own error; more only multiply the dofs).
const MAX_SECTORS: usize = 16;

/// How a dimension builds the plastic pile: the axisymmetric meridian (no `sectors`) or the
/// 3D quarter (`sectors`, 2 by default).
pub(crate) trait PresetPileDim<const D: usize>: StudyDim<D> + PileSpace<D>
where
    Dim<D>: StudyDim<D> + PileSpace<D>,
{
    /// The built pull-out.
    fn build(
        spec: &PulloutSpec,
        sectors: Option<usize>,
        soil: DruckerPrager,
        settings: (SimulationSettings, NewtonSettings),
    ) -> Result<PlasticPullout<D>, SolverError>;
}

impl PresetPileDim<2> for Dim<2> {
    fn build(
        spec: &PulloutSpec,
        _: Option<usize>,
        soil: DruckerPrager,
        settings: (SimulationSettings, NewtonSettings),
    ) -> Result<PlasticPullout<2>, SolverError> {
        spec.build_plastic(Some(soil), settings)
    }
}

impl PresetPileDim<3> for Dim<3> {
    fn build(
        spec: &PulloutSpec,
        sectors: Option<usize>,
        soil: DruckerPrager,
        settings: (SimulationSettings, NewtonSettings),
    ) -> Result<PlasticPullout<3>, SolverError> {
        spec.build_plastic_3d(sectors.unwrap_or(2), Some(soil), settings)
    }
}

/// Refuses what a plastic pile preset scene may not give (the preset builds it).
fn preset_only(scene: &Scene) -> CliResult<()> {
    let present = [
        ("mesh", scene.mesh.is_some()),
        ("initial_stress", scene.initial_stress.is_some()),
        ("functions", !scene.functions.is_empty()),
        ("supports", !scene.supports.is_empty()),
        ("ties", !scene.ties.is_empty()),
        ("loads", !scene.loads.is_empty()),
        ("contact", !scene.contact.is_empty()),
        ("steps", scene.steps.is_some()),
        ("phases", !scene.phases.is_empty()),
        ("hertz", scene.hertz.is_some()),
    ];
    if let Some((k, _)) = present.iter().find(|(_, p)| *p) {
        bail!(
            KeyPath::root().key(k),
            "`{k}` cannot be combined with [preset]: the pile preset builds its own mesh, \
             supports, loads, contact zones and phases (override them inside [preset])"
        );
    }
    Ok(())
}

/// The preset's spec with the overrides, the soil's constants from `materials[0]` (at `mp`),
/// and what the plastic path refuses refused at its key.
fn spec_of(pp: &KeyPath, o: &PileOverride, mp: &KeyPath, scene: &Scene) -> CliResult<PulloutSpec> {
    for (key, given) in [
        ("soil_young", o.soil_young.is_some()),
        ("soil_poisson", o.soil_poisson.is_some()),
        ("soil_unit_weight", o.soil_unit_weight.is_some()),
    ] {
        if given {
            let kp = pp.key(key);
            bail!(
                kp,
                "`{kp}`: with a plastic soil the soil's constants are its [[materials]]'s \
                 (`young`, `poisson`, `unit_weight` of `{mp}`)"
            );
        }
    }
    if let Some(i) = o.installation
        && !matches!(i, InstallationSpec::None {})
    {
        let ip = pp.key("installation");
        bail!(
            ip,
            "`{ip}`: the installation phase is not served with a plastic soil (its radial \
             displacement is calibrated on the elastic soil): give {{ type = \"none\" }} or \
             leave it out"
        );
    }
    if o.head_force.is_some() {
        let hp = pp.key("head_force");
        bail!(
            hp,
            "`{hp}`: force control (a floating pile) is not served with a plastic soil (the \
             global Newton needs supports that hold the body): give `head_displacement`"
        );
    }
    let mut spec = pile(pp, o)?;
    let Some(m) = scene.materials.first() else {
        bail!(mp, "`{mp}`: the soil's material is missing");
    };
    spec.installation = Installation::None;
    (spec.soil_young, spec.soil_poisson, spec.soil_unit_weight) =
        (m.young, m.poisson, m.unit_weight);
    Ok(spec)
}

/// The soil's law: the scene's one material, plastic, of region 0 (or none given).
fn soil_law(scene: &Scene) -> CliResult<(KeyPath, DruckerPrager)> {
    let root = KeyPath::root().key("materials");
    if scene.materials.len() > 1 {
        let p = root.index(1);
        bail!(
            p,
            "`{p}`: the pile preset takes one [[materials]], the soil's (region {SOIL}); the \
             pile stays linear elastic (the preset's `pile_young`, `pile_poisson`)"
        );
    }
    let mp = root.index(0);
    let Some(m) = scene.materials.first() else {
        bail!(
            root,
            "`{root}`: the pile preset with a plastic soil needs the soil's [[materials]]"
        );
    };
    let soil_only = m.region.is_none_or(|r| r == SOIL)
        && m.regions
            .as_deref()
            .is_none_or(|r| r.iter().all(|&r| r == SOIL));
    if !soil_only {
        let rp = mp.key("region");
        bail!(
            rp,
            "`{rp}`: the pile preset's material is the soil's, region {SOIL} (the pile, region \
             {PILE}, stays linear elastic)"
        );
    }
    match plastic_law(&mp, m)? {
        Some(law) => Ok((mp, law)),
        None => bail!(
            mp.key("type"),
            "`{mp}.type`: expected \"drucker-prager\" or \"von-mises\""
        ),
    }
}

/// A build error at its key: a geostatic state outside the yield surface at `materials[0]`,
/// the rest at `preset`.
fn build_error(pp: &KeyPath, mp: &KeyPath, e: SolverError) -> CliError {
    match e {
        SolverError::Structure(FemError::OutsideYieldSurface {
            element,
            point,
            yield_function,
            ..
        }) => CliError::at(
            mp,
            format!(
                "`{mp}`: the preset's geostatic stress is outside the soil's yield surface at \
                 element {element}, point {point} (yield function {yield_function:.3e} > 0): \
                 raise the cohesion or bring the preset's `k0` closer to 1"
            ),
        ),
        e => solver_error(pp, e),
    }
}

/// Validates and builds a plastic pile preset scene of dimension `D`.
pub(super) fn build<const D: usize>(loaded: &Loaded) -> CliResult<PlasticStudy<D>>
where
    Dim<D>: PresetPileDim<D>,
{
    let scene = &loaded.scene;
    let root = KeyPath::root();
    let (pp, ap) = (root.key("preset"), root.key("analysis"));
    preset_only(scene)?;
    let Some(raw) = &scene.preset else {
        bail!(pp, "`{pp}`: expected the pile preset");
    };
    let Preset::Pile(o) = raw.resolve(&pp)? else {
        let kp = pp.key("kind");
        bail!(
            kp,
            "`{kp}`: with a plastic material the preset is \"pile\" (the plates' presets build \
             linear elastic bodies)"
        );
    };
    let Some(analysis) = &scene.analysis else {
        bail!(
            root,
            "the pile preset with a plastic soil needs [analysis] type = \"axisymmetric\" or \
             \"3d\""
        );
    };
    let solid = analysis.pile_preset_is_solid(&ap)?;
    if let Some(s) = o.sectors
        && (!solid || s == 0 || s > MAX_SECTORS)
    {
        let sp = pp.key("sectors");
        bail!(
            sp,
            "`{sp}` = {s}: the quarter's sectors, 1 to {MAX_SECTORS}, with [analysis] type = \
             \"3d\" only"
        );
    }
    let (mp, soil) = soil_law(scene)?;
    let spec = spec_of(&pp, &o, &mp, scene)?;
    let newton = analysis.newton(&ap)?;
    let contact = settings::<D>(&scene.solver)?;
    // the run cuts a step itself (its time, hence its prescribed values)
    let settings_n = NewtonSettings::default()
        .with_tol(newton.tol)
        .with_max_iterations(newton.max_iterations)
        .with_max_cuts(0);
    let mut pile = Dim::<D>::build(&spec, o.sectors, soil, (contact, settings_n))
        .map_err(|e| build_error(&pp, &mp, e))?;
    if let Some(kind) = newton.tangent {
        pile.simulation
            .structure_mut()
            .set_tangent_kind(kind)
            .map_err(|e| super::checks::fem(&ap.key("newton").key("tangent"), e))?;
    }
    let sim = pile.simulation;
    let zone_names: Vec<String> = sim.zones().iter().map(|z| z.name.clone()).collect();
    let zone_laws = sim
        .zones()
        .iter()
        .map(|z| zone_law(&z.law).to_string())
        .collect();
    check_plots(&scene.plots, &zone_names, sim.structure().elastic())?;
    if scene.output.every == 0 {
        let p = root.key("output").key("every");
        bail!(
            p,
            "`{p}` = 0: expected a stride ≥ 1 (every k-th step is written)"
        );
    }
    let steps = spec.steps;
    let end = 1.0 + steps as f64;
    let functions = BTreeMap::from([(
        "lift".to_string(),
        TimeFunction::from_points(vec![[0.0, 0.0], [1.0, 0.0], [end, 1.0]]),
    )]);
    let head = SupportRt {
        name: Some("head".into()),
        nodes: pile.head,
        components: vec![Component::all::<D>()[D - 1]],
        value: spec.head_displacement,
        function: Some("lift".into()),
        phases: vec![true; 2],
    };
    let kind = scene
        .materials
        .first()
        .map_or(MaterialKind::Elastic, |m| m.kind);
    Ok(PlasticStudy {
        title: scene
            .title
            .clone()
            .unwrap_or_else(|| "preset pile (plastic soil)".into()),
        units: scene.units.clone().unwrap_or_default(),
        sim,
        supports: vec![head],
        load_function: (None, None),
        functions,
        phases: vec![
            phase("geostatic", 1, 0.0, 1.0),
            phase("pullout", steps, 1.0, end),
        ],
        newton,
        materials: vec![(SOIL, kind.name()), (PILE, MaterialKind::Elastic.name())],
        zone_names,
        zone_laws,
        plots: scene.plots.clone(),
        output: scene.output.clone(),
        warnings: Vec::new(),
    })
}

/// A zone's law as the preset's header names it.
fn zone_law(law: &StandardLaw) -> &'static str {
    if law.has_adhesion() {
        "rccm"
    } else if law.has_friction() {
        "rccm (coulomb)"
    } else {
        "rccm (signorini)"
    }
}
