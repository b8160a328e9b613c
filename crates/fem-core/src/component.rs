//! The two displacement components of a 2D node.

use core::fmt;

/// A displacement component: `X` (`u_x`, or `u_r` in axisymmetry) or `Y` (`u_y`, or `u_z`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Component {
    /// First component (`x` or `r`).
    X = 0,
    /// Second component (`y` or `z`).
    Y = 1,
}

impl fmt::Display for Component {
    /// `x` or `y` (the first or second component, also in axisymmetry where they are `r`
    /// and `z`).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Component::X => "x",
            Component::Y => "y",
        })
    }
}
