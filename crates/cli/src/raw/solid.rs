//! The flat tables of a 3D scene resolved: `[[loads]]` and `target` with three-number vectors,
//! and the error that names a 2D-only type in a 3D scene.

use super::keys::{need, only};
use super::{LoadKindSpec, RawLoad, RawTarget, TargetKind};
use crate::error::{CliError, CliResult, KeyPath};
use crate::spec::ArcSideSpec;
use crate::spec3::{Coords, LoadSpec3, LoadValue, TargetSpec3};

/// A 3D vector `[x, y, z]` at `p`, or the error a 3D scene gives for two numbers.
pub fn triple(p: &KeyPath, c: &Coords) -> CliResult<[f64; 3]> {
    match c.0[..] {
        [x, y, z] => Ok([x, y, z]),
        _ => Err(CliError::at(
            p,
            format!(
                "`{p}`: invalid length {}, expected three numbers [x, y, z] (a 3D scene)",
                c.0.len()
            ),
        )),
    }
}

/// A 3D load's vector `value`.
fn vector(p: &KeyPath, v: &Option<LoadValue>, what: &str) -> CliResult<Coords> {
    let vp = p.key("value");
    match need(p, v, "value", what)? {
        LoadValue::Vector(c) => {
            triple(&vp, &c)?;
            Ok(c)
        }
        LoadValue::Scalar(x) => Err(CliError::at(
            &vp,
            format!("`{vp}` = {x:?}: {what} takes three numbers [x, y, z]"),
        )),
    }
}

impl RawLoad {
    /// The load of a 3D scene, with its name, function and phases.
    pub fn resolve_3d(&self, p: &KeyPath) -> CliResult<LoadSpec3> {
        let present = [
            ("set", self.set.is_some()),
            ("value", self.value.is_some()),
            ("function", self.function.is_some()),
        ];
        Ok(match self.kind {
            LoadKindSpec::Traction => LoadSpec3::Traction {
                set: need(p, &self.set, "set", "a traction (a face set)")?,
                value: vector(p, &self.value, "a traction")?,
            },
            LoadKindSpec::Pressure => {
                let what = "a pressure (a face set)";
                let vp = p.key("value");
                LoadSpec3::Pressure {
                    set: need(p, &self.set, "set", what)?,
                    value: match need(p, &self.value, "value", what)? {
                        LoadValue::Scalar(x) => x,
                        LoadValue::Vector(_) => {
                            return Err(CliError::at(
                                &vp,
                                format!(
                                    "`{vp}`: a pressure is one number (positive pushes into \
                                     the body); for a vector give type = \"traction\""
                                ),
                            ));
                        }
                    },
                }
            }
            LoadKindSpec::NodalForce => LoadSpec3::NodalForce {
                set: need(p, &self.set, "set", "a nodal force (a node set)")?,
                value: vector(p, &self.value, "a nodal force")?,
            },
            LoadKindSpec::Resultant => LoadSpec3::Resultant {
                set: need(p, &self.set, "set", "a resultant force (a tied node set)")?,
                value: vector(p, &self.value, "a resultant force")?,
            },
            LoadKindSpec::BodyForce => {
                only(p, "a body force", &present, &["value", "function"])?;
                LoadSpec3::BodyForce {
                    value: vector(p, &self.value, "a body force")?,
                }
            }
            LoadKindSpec::Gravity => {
                only(
                    p,
                    "a gravity load (the self-weight is applied in full: it has no function)",
                    &present,
                    &[],
                )?;
                LoadSpec3::Gravity
            }
        })
    }
}

impl RawTarget {
    /// The target of a 3D scene.
    pub fn resolve_3d(&self, p: &KeyPath) -> CliResult<TargetSpec3> {
        let present = self.present();
        let side = self.side.unwrap_or(ArcSideSpec::Outside);
        Ok(match self.kind {
            TargetKind::Plane => {
                let what = "a plane target";
                only(p, what, &present, &["point", "normal"])?;
                TargetSpec3::Plane {
                    point: need(p, &self.point, "point", what)?,
                    normal: need(p, &self.normal, "normal", what)?,
                }
            }
            TargetKind::Sphere => {
                let what = "a sphere target";
                only(p, what, &present, &["center", "radius", "side"])?;
                TargetSpec3::Sphere {
                    center: need(p, &self.center, "center", what)?,
                    radius: need(p, &self.radius, "radius", what)?,
                    side,
                }
            }
            TargetKind::Cylinder => {
                let what = "a cylinder target";
                only(p, what, &present, &["point", "axis", "radius", "side"])?;
                TargetSpec3::Cylinder {
                    point: need(p, &self.point, "point", what)?,
                    axis: need(p, &self.axis, "axis", what)?,
                    radius: need(p, &self.radius, "radius", what)?,
                    side,
                }
            }
            TargetKind::NodePairs => {
                let what = "a node_pairs target";
                only(p, what, &present, &["set", "normal"])?;
                TargetSpec3::NodePairs {
                    set: need(p, &self.set, "set", what)?,
                    normal: self.normal.clone(),
                }
            }
            TargetKind::Faces => {
                let what = "a faces target";
                only(p, what, &present, &["set"])?;
                TargetSpec3::Faces {
                    set: need(p, &self.set, "set", what)?,
                }
            }
            TargetKind::Line | TargetKind::Arc | TargetKind::Segments => {
                let tp = p.key("type");
                return Err(CliError::at(
                    &tp,
                    format!(
                        "`{tp}` = \"{}\" is a target of a 2D scene; a 3D scene takes plane, \
                         sphere, cylinder, node_pairs or faces",
                        self.kind.name()
                    ),
                ));
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
    fn triple_rejects_two_numbers() {
        let p = KeyPath::root().key("v");
        assert_eq!(
            triple(&p, &Coords(vec![1.0, 2.0, 3.0])).unwrap(),
            [1.0, 2.0, 3.0]
        );
        let e = triple(&p, &Coords(vec![1.0, 2.0])).unwrap_err();
        assert_eq!(e.path.unwrap().to_string(), "v");
        assert!(
            e.message.contains("expected three numbers"),
            "{}",
            e.message
        );
    }

    #[test]
    fn targets_resolve_in_3d_works() {
        let p = KeyPath::root().key("target");
        let t = target("type = \"sphere\"\ncenter = [0, 0, 1]\nradius = 2.0");
        match t.resolve_3d(&p).unwrap() {
            TargetSpec3::Sphere { radius, side, .. } => {
                assert_eq!(radius, 2.0);
                assert!(matches!(side, ArcSideSpec::Outside));
            }
            other => panic!("{other:?}"),
        }
        let t = target(
            "type = \"cylinder\"\npoint = [0, 0, 1]\naxis = [1, 0, 0]\nradius = 1.0\nside = \"inside\"",
        );
        assert!(matches!(
            t.resolve_3d(&p).unwrap(),
            TargetSpec3::Cylinder {
                side: ArcSideSpec::Inside,
                ..
            }
        ));
    }

    #[test]
    fn targets_rejects_the_other_dimension() {
        let p = KeyPath::root().key("target");
        let e = target("type = \"line\"\na = [0, 0]\nb = [1, 0]")
            .resolve_3d(&p)
            .unwrap_err();
        assert_eq!(e.path.unwrap().to_string(), "target.type");
        let e = target("type = \"plane\"\npoint = [0, 0, 0]\nnormal = [0, 0, 1]")
            .resolve(&p)
            .unwrap_err();
        assert!(
            e.message.contains("is a target of a 3D scene"),
            "{}",
            e.message
        );
        let e = target("type = \"plane\"\npoint = [0, 0, 0]\nnormal = [0, 0, 1]\nradius = 1.0")
            .resolve_3d(&p)
            .unwrap_err();
        assert_eq!(e.path.unwrap().to_string(), "target.radius");
    }
}
