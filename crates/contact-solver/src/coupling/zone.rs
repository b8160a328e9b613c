//! Contact zones (seed 5.5) and obstacle recognition (5.5.6).
//!
//! A [`ContactZone`] is a set of *contactor* nodes facing a [`Target`] — a rigid
//! [`Obstacle`], the nodes of another body paired one to one (matching interfaces such as the
//! pile–soil shaft), or a polyline of another body's nodes (node-to-segment) — with its law
//! and its alert distance `Δx`.
//!
//! Recognition happens once, on the reference configuration (small displacements, as the
//! seed's quasi-static setting): every contactor node gets its closest target point, the
//! local frame `(n, t)`, the initial gap `g₀`, and the row pair of `H` that maps the
//! structure's displacements to the local relative displacement
//!
//! ```text
//! u_rel = u_contactor − Σ_k w_k u_target,k      (w = 1 for a pair, (1 − ξ, ξ) on a segment)
//! x_n = g₀ + n·u_rel   (the gap, ≥ 0 open),     u_t = t·u_rel
//! ```
//! At each step, a candidate becomes a contact element (enters the reduced problem) only when
//! its gap at the start of the step or under the free response is within `Δx`, or while it is
//! adhesive (β > 0). See [`crate::coupling::simulation`].

use crate::coupling::obstacle::Obstacle;
use crate::error::SolverError;
use fem_core::{Idealization, Structure};
use std::sync::Arc;

/// What the contactor nodes of a zone face.
#[derive(Clone, Debug)]
pub enum Target {
    /// A rigid obstacle (LINE, ARC or your own [`Obstacle`]).
    Rigid(Arc<dyn Obstacle>),
    /// Node-to-node: `nodes[i]` is the target of contactor node `i` (matching meshes). The
    /// normal, pointing from the target body to the contactor, is `normal` if given, else it
    /// is computed on the target nodes taken as a polyline in the given order, with the
    /// contactor on the left (`n = (−t_y, t_x)`).
    NodePairs {
        /// Target node of each contactor node.
        nodes: Vec<usize>,
        /// A fixed unit normal for every pair (normalised on use), or `None`.
        normal: Option<[f64; 2]>,
    },
    /// Node-to-segment: the target surface is the polyline through these nodes, in order, with
    /// the contactor on its left. A closed polyline repeats its first node at the end (its
    /// joint there is then a vertex like the others).
    Segments(Vec<usize>),
}

/// One contact zone: contactor nodes, target, law and alert distance.
#[derive(Clone, Debug)]
pub struct ContactZone<L> {
    /// A name for reports.
    pub name: String,
    /// The contactor nodes.
    pub contactor: Vec<usize>,
    /// What they face.
    pub target: Target,
    /// The interface law.
    pub law: L,
    /// Alert distance `Δx ≥ 0`: candidates farther than this are left out of the step.
    pub alert_distance: f64,
    /// Tributary area of each contactor node (length × thickness in plane problems, length ×
    /// radius per radian in axisymmetry), which turns the law's per-area adhesive stiffness
    /// into nodal springs. `None`: lumped from the contactor nodes taken as a polyline in the
    /// given order (half of each adjacent segment; `× r` in axisymmetry, `× thickness` in
    /// plane stress). Set it with [`ContactZone::with_areas`] for consistent P2 weights.
    pub areas: Option<Vec<f64>>,
}

impl<L> ContactZone<L> {
    /// Sets the tributary area of each contactor node (same order as `contactor`).
    pub fn with_areas(mut self, areas: Vec<f64>) -> Self {
        self.areas = Some(areas);
        self
    }

    /// A zone facing a rigid obstacle.
    pub fn rigid(
        name: impl Into<String>,
        contactor: Vec<usize>,
        obstacle: impl Obstacle + 'static,
        law: L,
        alert_distance: f64,
    ) -> Self {
        Self {
            name: name.into(),
            contactor,
            target: Target::Rigid(Arc::new(obstacle)),
            law,
            alert_distance,
            areas: None,
        }
    }

    /// A node-to-node zone: `targets[i]` faces `contactor[i]`.
    pub fn node_pairs(
        name: impl Into<String>,
        contactor: Vec<usize>,
        targets: Vec<usize>,
        normal: Option<[f64; 2]>,
        law: L,
        alert_distance: f64,
    ) -> Self {
        Self {
            name: name.into(),
            contactor,
            target: Target::NodePairs {
                nodes: targets,
                normal,
            },
            law,
            alert_distance,
            areas: None,
        }
    }

    /// A node-to-segment zone facing the polyline `surface`.
    pub fn node_to_segment(
        name: impl Into<String>,
        contactor: Vec<usize>,
        surface: Vec<usize>,
        law: L,
        alert_distance: f64,
    ) -> Self {
        Self {
            name: name.into(),
            contactor,
            target: Target::Segments(surface),
            law,
            alert_distance,
            areas: None,
        }
    }
}

/// A contact candidate: one contactor node with its target point and frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Candidate {
    /// Index of its zone.
    pub zone: usize,
    /// The contactor node.
    pub node: usize,
    /// Target nodes and weights (`None` for rigid obstacles and unused slots).
    pub targets: [Option<(usize, f64)>; 2],
    /// Unit normal, from the target towards the contactor.
    pub normal: [f64; 2],
    /// Unit tangent `t = (n_y, −n_x)`.
    pub tangent: [f64; 2],
    /// Initial gap `g₀` (reference configuration).
    pub gap0: f64,
    /// The target point in the reference configuration.
    pub point: [f64; 2],
    /// Tributary area of the contactor node (see [`ContactZone::areas`]).
    pub area: f64,
}

impl Candidate {
    /// The entries `(dof, coefficient)` of this candidate's `H` row for direction `dir`
    /// (`n` or `t`), on the structure's free dofs; at most six.
    pub(crate) fn h_row<S: Structure + ?Sized>(
        &self,
        s: &S,
        dir: [f64; 2],
        out: &mut Vec<(usize, f64)>,
    ) {
        let mut push = |node: usize, w: f64| {
            for (c, d) in s.node_dofs(node).into_iter().enumerate() {
                if let Some(i) = d {
                    let a = w * dir[c];
                    if a != 0.0 {
                        out.push((i, a));
                    }
                }
            }
        };
        push(self.node, 1.0);
        for &(node, w) in self.targets.iter().flatten() {
            push(node, -w);
        }
    }

    /// The relative displacement `u_rel` from a full nodal displacement lookup.
    pub(crate) fn relative(&self, disp: impl Fn(usize) -> [f64; 2]) -> [f64; 2] {
        let mut u = disp(self.node);
        for &(node, w) in self.targets.iter().flatten() {
            let v = disp(node);
            u[0] -= w * v[0];
            u[1] -= w * v[1];
        }
        u
    }

    /// `(x_n, u_t) = (g₀ + n·u_rel, t·u_rel)`.
    pub(crate) fn local(&self, u_rel: [f64; 2]) -> [f64; 2] {
        [
            self.gap0 + dot(self.normal, u_rel),
            dot(self.tangent, u_rel),
        ]
    }
}

#[inline]
fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

fn unit(v: [f64; 2], what: &str) -> Result<[f64; 2], SolverError> {
    let l = v[0].hypot(v[1]);
    if !(l > 0.0 && l.is_finite()) {
        return Err(SolverError::InvalidGeometry(format!(
            "{what}: cannot build a unit normal from {v:?}"
        )));
    }
    Ok([v[0] / l, v[1] / l])
}

fn left_normal(t: [f64; 2]) -> [f64; 2] {
    [-t[1], t[0]]
}

fn check_node<S: Structure + ?Sized>(s: &S, zone: &str, node: usize) -> Result<(), SolverError> {
    if node >= s.node_count() {
        return Err(SolverError::InvalidGeometry(format!(
            "zone `{zone}`: node {node} is out of range (the structure has {} nodes)",
            s.node_count()
        )));
    }
    Ok(())
}

/// A rigid target shorter than this fraction of the contactor's extent is degenerate.
pub const DEGENERATE_TARGET: f64 = 1e-9;

/// Physical checks of the rigid zones after [`recognize`], where the sign of a gap alone is
/// ambiguous (run by [`ContactSimulation::new`](crate::ContactSimulation::new)):
/// - every rigid zone has at least one candidate (a zone whose contactor nodes all miss the
///   obstacle would never act: recognition is done once, on the reference configuration);
/// - the obstacle is not degenerate: its [`extent`](crate::Obstacle::extent) is at least
///   [`DEGENERATE_TARGET`] times the diagonal of the contactor's bounding box;
/// - the obstacle faces the body: at the candidate closest to it (smallest `|g₀|`), the
///   body's own [outward normal](fem_core::Structure::outward_normal), where the structure
///   knows it, must point against the obstacle's normal (`n_body · n_obstacle ≤ 0`). A LINE
///   given from `b` to `a` while the body touches it has gaps of 0 on the wrong side: without
///   this check the body would fall through.
///
/// # Errors
/// [`SolverError::InvalidGeometry`] naming the zone (and the node) for each case.
pub fn check_rigid_targets<S: Structure + ?Sized, L>(
    s: &S,
    zones: &[ContactZone<L>],
    candidates: &[Candidate],
) -> Result<(), SolverError> {
    for (z, zone) in zones.iter().enumerate() {
        let Target::Rigid(obstacle) = &zone.target else {
            continue;
        };
        let name = zone.name.as_str();
        let mine: Vec<&Candidate> = candidates.iter().filter(|c| c.zone == z).collect();
        let Some(closest) = mine
            .iter()
            .min_by(|a, b| a.gap0.abs().total_cmp(&b.gap0.abs()))
        else {
            return Err(SolverError::InvalidGeometry(format!(
                "zone `{name}`: none of its {} contactor nodes projects onto its obstacle \
                 (check the obstacle's ends and its side)",
                zone.contactor.len()
            )));
        };
        if let Some(extent) = obstacle.extent() {
            let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
            for &n in &zone.contactor {
                let x = s.node_position(n);
                for k in 0..2 {
                    lo[k] = lo[k].min(x[k]);
                    hi[k] = hi[k].max(x[k]);
                }
            }
            let size = (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
            if extent < DEGENERATE_TARGET * size {
                return Err(SolverError::InvalidGeometry(format!(
                    "zone `{name}`: its obstacle is {extent:e} long, less than \
                     {DEGENERATE_TARGET:e} of the contactor's extent {size:e}: a degenerate target"
                )));
            }
        }
        if let Some(outward) = s.outward_normal(closest.node) {
            let n = closest.normal;
            if outward[0] * n[0] + outward[1] * n[1] > 0.0 {
                let x = s.node_position(closest.node);
                return Err(SolverError::InvalidGeometry(format!(
                    "zone `{name}`: contactor node {} at ({}, {}) faces away from its obstacle \
                     (the body's outward normal ({:.3}, {:.3}), the obstacle's normal towards \
                     the contactor ({:.3}, {:.3})): the obstacle is given on the wrong side (a \
                     LINE has the contactor on its left, from a to b; an ARC has its side)",
                    closest.node, x[0], x[1], outward[0], outward[1], n[0], n[1]
                )));
            }
        }
    }
    Ok(())
}

impl<L> ContactZone<L> {
    /// This zone without the contactor nodes of `leave_out` (their paired target nodes and
    /// their areas go with them): e.g. the nodes [`supported_contactors`] finds, which cannot
    /// take part in contact.
    #[must_use]
    pub fn without_contactors(mut self, leave_out: &[usize]) -> Self {
        let keep: Vec<bool> = self
            .contactor
            .iter()
            .map(|n| !leave_out.contains(n))
            .collect();
        let kept = |v: &mut Vec<_>| {
            let mut k = keep.iter();
            v.retain(|_| *k.next().unwrap_or(&true));
        };
        if let Target::NodePairs { nodes, .. } = &mut self.target
            && nodes.len() == keep.len()
        {
            kept(nodes);
        }
        if let Some(a) = &mut self.areas
            && a.len() == keep.len()
        {
            let mut k = keep.iter();
            a.retain(|_| *k.next().unwrap_or(&true));
        }
        kept(&mut self.contactor);
        self
    }
}

/// The contactor nodes of `zones` that a support holds along their contact normal: their
/// normal displacement relative to the target is fully prescribed (no free dof along it), so
/// they cannot take part in contact and [`ContactSimulation::new`](crate::ContactSimulation::new)
/// refuses them. `(zone, node)`, in recognition order (zone, then contactor).
///
/// # Errors
/// As [`recognize`].
///
/// # Examples
/// ```
/// use contact_solver::{ContactZone, supported_contactors};
/// use contact_solver::coupling::obstacle::RigidLine;
/// use contact_laws::Signorini;
/// use fem_core::{Component, Idealization, LinearElasticModel, Material, Supports};
/// use fem_core::generate::{RectangleSpec, rectangle};
///
/// let mesh = rectangle(&RectangleSpec::new([0.0, 1.0], [0.0, 1.0], 2, 2))?;
/// let bottom = mesh.node_set("bottom")?.to_vec();
/// let mut supports = Supports::new();
/// supports.fix(&mesh.node_set("top")?.to_vec(), Component::Y);
/// supports.fix(&bottom[..1], Component::Y); // a corner held along the contact normal
/// supports.fix(&bottom[..1], Component::X);
/// let model = LinearElasticModel::new(mesh, Idealization::PlaneStrain,
///     &[(0, Material::new(100.0, 0.3, 0.0)?)], supports)?;
/// let ground = RigidLine::new([-1.0, 0.0], [2.0, 0.0])?;
/// let zone = ContactZone::rigid("base", bottom.clone(), ground, Signorini, 0.1);
/// assert_eq!(supported_contactors(&model, &[zone.clone()])?, [(0, bottom[0])]);
/// let zone = zone.without_contactors(&[bottom[0]]);
/// assert!(supported_contactors(&model, &[zone])?.is_empty());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn supported_contactors<S: Structure + ?Sized, L>(
    structure: &S,
    zones: &[ContactZone<L>],
) -> Result<Vec<(usize, usize)>, SolverError> {
    let mut row = Vec::new();
    Ok(recognize(structure, zones)?
        .iter()
        .filter(|c| {
            row.clear();
            c.h_row(structure, c.normal, &mut row);
            row.is_empty()
        })
        .map(|c| (c.zone, c.node))
        .collect())
}

/// Obstacle recognition on the reference configuration: the candidates of every zone, in zone
/// order then contactor order. Contactor nodes of a rigid zone with no orthogonal projection on
/// the obstacle are not candidates.
///
/// # Errors
/// [`SolverError::InvalidGeometry`] for an empty zone, a node out of range, mismatched pair
/// lists, a polyline with fewer than two nodes or a degenerate normal;
/// [`SolverError::InvalidSetting`] for a negative or non-finite alert distance.
pub fn recognize<S: Structure + ?Sized, L>(
    s: &S,
    zones: &[ContactZone<L>],
) -> Result<Vec<Candidate>, SolverError> {
    let mut out = Vec::new();
    for (z, zone) in zones.iter().enumerate() {
        let name = zone.name.as_str();
        if !(zone.alert_distance >= 0.0 && zone.alert_distance.is_finite()) {
            return Err(SolverError::InvalidSetting {
                what: "alert_distance",
                value: zone.alert_distance,
                expected: "a finite distance >= 0",
            });
        }
        if zone.contactor.is_empty() {
            return Err(SolverError::InvalidGeometry(format!(
                "zone `{name}` has no contactor node"
            )));
        }
        for &n in &zone.contactor {
            check_node(s, name, n)?;
        }
        let areas = zone_areas(s, zone)?;
        match &zone.target {
            Target::Rigid(obstacle) => {
                for (k, &node) in zone.contactor.iter().enumerate() {
                    let x = s.node_position(node);
                    if let Some(p) = obstacle.project(x) {
                        out.push(Candidate {
                            zone: z,
                            node,
                            targets: [None, None],
                            normal: p.normal,
                            tangent: p.tangent(),
                            gap0: p.gap,
                            point: p.point,
                            area: areas[k],
                        });
                    }
                }
            }
            Target::NodePairs { nodes, normal } => {
                if nodes.len() != zone.contactor.len() {
                    return Err(SolverError::InvalidGeometry(format!(
                        "zone `{name}`: {} contactor nodes but {} target nodes",
                        zone.contactor.len(),
                        nodes.len()
                    )));
                }
                for &n in nodes {
                    check_node(s, name, n)?;
                }
                let fixed = normal.map(|n| unit(n, name)).transpose()?;
                if fixed.is_none() && nodes.len() < 2 {
                    return Err(SolverError::InvalidGeometry(format!(
                        "zone `{name}`: a single pair needs an explicit normal"
                    )));
                }
                for (k, (&node, &target)) in zone.contactor.iter().zip(nodes).enumerate() {
                    let n = match fixed {
                        Some(n) => n,
                        None => {
                            let a = nodes[k.saturating_sub(1)];
                            let b = nodes[(k + 1).min(nodes.len() - 1)];
                            let t = unit(sub(s.node_position(b), s.node_position(a)), name)?;
                            left_normal(t)
                        }
                    };
                    let xt = s.node_position(target);
                    out.push(Candidate {
                        zone: z,
                        node,
                        targets: [Some((target, 1.0)), None],
                        normal: n,
                        tangent: [n[1], -n[0]],
                        gap0: dot(n, sub(s.node_position(node), xt)),
                        point: xt,
                        area: areas[k],
                    });
                }
            }
            Target::Segments(surface) => {
                if surface.len() < 2 {
                    return Err(SolverError::InvalidGeometry(format!(
                        "zone `{name}`: a target polyline needs at least two nodes"
                    )));
                }
                for &n in surface {
                    check_node(s, name, n)?;
                }
                for (k, &node) in zone.contactor.iter().enumerate() {
                    if let Some(c) = project_on_polyline(s, surface, node, name)? {
                        out.push(Candidate {
                            zone: z,
                            area: areas[k],
                            ..c
                        });
                    }
                }
            }
        }
    }
    Ok(out)
}

/// The tributary areas of a zone's contactor nodes: given, or lumped along the polyline.
fn zone_areas<S: Structure + ?Sized, L>(
    s: &S,
    zone: &ContactZone<L>,
) -> Result<Vec<f64>, SolverError> {
    let nodes = &zone.contactor;
    if let Some(a) = &zone.areas {
        if a.len() != nodes.len() {
            return Err(SolverError::InvalidGeometry(format!(
                "zone `{}`: {} areas for {} contactor nodes",
                zone.name,
                a.len(),
                nodes.len()
            )));
        }
        if let Some(bad) = a.iter().find(|x| !(x.is_finite() && **x >= 0.0)) {
            return Err(SolverError::InvalidSetting {
                what: "area",
                value: *bad,
                expected: "a finite area >= 0",
            });
        }
        return Ok(a.clone());
    }
    Ok(lumped_areas(s, nodes, false))
}

/// The tributary areas of `nodes` taken as a polyline in their order, as a zone without
/// [`areas`](ContactZone::areas) gets them: each node takes half of each segment next to it,
/// weighted at its own position (`× r` in axisymmetry, `× thickness` in plane stress, 1 per
/// unit thickness in plane strain). `closed`: the polyline also runs from the last node back
/// to the first (the nodes of a closed curve, each listed once). On the nodes of a P2 curve in
/// their order along it (corner, mid-side, corner, …) the areas sum to the curve's length
/// (plane strain). A single node gets 1.
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
    let index: std::collections::HashMap<usize, usize> =
        nodes.iter().enumerate().map(|(k, &n)| (n, k)).collect();
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

/// Closest point of `node` on the polyline: the segment of smallest `|gap|` among those it
/// projects on orthogonally, else the closest interior vertex (normal: mean of its two
/// segments' normals). `None` if it projects nowhere (beyond both ends).
fn project_on_polyline<S: Structure + ?Sized>(
    s: &S,
    surface: &[usize],
    node: usize,
    name: &str,
) -> Result<Option<Candidate>, SolverError> {
    let p = s.node_position(node);
    let mut best: Option<(f64, Candidate)> = None;
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
        let t = unit(d, name)?;
        let n = left_normal(t);
        let point = [a[0] + xi * d[0], a[1] + xi * d[1]];
        let gap = dot(n, sub(p, point));
        if best.as_ref().is_none_or(|(g, _)| gap.abs() < *g) {
            best = Some((
                gap.abs(),
                Candidate {
                    zone: 0,
                    node,
                    targets: [Some((seg[0], 1.0 - xi)), Some((seg[1], xi))],
                    normal: n,
                    tangent: [n[1], -n[0]],
                    gap0: gap,
                    point,
                    area: 0.0,
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
            let na = left_normal(unit(sub(v, s.node_position(surface[prev])), name)?);
            let nb = left_normal(unit(sub(s.node_position(surface[next]), v), name)?);
            let n = unit([na[0] + nb[0], na[1] + nb[1]], name)?;
            let d = dist[0].hypot(dist[1]);
            // only in the vertex's own region: past the end of the previous segment and before
            // the start of the next one
            let before = sub(v, s.node_position(surface[prev]));
            let after = sub(s.node_position(surface[next]), v);
            let in_wedge = dot(dist, before) > 0.0 && dot(dist, after) < 0.0;
            if in_wedge && surface[k] != node && best.as_ref().is_none_or(|(g, _)| d < *g) {
                best = Some((
                    d,
                    Candidate {
                        zone: 0,
                        node,
                        targets: [Some((surface[k], 1.0)), None],
                        normal: n,
                        tangent: [n[1], -n[0]],
                        gap0: dot(n, dist),
                        point: v,
                        area: 0.0,
                    },
                ));
            }
        }
    }
    Ok(best.map(|(_, c)| c))
}
