//! From a parsed [`Scene`] to a ready-to-step study: every value is checked with its key path,
//! then the mesh, the model, the contact zones and the simulation are built through the
//! library's public API, and the zones are recognised (a zone with no candidate within its
//! alert distance at the start is an error).

use crate::error::{CliError, CliResult, KeyPath};
use crate::scene::*;
use crate::spec::*;
use bipo::presets::{DelaminationSpec, ShearSpec};
use contact_laws::{BetaScheme, Coulomb, LawError, Rccm, RccmParams, Signorini, StandardLaw};
use contact_solver::error::chain;
use contact_solver::{
    Algorithm, ArcSide, Candidate, ContactSimulation, ContactZone, DEFAULT_DENSE_LIMIT,
    FlexibilityMode, RigidArc, RigidLine, SimulationSettings, SolverError, recognize,
};
use fem_core::generate::{Grading, Layer, PileSpec, RectangleSpec, TipCorner};
use fem_core::{
    Component, ElementKind, FemError, Idealization, LinearElasticModel, Material, Mesh, Supports,
};
use std::collections::{BTreeMap, BTreeSet};
use std::f64::consts::TAU;
use std::path::{Path, PathBuf};

/// A scene file read from disk.
pub struct Loaded {
    /// Its path.
    pub path: PathBuf,
    /// Its text.
    pub source: String,
    /// Its content.
    pub scene: Scene,
}

/// Parses scene text.
pub fn parse(source: &str) -> CliResult<Scene> {
    let de = toml::Deserializer::parse(source).map_err(|e| CliError {
        file: None,
        span: e.span(),
        path: None,
        message: format!("invalid TOML: {}", e.message()),
        code: 2,
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
            file: None,
            span: inner.span(),
            path: None,
            message,
            code: 2,
        }
    })
}

// ---------------------------------------------------------------------------------------------
// value checks

fn expect(path: &KeyPath, value: f64, ok: bool, expected: &str) -> CliResult<f64> {
    if ok {
        Ok(value)
    } else {
        Err(CliError::at(
            path,
            format!("`{path}` = {value:?}: expected {expected}"),
        ))
    }
}

fn positive(path: &KeyPath, v: f64) -> CliResult<f64> {
    expect(path, v, v.is_finite() && v > 0.0, "a finite number > 0")
}

fn non_negative(path: &KeyPath, v: f64) -> CliResult<f64> {
    expect(path, v, v.is_finite() && v >= 0.0, "a finite number >= 0")
}

fn finite(path: &KeyPath, v: f64) -> CliResult<f64> {
    expect(path, v, v.is_finite(), "a finite number (not nan or inf)")
}

fn finite2(path: &KeyPath, v: Pair) -> CliResult<[f64; 2]> {
    let v = v.0;
    finite(&path.index(0), v[0])?;
    finite(&path.index(1), v[1])?;
    Ok(v)
}

fn at_least(path: &KeyPath, v: usize, min: usize) -> CliResult<usize> {
    if v >= min {
        Ok(v)
    } else {
        Err(CliError::at(
            path,
            format!("`{path}` = {v}: expected an integer >= {min}"),
        ))
    }
}

fn grading(path: &KeyPath, g: GradingSpec) -> CliResult<Grading> {
    Ok(match g {
        GradingSpec::Uniform {} => Grading::Uniform,
        GradingSpec::Geometric { ratio } => Grading::Geometric {
            ratio: positive(&path.key("ratio"), ratio)?,
        },
        GradingSpec::BothEnds { ratio } => Grading::BothEnds {
            ratio: positive(&path.key("ratio"), ratio)?,
        },
    })
}

fn kind(e: Element) -> ElementKind {
    match e {
        Element::P1 => ElementKind::Tri3,
        Element::P2 => ElementKind::Tri6,
    }
}

/// Name of an element kind for messages.
pub fn kind_name(k: ElementKind) -> &'static str {
    match k {
        ElementKind::Tri3 => "P1 (3-node triangles)",
        ElementKind::Tri6 => "P2 (6-node triangles)",
    }
}

fn fem(path: &KeyPath, e: FemError) -> CliError {
    let hint = match e {
        FemError::NotPositiveDefinite { .. } => {
            " — add supports so that the body cannot move as a rigid body"
        }
        _ => "",
    };
    CliError::at(path, format!("{}{hint}", chain(&e)))
}

fn law_error(path: &KeyPath, e: LawError) -> CliError {
    match e {
        LawError::InvalidParameter {
            name,
            value,
            expected,
        } => {
            let p = path.key(name);
            CliError::at(&p, format!("`{p}` = {value:?}: expected {expected}"))
        }
        LawError::InvalidExponent { m } => {
            let p = path.key("m");
            CliError::at(&p, format!("`{p}` = {m}: expected 1 or 2"))
        }
        other => CliError::at(path, chain(&other)),
    }
}

// ---------------------------------------------------------------------------------------------
// time functions

/// A piecewise linear function of time, constant beyond its first and last points.
#[derive(Clone, Debug, PartialEq)]
pub struct TimeFunction {
    points: Vec<[f64; 2]>,
}

impl TimeFunction {
    /// Value at `t`.
    pub fn eval(&self, t: f64) -> f64 {
        let p = &self.points;
        if t <= p[0][0] {
            return p[0][1];
        }
        for w in p.windows(2) {
            let ([t0, v0], [t1, v1]) = (w[0], w[1]);
            if t <= t1 {
                return v0 + (v1 - v0) * (t - t0) / (t1 - t0);
            }
        }
        p[p.len() - 1][1]
    }
}

fn time_function(path: &KeyPath, pts: &[Pair]) -> CliResult<TimeFunction> {
    let pts: Vec<[f64; 2]> = pts.iter().map(|p| p.0).collect();
    if pts.is_empty() {
        return Err(CliError::at(
            path,
            format!("`{path}` is empty: expected a table of [time, value] points"),
        ));
    }
    for (i, p) in pts.iter().enumerate() {
        finite2(&path.index(i), Pair(*p))?;
        if i > 0 && p[0] <= pts[i - 1][0] {
            let q = path.index(i).index(0);
            return Err(CliError::at(
                &q,
                format!(
                    "`{q}` = {}: times must increase strictly (the previous point is at t = {})",
                    p[0],
                    pts[i - 1][0]
                ),
            ));
        }
    }
    Ok(TimeFunction { points: pts })
}

// ---------------------------------------------------------------------------------------------
// phases

/// One phase of load steps.
#[derive(Clone, Debug)]
pub struct Phase {
    /// Name.
    pub name: String,
    /// Steps.
    pub steps: usize,
    /// Start time.
    pub t0: f64,
    /// End time.
    pub t1: f64,
    /// Function overrides: load or support name → function name.
    pub overrides: BTreeMap<String, String>,
    /// Reset displacements at the end.
    pub reset_displacements: bool,
}

impl Phase {
    /// Time at the end of step `k` (1-based) of this phase.
    pub fn time(&self, k: usize) -> f64 {
        if k == self.steps {
            self.t1
        } else {
            self.t0 + (self.t1 - self.t0) * k as f64 / self.steps as f64
        }
    }
}

// ---------------------------------------------------------------------------------------------
// studies

/// A support ready to apply.
#[derive(Clone, Debug)]
pub struct SupportRt {
    /// Name.
    pub name: Option<String>,
    /// Nodes.
    pub nodes: Vec<usize>,
    /// Components.
    pub components: Vec<Component>,
    /// Value.
    pub value: f64,
    /// Function name.
    pub function: Option<String>,
    /// Phase mask.
    pub phases: Vec<bool>,
}

/// What a load is.
#[derive(Clone, Debug)]
pub enum LoadKind {
    /// Edge traction.
    Traction(String, [f64; 2]),
    /// Force on each node.
    Nodal(Vec<usize>, [f64; 2]),
    /// Body force.
    Body([f64; 2]),
    /// Self-weight.
    Gravity,
}

/// A load ready to apply.
#[derive(Clone, Debug)]
pub struct LoadRt {
    /// Name.
    pub name: Option<String>,
    /// Kind.
    pub kind: LoadKind,
    /// Function name.
    pub function: Option<String>,
    /// Phase mask.
    pub phases: Vec<bool>,
}

/// A scene described key by key.
pub struct Custom {
    /// The simulation.
    pub sim: ContactSimulation<LinearElasticModel, StandardLaw>,
    /// Supports.
    pub supports: Vec<SupportRt>,
    /// Loads.
    pub loads: Vec<LoadRt>,
    /// Time functions.
    pub functions: BTreeMap<String, TimeFunction>,
}

/// The library's scene of a preset.
pub enum Library {
    /// Delamination or shear (one loading phase).
    Seed(Box<bipo::presets::Scene>),
    /// The pile pull-out (three phases).
    Pile(Box<bipo::presets::PulloutScene>),
}

/// A seed study built by the library.
pub struct PresetStudy {
    /// `delamination`, `shear` or `pile`.
    pub kind: &'static str,
    /// The library's scene.
    pub scene: Library,
}

impl PresetStudy {
    /// The simulation.
    pub fn sim(&self) -> &ContactSimulation<LinearElasticModel, Rccm> {
        match &self.scene {
            Library::Seed(s) => &s.simulation,
            Library::Pile(p) => &p.simulation,
        }
    }
}

/// The body of a study.
pub enum Body {
    /// Key by key.
    Custom(Box<Custom>),
    /// A preset.
    Preset(Box<PresetStudy>),
}

/// A scene ready to run.
pub struct Study {
    /// Title.
    pub title: String,
    /// Units.
    pub units: Units,
    /// The body.
    pub body: Body,
    /// Phases.
    pub phases: Vec<Phase>,
    /// Outputs.
    pub output: OutputSpec,
    /// Plots (validated).
    pub plots: Vec<PlotSpec>,
    /// Zone names.
    pub zone_names: Vec<String>,
    /// Zone law names.
    pub zone_laws: Vec<String>,
    /// Zones with adhesion.
    pub adhesive_zones: usize,
    /// Zones with friction.
    pub friction_zones: usize,
}

impl Study {
    /// The candidates.
    pub fn candidates(&self) -> &[Candidate] {
        match &self.body {
            Body::Custom(c) => c.sim.candidates(),
            Body::Preset(p) => p.sim().candidates(),
        }
    }

    /// The model.
    pub fn model(&self) -> &LinearElasticModel {
        match &self.body {
            Body::Custom(c) => c.sim.structure(),
            Body::Preset(p) => p.sim().structure(),
        }
    }

    /// Alert distance of each zone.
    pub fn alert_distances(&self) -> Vec<f64> {
        match &self.body {
            Body::Custom(c) => c.sim.zones().iter().map(|z| z.alert_distance).collect(),
            Body::Preset(p) => p.sim().zones().iter().map(|z| z.alert_distance).collect(),
        }
    }

    /// Total steps.
    pub fn total_steps(&self) -> usize {
        self.phases.iter().map(|p| p.steps).sum()
    }
}

fn solver_settings(s: &SolverSpec) -> CliResult<SimulationSettings> {
    let root = KeyPath::root().key("solver");
    let mut out = SimulationSettings::default();
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
        out.solver.rho_scale = positive(&root.key("rho_scale"), r)?;
    }
    if let Some(n) = s.max_iterations {
        out.solver.max_iterations = at_least(&root.key("max_iterations"), n, 1)?;
    }
    if let Some(w) = s.omega {
        let p = root.key("omega");
        out.solver.omega = expect(&p, w, w > 0.0 && w < 2.0, "a factor in (0, 2)")?;
    }
    if let Some(t) = s.adhesion_tol {
        out.adhesion_tol = positive(&root.key("adhesion_tol"), t)?;
    }
    if let Some(n) = s.max_adhesion_iterations {
        out.max_adhesion_iterations = at_least(&root.key("max_adhesion_iterations"), n, 1)?;
    }
    if let Some(n) = s.max_detection_passes {
        out.max_detection_passes = at_least(&root.key("max_detection_passes"), n, 1)?;
    }
    if let Some(b) = s.accept_non_converged {
        out.solver.accept_non_converged = b;
    }
    let dense_limit = s.dense_limit.unwrap_or(DEFAULT_DENSE_LIMIT);
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

fn rccm_params(path: &KeyPath, r: &RccmSpec) -> CliResult<RccmParams> {
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

fn law(path: &KeyPath, l: &LawSpec) -> CliResult<(StandardLaw, &'static str)> {
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

fn phases_of(scene: &Scene, total_default: Option<(usize, f64)>) -> CliResult<Vec<Phase>> {
    let mut out = Vec::new();
    match (&scene.steps, scene.phases.is_empty(), total_default) {
        (Some(_), false, _) => {
            return Err(CliError::at(
                &KeyPath::root().key("phases"),
                "give either [steps] (one phase) or [[phases]], not both",
            ));
        }
        (Some(s), true, _) => {
            let p = KeyPath::root().key("steps");
            out.push(Phase {
                name: "steps".into(),
                steps: at_least(&p.key("count"), s.count, 1)?,
                t0: 0.0,
                t1: positive(&p.key("duration"), s.duration)?,
                overrides: BTreeMap::new(),
                reset_displacements: false,
            });
        }
        (None, false, _) => {
            let mut t = 0.0;
            let mut names = BTreeSet::new();
            for (i, ph) in scene.phases.iter().enumerate() {
                let p = KeyPath::root().key("phases").index(i);
                if !names.insert(ph.name.clone()) {
                    return Err(CliError::at(
                        &p.key("name"),
                        format!("phase name `{}` is used twice", ph.name),
                    ));
                }
                let d = positive(&p.key("duration"), ph.duration)?;
                out.push(Phase {
                    name: ph.name.clone(),
                    steps: at_least(&p.key("steps"), ph.steps, 1)?,
                    t0: t,
                    t1: t + d,
                    overrides: ph.functions.clone(),
                    reset_displacements: ph.reset_displacements,
                });
                t += d;
            }
        }
        (None, true, Some((steps, duration))) => out.push(Phase {
            name: "loading".into(),
            steps,
            t0: 0.0,
            t1: duration,
            overrides: BTreeMap::new(),
            reset_displacements: false,
        }),
        (None, true, None) => {
            return Err(CliError::at(
                &KeyPath::root(),
                "the scene has no load steps: add [steps] with `count` and `duration`, or [[phases]]",
            ));
        }
    }
    Ok(out)
}

fn phase_mask(
    path: &KeyPath,
    list: &Option<Vec<String>>,
    phases: &[Phase],
) -> CliResult<Vec<bool>> {
    match list {
        None => Ok(vec![true; phases.len()]),
        Some(names) => {
            let mut mask = vec![false; phases.len()];
            for (i, n) in names.iter().enumerate() {
                match phases.iter().position(|p| &p.name == n) {
                    Some(k) => mask[k] = true,
                    None => {
                        let p = path.index(i);
                        return Err(CliError::at(
                            &p,
                            format!(
                                "`{p}` = \"{n}\": no such phase (phases: {})",
                                list_names(phases.iter().map(|p| p.name.as_str()))
                            ),
                        ));
                    }
                }
            }
            Ok(mask)
        }
    }
}

fn list_names<'a>(names: impl Iterator<Item = &'a str>) -> String {
    let v: Vec<String> = names.map(|n| format!("`{n}`")).collect();
    if v.is_empty() {
        "none".into()
    } else {
        v.join(", ")
    }
}

fn node_set(path: &KeyPath, mesh: &Mesh, name: &str) -> CliResult<Vec<usize>> {
    mesh.node_set(name).map(|s| s.to_vec()).map_err(|_| {
        CliError::at(
            path,
            format!(
                "`{path}` = \"{name}\": the mesh has no node set of that name (node sets: {})",
                list_names(mesh.node_set_names())
            ),
        )
    })
}

fn check_function(
    path: &KeyPath,
    name: &Option<String>,
    f: &BTreeMap<String, TimeFunction>,
) -> CliResult<()> {
    if let Some(n) = name
        && !f.contains_key(n)
    {
        return Err(CliError::at(
            path,
            format!(
                "`{path}` = \"{n}\": no such function in [functions] (functions: {})",
                list_names(f.keys().map(|k| k.as_str()))
            ),
        ));
    }
    Ok(())
}

fn preset_only(scene: &Scene) -> CliResult<()> {
    let present = [
        ("mesh", scene.mesh.is_some()),
        ("analysis", scene.analysis.is_some()),
        ("materials", !scene.materials.is_empty()),
        ("initial_stress", scene.initial_stress.is_some()),
        ("functions", !scene.functions.is_empty()),
        ("supports", !scene.supports.is_empty()),
        ("loads", !scene.loads.is_empty()),
        ("contact", !scene.contact.is_empty()),
        ("steps", scene.steps.is_some()),
        ("phases", !scene.phases.is_empty()),
    ];
    if let Some((k, _)) = present.iter().find(|(_, p)| *p) {
        return Err(CliError::at(
            &KeyPath::root().key(k),
            format!(
                "`{k}` cannot be combined with [preset]: the preset builds its own mesh, \
                 supports, loads, contact zone and steps (override them inside [preset])"
            ),
        ));
    }
    Ok(())
}

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
                return Err(CliError::at(
                    &p,
                    format!("`{p}` is only read with scheme = \"theta\""),
                ));
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

fn solver_error(path: &KeyPath, e: SolverError) -> CliError {
    match e {
        SolverError::Structure(f) => fem(path, f),
        other => CliError::at(path, chain(&other)),
    }
}

fn build_preset(scene: &Scene, preset: &Preset) -> CliResult<Study> {
    preset_only(scene)?;
    if let Preset::Pile { .. } = preset {
        return build_pile(scene, preset);
    }
    let settings = solver_settings(&scene.solver)?;
    let p = KeyPath::root().key("preset");
    macro_rules! set {
        ($spec:ident, $field:ident, positive) => {
            if let Some(v) = $field {
                $spec.$field = positive(&p.key(stringify!($field)), *v)?;
            }
        };
        ($spec:ident, $field:ident, finite) => {
            if let Some(v) = $field {
                $spec.$field = finite(&p.key(stringify!($field)), *v)?;
            }
        };
        ($spec:ident, $field:ident, count) => {
            if let Some(v) = $field {
                $spec.$field = at_least(&p.key(stringify!($field)), *v, 1)?;
            }
        };
    }
    let poisson_ok = |v: &Option<f64>| -> CliResult<Option<f64>> {
        match v {
            Some(x) => Ok(Some(expect(
                &p.key("poisson"),
                *x,
                *x > -1.0 && *x < 0.5,
                "a Poisson's ratio in (-1, 0.5)",
            )?)),
            None => Ok(None),
        }
    };
    let (kind, built) = match preset {
        Preset::Delamination {
            length,
            height,
            young,
            poisson,
            nx,
            ny,
            element,
            lift,
            duration,
            steps,
            interface,
        } => {
            let mut spec = DelaminationSpec::default();
            set!(spec, length, positive);
            set!(spec, height, positive);
            set!(spec, young, positive);
            if let Some(v) = poisson_ok(poisson)? {
                spec.poisson = v;
            }
            set!(spec, nx, count);
            set!(spec, ny, count);
            if let Some(e) = element {
                spec.kind = kind(*e);
            }
            set!(spec, lift, finite);
            set!(spec, duration, positive);
            set!(spec, steps, count);
            spec.interface = override_rccm(&p.key("interface"), spec.interface, interface)?;
            (
                "delamination",
                spec.build(settings).map_err(|e| solver_error(&p, e))?,
            )
        }
        Preset::Shear {
            length,
            height,
            young,
            poisson,
            nx,
            ny,
            element,
            press,
            push,
            duration,
            steps,
            interface,
        } => {
            let mut spec = ShearSpec::default();
            set!(spec, length, positive);
            set!(spec, height, positive);
            set!(spec, young, positive);
            if let Some(v) = poisson_ok(poisson)? {
                spec.poisson = v;
            }
            set!(spec, nx, count);
            set!(spec, ny, count);
            if let Some(e) = element {
                spec.kind = kind(*e);
            }
            set!(spec, press, finite);
            set!(spec, push, finite);
            set!(spec, duration, positive);
            set!(spec, steps, count);
            spec.interface = override_rccm(&p.key("interface"), spec.interface, interface)?;
            (
                "shear",
                spec.build(settings).map_err(|e| solver_error(&p, e))?,
            )
        }
        Preset::Pile { .. } => unreachable!("handled above"),
    };
    finish_preset(scene, kind, Library::Seed(Box::new(built)), None)
}

fn phase(name: &str, steps: usize, t0: f64, t1: f64) -> Phase {
    Phase {
        name: name.into(),
        steps,
        t0,
        t1,
        overrides: BTreeMap::new(),
        reset_displacements: false,
    }
}

fn finish_preset(
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
    use contact_laws::ContactLaw;
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
        output: scene.output.clone(),
        plots: Vec::new(),
        zone_names,
        zone_laws,
        adhesive_zones,
        friction_zones,
    };
    check_outputs(scene, &mut study)?;
    Ok(study)
}

fn build_pile(scene: &Scene, preset: &Preset) -> CliResult<Study> {
    use bipo::presets::{Installation, PulloutSpec};
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
        steps,
        alert_distance,
        interface,
        mesh,
    } = preset
    else {
        unreachable!("called for the pile preset")
    };
    let settings = solver_settings(&scene.solver)?;
    let p = KeyPath::root().key("preset");
    let mut spec = match site {
        Some(Site::Cran) => PulloutSpec::cran(),
        _ => PulloutSpec::plancoet(),
    };
    if *coulomb {
        spec = spec.with_coulomb_interface();
    }
    for (name, value, slot, poisson) in [
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
            *slot = if poisson {
                expect(
                    &p.key(name),
                    *v,
                    *v > -1.0 && *v < 0.5,
                    "a Poisson's ratio in (-1, 0.5)",
                )?
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
    let steps = spec.steps;
    let built = spec.build(settings).map_err(|e| solver_error(&p, e))?;
    let phases = vec![
        phase("geostatic", 1, 0.0, 1.0),
        phase("installation", 1, 1.0, 2.0),
        phase("pullout", steps, 2.0, 2.0 + steps as f64),
    ];
    finish_preset(scene, "pile", Library::Pile(Box::new(built)), Some(phases))
}

/// Validates the scene and builds the study (mesh, model, zones, recognition, simulation).
pub fn build(loaded: &Loaded) -> CliResult<Study> {
    let scene = &loaded.scene;
    if let Some(preset) = &scene.preset {
        let preset = preset.resolve(&KeyPath::root().key("preset"))?;
        return build_preset(scene, &preset);
    }
    let root = KeyPath::root();
    let base_dir = loaded
        .path
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_default();

    // time functions and phases first: supports and loads refer to them
    let mut functions = BTreeMap::new();
    for (name, pts) in &scene.functions {
        functions.insert(
            name.clone(),
            time_function(&root.key("functions").key(name), pts)?,
        );
    }
    let phases = phases_of(scene, None)?;

    // mesh
    let mesh_raw = scene.mesh.as_ref().ok_or_else(|| {
        CliError::at(
            &root,
            "the scene has no [mesh] (give `generator = \"rectangle\"`, `\"pile\"` or `\"gmsh\"`) \
             and no [preset]",
        )
    })?;
    let mp = root.key("mesh");
    let mesh_spec = &mesh_raw.resolve(&mp)?;
    let analysis = scene.analysis.ok_or_else(|| {
        CliError::at(
            &root,
            "the scene has no [analysis] (type = \"plane_strain\", \"plane_stress\" or \"axisymmetric\")",
        )
    })?;
    let analysis = analysis.resolve(&root.key("analysis"))?;
    let idealization = match analysis {
        Analysis::PlaneStrain {} => Idealization::PlaneStrain,
        Analysis::PlaneStress { thickness } => Idealization::PlaneStress {
            thickness: positive(&root.key("analysis").key("thickness"), thickness)?,
        },
        Analysis::Axisymmetric {} => Idealization::Axisymmetric,
    };
    let mesh = build_mesh(&mp, mesh_spec, &base_dir, idealization)?;
    if let Idealization::Axisymmetric = idealization
        && let Some((node, p)) = mesh.nodes().iter().enumerate().find(|(_, p)| p[0] < 0.0)
    {
        return Err(CliError::at(
            &root.key("analysis"),
            format!(
                "axisymmetric analysis needs every node at r = x >= 0, but node {node} is at x = {} \
                 (the mesh must lie right of the axis x = 0)",
                p[0]
            ),
        ));
    }

    // materials
    if scene.materials.is_empty() {
        return Err(CliError::at(
            &root,
            "the scene has no [[materials]] (each with `region`, `young`, `poisson`)",
        ));
    }
    let mesh_regions: BTreeSet<u32> = mesh.regions().iter().copied().collect();
    let mut materials: Vec<(u32, Material)> = Vec::new();
    let mut any_weight = false;
    for (i, m) in scene.materials.iter().enumerate() {
        let p = root.key("materials").index(i);
        let young = positive(&p.key("young"), m.young)?;
        let poisson = expect(
            &p.key("poisson"),
            m.poisson,
            m.poisson > -1.0 && m.poisson < 0.5,
            "a Poisson's ratio in (-1, 0.5)",
        )?;
        let weight = non_negative(&p.key("unit_weight"), m.unit_weight)?;
        any_weight |= weight > 0.0;
        let material = Material::new(young, poisson, weight).map_err(|e| fem(&p, e))?;
        let regions: Vec<(KeyPath, u32)> = match (&m.region, &m.regions) {
            (Some(r), None) => vec![(p.key("region"), *r)],
            (None, Some(rs)) if !rs.is_empty() => rs
                .iter()
                .enumerate()
                .map(|(k, r)| (p.key("regions").index(k), *r))
                .collect(),
            (Some(_), Some(_)) => {
                return Err(CliError::at(&p, "give `region` or `regions`, not both"));
            }
            _ => {
                return Err(CliError::at(
                    &p,
                    format!("`{p}` needs `region = <id>` or `regions = [ids]`"),
                ));
            }
        };
        for (rp, r) in regions {
            if !mesh_regions.contains(&r) {
                return Err(CliError::at(
                    &rp,
                    format!(
                        "`{rp}` = {r}: the mesh has no element in region {r} (regions: {})",
                        join(&mesh_regions)
                    ),
                ));
            }
            if materials.iter().any(|(q, _)| *q == r) {
                return Err(CliError::at(
                    &rp,
                    format!("`{rp}` = {r}: region {r} already has a material"),
                ));
            }
            materials.push((r, material));
        }
    }
    if let Some(r) = mesh_regions
        .iter()
        .find(|r| !materials.iter().any(|(q, _)| q == *r))
    {
        return Err(CliError::at(
            &root.key("materials"),
            format!(
                "region {r} of the mesh has no material (add a [[materials]] with region = {r})"
            ),
        ));
    }

    // supports
    let mut supports = Vec::new();
    for (i, s) in scene.supports.iter().enumerate() {
        let p = root.key("supports").index(i);
        let nodes = node_set(&p.key("set"), &mesh, &s.set)?;
        let value = finite(&p.key("value"), s.value)?;
        check_function(&p.key("function"), &s.function, &functions)?;
        let components = match s.component {
            ComponentSpec::X => vec![Component::X],
            ComponentSpec::Y => vec![Component::Y],
            ComponentSpec::Both => vec![Component::X, Component::Y],
        };
        supports.push(SupportRt {
            name: s.name.clone(),
            nodes,
            components,
            value,
            function: s.function.clone(),
            phases: phase_mask(&p.key("phases"), &s.phases, &phases)?,
        });
    }
    if supports.is_empty() {
        return Err(CliError::at(
            &root,
            "the scene has no [[supports]]: a body without supports has rigid-body modes",
        ));
    }

    // loads
    let mut loads = Vec::new();
    for (i, l) in scene.loads.iter().enumerate() {
        let p = root.key("loads").index(i);
        let l = &l.resolve(&p)?;
        let (name, kind, function, ph) = match l {
            LoadSpec::Traction {
                name,
                set,
                value,
                function,
                phases,
            } => {
                if mesh.edge_set(set).is_err() {
                    return Err(CliError::at(
                        &p.key("set"),
                        format!(
                            "`{}` = \"{set}\": the mesh has no edge set of that name (edge sets: {})",
                            p.key("set"),
                            list_names(mesh.edge_set_names())
                        ),
                    ));
                }
                (
                    name,
                    LoadKind::Traction(set.clone(), finite2(&p.key("value"), *value)?),
                    function,
                    phases,
                )
            }
            LoadSpec::NodalForce {
                name,
                set,
                value,
                function,
                phases,
            } => (
                name,
                LoadKind::Nodal(
                    node_set(&p.key("set"), &mesh, set)?,
                    finite2(&p.key("value"), *value)?,
                ),
                function,
                phases,
            ),
            LoadSpec::BodyForce {
                name,
                value,
                function,
                phases,
            } => (
                name,
                LoadKind::Body(finite2(&p.key("value"), *value)?),
                function,
                phases,
            ),
            LoadSpec::Gravity { name, phases } => {
                if !any_weight {
                    return Err(CliError::at(
                        &p,
                        "a gravity load needs a material with `unit_weight` > 0 (every unit weight is 0)",
                    ));
                }
                (name, LoadKind::Gravity, &None, phases)
            }
        };
        check_function(&p.key("function"), function, &functions)?;
        loads.push(LoadRt {
            name: name.clone(),
            kind,
            function: function.clone(),
            phases: phase_mask(&p.key("phases"), ph, &phases)?,
        });
    }

    // phase overrides name loads and supports
    let mut named: BTreeSet<String> = BTreeSet::new();
    for (i, s) in scene.supports.iter().enumerate() {
        if let Some(n) = &s.name
            && !named.insert(n.clone())
        {
            return Err(CliError::at(
                &root.key("supports").index(i).key("name"),
                format!("name `{n}` is used twice among supports and loads"),
            ));
        }
    }
    for l in &loads {
        if let Some(n) = &l.name
            && !named.insert(n.clone())
        {
            return Err(CliError::at(
                &root.key("loads"),
                format!("name `{n}` is used twice among supports and loads"),
            ));
        }
    }
    for (i, ph) in phases.iter().enumerate() {
        for (target, f) in &ph.overrides {
            let p = root.key("phases").index(i).key("functions").key(target);
            if !named.contains(target) {
                return Err(CliError::at(
                    &p,
                    format!(
                        "`{p}`: no support or load is named `{target}` (named: {})",
                        list_names(named.iter().map(|s| s.as_str()))
                    ),
                ));
            }
            check_function(&p, &Some(f.clone()), &functions)?;
        }
    }

    // the model, with the supports of the first phase at t = 0
    let mut sup = Supports::new();
    for s in supports.iter().filter(|s| s.phases[0]) {
        let f = function_value(&phases[0], &s.name, &s.function, &functions, 0.0);
        for &c in &s.components {
            sup.prescribe(&s.nodes, c, s.value * f)
                .map_err(|e| fem(&root.key("supports"), e))?;
        }
    }
    let mut model = LinearElasticModel::new(mesh, idealization, &materials, sup)
        .map_err(|e| fem(&root.key("supports"), e))?;
    let initial = scene
        .initial_stress
        .map(|s| s.resolve(&root.key("initial_stress")))
        .transpose()?;
    if let Some(InitialStress::Geostatic {
        gamma,
        k0,
        z_surface,
    }) = initial
    {
        let p = root.key("initial_stress");
        let gamma = non_negative(&p.key("gamma"), gamma)?;
        let k0 = non_negative(&p.key("k0"), k0)?;
        let z = finite(&p.key("z_surface"), z_surface)?;
        model
            .set_initial_stress(fem_core::geostatic(gamma, k0, z))
            .map_err(|e| fem(&p, e))?;
    }

    // contact zones
    if scene.contact.is_empty() {
        return Err(CliError::at(
            &root,
            "the scene has no [[contact]] zone (bipo solves contact problems)",
        ));
    }
    let settings = solver_settings(&scene.solver)?;
    let mut zones = Vec::new();
    let mut zone_laws = Vec::new();
    let mut names = BTreeSet::new();
    let (mut adhesive_zones, mut friction_zones) = (0, 0);
    for (i, z) in scene.contact.iter().enumerate() {
        let p = root.key("contact").index(i);
        if !names.insert(z.name.clone()) {
            return Err(CliError::at(
                &p.key("name"),
                format!("zone name `{}` is used twice", z.name),
            ));
        }
        let mesh = model.mesh();
        let contactor = node_set(&p.key("contactor"), mesh, &z.contactor)?;
        let alert = non_negative(&p.key("alert_distance"), z.alert_distance)?;
        let (l, lname) = law(&p.key("law"), &z.law.resolve(&p.key("law"))?)?;
        use contact_laws::ContactLaw;
        if l.has_adhesion() {
            adhesive_zones += 1;
        }
        if l.has_friction() {
            friction_zones += 1;
        }
        zone_laws.push(lname.to_string());
        let tp = p.key("target");
        let zone = match &z.target.resolve(&tp)? {
            TargetSpec::Line { a, b } => {
                let a = finite2(&tp.key("a"), *a)?;
                let b = finite2(&tp.key("b"), *b)?;
                let line = RigidLine::new(a, b).map_err(|e| solver_error(&tp, e))?;
                ContactZone::rigid(&z.name, contactor, line, l, alert)
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
                let arc = RigidArc::new(center, radius, start, sweep, side)
                    .map_err(|e| solver_error(&tp, e))?;
                ContactZone::rigid(&z.name, contactor, arc, l, alert)
            }
            TargetSpec::NodePairs { set, normal } => {
                let targets = node_set(&tp.key("set"), mesh, set)?;
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
                if let Some(n) = normal {
                    let n = finite2(&tp.key("normal"), *n)?;
                    if n[0] == 0.0 && n[1] == 0.0 {
                        return Err(CliError::at(
                            &tp.key("normal"),
                            "the normal [0, 0] has no direction",
                        ));
                    }
                }
                ContactZone::node_pairs(&z.name, contactor, targets, normal.map(|n| n.0), l, alert)
            }
            TargetSpec::Segments { set } => {
                let surface = node_set(&tp.key("set"), mesh, set)?;
                if surface.len() < 2 {
                    return Err(CliError::at(
                        &tp.key("set"),
                        format!(
                            "node set `{set}` has {} node: a target polyline needs at least two",
                            surface.len()
                        ),
                    ));
                }
                ContactZone::node_to_segment(&z.name, contactor, surface, l, alert)
            }
        };
        zones.push(zone);
    }
    let candidates =
        recognize(&model, &zones).map_err(|e| solver_error(&root.key("contact"), e))?;
    check_candidates(&candidates, &zones, &model)?;
    let sim = ContactSimulation::new(model, zones, settings)
        .map_err(|e| solver_error(&root.key("contact"), e))?;
    let zone_names = sim.zones().iter().map(|z| z.name.clone()).collect();
    let mut study = Study {
        title: scene.title.clone().unwrap_or_else(|| {
            loaded
                .path
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default()
        }),
        units: scene.units.clone().unwrap_or_default(),
        body: Body::Custom(Box::new(Custom {
            sim,
            supports,
            loads,
            functions,
        })),
        phases,
        output: scene.output.clone(),
        plots: Vec::new(),
        zone_names,
        zone_laws,
        adhesive_zones,
        friction_zones,
    };
    check_outputs(scene, &mut study)?;
    Ok(study)
}

/// The value of the time function of a support or load at `t` in `phase` (with the phase's
/// override by name); 1 without a function.
pub fn function_value(
    phase: &Phase,
    name: &Option<String>,
    function: &Option<String>,
    functions: &BTreeMap<String, TimeFunction>,
    t: f64,
) -> f64 {
    let f = name
        .as_ref()
        .and_then(|n| phase.overrides.get(n))
        .or(function.as_ref());
    f.and_then(|f| functions.get(f)).map_or(1.0, |f| f.eval(t))
}

fn join(s: &BTreeSet<u32>) -> String {
    s.iter()
        .map(|r| r.to_string())
        .collect::<Vec<_>>()
        .join(", ")
}

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

fn build_mesh(
    mp: &KeyPath,
    spec: &MeshSpec,
    base_dir: &Path,
    idealization: Idealization,
) -> CliResult<Mesh> {
    match spec {
        MeshSpec::Rectangle {
            element,
            x,
            nx,
            grading_x,
            y,
            ny,
            grading_y,
            region,
            y0,
            layers,
        } => {
            let xs = finite2(&mp.key("x"), *x)?;
            if xs[0] >= xs[1] {
                return Err(CliError::at(
                    &mp.key("x"),
                    format!(
                        "`{}` = [{}, {}]: expected x0 < x1",
                        mp.key("x"),
                        xs[0],
                        xs[1]
                    ),
                ));
            }
            let mut spec = RectangleSpec::new(xs, [0.0, 1.0], at_least(&mp.key("nx"), *nx, 1)?, 1);
            spec.grading_x = grading(&mp.key("grading_x"), *grading_x)?;
            spec.kind = kind(*element);
            match (y, layers) {
                (Some(y), None) => {
                    if y0.is_some() {
                        return Err(CliError::at(
                            &mp.key("y0"),
                            "`y0` goes with `layers`; with `y = [y0, y1]` leave it out",
                        ));
                    }
                    let ys = finite2(&mp.key("y"), *y)?;
                    if ys[0] >= ys[1] {
                        return Err(CliError::at(
                            &mp.key("y"),
                            format!(
                                "`{}` = [{}, {}]: expected y0 < y1",
                                mp.key("y"),
                                ys[0],
                                ys[1]
                            ),
                        ));
                    }
                    let ny =
                        ny.ok_or_else(|| CliError::at(mp, "`mesh.ny` is missing (cells along y)"))?;
                    spec.y0 = ys[0];
                    spec.layers = vec![Layer {
                        top: ys[1],
                        ny: at_least(&mp.key("ny"), ny, 1)?,
                        grading: grading(&mp.key("grading_y"), grading_y.unwrap_or_default())?,
                        region: region.unwrap_or(0),
                    }];
                }
                (None, Some(layers)) => {
                    for (k, key) in [
                        (ny.is_some(), "ny"),
                        (grading_y.is_some(), "grading_y"),
                        (region.is_some(), "region"),
                    ] {
                        if k {
                            return Err(CliError::at(
                                &mp.key(key),
                                format!(
                                    "`mesh.{key}` goes with `y = [y0, y1]`; with `layers` give it per layer"
                                ),
                            ));
                        }
                    }
                    spec.y0 = finite(&mp.key("y0"), y0.unwrap_or(0.0))?;
                    if layers.is_empty() {
                        return Err(CliError::at(&mp.key("layers"), "`mesh.layers` is empty"));
                    }
                    let mut below = spec.y0;
                    spec.layers = Vec::new();
                    for (i, l) in layers.iter().enumerate() {
                        let lp = mp.key("layers").index(i);
                        let top = finite(&lp.key("top"), l.top)?;
                        if top <= below {
                            return Err(CliError::at(
                                &lp.key("top"),
                                format!(
                                    "`{}` = {top}: layers go upward, expected a top above {below}",
                                    lp.key("top")
                                ),
                            ));
                        }
                        below = top;
                        spec.layers.push(Layer {
                            top,
                            ny: at_least(&lp.key("ny"), l.ny, 1)?,
                            grading: grading(&lp.key("grading"), l.grading)?,
                            region: l.region,
                        });
                    }
                }
                (Some(_), Some(_)) => {
                    return Err(CliError::at(
                        &mp.key("layers"),
                        "give `y = [y0, y1]` or `layers`, not both",
                    ));
                }
                (None, None) => {
                    return Err(CliError::at(
                        mp,
                        "the rectangle needs `y = [y0, y1]` and `ny`, or `y0` and `layers`",
                    ));
                }
            }
            fem_core::generate::rectangle(&spec).map_err(|e| fem(mp, e))
        }
        MeshSpec::Pile {
            element,
            diameter,
            length,
            width,
            depth,
            cells_pile_r,
            cells_soil_r,
            cells_shaft,
            cells_below_tip,
            grading_pile_r,
            grading_soil_r,
            grading_shaft,
            grading_below_tip,
            tip_corner,
        } => {
            if !matches!(idealization, Idealization::Axisymmetric) {
                return Err(CliError::at(
                    &KeyPath::root().key("analysis"),
                    "the pile generator builds an axisymmetric (r, z) mesh: it needs \
                     [analysis] type = \"axisymmetric\"",
                ));
            }
            let mut s = PileSpec::default();
            macro_rules! pos {
                ($f:ident) => {
                    if let Some(v) = $f {
                        s.$f = positive(&mp.key(stringify!($f)), *v)?;
                    }
                };
            }
            macro_rules! cnt {
                ($f:ident) => {
                    if let Some(v) = $f {
                        s.$f = at_least(&mp.key(stringify!($f)), *v, 1)?;
                    }
                };
            }
            macro_rules! grd {
                ($f:ident) => {
                    if let Some(v) = $f {
                        s.$f = grading(&mp.key(stringify!($f)), *v)?;
                    }
                };
            }
            if length.is_some() && width.is_none() && depth.is_none() {
                // keep the seed's proportions W = 2 L_p, H = 3.5 L_p
                let l = positive(&mp.key("length"), length.unwrap_or(13.0))?;
                s.width = 2.0 * l;
                s.depth = 3.5 * l;
            }
            pos!(diameter);
            pos!(length);
            pos!(width);
            pos!(depth);
            cnt!(cells_pile_r);
            cnt!(cells_soil_r);
            cnt!(cells_shaft);
            cnt!(cells_below_tip);
            grd!(grading_pile_r);
            grd!(grading_soil_r);
            grd!(grading_shaft);
            grd!(grading_below_tip);
            if let Some(e) = element {
                s.kind = kind(*e);
            }
            if let Some(t) = tip_corner {
                s.tip_corner = match t {
                    TipCornerSpec::Split => TipCorner::Split,
                    TipCornerSpec::Shared => TipCorner::Shared,
                };
            }
            fem_core::generate::pile_in_soil(&s).map_err(|e| fem(mp, e))
        }
        MeshSpec::Gmsh { file, element } => {
            let path = base_dir.join(file);
            if !path.is_file() {
                return Err(CliError::at(
                    &mp.key("file"),
                    format!(
                        "`mesh.file` = \"{file}\": no such file ({}; paths are relative to the scene file)",
                        path.display()
                    ),
                ));
            }
            let mesh = fem_core::gmsh::read_msh(&path).map_err(|e| fem(&mp.key("file"), e))?;
            if let Some(e) = element
                && kind(*e) != mesh.kind()
            {
                return Err(CliError::at(
                    &mp.key("element"),
                    format!(
                        "`mesh.element` = \"{e:?}\" but `{file}` holds {}",
                        kind_name(mesh.kind())
                    ),
                ));
            }
            Ok(mesh)
        }
    }
}

/// Quantities of the plots: (name, needs).
pub const QUANTITIES: &[(&str, &str)] = &[
    ("force_n", "zone"),
    ("force_t", "zone"),
    ("beta_mean", "zone"),
    ("beta_min", "zone"),
    ("closed", "zone"),
    ("gap", "node"),
    ("u_t", "node"),
    ("beta", "node"),
    ("r_n", "node"),
    ("r_t", "node"),
    ("u_x", "point"),
    ("u_y", "point"),
    ("reaction_x", "set"),
    ("reaction_y", "set"),
    ("contact_iterations", "step"),
    ("adhesion_iterations", "step"),
    ("active_contacts", "step"),
    ("residual", "step"),
    ("head_load", "pile"),
    ("head_displacement", "pile"),
];

fn check_outputs(scene: &Scene, study: &mut Study) -> CliResult<()> {
    let root = KeyPath::root();
    let op = root.key("output");
    let o = &study.output;
    at_least(&op.key("every"), o.every, 1)?;
    let total = study.total_steps();
    if let Some(steps) = &o.steps {
        for (i, s) in steps.iter().enumerate() {
            if *s < 1 || *s > total {
                let p = op.key("steps").index(i);
                return Err(CliError::at(
                    &p,
                    format!("`{p}` = {s}: expected a step in 1..={total}"),
                ));
            }
        }
    }
    if let Some(zs) = &o.zones {
        for (i, z) in zs.iter().enumerate() {
            zone_index(&op.key("zones").index(i), &study.zone_names, z)?;
        }
    }
    let node_count = study.model().mesh().node_count();
    if let Some(ns) = &o.nodes {
        for (i, n) in ns.iter().enumerate() {
            if !study.candidates().iter().any(|c| c.node == *n) {
                let p = op.key("nodes").index(i);
                return Err(CliError::at(
                    &p,
                    format!(
                        "`{p}` = {n}: not a contactor node of any zone (the mesh has {node_count} nodes)"
                    ),
                ));
            }
        }
    }
    let mut files = BTreeSet::new();
    for (i, plot) in scene.plots.iter().enumerate() {
        let pp = root.key("plots").index(i);
        if !plot.file.ends_with(".svg") || plot.file.contains(['/', '\\']) {
            return Err(CliError::at(
                &pp.key("file"),
                format!(
                    "`{}` = \"{}\": expected a file name ending in .svg (written in the output directory)",
                    pp.key("file"),
                    plot.file
                ),
            ));
        }
        if !files.insert(plot.file.clone()) {
            return Err(CliError::at(
                &pp.key("file"),
                format!("plot file `{}` is used twice", plot.file),
            ));
        }
        if plot.curves.is_empty() {
            return Err(CliError::at(
                &pp.key("curves"),
                "a plot needs at least one curve",
            ));
        }
        for (k, c) in plot.curves.iter().enumerate() {
            check_curve(&pp.key("curves").index(k), c, study)?;
        }
        if let Some(c) = &plot.x_quantity {
            check_curve(&pp.key("x_quantity"), c, study)?;
        }
    }
    study.plots = scene.plots.clone();
    Ok(())
}

/// Index of a zone by name.
pub fn zone_index(path: &KeyPath, names: &[String], name: &str) -> CliResult<usize> {
    names.iter().position(|n| n == name).ok_or_else(|| {
        CliError::at(
            path,
            format!(
                "`{path}` = \"{name}\": no such contact zone (zones: {})",
                list_names(names.iter().map(|s| s.as_str()))
            ),
        )
    })
}

fn check_curve(p: &KeyPath, c: &CurveSpec, study: &Study) -> CliResult<()> {
    let Some((_, needs)) = QUANTITIES.iter().find(|(q, _)| *q == c.quantity) else {
        let q = p.key("quantity");
        return Err(CliError::at(
            &q,
            format!(
                "`{q}` = \"{}\": unknown quantity (expected one of {})",
                c.quantity,
                QUANTITIES
                    .iter()
                    .map(|(q, _)| *q)
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        ));
    };
    let zone = match &c.zone {
        Some(z) => Some(zone_index(&p.key("zone"), &study.zone_names, z)?),
        None => None,
    };
    let mesh = study.model().mesh();
    match *needs {
        "zone" if zone.is_none() && study.zone_names.len() > 1 => {
            return Err(CliError::at(
                p,
                format!(
                    "`{p}`: quantity `{}` needs `zone` (the scene has several zones)",
                    c.quantity
                ),
            ));
        }
        "node" => {
            let Some(n) = c.node else {
                return Err(CliError::at(
                    p,
                    format!(
                        "`{p}`: quantity `{}` needs `node` (a contactor node)",
                        c.quantity
                    ),
                ));
            };
            if !study
                .candidates()
                .iter()
                .any(|k| k.node == n && zone.is_none_or(|z| z == k.zone))
            {
                let q = p.key("node");
                return Err(CliError::at(
                    &q,
                    format!(
                        "`{q}` = {n}: not a contactor node{} (the mesh has {} nodes)",
                        zone.map(|z| format!(" of zone `{}`", study.zone_names[z]))
                            .unwrap_or_default(),
                        mesh.node_count()
                    ),
                ));
            }
        }
        "point" => match (c.node, &c.set) {
            (Some(n), None) => {
                if n >= mesh.node_count() {
                    let q = p.key("node");
                    return Err(CliError::at(
                        &q,
                        format!(
                            "`{q}` = {n}: the mesh has {} nodes (0..{})",
                            mesh.node_count(),
                            mesh.node_count()
                        ),
                    ));
                }
            }
            (None, Some(s)) => {
                node_set(&p.key("set"), mesh, s)?;
            }
            _ => {
                return Err(CliError::at(
                    p,
                    format!(
                        "`{p}`: quantity `{}` needs `node` or `set` (one of them)",
                        c.quantity
                    ),
                ));
            }
        },
        "pile" if !matches!(&study.body, Body::Preset(p) if p.kind == "pile") => {
            return Err(CliError::at(
                &p.key("quantity"),
                format!(
                    "`{}` = \"{}\": only the pile preset has this quantity",
                    p.key("quantity"),
                    c.quantity
                ),
            ));
        }
        "set" => {
            let Some(s) = &c.set else {
                return Err(CliError::at(
                    p,
                    format!(
                        "`{p}`: quantity `{}` needs `set` (a supported node set)",
                        c.quantity
                    ),
                ));
            };
            let nodes = node_set(&p.key("set"), mesh, s)?;
            let comp = if c.quantity == "reaction_x" {
                Component::X
            } else {
                Component::Y
            };
            let supports = study.model().supports();
            let any = nodes.iter().any(|&n| supports.value(n, comp).is_some())
                || matches!(&study.body, Body::Custom(cu) if cu.supports.iter().any(|s| s.components.contains(&comp) && s.nodes.iter().any(|n| nodes.contains(n))));
            if !any {
                let q = p.key("set");
                return Err(CliError::at(
                    &q,
                    format!(
                        "`{q}` = \"{s}\": no node of this set has a support on {comp:?}, so it has no reaction"
                    ),
                ));
            }
        }
        _ => {}
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn time_functions_interpolate_and_hold_works() {
        let p = KeyPath::root().key("functions").key("f");
        let f = time_function(&p, &[Pair([0.0, 0.0]), Pair([1.0, 2.0]), Pair([3.0, 2.0])]).unwrap();
        assert_eq!(f.eval(-1.0), 0.0);
        assert_eq!(f.eval(0.5), 1.0);
        assert_eq!(f.eval(2.0), 2.0);
        assert_eq!(f.eval(10.0), 2.0);
    }

    #[test]
    fn time_functions_rejects_non_increasing_times() {
        let p = KeyPath::root().key("functions").key("f");
        let e = time_function(&p, &[Pair([0.0, 0.0]), Pair([0.0, 1.0])]).unwrap_err();
        assert_eq!(e.path.unwrap().to_string(), "functions.f[1][0]");
        assert!(time_function(&p, &[]).is_err());
    }

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

    #[test]
    fn phase_times_end_exactly_works() {
        let ph = phase("p", 3, 2.0, 2.3);
        assert_eq!(ph.time(3), 2.3);
        assert!((ph.time(1) - 2.1).abs() < 1e-15);
    }
}
