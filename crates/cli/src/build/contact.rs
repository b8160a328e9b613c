//! Contact, in both dimensions: the solver settings, the laws and the targets of the zones
//! checked first, then the zones built on the model's sets, recognised (every zone must have a
//! candidate within its alert distance at the start), and the simulation made. What a zone reads
//! differently per dimension (rigid shapes, node pairs, target surfaces, contactor areas) is
//! [`SceneDim`]'s.

use super::checks::{
    at_least, expect, law_error, list_names, non_negative, positive, solver_error,
};
use super::dim::SceneDim;
use super::phases::law_name;
use super::supported::{Policy, point, resolve};
use crate::error::{CliResult, KeyPath, bail};
use crate::raw::RawTarget;
use crate::scene::{
    AdhesionMethodSpec, AlgorithmSpec, FlexibilitySpec, Scene, SolverSpec, SupportedContactors,
};
use crate::spec::{LawSpec, RccmSpec, SchemeSpec, TargetSpec};
use contact_laws::{BetaScheme, ContactLaw, Coulomb, Rccm, RccmParams, Signorini, StandardLaw};
use contact_solver::coupling::simulation::TimeScheme;
use contact_solver::coupling::space::ContactSpace;
use contact_solver::local::adhesion::AdhesionMethod;
use contact_solver::local::stall::MIN_STALL_WINDOW;
use contact_solver::{
    Algorithm, Candidate, ContactSimulation, ContactZone, FlexibilityMode, Obstacle,
    SimulationSettings, Target, recognize, supported_contactors,
};
use fem_core::{Dim, ElasticModel, Structure};
use std::collections::BTreeSet;
use std::sync::Arc;

/// What a zone faces, checked: a rigid shape (built), node pairs or another body's surface
/// (their sets are looked up in the mesh at build).
pub(super) enum TargetPlan<const D: usize> {
    /// A LINE or an ARC (2D); a plane, a sphere or a cylinder (3D).
    Rigid(Arc<dyn Obstacle<D>>),
    /// Node pairs with the nodes of `set`, and a fixed normal if given.
    NodePairs {
        set: String,
        normal: Option<[f64; D]>,
    },
    /// The polyline of a node set (2D `segments`), the faces of a face set (3D `faces`).
    Surface(String),
}

/// A contact zone of a scene of dimension `D`, checked.
pub(super) struct ZonePlan<const D: usize> {
    pub(super) path: KeyPath,
    pub(super) name: String,
    pub(super) contactor: String,
    pub(super) law: StandardLaw,
    pub(super) alert: f64,
    pub(super) target: TargetPlan<D>,
    pub(super) supported: SupportedContactors,
}

/// The zones of a scene, checked, how many have adhesion and friction, and the solver settings.
pub(super) struct ContactPlan<const D: usize> {
    /// Zones, in the scene's order.
    pub(super) zones: Vec<ZonePlan<D>>,
    /// Zones whose law has adhesion.
    pub(super) adhesive: usize,
    /// Zones whose law has friction.
    pub(super) friction: usize,
    /// `[solver]`.
    pub(super) settings: SimulationSettings,
    /// Per phase (in order), the laws it sets: `(zone, law)`.
    pub(super) phase_laws: Vec<Vec<(String, StandardLaw)>>,
}

/// The most contact iterations a step may take: beyond, a step that does not converge would
/// not end in a useful time.
pub const MAX_ITERATIONS: usize = 10_000_000;
/// The most adhesion iterations a step may take.
pub const MAX_ADHESION_ITERATIONS: usize = 100_000;
/// The most penetration-check passes a step may take.
pub const MAX_DETECTION_PASSES: usize = 1_000;

/// An iteration count in `1..=max` at `path`.
fn count(path: &KeyPath, n: usize, max: usize) -> CliResult<usize> {
    at_least(path, n, 1)?;
    if n > max {
        bail!(
            path,
            "`{path}` = {n}: expected an integer in 1..={max} (more would let a step that \
                 does not converge run without end)"
        );
    }
    Ok(n)
}

/// `[solver]`, checked, as the library's settings of dimension `D`: the keys the scene gives
/// over [`SimulationSettings::for_dimension`]`::<D>()` (the `Auto` dense limit, the right-hand
/// sides per solve and the detection passes measured for each dimension).
pub(super) fn settings<const D: usize>(s: &SolverSpec) -> CliResult<SimulationSettings>
where
    Dim<D>: ContactSpace<D>,
{
    let root = KeyPath::root().key("solver");
    let mut out = SimulationSettings::for_dimension::<D>();
    if let Some(a) = s.algorithm {
        out.solver.algorithm = match a {
            AlgorithmSpec::Bipotential => Algorithm::default(),
            AlgorithmSpec::Uzawa => Algorithm::Uzawa,
            AlgorithmSpec::RccmClassic => Algorithm::ClassicRccm,
        };
    }
    if let Some(t) = s.tol {
        out.solver.tol = positive(&root.key("tol"), t)?;
    }
    if let Some(r) = s.rho_scale {
        out.solver.tuning.rho_scale = positive(&root.key("rho_scale"), r)?;
    }
    if let Some(n) = s.max_iterations {
        out.solver.max_iterations = count(&root.key("max_iterations"), n, MAX_ITERATIONS)?;
    }
    if let Some(w) = s.omega {
        let p = root.key("omega");
        if s.algorithm != Some(AlgorithmSpec::RccmClassic) {
            bail!(
                p,
                "`{p}` is only read with algorithm = \"rccm-classic\" (its SOR factor)"
            );
        }
        out.solver.tuning.omega = expect(&p, w, w > 0.0 && w < 2.0, "a factor in (0, 2)")?;
    }
    if let Some(t) = s.adhesion_tol {
        out.adhesion_tol = positive(&root.key("adhesion_tol"), t)?;
    }
    if let Some(m) = s.adhesion_method {
        let p = root.key("adhesion_method");
        out.tuning.adhesion_method = match m {
            AdhesionMethodSpec::FixedPoint => AdhesionMethod::FixedPoint,
            AdhesionMethodSpec::Newton if s.algorithm == Some(AlgorithmSpec::RccmClassic) => {
                bail!(
                    p,
                    "`{p}` = \"newton\" does not combine with algorithm = \"rccm-classic\" \
                         (the classical solver is a fixed point by definition): use \"fixed-point\" \
                         or leave the key out"
                );
            }
            AdhesionMethodSpec::Newton => AdhesionMethod::Newton,
        };
    }
    if let Some(w) = s.adhesion_warm_start {
        let p = root.key("adhesion_warm_start");
        if w && out.tuning.adhesion_method == AdhesionMethod::FixedPoint {
            bail!(
                p,
                "`{p}` = true is only read with adhesion_method = \"newton\" (it starts \
                     Newton from the previous step's reactions)"
            );
        }
        out.tuning.adhesion_warm_start = w;
    }
    if let Some(n) = s.max_adhesion_iterations {
        out.max_adhesion_iterations = count(
            &root.key("max_adhesion_iterations"),
            n,
            MAX_ADHESION_ITERATIONS,
        )?;
    }
    if let Some(n) = s.max_detection_passes {
        out.tuning.max_detection_passes =
            count(&root.key("max_detection_passes"), n, MAX_DETECTION_PASSES)?;
    }
    if let Some(b) = s.accept_non_converged {
        out.solver.accept_non_converged = b;
    }
    if let Some(n) = s.stall_window {
        let p = root.key("stall_window");
        if n != 0 && !(MIN_STALL_WINDOW..=MAX_ITERATIONS).contains(&n) {
            bail!(
                p,
                "`{p}` = {n}: expected 0 (no stall detection) or an integer in \
                     {MIN_STALL_WINDOW}..={MAX_ITERATIONS}"
            );
        }
        out.solver.tuning.stall_window = n;
    }
    if let Some(b) = s.fallback {
        out.solver.fallback = b;
    }
    let dense_limit = s
        .dense_limit
        .unwrap_or(<Dim<D> as ContactSpace<D>>::DENSE_LIMIT);
    out.flexibility = match s.flexibility.unwrap_or(FlexibilitySpec::Auto) {
        FlexibilitySpec::Auto => FlexibilityMode::Auto { dense_limit },
        other if s.dense_limit.is_some() => {
            let p = root.key("dense_limit");
            bail!(
                p,
                "`{p}` only applies to flexibility = \"auto\" (here {other:?})"
            );
        }
        FlexibilitySpec::Dense => FlexibilityMode::Dense,
        FlexibilitySpec::ActiveSet => FlexibilityMode::ActiveSet,
        FlexibilitySpec::MatrixFree => FlexibilityMode::MatrixFree,
    };
    Ok(out)
}

/// A θ in [0, 1] at `path`.
pub(super) fn theta(path: &KeyPath, t: f64) -> CliResult<f64> {
    expect(path, t, (0.0..=1.0).contains(&t), "a value in [0, 1]")
}

/// The β scheme of an RCCM law at `path`: `scheme` with its `theta` key, checked.
pub(super) fn scheme(path: &KeyPath, s: SchemeSpec, t: Option<f64>) -> CliResult<BetaScheme> {
    Ok(match (s, t) {
        (SchemeSpec::ImplicitEuler, None) => BetaScheme::ImplicitEuler,
        (SchemeSpec::ImplicitEuler, Some(_)) => {
            let p = path.key("theta");
            bail!(
                p,
                "`{p}` is only read with scheme = \"theta\" (the scheme is implicit_euler)"
            );
        }
        (SchemeSpec::Theta, Some(t)) => BetaScheme::Theta(theta(&path.key("theta"), t)?),
        (SchemeSpec::Theta, None) => {
            bail!(
                path,
                "`{path}`: scheme = \"theta\" needs `theta` (a value in [0, 1])"
            );
        }
    })
}

/// RCCM parameters, checked (the θ key against the scheme, then the law's own checks).
pub(super) fn rccm_params(path: &KeyPath, r: &RccmSpec) -> CliResult<RccmParams> {
    let scheme = scheme(path, r.scheme, r.theta)?;
    let p = RccmParams {
        c_n: r.c_n,
        c_t: r.c_t,
        w: r.w,
        alpha: r.alpha,
        mu: r.mu,
        m: r.m,
        beta_0: r.beta_0,
        scheme,
    };
    Rccm::new(p).map_err(|e| law_error(path, e))?;
    Ok(p)
}

/// The law of a zone, checked.
pub(super) fn law(path: &KeyPath, l: &LawSpec) -> CliResult<StandardLaw> {
    Ok(match l {
        LawSpec::Signorini {} => Signorini.into(),
        LawSpec::Coulomb { mu } => Coulomb::new(*mu).map_err(|e| law_error(path, e))?.into(),
        LawSpec::Rccm(r) => Rccm::new(rccm_params(path, r)?)
            .map_err(|e| law_error(path, e))?
            .into(),
    })
}

/// Checks `[[contact]]` (unique names, alert distances, laws and the targets' geometry) and
/// `[solver]`, in a scene of dimension `D`.
pub(super) fn validate<const D: usize>(scene: &Scene) -> CliResult<ContactPlan<D>>
where
    Dim<D>: SceneDim<D>,
{
    let root = KeyPath::root();
    if scene.contact.is_empty() {
        bail!(
            root,
            "the scene has no [[contact]] zone (bipo solves contact problems)"
        );
    }
    let settings = settings::<D>(&scene.solver)?;
    let mut zones = Vec::new();
    let mut names = BTreeSet::new();
    let (mut adhesive, mut friction) = (0, 0);
    for (i, z) in scene.contact.iter().enumerate() {
        let p = root.key("contact").index(i);
        zone_name(&p, &z.name, &mut names)?;
        let alert = non_negative(&p.key("alert_distance"), z.alert_distance)?;
        let l = law(&p.key("law"), &z.law.resolve(&p.key("law"))?)?;
        if l.has_adhesion() {
            adhesive += 1;
        }
        if l.has_friction() {
            friction += 1;
        }
        let target = target::<D>(&p.key("target"), &z.target)?;
        zones.push(ZonePlan {
            path: p,
            name: z.name.clone(),
            contactor: z.contactor.clone(),
            law: l,
            alert,
            target,
            supported: z.supported_contactors,
        });
    }
    let phase_laws = phase_laws(scene, &names)?;
    for l in phase_laws.iter().flatten().map(|(_, l)| l) {
        adhesive += usize::from(l.has_adhesion());
        friction += usize::from(l.has_friction());
    }
    Ok(ContactPlan {
        zones,
        adhesive,
        friction,
        settings,
        phase_laws,
    })
}

/// The laws `[[phases]]` set, per phase (in order): `(zone, law)`, every zone named one of
/// `names` (2D and 3D scenes).
pub(super) fn phase_laws(
    scene: &Scene,
    names: &BTreeSet<String>,
) -> CliResult<Vec<Vec<(String, StandardLaw)>>> {
    let root = KeyPath::root();
    let mut out = Vec::new();
    for (i, ph) in scene.phases.iter().enumerate() {
        let mut laws = Vec::new();
        for (zone, raw) in &ph.laws {
            let p = root.key("phases").index(i).key("laws").key(zone);
            if !names.contains(zone) {
                bail!(
                    p,
                    "`{p}`: no [[contact]] zone is named `{zone}` (zones: {})",
                    list_names(names.iter().map(String::as_str))
                );
            }
            let l = law(&p, &raw.resolve(&p)?)?;
            laws.push((zone.clone(), l));
        }
        out.push(laws);
    }
    Ok(out)
}

/// The target of a zone at `tp` in a scene of dimension `D`, its geometry checked (rigid
/// shapes are built here).
pub(super) fn target<const D: usize>(tp: &KeyPath, t: &RawTarget) -> CliResult<TargetPlan<D>>
where
    Dim<D>: SceneDim<D>,
{
    Ok(match t.resolve::<D>(tp)? {
        TargetSpec::NodePairs { set, normal } => TargetPlan::NodePairs {
            set,
            normal: normal
                .map(|n| Dim::<D>::pair_normal(&tp.key("normal"), &n))
                .transpose()?,
        },
        TargetSpec::Surface { set } => TargetPlan::Surface(set),
        rigid => TargetPlan::Rigid(Dim::<D>::obstacle(tp, &rigid)?),
    })
}

/// The simulation of a scene of dimension `D`.
pub(super) type Simulation<const D: usize> = ContactSimulation<ElasticModel<D>, StandardLaw, D>;

/// The simulation, each zone's law name, and the warnings of [`build`].
pub(super) type BuiltContact<const D: usize> = (Simulation<D>, Vec<String>, Vec<String>);

/// What [`build_with`] gives: the simulation of structure `S` stepped by the scheme `T`, the
/// laws' names and the warnings.
pub(super) type BuiltWith<S, const D: usize, T> = (
    ContactSimulation<S, StandardLaw, D, T>,
    Vec<String>,
    Vec<String>,
);

/// One zone on the model's sets: its contactor nodes (with their tributary areas where the
/// set gives them or the zone's own lumping would be wrong) against its target.
fn zone<const D: usize>(
    model: &ElasticModel<D>,
    z: &ZonePlan<D>,
) -> CliResult<ContactZone<StandardLaw, D>>
where
    Dim<D>: SceneDim<D>,
{
    let cp = z.path.key("contactor");
    let (mut contactor, areas) = Dim::<D>::contactor(model.mesh(), &cp, &z.contactor)?;
    let tp = z.path.key("target");
    let (name, l, alert) = (z.name.as_str(), z.law, z.alert);
    let zone = match &z.target {
        TargetPlan::Rigid(o) => {
            ContactZone::new(name, contactor, Target::Rigid(o.clone()), l, alert)
        }
        TargetPlan::NodePairs { set, normal } => {
            let (targets, normals) =
                Dim::<D>::pairs(model, &tp, &z.contactor, set, *normal, &mut contactor)?;
            ContactZone::node_pairs(name, contactor, targets, normals, l, alert)
        }
        TargetPlan::Surface(set) => {
            let surface = Dim::<D>::surface(model, &tp.key("set"), set)?;
            ContactZone::on_surface(name, contactor, surface, l, alert)
        }
    };
    Ok(
        match areas.or_else(|| Dim::<D>::areas(model, &z.contactor, &zone.contactor)) {
            Some(a) => zone.with_areas(a),
            None => zone,
        },
    )
}

/// The simulation of `model` with the zones of `plans`: zones built ([`zone`]), contactor nodes
/// held by a support refused or left out (`supported_contactors`; the warnings are returned),
/// candidates recognised and checked (each zone has one, none deeper in its target than the
/// alert distance, one within it; before the simulation is made in 2D, with the facing check,
/// after in 3D). Also gives each zone's law name. A library refusal is told at the `contact`
/// key.
pub(super) fn build<const D: usize>(
    model: ElasticModel<D>,
    plans: &[ZonePlan<D>],
    settings: SimulationSettings,
) -> CliResult<BuiltContact<D>>
where
    Dim<D>: SceneDim<D>,
{
    let contact = KeyPath::root().key("contact");
    build_with(
        model,
        plans,
        |model, zones| {
            ContactSimulation::new(model, zones, settings).map_err(|e| solver_error(&contact, e))
        },
        |s| s,
    )
}

/// As [`build`], the simulation made by `make` from the model and the zones (another structure
/// or time scheme: a dynamic scene's); `model_of` gives back the model inside its structure
/// for the checks of candidates made after the simulation (3D).
pub(super) fn build_with<const D: usize, S: fem_core::Structure<D>, T: TimeScheme<S, D>>(
    model: ElasticModel<D>,
    plans: &[ZonePlan<D>],
    make: impl FnOnce(
        ElasticModel<D>,
        Vec<ContactZone<StandardLaw, D>>,
    ) -> CliResult<ContactSimulation<S, StandardLaw, D, T>>,
    model_of: impl Fn(&S) -> &ElasticModel<D>,
) -> CliResult<BuiltWith<S, D, T>>
where
    Dim<D>: SceneDim<D>,
{
    let contact = KeyPath::root().key("contact");
    let zones = plans
        .iter()
        .map(|z| zone(&model, z))
        .collect::<CliResult<Vec<_>>>()?;
    let zone_laws = plans.iter().map(|z| law_name(&z.law).to_string()).collect();
    let held = supported_contactors(&model, &zones).map_err(|e| solver_error(&contact, e))?;
    let policies: Vec<Policy<'_>> = plans
        .iter()
        .map(|z| Policy {
            path: z.path.clone(),
            name: &z.name,
            contactor: &z.contactor,
            choice: z.supported,
        })
        .collect();
    let position = |n: usize| point(&model.node_position(n));
    let (leave_out, warnings) = resolve(&held, &policies, &position)?;
    let zones: Vec<_> = zones
        .into_iter()
        .zip(&leave_out)
        .map(|(z, l)| {
            if l.is_empty() {
                z
            } else {
                z.without_contactors(l)
            }
        })
        .collect();
    let sim = if <Dim<D> as SceneDim<D>>::CANDIDATES_FIRST {
        let candidates = recognize(&model, &zones).map_err(|e| solver_error(&contact, e))?;
        check_candidates(&candidates, plans, &zones, &model)?;
        Dim::<D>::check_facing(&candidates, &zones, &model)?;
        make(model, zones)?
    } else {
        let sim = make(model, zones)?;
        check_candidates(
            sim.candidates(),
            plans,
            sim.zones(),
            model_of(sim.structure()),
        )?;
        sim
    };
    Ok((sim, zone_laws, warnings))
}

/// Every zone must have a candidate, none deeper inside its target than the alert distance, and
/// one within the alert distance.
fn check_candidates<const D: usize>(
    candidates: &[Candidate<D>],
    plans: &[ZonePlan<D>],
    zones: &[ContactZone<StandardLaw, D>],
    model: &ElasticModel<D>,
) -> CliResult<()>
where
    Dim<D>: SceneDim<D>,
{
    for (z, (plan, zone)) in plans.iter().zip(zones).enumerate() {
        let p = &plan.path;
        let Some(closest) = candidates
            .iter()
            .filter(|c| c.zone == z)
            .min_by(|a, b| a.gap0.total_cmp(&b.gap0))
        else {
            bail!(
                p.key("target"),
                "zone `{}`: {}",
                plan.name,
                Dim::<D>::no_projection(&plan.contactor, zone.contactor.len())
            );
        };
        let x = point(&model.node_position(closest.node));
        if closest.gap0 < -plan.alert {
            bail!(
                p.key("target"),
                "zone `{}`: contactor node {} at {x} starts inside the target by {}, more \
                     than the alert distance {}: {}",
                plan.name,
                closest.node,
                -closest.gap0,
                plan.alert,
                <Dim<D> as SceneDim<D>>::INSIDE_HINT
            );
        }
        if closest.gap0 > plan.alert {
            bail!(
                p.key("alert_distance"),
                "zone `{}`: every contactor node is outside the alert distance {} at the start \
                     (the closest, node {} at {x}, has a gap of {}); move the target closer \
                     or raise `alert_distance`",
                plan.name,
                plan.alert,
                closest.node,
                closest.gap0
            );
        }
    }
    Ok(())
}

/// A zone's name at `p`: not empty, not used by an earlier zone (`names` collects them).
pub(super) fn zone_name(p: &KeyPath, name: &str, names: &mut BTreeSet<String>) -> CliResult<()> {
    if name.trim().is_empty() {
        bail!(
            p.key("name"),
            "`{}` is empty: a zone needs a name",
            p.key("name")
        );
    }
    if !names.insert(name.to_string()) {
        bail!(p.key("name"), "zone name `{name}` is used twice");
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn settings_3d_reads_the_paths_with_the_3d_default() {
        use contact_solver::FlexibilityMode;
        let s = SolverSpec {
            max_detection_passes: Some(7),
            flexibility: Some(FlexibilitySpec::Dense),
            ..SolverSpec::default()
        };
        let out = settings::<3>(&s).unwrap();
        assert_eq!(out.tuning.max_detection_passes, 7);
        assert_eq!(out.flexibility, FlexibilityMode::Dense);
        let auto = settings::<3>(&SolverSpec::default()).unwrap().flexibility;
        assert_eq!(auto, FlexibilityMode::Auto { dense_limit: 3000 });
        let s = SolverSpec {
            dense_limit: Some(10),
            ..SolverSpec::default()
        };
        let limited = settings::<3>(&s).unwrap().flexibility;
        assert_eq!(limited, FlexibilityMode::Auto { dense_limit: 10 });
        let s = SolverSpec {
            flexibility: Some(FlexibilitySpec::ActiveSet),
            ..SolverSpec::default()
        };
        assert_eq!(
            settings::<3>(&s).unwrap().flexibility,
            FlexibilityMode::ActiveSet
        );
        // dense_limit with another path is refused at its key, as in 2D
        let s = SolverSpec {
            flexibility: Some(FlexibilitySpec::MatrixFree),
            dense_limit: Some(10),
            ..SolverSpec::default()
        };
        let e = settings::<3>(&s).unwrap_err();
        assert_eq!(e.path.unwrap().to_string(), "solver.dense_limit");
    }
}
