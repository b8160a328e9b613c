//! The model of a 3D scene: its loads checked (three-number vectors, pressures on face sets),
//! then the supports, ties and loads looked up in the mesh and the [`SolidModel`] built with
//! the supports' values at t = 0. Materials, supports' values and names, time functions and
//! phases are checked by the 2D code ([`super::super::model`], [`super::super::phases`]).

use super::super::checks::{fem, finite};
use super::super::model::{
    InitialStressPlan, MaterialPlan, SupportPlan, Ties, check_prescriptions, regions, young_keys,
};
use super::super::phases::{Phase, TimeFunction, check_function, function_value, phase_mask};
use super::super::study::SupportRt;
use super::mesh::{face_set, node_set};
use crate::error::{CliError, CliResult, KeyPath};
use crate::raw::triple;
use crate::scene::Scene;
use crate::spec3::LoadSpec3;
use fem_core::solid::{SolidMesh, SolidModel, geostatic_3d};
use fem_core::{Component, FemError, Supports};
use std::collections::{BTreeMap, BTreeSet};

/// What a 3D load is, ready to apply (sets resolved to nodes where the model needs nodes).
#[derive(Clone, Debug)]
pub enum LoadKind3 {
    /// Traction on a face set.
    Traction(String, [f64; 3]),
    /// Pressure on a face set (positive into the body).
    Pressure(String, f64),
    /// Force on each node.
    Nodal(Vec<usize>, [f64; 3]),
    /// One force on a tied set, applied at this node of it.
    Resultant(usize, [f64; 3]),
    /// Body force.
    Body([f64; 3]),
    /// Self-weight (along −z).
    Gravity,
}

/// A 3D load ready to apply.
#[derive(Clone, Debug)]
pub struct LoadRt3 {
    /// Name.
    pub name: Option<String>,
    /// Kind.
    pub kind: LoadKind3,
    /// Function name.
    pub function: Option<String>,
    /// Phase mask.
    pub phases: Vec<bool>,
}

/// A 3D load, checked; its set is looked up in the mesh at build.
pub(super) struct LoadPlan3 {
    path: KeyPath,
    spec: LoadSpec3,
    rt: LoadRt3,
}

impl LoadPlan3 {
    /// The load's name.
    pub(super) fn name(&self) -> Option<String> {
        self.rt.name.clone()
    }
}

/// Checks `[[loads]]` of a 3D scene: types and keys, finite values, functions and phases.
pub(super) fn validate_loads(
    scene: &Scene,
    functions: &BTreeMap<String, TimeFunction>,
    phases: &[Phase],
    any_weight: bool,
) -> CliResult<Vec<LoadPlan3>> {
    let root = KeyPath::root();
    let mut out = Vec::new();
    for (i, l) in scene.loads.iter().enumerate() {
        let p = root.key("loads").index(i);
        let spec = l.resolve_3d(&p)?;
        let vp = p.key("value");
        let v3 = |c: &crate::spec3::Coords| -> CliResult<[f64; 3]> {
            let v = triple(&vp, c)?;
            for (k, x) in v.iter().enumerate() {
                finite(&vp.index(k), *x)?;
            }
            Ok(v)
        };
        let kind = match &spec {
            LoadSpec3::Traction { value, .. } => LoadKind3::Traction(String::new(), v3(value)?),
            LoadSpec3::Pressure { value, .. } => {
                LoadKind3::Pressure(String::new(), finite(&vp, *value)?)
            }
            LoadSpec3::NodalForce { value, .. } => LoadKind3::Nodal(Vec::new(), v3(value)?),
            LoadSpec3::Resultant { value, .. } => LoadKind3::Resultant(0, v3(value)?),
            LoadSpec3::BodyForce { value } => LoadKind3::Body(v3(value)?),
            LoadSpec3::Gravity => {
                if !any_weight {
                    return Err(CliError::at(
                        &p,
                        "a gravity load needs a material with `unit_weight` > 0 (every unit \
                         weight is 0)",
                    ));
                }
                LoadKind3::Gravity
            }
        };
        let (name, function, ph) = l.common();
        check_function(&p.key("function"), &function, functions)?;
        out.push(LoadPlan3 {
            rt: LoadRt3 {
                name,
                kind,
                function,
                phases: phase_mask(&p.key("phases"), &ph, phases)?,
            },
            path: p,
            spec,
        });
    }
    Ok(out)
}

/// What the 3D model is built from.
pub(super) struct ModelPlan3 {
    /// Materials.
    pub(super) materials: Vec<MaterialPlan>,
    /// Supports.
    pub(super) supports: Vec<SupportPlan>,
    /// Loads.
    pub(super) loads: Vec<LoadPlan3>,
    /// Ties.
    pub(super) ties: Ties,
    /// Initial stress.
    pub(super) initial_stress: InitialStressPlan,
}

/// The model: materials on the mesh's regions, the supports of the first phase (the others are
/// added and released between phases by the run), ties, loads on their sets, the initial
/// stress.
pub(super) fn build(
    mesh: SolidMesh,
    plan: ModelPlan3,
    functions: &BTreeMap<String, TimeFunction>,
    phases: &[Phase],
) -> CliResult<(SolidModel, Vec<SupportRt>, Vec<LoadRt3>)> {
    let root = KeyPath::root();
    let young_keys = young_keys(&plan.materials);
    let materials = regions(mesh.regions(), plan.materials)?;
    let mut supports = Vec::new();
    let mut paths = Vec::new();
    for s in plan.supports {
        let sp = s.path.parent();
        let mut rt = s.rt;
        rt.nodes = node_set(&s.path, &mesh, &s.set)?;
        supports.push(rt);
        paths.push(sp);
    }
    check_prescriptions(&supports, &paths)?;
    let mut sup = Supports::new();
    let mut tied = BTreeSet::new();
    for (path, set, components) in &plan.ties {
        let nodes = node_set(path, &mesh, set)?;
        for &c in components {
            sup.tie(&nodes, c).map_err(|e| fem(path, e))?;
            tied.extend(nodes.iter().map(|&n| (n, c)));
        }
    }
    let mut loads = Vec::new();
    for l in plan.loads {
        let (p, mut rt) = (l.path, l.rt);
        let sp = p.key("set");
        rt.kind = match (l.spec, rt.kind) {
            (LoadSpec3::Traction { set, .. }, LoadKind3::Traction(_, v)) => {
                face_set(&sp, &mesh, &set)?;
                LoadKind3::Traction(set, v)
            }
            (LoadSpec3::Pressure { set, .. }, LoadKind3::Pressure(_, v)) => {
                face_set(&sp, &mesh, &set)?;
                LoadKind3::Pressure(set, v)
            }
            (LoadSpec3::NodalForce { set, .. }, LoadKind3::Nodal(_, v)) => {
                LoadKind3::Nodal(node_set(&sp, &mesh, &set)?, v)
            }
            (LoadSpec3::Resultant { set, .. }, LoadKind3::Resultant(_, v)) => {
                let nodes = node_set(&sp, &mesh, &set)?;
                let comps = [Component::X, Component::Y, Component::Z];
                for (c, comp) in comps.into_iter().enumerate() {
                    if v[c] != 0.0 && nodes.iter().any(|&n| !tied.contains(&(n, comp))) {
                        return Err(CliError::at(
                            &sp,
                            format!(
                                "`{sp}` = \"{set}\": a resultant force along {comp} needs the set \
                                 tied along {comp} (a [[ties]] entry with set = \"{set}\"), so \
                                 that it has one point of application; for a force on each node \
                                 use type = \"nodal_force\""
                            ),
                        ));
                    }
                }
                let Some(&first) = nodes.first() else {
                    return Err(CliError::at(&sp, format!("`{sp}` = \"{set}\" is empty")));
                };
                LoadKind3::Resultant(first, v)
            }
            (_, kind) => kind,
        };
        loads.push(rt);
    }
    // the supports of the first phase; the others are added and released between phases
    for s in supports.iter().filter(|s| s.phases[0]) {
        let f = function_value(&phases[0], &s.name, &s.function, functions, 0.0);
        for &c in &s.components {
            sup.prescribe(&s.nodes, c, s.value * f)
                .map_err(|e| fem(&root.key("supports"), e))?;
        }
    }
    let mut model = SolidModel::new(mesh, &materials, sup).map_err(|e| {
        let at = match &e {
            FemError::NonFiniteStiffness { region, .. } => young_keys.get(region).cloned(),
            FemError::InvalidTie { .. } => Some(root.key("ties")),
            _ => None,
        };
        fem(&at.unwrap_or_else(|| root.key("supports")), e)
    })?;
    if let Some((gamma, k0, z)) = plan.initial_stress {
        model
            .set_initial_stress(geostatic_3d(gamma, k0, z))
            .map_err(|e| fem(&root.key("initial_stress"), e))?;
    }
    Ok((model, supports, loads))
}
