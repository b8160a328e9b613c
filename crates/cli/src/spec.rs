//! The typed values of a scene, 2D and 3D alike: what each tagged table (`[mesh]`,
//! `[analysis]`, `[[loads]]`, `target`, `law`, `[preset]`, …) means once [`crate::raw`] has
//! resolved its `type` for the scene's dimension, and the small value types (`Pair`, [`Coords`],
//! `Element`, grading and scheme names, the preset overrides) that both the flat tables of
//! [`crate::raw`] and the tables of [`crate::scene`] read. A load's vectors have the scene's
//! dimension ([`LoadSpec<D>`]); the rigid shapes of a target are those of one dimension each
//! (a LINE and an ARC in 2D, a plane, a sphere and a cylinder in 3D) in one [`TargetSpec`].
//!
//! This module depends on no other module of the crate: [`crate::raw`] resolves into it and
//! [`crate::scene`] holds the raw tables, so the imports go `scene → raw → spec`.

use serde::de::{self, SeqAccess, Visitor};
use serde::{Deserialize, Deserializer};
use std::fmt;

/// Two numbers `[a, b]` (a point, a vector, a `[time, value]` row): exactly two, so that a
/// third value is an error rather than silently dropped.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pair(pub [f64; 2]);

impl<'de> Deserialize<'de> for Pair {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let v = Vec::<f64>::deserialize(d)?;
        match v[..] {
            [a, b] => Ok(Pair([a, b])),
            _ => Err(serde::de::Error::invalid_length(
                v.len(),
                &"two numbers [a, b]",
            )),
        }
    }
}

/// A point or a vector: two numbers `[x, y]` (a 2D scene) or three `[x, y, z]` (a 3D scene).
/// Which length a key takes is checked when the table is resolved, with its key path.
#[derive(Debug, Clone, PartialEq)]
pub struct Coords(pub Vec<f64>);

impl<'de> Deserialize<'de> for Coords {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let v = Vec::<f64>::deserialize(d)?;
        match v.len() {
            2 | 3 => Ok(Coords(v)),
            n => Err(de::Error::invalid_length(
                n,
                &"two numbers [x, y] (2D) or three [x, y, z] (3D)",
            )),
        }
    }
}

/// A load's `value`: one number (a pressure) or a vector ([`Coords`]).
#[derive(Debug, Clone, PartialEq)]
pub enum LoadValue {
    /// `value = 2.0`.
    Scalar(f64),
    /// `value = [0.0, 0.0, -1.0]`.
    Vector(Coords),
}

impl<'de> Deserialize<'de> for LoadValue {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = LoadValue;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a number (a pressure) or a vector [x, y] (2D) or [x, y, z] (3D)")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<LoadValue, E> {
                Ok(LoadValue::Scalar(v))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<LoadValue, E> {
                Ok(LoadValue::Scalar(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<LoadValue, E> {
                Ok(LoadValue::Scalar(v as f64))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<LoadValue, A::Error> {
                let mut v = Vec::new();
                while let Some(x) = seq.next_element::<f64>()? {
                    v.push(x);
                }
                match v.len() {
                    2 | 3 => Ok(LoadValue::Vector(Coords(v))),
                    n => Err(de::Error::invalid_length(
                        n,
                        &"two numbers [x, y] (2D) or three [x, y, z] (3D)",
                    )),
                }
            }
        }
        d.deserialize_any(V)
    }
}

/// P1 or P2 elements (triangles or quadrilaterals in 2D, tetrahedra or hexahedra in 3D).
#[derive(Debug, Deserialize, Clone, Copy, PartialEq, Eq)]
pub enum Element {
    /// 3-node triangles.
    #[serde(alias = "p1", alias = "tri3")]
    P1,
    /// 6-node triangles.
    #[serde(alias = "p2", alias = "tri6")]
    P2,
}

/// Geometric grading of a 1D subdivision.
#[derive(Debug, Clone, Copy)]
pub enum GradingSpec {
    /// Equal cells.
    Uniform {},
    /// Last cell over first cell = `ratio`.
    Geometric {
        /// h_last / h_first.
        ratio: f64,
    },
    /// Refined toward both ends, `ratio` = h_middle / h_end.
    BothEnds {
        /// h_middle / h_end.
        ratio: f64,
    },
}

impl Default for GradingSpec {
    fn default() -> Self {
        Self::Uniform {}
    }
}

#[derive(Debug, Clone)]
pub struct LayerSpec {
    /// Upper edge.
    pub top: f64,
    /// Cells across.
    pub ny: usize,
    /// Grading upward.
    pub grading: GradingSpec,
    pub region: u32,
}

/// The box generator (`fem_core::solid::generate::box_mesh`; every element in region 0), its
/// values checked later.
#[derive(Debug, Clone)]
pub struct BoxSpec {
    /// P1 (4-node) or P2 (10-node) tetrahedra.
    pub element: Element,
    /// `[x0, x1]`, `[y0, y1]`, `[z0, z1]`.
    pub ranges: [Pair; 3],
    /// Cells along x, y, z.
    pub cells: [usize; 3],
    /// Gradings along x, y, z.
    pub gradings: [GradingSpec; 3],
}

/// The pile generator's keys (each optional: the seed's pile by default): those a pile preset
/// overrides too, the gradings and the tip corner.
#[derive(Debug, Clone)]
pub struct PileMeshSpec {
    pub sizes: PileMeshOverride,
    /// Grading across the pile radius.
    pub grading_pile_r: Option<GradingSpec>,
    /// Grading of the soil, outward.
    pub grading_soil_r: Option<GradingSpec>,
    /// Grading along the shaft, upward.
    pub grading_shaft: Option<GradingSpec>,
    /// Grading below the tip, upward.
    pub grading_below_tip: Option<GradingSpec>,
    /// `split` or `shared`.
    pub tip_corner: Option<TipCornerSpec>,
    /// Whether the pile's tip is detached from the soil below (its nodes at `r < R`
    /// duplicated, node sets `tip_pile` and `tip_soil` paired by index), as the pile preset's.
    pub detach_tip: bool,
}

/// The mesh: a generator or a Gmsh file.
#[derive(Debug, Clone)]
pub enum MeshSpec {
    /// `fem_core::generate::rectangle`.
    Rectangle {
        /// P1 / P2.
        element: Element,
        /// `[x0, x1]`.
        x: Pair,
        /// Cells along x.
        nx: usize,
        grading_x: GradingSpec,
        /// `[y0, y1]` (one layer; or `y0` and `layers`).
        y: Option<Pair>,
        /// Cells along y for the one-layer form.
        ny: Option<usize>,
        /// Grading along y for the one-layer form.
        grading_y: Option<GradingSpec>,
        /// Region of the one-layer form.
        region: Option<u32>,
        /// Bottom edge (layered form).
        y0: Option<f64>,
        /// Layers from bottom to top (layered form).
        layers: Option<Vec<LayerSpec>>,
    },
    /// `fem_core::generate::pile_in_soil` (axisymmetric).
    Pile(PileMeshSpec),
    /// `fem_core::solid::generate::box_mesh` (3D).
    Box(BoxSpec),
    /// A Gmsh `.msh` 4.1 file (of the scene's dimension).
    Gmsh {
        /// Path, relative to the scene file.
        file: String,
        /// Expected element order (checked against the file).
        element: Option<Element>,
    },
}

#[derive(Debug, Deserialize, Clone, Copy)]
#[serde(rename_all = "snake_case")]
pub enum TipCornerSpec {
    /// Duplicated, first interface pair.
    Split,
    /// Shared by pile and soil.
    Shared,
}

/// The idealisation.
#[derive(Debug, Clone, Copy)]
pub enum Analysis {
    /// Plane strain (per unit thickness).
    PlaneStrain {},
    PlaneStress {
        thickness: f64,
    },
    /// Axisymmetric `(r, z)`, per radian.
    Axisymmetric {},
    /// A 3D solid (tetrahedra).
    Solid {},
}

#[derive(Debug, Clone, Copy)]
pub enum InitialStress {
    /// `fem_core::geostatic(gamma, k0, z_surface)`.
    Geostatic {
        /// Unit weight.
        gamma: f64,
        /// Earth pressure coefficient at rest.
        k0: f64,
        /// Ground surface elevation.
        z_surface: f64,
    },
}

/// A load of a scene of dimension `D` (its name, function and phases are `RawLoad::common`'s).
#[derive(Debug, Clone)]
pub enum LoadSpec<const D: usize> {
    /// Traction (force per area, global frame) on an edge set (2D) or a face set (3D).
    Traction {
        set: String,
        /// `[t_x, t_y]` or `[t_x, t_y, t_z]`.
        value: [f64; D],
    },
    /// A pressure on a face set, positive into the body (3D only).
    Pressure { set: String, value: f64 },
    /// A force on every node of a node set.
    NodalForce {
        set: String,
        /// The force per node.
        value: [f64; D],
    },
    /// One force on a node set tied along its non-zero components (a rigid cap's resultant).
    Resultant {
        set: String,
        /// The force on the whole set.
        value: [f64; D],
    },
    /// A uniform body force (force per volume) over the whole mesh.
    BodyForce { value: [f64; D] },
    /// The self-weight of every region (its material's `unit_weight`, along −y in 2D, −z in
    /// 3D), in full.
    Gravity,
}

#[derive(Debug, Deserialize, Clone, Copy)]
#[serde(rename_all = "snake_case")]
pub enum ArcSideSpec {
    /// Contactor outside the circle.
    Outside,
    /// Contactor inside the circle.
    Inside,
}

/// Target of a zone: a rigid shape of the scene's dimension (LINE, ARC in 2D; plane, sphere,
/// cylinder in 3D), node pairs, or another body's surface. Vectors are as written (their length
/// and values are checked when the target is built).
#[derive(Debug, Clone)]
pub enum TargetSpec {
    /// Rigid segment a → b, contactor on its left (2D).
    Line { a: Pair, b: Pair },
    /// Rigid circular arc (2D).
    Arc {
        center: Pair,
        radius: f64,
        /// Start angle (radians, counter-clockwise from +x).
        start_angle: f64,
        /// Sweep (radians, default 2π).
        sweep: Option<f64>,
        /// `outside` or `inside`.
        side: ArcSideSpec,
    },
    /// The rigid plane through `point`, the contactor on the side `normal` points to (3D).
    Plane {
        /// A point of the plane.
        point: Coords,
        /// Its normal, towards the contactor.
        normal: Coords,
    },
    /// A rigid sphere (3D).
    Sphere {
        center: Coords,
        radius: f64,
        /// The contactor's side (default outside).
        side: ArcSideSpec,
    },
    /// An infinite rigid circular cylinder (3D).
    Cylinder {
        /// A point of the axis.
        point: Coords,
        axis: Coords,
        radius: f64,
        /// The contactor's side (default outside).
        side: ArcSideSpec,
    },
    /// Node pairs: each contactor node with a node of `set` (2D: in the set's order, 3D: at
    /// its position).
    NodePairs {
        set: String,
        /// A fixed normal from the target to the contactor; absent: from the target nodes in
        /// order (2D) or the target body's faces (3D).
        normal: Option<Coords>,
    },
    /// Another body's surface: the polyline through a node set in order (2D `segments`), the
    /// faces of a face set (3D `faces`).
    Surface { set: String },
}

/// β time integration.
#[derive(Debug, Deserialize, Clone, Copy, Default, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum SchemeSpec {
    #[default]
    ImplicitEuler,
    /// θ-method (with `theta`).
    Theta,
}

#[derive(Debug, Clone, Copy)]
pub enum LawSpec {
    /// Frictionless unilateral contact.
    Signorini {},
    Coulomb {
        /// Friction coefficient.
        mu: f64,
    },
    Rccm(RccmSpec),
}

/// RCCM parameters (all required except `m`, `beta_0`, `scheme`, `theta`).
#[derive(Debug, Clone, Copy)]
pub struct RccmSpec {
    /// Normal stiffness.
    pub c_n: f64,
    /// Tangential stiffness.
    pub c_t: f64,
    /// Dupré's energy.
    pub w: f64,
    /// Viscosity.
    pub alpha: f64,
    /// Friction coefficient.
    pub mu: f64,
    /// Exponent of f(β).
    pub m: u32,
    /// Initial β.
    pub beta_0: f64,
    /// β scheme.
    pub scheme: SchemeSpec,
    /// θ of the θ-scheme.
    pub theta: Option<f64>,
}

/// The overrides the two seed plates (5.6.1, 5.6.2) share.
#[derive(Debug, Clone)]
pub struct PlateOverride {
    pub length: Option<f64>,
    pub height: Option<f64>,
    pub young: Option<f64>,
    pub poisson: Option<f64>,
    /// Cells along the interface.
    pub nx: Option<usize>,
    /// Cells across.
    pub ny: Option<usize>,
    pub element: Option<Element>,
    pub duration: Option<f64>,
    pub steps: Option<usize>,
    /// Interface law parameters (each optional).
    pub interface: Option<RccmOverride>,
}

/// A seed study built by the library.
#[derive(Debug, Clone)]
pub enum Preset {
    /// Seed 5.6.1.
    Delamination {
        plate: PlateOverride,
        /// Lift of point A.
        lift: Option<f64>,
    },
    /// Seed 5.6.2.
    Shear {
        plate: PlateOverride,
        /// Top `u_y` at the end.
        press: Option<f64>,
        /// Left `u_x` at the end.
        push: Option<f64>,
    },
    /// Seed chapter 6: pile pull-out (geostatic, installation, pull-out phases).
    Pile(PileOverride),
}

/// The overrides of the pile preset.
#[derive(Debug, Clone)]
pub struct PileOverride {
    /// `plancoet` (default) or `cran`.
    pub site: Option<Site>,
    /// Plain Coulomb interface (β₀ = 0) instead of RCCM.
    pub coulomb: bool,
    /// Pile Young's modulus (kPa).
    pub pile_young: Option<f64>,
    pub pile_poisson: Option<f64>,
    /// Pile unit weight (kN/m³).
    pub pile_unit_weight: Option<f64>,
    /// Soil Young's modulus (kPa).
    pub soil_young: Option<f64>,
    pub soil_poisson: Option<f64>,
    /// Soil unit weight (kN/m³).
    pub soil_unit_weight: Option<f64>,
    pub k0: Option<f64>,
    /// Phase 2.
    pub installation: Option<InstallationSpec>,
    /// Final head displacement (m).
    pub head_displacement: Option<f64>,
    /// Force control: the final jack force (kN, full ring, upwards).
    pub head_force: Option<f64>,
    /// Pull-out increments.
    pub steps: Option<usize>,
    /// Alert distance (m).
    pub alert_distance: Option<f64>,
    /// Interface law parameters (each optional).
    pub interface: Option<RccmOverride>,
    pub mesh: Option<PileMeshOverride>,
    /// The 3D quarter's sectors (a plastic scene with `[analysis] type = "3d"`).
    pub sectors: Option<usize>,
}

/// Which pile of the seed a pile preset starts from.
#[derive(Debug, Deserialize, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Site {
    /// Plancoët (L_p = 13 m).
    #[serde(alias = "plancoët")]
    Plancoet,
    /// Cran (L_p = 17 m).
    Cran,
}

/// Phase 2 of the pile preset.
#[derive(Debug, Clone, Copy)]
pub enum InstallationSpec {
    /// No installation.
    None {},
    /// Imposed radial displacement δ of the soil's interface nodes.
    RadialDisplacement {
        /// δ (m).
        value: f64,
    },
    /// δ such that the shaft normal force is this multiple of the geostatic one.
    NormalForceRatio {
        /// Ratio (>= 1).
        value: f64,
    },
}

/// The pile's sizes: `[preset] mesh` of the pile preset, and keys of the pile generator.
#[derive(Debug, Deserialize, Clone, Copy, Default)]
#[serde(deny_unknown_fields)]
pub struct PileMeshOverride {
    /// P1 / P2 (the generator's default: P2).
    pub element: Option<Element>,
    pub diameter: Option<f64>,
    /// Embedded length.
    pub length: Option<f64>,
    /// Radial extent of the soil.
    pub width: Option<f64>,
    /// Depth of the soil.
    pub depth: Option<f64>,
    /// Cells across the pile radius.
    pub cells_pile_r: Option<usize>,
    /// Cells in the soil, radially.
    pub cells_soil_r: Option<usize>,
    pub cells_shaft: Option<usize>,
    pub cells_below_tip: Option<usize>,
}

/// Optional overrides of RCCM parameters.
#[derive(Debug, Deserialize, Clone, Copy, Default)]
#[serde(deny_unknown_fields)]
pub struct RccmOverride {
    /// Normal stiffness.
    pub c_n: Option<f64>,
    /// Tangential stiffness.
    pub c_t: Option<f64>,
    /// Dupré's energy.
    pub w: Option<f64>,
    /// Viscosity.
    pub alpha: Option<f64>,
    /// Friction.
    pub mu: Option<f64>,
    /// Exponent.
    pub m: Option<u32>,
    /// Initial β.
    pub beta_0: Option<f64>,
    pub scheme: Option<SchemeSpec>,
    /// θ.
    pub theta: Option<f64>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, Deserialize)]
    struct T {
        c: Option<Coords>,
        v: Option<LoadValue>,
    }

    fn parse(s: &str) -> Result<T, String> {
        toml::from_str(s).map_err(|e| e.to_string())
    }

    #[test]
    fn coords_take_two_or_three_numbers_works() {
        assert_eq!(parse("c = [1, 2]").unwrap().c, Some(Coords(vec![1.0, 2.0])));
        assert_eq!(
            parse("c = [1.0, 2.0, 3.5]").unwrap().c,
            Some(Coords(vec![1.0, 2.0, 3.5]))
        );
    }

    #[test]
    fn coords_rejects_other_lengths() {
        let e = parse("c = [1.0]").unwrap_err();
        assert!(e.contains("invalid length 1"), "{e}");
        let e = parse("c = [1.0, 2.0, 3.0, 4.0]").unwrap_err();
        assert!(e.contains("three [x, y, z]"), "{e}");
    }

    #[test]
    fn load_values_are_numbers_or_vectors_works() {
        assert_eq!(parse("v = 2").unwrap().v, Some(LoadValue::Scalar(2.0)));
        assert_eq!(parse("v = -1.5").unwrap().v, Some(LoadValue::Scalar(-1.5)));
        assert_eq!(
            parse("v = [0, 0, -1]").unwrap().v,
            Some(LoadValue::Vector(Coords(vec![0.0, 0.0, -1.0])))
        );
    }

    #[test]
    fn load_values_rejects_text_and_bad_lengths() {
        let e = parse("v = \"up\"").unwrap_err();
        assert!(e.contains("a number (a pressure) or a vector"), "{e}");
        let e = parse("v = [1.0]").unwrap_err();
        assert!(e.contains("invalid length 1"), "{e}");
    }
}
