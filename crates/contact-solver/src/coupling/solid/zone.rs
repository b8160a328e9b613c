//! Contact zones in 3D and their candidates: nodes of a body against a rigid [`Obstacle3`],
//! against the nodes of another body paired one to one (matching interfaces), or against
//! another body's triangle faces (node-to-face, [`TriSurface`]).
//!
//! Recognition happens once, on the reference configuration (small displacements, as in 2D):
//! every contactor node gets its target point, its frame `(n, t₁, t₂)` (`n` from the target
//! towards the contactor, the tangents from [`tangent_frame`]), its initial gap `g₀` and the
//! weights of its target nodes, so that
//!
//! ```text
//! u_rel = u_contactor − Σ_k w_k u_target,k     (w = 1 for a pair, N_k(ξ, η) on a face)
//! x_n = g₀ + n·u_rel,   u_t1 = t₁·u_rel,   u_t2 = t₂·u_rel
//! ```
//!
//! The tributary area of a contactor node (for pressures and for the adhesive springs of an
//! RCCM interface) is given with [`ContactZone3::with_areas`], e.g. the consistent
//! `∫ N_i dA` of [`SolidMesh::nodal_areas`](fem_core::solid::SolidMesh::nodal_areas) over the
//! contactor's own face set; a zone without areas counts 1 per node, and an adhesive zone
//! without them is refused.

use super::obstacle::{Obstacle3, tangent_frame};
use super::surface::{Topology, TriSurface, node_normals, project_on_surface};
use crate::error::SolverError;
use fem_core::Structure;
use std::sync::Arc;

/// The normals of a node-pair zone.
#[derive(Clone, Debug)]
pub enum PairNormals3 {
    /// One normal for every pair (normalised on use), from the target body to the contactor.
    Fixed([f64; 3]),
    /// One normal per pair (normalised on use).
    PerPair(Vec<[f64; 3]>),
    /// The target body's outward normal at each target node, averaged over the faces of this
    /// surface around it (its faces oriented outward of the target body).
    Surface(TriSurface),
}

/// What the contactor nodes of a 3D zone face.
#[derive(Clone, Debug)]
pub enum Target3 {
    /// A rigid obstacle.
    Rigid(Arc<dyn Obstacle3>),
    /// Node-to-node: `nodes[i]` is the target of contactor node `i` (matching meshes).
    NodePairs {
        /// Target node of each contactor node.
        nodes: Vec<usize>,
        /// The pairs' normals.
        normals: PairNormals3,
    },
    /// Node-to-face: the triangles of another body's boundary.
    Faces(TriSurface),
}

/// A 3D contact zone: contactor nodes facing a [`Target3`], with one law.
#[derive(Clone, Debug)]
pub struct ContactZone3<L> {
    /// Name, for reports and errors.
    pub name: String,
    /// Contactor nodes.
    pub nodes: Vec<usize>,
    /// What they face.
    pub target: Target3,
    /// The contact law of every node of the zone.
    pub law: L,
    /// Alert distance `≥ 0`: a node is active in a step when its gap under the free response
    /// is below it (or it was in contact at the end of the last step, or it is adhesive).
    pub alert: f64,
    /// Tributary area of each node (same order as `nodes`), for pressures in the reports and
    /// the adhesive springs; `None`: every node counts 1 (the reports' pressure is then the
    /// nodal force; an adhesive law then is refused).
    pub areas: Option<Vec<f64>>,
}

impl<L> ContactZone3<L> {
    /// Nodes against a rigid obstacle.
    pub fn rigid(
        name: &str,
        nodes: Vec<usize>,
        obstacle: impl Obstacle3 + 'static,
        law: L,
        alert: f64,
    ) -> Self {
        Self::with_target(name, nodes, Target3::Rigid(Arc::new(obstacle)), law, alert)
    }

    /// Node-to-node: `targets[i]` faces `nodes[i]`.
    pub fn node_pairs(
        name: &str,
        nodes: Vec<usize>,
        targets: Vec<usize>,
        normals: PairNormals3,
        law: L,
        alert: f64,
    ) -> Self {
        let target = Target3::NodePairs {
            nodes: targets,
            normals,
        };
        Self::with_target(name, nodes, target, law, alert)
    }

    /// Node-to-face: the contactor nodes against the triangles of `surface`.
    pub fn node_to_face(
        name: &str,
        nodes: Vec<usize>,
        surface: TriSurface,
        law: L,
        alert: f64,
    ) -> Self {
        Self::with_target(name, nodes, Target3::Faces(surface), law, alert)
    }

    fn with_target(name: &str, nodes: Vec<usize>, target: Target3, law: L, alert: f64) -> Self {
        Self {
            name: name.to_string(),
            nodes,
            target,
            law,
            alert,
            areas: None,
        }
    }

    /// The zone with tributary areas (one per node, e.g. from
    /// [`SolidMesh::nodal_areas`](fem_core::solid::SolidMesh::nodal_areas)).
    #[must_use]
    pub fn with_areas(mut self, areas: Vec<f64>) -> Self {
        self.areas = Some(areas);
        self
    }

    /// This zone without the contactor nodes of `leave_out` (their paired target nodes, pair
    /// normals and areas go with them): e.g. the nodes [`supported_contactors_3d`] finds,
    /// which cannot take part in contact.
    #[must_use]
    pub fn without_contactors(mut self, leave_out: &[usize]) -> Self {
        let keep: Vec<bool> = self.nodes.iter().map(|n| !leave_out.contains(n)).collect();
        fn retain<T>(v: &mut Vec<T>, keep: &[bool]) {
            if v.len() == keep.len() {
                let mut k = keep.iter();
                v.retain(|_| *k.next().unwrap_or(&true));
            }
        }
        if let Target3::NodePairs { nodes, normals } = &mut self.target {
            retain(nodes, &keep);
            if let PairNormals3::PerPair(n) = normals {
                retain(n, &keep);
            }
        }
        if let Some(a) = &mut self.areas {
            retain(a, &keep);
        }
        retain(&mut self.nodes, &keep);
        self
    }
}

/// The contactor nodes of `zones` that supports hold along their contact normal: every
/// component of their displacement along it, relative to the target, is prescribed, so they
/// cannot take part in contact and [`recognize_3d`] refuses them. `(zone, node)`, in
/// recognition order.
///
/// # Errors
/// As [`recognize_3d`], but for the refusal of these nodes.
pub fn supported_contactors_3d<S: Structure<3> + ?Sized, L>(
    structure: &S,
    zones: &[ContactZone3<L>],
) -> Result<Vec<(usize, usize)>, SolverError> {
    Ok(recognize_all(structure, zones)?
        .iter()
        .filter(|c| held_along_normal(structure, c))
        .map(|c| (c.zone, c.node))
        .collect())
}

/// Whether `c`'s relative displacement along its normal is fully prescribed (its `H` row is
/// empty to round-off).
fn held_along_normal<S: Structure<3> + ?Sized>(structure: &S, c: &Candidate3) -> bool {
    let row = c.h_row(structure, c.normal);
    row.iter().map(|(_, a)| a * a).sum::<f64>() < 1e-24
}

/// A contactor node of a 3D zone, its frame and initial gap (reference configuration).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Candidate3 {
    /// Zone index.
    pub zone: usize,
    /// Contactor node.
    pub node: usize,
    /// Target nodes and their weights (`None` for a rigid obstacle and unused slots).
    pub targets: [Option<(usize, f64)>; 6],
    /// Unit normal, from the target towards the contactor.
    pub normal: [f64; 3],
    /// First tangent ([`tangent_frame`]).
    pub t1: [f64; 3],
    /// Second tangent, `n × t₁`.
    pub t2: [f64; 3],
    /// Initial gap.
    pub gap0: f64,
    /// The target point in the reference configuration.
    pub point: [f64; 3],
    /// Tributary area.
    pub area: f64,
}

impl Candidate3 {
    /// The frame's three directions `(n, t₁, t₂)`.
    #[inline]
    pub fn frame(&self) -> [[f64; 3]; 3] {
        [self.normal, self.t1, self.t2]
    }

    /// The entries `(dof, coefficient)` of this candidate's `H` row along `dir`, on the
    /// structure's free dofs: `dir·u_contactor − Σ w_k dir·u_target,k`. Coefficients below
    /// `1e-14` are round-off (a unit direction's component `cos 90°`, a shape value at a
    /// vertex) and dropped, so a direction held on both sides has an empty row.
    pub(crate) fn h_row<S: Structure<3> + ?Sized>(
        &self,
        s: &S,
        dir: [f64; 3],
    ) -> Vec<(usize, f64)> {
        let mut out = Vec::new();
        let mut push = |node: usize, w: f64| {
            for (c, d) in s.node_dofs(node).into_iter().enumerate() {
                if let Some(i) = d {
                    let a = w * dir[c];
                    if a.abs() > 1e-14 {
                        out.push((i, a));
                    }
                }
            }
        };
        push(self.node, 1.0);
        for &(node, w) in self.targets.iter().flatten() {
            push(node, -w);
        }
        // one entry per dof (a node on both sides cancels)
        out.sort_unstable_by_key(|e| e.0);
        let mut merged: Vec<(usize, f64)> = Vec::with_capacity(out.len());
        for (dof, a) in out {
            match merged.last_mut() {
                Some(last) if last.0 == dof => last.1 += a,
                _ => merged.push((dof, a)),
            }
        }
        merged.retain(|e| e.1.abs() > 1e-14);
        merged
    }

    /// The relative displacement `u_rel` from a nodal displacement lookup.
    pub(crate) fn relative(&self, disp: impl Fn(usize) -> [f64; 3]) -> [f64; 3] {
        let mut u = disp(self.node);
        for &(node, w) in self.targets.iter().flatten() {
            let v = disp(node);
            for a in 0..3 {
                u[a] -= w * v[a];
            }
        }
        u
    }
}

fn unit(zone: &str, v: [f64; 3]) -> Result<[f64; 3], SolverError> {
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if !(l > 0.0 && l.is_finite()) {
        return Err(SolverError::InvalidGeometry(format!(
            "zone `{zone}`: cannot build a unit normal from {v:?}"
        )));
    }
    Ok(v.map(|x| x / l))
}

fn check_node<S: Structure<3> + ?Sized>(s: &S, zone: &str, node: usize) -> Result<(), SolverError> {
    if node >= s.node_count() {
        return Err(SolverError::InvalidGeometry(format!(
            "zone `{zone}`: node {node} does not exist (the structure has {} nodes)",
            s.node_count()
        )));
    }
    Ok(())
}

/// The candidates of `zones` on `structure` (module docs): every contactor node with a target
/// point, in zone order then node order.
///
/// # Errors
/// [`SolverError::InvalidGeometry`] for an unknown node (contactor, target or face), an empty
/// zone, pair lists of different lengths, a degenerate normal, a candidate whose relative
/// normal displacement is prescribed on every side (no free dof along its normal), or a zone
/// without a single candidate; [`SolverError::InvalidSetting`] for a negative or non-finite
/// alert distance or area, or areas of the wrong length.
pub fn recognize_3d<S: Structure<3> + ?Sized, L>(
    structure: &S,
    zones: &[ContactZone3<L>],
) -> Result<Vec<Candidate3>, SolverError> {
    let out = recognize_all(structure, zones)?;
    if let Some(c) = out.iter().find(|c| held_along_normal(structure, c)) {
        return Err(SolverError::InvalidGeometry(format!(
            "zone `{}`: node {} cannot move along the contact normal {:?} relative to its \
             target (every component along it is prescribed)",
            zones[c.zone].name, c.node, c.normal
        )));
    }
    Ok(out)
}

/// [`recognize_3d`] without the refusal of the candidates held along their normal.
fn recognize_all<S: Structure<3> + ?Sized, L>(
    structure: &S,
    zones: &[ContactZone3<L>],
) -> Result<Vec<Candidate3>, SolverError> {
    let mut out = Vec::new();
    for (z, zone) in zones.iter().enumerate() {
        let name = zone.name.as_str();
        if !(zone.alert >= 0.0 && zone.alert.is_finite()) {
            return Err(SolverError::InvalidSetting {
                what: "alert distance",
                value: zone.alert,
                expected: "a finite distance >= 0",
            });
        }
        if zone.nodes.is_empty() {
            return Err(SolverError::InvalidGeometry(format!(
                "zone `{name}` has no contactor node"
            )));
        }
        if let Some(a) = &zone.areas {
            if a.len() != zone.nodes.len() {
                return Err(SolverError::InvalidGeometry(format!(
                    "zone `{name}`: {} areas for {} nodes",
                    a.len(),
                    zone.nodes.len()
                )));
            }
            if let Some(bad) = a.iter().find(|v| !(v.is_finite() && **v >= 0.0)) {
                return Err(SolverError::InvalidSetting {
                    what: "area",
                    value: *bad,
                    expected: "a finite area >= 0",
                });
            }
        }
        for &node in &zone.nodes {
            check_node(structure, name, node)?;
        }
        let area = |k: usize| zone.areas.as_ref().map_or(1.0, |a| a[k]);
        let before = out.len();
        let mut push = |node: usize, k: usize, normal, targets, gap0, point| {
            let (t1, t2) = tangent_frame(normal);
            out.push(Candidate3 {
                zone: z,
                node,
                targets,
                normal,
                t1,
                t2,
                gap0,
                point,
                area: area(k),
            });
        };
        match &zone.target {
            Target3::Rigid(obstacle) => {
                for (k, &node) in zone.nodes.iter().enumerate() {
                    if let Some(p) = obstacle.project(structure.node_position(node)) {
                        push(node, k, p.normal, [None; 6], p.gap, p.point);
                    }
                }
            }
            Target3::NodePairs { nodes, normals } => {
                if nodes.len() != zone.nodes.len() {
                    return Err(SolverError::InvalidGeometry(format!(
                        "zone `{name}`: {} contactor nodes but {} target nodes",
                        zone.nodes.len(),
                        nodes.len()
                    )));
                }
                for &n in nodes {
                    check_node(structure, name, n)?;
                }
                let from_surface = match normals {
                    PairNormals3::Surface(surface) => {
                        check_surface(structure, name, surface)?;
                        Some(node_normals(structure, surface))
                    }
                    PairNormals3::PerPair(v) if v.len() != nodes.len() => {
                        return Err(SolverError::InvalidGeometry(format!(
                            "zone `{name}`: {} normals for {} pairs",
                            v.len(),
                            nodes.len()
                        )));
                    }
                    _ => None,
                };
                for (k, (&node, &target)) in zone.nodes.iter().zip(nodes).enumerate() {
                    let n = match normals {
                        PairNormals3::Fixed(n) => unit(name, *n)?,
                        PairNormals3::PerPair(v) => unit(name, v[k])?,
                        PairNormals3::Surface(_) => {
                            let map = from_surface.as_ref();
                            *map.and_then(|m| m.get(&target)).ok_or_else(|| {
                                SolverError::InvalidGeometry(format!(
                                    "zone `{name}`: target node {target} is on no face of \
                                     the zone's normal surface (or its normals cancel)"
                                ))
                            })?
                        }
                    };
                    let xt = structure.node_position(target);
                    let xc = structure.node_position(node);
                    let d = [xc[0] - xt[0], xc[1] - xt[1], xc[2] - xt[2]];
                    let gap = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
                    let mut targets = [None; 6];
                    targets[0] = Some((target, 1.0));
                    push(node, k, n, targets, gap, xt);
                }
            }
            Target3::Faces(surface) => {
                check_surface(structure, name, surface)?;
                let topo = Topology::new(structure, surface);
                for (k, &node) in zone.nodes.iter().enumerate() {
                    if let Some(h) = project_on_surface(structure, surface, &topo, node) {
                        push(node, k, h.normal, h.targets, h.gap, h.point);
                    }
                }
            }
        }
        if out.len() == before {
            return Err(SolverError::InvalidGeometry(format!(
                "zone `{name}` has no candidate: none of its {} nodes projects on its target",
                zone.nodes.len()
            )));
        }
    }
    Ok(out)
}

fn check_surface<S: Structure<3> + ?Sized>(
    s: &S,
    zone: &str,
    surface: &TriSurface,
) -> Result<(), SolverError> {
    for k in 0..surface.face_count() {
        for &n in surface.face(k) {
            check_node(s, zone, n)?;
        }
    }
    Ok(())
}
