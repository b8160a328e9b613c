//! What a scene reads differently in 2D and 3D, in one place: the trait [`SceneDim`], for
//! `Dim<2>` and `Dim<3>`. The passes are written once over the dimension `D` and ask it for
//! the boundary sets tractions name (edge sets, face sets), the Gmsh reader and element names,
//! the generators (rectangle and pile, box), the model's constructor (the 2D idealisation and
//! `floating`) and the geostatic stress; and, for contact, the rigid shapes (LINE and ARC;
//! plane, sphere and cylinder), node pairs (by the sets' order, by position), target surfaces
//! (a node set's polyline, a face set's triangles), the contactor's areas and the wording and
//! order of the candidates' checks.

use super::checks::{expect, solver_error};
use super::checks::{fem, finite, finite_all, kind_name, list_names, node_set, positive};
use super::curves;
use super::mesh::MeshPlan;
use super::model::Solves;
use crate::error::{CliError, CliResult, KeyPath, bail, err};
use crate::raw::vector;
use crate::spec::{ArcSideSpec, Coords, Element, TargetSpec};
use contact_laws::StandardLaw;
use contact_solver::SolverError;
use contact_solver::coupling::solid::{RigidCylinder, RigidPlane, RigidSphere, Side3, TriSurface};
use contact_solver::coupling::space::ContactSpace;
use contact_solver::coupling::zone::Polyline;
use contact_solver::{ArcSide, Candidate, ContactZone, Obstacle, PairNormals, RigidArc, RigidLine};
use fem_core::model::ModelSpace;
use fem_core::solid::{SolidMesh, SolidModel, geostatic_3d};
use fem_core::{Dim, ElasticModel, ElementKind, FemError, Idealization, LinearElasticModel};
use fem_core::{Material, Mesh, StressField, Supports};
use std::collections::HashMap;
use std::f64::consts::TAU;
use std::path::Path;
use std::sync::Arc;

/// What a scene reads differently in each dimension (see the module docs).
pub(crate) trait SceneDim<const D: usize>: ModelSpace<D> + ContactSpace<D>
where
    Dim<D>: ModelSpace<D> + ContactSpace<D>,
{
    /// What the model is built in besides its mesh, materials and supports.
    type Options;
    /// The 2D idealisation among the options (none in 3D).
    fn idealization(options: &Self::Options) -> Option<Idealization>;
    /// Checks that the boundary set a traction or pressure names exists.
    fn boundary_set(path: &KeyPath, mesh: &Mesh<D>, set: &str) -> CliResult<()>;
    fn model(
        mesh: Mesh<D>,
        options: &Self::Options,
        materials: &[(u32, Material)],
        supports: Supports,
        solves: Solves,
    ) -> Result<ElasticModel<D>, FemError>;
    /// The geostatic initial stress (`gamma`, `k0`, the surface's height).
    fn geostatic(gamma: f64, k0: f64, z: f64) -> StressField<D>;
    /// Reads a Gmsh 4.1 file of this dimension.
    fn read_msh(path: &Path) -> Result<Mesh<D>, FemError>;
    /// Whether `mesh`'s elements have the order `e` names (`mesh.element` of a Gmsh file names
    /// the order, the file the shape), and their name for messages.
    fn element_order(e: Element, mesh: &Mesh<D>) -> (bool, &'static str);
    /// Adds a uniform traction on the boundary set `set` (edges, faces) to the model's loads.
    ///
    /// # Errors
    /// The model's, for a set it does not have.
    fn traction(model: &mut ElasticModel<D>, set: &str, t: [f64; D]) -> Result<(), FemError>;
    /// Adds a pressure `p` (positive into the body) on the face set `set`.
    ///
    /// # Errors
    /// The model's, for a set it does not have; in 2D, always (a 2D scene has no pressure).
    fn pressure(model: &mut ElasticModel<D>, set: &str, p: f64) -> Result<(), FemError>;
    /// Generates the mesh of one of this dimension's generators (`[mesh]` at `mp`).
    fn generate(mp: &KeyPath, plan: MeshPlan) -> CliResult<Mesh<D>>;

    /// Whether the scene checks the candidates before the simulation is made, with
    /// [`check_facing`](Self::check_facing) (2D), or after, behind the simulation's own checks
    /// (3D).
    const CANDIDATES_FIRST: bool;
    /// What an error says to do when a zone's contactor starts too deep in its target.
    const INSIDE_HINT: &'static str;
    /// A rigid target of this dimension's shapes (at `tp`), its geometry checked, built.
    fn obstacle(tp: &KeyPath, t: &TargetSpec) -> CliResult<Arc<dyn Obstacle<D>>>;
    /// A node-pair zone's fixed normal at `p`, checked.
    fn pair_normal(p: &KeyPath, n: &Coords) -> CliResult<[f64; D]>;
    /// The nodes of the contactor set `set` (at `p`), and their tributary areas where the set
    /// gives them (a face set in 3D).
    fn contactor(
        mesh: &Mesh<D>,
        p: &KeyPath,
        set: &str,
    ) -> CliResult<(Vec<usize>, Option<Vec<f64>>)>;
    /// The target node of each contactor node (of the set `contactor_set`) of a node-pair zone
    /// against the set `set`, and the pairs' normals (the contactor may be reordered to pair
    /// better).
    fn pairs(
        model: &ElasticModel<D>,
        tp: &KeyPath,
        contactor_set: &str,
        set: &str,
        normal: Option<[f64; D]>,
        contactor: &mut Vec<usize>,
    ) -> CliResult<(Vec<usize>, PairNormals<D>)>;
    /// The target surface of the set `set` (at `sp`) of a node-to-surface zone.
    fn surface(
        model: &ElasticModel<D>,
        sp: &KeyPath,
        set: &str,
    ) -> CliResult<<Dim<D> as ContactSpace<D>>::Surface>;
    /// The tributary areas of the contactor set `set` (its nodes `nodes`, as the zone holds
    /// them) where the zone's own would be wrong; `None`: the zone's.
    fn areas(model: &ElasticModel<D>, set: &str, nodes: &[usize]) -> Option<Vec<f64>>;
    /// The checks of candidates only this dimension makes (2D: that node pairs and segments
    /// face their targets).
    fn check_facing(
        candidates: &[Candidate<D>],
        zones: &[ContactZone<StandardLaw, D>],
        model: &ElasticModel<D>,
    ) -> CliResult<()>;
    /// Why a zone whose contactor set is `set` (of `nodes` nodes) has no candidate.
    fn no_projection(set: &str, nodes: usize) -> String;
}

/// The error of a value of the other dimension that the resolve should have refused.
fn routing(p: &KeyPath) -> CliError {
    CliError::at(
        p,
        "a value of the other dimension reached this scene's builder (internal routing error)",
    )
}

impl SceneDim<2> for Dim<2> {
    /// The idealisation and `[analysis] floating`.
    type Options = (Idealization, bool);

    fn idealization(options: &Self::Options) -> Option<Idealization> {
        Some(options.0)
    }

    fn boundary_set(path: &KeyPath, mesh: &Mesh, set: &str) -> CliResult<()> {
        mesh.edge_set(set).map(|_| ()).map_err(|_| {
            err!(
                path,
                "`{path}` = \"{set}\": the mesh has no edge set of that name (edge sets: {})",
                list_names(mesh.edge_set_names())
            )
        })
    }

    fn model(
        mesh: Mesh,
        &(idealization, floating): &Self::Options,
        materials: &[(u32, Material)],
        supports: Supports,
        solves: Solves,
    ) -> Result<LinearElasticModel, FemError> {
        match (floating, solves) {
            // a floating body's solves are its own (`K⁺`): an external solver is refused later
            (true, _) => LinearElasticModel::floating(mesh, idealization, materials, supports),
            (false, Solves::Factorised) => {
                LinearElasticModel::new(mesh, idealization, materials, supports)
            }
            (false, Solves::External) => {
                LinearElasticModel::unfactored(mesh, idealization, materials, supports)
            }
        }
    }

    fn geostatic(gamma: f64, k0: f64, z: f64) -> StressField<2> {
        fem_core::geostatic(gamma, k0, z)
    }

    fn read_msh(path: &Path) -> Result<Mesh, FemError> {
        fem_core::gmsh::read_msh(path)
    }

    /// `P1`: linear triangles or quadrilaterals, `P2`: quadratic ones.
    fn element_order(e: Element, mesh: &Mesh) -> (bool, &'static str) {
        let k = mesh.kind();
        let order = match e {
            Element::P1 => matches!(k, ElementKind::Tri3 | ElementKind::Quad4),
            Element::P2 => matches!(
                k,
                ElementKind::Tri6 | ElementKind::Quad8 | ElementKind::Quad9
            ),
        };
        (order, kind_name(k))
    }

    fn traction(model: &mut LinearElasticModel, set: &str, t: [f64; 2]) -> Result<(), FemError> {
        model.add_edge_traction(set, |_| t)
    }

    /// Refused when a 2D scene is read: a pressure is a load of a 3D scene.
    fn pressure(_: &mut LinearElasticModel, _: &str, p: f64) -> Result<(), FemError> {
        Err(FemError::InvalidParameter {
            name: "pressure",
            value: p,
            expected: "no pressure in a 2D scene (a traction on an edge set)",
        })
    }

    /// The rectangle and the pile.
    fn generate(mp: &KeyPath, plan: MeshPlan) -> CliResult<Mesh> {
        match plan {
            MeshPlan::Rectangle(spec) => fem_core::generate::rectangle(&spec),
            MeshPlan::Pile(s, detach) => fem_core::generate::pile_in_soil(&s).and_then(|m| {
                if detach {
                    let radius = 0.5 * s.diameter;
                    crate::presets::pile::detach_tip(m, radius, s.length).map(|(m, _, _)| m)
                } else {
                    Ok(m)
                }
            }),
            _ => return Err(routing(mp)),
        }
        .map_err(|e| fem(mp, e))
    }

    const CANDIDATES_FIRST: bool = true;
    const INSIDE_HINT: &'static str = "is the target on the right side (a LINE has the \
        contactor on its left, from a to b; an ARC has `side`)?";

    /// A LINE or an ARC.
    fn obstacle(tp: &KeyPath, t: &TargetSpec) -> CliResult<Arc<dyn Obstacle<2>>> {
        Ok(match t {
            TargetSpec::Line { a, b } => {
                let a = finite_all(&tp.key("a"), a.0)?;
                let b = finite_all(&tp.key("b"), b.0)?;
                let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
                if !(dx.is_finite() && dy.is_finite() && dx.hypot(dy).is_finite()) {
                    bail!(
                        tp,
                        "`{tp}`: the length of the LINE from {a:?} to {b:?} overflows \
                             (expected end points whose distance stays finite)"
                    );
                }
                Arc::new(RigidLine::new(a, b).map_err(|e| solver_error(tp, e))?)
            }
            TargetSpec::Arc {
                center,
                radius,
                start_angle,
                sweep,
                side,
            } => {
                let center = finite_all(&tp.key("center"), center.0)?;
                let radius = positive(&tp.key("radius"), *radius)?;
                let start = finite(&tp.key("start_angle"), *start_angle)?;
                let sweep = match sweep {
                    Some(s) => expect(
                        &tp.key("sweep"),
                        *s,
                        *s > 0.0 && *s <= TAU * (1.0 + 1e-12),
                        "an angle in (0, 2π] radians",
                    )?,
                    None => TAU,
                };
                let side = match side {
                    ArcSideSpec::Outside => ArcSide::Outside,
                    ArcSideSpec::Inside => ArcSide::Inside,
                };
                Arc::new(
                    RigidArc::new(center, radius, start, sweep, side)
                        .map_err(|e| solver_error(tp, e))?,
                )
            }
            _ => return Err(routing(tp)),
        })
    }

    fn pair_normal(p: &KeyPath, n: &Coords) -> CliResult<[f64; 2]> {
        let n = finite_all(p, vector::<2>(p, n)?)?;
        if n == [0.0, 0.0] {
            bail!(p, "the normal [0, 0] has no direction");
        }
        Ok(n)
    }

    fn contactor(mesh: &Mesh, p: &KeyPath, set: &str) -> CliResult<(Vec<usize>, Option<Vec<f64>>)> {
        Ok((node_set(p, mesh, set)?, None))
    }

    /// With the nodes of `set` in order (a fixed normal: as listed, or else along the curve),
    /// of the contactor's length; no node paired with itself. Without a normal, the normals
    /// come from the target nodes in order.
    fn pairs(
        model: &LinearElasticModel,
        tp: &KeyPath,
        contactor_set: &str,
        set: &str,
        normal: Option<[f64; 2]>,
        contactor: &mut Vec<usize>,
    ) -> CliResult<(Vec<usize>, PairNormals<2>)> {
        let mesh = model.mesh();
        let sp = tp.key("set");
        let targets = match normal {
            Some(_) => node_set(&sp, mesh, set)?,
            None => curves::target_nodes(&sp, mesh, set)?.0,
        };
        curves::match_pairs(
            mesh,
            (contactor_set, contactor.as_mut_slice()),
            (set, targets.as_slice()),
        );
        if targets.len() != contactor.len() {
            bail!(
                sp,
                "node set `{set}` has {} nodes but the contactor set `{}` has {}: node pairs \
                     need sets of the same length, in matching order",
                targets.len(),
                contactor_set,
                contactor.len()
            );
        }
        if let Some((c, _)) = contactor.iter().zip(&targets).find(|(c, t)| c == t) {
            bail!(
                sp,
                "`{sp}` = \"{set}\": node {c} of the contactor set `{}` is paired with \
                     itself (a node cannot touch itself; pair two distinct surfaces)",
                contactor_set
            );
        }
        Ok((targets, normal.into()))
    }

    /// The polyline through the set's nodes in order (closed when its curve is).
    fn surface(model: &LinearElasticModel, sp: &KeyPath, set: &str) -> CliResult<Polyline> {
        let (mut surface, closed) = curves::target_nodes(sp, model.mesh(), set)?;
        if closed {
            surface.push(surface[0]);
        }
        if surface.len() < 2 {
            bail!(
                sp,
                "node set `{set}` has {} node: a target polyline needs at least two",
                surface.len()
            );
        }
        curves::check_polyline(sp, set, model, &surface)?;
        Ok(Polyline::new(surface))
    }

    fn areas(model: &LinearElasticModel, set: &str, nodes: &[usize]) -> Option<Vec<f64>> {
        curves::contactor_areas(model, set, nodes)
    }

    fn check_facing(
        candidates: &[Candidate],
        zones: &[ContactZone<StandardLaw>],
        model: &LinearElasticModel,
    ) -> CliResult<()> {
        curves::check_facing(candidates, zones, model)
    }

    fn no_projection(_: &str, nodes: usize) -> String {
        format!(
            "none of its {nodes} contactor nodes projects onto the target (a LINE or ARC must \
             face the nodes; check its ends and its side)"
        )
    }
}

impl SceneDim<3> for Dim<3> {
    /// Whether the body may float (rigid-body modes accepted): a dynamic scene's, whose
    /// inertia holds them; a static 3D scene does not float yet.
    type Options = bool;

    fn idealization(_: &bool) -> Option<Idealization> {
        None
    }

    fn boundary_set(path: &KeyPath, mesh: &SolidMesh, set: &str) -> CliResult<()> {
        mesh.face_set(set).map(|_| ()).map_err(|_| {
            err!(
                path,
                "`{path}` = \"{set}\": the mesh has no face set of that name (face sets, the \
                     physical surfaces: {})",
                list_names(mesh.facet_set_names())
            )
        })
    }

    fn model(
        mesh: SolidMesh,
        &floating: &bool,
        materials: &[(u32, Material)],
        supports: Supports,
        solves: Solves,
    ) -> Result<SolidModel, FemError> {
        match (floating, solves) {
            // a floating body's solves are its own (`K⁺`): an external solver is refused later
            (true, _) => SolidModel::floating(mesh, materials, supports),
            (false, Solves::Factorised) => SolidModel::new(mesh, materials, supports),
            (false, Solves::External) => SolidModel::unfactored(mesh, (), materials, supports),
        }
    }

    fn geostatic(gamma: f64, k0: f64, z: f64) -> StressField<3> {
        geostatic_3d(gamma, k0, z)
    }

    fn read_msh(path: &Path) -> Result<SolidMesh, FemError> {
        fem_core::solid::gmsh::read_msh_3d(path)
    }

    /// `P1`: Tet4 or Hex8, `P2`: Tet10 or Hex20.
    fn element_order(e: Element, mesh: &SolidMesh) -> (bool, &'static str) {
        let k = mesh.kind();
        let order = match e {
            Element::P1 => matches!(k, ElementKind::Tet4 | ElementKind::Hex8),
            Element::P2 => matches!(k, ElementKind::Tet10 | ElementKind::Hex20),
        };
        (order, kind_name(k))
    }

    fn traction(model: &mut SolidModel, set: &str, t: [f64; 3]) -> Result<(), FemError> {
        model.add_face_traction(set, |_, _| t)
    }

    fn pressure(model: &mut SolidModel, set: &str, p: f64) -> Result<(), FemError> {
        model.add_face_traction(set, |_, n| n.map(|c| -p * c))
    }

    /// The box.
    fn generate(mp: &KeyPath, plan: MeshPlan) -> CliResult<SolidMesh> {
        match plan {
            MeshPlan::Box([xs, ys, zs], kind) => {
                fem_core::solid::generate::box_mesh(&xs, &ys, &zs, kind).map_err(|e| fem(mp, e))
            }
            _ => Err(routing(mp)),
        }
    }

    const CANDIDATES_FIRST: bool = false;
    const INSIDE_HINT: &'static str =
        "does the plane's normal (or the side) point towards the contactor?";

    /// A plane, a sphere or a cylinder.
    fn obstacle(tp: &KeyPath, t: &TargetSpec) -> CliResult<Arc<dyn Obstacle<3>>> {
        let err = |e: SolverError| solver_error(tp, e);
        let side = |s: &ArcSideSpec| match s {
            ArcSideSpec::Outside => Side3::Outside,
            ArcSideSpec::Inside => Side3::Inside,
        };
        Ok(match t {
            TargetSpec::Plane { point: x, normal } => Arc::new(
                RigidPlane::new(
                    point(&tp.key("point"), x)?,
                    direction(&tp.key("normal"), normal)?,
                )
                .map_err(err)?,
            ),
            TargetSpec::Sphere {
                center,
                radius,
                side: s,
            } => Arc::new(
                RigidSphere::new(
                    point(&tp.key("center"), center)?,
                    positive(&tp.key("radius"), *radius)?,
                    side(s),
                )
                .map_err(err)?,
            ),
            TargetSpec::Cylinder {
                point: x,
                axis,
                radius,
                side: s,
            } => Arc::new(
                RigidCylinder::new(
                    point(&tp.key("point"), x)?,
                    direction(&tp.key("axis"), axis)?,
                    positive(&tp.key("radius"), *radius)?,
                    side(s),
                )
                .map_err(err)?,
            ),
            _ => return Err(routing(tp)),
        })
    }

    fn pair_normal(p: &KeyPath, n: &Coords) -> CliResult<[f64; 3]> {
        direction(p, n)
    }

    /// A face set (a physical surface) gives its nodes with their consistent nodal areas (the
    /// reports' pressures are then `r_n / A_i`); a node set, its nodes.
    fn contactor(
        mesh: &SolidMesh,
        p: &KeyPath,
        set: &str,
    ) -> CliResult<(Vec<usize>, Option<Vec<f64>>)> {
        Ok(match mesh.nodal_areas(set) {
            Ok((nodes, areas)) => (nodes, Some(areas)),
            Err(_) => (node_set(p, mesh, set)?, None),
        })
    }

    /// By position; a fixed normal, or the target body's from the faces of `set`.
    fn pairs(
        model: &SolidModel,
        tp: &KeyPath,
        contactor_set: &str,
        set: &str,
        normal: Option<[f64; 3]>,
        contactor: &mut Vec<usize>,
    ) -> CliResult<(Vec<usize>, PairNormals<3>)> {
        let sp = tp.key("set");
        let targets = pair_by_position(model.mesh(), &sp, set, contactor_set, contactor)?;
        let normals = match normal {
            Some(n) => PairNormals::Fixed(n),
            None => PairNormals::Surface(Self::surface(model, &sp, set)?),
        };
        Ok((targets, normals))
    }

    /// The triangles of the face set.
    fn surface(model: &SolidModel, sp: &KeyPath, set: &str) -> CliResult<TriSurface> {
        TriSurface::from_face_set(model.mesh(), set).map_err(|_| {
            err!(
                sp,
                "`{sp}` = \"{set}\" is not a face set of the mesh (a physical surface, or a \
                     side of the box): a faces target, and node pairs without a `normal`, need \
                     the target body's faces"
            )
        })
    }

    fn areas(_: &SolidModel, _: &str, _: &[usize]) -> Option<Vec<f64>> {
        None
    }

    fn check_facing(
        _: &[Candidate<3>],
        _: &[ContactZone<StandardLaw, 3>],
        _: &SolidModel,
    ) -> CliResult<()> {
        Ok(())
    }

    fn no_projection(set: &str, _: usize) -> String {
        format!("none of the nodes of `{set}` projects onto the target")
    }
}

/// Three finite numbers at `p`.
fn point(p: &KeyPath, c: &Coords) -> CliResult<[f64; 3]> {
    finite_all(p, vector::<3>(p, c)?)
}

/// A direction at `p`: three finite numbers, not all zero, whose length does not overflow.
fn direction(p: &KeyPath, c: &Coords) -> CliResult<[f64; 3]> {
    let v = point(p, c)?;
    let len = v.iter().map(|x| x * x).sum::<f64>().sqrt();
    if !(len > 0.0 && len.is_finite()) {
        bail!(
            p,
            "`{p}` = {v:?}: expected a direction (not [0, 0, 0], and of a length that stays \
                 finite)"
        );
    }
    Ok(v)
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
    let mut by_position: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
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
                err!(
                    sp,
                    "node {c} of the contactor set `{contactor_set}` at ({}, {}, {}) has no \
                         node of `{sp}` = \"{set}\" at its position: node pairs need matching \
                         meshes, each body with its own nodes on the interface (use a faces \
                         target otherwise)",
                    x[0],
                    x[1],
                    x[2]
                )
            })
        })
        .collect()
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
}
