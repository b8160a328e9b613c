//! Vectors of the local contact frame `(n, t)`.
//!
//! See the [crate-level conventions](crate#sign-conventions) for signs.

use core::ops::{Add, Mul, Neg, Sub};
use nalgebra::SVector;

/// A vector in the local contact frame: normal component `n` and tangential part `t`.
///
/// Used for the reaction `r` (force on the contactor, N or N/mm² depending on the model),
/// the jump `u` and its increment `Δu` or rate `u̇` (length or length per time), and the
/// augmented reaction `τ` of the Uzawa prediction (seed eq. 5.26a). Named fields keep the
/// normal and tangential components from being swapped.
///
/// `DT` is the dimension of the tangent plane: `1` for 2D problems ([`LocalVec2`]), `2` for
/// 3D problems ([`LocalVec3`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LocalVec<const DT: usize> {
    /// Normal component (along the obstacle's outward normal `n`).
    pub n: f64,
    /// Tangential components (along the tangent basis of the frame).
    pub t: SVector<f64, DT>,
}

/// Local vector of a 2D problem: one normal and one tangential component.
pub type LocalVec2 = LocalVec<1>;
/// Local vector of a 3D problem: one normal and two tangential components.
pub type LocalVec3 = LocalVec<2>;

impl<const DT: usize> LocalVec<DT> {
    /// Builds a local vector from its normal component and tangential part.
    #[inline]
    pub fn new(n: f64, t: SVector<f64, DT>) -> Self {
        Self { n, t }
    }

    /// The zero vector.
    #[inline]
    pub fn zeros() -> Self {
        Self {
            n: 0.0,
            t: SVector::zeros(),
        }
    }

    /// Euclidean norm of the tangential part, `‖t‖` (exact `|t|` when `DT = 1`).
    #[inline]
    pub fn t_norm(&self) -> f64 {
        if DT == 1 {
            self.t[0].abs()
        } else {
            self.t.norm()
        }
    }

    /// Euclidean norm of the whole vector.
    #[inline]
    pub fn norm(&self) -> f64 {
        (self.n * self.n + self.t.norm_squared()).sqrt()
    }

    /// Scalar product `a · b = a_n b_n + a_t · b_t`.
    #[inline]
    pub fn dot(&self, other: &Self) -> f64 {
        self.n * other.n + self.t.dot(&other.t)
    }

    /// `true` when every component is finite (neither NaN nor infinite).
    #[inline]
    pub fn is_finite(&self) -> bool {
        self.n.is_finite() && self.t.iter().all(|x| x.is_finite())
    }
}

impl LocalVec<1> {
    /// Builds a 2D local vector `(n, t)`.
    #[inline]
    pub fn planar(n: f64, t: f64) -> Self {
        Self {
            n,
            t: SVector::<f64, 1>::new(t),
        }
    }
}

impl LocalVec<2> {
    /// Builds a 3D local vector `(n, t1, t2)`.
    #[inline]
    pub fn spatial(n: f64, t1: f64, t2: f64) -> Self {
        Self {
            n,
            t: SVector::<f64, 2>::new(t1, t2),
        }
    }
}

impl<const DT: usize> Add for LocalVec<DT> {
    type Output = Self;
    #[inline]
    fn add(self, rhs: Self) -> Self {
        Self {
            n: self.n + rhs.n,
            t: self.t + rhs.t,
        }
    }
}

impl<const DT: usize> Sub for LocalVec<DT> {
    type Output = Self;
    #[inline]
    fn sub(self, rhs: Self) -> Self {
        Self {
            n: self.n - rhs.n,
            t: self.t - rhs.t,
        }
    }
}

impl<const DT: usize> Neg for LocalVec<DT> {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        Self {
            n: -self.n,
            t: -self.t,
        }
    }
}

impl<const DT: usize> Mul<f64> for LocalVec<DT> {
    type Output = Self;
    #[inline]
    fn mul(self, s: f64) -> Self {
        Self {
            n: self.n * s,
            t: self.t * s,
        }
    }
}

impl<const DT: usize> Default for LocalVec<DT> {
    fn default() -> Self {
        Self::zeros()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arithmetic_works() {
        let a = LocalVec::planar(1.0, -2.0);
        let b = LocalVec::planar(0.5, 4.0);
        assert_eq!(a + b, LocalVec::planar(1.5, 2.0));
        assert_eq!(a - b, LocalVec::planar(0.5, -6.0));
        assert_eq!(-a, LocalVec::planar(-1.0, 2.0));
        assert_eq!(a * 2.0, LocalVec::planar(2.0, -4.0));
        assert_eq!(a.dot(&b), 0.5 - 8.0);
        assert_eq!(a.t_norm(), 2.0);
        assert_eq!(LocalVec3::spatial(0.0, 3.0, 4.0).t_norm(), 5.0);
        assert_eq!(LocalVec3::spatial(12.0, 3.0, 4.0).norm(), 13.0);
        assert_eq!(LocalVec3::default(), LocalVec3::zeros());
    }

    #[test]
    fn is_finite_detects_nan_and_infinity() {
        assert!(LocalVec::planar(1.0, 2.0).is_finite());
        assert!(!LocalVec::planar(f64::NAN, 2.0).is_finite());
        assert!(!LocalVec::spatial(1.0, 2.0, f64::INFINITY).is_finite());
    }
}
