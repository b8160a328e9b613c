//! Contact zones in 3D and their candidates: nodes of a body against a rigid [`Obstacle3`].

use super::obstacle::{Obstacle3, tangent_frame};
use crate::error::SolverError;
use fem_core::Structure;
use std::sync::Arc;

/// A 3D contact zone: contactor nodes against a rigid obstacle, with one law.
#[derive(Clone, Debug)]
pub struct ContactZone3<L> {
    /// Name, for reports and errors.
    pub name: String,
    /// Contactor nodes.
    pub nodes: Vec<usize>,
    /// The rigid target.
    pub obstacle: Arc<dyn Obstacle3>,
    /// The contact law of every node of the zone.
    pub law: L,
    /// Alert distance `≥ 0`: a node is active in a step when its gap under the free response
    /// is below it (or it was in contact at the end of the last step).
    pub alert: f64,
    /// Tributary area of each node (same order as `nodes`), for pressures in the reports;
    /// `None`: every node counts 1 (the reports' pressure is then the nodal force).
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
        Self {
            name: name.to_string(),
            nodes,
            obstacle: Arc::new(obstacle),
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
}

/// A contactor node of a 3D zone, its frame and initial gap (reference configuration).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Candidate3 {
    /// Zone index.
    pub zone: usize,
    /// Contactor node.
    pub node: usize,
    /// Unit normal, from the obstacle towards the contactor.
    pub normal: [f64; 3],
    /// First tangent ([`tangent_frame`]).
    pub t1: [f64; 3],
    /// Second tangent, `n × t₁`.
    pub t2: [f64; 3],
    /// Initial gap.
    pub gap0: f64,
    /// The obstacle's closest point in the reference configuration.
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
}

/// The candidates of `zones` on `structure`: every zone node that projects on its obstacle.
///
/// # Errors
/// [`SolverError::InvalidGeometry`] for an unknown node, a node with no free dof along the
/// normal, or a zone without a single candidate; [`SolverError::InvalidSetting`] for a
/// negative or non-finite alert distance or area, or areas of the wrong length.
pub fn recognize_3d<S: Structure<3> + ?Sized, L>(
    structure: &S,
    zones: &[ContactZone3<L>],
) -> Result<Vec<Candidate3>, SolverError> {
    let mut out = Vec::new();
    for (z, zone) in zones.iter().enumerate() {
        if !(zone.alert >= 0.0 && zone.alert.is_finite()) {
            return Err(SolverError::InvalidSetting {
                what: "alert distance",
                value: zone.alert,
                expected: "a finite distance >= 0",
            });
        }
        if let Some(a) = &zone.areas {
            if a.len() != zone.nodes.len() {
                return Err(SolverError::InvalidGeometry(format!(
                    "zone `{}`: {} areas for {} nodes",
                    zone.name,
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
        let before = out.len();
        for (k, &node) in zone.nodes.iter().enumerate() {
            if node >= structure.node_count() {
                return Err(SolverError::InvalidGeometry(format!(
                    "zone `{}`: node {node} does not exist (the structure has {} nodes)",
                    zone.name,
                    structure.node_count()
                )));
            }
            let x = structure.node_position(node);
            let Some(p) = zone.obstacle.project(x) else {
                continue;
            };
            let dofs = structure.node_dofs(node);
            let along: f64 = (0..3)
                .filter(|&c| dofs[c].is_some())
                .map(|c| p.normal[c] * p.normal[c])
                .sum();
            if along < 1e-24 {
                return Err(SolverError::InvalidGeometry(format!(
                    "zone `{}`: node {node} cannot move along the contact normal {:?} (its \
                     components along it are prescribed)",
                    zone.name, p.normal
                )));
            }
            let (t1, t2) = tangent_frame(p.normal);
            out.push(Candidate3 {
                zone: z,
                node,
                normal: p.normal,
                t1,
                t2,
                gap0: p.gap,
                point: p.point,
                area: zone.areas.as_ref().map_or(1.0, |a| a[k]),
            });
        }
        if out.len() == before {
            return Err(SolverError::InvalidGeometry(format!(
                "zone `{}` has no candidate: none of its {} nodes projects on its obstacle",
                zone.name,
                zone.nodes.len()
            )));
        }
    }
    Ok(out)
}
