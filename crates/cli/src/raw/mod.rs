//! The tables of the scene that have a `type` (or `generator`, `kind`) key, as read: one flat
//! struct per table, every key optional, then [`resolve`](RawLaw::resolve)d into the typed
//! enums of [`crate::spec`] with a check of which keys that type needs and accepts.
//!
//! Why not serde's internally tagged enums: they buffer the table before choosing the variant,
//! so a wrong value inside (`nx = "two"`) is reported at the table, without the key. Flat
//! structs keep the line, the column and the key path of every value.
//!
//! [`keys`] holds the two checks of keys; `[mesh]` and `[preset]`, the two largest tables, have
//! a file each; [`solid`] resolves `[[loads]]` and `target` of a 3D scene (the typed values of
//! [`crate::spec3`]; `[mesh]`'s 3D form is in [`mesh`]).

mod keys;
mod mesh;
mod preset;
mod solid;

pub use mesh::RawMesh;
pub use preset::RawPreset;
pub use solid::triple;

use crate::error::{CliError, CliResult, KeyPath};
use crate::spec::*;
use crate::spec3::{Coords, LoadValue};
use keys::{need, only};
use serde::Deserialize;

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
    /// A 3D solid of tetrahedra (`type = "3d"`, or `"solid"`).
    #[serde(rename = "3d", alias = "solid")]
    Solid,
}

/// `[analysis]`.
#[derive(Debug, Deserialize, Clone, Copy)]
#[serde(deny_unknown_fields)]
pub struct RawAnalysis {
    #[serde(rename = "type")]
    kind: AnalysisKind,
    thickness: Option<f64>,
    floating: Option<bool>,
}

impl RawAnalysis {
    /// Whether the scene is 3D (`type = "3d"`).
    pub fn is_solid(&self) -> bool {
        self.kind == AnalysisKind::Solid
    }

    /// `floating = true`: bodies that contact alone holds (rigid-body modes left by the
    /// supports are solved for with the contact, `LinearElasticModel::floating`).
    pub fn floating(&self) -> bool {
        self.floating.unwrap_or(false)
    }

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
            AnalysisKind::Solid => {
                only(p, "a 3D analysis", &present, &[])?;
                if self.floating == Some(true) {
                    let f = p.key("floating");
                    return Err(CliError::at(
                        &f,
                        format!(
                            "`{f}` = true: floating bodies are not supported in 3D yet (hold \
                             the body with supports)"
                        ),
                    ));
                }
                Analysis::Solid {}
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
    /// A resultant force on a tied node set.
    Resultant,
    /// A pressure on a face set (3D).
    Pressure,
}

/// `[[loads]]`.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct RawLoad {
    #[serde(rename = "type")]
    kind: LoadKindSpec,
    name: Option<String>,
    set: Option<String>,
    value: Option<LoadValue>,
    function: Option<String>,
    phases: Option<Vec<String>>,
}

/// Two or three numbers as a 2D scene's `[a, b]`, with the error a 2D scene gives for three.
fn pair_of(p: &KeyPath, c: &Coords) -> CliResult<Pair> {
    match c.0[..] {
        [a, b] => Ok(Pair([a, b])),
        _ => Err(CliError::at(
            p,
            format!(
                "`{p}`: invalid length {}, expected two numbers [a, b] (three numbers [x, y, z] \
                 are for a 3D scene: [analysis] type = \"3d\")",
                c.0.len()
            ),
        )),
    }
}

/// A 2D load's `value`: a vector `[a, b]`.
fn load_pair(p: &KeyPath, v: &Option<LoadValue>, what: &str) -> CliResult<Pair> {
    let vp = p.key("value");
    match need(p, v, "value", what)? {
        LoadValue::Vector(c) => pair_of(&vp, &c),
        LoadValue::Scalar(x) => Err(CliError::at(
            &vp,
            format!("`{vp}` = {x:?}: {what} takes two numbers [a, b]"),
        )),
    }
}

impl RawLoad {
    /// `name`, `function` and `phases`, as written (the same in both dimensions).
    pub fn common(&self) -> (Option<String>, Option<String>, Option<Vec<String>>) {
        (
            self.name.clone(),
            self.function.clone(),
            self.phases.clone(),
        )
    }

    /// The load of a 2D scene.
    pub fn resolve(&self, p: &KeyPath) -> CliResult<LoadSpec> {
        let present = [
            ("set", self.set.is_some()),
            ("value", self.value.is_some()),
            ("function", self.function.is_some()),
        ];
        Ok(match self.kind {
            LoadKindSpec::Traction => LoadSpec::Traction {
                set: need(p, &self.set, "set", "a traction (an edge set)")?,
                value: load_pair(p, &self.value, "a traction")?,
            },
            LoadKindSpec::NodalForce => LoadSpec::NodalForce {
                set: need(p, &self.set, "set", "a nodal force (a node set)")?,
                value: load_pair(p, &self.value, "a nodal force")?,
            },
            LoadKindSpec::Resultant => LoadSpec::Resultant {
                set: need(p, &self.set, "set", "a resultant force (a tied node set)")?,
                value: load_pair(p, &self.value, "a resultant force")?,
            },
            LoadKindSpec::BodyForce => {
                only(p, "a body force", &present, &["value", "function"])?;
                LoadSpec::BodyForce {
                    value: load_pair(p, &self.value, "a body force")?,
                }
            }
            LoadKindSpec::Gravity => {
                only(
                    p,
                    "a gravity load (the self-weight is applied in full: it has no function)",
                    &present,
                    &[],
                )?;
                LoadSpec::Gravity
            }
            LoadKindSpec::Pressure => {
                let tp = p.key("type");
                return Err(CliError::at(
                    &tp,
                    format!(
                        "`{tp}` = \"pressure\" is a load of a 3D scene ([analysis] type = \
                         \"3d\"); in 2D give a traction [t_x, t_y] on an edge set"
                    ),
                ));
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
    /// A rigid plane (3D).
    Plane,
    /// A rigid sphere (3D).
    Sphere,
    /// A rigid cylinder (3D).
    Cylinder,
    /// Node-to-face: another body's faces (3D).
    Faces,
}

impl TargetKind {
    /// The name in a scene file.
    pub fn name(self) -> &'static str {
        match self {
            TargetKind::Line => "line",
            TargetKind::Arc => "arc",
            TargetKind::NodePairs => "node_pairs",
            TargetKind::Segments => "segments",
            TargetKind::Plane => "plane",
            TargetKind::Sphere => "sphere",
            TargetKind::Cylinder => "cylinder",
            TargetKind::Faces => "faces",
        }
    }
}

/// `target = {...}`.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct RawTarget {
    #[serde(rename = "type")]
    kind: TargetKind,
    a: Option<Pair>,
    b: Option<Pair>,
    center: Option<Coords>,
    radius: Option<f64>,
    start_angle: Option<f64>,
    sweep: Option<f64>,
    side: Option<ArcSideSpec>,
    set: Option<String>,
    normal: Option<Coords>,
    point: Option<Coords>,
    axis: Option<Coords>,
}

impl RawTarget {
    /// Which keys the table has (for the checks of which keys a type takes).
    fn present(&self) -> [(&'static str, bool); 11] {
        [
            ("a", self.a.is_some()),
            ("b", self.b.is_some()),
            ("center", self.center.is_some()),
            ("radius", self.radius.is_some()),
            ("start_angle", self.start_angle.is_some()),
            ("sweep", self.sweep.is_some()),
            ("side", self.side.is_some()),
            ("set", self.set.is_some()),
            ("normal", self.normal.is_some()),
            ("point", self.point.is_some()),
            ("axis", self.axis.is_some()),
        ]
    }

    /// The target of a 2D scene.
    pub fn resolve(&self, p: &KeyPath) -> CliResult<TargetSpec> {
        let present = self.present();
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
                    center: pair_of(&p.key("center"), &need(p, &self.center, "center", what)?)?,
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
                    normal: self
                        .normal
                        .as_ref()
                        .map(|n| pair_of(&p.key("normal"), n))
                        .transpose()?,
                }
            }
            TargetKind::Segments => {
                only(p, "a segments target", &present, &["set"])?;
                TargetSpec::Segments {
                    set: need(p, &self.set, "set", "a segments target")?,
                }
            }
            TargetKind::Plane | TargetKind::Sphere | TargetKind::Cylinder | TargetKind::Faces => {
                let tp = p.key("type");
                return Err(CliError::at(
                    &tp,
                    format!(
                        "`{tp}` = \"{}\" is a target of a 3D scene ([analysis] type = \"3d\"); \
                         a 2D scene takes line, arc, node_pairs or segments",
                        self.kind.name()
                    ),
                ));
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
