//! Contact zones (seed 5.5) and obstacle recognition (5.5.6), one for 2D and 3D.
//!
//! A [`ContactZone`] is a set of *contactor* nodes facing a [`Target`] — a rigid
//! [`Obstacle`], the nodes of another body paired one to one (matching interfaces such as the
//! pile–soil shaft), or the surface of another body (node-to-segment on a [`Polyline`] in 2D,
//! node-to-face on a [`TriSurface`](crate::coupling::solid::TriSurface) in 3D) — with its law
//! and its alert distance `Δx`.
//!
//! Recognition happens once, on the reference configuration (small displacements, as the
//! seed's quasi-static setting): every contactor node gets its closest target point, the
//! local frame `(n, t)` in 2D or `(n, t₁, t₂)` in 3D
//! ([`ContactSpace::frame`]), the initial gap `g₀`, and the rows of `H` that map the
//! structure's displacements to the local relative displacement
//!
//! ```text
//! u_rel = u_contactor − Σ_k w_k u_target,k   (w = 1 for a pair, (1 − ξ, ξ) on a segment,
//!                                             N_k(ξ, η) on a face)
//! x_n = g₀ + n·u_rel   (the gap, ≥ 0 open),   u_t = t·u_rel   (each tangent)
//! ```
//! At each step, a candidate becomes a contact element (enters the reduced problem) only when
//! its gap at the start of the step or under the free response is within `Δx`, or while it is
//! adhesive (β > 0). See [`crate::coupling::simulation`].
//!
//! What stays per dimension is geometry: the obstacles' shapes, the frames and the target
//! surfaces ([`TargetSurface`]), with the dimension's rules in [`ContactSpace`].

use crate::coupling::obstacle::Obstacle;
use crate::coupling::space::{ContactSpace, dot, sub, unit};
use crate::error::SolverError;
use fem_core::{Dim, Structure};
use std::collections::HashMap;
use std::fmt::Debug;
use std::sync::Arc;

mod candidate;
mod polyline;

pub use candidate::Candidate;
pub use polyline::{Polyline, lumped_areas, segment_areas};

/// The most target nodes of one candidate (a 6-node face).
pub const MAX_TARGETS: usize = 6;

/// A contactor node's target on a deformable surface: the target nodes and their weights, the
/// target point, the unit normal (from the target towards the contactor) and the signed gap.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Projection<const D: usize> {
    /// Target nodes and weights (the unused slots `None`).
    pub targets: [Option<(usize, f64)>; MAX_TARGETS],
    /// The target point.
    pub point: [f64; D],
    /// Unit normal at the point, towards the contactor.
    pub normal: [f64; D],
    /// Signed gap `n·(p − point)`.
    pub gap: f64,
}

/// The surface of a deformable target: what recognition asks of the segments of a 2D
/// [`Polyline`] and of the faces of a 3D [`TriSurface`](crate::coupling::solid::TriSurface).
pub trait TargetSurface<const D: usize>: Clone + Debug + Send + Sync + 'static {
    /// Checks the surface against the structure (its nodes exist, it has enough of them).
    ///
    /// # Errors
    /// [`SolverError::InvalidGeometry`] naming the zone.
    fn check<S: Structure<D> + ?Sized>(&self, s: &S, zone: &str) -> Result<(), SolverError>;

    /// The target of each of `nodes` (reference configuration), `None` for a node that
    /// projects nowhere on the surface.
    ///
    /// # Errors
    /// [`SolverError::InvalidGeometry`] naming the zone for a degenerate surface.
    fn project_all<S: Structure<D> + ?Sized>(
        &self,
        s: &S,
        zone: &str,
        nodes: &[usize],
    ) -> Result<Vec<Option<Projection<D>>>, SolverError>;

    /// The unit normal of the surface at each of its nodes (the mean of the normals of the
    /// segments or faces around it, weighted by their size); a node whose normals cancel has
    /// none.
    fn node_normals<S: Structure<D> + ?Sized>(&self, s: &S) -> HashMap<usize, [f64; D]>;
}

/// The normals of a node-pair zone.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub enum PairNormals<const D: usize = 2>
where
    Dim<D>: ContactSpace<D>,
{
    /// One normal for every pair (normalised on use), from the target body to the contactor.
    Fixed([f64; D]),
    /// One normal per pair (normalised on use).
    PerPair(Vec<[f64; D]>),
    /// The target body's outward normal at each target node, averaged over the segments or
    /// faces of this surface around it (oriented outward of the target body).
    Surface(<Dim<D> as ContactSpace<D>>::Surface),
    /// In 2D, the target nodes taken as a polyline in the given order, with the contactor on
    /// the left (`n = (−t_y, t_x)`, `t` along the chord of the neighbouring target nodes);
    /// refused in 3D ([`ContactSpace::normals_from_targets`]).
    FromTargets,
}

impl From<Option<[f64; 2]>> for PairNormals<2> {
    /// `Some(n)`: [`PairNormals::Fixed`]; `None`: [`PairNormals::FromTargets`].
    fn from(normal: Option<[f64; 2]>) -> Self {
        normal.map_or(Self::FromTargets, Self::Fixed)
    }
}

/// What the contactor nodes of a zone face.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub enum Target<const D: usize = 2>
where
    Dim<D>: ContactSpace<D>,
{
    /// A rigid obstacle (LINE, ARC; plane, sphere, cylinder; or your own [`Obstacle`]).
    Rigid(Arc<dyn Obstacle<D>>),
    /// Node-to-node: `nodes[i]` is the target of contactor node `i` (matching meshes).
    NodePairs {
        /// Target node of each contactor node.
        nodes: Vec<usize>,
        /// The pairs' normals, from the target body to the contactor.
        normals: PairNormals<D>,
    },
    /// Node-to-surface: the segments of a [`Polyline`] (2D) or the triangles of a
    /// [`TriSurface`](crate::coupling::solid::TriSurface) (3D) of another body.
    Surface(<Dim<D> as ContactSpace<D>>::Surface),
}

/// One contact zone: contactor nodes, target, law and alert distance.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct ContactZone<L, const D: usize = 2>
where
    Dim<D>: ContactSpace<D>,
{
    /// A name for reports and errors.
    pub name: String,
    /// The contactor nodes.
    pub contactor: Vec<usize>,
    /// What they face.
    pub target: Target<D>,
    /// The interface law.
    pub law: L,
    /// Alert distance `Δx ≥ 0`: candidates farther than this are left out of the step.
    pub alert_distance: f64,
    /// Tributary area of each contactor node (same order as `contactor`), which turns the
    /// law's per-area adhesive stiffness into nodal springs and reactions into pressures.
    /// `None`: in 2D lumped from the contactor nodes taken as a polyline in the given order
    /// ([`lumped_areas`]: length × thickness in plane problems, length × radius per radian in
    /// axisymmetry); in 3D 1 per node (an adhesive 3D zone then is refused). Set it with
    /// [`ContactZone::with_areas`], e.g. with consistent P2 weights or the `∫ N_i dA` of
    /// [`SolidMesh::nodal_areas`](fem_core::solid::SolidMesh::nodal_areas).
    pub areas: Option<Vec<f64>>,
}

impl<L, const D: usize> ContactZone<L, D>
where
    Dim<D>: ContactSpace<D>,
{
    /// A zone facing `target`.
    pub fn new(
        name: impl Into<String>,
        contactor: Vec<usize>,
        target: Target<D>,
        law: L,
        alert_distance: f64,
    ) -> Self {
        Self {
            name: name.into(),
            contactor,
            target,
            law,
            alert_distance,
            areas: None,
        }
    }

    /// Sets the tributary area of each contactor node (same order as `contactor`).
    #[must_use]
    pub fn with_areas(mut self, areas: Vec<f64>) -> Self {
        self.areas = Some(areas);
        self
    }

    /// A zone facing a rigid obstacle.
    pub fn rigid(
        name: impl Into<String>,
        contactor: Vec<usize>,
        obstacle: impl Obstacle<D> + 'static,
        law: L,
        alert_distance: f64,
    ) -> Self {
        let target = Target::Rigid(Arc::new(obstacle));
        Self::new(name, contactor, target, law, alert_distance)
    }

    /// A node-to-node zone: `targets[i]` faces `contactor[i]`; in 2D `normals` may be an
    /// `Option<[f64; 2]>` (a fixed normal, or `None` for [`PairNormals::FromTargets`]).
    pub fn node_pairs(
        name: impl Into<String>,
        contactor: Vec<usize>,
        targets: Vec<usize>,
        normals: impl Into<PairNormals<D>>,
        law: L,
        alert_distance: f64,
    ) -> Self {
        let target = Target::NodePairs {
            nodes: targets,
            normals: normals.into(),
        };
        Self::new(name, contactor, target, law, alert_distance)
    }

    /// A node-to-surface zone: the contactor nodes against the segments or faces of
    /// `surface`.
    pub fn on_surface(
        name: impl Into<String>,
        contactor: Vec<usize>,
        surface: <Dim<D> as ContactSpace<D>>::Surface,
        law: L,
        alert_distance: f64,
    ) -> Self {
        let target = Target::Surface(surface);
        Self::new(name, contactor, target, law, alert_distance)
    }

    /// This zone without the contactor nodes of `leave_out` (their paired target nodes, pair
    /// normals and areas go with them): e.g. the nodes [`supported_contactors`] finds, which
    /// cannot take part in contact.
    #[must_use]
    pub fn without_contactors(mut self, leave_out: &[usize]) -> Self {
        let keep: Vec<bool> = self
            .contactor
            .iter()
            .map(|n| !leave_out.contains(n))
            .collect();
        fn retain<T>(v: &mut Vec<T>, keep: &[bool]) {
            if v.len() == keep.len() {
                let mut k = keep.iter();
                v.retain(|_| *k.next().unwrap_or(&true));
            }
        }
        if let Target::NodePairs { nodes, normals } = &mut self.target {
            retain(nodes, &keep);
            if let PairNormals::PerPair(n) = normals {
                retain(n, &keep);
            }
        }
        if let Some(a) = &mut self.areas {
            retain(a, &keep);
        }
        retain(&mut self.contactor, &keep);
        self
    }
}

impl<L> ContactZone<L, 2> {
    /// A node-to-segment zone facing the polyline through `surface` (in order, contactor on
    /// its left).
    pub fn node_to_segment(
        name: impl Into<String>,
        contactor: Vec<usize>,
        surface: Vec<usize>,
        law: L,
        alert_distance: f64,
    ) -> Self {
        Self::on_surface(name, contactor, Polyline::new(surface), law, alert_distance)
    }
}

impl<L> ContactZone<L, 3> {
    /// A node-to-face zone: the contactor nodes against the triangles of `surface`.
    pub fn node_to_face(
        name: impl Into<String>,
        contactor: Vec<usize>,
        surface: crate::coupling::solid::TriSurface,
        law: L,
        alert_distance: f64,
    ) -> Self {
        Self::on_surface(name, contactor, surface, law, alert_distance)
    }
}

pub(crate) fn check_node<const D: usize, S: Structure<D> + ?Sized>(
    s: &S,
    zone: &str,
    node: usize,
) -> Result<(), SolverError> {
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

/// `(x, y)` or `(x, y, z)`, each coordinate with `f`.
fn tuple<const D: usize>(x: [f64; D], f: impl Fn(f64) -> String) -> String {
    let each: Vec<String> = x.into_iter().map(f).collect();
    format!("({})", each.join(", "))
}

/// Physical checks of the rigid zones after [`recognize`], where the sign of a gap alone is
/// ambiguous (run by [`ContactSimulation::new`](crate::ContactSimulation::new)):
/// - every rigid zone has at least one candidate (a zone whose contactor nodes all miss the
///   obstacle would never act: recognition is done once, on the reference configuration);
/// - the obstacle is not degenerate: its [`extent`](crate::Obstacle::extent), where it has
///   one, is at least [`DEGENERATE_TARGET`] times the diagonal of the contactor's bounding box;
/// - the obstacle faces the body: at the candidate closest to it (smallest `|g₀|`), the
///   body's own [outward normal](fem_core::Structure::outward_normal), where the structure
///   knows it, must point against the obstacle's normal (`n_body · n_obstacle ≤ 0`). A LINE
///   given from `b` to `a` while the body touches it has gaps of 0 on the wrong side: without
///   this check the body would fall through.
///
/// # Errors
/// [`SolverError::InvalidGeometry`] naming the zone (and the node) for each case.
pub fn check_rigid_targets<S, L, const D: usize>(
    s: &S,
    zones: &[ContactZone<L, D>],
    candidates: &[Candidate<D>],
) -> Result<(), SolverError>
where
    S: Structure<D> + ?Sized,
    Dim<D>: ContactSpace<D>,
{
    for (z, zone) in zones.iter().enumerate() {
        let Target::Rigid(obstacle) = &zone.target else {
            continue;
        };
        let name = zone.name.as_str();
        let mine: Vec<&Candidate<D>> = candidates.iter().filter(|c| c.zone == z).collect();
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
            let (mut lo, mut hi) = ([f64::INFINITY; D], [f64::NEG_INFINITY; D]);
            for &n in &zone.contactor {
                let x = s.node_position(n);
                for k in 0..D {
                    lo[k] = lo[k].min(x[k]);
                    hi[k] = hi[k].max(x[k]);
                }
            }
            let d = sub(hi, lo);
            let size = if D == 2 {
                d[0].hypot(d[1])
            } else {
                dot(d, d).sqrt()
            };
            if extent < DEGENERATE_TARGET * size {
                return Err(SolverError::InvalidGeometry(format!(
                    "zone `{name}`: its obstacle is {extent:e} long, less than \
                     {DEGENERATE_TARGET:e} of the contactor's extent {size:e}: a degenerate target"
                )));
            }
        }
        if let Some(outward) = s.outward_normal(closest.node) {
            let n = closest.normal();
            if dot(outward, n) > 0.0 {
                let x = s.node_position(closest.node);
                return Err(SolverError::InvalidGeometry(format!(
                    "zone `{name}`: contactor node {} at {} faces away from its obstacle \
                     (the body's outward normal {}, the obstacle's normal towards \
                     the contactor {}): the obstacle is given on the wrong side (a \
                     LINE has the contactor on its left, from a to b; an ARC has its side)",
                    closest.node,
                    tuple(x, |v| v.to_string()),
                    tuple(outward, |v| format!("{v:.3}")),
                    tuple(n, |v| format!("{v:.3}")),
                )));
            }
        }
    }
    Ok(())
}

/// The contactor nodes of `zones` that a support holds along their contact normal: their
/// normal displacement relative to the target is prescribed (no free dof along it, see
/// [`ContactSpace::HELD`]), so they cannot take part in contact and the simulations refuse
/// them. `(zone, node)`, in recognition order (zone, then contactor).
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
pub fn supported_contactors<S, L, const D: usize>(
    structure: &S,
    zones: &[ContactZone<L, D>],
) -> Result<Vec<(usize, usize)>, SolverError>
where
    S: Structure<D> + ?Sized,
    Dim<D>: ContactSpace<D>,
{
    Ok(recognize(structure, zones)?
        .iter()
        .filter(|c| c.held_along_normal(structure))
        .map(|c| (c.zone, c.node))
        .collect())
}

/// The checks the 3D simulation runs after [`recognize`] (the 2D one runs
/// [`check_rigid_targets`] and refuses a held candidate when it builds `H`): every zone has a
/// candidate, and none is held along its normal ([`supported_contactors`]).
///
/// # Errors
/// [`SolverError::InvalidGeometry`] naming the zone (and the node).
pub fn check_candidates<S, L, const D: usize>(
    structure: &S,
    zones: &[ContactZone<L, D>],
    candidates: &[Candidate<D>],
) -> Result<(), SolverError>
where
    S: Structure<D> + ?Sized,
    Dim<D>: ContactSpace<D>,
{
    for (z, zone) in zones.iter().enumerate() {
        if !candidates.iter().any(|c| c.zone == z) {
            return Err(SolverError::InvalidGeometry(format!(
                "zone `{}` has no candidate: none of its {} nodes projects on its target",
                zone.name,
                zone.contactor.len()
            )));
        }
    }
    if let Some(c) = candidates.iter().find(|c| c.held_along_normal(structure)) {
        return Err(SolverError::InvalidGeometry(format!(
            "zone `{}`: node {} cannot move along the contact normal {:?} relative to its \
             target (every component along it is prescribed)",
            zones[c.zone].name,
            c.node,
            c.normal()
        )));
    }
    Ok(())
}

/// Obstacle recognition on the reference configuration: the candidates of every zone, in zone
/// order then contactor order. Contactor nodes with no projection on their target are not
/// candidates.
///
/// # Errors
/// [`SolverError::InvalidGeometry`] for an empty zone, a node out of range, mismatched pair
/// lists, a target surface that is too small or degenerate, or a degenerate normal;
/// [`SolverError::InvalidSetting`] for a negative or non-finite alert distance or area, or
/// areas of the wrong length.
pub fn recognize<S, L, const D: usize>(
    s: &S,
    zones: &[ContactZone<L, D>],
) -> Result<Vec<Candidate<D>>, SolverError>
where
    S: Structure<D> + ?Sized,
    Dim<D>: ContactSpace<D>,
{
    let mut out = Vec::new();
    for (z, zone) in zones.iter().enumerate() {
        let name = zone.name.as_str();
        if !(zone.alert_distance >= 0.0 && zone.alert_distance.is_finite()) {
            return Err(SolverError::InvalidSetting {
                what: "alert distance",
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
        let mut push = |k: usize, node: usize, p: Projection<D>| {
            out.push(Candidate::new(z, node, p, areas[k]));
        };
        match &zone.target {
            Target::Rigid(obstacle) => {
                for (k, &node) in zone.contactor.iter().enumerate() {
                    if let Some(p) = obstacle.project(s.node_position(node)) {
                        let projection = Projection {
                            targets: [None; MAX_TARGETS],
                            point: p.point,
                            normal: p.normal,
                            gap: p.gap,
                        };
                        push(k, node, projection);
                    }
                }
            }
            Target::NodePairs { nodes, normals } => {
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
                let normals = pair_normals(s, name, nodes, normals)?;
                for (k, ((&node, &target), n)) in
                    zone.contactor.iter().zip(nodes).zip(normals).enumerate()
                {
                    let xt = s.node_position(target);
                    let mut targets = [None; MAX_TARGETS];
                    targets[0] = Some((target, 1.0));
                    let gap = dot(n, sub(s.node_position(node), xt));
                    push(
                        k,
                        node,
                        Projection {
                            targets,
                            point: xt,
                            normal: n,
                            gap,
                        },
                    );
                }
            }
            Target::Surface(surface) => {
                surface.check(s, name)?;
                let hits = surface.project_all(s, name, &zone.contactor)?;
                for (k, (&node, hit)) in zone.contactor.iter().zip(hits).enumerate() {
                    if let Some(p) = hit {
                        push(k, node, p);
                    }
                }
            }
        }
    }
    Ok(out)
}

/// The unit normal of each pair of a node-pair zone.
fn pair_normals<S, const D: usize>(
    s: &S,
    name: &str,
    nodes: &[usize],
    normals: &PairNormals<D>,
) -> Result<Vec<[f64; D]>, SolverError>
where
    S: Structure<D> + ?Sized,
    Dim<D>: ContactSpace<D>,
{
    match normals {
        PairNormals::Fixed(n) => Ok(vec![unit(name, *n)?; nodes.len()]),
        PairNormals::PerPair(v) => {
            if v.len() != nodes.len() {
                return Err(SolverError::InvalidGeometry(format!(
                    "zone `{name}`: {} normals for {} pairs",
                    v.len(),
                    nodes.len()
                )));
            }
            v.iter().map(|n| unit(name, *n)).collect()
        }
        PairNormals::Surface(surface) => {
            surface.check(s, name)?;
            let map = surface.node_normals(s);
            nodes
                .iter()
                .map(|target| {
                    map.get(target).copied().ok_or_else(|| {
                        SolverError::InvalidGeometry(format!(
                            "zone `{name}`: target node {target} is on no face of the zone's \
                             normal surface (or its normals cancel)"
                        ))
                    })
                })
                .collect()
        }
        PairNormals::FromTargets => {
            <Dim<D> as ContactSpace<D>>::normals_from_targets(s, name, nodes)
        }
    }
}

/// The tributary areas of a zone's contactor nodes: given (and checked), or the dimension's
/// default ([`ContactSpace::default_areas`]).
fn zone_areas<S, L, const D: usize>(
    s: &S,
    zone: &ContactZone<L, D>,
) -> Result<Vec<f64>, SolverError>
where
    S: Structure<D> + ?Sized,
    Dim<D>: ContactSpace<D>,
{
    let nodes = &zone.contactor;
    let Some(a) = &zone.areas else {
        return Ok(<Dim<D> as ContactSpace<D>>::default_areas(s, nodes));
    };
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
    Ok(a.clone())
}
