//! The typed values of a 3D scene (`[analysis] type = "3d"`): the box generator, the loads and
//! the rigid targets of a solid, and the one value type every 3D table reads, [`Coords`] (two or
//! three numbers, so that a 2D scene and a 3D one read the same keys and each says which length
//! it takes).
//!
//! Like [`crate::spec`], this module only depends on [`crate::spec`]: [`crate::raw`] resolves
//! into it.

use crate::spec::{ArcSideSpec, Element, GradingSpec, Pair};
use serde::de::{self, SeqAccess, Visitor};
use serde::{Deserialize, Deserializer};
use std::fmt;

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

/// A load on a 3D body.
#[derive(Debug, Clone)]
pub enum LoadSpec3 {
    /// Traction `[t_x, t_y, t_z]` (force per area, global frame) on a face set.
    Traction {
        /// Face set.
        set: String,
        /// The traction.
        value: Coords,
    },
    /// A pressure on a face set (positive pushes into the body).
    Pressure {
        /// Face set.
        set: String,
        /// The pressure.
        value: f64,
    },
    /// A force on every node of a node set.
    NodalForce {
        /// Node set.
        set: String,
        /// `[f_x, f_y, f_z]` per node.
        value: Coords,
    },
    /// One force on a node set tied along its non-zero components.
    Resultant {
        /// Node set.
        set: String,
        /// `[F_x, F_y, F_z]` on the whole set.
        value: Coords,
    },
    /// A uniform body force (force per volume).
    BodyForce {
        /// `[b_x, b_y, b_z]`.
        value: Coords,
    },
    /// The self-weight of every region, along −z, in full.
    Gravity,
}

/// A rigid target of a 3D zone.
#[derive(Debug, Clone)]
pub enum TargetSpec3 {
    /// The plane through `point`, the contactor on the side `normal` points to.
    Plane {
        /// A point of the plane.
        point: Coords,
        /// Its normal, towards the contactor.
        normal: Coords,
    },
    /// A sphere.
    Sphere {
        /// Centre.
        center: Coords,
        /// Radius.
        radius: f64,
        /// The contactor's side (default outside).
        side: ArcSideSpec,
    },
    /// An infinite circular cylinder.
    Cylinder {
        /// A point of the axis.
        point: Coords,
        /// The axis direction.
        axis: Coords,
        /// Radius.
        radius: f64,
        /// The contactor's side (default outside).
        side: ArcSideSpec,
    },
    /// Node pairs: each contactor node with the node of `set` at its position.
    NodePairs {
        /// The target node set (a face set when `normal` is absent).
        set: String,
        /// A fixed normal for every pair, from the target to the contactor; absent: the
        /// target body's outward normal from the faces of `set`.
        normal: Option<Coords>,
    },
    /// Node-to-face: the faces of another body's face set.
    Faces {
        /// The target face set.
        set: String,
    },
}

/// The mesh of a 3D scene.
#[derive(Debug, Clone)]
pub enum MeshSpec3 {
    /// The box generator.
    Box(BoxSpec),
    /// A Gmsh `.msh` 4.1 volume file.
    Gmsh {
        /// Path, relative to the scene file.
        file: String,
        /// Expected element order (checked against the file).
        element: Option<Element>,
    },
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
