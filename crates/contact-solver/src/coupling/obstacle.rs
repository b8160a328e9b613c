//! Rigid obstacles (seed 5.5): the [`Obstacle`] trait, one for 2D and 3D, with the analytic
//! LINE segment and circular ARC of the plane here and the plane, sphere and cylinder of space
//! in [`solid::obstacle`](super::solid::obstacle).
//!
//! An obstacle answers one question: the closest point of its surface to a point `p`, with the
//! unit normal `n` pointing *towards the contactor's side* and the signed gap
//! `g = (p − point)·n` (positive outside the obstacle). In 2D the tangent of the contact frame
//! is `t = (n_y, −n_x)`, so that walking a LINE from `a` to `b` goes along `t` with the
//! contactor on the left (`docs/theory.md` §13); in 3D the tangents follow
//! [`tangent_frame`](super::solid::tangent_frame).

use crate::error::SolverError;
use std::f64::consts::TAU;
use std::fmt::Debug;

/// The closest point of an obstacle to a query point, in `D` dimensions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ObstaclePoint<const D: usize = 2> {
    /// The closest point on the obstacle's surface.
    pub point: [f64; D],
    /// Unit normal at `point`, towards the contactor's side.
    pub normal: [f64; D],
    /// Signed gap `(p − point)·normal`: positive when `p` is outside the obstacle.
    pub gap: f64,
}

impl ObstaclePoint<2> {
    /// The frame's tangent `t = (n_y, −n_x)`.
    #[inline]
    pub fn tangent(&self) -> [f64; 2] {
        [self.normal[1], -self.normal[0]]
    }
}

/// A rigid obstacle in `D` dimensions (2 unless said): the closest point of its surface to a
/// point.
///
/// Implement it for your own shape; it must return a unit normal and a gap consistent with
/// it, and `None` for points whose orthogonal projection falls outside the surface (they are
/// not contact candidates).
///
/// # Examples
/// ```
/// use contact_solver::coupling::obstacle::{Obstacle, RigidLine};
/// use contact_solver::coupling::solid::RigidPlane;
/// let ground = RigidLine::new([0.0, 0.0], [10.0, 0.0])?; // contactor above (left of a → b)
/// let p = ground.project([2.0, 0.5]).unwrap();
/// assert_eq!((p.point, p.normal, p.gap), ([2.0, 0.0], [0.0, 1.0], 0.5));
/// assert!(ground.project([11.0, 0.5]).is_none()); // beyond the end b
/// let floor = RigidPlane::new([0.0, 0.0, 0.0], [0.0, 0.0, 1.0])?; // an `Obstacle<3>`
/// let p = floor.project([2.0, 1.0, 0.5]).unwrap();
/// assert_eq!((p.point, p.gap), ([2.0, 1.0, 0.0], 0.5));
/// # Ok::<(), contact_solver::SolverError>(())
/// ```
pub trait Obstacle<const D: usize = 2>: Debug + Send + Sync {
    /// The closest point to `p`, or `None` if `p` has no orthogonal projection on the surface.
    fn project(&self, p: [f64; D]) -> Option<ObstaclePoint<D>>;

    /// A length of the surface (a LINE's length, an ARC's length), if it has one: a simulation
    /// refuses a target that is degenerate against the body it faces (see
    /// [`check_rigid_targets`](crate::coupling::zone::check_rigid_targets)). `None` (the
    /// default, and every unbounded surface) skips that check.
    fn extent(&self) -> Option<f64> {
        None
    }
}

/// `p` if every coordinate is finite, else [`SolverError::NonFinite`] naming `what`.
pub(crate) fn finite_point<const D: usize>(
    what: &'static str,
    p: [f64; D],
) -> Result<[f64; D], SolverError> {
    for (index, &value) in p.iter().enumerate() {
        if !value.is_finite() {
            return Err(SolverError::NonFinite { what, index, value });
        }
    }
    Ok(p)
}

/// Relative tolerance on the ends of a LINE and an ARC: a point projecting exactly on an end
/// (up to rounding) is a candidate.
const END_TOL: f64 = 1e-12;

/// A rigid straight segment from `a` to `b`; the contactor lies on its left (normal
/// `n = (−t_y, t_x)`, `t = (b − a)/|b − a|`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RigidLine {
    a: [f64; 2],
    t: [f64; 2],
    length: f64,
}

impl RigidLine {
    /// The segment from `a` to `b`.
    ///
    /// # Errors
    /// [`SolverError::NonFinite`] for a non-finite coordinate;
    /// [`SolverError::InvalidGeometry`] if `a == b` or the length overflows `f64`.
    pub fn new(a: [f64; 2], b: [f64; 2]) -> Result<Self, SolverError> {
        let a = finite_point("LINE start", a)?;
        let b = finite_point("LINE end", b)?;
        let d = [b[0] - a[0], b[1] - a[1]];
        let length = d[0].hypot(d[1]);
        if !length.is_finite() {
            return Err(SolverError::InvalidGeometry(format!(
                "LINE from {a:?} to {b:?}: its length overflows (larger than {:e})",
                f64::MAX
            )));
        }
        if length == 0.0 {
            return Err(SolverError::InvalidGeometry(format!(
                "LINE from {a:?} to {b:?} has zero length"
            )));
        }
        Ok(Self {
            a,
            t: [d[0] / length, d[1] / length],
            length,
        })
    }

    /// The start point `a`.
    pub fn start(&self) -> [f64; 2] {
        self.a
    }

    /// The end point `b`.
    pub fn end(&self) -> [f64; 2] {
        [
            self.a[0] + self.length * self.t[0],
            self.a[1] + self.length * self.t[1],
        ]
    }
}

impl Obstacle for RigidLine {
    fn extent(&self) -> Option<f64> {
        Some(self.length)
    }

    fn project(&self, p: [f64; 2]) -> Option<ObstaclePoint> {
        let d = [p[0] - self.a[0], p[1] - self.a[1]];
        let s = d[0] * self.t[0] + d[1] * self.t[1];
        let slack = END_TOL * self.length;
        if !(s >= -slack && s <= self.length + slack) {
            return None;
        }
        let s = s.clamp(0.0, self.length);
        let normal = [-self.t[1], self.t[0]];
        Some(ObstaclePoint {
            point: [self.a[0] + s * self.t[0], self.a[1] + s * self.t[1]],
            normal,
            gap: d[0] * normal[0] + d[1] * normal[1],
        })
    }
}

/// Which side of a curved rigid obstacle the contactor is on: of a 2D [`RigidArc`], of a 3D
/// [`RigidSphere`](super::solid::RigidSphere) or [`RigidCylinder`](super::solid::RigidCylinder).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ObstacleSide {
    /// The contactor is outside the circle, sphere or cylinder (a rigid cylinder, ball or rod
    /// pressed into a body); the normal points away from the centre (or the axis).
    Outside,
    /// The contactor is inside the circle, sphere or cylinder (a body in a rigid bore or
    /// cavity); the normal points to the centre (or the axis).
    Inside,
}

impl ObstacleSide {
    /// The normal and the gap at a point at distance `dist > 0` from the centre (or the axis)
    /// along the unit vector `out`, for a surface of `radius`.
    #[inline]
    pub(crate) fn normal_and_gap<const D: usize>(
        self,
        out: [f64; D],
        dist: f64,
        radius: f64,
    ) -> ([f64; D], f64) {
        match self {
            ObstacleSide::Outside => (out, dist - radius),
            ObstacleSide::Inside => (out.map(|v| -v), radius - dist),
        }
    }
}

/// The side of a 2D [`RigidArc`]: [`ObstacleSide`] (the name the 2D API has always used).
pub type ArcSide = ObstacleSide;

/// A rigid circular arc: centre, radius, and the angles it spans counter-clockwise from
/// `start_angle` over `sweep` (radians, `0 < sweep ≤ 2π`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RigidArc {
    center: [f64; 2],
    radius: f64,
    start_angle: f64,
    sweep: f64,
    side: ObstacleSide,
}

impl RigidArc {
    /// Builds the arc.
    ///
    /// # Errors
    /// [`SolverError::NonFinite`] for a non-finite input; [`SolverError::InvalidGeometry`] if
    /// `radius ≤ 0` or `sweep ∉ (0, 2π]`.
    pub fn new(
        center: [f64; 2],
        radius: f64,
        start_angle: f64,
        sweep: f64,
        side: ObstacleSide,
    ) -> Result<Self, SolverError> {
        let center = finite_point("ARC centre", center)?;
        for (what, value) in [
            ("ARC radius", radius),
            ("ARC angle", start_angle),
            ("ARC sweep", sweep),
        ] {
            if !value.is_finite() {
                return Err(SolverError::NonFinite {
                    what,
                    index: 0,
                    value,
                });
            }
        }
        if radius <= 0.0 {
            return Err(SolverError::InvalidGeometry(format!(
                "ARC radius {radius} must be positive"
            )));
        }
        if !(sweep > 0.0 && sweep <= TAU * (1.0 + END_TOL)) {
            return Err(SolverError::InvalidGeometry(format!(
                "ARC sweep {sweep} must be in (0, 2π]"
            )));
        }
        Ok(Self {
            center,
            radius,
            start_angle: start_angle.rem_euclid(TAU),
            sweep: sweep.min(TAU),
            side,
        })
    }

    /// The full circle.
    ///
    /// # Errors
    /// As for [`RigidArc::new`].
    pub fn circle(center: [f64; 2], radius: f64, side: ObstacleSide) -> Result<Self, SolverError> {
        Self::new(center, radius, 0.0, TAU, side)
    }

    /// The centre.
    pub fn center(&self) -> [f64; 2] {
        self.center
    }

    /// The radius.
    pub fn radius(&self) -> f64 {
        self.radius
    }
}

impl Obstacle for RigidArc {
    fn extent(&self) -> Option<f64> {
        Some(self.radius * self.sweep.abs())
    }

    fn project(&self, p: [f64; 2]) -> Option<ObstaclePoint> {
        let d = [p[0] - self.center[0], p[1] - self.center[1]];
        let dist = d[0].hypot(d[1]);
        if dist == 0.0 {
            return None; // the centre: every point of the circle is closest
        }
        if self.sweep < TAU {
            let phi = (d[1].atan2(d[0]) - self.start_angle).rem_euclid(TAU);
            let slack = END_TOL * TAU;
            // past the end, or just before the start (phi wrapped to ~2π)
            if phi > self.sweep + slack && phi < TAU - slack {
                return None;
            }
        }
        let e = [d[0] / dist, d[1] / dist];
        let point = [
            self.center[0] + self.radius * e[0],
            self.center[1] + self.radius * e[1],
        ];
        let (normal, gap) = self.side.normal_and_gap(e, dist, self.radius);
        Some(ObstaclePoint { point, normal, gap })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use std::f64::consts::{FRAC_PI_2, PI};

    #[test]
    fn line_projects_with_left_normal_and_signed_gap() {
        let l = RigidLine::new([1.0, 1.0], [1.0, 3.0]).unwrap(); // going up: left is −x
        let p = l.project([0.5, 2.0]).unwrap();
        assert_eq!(p.normal, [-1.0, 0.0]);
        assert_eq!(p.point, [1.0, 2.0]);
        assert_eq!(p.gap, 0.5);
        assert_eq!(p.tangent(), [0.0, 1.0]);
        assert_eq!(l.project([1.5, 2.0]).unwrap().gap, -0.5); // penetrated
        assert!(l.project([0.5, 3.5]).is_none());
        // exactly on the ends
        assert_eq!(l.project([0.0, 3.0]).unwrap().point, [1.0, 3.0]);
        assert_eq!(l.project([0.0, 1.0]).unwrap().point, [1.0, 1.0]);
        assert_eq!(l.end(), [1.0, 3.0]);
    }

    #[test]
    fn arc_outside_and_inside() {
        let c = RigidArc::new([0.0, 0.0], 2.0, 0.0, PI, ObstacleSide::Outside).unwrap();
        let p = c.project([0.0, 3.0]).unwrap();
        assert_relative_eq!(p.point[1], 2.0);
        assert_relative_eq!(p.normal[1], 1.0);
        assert_relative_eq!(p.gap, 1.0);
        assert!(c.project([0.0, -3.0]).is_none()); // lower half not in the arc
        // endpoints (angle 0 and π) are candidates
        assert!(c.project([3.0, 0.0]).is_some());
        assert!(c.project([-3.0, 0.0]).is_some());
        assert!(c.project([3.0, -1e-3]).is_none());
        let i = RigidArc::circle([1.0, 1.0], 2.0, ObstacleSide::Inside).unwrap();
        let p = i.project([1.0, 2.5]).unwrap();
        assert_relative_eq!(p.gap, 0.5);
        assert_relative_eq!(p.normal[1], -1.0);
        assert!(i.project([1.0, 1.0]).is_none());
        // an arc whose span wraps through angle 0
        let w = RigidArc::new([0.0, 0.0], 1.0, -FRAC_PI_2, PI, ObstacleSide::Outside).unwrap();
        assert!(w.project([2.0, -0.5]).is_some());
        assert!(w.project([-2.0, 0.1]).is_none());
    }

    #[test]
    fn bad_geometry_is_an_error() {
        assert!(matches!(
            RigidLine::new([1.0, 1.0], [1.0, 1.0]),
            Err(SolverError::InvalidGeometry(_))
        ));
        assert!(matches!(
            RigidLine::new([f64::NAN, 1.0], [1.0, 1.0]),
            Err(SolverError::NonFinite { .. })
        ));
        match RigidLine::new([-1e308, 0.0], [1e308, 0.0]) {
            Err(SolverError::InvalidGeometry(m)) => assert!(m.contains("overflows"), "{m}"),
            other => panic!("{other:?}"),
        }
        assert!(RigidArc::new([0.0, 0.0], -1.0, 0.0, 1.0, ObstacleSide::Outside).is_err());
        assert!(RigidArc::new([0.0, 0.0], 1.0, 0.0, 7.0, ObstacleSide::Outside).is_err());
        assert!(RigidArc::new([0.0, 0.0], 1.0, 0.0, 0.0, ObstacleSide::Outside).is_err());
    }
}
