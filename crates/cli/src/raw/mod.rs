//! The tables of the scene that have a `type` (or `generator`, `kind`) key, as read: one flat
//! struct per table, every key optional, then [`resolve`](RawLaw::resolve)d into the typed
//! enums of [`crate::spec`] with a check of which keys that type needs and accepts.
//!
//! Why not serde's internally tagged enums: they buffer the table before choosing the variant,
//! so a wrong value inside (`nx = "two"`) is reported at the table, without the key. Flat
//! structs keep the line, the column and the key path of every value.
//!
//! A table is resolved once for both dimensions (`resolve::<D>`): the types of the other
//! dimension are refused with a message that names it, and vectors take `D` numbers.
//!
//! [`keys`] holds the two checks of keys; `[mesh]` and `[preset]`, the two largest tables, have
//! a file each.

mod dynamic;
mod keys;
mod linear;
mod mesh;
mod plastic;
mod preset;

pub use dynamic::{DynamicSpec, MassSpec, restitution};
pub use linear::{LinearSolverSpec, PetscSpec};
pub use mesh::RawMesh;
pub use plastic::{ConeSpec, MaterialKind, NewtonSpec, RawNewton};
pub use preset::RawPreset;

use crate::error::{CliResult, KeyPath, bail, err};
use crate::spec::*;
use keys::{need, only, present};
use serde::Deserialize;

#[derive(Debug, Deserialize, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum AnalysisKind {
    PlaneStrain,
    PlaneStress,
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
    /// `dynamic = true`: a Moreau–Jean run ([`dynamic`] reads the keys below).
    dynamic: Option<bool>,
    time_step: Option<f64>,
    end_time: Option<f64>,
    theta: Option<f64>,
    mass: Option<MassSpec>,
    rayleigh_alpha: Option<f64>,
    rayleigh_beta: Option<f64>,
    /// `[analysis.newton]`: the global Newton of a scene with a plastic material (issue 40).
    newton: Option<RawNewton>,
    /// `linear_solver = "petsc"`: the bulk solved by PETSc under MPI ([`linear`]).
    linear_solver: Option<linear::LinearSolverKind>,
    /// `[analysis.petsc]`: PETSc's method and tolerance.
    petsc: Option<linear::RawPetsc>,
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
        let present = present!(self; thickness);
        Ok(match self.kind {
            AnalysisKind::PlaneStrain => {
                only(
                    p,
                    "a plane strain analysis (per unit thickness)",
                    &present,
                    "",
                )?;
                Analysis::PlaneStrain {}
            }
            AnalysisKind::PlaneStress => Analysis::PlaneStress {
                thickness: need(p, &self.thickness, "thickness", "a plane stress analysis")?,
            },
            AnalysisKind::Axisymmetric => {
                only(p, "an axisymmetric analysis (per radian)", &present, "")?;
                Analysis::Axisymmetric {}
            }
            AnalysisKind::Solid => {
                only(p, "a 3D analysis", &present, "")?;
                if self.floating == Some(true) {
                    let f = p.key("floating");
                    bail!(
                        f,
                        "`{f}` = true: floating bodies are not supported in 3D yet (hold \
                             the body with supports)"
                    );
                }
                Analysis::Solid {}
            }
        })
    }
}

// ---------------------------------------------------------------------------------------------

#[derive(Debug, Deserialize, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum InitialStressKind {
    Geostatic,
}

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

#[derive(Debug, Deserialize, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum LoadKindSpec {
    Traction,
    NodalForce,
    BodyForce,
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

/// How a scene of dimension `D` writes a vector: "two numbers [a, b]" or "three numbers [x,
/// y, z]".
fn numbers<const D: usize>() -> &'static str {
    if D == 2 {
        "two numbers [a, b]"
    } else {
        "three numbers [x, y, z]"
    }
}

/// The vector `c` at `p` in a scene of dimension `D`, or the error that says which length the
/// scene takes (and, for three numbers in 2D, that they are for a 3D scene).
pub fn vector<const D: usize>(p: &KeyPath, c: &Coords) -> CliResult<[f64; D]> {
    <[f64; D]>::try_from(c.0.as_slice()).map_err(|_| {
        let hint = if D == 2 {
            " (three numbers [x, y, z] are for a 3D scene: [analysis] type = \"3d\")"
        } else {
            " (a 3D scene)"
        };
        err!(
            p,
            "`{p}`: invalid length {}, expected {}{hint}",
            c.0.len(),
            numbers::<D>()
        )
    })
}

/// A load's vector `value` in a scene of dimension `D`.
fn load_vector<const D: usize>(
    p: &KeyPath,
    v: &Option<LoadValue>,
    what: &str,
) -> CliResult<[f64; D]> {
    let vp = p.key("value");
    match need(p, v, "value", what)? {
        LoadValue::Vector(c) => vector(&vp, &c),
        LoadValue::Scalar(x) => bail!(vp, "`{vp}` = {x:?}: {what} takes {}", numbers::<D>()),
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

    /// The load of a scene of dimension `D` (a pressure is a load of a 3D scene).
    pub fn resolve<const D: usize>(&self, p: &KeyPath) -> CliResult<LoadSpec<D>> {
        let present = present!(self; set, value, function);
        let boundary = if D == 2 { "an edge set" } else { "a face set" };
        Ok(match self.kind {
            LoadKindSpec::Traction => LoadSpec::Traction {
                set: need(p, &self.set, "set", &format!("a traction ({boundary})"))?,
                value: load_vector(p, &self.value, "a traction")?,
            },
            LoadKindSpec::Pressure if D == 2 => {
                let tp = p.key("type");
                bail!(
                    tp,
                    "`{tp}` = \"pressure\" is a load of a 3D scene ([analysis] type = \
                         \"3d\"); in 2D give a traction [t_x, t_y] on an edge set"
                );
            }
            LoadKindSpec::Pressure => {
                let what = "a pressure (a face set)";
                let vp = p.key("value");
                LoadSpec::Pressure {
                    set: need(p, &self.set, "set", what)?,
                    value: match need(p, &self.value, "value", what)? {
                        LoadValue::Scalar(x) => x,
                        LoadValue::Vector(_) => {
                            bail!(
                                vp,
                                "`{vp}`: a pressure is one number (positive pushes into \
                                     the body); for a vector give type = \"traction\""
                            );
                        }
                    },
                }
            }
            LoadKindSpec::NodalForce => LoadSpec::NodalForce {
                set: need(p, &self.set, "set", "a nodal force (a node set)")?,
                value: load_vector(p, &self.value, "a nodal force")?,
            },
            LoadKindSpec::Resultant => LoadSpec::Resultant {
                set: need(p, &self.set, "set", "a resultant force (a tied node set)")?,
                value: load_vector(p, &self.value, "a resultant force")?,
            },
            LoadKindSpec::BodyForce => {
                only(p, "a body force", &present, "value function")?;
                LoadSpec::BodyForce {
                    value: load_vector(p, &self.value, "a body force")?,
                }
            }
            LoadKindSpec::Gravity => {
                let what =
                    "a gravity load (the self-weight is applied in full: it has no function)";
                only(p, what, &present, "")?;
                LoadSpec::Gravity
            }
        })
    }
}

// ---------------------------------------------------------------------------------------------

#[derive(Debug, Deserialize, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum TargetKind {
    Line,
    Arc,
    NodePairs,
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
        present!(self; a, b, center, radius, start_angle, sweep, side, set, normal, point, axis)
    }

    /// The target of a scene of dimension `D`: the types of the other dimension are refused
    /// at `type`.
    pub fn resolve<const D: usize>(&self, p: &KeyPath) -> CliResult<TargetSpec> {
        use TargetKind::*;
        let present = self.present();
        let kind = self.kind.name();
        if D == 2 && matches!(self.kind, Plane | Sphere | Cylinder | Faces) {
            let tp = p.key("type");
            bail!(
                tp,
                "`{tp}` = \"{kind}\" is a target of a 3D scene ([analysis] type = \"3d\"); \
                     a 2D scene takes line, arc, node_pairs or segments"
            );
        }
        if D == 3 && matches!(self.kind, Line | Arc | Segments) {
            let tp = p.key("type");
            bail!(
                tp,
                "`{tp}` = \"{kind}\" is a target of a 2D scene; a 3D scene takes plane, \
                     sphere, cylinder, node_pairs or faces"
            );
        }
        let side = self.side.unwrap_or(ArcSideSpec::Outside);
        Ok(match self.kind {
            Line => {
                only(p, "a LINE target", &present, "a b")?;
                TargetSpec::Line {
                    a: need(p, &self.a, "a", "a LINE target")?,
                    b: need(p, &self.b, "b", "a LINE target")?,
                }
            }
            Arc => {
                let what = "an ARC target";
                only(p, what, &present, "center radius start_angle sweep side")?;
                let center = need(p, &self.center, "center", what)?;
                TargetSpec::Arc {
                    center: Pair(vector(&p.key("center"), &center)?),
                    radius: need(p, &self.radius, "radius", what)?,
                    start_angle: self.start_angle.unwrap_or(0.0),
                    sweep: self.sweep,
                    side: need(p, &self.side, "side", what)?,
                }
            }
            Plane => {
                let what = "a plane target";
                only(p, what, &present, "point normal")?;
                TargetSpec::Plane {
                    point: need(p, &self.point, "point", what)?,
                    normal: need(p, &self.normal, "normal", what)?,
                }
            }
            Sphere => {
                let what = "a sphere target";
                only(p, what, &present, "center radius side")?;
                TargetSpec::Sphere {
                    center: need(p, &self.center, "center", what)?,
                    radius: need(p, &self.radius, "radius", what)?,
                    side,
                }
            }
            Cylinder => {
                let what = "a cylinder target";
                only(p, what, &present, "point axis radius side")?;
                TargetSpec::Cylinder {
                    point: need(p, &self.point, "point", what)?,
                    axis: need(p, &self.axis, "axis", what)?,
                    radius: need(p, &self.radius, "radius", what)?,
                    side,
                }
            }
            NodePairs => {
                let what = "a node_pairs target";
                only(p, what, &present, "set normal")?;
                TargetSpec::NodePairs {
                    set: need(p, &self.set, "set", what)?,
                    normal: self.normal.clone(),
                }
            }
            Segments | Faces => {
                let what = format!("a {kind} target");
                only(p, &what, &present, "set")?;
                TargetSpec::Surface {
                    set: need(p, &self.set, "set", &what)?,
                }
            }
        })
    }
}

// ---------------------------------------------------------------------------------------------

#[derive(Debug, Deserialize, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum LawKind {
    Signorini,
    Coulomb,
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
    /// Newton's restitution `e` of a dynamic scene (any law type).
    restitution: Option<f64>,
}

impl RawLaw {
    /// `restitution`, as written (a key of a dynamic scene, for every law type).
    pub fn restitution(&self) -> Option<f64> {
        self.restitution
    }

    /// The law.
    pub fn resolve(&self, p: &KeyPath) -> CliResult<LawSpec> {
        let present = present!(self; mu, c_n, c_t, w, alpha, m, beta_0, scheme, theta);
        Ok(match self.kind {
            LawKind::Signorini => {
                only(p, "the signorini law (frictionless)", &present, "")?;
                LawSpec::Signorini {}
            }
            LawKind::Coulomb => {
                only(p, "the coulomb law", &present, "mu")?;
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

#[cfg(test)]
mod tests {
    use super::*;

    fn target(s: &str) -> RawTarget {
        toml::from_str(s).unwrap()
    }

    #[test]
    fn vector_takes_the_scene_s_length_works() {
        let p = KeyPath::root().key("v");
        let three = Coords(vec![1.0, 2.0, 3.0]);
        assert_eq!(vector::<3>(&p, &three).unwrap(), [1.0, 2.0, 3.0]);
        assert_eq!(
            vector::<2>(&p, &Coords(vec![1.0, 2.0])).unwrap(),
            [1.0, 2.0]
        );
        let e = vector::<3>(&p, &Coords(vec![1.0, 2.0])).unwrap_err();
        assert_eq!(e.path.unwrap().to_string(), "v");
        assert!(
            e.message.contains("expected three numbers"),
            "{}",
            e.message
        );
        let e = vector::<2>(&p, &three).unwrap_err();
        assert!(e.message.contains("are for a 3D scene"), "{}", e.message);
    }

    #[test]
    fn targets_resolve_in_3d_works() {
        let p = KeyPath::root().key("target");
        let t = target("type = \"sphere\"\ncenter = [0, 0, 1]\nradius = 2.0");
        match t.resolve::<3>(&p).unwrap() {
            TargetSpec::Sphere { radius, side, .. } => {
                assert_eq!(radius, 2.0);
                assert!(matches!(side, ArcSideSpec::Outside));
            }
            other => panic!("{other:?}"),
        }
        let t = target(
            "type = \"cylinder\"\npoint = [0, 0, 1]\naxis = [1, 0, 0]\nradius = 1.0\nside = \"inside\"",
        );
        assert!(matches!(
            t.resolve::<3>(&p).unwrap(),
            TargetSpec::Cylinder {
                side: ArcSideSpec::Inside,
                ..
            }
        ));
    }

    #[test]
    fn targets_rejects_the_other_dimension() {
        let p = KeyPath::root().key("target");
        let e = target("type = \"line\"\na = [0, 0]\nb = [1, 0]")
            .resolve::<3>(&p)
            .unwrap_err();
        assert_eq!(e.path.unwrap().to_string(), "target.type");
        let e = target("type = \"plane\"\npoint = [0, 0, 0]\nnormal = [0, 0, 1]")
            .resolve::<2>(&p)
            .unwrap_err();
        assert!(
            e.message.contains("is a target of a 3D scene"),
            "{}",
            e.message
        );
        let e = target("type = \"plane\"\npoint = [0, 0, 0]\nnormal = [0, 0, 1]\nradius = 1.0")
            .resolve::<3>(&p)
            .unwrap_err();
        assert_eq!(e.path.unwrap().to_string(), "target.radius");
    }
}
