//! Rigid obstacles in 3D: [`RigidPlane`], [`RigidSphere`], [`RigidCylinder`]; your own
//! implements [`Obstacle<3>`].
//!
//! An obstacle answers the closest point of its surface to a point `p`, with the unit normal
//! `n` towards the contactor's side and the signed gap `g = (p − point)·n` (positive outside the
//! obstacle). The contact frame's tangents come from the normal by one fixed rule,
//! [`tangent_frame`]: `t₁` is the first of `e_x`, `e_y` not within 25° of `n`, made orthogonal
//! to `n`, and `t₂ = n × t₁`, so `(n, t₁, t₂)` is right-handed; on a plane of normal `e_z`,
//! `t₁ = e_x` and `t₂ = e_y`.

use crate::coupling::obstacle::{Obstacle, ObstaclePoint, ObstacleSide, finite_point};
use crate::coupling::space::{cross, dot, sub};
use crate::error::SolverError;

/// The closest point of a 3D obstacle: [`ObstaclePoint<3>`].
pub type ObstaclePoint3 = ObstaclePoint<3>;

/// The side of a 3D sphere or cylinder: [`ObstacleSide`], the one type of both dimensions.
pub type Side3 = ObstacleSide;

/// The tangents `(t₁, t₂)` of the contact frame of unit normal `n` (module docs).
pub fn tangent_frame(n: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    // cos 25° ≈ 0.906: e_x unless n is within 25° of it
    let e = if n[0].abs() < 0.906 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let d = dot(e, n);
    let t = [e[0] - d * n[0], e[1] - d * n[1], e[2] - d * n[2]];
    let len = dot(t, t).sqrt();
    let t1 = t.map(|v| v / len);
    (t1, cross(n, t1))
}

fn unit(what: &'static str, v: [f64; 3]) -> Result<[f64; 3], SolverError> {
    let v = finite_point(what, v)?;
    let len = dot(v, v).sqrt();
    if !(len > 0.0 && len.is_finite()) {
        return Err(SolverError::InvalidGeometry(format!(
            "{what} must be a nonzero vector, got {v:?}"
        )));
    }
    Ok(v.map(|x| x / len))
}

fn radius(what: &'static str, r: f64) -> Result<f64, SolverError> {
    if r > 0.0 && r.is_finite() {
        Ok(r)
    } else {
        Err(SolverError::InvalidSetting {
            what,
            value: r,
            expected: "a finite radius > 0",
        })
    }
}

/// An infinite rigid plane through `point`; the contactor lies on the side `normal` points to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RigidPlane {
    point: [f64; 3],
    normal: [f64; 3],
}

impl RigidPlane {
    /// The plane through `point` with the contactor on the side of `normal` (normalised here).
    ///
    /// # Errors
    /// [`SolverError::NonFinite`] for a non-finite coordinate;
    /// [`SolverError::InvalidGeometry`] for a zero normal.
    pub fn new(point: [f64; 3], normal: [f64; 3]) -> Result<Self, SolverError> {
        Ok(Self {
            point: finite_point("plane point", point)?,
            normal: unit("plane normal", normal)?,
        })
    }
}

impl Obstacle<3> for RigidPlane {
    fn project(&self, p: [f64; 3]) -> Option<ObstaclePoint<3>> {
        let gap = dot(sub(p, self.point), self.normal);
        Some(ObstaclePoint {
            point: core::array::from_fn(|a| p[a] - gap * self.normal[a]),
            normal: self.normal,
            gap,
        })
    }
}

/// A rigid sphere.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RigidSphere {
    center: [f64; 3],
    radius: f64,
    side: ObstacleSide,
}

impl RigidSphere {
    /// A sphere of `radius` about `center`, with the contactor on `side`.
    ///
    /// # Errors
    /// [`SolverError::NonFinite`]; [`SolverError::InvalidSetting`] for a radius that is not
    /// finite and positive.
    pub fn new(center: [f64; 3], radius_: f64, side: ObstacleSide) -> Result<Self, SolverError> {
        Ok(Self {
            center: finite_point("sphere center", center)?,
            radius: radius("sphere radius", radius_)?,
            side,
        })
    }
}

impl Obstacle<3> for RigidSphere {
    fn project(&self, p: [f64; 3]) -> Option<ObstaclePoint<3>> {
        let d = sub(p, self.center);
        let len = dot(d, d).sqrt();
        if len == 0.0 {
            return None; // the centre: every direction is as close
        }
        let out = d.map(|v| v / len);
        let (normal, gap) = self.side.normal_and_gap(out, len, self.radius);
        Some(ObstaclePoint {
            point: core::array::from_fn(|a| self.center[a] + self.radius * out[a]),
            normal,
            gap,
        })
    }
}

/// An infinite rigid circular cylinder.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RigidCylinder {
    point: [f64; 3],
    axis: [f64; 3],
    radius: f64,
    side: ObstacleSide,
}

impl RigidCylinder {
    /// The cylinder of `radius` about the line through `point` along `axis`, with the
    /// contactor on `side`.
    ///
    /// # Errors
    /// [`SolverError::NonFinite`]; [`SolverError::InvalidGeometry`] for a zero axis;
    /// [`SolverError::InvalidSetting`] for a bad radius.
    pub fn new(
        point: [f64; 3],
        axis: [f64; 3],
        radius_: f64,
        side: ObstacleSide,
    ) -> Result<Self, SolverError> {
        Ok(Self {
            point: finite_point("cylinder point", point)?,
            axis: unit("cylinder axis", axis)?,
            radius: radius("cylinder radius", radius_)?,
            side,
        })
    }
}

impl Obstacle<3> for RigidCylinder {
    fn project(&self, p: [f64; 3]) -> Option<ObstaclePoint<3>> {
        let d = sub(p, self.point);
        let along = dot(d, self.axis);
        let radial: [f64; 3] = core::array::from_fn(|a| d[a] - along * self.axis[a]);
        let len = dot(radial, radial).sqrt();
        if len == 0.0 {
            return None; // on the axis
        }
        let out = radial.map(|v| v / len);
        let (normal, gap) = self.side.normal_and_gap(out, len, self.radius);
        Some(ObstaclePoint {
            point: core::array::from_fn(|a| {
                self.point[a] + along * self.axis[a] + self.radius * out[a]
            }),
            normal,
            gap,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tangent_frame_is_orthonormal_and_right_handed_works() {
        for n in [
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 0.0],
            [0.0, -1.0, 0.0],
            [0.6, 0.0, 0.8],
            [-0.48, 0.6, 0.64],
        ] {
            let (t1, t2) = tangent_frame(n);
            assert!(dot(t1, n).abs() < 1e-15 && dot(t2, n).abs() < 1e-15);
            assert!((dot(t1, t1) - 1.0).abs() < 1e-15 && (dot(t2, t2) - 1.0).abs() < 1e-15);
            let c = cross(t1, t2);
            assert!((dot(c, n) - 1.0).abs() < 1e-14, "(n, t1, t2) right-handed");
        }
        assert_eq!(
            tangent_frame([0.0, 0.0, 1.0]),
            ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0])
        );
    }

    #[test]
    fn obstacles_project_works() {
        let s = RigidSphere::new([0.0, 0.0, 2.0], 1.0, ObstacleSide::Outside).unwrap();
        let p = s.project([0.0, 0.0, 0.5]).unwrap();
        assert_eq!(p.point, [0.0, 0.0, 1.0]);
        assert_eq!(p.normal, [0.0, 0.0, -1.0]);
        assert!((p.gap - 0.5).abs() < 1e-15);
        let c = RigidCylinder::new([0.0; 3], [0.0, 0.0, 2.0], 1.0, ObstacleSide::Inside).unwrap();
        let p = c.project([0.5, 0.0, 7.0]).unwrap();
        assert_eq!(p.point, [1.0, 0.0, 7.0]);
        assert_eq!(p.normal, [-1.0, 0.0, 0.0]);
        assert!((p.gap - 0.5).abs() < 1e-15);
        assert!(RigidPlane::new([0.0; 3], [0.0; 3]).is_err());
        assert!(RigidSphere::new([0.0; 3], -1.0, ObstacleSide::Outside).is_err());
        assert!(
            RigidCylinder::new(
                [f64::NAN, 0.0, 0.0],
                [0.0, 0.0, 1.0],
                1.0,
                ObstacleSide::Outside
            )
            .is_err()
        );
    }
}
