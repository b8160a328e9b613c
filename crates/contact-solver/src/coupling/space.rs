//! What the contact geometry needs to know of the dimension: [`ContactSpace`], implemented for
//! [`Dim<2>`] and [`Dim<3>`] (sealed, as [`Space`] is), so that the obstacles, the zones, the
//! candidates and recognition ([`zone`](super::zone)) are written once over `const D: usize`.
//!
//! What stays per dimension is geometry (frame tangents, the surface of a deformable target,
//! default tributary areas) and the measured or inherited constants, each kept as that
//! dimension had it so that no number moves.
//!
//! Generic code is written with the bound `Dim<D>: ContactSpace<D>`:
//!
//! ```
//! use contact_solver::coupling::space::ContactSpace;
//! use fem_core::Dim;
//!
//! fn tangents<const D: usize>(n: [f64; D]) -> usize
//! where
//!     Dim<D>: ContactSpace<D>,
//! {
//!     let frame = <Dim<D> as ContactSpace<D>>::frame(n);
//!     frame.len() - 1
//! }
//! assert_eq!(tangents([0.0, 1.0]), 1);
//! assert_eq!(tangents([0.0, 0.0, 1.0]), 2);
//! ```

use super::solid::{TriSurface, tangent_frame};
use super::zone::{Polyline, TargetSurface, lumped_areas};
use crate::error::SolverError;
use contact_laws::LocalVec;
use fem_core::{Dim, Space, Structure};
use std::fmt::Debug;

mod sealed {
    pub trait Sealed {}
    impl Sealed for fem_core::Dim<2> {}
    impl Sealed for fem_core::Dim<3> {}
}

/// What differs between 2D and 3D contact (module docs); implemented for [`Dim<2>`] and
/// [`Dim<3>`] only (sealed).
pub trait ContactSpace<const D: usize>: Space + sealed::Sealed {
    /// The number of tangential directions of a contact frame, `D − 1`.
    const TANGENTS: usize;
    /// The coefficients of an `H` row at or below this size are dropped, and the row is merged
    /// to one entry per dof: `0` in 2D (one entry per node and component), `1e-14` in 3D (a
    /// unit direction's `cos 90°`, a shape value at a vertex: so that a direction held on both
    /// sides has an empty row).
    const ROUND_OFF: f64;
    /// A candidate is held along its normal when the squared norm of its normal `H` row is
    /// below this (or the row is empty): `0` in 2D (the row must be empty), `1e-24` in 3D.
    const HELD: f64;
    /// The local vector of one contact, `(n, t)`: [`LocalVec<1>`] or [`LocalVec<2>`].
    type Local: Copy + Debug + PartialEq + Send + Sync + 'static;
    /// The surface of a deformable target: [`Polyline`] in 2D, [`TriSurface`] in 3D.
    type Surface: TargetSurface<D>;
    /// A tangential quantity of one contact (`u_t`, a slip): `f64` in 2D, `[f64; 2]` in 3D.
    type Tangential: Copy + Debug + PartialEq + Send + Sync + 'static;
    /// The tangents of a contact frame: `[f64; 2]` (one tangent) in 2D, `[[f64; 3]; 2]` in 3D.
    type Tangents: Copy + Debug + PartialEq + Send + Sync + 'static;
    /// An inactive candidate outside the reduced problem penetrates when its gap is below
    /// `−PENETRATION_TOL × extent` (`extent`: the largest side of the contactor nodes' box):
    /// `0` in 2D (any negative gap), `1e-9` in 3D (round-off of the nodes' positions on curved
    /// faces).
    const PENETRATION_TOL: f64;
    /// Whether a tangential direction that cannot move relative to the target (its `H` row is
    /// empty: held on both sides, e.g. across a symmetry plane) is decoupled like a
    /// frictionless one (`W_tt = W_nn`, `r_t = 0`): `false` in 2D (its column is solved),
    /// `true` in 3D.
    const DECOUPLE_HELD_TANGENTS: bool;
    /// The default [`FlexibilityMode::Auto`](super::simulation::FlexibilityMode::Auto) limit
    /// of a dense `F*`, measured per dimension (`docs/benchmarks.md`): 500 contacts in 2D,
    /// 3000 in 3D.
    const DENSE_LIMIT: usize;
    /// The largest active set that `Auto` solves with a dense `F*` when its active-set
    /// iteration did not converge (matrix-free beyond): 8000 contacts in 2D (2 GiB), 3000 in
    /// 3D (648 MB).
    const FALLBACK_DENSE_LIMIT: usize;
    /// The default right-hand sides per solve when building `F*`
    /// ([`SimulationSettings::columns_per_solve`](super::simulation::SimulationSettings::columns_per_solve)):
    /// 64 in 2D, 96 in 3D.
    const COLUMNS_PER_SOLVE: usize;
    /// The default cap on the penetration-check passes of a step
    /// ([`SimulationTuning::max_detection_passes`](super::simulation::SimulationTuning::max_detection_passes)):
    /// 5 in 2D, 20 in 3D.
    const MAX_DETECTION_PASSES: usize;
    /// Whether the primal active-set path frees the structure's factor of `K` while it holds
    /// its own of the constrained stiffness, and refactors `K` after
    /// ([`Structure::release_factor`]): one factor at a time, for one more factorisation of
    /// `K` a step and none of the active set's factor kept from step to step. `true` in 3D,
    /// where the two factors dominate the peak memory (the 3D Hertz: 304 MB against the
    /// dense path's 204 MB with both, `docs/benchmarks.md`, issue 38); `false` in 2D, whose
    /// factors are small and whose many-step scenes reuse the active set's factor.
    const ONE_FACTOR: bool;
    /// Whether [`FlexibilityMode::Auto`](super::simulation::FlexibilityMode::Auto) weighs the
    /// active contacts against the model's DOF below its `dense_limit` (the dense columns'
    /// cost against the active set's factorisations, `simulation::choice`'s rule): `true` in
    /// 3D, where it was measured (issue 38); `false` in 2D, whose limit of 500 contacts
    /// already sits at the crossover.
    const DENSE_BY_DOFS: bool;
    /// The default depth of the Anderson memory of matrix-free steps
    /// ([`SimulationTuning::matrix_free_window`](super::simulation::SimulationTuning::matrix_free_window)):
    /// 20 in both dimensions, measured against the momentum iteration (0) and a depth of 10
    /// (`docs/benchmarks.md`, "Matrix-free preconditioned (issue 38)": 7–20× fewer products
    /// in 2D, 1.6–16× in 3D; 20 ahead of 10 or within one product).
    const MATRIX_FREE_WINDOW: usize;

    /// The typed local vector of `D` consecutive components `[n, t…]`.
    fn local_of(x: &[f64]) -> Self::Local;

    /// The tangential part of `[n, t…]` (the components after the first).
    fn tangential_of(x: &[f64]) -> Self::Tangential;

    /// The tangents of a frame `[n, t…]`.
    fn tangents_of(frame: [[f64; D]; D]) -> Self::Tangents;

    /// The frame `[n, t…]` of a normal and its tangents (the inverse of
    /// [`tangents_of`](Self::tangents_of)).
    fn frame_of(normal: [f64; D], tangents: &Self::Tangents) -> [[f64; D]; D];

    /// The components `[n, t…]` of a typed local vector.
    fn components(l: &Self::Local) -> [f64; D];

    /// The contact frame `[n, t…]` of the unit normal `n`: `t = (n_y, −n_x)` in 2D,
    /// [`tangent_frame`] in 3D.
    fn frame(normal: [f64; D]) -> [[f64; D]; D];

    /// The local components `[n, t…]` as the typed local vector.
    fn local_vec(x: [f64; D]) -> Self::Local;

    /// The tributary areas of a zone's contactor nodes when the zone gives none: lumped along
    /// the nodes taken as a polyline in 2D ([`lumped_areas`]), 1 per node in 3D.
    fn default_areas<S: Structure<D> + ?Sized>(s: &S, nodes: &[usize]) -> Vec<f64>;

    /// The normals of node pairs taken from the target nodes themselves
    /// ([`PairNormals::FromTargets`](super::zone::PairNormals::FromTargets)): in 2D the
    /// target nodes as a polyline in the given order, contactor on its left (at pair `k`, the
    /// chord from target `k − 1` to `k + 1`).
    ///
    /// # Errors
    /// [`SolverError::InvalidGeometry`] naming the zone: a single pair, a degenerate chord, or
    /// in 3D always (a list of nodes has no normal there: give `Fixed`, `PerPair` or
    /// `Surface` normals).
    fn normals_from_targets<S: Structure<D> + ?Sized>(
        s: &S,
        zone: &str,
        targets: &[usize],
    ) -> Result<Vec<[f64; D]>, SolverError>;
}

/// `a·b`, summed left to right.
#[inline]
pub(crate) fn dot<const D: usize>(a: [f64; D], b: [f64; D]) -> f64 {
    let mut s = a[0] * b[0];
    for k in 1..D {
        s += a[k] * b[k];
    }
    s
}

/// `a − b`.
#[inline]
pub(crate) fn sub<const D: usize>(a: [f64; D], b: [f64; D]) -> [f64; D] {
    core::array::from_fn(|k| a[k] - b[k])
}

/// `a × b`.
#[inline]
pub(crate) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `v / |v|`, or an error naming the zone for a zero or non-finite `v`.
pub(crate) fn unit<const D: usize>(zone: &str, v: [f64; D]) -> Result<[f64; D], SolverError> {
    let l = if D == 2 {
        v[0].hypot(v[1])
    } else {
        dot(v, v).sqrt()
    };
    if !(l > 0.0 && l.is_finite()) {
        return Err(SolverError::InvalidGeometry(format!(
            "zone `{zone}`: cannot build a unit normal from {v:?}"
        )));
    }
    Ok(v.map(|x| x / l))
}

/// The left normal `(−t_y, t_x)` of a 2D direction.
#[inline]
pub(crate) fn left_normal(t: [f64; 2]) -> [f64; 2] {
    [-t[1], t[0]]
}

impl ContactSpace<2> for Dim<2> {
    const TANGENTS: usize = 1;
    const ROUND_OFF: f64 = 0.0;
    const HELD: f64 = 0.0;
    type Local = LocalVec<1>;
    type Surface = Polyline;
    type Tangential = f64;
    type Tangents = [f64; 2];
    const PENETRATION_TOL: f64 = 0.0;
    const DECOUPLE_HELD_TANGENTS: bool = false;
    const DENSE_LIMIT: usize = 500;
    const FALLBACK_DENSE_LIMIT: usize = 8000;
    const COLUMNS_PER_SOLVE: usize = 64;
    const MAX_DETECTION_PASSES: usize = 5;
    const ONE_FACTOR: bool = false;
    const DENSE_BY_DOFS: bool = false;
    const MATRIX_FREE_WINDOW: usize =
        crate::local::matrix_free_anderson::DEFAULT_MATRIX_FREE_WINDOW;

    #[inline]
    fn local_of(x: &[f64]) -> LocalVec<1> {
        LocalVec::planar(x[0], x[1])
    }

    #[inline]
    fn tangential_of(x: &[f64]) -> f64 {
        x[1]
    }

    #[inline]
    fn tangents_of(frame: [[f64; 2]; 2]) -> [f64; 2] {
        frame[1]
    }

    #[inline]
    fn frame_of(normal: [f64; 2], tangent: &[f64; 2]) -> [[f64; 2]; 2] {
        [normal, *tangent]
    }

    #[inline]
    fn components(l: &LocalVec<1>) -> [f64; 2] {
        [l.n, l.t[0]]
    }

    #[inline]
    fn frame(n: [f64; 2]) -> [[f64; 2]; 2] {
        [n, [n[1], -n[0]]]
    }

    #[inline]
    fn local_vec(x: [f64; 2]) -> LocalVec<1> {
        LocalVec::planar(x[0], x[1])
    }

    fn default_areas<S: Structure<2> + ?Sized>(s: &S, nodes: &[usize]) -> Vec<f64> {
        lumped_areas(s, nodes, false)
    }

    fn normals_from_targets<S: Structure<2> + ?Sized>(
        s: &S,
        zone: &str,
        nodes: &[usize],
    ) -> Result<Vec<[f64; 2]>, SolverError> {
        if nodes.len() < 2 {
            return Err(SolverError::InvalidGeometry(format!(
                "zone `{zone}`: a single pair needs an explicit normal"
            )));
        }
        (0..nodes.len())
            .map(|k| {
                let a = nodes[k.saturating_sub(1)];
                let b = nodes[(k + 1).min(nodes.len() - 1)];
                let t = unit(zone, sub(s.node_position(b), s.node_position(a)))?;
                Ok(left_normal(t))
            })
            .collect()
    }
}

impl ContactSpace<3> for Dim<3> {
    const TANGENTS: usize = 2;
    const ROUND_OFF: f64 = 1e-14;
    const HELD: f64 = 1e-24;
    type Local = LocalVec<2>;
    type Surface = TriSurface;
    type Tangential = [f64; 2];
    type Tangents = [[f64; 3]; 2];
    const PENETRATION_TOL: f64 = 1e-9;
    const DECOUPLE_HELD_TANGENTS: bool = true;
    const DENSE_LIMIT: usize = 3000;
    const FALLBACK_DENSE_LIMIT: usize = 3000;
    const COLUMNS_PER_SOLVE: usize = 96;
    const MAX_DETECTION_PASSES: usize = 20;
    const ONE_FACTOR: bool = true;
    const DENSE_BY_DOFS: bool = true;
    const MATRIX_FREE_WINDOW: usize =
        crate::local::matrix_free_anderson::DEFAULT_MATRIX_FREE_WINDOW;

    #[inline]
    fn local_of(x: &[f64]) -> LocalVec<2> {
        LocalVec::spatial(x[0], x[1], x[2])
    }

    #[inline]
    fn tangential_of(x: &[f64]) -> [f64; 2] {
        [x[1], x[2]]
    }

    #[inline]
    fn tangents_of(frame: [[f64; 3]; 3]) -> [[f64; 3]; 2] {
        [frame[1], frame[2]]
    }

    #[inline]
    fn frame_of(normal: [f64; 3], [t1, t2]: &[[f64; 3]; 2]) -> [[f64; 3]; 3] {
        [normal, *t1, *t2]
    }

    #[inline]
    fn components(l: &LocalVec<2>) -> [f64; 3] {
        [l.n, l.t[0], l.t[1]]
    }

    #[inline]
    fn frame(n: [f64; 3]) -> [[f64; 3]; 3] {
        let (t1, t2) = tangent_frame(n);
        [n, t1, t2]
    }

    #[inline]
    fn local_vec(x: [f64; 3]) -> LocalVec<2> {
        LocalVec::spatial(x[0], x[1], x[2])
    }

    fn default_areas<S: Structure<3> + ?Sized>(_: &S, nodes: &[usize]) -> Vec<f64> {
        vec![1.0; nodes.len()]
    }

    fn normals_from_targets<S: Structure<3> + ?Sized>(
        _: &S,
        zone: &str,
        _: &[usize],
    ) -> Result<Vec<[f64; 3]>, SolverError> {
        Err(SolverError::InvalidGeometry(format!(
            "zone `{zone}`: 3D node pairs need their normals (`Fixed`, `PerPair` or `Surface`): \
             a list of target nodes has no normal in space"
        )))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_are_orthonormal_works() {
        let [n, t] = <Dim<2> as ContactSpace<2>>::frame([0.6, 0.8]);
        assert_eq!((n, t), ([0.6, 0.8], [0.8, -0.6]));
        let f = <Dim<3> as ContactSpace<3>>::frame([0.0, 0.0, 1.0]);
        assert_eq!(f, [[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
        assert_eq!(dot([1.0, 2.0, 3.0], [4.0, 5.0, 6.0]), 32.0);
        let l = <Dim<3> as ContactSpace<3>>::local_vec([1.0, 2.0, 3.0]);
        assert_eq!((l.n, l.t[0], l.t[1]), (1.0, 2.0, 3.0));
    }

    #[test]
    fn unit_rejects_zero_vectors() {
        assert!(matches!(
            unit("z", [0.0, 0.0, 0.0]),
            Err(SolverError::InvalidGeometry(m)) if m.contains("unit normal")
        ));
        assert_eq!(unit("z", [3.0, 4.0]).unwrap(), [0.6, 0.8]);
    }
}
