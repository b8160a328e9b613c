//! The dimension of a body as a type, so that one generic code path serves 2D and 3D (the
//! pattern of nalgebra's `Const<D>`): [`Dim<2>`] ([`Plane`]: plane strain, plane stress and
//! axisymmetry) and [`Dim<3>`] ([`Solid`]).
//!
//! Generic code is written over `const D: usize` with the bound `Dim<D>: Space`, so that a
//! point stays a plain `[f64; D]` and what differs between the dimensions (the Voigt stress
//! type, …) comes from the [`Space`] implementation. `Space` is sealed: the two dimensions
//! are the ones the library's geometry (obstacles, frames, element kernels) is written for.
//!
//! # Examples
//! ```
//! use fem_core::space::{Dim, Space};
//!
//! fn voigt<const D: usize>() -> usize
//! where
//!     Dim<D>: Space,
//! {
//!     <Dim<D> as Space>::VOIGT
//! }
//! assert_eq!((voigt::<2>(), voigt::<3>()), (4, 6));
//! ```

use crate::idealization::Idealization;
use std::fmt::Debug;

/// The dimension `D` as a type (see the module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Dim<const D: usize>;

/// Bodies in the plane: plane strain, plane stress or axisymmetry (`(r, z)`).
pub type Plane = Dim<2>;

/// Bodies in space.
pub type Solid = Dim<3>;

pub(crate) mod sealed {
    /// Implemented by the crate's dimensions only.
    pub trait Sealed {}
    impl Sealed for super::Dim<2> {}
    impl Sealed for super::Dim<3> {}
}

/// What differs between the two dimensions a body may have; implemented for [`Dim<2>`] and
/// [`Dim<3>`] only (sealed).
pub trait Space:
    sealed::Sealed + Copy + Debug + Default + PartialEq + Send + Sync + 'static
{
    /// The number of coordinates of a point (and of displacement components of a node).
    const D: usize;
    /// The number of Voigt components of a stress or strain.
    const VOIGT: usize;
    /// `"2D"` or `"3D"`, for messages.
    const NAME: &'static str;
    /// What a facet of an element (a side in 2D, a face in 3D) is called in messages:
    /// `"edge"` or `"face"`.
    const FACET: &'static str;
    /// A stress or strain in Voigt form: `(xx, yy, xy, zz)` in the plane (`(rr, zz, rz, θθ)`
    /// in axisymmetry), `(xx, yy, zz, xy, yz, zx)` in 3D.
    type Stress: Copy
        + Debug
        + Default
        + PartialEq
        + Send
        + Sync
        + AsRef<[f64]>
        + AsMut<[f64]>
        + 'static;
    /// The kinematic setting an element's kernels take: the [`Idealization`] in the plane
    /// (plane strain, plane stress with its thickness, axisymmetry with its `2πr` weight and
    /// hoop strain), `()` in 3D.
    type Setting: Copy + Debug + PartialEq + Send + Sync + 'static;

    /// The plane idealisation a setting stands for; `None` in 3D.
    fn idealization(setting: &Self::Setting) -> Option<&Idealization>;
}

impl Space for Dim<2> {
    const D: usize = 2;
    const VOIGT: usize = 4;
    const NAME: &'static str = "2D";
    const FACET: &'static str = "edge";
    type Stress = [f64; 4];
    type Setting = Idealization;

    #[inline]
    fn idealization(setting: &Idealization) -> Option<&Idealization> {
        Some(setting)
    }
}

impl Space for Dim<3> {
    const D: usize = 3;
    const VOIGT: usize = 6;
    const NAME: &'static str = "3D";
    const FACET: &'static str = "face";
    type Stress = [f64; 6];
    type Setting = ();

    #[inline]
    fn idealization(_: &()) -> Option<&Idealization> {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check<const D: usize>()
    where
        Dim<D>: Space,
    {
        assert_eq!(<Dim<D> as Space>::D, D);
        let s = <Dim<D> as Space>::Stress::default();
        assert_eq!(s.as_ref().len(), <Dim<D> as Space>::VOIGT);
    }

    #[test]
    fn the_constants_match_the_dimension_works() {
        check::<2>();
        check::<3>();
        assert_eq!((Plane::NAME, Solid::NAME), ("2D", "3D"));
    }
}
