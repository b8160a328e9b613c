//! The deformable target of a 2D zone: a polyline of another body's nodes (node-to-segment),
//! and the tributary areas of nodes taken along a curve ([`lumped_areas`], [`segment_areas`]).
//!
//! A contactor node is projected on every segment of the polyline (skipping those that contain
//! it); among those it projects on orthogonally (`ξ ∈ [−1e-12, 1 + 1e-12]`) the one of smallest
//! `|gap|` is kept, with the segment's left normal `n = (−t_y, t_x)` (the contactor on the left
//! of the polyline) and the weights `(1 − ξ, ξ)` of its ends. A node that projects on no
//! segment takes the closest interior vertex whose region it lies in (past the end of the
//! previous segment and before the start of the next one), with the mean of the two segments'
//! normals; a node beyond both ends is not a candidate.

use super::{MAX_TARGETS, Projection, TargetSurface, check_node};
use crate::coupling::space::{dot, left_normal, sub, unit};
use crate::error::SolverError;
use fem_core::{Idealization, Structure};
use std::collections::HashMap;

/// The target surface of a 2D zone: the polyline through these nodes, in order, with the
/// contactor on its left. A closed polyline repeats its first node at the end (its joint there
/// is then a vertex like the others).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Polyline {
    nodes: Vec<usize>,
}

impl Polyline {
    /// The polyline through `nodes` in order (checked against the structure by
    /// [`recognize`](super::recognize)).
    pub fn new(nodes: Vec<usize>) -> Self {
        Self { nodes }
    }

    /// Its nodes, in order.
    pub fn nodes(&self) -> &[usize] {
        &self.nodes
    }
}

impl From<Vec<usize>> for Polyline {
    fn from(nodes: Vec<usize>) -> Self {
        Self::new(nodes)
    }
}

impl TargetSurface<2> for Polyline {
    fn check<S: Structure<2> + ?Sized>(&self, s: &S, zone: &str) -> Result<(), SolverError> {
        if self.nodes.len() < 2 {
            return Err(SolverError::InvalidGeometry(format!(
                "zone `{zone}`: a target polyline needs at least two nodes"
            )));
        }
        self.nodes.iter().try_for_each(|&n| check_node(s, zone, n))
    }

    fn project_all<S: Structure<2> + ?Sized>(
        &self,
        s: &S,
        zone: &str,
        nodes: &[usize],
    ) -> Result<Vec<Option<Projection<2>>>, SolverError> {
        nodes
            .iter()
            .map(|&node| project_on_polyline(s, &self.nodes, node, zone))
            .collect()
    }

    fn node_normals<S: Structure<2> + ?Sized>(&self, s: &S) -> HashMap<usize, [f64; 2]> {
        // the mean of the segments' left normals weighted by their lengths
        let mut sum: HashMap<usize, [f64; 2]> = HashMap::new();
        for seg in self.nodes.windows(2) {
            let n = left_normal(sub(s.node_position(seg[1]), s.node_position(seg[0])));
            for &node in seg {
                let v = sum.entry(node).or_insert([0.0; 2]);
                v[0] += n[0];
                v[1] += n[1];
            }
        }
        sum.into_iter()
            .filter_map(|(node, n)| unit("", n).ok().map(|n| (node, n)))
            .collect()
    }
}

/// Closest point of `node` on the polyline (module docs); `None` if it projects nowhere.
fn project_on_polyline<S: Structure<2> + ?Sized>(
    s: &S,
    surface: &[usize],
    node: usize,
    name: &str,
) -> Result<Option<Projection<2>>, SolverError> {
    let p = s.node_position(node);
    let mut best: Option<(f64, Projection<2>)> = None;
    let mut targets = [None; MAX_TARGETS];
    for seg in surface.windows(2) {
        let (a, b) = (s.node_position(seg[0]), s.node_position(seg[1]));
        let d = sub(b, a);
        let l2 = dot(d, d);
        if l2 == 0.0 || seg[0] == node || seg[1] == node {
            continue;
        }
        let xi = dot(sub(p, a), d) / l2;
        if !(-1e-12..=1.0 + 1e-12).contains(&xi) {
            continue;
        }
        let xi = xi.clamp(0.0, 1.0);
        let n = left_normal(unit(name, d)?);
        let point = [a[0] + xi * d[0], a[1] + xi * d[1]];
        let gap = dot(n, sub(p, point));
        if best.as_ref().is_none_or(|(g, _)| gap.abs() < *g) {
            targets[0] = Some((seg[0], 1.0 - xi));
            targets[1] = Some((seg[1], xi));
            best = Some((
                gap.abs(),
                Projection {
                    targets,
                    normal: n,
                    gap,
                    point,
                },
            ));
        }
    }
    if best.is_none() {
        // the interior vertices, and the joint of a closed polyline (first node = last)
        let last = surface.len() - 1;
        let closed = surface.len() > 3 && surface[0] == surface[last];
        let joint = closed.then_some((0, last - 1, 1));
        let interior = (1..last).map(|k| (k, k - 1, k + 1));
        for (k, prev, next) in joint.into_iter().chain(interior) {
            let v = s.node_position(surface[k]);
            let dist = sub(p, v);
            let na = left_normal(unit(name, sub(v, s.node_position(surface[prev])))?);
            let nb = left_normal(unit(name, sub(s.node_position(surface[next]), v))?);
            let n = unit(name, [na[0] + nb[0], na[1] + nb[1]])?;
            let d = dist[0].hypot(dist[1]);
            // only in the vertex's own region: past the end of the previous segment and before
            // the start of the next one
            let before = sub(v, s.node_position(surface[prev]));
            let after = sub(s.node_position(surface[next]), v);
            let in_wedge = dot(dist, before) > 0.0 && dot(dist, after) < 0.0;
            if in_wedge && surface[k] != node && best.as_ref().is_none_or(|(g, _)| d < *g) {
                let mut targets = [None; MAX_TARGETS];
                targets[0] = Some((surface[k], 1.0));
                best = Some((
                    d,
                    Projection {
                        targets,
                        normal: n,
                        gap: dot(n, dist),
                        point: v,
                    },
                ));
            }
        }
    }
    Ok(best.map(|(_, c)| c))
}

/// The tributary areas of `nodes` taken as a polyline in their order, as a 2D zone without
/// [`areas`](super::ContactZone::areas) gets them: each node takes half of each segment next
/// to it, weighted at its own position (`× r` in axisymmetry, `× thickness` in plane stress, 1
/// per unit thickness in plane strain). `closed`: the polyline also runs from the last node
/// back to the first (the nodes of a closed curve, each listed once). On the nodes of a P2
/// curve in their order along it (corner, mid-side, corner, …) the areas sum to the curve's
/// length (plane strain). A single node gets 1.
///
/// The areas depend on the order: nodes sorted by index, not along their curve, give a
/// zig-zag and areas that sum to more than the curve's length.
pub fn lumped_areas<S: Structure + ?Sized>(s: &S, nodes: &[usize], closed: bool) -> Vec<f64> {
    let mut areas = vec![0.0; nodes.len()];
    let mut add = |i: usize, j: usize| {
        let [ai, aj] = half_segment(s, nodes[i], nodes[j]);
        areas[i] += ai;
        areas[j] += aj;
    };
    for k in 1..nodes.len() {
        add(k - 1, k);
    }
    if closed && nodes.len() > 2 {
        add(nodes.len() - 1, 0);
    }
    if nodes.len() == 1 {
        areas[0] = 1.0;
    }
    areas
}

/// The tributary areas of `nodes` from `segments` (pairs of nodes, in any order and
/// direction, e.g. the corner-to-mid-side halves of a curve's P2 sides), lumped as
/// [`lumped_areas`] does: each end of a segment takes half of it, weighted at its own
/// position. The order of `nodes` plays no part: the areas of a set that is not one curve
/// (disjoint pieces, a branch) come out right.
///
/// # Errors
/// [`SolverError::InvalidGeometry`] for a segment end that is not one of `nodes`.
pub fn segment_areas<S: Structure + ?Sized>(
    s: &S,
    nodes: &[usize],
    segments: &[[usize; 2]],
) -> Result<Vec<f64>, SolverError> {
    let index: HashMap<usize, usize> = nodes.iter().enumerate().map(|(k, &n)| (n, k)).collect();
    let mut areas = vec![0.0; nodes.len()];
    for &[a, b] in segments {
        let (Some(&i), Some(&j)) = (index.get(&a), index.get(&b)) else {
            return Err(SolverError::InvalidGeometry(format!(
                "segment {a}–{b} has an end outside the {} nodes given",
                nodes.len()
            )));
        };
        let [ai, aj] = half_segment(s, a, b);
        areas[i] += ai;
        areas[j] += aj;
    }
    Ok(areas)
}

/// Half the length of the segment `a`–`b` for each end, weighted at the end's own position
/// (`× r` in axisymmetry, `× thickness` in plane stress, 1 in plane strain).
fn half_segment<S: Structure + ?Sized>(s: &S, a: usize, b: usize) -> [f64; 2] {
    let factor = |x: [f64; 2]| match s.idealization() {
        Idealization::Axisymmetric => x[0],
        Idealization::PlaneStress { thickness } => thickness,
        _ => 1.0, // plane strain: per unit thickness
    };
    let (a, b) = (s.node_position(a), s.node_position(b));
    let d = sub(b, a);
    let half = 0.5 * d[0].hypot(d[1]);
    // midpoint-lumped: each node takes half the segment, weighted at its own position
    [half * factor(a).abs(), half * factor(b).abs()]
}
