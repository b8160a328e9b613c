//! The node sets of 2D contact zones taken as curves, and the checks of their geometry
//! (issue 36).
//!
//! A `segments` target is the polyline through its set's nodes in order, node pairs take
//! their normals from the target set in order, and a contactor's tributary areas are lumped
//! along its set in order. Node sets read from Gmsh physical curves are ordered along the
//! curve ([`fem_core::Mesh::add_curve_node_set`]); the generators' sets are sorted along their
//! straight lines. What is refused here, with the key path and the node:
//! - a target set read from a curve that is not one curve (a branch, disjoint pieces): its
//!   polyline would bridge a gap or cross itself;
//! - a `segments` polyline that visits a node twice or turns back by more than 90° at a node
//!   (a set not in order along its surface);
//! - after recognition, a pair's or segment's normal (from the target towards the contactor)
//!   that points along the contactor body's own outward normal: the target runs the wrong way
//!   (the contactor must be on its left) or does not face the contactor.
//!
//! A closed curve's set lists each node once: its `segments` polyline is closed here by
//! repeating the first node at the end, and a closed contactor's areas include the closing
//! segment. A contactor read from a curve that is not one curve gets its areas from its sides.

use super::checks::node_set;
use crate::error::{CliResult, KeyPath, bail};
use contact_laws::StandardLaw;
use contact_solver::coupling::zone::{lumped_areas, segment_areas};
use contact_solver::{Candidate, ContactZone, PairNormals, Target};
use fem_core::curve::{CurveOrder, NotACurve, chain_sides};
use fem_core::{LinearElasticModel, Mesh, Structure};

/// The nodes of the target set `name` (at `path`) in order, and whether the curve they come
/// from is closed.
///
/// # Errors
/// An unknown set, or a set read from a curve that is not one curve.
pub(super) fn target_nodes(
    path: &KeyPath,
    mesh: &Mesh,
    name: &str,
) -> CliResult<(Vec<usize>, bool)> {
    let nodes = node_set(path, mesh, name)?;
    match mesh.curve_order(name) {
        Some(CurveOrder::NotACurve(why)) => {
            let at = match why {
                NotACurve::Branch { node, .. } => {
                    let x = mesh.nodes()[*node];
                    format!(" (node {node} is at ({}, {}))", x[0], x[1])
                }
                _ => String::new(),
            };
            bail!(
                path,
                "`{path}` = \"{name}\": a target must follow one curve, but the curve \
                     `{name}` is not one: {why}{at}; give each piece its own physical curve \
                     and zone"
            )
        }
        Some(CurveOrder::Closed) => Ok((nodes, true)),
        _ => Ok((nodes, false)),
    }
}

/// The tributary areas of the contactor set `name` (nodes `nodes`, in the set's order) where
/// the zone's own lumping along the order would be wrong: a closed curve (its closing
/// segment), a curve that is not one curve, and a generator's set whose order does not run
/// along its sides (the pile's `surface`): the last two from the sides of the edge set of the
/// same name. `None` otherwise (the zone lumps along the set's order; every contact set of the
/// shipped scenes).
pub(super) fn contactor_areas(
    model: &LinearElasticModel,
    name: &str,
    nodes: &[usize],
) -> Option<Vec<f64>> {
    let mesh = model.mesh();
    let sides = mesh.edge_set(name).ok();
    match mesh.curve_order(name) {
        Some(CurveOrder::Open) => return None,
        Some(CurveOrder::Closed) => return Some(lumped_areas(model, nodes, true)),
        Some(CurveOrder::NotACurve(_)) => {}
        None => {
            let curve = chain_sides(mesh, sides?).ok()?;
            let along = |a: &[usize]| a.iter().eq(nodes.iter()) || a.iter().rev().eq(nodes.iter());
            if along(&curve.nodes) {
                return None;
            }
        }
    }
    let mut segments = Vec::new();
    for &side in sides? {
        let s: Vec<usize> = mesh.side_nodes(side).collect();
        match s[..] {
            [a, b, m] => segments.extend([[a, m], [m, b]]),
            [a, b] => segments.push([a, b]),
            _ => {}
        }
    }
    segment_areas(model, nodes, &segments).ok()
}

/// For node pairs between two open curves: the contactor's nodes reversed when that pairs
/// them better with the target's (two facing curves ordered with their bodies on the right
/// run opposite ways). Sets not read from curves are kept as given ("in matching order").
pub(super) fn match_pairs(mesh: &Mesh, contactor: (&str, &mut [usize]), target: (&str, &[usize])) {
    let (c_name, c) = contactor;
    let (t_name, t) = target;
    let open = |n: &str| mesh.curve_order(n) == Some(&CurveOrder::Open);
    if !(open(c_name) && open(t_name)) || c.len() != t.len() || c.is_empty() {
        return;
    }
    let x = mesh.nodes();
    let d = |a: usize, b: usize| (x[a][0] - x[b][0]).hypot(x[a][1] - x[b][1]);
    let last = c.len() - 1;
    let straight = d(c[0], t[0]) + d(c[last], t[last]);
    let crossed = d(c[last], t[0]) + d(c[0], t[last]);
    if crossed < straight {
        c.reverse();
    }
}

/// A `segments` target's polyline (at `path`, from the set `name`): no node twice (but the
/// first repeated at the end of a closed one), no turn of more than 90° at a node.
///
/// # Errors
/// The first node where it revisits or doubles back, with its position and the turn.
pub(super) fn check_polyline(
    path: &KeyPath,
    name: &str,
    model: &LinearElasticModel,
    surface: &[usize],
) -> CliResult<()> {
    let n = surface.len();
    let closed = n > 3 && surface[0] == surface[n - 1];
    let x = |k: usize| model.node_position(surface[k]);
    let open_part = if closed { &surface[..n - 1] } else { surface };
    let mut seen = std::collections::HashSet::new();
    for (k, &node) in open_part.iter().enumerate() {
        if !seen.insert(node) {
            let p = x(k);
            bail!(
                path,
                "`{path}` = \"{name}\": the target polyline visits node {node} at ({}, {}) \
                     twice (a `segments` target runs once along the surface, in order)",
                p[0],
                p[1]
            );
        }
    }
    let joint = closed.then_some((0, n - 2, 1));
    for (k, prev, next) in joint
        .into_iter()
        .chain((1..n.saturating_sub(1)).map(|k| (k, k - 1, k + 1)))
    {
        let (a, v, b) = (x(prev), x(k), x(next));
        let (t1, t2) = ([v[0] - a[0], v[1] - a[1]], [b[0] - v[0], b[1] - v[1]]);
        let dot = t1[0] * t2[0] + t1[1] * t2[1];
        let lengths = t1[0].hypot(t1[1]) * t2[0].hypot(t2[1]);
        if dot < 0.0 && lengths > 0.0 {
            let turn = (dot / lengths).clamp(-1.0, 1.0).acos().to_degrees();
            bail!(
                path,
                "`{path}` = \"{name}\": the target polyline doubles back at node {} at \
                     ({}, {}): it turns by {turn:.0}° there (more than 90°). A `segments` target \
                     is the polyline through its set's nodes in order: the set must run along \
                     the surface (a Gmsh physical curve does; a hand-made set sorted by index \
                     may not)",
                surface[k],
                v[0],
                v[1]
            );
        }
    }
    Ok(())
}

/// Every candidate of a node-pair or node-to-segment zone must face its target: the normal
/// from the target towards the contactor must not point along the contactor body's own
/// outward normal at the node (where the model knows it).
///
/// # Errors
/// The first candidate that faces away, at `contact[i].target`, with its nodes and normals.
pub(super) fn check_facing(
    candidates: &[Candidate],
    zones: &[ContactZone<StandardLaw>],
    model: &LinearElasticModel,
) -> CliResult<()> {
    for c in candidates {
        let zone = &zones[c.zone];
        let what = match zone.target {
            Target::Rigid(_) => continue,
            Target::NodePairs {
                normals: PairNormals::FromTargets,
                ..
            } => {
                "the normal of the target nodes taken as a polyline in order, contactor on \
                 its left"
            }
            Target::NodePairs { .. } => "the zone's `normal`",
            Target::Surface(_) => "the target polyline's normal (contactor on its left)",
            // a target kind the library adds later: nothing to check yet
            _ => continue,
        };
        let Some(out) = model.outward_normal(c.node) else {
            continue;
        };
        let n = c.normal();
        if out[0] * n[0] + out[1] * n[1] > 1e-9 {
            let p = KeyPath::root().key("contact").index(c.zone).key("target");
            let x = model.node_position(c.node);
            let target = c
                .targets
                .iter()
                .flatten()
                .map(|(t, _)| t.to_string())
                .collect::<Vec<_>>()
                .join(" and ");
            bail!(
                p,
                "zone `{}`: contactor node {} at ({}, {}) faces away from its target (node \
                     {target}): {what} points ({:.3}, {:.3}), along the contactor body's own \
                     outward normal ({:.3}, {:.3}). The target set runs the wrong way (reverse \
                     it, or give node pairs a `normal` from the target towards the contactor) \
                     or does not face the contactor",
                zone.name,
                c.node,
                x[0],
                x[1],
                n[0],
                n[1],
                out[0],
                out[1]
            );
        }
    }
    Ok(())
}
