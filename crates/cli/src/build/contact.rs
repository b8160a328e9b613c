//! Contact: the solver settings, the laws and the targets of the zones checked first, then the
//! zones built on the model's node sets, recognised (every zone must have a candidate within its
//! alert distance at the start), and the simulation made.

use super::checks::{
    at_least, expect, finite, finite2, law_error, list_names, node_set, non_negative, positive,
    solver_error,
};
use super::curves;
use super::supported::{Policy, point, resolve};
use crate::error::{CliError, CliResult, KeyPath};
use crate::raw::RawTarget;
use crate::scene::{
    AdhesionMethodSpec, AlgorithmSpec, FlexibilitySpec, Scene, SolverSpec, SupportedContactors,
};
use crate::spec::{ArcSideSpec, LawSpec, RccmSpec, SchemeSpec, TargetSpec};
use contact_laws::{BetaScheme, ContactLaw, Coulomb, Rccm, RccmParams, Signorini, StandardLaw};
use contact_solver::coupling::space::ContactSpace;
use contact_solver::local::adhesion::AdhesionMethod;
use contact_solver::local::stall::MIN_STALL_WINDOW;
use contact_solver::{
    Algorithm, ArcSide, Candidate, ContactSimulation, ContactZone, FlexibilityMode, RigidArc,
    RigidLine, SimulationSettings, recognize, supported_contactors,
};
use fem_core::{Dim, LinearElasticModel};
use std::collections::BTreeSet;
use std::f64::consts::TAU;

/// What a zone faces, checked; node sets are looked up in the mesh at build.
pub(super) enum TargetPlan {
    Line(RigidLine),
    Arc(RigidArc),
    NodePairs {
        set: String,
        normal: Option<[f64; 2]>,
    },
    Segments {
        set: String,
    },
}

/// A contact zone, checked, against a target of type `T` (2D: [`TargetPlan`], 3D: the solid
/// obstacle).
pub(super) struct ZonePlan<T> {
    pub(super) path: KeyPath,
    pub(super) name: String,
    pub(super) contactor: String,
    pub(super) law: StandardLaw,
    pub(super) law_name: &'static str,
    pub(super) alert: f64,
    pub(super) target: T,
    pub(super) supported: SupportedContactors,
}

/// The zones of a scene, checked, how many have adhesion and friction, and the solver settings.
pub(super) struct ContactPlan<T> {
    /// Zones, in the scene's order.
    pub(super) zones: Vec<ZonePlan<T>>,
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
        return Err(CliError::at(
            path,
            format!(
                "`{path}` = {n}: expected an integer in 1..={max} (more would let a step that \
                 does not converge run without end)"
            ),
        ));
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
            return Err(CliError::at(
                &p,
                format!("`{p}` is only read with algorithm = \"rccm-classic\" (its SOR factor)"),
            ));
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
                return Err(CliError::at(
                    &p,
                    format!(
                        "`{p}` = \"newton\" does not combine with algorithm = \"rccm-classic\" \
                         (the classical solver is a fixed point by definition): use \"fixed-point\" \
                         or leave the key out"
                    ),
                ));
            }
            AdhesionMethodSpec::Newton => AdhesionMethod::Newton,
        };
    }
    if let Some(w) = s.adhesion_warm_start {
        let p = root.key("adhesion_warm_start");
        if w && out.tuning.adhesion_method == AdhesionMethod::FixedPoint {
            return Err(CliError::at(
                &p,
                format!(
                    "`{p}` = true is only read with adhesion_method = \"newton\" (it starts \
                     Newton from the previous step's reactions)"
                ),
            ));
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
            return Err(CliError::at(
                &p,
                format!(
                    "`{p}` = {n}: expected 0 (no stall detection) or an integer in \
                     {MIN_STALL_WINDOW}..={MAX_ITERATIONS}"
                ),
            ));
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
            return Err(CliError::at(
                &p,
                format!("`{p}` only applies to flexibility = \"auto\" (here {other:?})"),
            ));
        }
        FlexibilitySpec::Dense => FlexibilityMode::Dense,
        FlexibilitySpec::ActiveSet => FlexibilityMode::ActiveSet,
        FlexibilitySpec::MatrixFree => FlexibilityMode::MatrixFree,
    };
    Ok(out)
}

/// RCCM parameters, checked (the θ key against the scheme, then the law's own checks).
pub(super) fn rccm_params(path: &KeyPath, r: &RccmSpec) -> CliResult<RccmParams> {
    let scheme = match (r.scheme, r.theta) {
        (SchemeSpec::ImplicitEuler, None) => BetaScheme::ImplicitEuler,
        (SchemeSpec::ImplicitEuler, Some(_)) => {
            let p = path.key("theta");
            return Err(CliError::at(
                &p,
                format!(
                    "`{p}` is only read with scheme = \"theta\" (the scheme is implicit_euler)"
                ),
            ));
        }
        (SchemeSpec::Theta, Some(t)) => {
            let p = path.key("theta");
            BetaScheme::Theta(expect(
                &p,
                t,
                (0.0..=1.0).contains(&t),
                "a value in [0, 1]",
            )?)
        }
        (SchemeSpec::Theta, None) => {
            return Err(CliError::at(
                path,
                format!("`{path}`: scheme = \"theta\" needs `theta` (a value in [0, 1])"),
            ));
        }
    };
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

/// The law of a zone, checked, and its name for reports.
pub(super) fn law(path: &KeyPath, l: &LawSpec) -> CliResult<(StandardLaw, &'static str)> {
    Ok(match l {
        LawSpec::Signorini {} => (Signorini.into(), "signorini"),
        LawSpec::Coulomb { mu } => (
            Coulomb::new(*mu).map_err(|e| law_error(path, e))?.into(),
            "coulomb",
        ),
        LawSpec::Rccm(r) => {
            let p = rccm_params(path, r)?;
            (Rccm::new(p).map_err(|e| law_error(path, e))?.into(), "rccm")
        }
    })
}

/// Checks `[[contact]]` (unique names, alert distances, laws and the targets' geometry, read by
/// `target` at each zone's `target` key) and `[solver]`, in a scene of dimension `D`.
pub(super) fn validate<const D: usize, T>(
    scene: &Scene,
    target: impl Fn(&KeyPath, &RawTarget) -> CliResult<T>,
) -> CliResult<ContactPlan<T>>
where
    Dim<D>: ContactSpace<D>,
{
    let root = KeyPath::root();
    if scene.contact.is_empty() {
        return Err(CliError::at(
            &root,
            "the scene has no [[contact]] zone (bipo solves contact problems)",
        ));
    }
    let settings = settings::<D>(&scene.solver)?;
    let mut zones = Vec::new();
    let mut names = BTreeSet::new();
    let (mut adhesive, mut friction) = (0, 0);
    for (i, z) in scene.contact.iter().enumerate() {
        let p = root.key("contact").index(i);
        zone_name(&p, &z.name, &mut names)?;
        let alert = non_negative(&p.key("alert_distance"), z.alert_distance)?;
        let (l, law_name) = law(&p.key("law"), &z.law.resolve(&p.key("law"))?)?;
        if l.has_adhesion() {
            adhesive += 1;
        }
        if l.has_friction() {
            friction += 1;
        }
        let target = target(&p.key("target"), &z.target)?;
        zones.push(ZonePlan {
            path: p,
            name: z.name.clone(),
            contactor: z.contactor.clone(),
            law: l,
            law_name,
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
                return Err(CliError::at(
                    &p,
                    format!(
                        "`{p}`: no [[contact]] zone is named `{zone}` (zones: {})",
                        list_names(names.iter().map(String::as_str))
                    ),
                ));
            }
            let (l, _) = law(&p, &raw.resolve(&p)?)?;
            laws.push((zone.clone(), l));
        }
        out.push(laws);
    }
    Ok(out)
}

/// The target of a 2D zone at `tp`, its geometry checked (rigid lines and arcs are built here).
pub(super) fn target(tp: &KeyPath, t: &RawTarget) -> CliResult<TargetPlan> {
    Ok(match &t.resolve(tp)? {
        TargetSpec::Line { a, b } => {
            let a = finite2(&tp.key("a"), *a)?;
            let b = finite2(&tp.key("b"), *b)?;
            let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
            if !(dx.is_finite() && dy.is_finite() && dx.hypot(dy).is_finite()) {
                return Err(CliError::at(
                    tp,
                    format!(
                        "`{tp}`: the length of the LINE from {a:?} to {b:?} overflows (expected \
                         end points whose distance stays finite)"
                    ),
                ));
            }
            TargetPlan::Line(RigidLine::new(a, b).map_err(|e| solver_error(tp, e))?)
        }
        TargetSpec::Arc {
            center,
            radius,
            start_angle,
            sweep,
            side,
        } => {
            let center = finite2(&tp.key("center"), *center)?;
            let radius = positive(&tp.key("radius"), *radius)?;
            let start = finite(&tp.key("start_angle"), *start_angle)?;
            let sweep = match sweep {
                Some(s) => expect(
                    &tp.key("sweep"),
                    *s,
                    *s > 0.0 && *s <= TAU * (1.0 + 1e-12),
                    "an angle in (0, 2π] radians",
                )?,
                None => TAU,
            };
            let side = match side {
                ArcSideSpec::Outside => ArcSide::Outside,
                ArcSideSpec::Inside => ArcSide::Inside,
            };
            TargetPlan::Arc(
                RigidArc::new(center, radius, start, sweep, side)
                    .map_err(|e| solver_error(tp, e))?,
            )
        }
        TargetSpec::NodePairs { set, normal } => {
            if let Some(n) = normal {
                let n = finite2(&tp.key("normal"), *n)?;
                if n[0] == 0.0 && n[1] == 0.0 {
                    return Err(CliError::at(
                        &tp.key("normal"),
                        "the normal [0, 0] has no direction",
                    ));
                }
            }
            TargetPlan::NodePairs {
                set: set.clone(),
                normal: normal.map(|n| n.0),
            }
        }
        TargetSpec::Segments { set } => TargetPlan::Segments { set: set.clone() },
    })
}

/// The simulation, each zone's law name, and the warnings of [`build`].
pub(super) type BuiltContact = (
    ContactSimulation<LinearElasticModel, StandardLaw>,
    Vec<String>,
    Vec<String>,
);

/// The zones on the model's node sets, recognised and checked, and the simulation; also gives
/// each zone's law name, and the warnings (contactor nodes held by a support, left out).
pub(super) fn build(
    model: LinearElasticModel,
    plan: Vec<ZonePlan<TargetPlan>>,
    settings: SimulationSettings,
) -> CliResult<BuiltContact> {
    let root = KeyPath::root();
    let mut zones = Vec::new();
    let mut zone_laws = Vec::new();
    let mut policies = Vec::new();
    for z in plan {
        policies.push((
            z.path.clone(),
            z.name.clone(),
            z.contactor.clone(),
            z.supported,
        ));
        let p = &z.path;
        let mesh = model.mesh();
        let mut contactor = node_set(&p.key("contactor"), mesh, &z.contactor)?;
        zone_laws.push(z.law_name.to_string());
        let tp = p.key("target");
        let (l, alert) = (z.law, z.alert);
        let zone = match z.target {
            TargetPlan::Line(line) => ContactZone::rigid(&z.name, contactor, line, l, alert),
            TargetPlan::Arc(arc) => ContactZone::rigid(&z.name, contactor, arc, l, alert),
            TargetPlan::NodePairs { set, normal } => {
                let targets = match normal {
                    Some(_) => node_set(&tp.key("set"), mesh, &set)?,
                    None => curves::target_nodes(&tp.key("set"), mesh, &set)?.0,
                };
                curves::match_pairs(
                    mesh,
                    (z.contactor.as_str(), contactor.as_mut_slice()),
                    (set.as_str(), targets.as_slice()),
                );
                if targets.len() != contactor.len() {
                    return Err(CliError::at(
                        &tp.key("set"),
                        format!(
                            "node set `{set}` has {} nodes but the contactor set `{}` has {}: \
                             node pairs need sets of the same length, in matching order",
                            targets.len(),
                            z.contactor,
                            contactor.len()
                        ),
                    ));
                }
                if let Some((c, _)) = contactor.iter().zip(&targets).find(|(c, t)| c == t) {
                    return Err(CliError::at(
                        &tp.key("set"),
                        format!(
                            "`{}` = \"{set}\": node {c} of the contactor set `{}` is paired \
                             with itself (a node cannot touch itself; pair two distinct surfaces)",
                            tp.key("set"),
                            z.contactor
                        ),
                    ));
                }
                ContactZone::node_pairs(&z.name, contactor, targets, normal, l, alert)
            }
            TargetPlan::Segments { set } => {
                let (mut surface, closed) = curves::target_nodes(&tp.key("set"), mesh, &set)?;
                if closed {
                    surface.push(surface[0]);
                }
                if surface.len() < 2 {
                    return Err(CliError::at(
                        &tp.key("set"),
                        format!(
                            "node set `{set}` has {} node: a target polyline needs at least two",
                            surface.len()
                        ),
                    ));
                }
                curves::check_polyline(&tp.key("set"), &set, &model, &surface)?;
                ContactZone::node_to_segment(&z.name, contactor, surface, l, alert)
            }
        };
        let zone = match curves::contactor_areas(&model, &z.contactor, &zone.contactor) {
            Some(areas) => zone.with_areas(areas),
            None => zone,
        };
        zones.push(zone);
    }
    let held =
        supported_contactors(&model, &zones).map_err(|e| solver_error(&root.key("contact"), e))?;
    let policies: Vec<Policy<'_>> = policies
        .iter()
        .map(|(path, name, contactor, choice)| Policy {
            path: path.clone(),
            name,
            contactor,
            choice: *choice,
        })
        .collect();
    let position = |n: usize| point(&fem_core::Structure::node_position(&model, n));
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
    let candidates =
        recognize(&model, &zones).map_err(|e| solver_error(&root.key("contact"), e))?;
    check_candidates(&candidates, &zones, &model)?;
    curves::check_facing(&candidates, &zones, &model)?;
    let sim = ContactSimulation::new(model, zones, settings)
        .map_err(|e| solver_error(&root.key("contact"), e))?;
    Ok((sim, zone_laws, warnings))
}

/// Every zone must have a candidate, none deeper inside its target than the alert distance, and
/// one within the alert distance.
fn check_candidates(
    candidates: &[Candidate],
    zones: &[ContactZone<StandardLaw>],
    model: &LinearElasticModel,
) -> CliResult<()> {
    use fem_core::Structure;
    for (z, zone) in zones.iter().enumerate() {
        let p = KeyPath::root().key("contact").index(z);
        let mine: Vec<&Candidate> = candidates.iter().filter(|c| c.zone == z).collect();
        if mine.is_empty() {
            return Err(CliError::at(
                &p.key("target"),
                format!(
                    "zone `{}`: none of its {} contactor nodes projects onto the target \
                     (a LINE or ARC must face the nodes; check its ends and its side)",
                    zone.name,
                    zone.contactor.len()
                ),
            ));
        }
        let closest = mine
            .iter()
            .min_by(|a, b| a.gap0.total_cmp(&b.gap0))
            .expect("non-empty");
        let deepest = mine
            .iter()
            .min_by(|a, b| a.gap0.total_cmp(&b.gap0))
            .expect("non-empty");
        if deepest.gap0 < -zone.alert_distance {
            let x = model.node_position(deepest.node);
            return Err(CliError::at(
                &p.key("target"),
                format!(
                    "zone `{}`: contactor node {} at ({}, {}) starts inside the target by {}, more \
                     than the alert distance {}: is the target on the right side (a LINE has the \
                     contactor on its left, from a to b; an ARC has `side`)?",
                    zone.name, deepest.node, x[0], x[1], -deepest.gap0, zone.alert_distance
                ),
            ));
        }
        if closest.gap0 > zone.alert_distance {
            let x = model.node_position(closest.node);
            return Err(CliError::at(
                &p.key("alert_distance"),
                format!(
                    "zone `{}`: every contactor node is outside the alert distance {} at the start \
                     (the closest, node {} at ({}, {}), has a gap of {}); move the target closer \
                     or raise `alert_distance`",
                    zone.name, zone.alert_distance, closest.node, x[0], x[1], closest.gap0
                ),
            ));
        }
    }
    Ok(())
}

/// A zone's name at `p`: not empty, not used by an earlier zone (`names` collects them).
pub(super) fn zone_name(p: &KeyPath, name: &str, names: &mut BTreeSet<String>) -> CliResult<()> {
    if name.trim().is_empty() {
        return Err(CliError::at(
            &p.key("name"),
            format!("`{}` is empty: a zone needs a name", p.key("name")),
        ));
    }
    if !names.insert(name.to_string()) {
        return Err(CliError::at(
            &p.key("name"),
            format!("zone name `{name}` is used twice"),
        ));
    }
    Ok(())
}
