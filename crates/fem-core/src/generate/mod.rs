//! Structured triangle meshes: graded 1D subdivisions, layered rectangles, and the
//! axisymmetric pile-in-soil domain of the seed's chapter 6.
//!
//! Every generator builds a tensor-product grid of points `x_i × y_j`, splits each cell into two
//! counter-clockwise triangles (the diagonal alternates from cell to cell, so the mesh has no
//! preferred direction) and, for P2, puts the mid-side nodes exactly at the middle of the
//! straight sides, shared by the neighbours. Grading is geometric:
//!
//! ```text
//! h_i = h_0 q^i,  i = 0 … n−1,   q = ratio^(1/(n−1)),   Σ h_i = b − a
//! ```
//!
//! Boundaries are named: edge sets hold the boundary [`Side`](crate::mesh::Side)s (sorted
//! along the boundary) and node sets of the same name hold all their nodes, mid-side nodes
//! included.
//!
//! The pile mesh follows Terfaya (2019), ch. 6 ([`PileSpec`]).

mod grid;
mod pile;
mod rectangle;
#[cfg(test)]
mod test_support;

pub use pile::{PILE, PileSpec, SOIL, TipCorner, pile_in_soil};
pub use rectangle::{Layer, RectangleSpec, rectangle};

pub(crate) use grid::lattice_lines;

use crate::error::{FemError, positive};

/// How the cells of a 1D subdivision grow from its start `a` to its end `b`.
///
/// Sizes follow a geometric progression; see the [module docs](self).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Grading {
    /// Equal cells.
    #[default]
    Uniform,
    /// Geometric progression with `ratio = h_last / h_first` (finite, `> 0`): `ratio > 1`
    /// refines toward the start `a`, `ratio < 1` toward the end `b`.
    Geometric {
        /// Last cell size over first cell size.
        ratio: f64,
    },
    /// Refined toward both ends, symmetrically: `ratio = h_middle / h_end` (finite, `> 0`,
    /// usually `> 1`). With fewer than three cells it is uniform.
    BothEnds {
        /// Middle cell size over end cell size.
        ratio: f64,
    },
}

impl Grading {
    /// Refined toward the start: the last cell is `ratio` times the first (`ratio ≥ 1` for a
    /// refinement).
    ///
    /// # Examples
    /// ```
    /// use fem_core::generate::{graded_points, Grading};
    /// let p = graded_points(0.0, 3.0, 2, Grading::fine_at_start(2.0)).unwrap();
    /// assert_eq!(p, vec![0.0, 1.0, 3.0]);
    /// ```
    pub fn fine_at_start(ratio: f64) -> Self {
        Grading::Geometric { ratio }
    }

    /// Refined toward the end: the first cell is `ratio` times the last (`ratio ≥ 1` for a
    /// refinement).
    ///
    /// # Examples
    /// ```
    /// use fem_core::generate::{graded_points, Grading};
    /// let p = graded_points(0.0, 3.0, 2, Grading::fine_at_end(2.0)).unwrap();
    /// assert_eq!(p, vec![0.0, 2.0, 3.0]);
    /// ```
    pub fn fine_at_end(ratio: f64) -> Self {
        Grading::Geometric { ratio: 1.0 / ratio }
    }

    /// The grading ratio (1 for uniform).
    fn ratio(self) -> f64 {
        match self {
            Grading::Uniform => 1.0,
            Grading::Geometric { ratio } | Grading::BothEnds { ratio } => ratio,
        }
    }

    /// Relative cell sizes, the largest being 1.
    fn weights(self, n: usize) -> Result<Vec<f64>, FemError> {
        let weights: Vec<f64> = match self {
            Grading::Uniform => vec![1.0; n],
            Grading::Geometric { ratio } => {
                let ratio = positive("ratio", ratio)?;
                let last = (n - 1).max(1) as f64;
                (0..n).map(|i| ratio.powf(i as f64 / last)).collect()
            }
            Grading::BothEnds { ratio } => {
                let ratio = positive("ratio", ratio)?;
                let k = (n - 1) / 2;
                (0..n)
                    .map(|i| match k {
                        0 => 1.0,
                        _ => ratio.powf(i.min(n - 1 - i) as f64 / k as f64),
                    })
                    .collect()
            }
        };
        let max = weights.iter().copied().fold(0.0, f64::max);
        let weights: Vec<f64> = weights.into_iter().map(|w| w / max).collect();
        if max.is_finite() && weights.iter().all(|&w| w > 0.0) {
            Ok(weights)
        } else {
            Err(FemError::InvalidParameter {
                name: "ratio",
                value: self.ratio(),
                expected: "a ratio whose powers stay finite and > 0 for this number of cells",
            })
        }
    }
}

/// The most nodes a generator builds (1e8: 1.6 GB of coordinates before the model's own
/// storage); a larger request is [`FemError::TooLarge`] before anything is allocated, instead
/// of an allocation failure that aborts the process.
pub const MAX_GENERATED_NODES: usize = 100_000_000;

/// Checks a structured grid of `cells_x × cells_y` cells (P2: twice the nodes per direction)
/// against [`MAX_GENERATED_NODES`] with overflow-checked arithmetic, and its kind against
/// the plane ([`FemError::KindDimension`] for a 3D kind).
pub(crate) fn check_grid_size(
    cells_x: usize,
    cells_y: usize,
    kind: crate::ElementKind,
) -> Result<(), FemError> {
    kind.of_dimension::<2>()?;
    let per = if kind.is_quadratic() { 2 } else { 1 };
    let line = |cells: usize| cells.checked_mul(per).and_then(|n| n.checked_add(1));
    let nodes = line(cells_x)
        .zip(line(cells_y))
        .and_then(|(a, b)| a.checked_mul(b));
    match nodes {
        Some(n) if n <= MAX_GENERATED_NODES => Ok(()),
        requested => Err(FemError::TooLarge {
            what: "nodes of the generated mesh",
            requested,
            limit: MAX_GENERATED_NODES,
        }),
    }
}

/// The `n + 1` points of a subdivision of `[a, b]` into `n` cells graded by `grading`,
/// from `a` to `b` exactly (strictly monotone; `b < a` is allowed and runs backwards).
///
/// # Errors
/// [`FemError::InvalidParameter`] if `a` or `b` is not finite, `a == b`, `n == 0`, or the
/// grading ratio is not finite and `> 0`.
///
/// # Examples
/// ```
/// use fem_core::generate::{graded_points, Grading};
/// let p = graded_points(0.0, 7.0, 3, Grading::Geometric { ratio: 4.0 }).unwrap();
/// // sizes 1, 2, 4
/// assert_eq!(p, vec![0.0, 1.0, 3.0, 7.0]);
/// ```
pub fn graded_points(a: f64, b: f64, n: usize, grading: Grading) -> Result<Vec<f64>, FemError> {
    if n > MAX_GENERATED_NODES {
        return Err(FemError::TooLarge {
            what: "cells of a graded line",
            requested: Some(n),
            limit: MAX_GENERATED_NODES,
        });
    }
    for (name, value) in [("a", a), ("b", b)] {
        if !value.is_finite() {
            return Err(FemError::InvalidParameter {
                name,
                value,
                expected: "a finite value",
            });
        }
    }
    if a == b {
        return Err(FemError::InvalidParameter {
            name: "b",
            value: b,
            expected: "an end point different from a",
        });
    }
    if !(b - a).is_finite() {
        return Err(FemError::InvalidParameter {
            name: "b - a",
            value: b - a,
            expected: "a length that does not overflow (|b - a| <= 1.8e308)",
        });
    }
    if n == 0 {
        return Err(FemError::InvalidParameter {
            name: "n",
            value: 0.0,
            expected: "at least one cell",
        });
    }
    let weights = grading.weights(n)?;
    let total: f64 = weights.iter().sum();
    let mut points = Vec::with_capacity(n + 1);
    let mut acc = 0.0;
    points.push(a);
    for w in &weights[..n - 1] {
        acc += w;
        points.push(a + (b - a) * (acc / total));
    }
    points.push(b);
    // a cell below 1e-14 of the line (round-off of its end points) makes elements that
    // `Mesh::new` calls degenerate: blame the ratio here
    let smallest = 1e-14 * (b - a).abs();
    if points
        .windows(2)
        .all(|w| (w[1] - w[0]) * (b - a).signum() > smallest)
    {
        Ok(points)
    } else {
        Err(FemError::InvalidParameter {
            name: "ratio",
            value: grading.ratio(),
            expected: "a grading whose smallest cell is at least 1e-14 of the line",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn graded_points_works() {
        let p = graded_points(1.0, 2.0, 4, Grading::Uniform).unwrap();
        assert_eq!(p, vec![1.0, 1.25, 1.5, 1.75, 2.0]);
        let p = graded_points(0.0, 10.0, 5, Grading::Geometric { ratio: 16.0 }).unwrap();
        let h: Vec<f64> = p.windows(2).map(|w| w[1] - w[0]).collect();
        // Round-off of a sum of five terms.
        assert_relative_eq!(h[4] / h[0], 16.0, max_relative = 1e-12);
        for w in h.windows(2) {
            assert_relative_eq!(w[1] / w[0], 2.0, max_relative = 1e-12);
        }
        let p = graded_points(0.0, 1.0, 5, Grading::fine_at_end(16.0)).unwrap();
        assert_relative_eq!((p[1] - p[0]) / (p[5] - p[4]), 16.0, max_relative = 1e-12);
        let p = graded_points(0.0, 1.0, 5, Grading::BothEnds { ratio: 4.0 }).unwrap();
        let h: Vec<f64> = p.windows(2).map(|w| w[1] - w[0]).collect();
        assert_relative_eq!(h[0], h[4], max_relative = 1e-12);
        assert_relative_eq!(h[1], h[3], max_relative = 1e-12);
        assert_relative_eq!(h[2] / h[0], 4.0, max_relative = 1e-12);
        assert_eq!(p[5], 1.0);
        // Backwards, and a single cell ignores the ratio.
        assert_eq!(
            graded_points(1.0, 0.0, 2, Grading::Uniform).unwrap(),
            [1.0, 0.5, 0.0]
        );
        assert_eq!(
            graded_points(0.0, 1.0, 1, Grading::Geometric { ratio: 9.0 }).unwrap(),
            [0.0, 1.0]
        );
        assert_eq!(
            graded_points(0.0, 1.0, 2, Grading::BothEnds { ratio: 9.0 }).unwrap(),
            [0.0, 0.5, 1.0]
        );
    }

    #[test]
    fn graded_points_rejects_bad_input() {
        let bad = |r| matches!(r, Err(FemError::InvalidParameter { .. }));
        assert!(bad(graded_points(0.0, 1.0, 0, Grading::Uniform)));
        assert!(bad(graded_points(0.0, 0.0, 3, Grading::Uniform)));
        assert!(bad(graded_points(f64::NAN, 1.0, 3, Grading::Uniform)));
        assert!(bad(graded_points(0.0, f64::INFINITY, 3, Grading::Uniform)));
        assert!(bad(graded_points(
            0.0,
            1.0,
            3,
            Grading::Geometric { ratio: 0.0 }
        )));
        assert!(bad(graded_points(0.0, 1.0, 3, Grading::fine_at_end(0.0))));
        assert!(bad(graded_points(
            0.0,
            1.0,
            3,
            Grading::BothEnds { ratio: -1.0 }
        )));
        assert!(bad(graded_points(
            0.0,
            1.0,
            3,
            Grading::BothEnds { ratio: f64::NAN }
        )));
        // Finite weights, but the smallest cells vanish next to the largest.
        assert!(bad(graded_points(
            1.0,
            2.0,
            1000,
            Grading::Geometric { ratio: 1e300 }
        )));
        assert!(graded_points(0.0, 1.0, 50, Grading::Geometric { ratio: 1e12 }).is_ok());
    }
}
