//! The tables of the scene that have a `type` (or `generator`, `kind`) key, as read: one flat
//! struct per table, every key optional, then [`resolve`](RawLaw::resolve)d into the typed
//! enums of [`crate::spec`] with a check of which keys that type needs and accepts.
//!
//! Why not serde's internally tagged enums: they buffer the table before choosing the variant,
//! so a wrong value inside (`nx = "two"`) is reported at the table, without the key. Flat
//! structs keep the line, the column and the key path of every value.

use crate::error::{CliError, CliResult, KeyPath};
use crate::spec::*;
use serde::Deserialize;

/// `need(path, &opt, "key", "what")`: the value, or the error "`path`: what needs `key`".
fn need<T: Clone>(path: &KeyPath, v: &Option<T>, key: &str, what: &str) -> CliResult<T> {
    v.clone()
        .ok_or_else(|| CliError::at(path, format!("`{path}`: {what} needs `{key}`")))
}

/// Refuses the keys present that `what` does not read.
fn only(path: &KeyPath, what: &str, present: &[(&str, bool)], accepted: &[&str]) -> CliResult<()> {
    if let Some((k, _)) = present.iter().find(|(k, p)| *p && !accepted.contains(k)) {
        let p = path.key(k);
        let keys = if accepted.is_empty() {
            "none".to_string()
        } else {
            accepted
                .iter()
                .map(|a| format!("`{a}`"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        return Err(CliError::at(
            &p,
            format!("`{p}` is not a key of {what} (its keys: {keys})"),
        ));
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------------

/// Grading kinds.
#[derive(Debug, Deserialize, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum GradingKind {
    /// Equal cells.
    Uniform,
    /// Geometric.
    Geometric,
    /// Both ends.
    BothEnds,
}

/// `{ type = "geometric", ratio = 4.0 }`.
#[derive(Debug, Deserialize, Clone, Copy)]
#[serde(deny_unknown_fields)]
pub struct RawGrading {
    #[serde(rename = "type")]
    kind: GradingKind,
    ratio: Option<f64>,
}

impl RawGrading {
    /// The grading.
    pub fn resolve(&self, p: &KeyPath) -> CliResult<GradingSpec> {
        Ok(match self.kind {
            GradingKind::Uniform => {
                only(
                    p,
                    "a uniform grading",
                    &[("ratio", self.ratio.is_some())],
                    &[],
                )?;
                GradingSpec::Uniform {}
            }
            GradingKind::Geometric => GradingSpec::Geometric {
                ratio: need(p, &self.ratio, "ratio", "a geometric grading")?,
            },
            GradingKind::BothEnds => GradingSpec::BothEnds {
                ratio: need(p, &self.ratio, "ratio", "a both_ends grading")?,
            },
        })
    }
}

fn grading(p: &KeyPath, g: &Option<RawGrading>) -> CliResult<Option<GradingSpec>> {
    g.as_ref().map(|g| g.resolve(p)).transpose()
}

/// One layer.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct RawLayer {
    top: f64,
    ny: usize,
    grading: Option<RawGrading>,
    #[serde(default)]
    region: u32,
}

/// Mesh generators.
#[derive(Debug, Deserialize, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Generator {
    /// `rectangle`.
    Rectangle,
    /// `pile`.
    Pile,
    /// `gmsh`.
    Gmsh,
}

/// `[mesh]`.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct RawMesh {
    generator: Generator,
    element: Option<Element>,
    // rectangle
    x: Option<Pair>,
    nx: Option<usize>,
    grading_x: Option<RawGrading>,
    y: Option<Pair>,
    ny: Option<usize>,
    grading_y: Option<RawGrading>,
    region: Option<u32>,
    y0: Option<f64>,
    layers: Option<Vec<RawLayer>>,
    // pile
    diameter: Option<f64>,
    length: Option<f64>,
    width: Option<f64>,
    depth: Option<f64>,
    cells_pile_r: Option<usize>,
    cells_soil_r: Option<usize>,
    cells_shaft: Option<usize>,
    cells_below_tip: Option<usize>,
    grading_pile_r: Option<RawGrading>,
    grading_soil_r: Option<RawGrading>,
    grading_shaft: Option<RawGrading>,
    grading_below_tip: Option<RawGrading>,
    tip_corner: Option<TipCornerSpec>,
    // gmsh
    file: Option<String>,
}

const RECTANGLE_KEYS: &[&str] = &[
    "element",
    "x",
    "nx",
    "grading_x",
    "y",
    "ny",
    "grading_y",
    "region",
    "y0",
    "layers",
];
const PILE_KEYS: &[&str] = &[
    "element",
    "diameter",
    "length",
    "width",
    "depth",
    "cells_pile_r",
    "cells_soil_r",
    "cells_shaft",
    "cells_below_tip",
    "grading_pile_r",
    "grading_soil_r",
    "grading_shaft",
    "grading_below_tip",
    "tip_corner",
];
const GMSH_KEYS: &[&str] = &["element", "file"];

impl RawMesh {
    /// The mesh spec.
    pub fn resolve(&self, p: &KeyPath) -> CliResult<MeshSpec> {
        let present = [
            ("element", self.element.is_some()),
            ("x", self.x.is_some()),
            ("nx", self.nx.is_some()),
            ("grading_x", self.grading_x.is_some()),
            ("y", self.y.is_some()),
            ("ny", self.ny.is_some()),
            ("grading_y", self.grading_y.is_some()),
            ("region", self.region.is_some()),
            ("y0", self.y0.is_some()),
            ("layers", self.layers.is_some()),
            ("diameter", self.diameter.is_some()),
            ("length", self.length.is_some()),
            ("width", self.width.is_some()),
            ("depth", self.depth.is_some()),
            ("cells_pile_r", self.cells_pile_r.is_some()),
            ("cells_soil_r", self.cells_soil_r.is_some()),
            ("cells_shaft", self.cells_shaft.is_some()),
            ("cells_below_tip", self.cells_below_tip.is_some()),
            ("grading_pile_r", self.grading_pile_r.is_some()),
            ("grading_soil_r", self.grading_soil_r.is_some()),
            ("grading_shaft", self.grading_shaft.is_some()),
            ("grading_below_tip", self.grading_below_tip.is_some()),
            ("tip_corner", self.tip_corner.is_some()),
            ("file", self.file.is_some()),
        ];
        Ok(match self.generator {
            Generator::Rectangle => {
                only(p, "the rectangle generator", &present, RECTANGLE_KEYS)?;
                let what = "the rectangle generator";
                let layers = match &self.layers {
                    None => None,
                    Some(ls) => Some(
                        ls.iter()
                            .enumerate()
                            .map(|(i, l)| {
                                Ok(LayerSpec {
                                    top: l.top,
                                    ny: l.ny,
                                    grading: grading(
                                        &p.key("layers").index(i).key("grading"),
                                        &l.grading,
                                    )?
                                    .unwrap_or_default(),
                                    region: l.region,
                                })
                            })
                            .collect::<CliResult<Vec<_>>>()?,
                    ),
                };
                MeshSpec::Rectangle {
                    element: need(p, &self.element, "element", what)?,
                    x: need(p, &self.x, "x", what)?,
                    nx: need(p, &self.nx, "nx", what)?,
                    grading_x: grading(&p.key("grading_x"), &self.grading_x)?.unwrap_or_default(),
                    y: self.y,
                    ny: self.ny,
                    grading_y: grading(&p.key("grading_y"), &self.grading_y)?,
                    region: self.region,
                    y0: self.y0,
                    layers,
                }
            }
            Generator::Pile => {
                only(p, "the pile generator", &present, PILE_KEYS)?;
                MeshSpec::Pile {
                    element: self.element,
                    diameter: self.diameter,
                    length: self.length,
                    width: self.width,
                    depth: self.depth,
                    cells_pile_r: self.cells_pile_r,
                    cells_soil_r: self.cells_soil_r,
                    cells_shaft: self.cells_shaft,
                    cells_below_tip: self.cells_below_tip,
                    grading_pile_r: grading(&p.key("grading_pile_r"), &self.grading_pile_r)?,
                    grading_soil_r: grading(&p.key("grading_soil_r"), &self.grading_soil_r)?,
                    grading_shaft: grading(&p.key("grading_shaft"), &self.grading_shaft)?,
                    grading_below_tip: grading(
                        &p.key("grading_below_tip"),
                        &self.grading_below_tip,
                    )?,
                    tip_corner: self.tip_corner,
                }
            }
            Generator::Gmsh => {
                only(p, "a gmsh mesh", &present, GMSH_KEYS)?;
                MeshSpec::Gmsh {
                    file: need(p, &self.file, "file", "a gmsh mesh")?,
                    element: self.element,
                }
            }
        })
    }
}

// ---------------------------------------------------------------------------------------------

/// Analysis types.
#[derive(Debug, Deserialize, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum AnalysisKind {
    /// Plane strain.
    PlaneStrain,
    /// Plane stress.
    PlaneStress,
    /// Axisymmetric.
    Axisymmetric,
}

/// `[analysis]`.
#[derive(Debug, Deserialize, Clone, Copy)]
#[serde(deny_unknown_fields)]
pub struct RawAnalysis {
    #[serde(rename = "type")]
    kind: AnalysisKind,
    thickness: Option<f64>,
}

impl RawAnalysis {
    /// The analysis.
    pub fn resolve(&self, p: &KeyPath) -> CliResult<Analysis> {
        let present = [("thickness", self.thickness.is_some())];
        Ok(match self.kind {
            AnalysisKind::PlaneStrain => {
                only(
                    p,
                    "a plane strain analysis (per unit thickness)",
                    &present,
                    &[],
                )?;
                Analysis::PlaneStrain {}
            }
            AnalysisKind::PlaneStress => Analysis::PlaneStress {
                thickness: need(p, &self.thickness, "thickness", "a plane stress analysis")?,
            },
            AnalysisKind::Axisymmetric => {
                only(p, "an axisymmetric analysis (per radian)", &present, &[])?;
                Analysis::Axisymmetric {}
            }
        })
    }
}

// ---------------------------------------------------------------------------------------------

/// Initial stress types.
#[derive(Debug, Deserialize, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum InitialStressKind {
    /// Geostatic.
    Geostatic,
}

/// `[initial_stress]`.
#[derive(Debug, Deserialize, Clone, Copy)]
#[serde(deny_unknown_fields)]
pub struct RawInitialStress {
    #[serde(rename = "type")]
    kind: InitialStressKind,
    gamma: Option<f64>,
    k0: Option<f64>,
    z_surface: Option<f64>,
}

impl RawInitialStress {
    /// The initial stress.
    pub fn resolve(&self, p: &KeyPath) -> CliResult<InitialStress> {
        let what = "a geostatic initial stress";
        match self.kind {
            InitialStressKind::Geostatic => Ok(InitialStress::Geostatic {
                gamma: need(p, &self.gamma, "gamma", what)?,
                k0: need(p, &self.k0, "k0", what)?,
                z_surface: self.z_surface.unwrap_or(0.0),
            }),
        }
    }
}

// ---------------------------------------------------------------------------------------------

/// Load types.
#[derive(Debug, Deserialize, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum LoadKindSpec {
    /// Traction.
    Traction,
    /// Nodal force.
    NodalForce,
    /// Body force.
    BodyForce,
    /// Gravity.
    Gravity,
}

/// `[[loads]]`.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct RawLoad {
    #[serde(rename = "type")]
    kind: LoadKindSpec,
    name: Option<String>,
    set: Option<String>,
    value: Option<Pair>,
    function: Option<String>,
    phases: Option<Vec<String>>,
}

impl RawLoad {
    /// The load.
    pub fn resolve(&self, p: &KeyPath) -> CliResult<LoadSpec> {
        let present = [
            ("set", self.set.is_some()),
            ("value", self.value.is_some()),
            ("function", self.function.is_some()),
        ];
        let (name, function, phases) = (
            self.name.clone(),
            self.function.clone(),
            self.phases.clone(),
        );
        Ok(match self.kind {
            LoadKindSpec::Traction => LoadSpec::Traction {
                set: need(p, &self.set, "set", "a traction (an edge set)")?,
                value: need(p, &self.value, "value", "a traction")?,
                name,
                function,
                phases,
            },
            LoadKindSpec::NodalForce => LoadSpec::NodalForce {
                set: need(p, &self.set, "set", "a nodal force (a node set)")?,
                value: need(p, &self.value, "value", "a nodal force")?,
                name,
                function,
                phases,
            },
            LoadKindSpec::BodyForce => {
                only(p, "a body force", &present, &["value", "function"])?;
                LoadSpec::BodyForce {
                    value: need(p, &self.value, "value", "a body force")?,
                    name,
                    function,
                    phases,
                }
            }
            LoadKindSpec::Gravity => {
                only(
                    p,
                    "a gravity load (the self-weight is applied in full: it has no function)",
                    &present,
                    &[],
                )?;
                LoadSpec::Gravity { name, phases }
            }
        })
    }
}

// ---------------------------------------------------------------------------------------------

/// Target types.
#[derive(Debug, Deserialize, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum TargetKind {
    /// LINE.
    Line,
    /// ARC.
    Arc,
    /// Node pairs.
    NodePairs,
    /// Node-to-segment.
    Segments,
}

/// `target = {...}`.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct RawTarget {
    #[serde(rename = "type")]
    kind: TargetKind,
    a: Option<Pair>,
    b: Option<Pair>,
    center: Option<Pair>,
    radius: Option<f64>,
    start_angle: Option<f64>,
    sweep: Option<f64>,
    side: Option<ArcSideSpec>,
    set: Option<String>,
    normal: Option<Pair>,
}

impl RawTarget {
    /// The target.
    pub fn resolve(&self, p: &KeyPath) -> CliResult<TargetSpec> {
        let present = [
            ("a", self.a.is_some()),
            ("b", self.b.is_some()),
            ("center", self.center.is_some()),
            ("radius", self.radius.is_some()),
            ("start_angle", self.start_angle.is_some()),
            ("sweep", self.sweep.is_some()),
            ("side", self.side.is_some()),
            ("set", self.set.is_some()),
            ("normal", self.normal.is_some()),
        ];
        Ok(match self.kind {
            TargetKind::Line => {
                only(p, "a LINE target", &present, &["a", "b"])?;
                TargetSpec::Line {
                    a: need(p, &self.a, "a", "a LINE target")?,
                    b: need(p, &self.b, "b", "a LINE target")?,
                }
            }
            TargetKind::Arc => {
                let what = "an ARC target";
                only(
                    p,
                    what,
                    &present,
                    &["center", "radius", "start_angle", "sweep", "side"],
                )?;
                TargetSpec::Arc {
                    center: need(p, &self.center, "center", what)?,
                    radius: need(p, &self.radius, "radius", what)?,
                    start_angle: self.start_angle.unwrap_or(0.0),
                    sweep: self.sweep,
                    side: need(p, &self.side, "side", what)?,
                }
            }
            TargetKind::NodePairs => {
                only(p, "a node_pairs target", &present, &["set", "normal"])?;
                TargetSpec::NodePairs {
                    set: need(p, &self.set, "set", "a node_pairs target")?,
                    normal: self.normal,
                }
            }
            TargetKind::Segments => {
                only(p, "a segments target", &present, &["set"])?;
                TargetSpec::Segments {
                    set: need(p, &self.set, "set", "a segments target")?,
                }
            }
        })
    }
}

// ---------------------------------------------------------------------------------------------

/// Law types.
#[derive(Debug, Deserialize, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum LawKind {
    /// Signorini.
    Signorini,
    /// Coulomb.
    Coulomb,
    /// RCCM.
    Rccm,
}

/// `law = {...}`.
#[derive(Debug, Deserialize, Clone, Copy)]
#[serde(deny_unknown_fields)]
pub struct RawLaw {
    #[serde(rename = "type")]
    kind: LawKind,
    mu: Option<f64>,
    c_n: Option<f64>,
    c_t: Option<f64>,
    w: Option<f64>,
    alpha: Option<f64>,
    m: Option<u32>,
    beta_0: Option<f64>,
    scheme: Option<SchemeSpec>,
    theta: Option<f64>,
}

impl RawLaw {
    /// The law.
    pub fn resolve(&self, p: &KeyPath) -> CliResult<LawSpec> {
        let present = [
            ("mu", self.mu.is_some()),
            ("c_n", self.c_n.is_some()),
            ("c_t", self.c_t.is_some()),
            ("w", self.w.is_some()),
            ("alpha", self.alpha.is_some()),
            ("m", self.m.is_some()),
            ("beta_0", self.beta_0.is_some()),
            ("scheme", self.scheme.is_some()),
            ("theta", self.theta.is_some()),
        ];
        Ok(match self.kind {
            LawKind::Signorini => {
                only(p, "the signorini law (frictionless)", &present, &[])?;
                LawSpec::Signorini {}
            }
            LawKind::Coulomb => {
                only(p, "the coulomb law", &present, &["mu"])?;
                LawSpec::Coulomb {
                    mu: need(p, &self.mu, "mu", "the coulomb law")?,
                }
            }
            LawKind::Rccm => {
                let what = "the rccm law";
                LawSpec::Rccm(RccmSpec {
                    c_n: need(p, &self.c_n, "c_n", what)?,
                    c_t: need(p, &self.c_t, "c_t", what)?,
                    w: need(p, &self.w, "w", what)?,
                    alpha: need(p, &self.alpha, "alpha", what)?,
                    mu: need(p, &self.mu, "mu", what)?,
                    m: self.m.unwrap_or(1),
                    beta_0: self.beta_0.unwrap_or(1.0),
                    scheme: self.scheme.unwrap_or_default(),
                    theta: self.theta,
                })
            }
        })
    }
}

// ---------------------------------------------------------------------------------------------

/// Preset kinds.
#[derive(Debug, Deserialize, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum PresetKind {
    /// Seed 5.6.1.
    Delamination,
    /// Seed 5.6.2.
    Shear,
    /// Seed ch. 6.
    Pile,
}

/// Installation types.
#[derive(Debug, Deserialize, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum InstallationKind {
    /// None.
    None,
    /// Radial displacement.
    RadialDisplacement,
    /// Normal force ratio.
    NormalForceRatio,
}

/// `installation = {...}`.
#[derive(Debug, Deserialize, Clone, Copy)]
#[serde(deny_unknown_fields)]
pub struct RawInstallation {
    #[serde(rename = "type")]
    kind: InstallationKind,
    value: Option<f64>,
}

/// `[preset]`.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct RawPreset {
    kind: PresetKind,
    length: Option<f64>,
    height: Option<f64>,
    young: Option<f64>,
    poisson: Option<f64>,
    nx: Option<usize>,
    ny: Option<usize>,
    element: Option<Element>,
    lift: Option<f64>,
    press: Option<f64>,
    push: Option<f64>,
    duration: Option<f64>,
    steps: Option<usize>,
    interface: Option<RccmOverride>,
    // pile
    site: Option<Site>,
    coulomb: Option<bool>,
    pile_young: Option<f64>,
    pile_poisson: Option<f64>,
    pile_unit_weight: Option<f64>,
    soil_young: Option<f64>,
    soil_poisson: Option<f64>,
    soil_unit_weight: Option<f64>,
    k0: Option<f64>,
    installation: Option<RawInstallation>,
    head_displacement: Option<f64>,
    alert_distance: Option<f64>,
    mesh: Option<PileMeshOverride>,
}

impl RawPreset {
    /// The preset.
    pub fn resolve(&self, p: &KeyPath) -> CliResult<Preset> {
        let present = [
            ("length", self.length.is_some()),
            ("height", self.height.is_some()),
            ("young", self.young.is_some()),
            ("poisson", self.poisson.is_some()),
            ("nx", self.nx.is_some()),
            ("ny", self.ny.is_some()),
            ("element", self.element.is_some()),
            ("lift", self.lift.is_some()),
            ("press", self.press.is_some()),
            ("push", self.push.is_some()),
            ("duration", self.duration.is_some()),
            ("steps", self.steps.is_some()),
            ("interface", self.interface.is_some()),
            ("site", self.site.is_some()),
            ("coulomb", self.coulomb.is_some()),
            ("pile_young", self.pile_young.is_some()),
            ("pile_poisson", self.pile_poisson.is_some()),
            ("pile_unit_weight", self.pile_unit_weight.is_some()),
            ("soil_young", self.soil_young.is_some()),
            ("soil_poisson", self.soil_poisson.is_some()),
            ("soil_unit_weight", self.soil_unit_weight.is_some()),
            ("k0", self.k0.is_some()),
            ("installation", self.installation.is_some()),
            ("head_displacement", self.head_displacement.is_some()),
            ("alert_distance", self.alert_distance.is_some()),
            ("mesh", self.mesh.is_some()),
        ];
        const COMMON: &[&str] = &[
            "length",
            "height",
            "young",
            "poisson",
            "nx",
            "ny",
            "element",
            "duration",
            "steps",
            "interface",
        ];
        Ok(match self.kind {
            PresetKind::Delamination => {
                let keys: Vec<&str> = COMMON.iter().copied().chain(["lift"]).collect();
                only(p, "the delamination preset", &present, &keys)?;
                Preset::Delamination {
                    length: self.length,
                    height: self.height,
                    young: self.young,
                    poisson: self.poisson,
                    nx: self.nx,
                    ny: self.ny,
                    element: self.element,
                    lift: self.lift,
                    duration: self.duration,
                    steps: self.steps,
                    interface: self.interface,
                }
            }
            PresetKind::Shear => {
                let keys: Vec<&str> = COMMON.iter().copied().chain(["press", "push"]).collect();
                only(p, "the shear preset", &present, &keys)?;
                Preset::Shear {
                    length: self.length,
                    height: self.height,
                    young: self.young,
                    poisson: self.poisson,
                    nx: self.nx,
                    ny: self.ny,
                    element: self.element,
                    press: self.press,
                    push: self.push,
                    duration: self.duration,
                    steps: self.steps,
                    interface: self.interface,
                }
            }
            PresetKind::Pile => {
                only(
                    p,
                    "the pile preset",
                    &present,
                    &[
                        "site",
                        "coulomb",
                        "pile_young",
                        "pile_poisson",
                        "pile_unit_weight",
                        "soil_young",
                        "soil_poisson",
                        "soil_unit_weight",
                        "k0",
                        "installation",
                        "head_displacement",
                        "steps",
                        "alert_distance",
                        "interface",
                        "mesh",
                    ],
                )?;
                let installation = match self.installation {
                    None => None,
                    Some(i) => {
                        let ip = p.key("installation");
                        let what = "this installation";
                        Some(match i.kind {
                            InstallationKind::None => {
                                only(
                                    &ip,
                                    "installation \"none\"",
                                    &[("value", i.value.is_some())],
                                    &[],
                                )?;
                                InstallationSpec::None {}
                            }
                            InstallationKind::RadialDisplacement => {
                                InstallationSpec::RadialDisplacement {
                                    value: need(&ip, &i.value, "value", what)?,
                                }
                            }
                            InstallationKind::NormalForceRatio => {
                                InstallationSpec::NormalForceRatio {
                                    value: need(&ip, &i.value, "value", what)?,
                                }
                            }
                        })
                    }
                };
                Preset::Pile {
                    site: self.site,
                    coulomb: self.coulomb.unwrap_or(false),
                    pile_young: self.pile_young,
                    pile_poisson: self.pile_poisson,
                    pile_unit_weight: self.pile_unit_weight,
                    soil_young: self.soil_young,
                    soil_poisson: self.soil_poisson,
                    soil_unit_weight: self.soil_unit_weight,
                    k0: self.k0,
                    installation,
                    head_displacement: self.head_displacement,
                    steps: self.steps,
                    alert_distance: self.alert_distance,
                    interface: self.interface,
                    mesh: self.mesh,
                }
            }
        })
    }
}
