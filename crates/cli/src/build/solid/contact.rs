//! Contact in a 3D scene: `[solver]` as the 3D simulation's settings, the zones' laws and rigid
//! targets (plane, sphere, cylinder) checked, then the zones built on the mesh's sets with
//! their tributary areas ([`zones`], the one place where a zone is made, so that node pairs and
//! node-to-face zones plug in there), their candidates checked, and the simulation made.

use super::super::checks::{finite, node_set, positive, solver_error};
use super::super::contact::ZonePlan;
use super::super::supported::{Policy, point as position_text, resolve};
use crate::error::{CliError, CliResult, KeyPath};
use crate::raw::{RawTarget, triple};
use crate::spec::ArcSideSpec;
use crate::spec3::{Coords, TargetSpec3};
use contact_laws::StandardLaw;
use contact_solver::coupling::solid::{
    Candidate3, ContactZone3, PairNormals3, RigidCylinder, RigidPlane, RigidSphere, Side3,
    SolidContactSimulation, TriSurface, supported_contactors_3d,
};
use contact_solver::{SimulationSettings, SolverError};
use fem_core::solid::{SolidMesh, SolidModel};

/// A target, checked: rigid (built), or another body's nodes or faces (looked up in the mesh
/// at build).
pub(super) enum Obstacle {
    Plane(RigidPlane),
    Sphere(RigidSphere),
    Cylinder(RigidCylinder),
    /// Node pairs by position with the nodes of a set; a fixed normal, or the set's faces'.
    NodePairs {
        set: String,
        normal: Option<[f64; 3]>,
    },
    /// Node-to-face on a face set.
    Faces(String),
}

/// Three finite numbers at `p`.
fn point(p: &KeyPath, c: &Coords) -> CliResult<[f64; 3]> {
    let v = triple(p, c)?;
    for (k, x) in v.iter().enumerate() {
        finite(&p.index(k), *x)?;
    }
    Ok(v)
}

/// A direction at `p`: three finite numbers, not all zero, whose length does not overflow.
fn direction(p: &KeyPath, c: &Coords) -> CliResult<[f64; 3]> {
    let v = point(p, c)?;
    let len = v.iter().map(|x| x * x).sum::<f64>().sqrt();
    if !(len > 0.0 && len.is_finite()) {
        return Err(CliError::at(
            p,
            format!(
                "`{p}` = {v:?}: expected a direction (not [0, 0, 0], and of a length that stays \
                 finite)"
            ),
        ));
    }
    Ok(v)
}

fn side(s: ArcSideSpec) -> Side3 {
    match s {
        ArcSideSpec::Outside => Side3::Outside,
        ArcSideSpec::Inside => Side3::Inside,
    }
}

/// The target of a 3D zone at `tp`, checked and built.
pub(super) fn target(tp: &KeyPath, t: &RawTarget) -> CliResult<Obstacle> {
    let err = |e: SolverError| solver_error(tp, e);
    Ok(match &t.resolve_3d(tp)? {
        TargetSpec3::Plane { point: x, normal } => Obstacle::Plane(
            RigidPlane::new(
                point(&tp.key("point"), x)?,
                direction(&tp.key("normal"), normal)?,
            )
            .map_err(err)?,
        ),
        TargetSpec3::Sphere {
            center,
            radius,
            side: s,
        } => Obstacle::Sphere(
            RigidSphere::new(
                point(&tp.key("center"), center)?,
                positive(&tp.key("radius"), *radius)?,
                side(*s),
            )
            .map_err(err)?,
        ),
        TargetSpec3::Cylinder {
            point: x,
            axis,
            radius,
            side: s,
        } => Obstacle::Cylinder(
            RigidCylinder::new(
                point(&tp.key("point"), x)?,
                direction(&tp.key("axis"), axis)?,
                positive(&tp.key("radius"), *radius)?,
                side(*s),
            )
            .map_err(err)?,
        ),
        TargetSpec3::NodePairs { set, normal } => Obstacle::NodePairs {
            set: set.clone(),
            normal: normal
                .as_ref()
                .map(|n| direction(&tp.key("normal"), n))
                .transpose()?,
        },
        TargetSpec3::Faces { set } => Obstacle::Faces(set.clone()),
    })
}

/// The contact zones on the mesh: each contactor set's nodes, with the consistent nodal areas
/// of its faces when it is a face set (a physical surface; the reports' pressures are then
/// `r_n / A_i`), against its target (rigid, node pairs by position, or faces).
pub(super) fn zones(
    mesh: &SolidMesh,
    plans: &[ZonePlan<Obstacle>],
) -> CliResult<Vec<ContactZone3<StandardLaw>>> {
    let mut out = Vec::with_capacity(plans.len());
    for z in plans {
        let cp = z.path.key("contactor");
        let (nodes, areas) = match mesh.nodal_areas(&z.contactor) {
            Ok((nodes, areas)) => (nodes, Some(areas)),
            Err(_) => (node_set(&cp, mesh, &z.contactor)?, None),
        };
        let (name, l, alert) = (z.name.as_str(), z.law, z.alert);
        let tp = z.path.key("target");
        let surface = |set: &str| {
            TriSurface::from_face_set(mesh, set).map_err(|_| {
                let sp = tp.key("set");
                CliError::at(
                    &sp,
                    format!(
                        "`{sp}` = \"{set}\" is not a face set of the mesh (a physical surface, \
                         or a side of the box): a faces target, and node pairs without a \
                         `normal`, need the target body's faces"
                    ),
                )
            })
        };
        let zone = match &z.target {
            Obstacle::Plane(o) => ContactZone3::rigid(name, nodes, *o, l, alert),
            Obstacle::Sphere(o) => ContactZone3::rigid(name, nodes, *o, l, alert),
            Obstacle::Cylinder(o) => ContactZone3::rigid(name, nodes, *o, l, alert),
            Obstacle::NodePairs { set, normal } => {
                let targets = pair_by_position(mesh, &tp.key("set"), set, &z.contactor, &nodes)?;
                let normals = match normal {
                    Some(n) => PairNormals3::Fixed(*n),
                    None => PairNormals3::Surface(surface(set)?),
                };
                ContactZone3::node_pairs(name, nodes, targets, normals, l, alert)
            }
            Obstacle::Faces(set) => {
                ContactZone3::node_to_face(name, nodes, surface(set)?, l, alert)
            }
        };
        out.push(match areas {
            Some(a) => zone.with_areas(a),
            None => zone,
        });
    }
    Ok(out)
}

/// For each contactor node, the node of `set` at the same position (to 1e-9 of the mesh's
/// extent): node pairs join two bodies whose meshes match on the interface, each with its own
/// nodes there.
fn pair_by_position(
    mesh: &SolidMesh,
    sp: &KeyPath,
    set: &str,
    contactor_set: &str,
    contactor: &[usize],
) -> CliResult<Vec<usize>> {
    let targets = node_set(sp, mesh, set)?;
    let nodes = mesh.nodes();
    let extent = nodes
        .iter()
        .flat_map(|p| p.iter())
        .fold(0.0_f64, |m, v| m.max(v.abs()));
    let tol = 1e-9 * extent.max(f64::MIN_POSITIVE);
    let key = |p: [f64; 3]| p.map(|v| (v / tol.max(1e-300) / 16.0).round() as i64);
    let mut by_position: std::collections::HashMap<[i64; 3], Vec<usize>> =
        std::collections::HashMap::new();
    for &t in &targets {
        by_position.entry(key(nodes[t])).or_default().push(t);
    }
    contactor
        .iter()
        .map(|&c| {
            let x = nodes[c];
            let k = key(x);
            let near = (-1..=1)
                .flat_map(|i| (-1..=1).flat_map(move |j| (-1..=1).map(move |l| [i, j, l])))
                .filter_map(|d| by_position.get(&[k[0] + d[0], k[1] + d[1], k[2] + d[2]]))
                .flatten()
                .copied()
                .filter(|&t| t != c && (0..3).all(|a| (nodes[t][a] - x[a]).abs() <= tol))
                .min();
            near.ok_or_else(|| {
                CliError::at(
                    sp,
                    format!(
                        "node {c} of the contactor set `{contactor_set}` at ({}, {}, {}) has no \
                         node of `{sp}` = \"{set}\" at its position: node pairs need matching \
                         meshes, each body with its own nodes on the interface (use a faces \
                         target otherwise)",
                        x[0], x[1], x[2]
                    ),
                )
            })
        })
        .collect()
}

/// The simulation of `model` with the zones of `plans`: zones built ([`zones`]), contactor
/// nodes held by a support refused or left out (`supported_contactors`; the warnings are
/// returned), candidates recognised and checked (each zone has one, none deeper in its target
/// than the alert distance, one within it). A library refusal is told at the `contact` key.
pub(super) fn build(
    model: SolidModel,
    plans: &[ZonePlan<Obstacle>],
    settings: SimulationSettings,
) -> CliResult<(SolidContactSimulation<SolidModel, StandardLaw>, Vec<String>)> {
    let contact = KeyPath::root().key("contact");
    let zones = zones(model.mesh(), plans)?;
    let nodes: Vec<[f64; 3]> = model.mesh().nodes().to_vec();
    let held = supported_contactors_3d(&model, &zones).map_err(|e| solver_error(&contact, e))?;
    let policies: Vec<Policy<'_>> = plans
        .iter()
        .map(|z| Policy {
            path: z.path.clone(),
            name: &z.name,
            contactor: &z.contactor,
            choice: z.supported,
        })
        .collect();
    let (leave_out, warnings) = resolve(&held, &policies, &|n| position_text(&nodes[n]))?;
    let zones: Vec<_> = zones
        .into_iter()
        .zip(&leave_out)
        .map(|(z, l)| {
            if l.is_empty() {
                z
            } else {
                z.without_contactors(l)
            }
        })
        .collect();
    let sim = SolidContactSimulation::new(model, zones, settings)
        .map_err(|e| solver_error(&contact, e))?;
    check_candidates(sim.candidates(), plans, &nodes)?;
    Ok((sim, warnings))
}

/// Every zone must have a candidate, none deeper inside its target than the alert distance,
/// and one within the alert distance.
fn check_candidates(
    candidates: &[Candidate3],
    plans: &[ZonePlan<Obstacle>],
    nodes: &[[f64; 3]],
) -> CliResult<()> {
    for (z, zone) in plans.iter().enumerate() {
        let p = &zone.path;
        let mut mine = candidates.iter().filter(|c| c.zone == z);
        let Some(first) = mine.next() else {
            return Err(CliError::at(
                &p.key("target"),
                format!(
                    "zone `{}`: none of the nodes of `{}` projects onto the target",
                    zone.name, zone.contactor
                ),
            ));
        };
        let closest = mine.fold(first, |a, c| if c.gap0 < a.gap0 { c } else { a });
        let x = nodes[closest.node];
        if closest.gap0 < -zone.alert {
            return Err(CliError::at(
                &p.key("target"),
                format!(
                    "zone `{}`: contactor node {} at ({}, {}, {}) starts inside the target by {}, \
                     more than the alert distance {}: does the plane's normal (or the side) \
                     point towards the contactor?",
                    zone.name, closest.node, x[0], x[1], x[2], -closest.gap0, zone.alert
                ),
            ));
        }
        if closest.gap0 > zone.alert {
            return Err(CliError::at(
                &p.key("alert_distance"),
                format!(
                    "zone `{}`: every contactor node is outside the alert distance {} at the \
                     start (the closest, node {} at ({}, {}, {}), has a gap of {}); move the \
                     target closer or raise `alert_distance`",
                    zone.name, zone.alert, closest.node, x[0], x[1], x[2], closest.gap0
                ),
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn direction_rejects_zero_and_overflow() {
        let p = KeyPath::root().key("normal");
        assert_eq!(
            direction(&p, &Coords(vec![0.0, 0.0, 2.0])).unwrap(),
            [0.0, 0.0, 2.0]
        );
        for v in [[0.0; 3], [1e200, 1e200, 0.0]] {
            let e = direction(&p, &Coords(v.to_vec())).unwrap_err();
            assert!(e.message.contains("expected a direction"), "{}", e.message);
        }
        let e = direction(&p, &Coords(vec![f64::NAN, 0.0, 1.0])).unwrap_err();
        assert_eq!(e.path.unwrap().to_string(), "normal[0]");
    }

    #[test]
    fn settings_3d_reads_the_paths_with_the_3d_default() {
        use super::super::super::contact::settings;
        use crate::scene::{FlexibilitySpec, SolverSpec};
        use contact_solver::FlexibilityMode;
        let s = SolverSpec {
            max_detection_passes: Some(7),
            flexibility: Some(FlexibilitySpec::Dense),
            ..SolverSpec::default()
        };
        let out = settings::<3>(&s).unwrap();
        assert_eq!(out.tuning.max_detection_passes, 7);
        assert_eq!(out.flexibility, FlexibilityMode::Dense);
        let auto = settings::<3>(&SolverSpec::default()).unwrap().flexibility;
        assert_eq!(auto, FlexibilityMode::Auto { dense_limit: 3000 });
        let s = SolverSpec {
            dense_limit: Some(10),
            ..SolverSpec::default()
        };
        let limited = settings::<3>(&s).unwrap().flexibility;
        assert_eq!(limited, FlexibilityMode::Auto { dense_limit: 10 });
        let s = SolverSpec {
            flexibility: Some(FlexibilitySpec::ActiveSet),
            ..SolverSpec::default()
        };
        assert_eq!(
            settings::<3>(&s).unwrap().flexibility,
            FlexibilityMode::ActiveSet
        );
        // dense_limit with another path is refused at its key, as in 2D
        let s = SolverSpec {
            flexibility: Some(FlexibilitySpec::MatrixFree),
            dense_limit: Some(10),
            ..SolverSpec::default()
        };
        let e = settings::<3>(&s).unwrap_err();
        assert_eq!(e.path.unwrap().to_string(), "solver.dense_limit");
    }
}
