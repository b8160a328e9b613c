//! The displacement components of a node: `X`, `Y` in 2D, and `Z` in 3D.

use core::fmt;

/// A displacement component: `X` (`u_x`, or `u_r` in axisymmetry), `Y` (`u_y`, or `u_z` in
/// axisymmetry) or, in 3D only, `Z` (`u_z`). A 2D model refuses `Z`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Component {
    /// First component (`x` or `r`).
    X = 0,
    /// Second component (`y` or `z`).
    Y = 1,
    /// Third component (`z`, 3D only).
    Z = 2,
}

impl Component {
    /// The components of a node in dimension `D` (2 or 3), in order.
    ///
    /// # Panics
    /// If `D` is neither 2 nor 3 (a compile-time constant of the caller).
    #[inline]
    #[track_caller]
    pub fn all<const D: usize>() -> [Component; D] {
        assert!(D == 2 || D == 3, "dimension 2 or 3");
        core::array::from_fn(|c| [Component::X, Component::Y, Component::Z][c])
    }
}

impl fmt::Display for Component {
    /// `x`, `y` or `z` (the first, second or third component; also `x` and `y` in
    /// axisymmetry, where they are `r` and `z`).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Component::X => "x",
            Component::Y => "y",
            Component::Z => "z",
        })
    }
}
