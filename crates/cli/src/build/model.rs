//! The model of a 2D or 3D scene: materials, supports, loads and the initial stress, their
//! values checked first (with the time functions and phases they name), then applied to the
//! mesh (regions, node sets, edge or face sets) to build the [`ElasticModel`] with the supports
//! of the first phase at t = 0. What the dimension reads differently is [`SceneDim`]'s.

use super::checks::{
    fem, finite, finite_all, join, list_names, node_set, non_negative, poisson, positive,
};
use super::dim::SceneDim;
use super::phases::{Phase, TimeFunction, check_function, function_value, phase_mask};
use super::study::{LoadKind, LoadRt, SupportRt};
use crate::error::{CliResult, KeyPath, bail};
use crate::raw::RawLoad;
use crate::scene::{ComponentSpec, Scene};
use crate::spec::{InitialStress, LoadSpec};
use fem_core::{Component, Dim, ElasticModel, FemError, Idealization, Material, Mesh, Supports};
use std::collections::{BTreeMap, BTreeSet};

/// A material, checked, and the regions it is given to (with their key paths).
pub(super) struct MaterialPlan {
    pub(super) material: Material,
    pub(super) regions: Vec<(KeyPath, u32)>,
    /// `materials[i].young`, where an overflowing stiffness is reported.
    pub(super) young: KeyPath,
    /// `initial_velocity` (a dynamic scene) and its key path, as written.
    pub(super) initial_velocity: Option<(KeyPath, crate::spec::Coords)>,
}

/// A support, checked; its node set is looked up in the mesh at build.
pub(super) struct SupportPlan {
    pub(super) path: KeyPath,
    pub(super) set: String,
    pub(super) rt: SupportRt,
}

/// A load, checked; its set (if it has one) is looked up in the mesh at build, where the
/// kind's set or node is filled in.
pub(super) struct LoadPlan<const D: usize> {
    path: KeyPath,
    set: Option<String>,
    /// The load, its set not yet looked up.
    pub(super) rt: LoadRt<D>,
}

/// Geostatic initial stress: (gamma, k0, z_surface), checked.
pub(super) type InitialStressPlan = Option<(f64, f64, f64)>;

/// In plane stress, the section stiffness `E·h` of every material must stay finite: a
/// thickness whose product with a Young modulus overflows is named here, not as an element
/// whose stiffness is not finite.
fn check_section(materials: &[MaterialPlan], idealization: Idealization) -> CliResult<()> {
    let Idealization::PlaneStress { thickness } = idealization else {
        return Ok(());
    };
    for m in materials {
        let young = m.material.young();
        if !(young * thickness).is_finite() {
            let p = KeyPath::root().key("analysis").key("thickness");
            bail!(
                p,
                "`{p}` = {thickness:?}: its product with `{}` = {young:?} overflows (the \
                     section stiffness E·h must stay below 1.8e308)",
                m.young
            );
        }
    }
    Ok(())
}

/// Two supports of the same component on a common node, in a common phase, must prescribe the
/// same thing (the same value and function, or both fixed): which one would win is not said,
/// so a conflict is an error naming both.
pub(super) fn check_prescriptions(supports: &[SupportRt], paths: &[KeyPath]) -> CliResult<()> {
    let same = |a: &SupportRt, b: &SupportRt| {
        (a.value == 0.0 && b.value == 0.0) || (a.value == b.value && a.function == b.function)
    };
    let describe = |s: &SupportRt| match &s.function {
        Some(f) if s.value != 0.0 => format!("{:?} · {f}(t)", s.value),
        _ => format!("{:?}", s.value),
    };
    for (j, b) in supports.iter().enumerate() {
        for (i, a) in supports[..j].iter().enumerate() {
            let common_phase = a.phases.iter().zip(&b.phases).any(|(x, y)| *x && *y);
            if !common_phase || same(a, b) {
                continue;
            }
            let Some(c) = b.components.iter().find(|c| a.components.contains(c)) else {
                continue;
            };
            if let Some(n) = b.nodes.iter().find(|n| a.nodes.contains(n)) {
                bail!(
                    paths[j],
                    "`{}` prescribes component {c} of node {n} as {}, but `{}` already \
                         prescribes it as {}: a degree of freedom takes one prescription \
                         (remove one, or give them the same value and function)",
                    paths[j],
                    describe(b),
                    paths[i],
                    describe(a)
                );
            }
        }
    }
    Ok(())
}

/// Checks `[[materials]]`: moduli, unit weights and the form of `region` / `regions`. Also
/// says whether any material has a unit weight (for gravity loads).
fn validate_materials(scene: &Scene) -> CliResult<(Vec<MaterialPlan>, bool)> {
    let root = KeyPath::root();
    if scene.materials.is_empty() {
        bail!(
            root,
            "the scene has no [[materials]] (each with `region`, `young`, `poisson`)"
        );
    }
    let mut plans = Vec::new();
    let mut any_weight = false;
    let dynamic = scene.analysis.as_ref().is_some_and(|a| a.is_dynamic());
    for (i, m) in scene.materials.iter().enumerate() {
        let p = root.key("materials").index(i);
        let young = positive(&p.key("young"), m.young)?;
        let poisson = poisson(&p.key("poisson"), m.poisson)?;
        let weight = non_negative(&p.key("unit_weight"), m.unit_weight)?;
        any_weight |= weight > 0.0;
        let mut material = Material::new(young, poisson, weight).map_err(|e| fem(&p, e))?;
        match m.density {
            Some(rho) => {
                let rho = positive(&p.key("density"), rho)?;
                material = material.with_density(rho).map_err(|e| fem(&p, e))?;
            }
            None if dynamic => {
                bail!(
                    p,
                    "`{p}` needs `density` (> 0): every material of a dynamic scene has a mass"
                );
            }
            None => {}
        }
        if !dynamic && m.initial_velocity.is_some() {
            let vp = p.key("initial_velocity");
            bail!(
                vp,
                "`{vp}` is a key of a dynamic scene (set `dynamic = true` in [analysis])"
            );
        }
        let regions: Vec<(KeyPath, u32)> = match (&m.region, &m.regions) {
            (Some(r), None) => vec![(p.key("region"), *r)],
            (None, Some(rs)) if !rs.is_empty() => rs
                .iter()
                .enumerate()
                .map(|(k, r)| (p.key("regions").index(k), *r))
                .collect(),
            (Some(_), Some(_)) => {
                bail!(p, "give `region` or `regions`, not both");
            }
            _ => {
                bail!(p, "`{p}` needs `region = <id>` or `regions = [ids]`");
            }
        };
        plans.push(MaterialPlan {
            material,
            regions,
            young: p.key("young"),
            initial_velocity: m
                .initial_velocity
                .clone()
                .map(|v| (p.key("initial_velocity"), v)),
        });
    }
    Ok((plans, any_weight))
}

/// Checks `[[supports]]`: values, function names and phase lists (one support at least).
fn validate_supports(
    scene: &Scene,
    functions: &BTreeMap<String, TimeFunction>,
    phases: &[Phase],
    dim: usize,
) -> CliResult<Vec<SupportPlan>> {
    let root = KeyPath::root();
    let mut supports = Vec::new();
    for (i, s) in scene.supports.iter().enumerate() {
        let p = root.key("supports").index(i);
        let value = finite(&p.key("value"), s.value)?;
        check_function(&p.key("function"), &s.function, functions)?;
        let components = components(&p.key("component"), s.component, dim)?;
        supports.push(SupportPlan {
            path: p.key("set"),
            set: s.set.clone(),
            rt: SupportRt {
                name: s.name.clone(),
                nodes: Vec::new(),
                components,
                value,
                function: s.function.clone(),
                phases: phase_mask(&p.key("phases"), &s.phases, phases)?,
            },
        });
    }
    // a dynamic body needs no support: its inertia holds its rigid-body modes
    let floating = scene
        .analysis
        .as_ref()
        .is_some_and(|a| a.floating() || a.is_dynamic());
    if supports.is_empty() && !floating {
        bail!(
            root,
            "the scene has no [[supports]]: a body without supports has rigid-body modes \
             (set `floating = true` in [analysis] if contact alone holds it)"
        );
    }
    Ok(supports)
}

/// A load's set (where it has one) and kind (its set or node not yet looked up), its type,
/// keys and values checked.
fn load<const D: usize>(l: &RawLoad, p: &KeyPath) -> CliResult<(Option<String>, LoadKind<D>)> {
    let vp = p.key("value");
    Ok(match l.resolve::<D>(p)? {
        LoadSpec::Traction { set, value } => (
            Some(set),
            LoadKind::Traction(String::new(), finite_all(&vp, value)?),
        ),
        LoadSpec::Pressure { set, value } => (
            Some(set),
            LoadKind::Pressure(String::new(), finite(&vp, value)?),
        ),
        LoadSpec::NodalForce { set, value } => (
            Some(set),
            LoadKind::Nodal(Vec::new(), finite_all(&vp, value)?),
        ),
        LoadSpec::Resultant { set, value } => {
            (Some(set), LoadKind::Resultant(0, finite_all(&vp, value)?))
        }
        LoadSpec::BodyForce { value } => (None, LoadKind::Body(finite_all(&vp, value)?)),
        LoadSpec::Gravity => (None, LoadKind::Gravity),
    })
}

/// Checks `[[loads]]`: their `type` and keys, values, function names and phase lists (a gravity
/// load needs a unit weight).
fn validate_loads<const D: usize>(
    scene: &Scene,
    functions: &BTreeMap<String, TimeFunction>,
    phases: &[Phase],
    any_weight: bool,
) -> CliResult<Vec<LoadPlan<D>>>
where
    Dim<D>: SceneDim<D>,
{
    let root = KeyPath::root();
    let mut loads = Vec::new();
    for (i, l) in scene.loads.iter().enumerate() {
        let p = root.key("loads").index(i);
        let (set, kind) = load::<D>(l, &p)?;
        if matches!(kind, LoadKind::Gravity) && !any_weight {
            bail!(
                p,
                "a gravity load needs a material with `unit_weight` > 0 (every unit weight is 0)"
            );
        }
        let (name, function, ph) = l.common();
        check_function(&p.key("function"), &function, functions)?;
        loads.push(LoadPlan {
            rt: LoadRt {
                name,
                kind,
                function,
                phases: phase_mask(&p.key("phases"), &ph, phases)?,
            },
            path: p,
            set,
        });
    }
    Ok(loads)
}

/// Checks the names of supports and loads (unique) and the phases' function overrides, which
/// name them.
fn validate_names(
    scene: &Scene,
    load_names: &[Option<String>],
    functions: &BTreeMap<String, TimeFunction>,
    phases: &[Phase],
) -> CliResult<()> {
    let root = KeyPath::root();
    let mut named: BTreeSet<String> = BTreeSet::new();
    for (i, s) in scene.supports.iter().enumerate() {
        if let Some(n) = &s.name
            && !named.insert(n.clone())
        {
            bail!(
                root.key("supports").index(i).key("name"),
                "name `{n}` is used twice among supports and loads"
            );
        }
    }
    for name in load_names {
        if let Some(n) = name
            && !named.insert(n.clone())
        {
            bail!(
                root.key("loads"),
                "name `{n}` is used twice among supports and loads"
            );
        }
    }
    for (i, ph) in phases.iter().enumerate() {
        for (target, f) in &ph.overrides {
            let p = root.key("phases").index(i).key("functions").key(target);
            if !named.contains(target) {
                bail!(
                    p,
                    "`{p}`: no support or load is named `{target}` (named: {})",
                    list_names(named.iter().map(|s| s.as_str()))
                );
            }
            check_function(&p, &Some(f.clone()), functions)?;
        }
    }
    Ok(())
}

fn validate_initial_stress(scene: &Scene) -> CliResult<InitialStressPlan> {
    let root = KeyPath::root();
    let initial = scene
        .initial_stress
        .map(|s| s.resolve(&root.key("initial_stress")))
        .transpose()?;
    Ok(match initial {
        Some(InitialStress::Geostatic {
            gamma,
            k0,
            z_surface,
        }) => {
            let p = root.key("initial_stress");
            let gamma = non_negative(&p.key("gamma"), gamma)?;
            let k0 = non_negative(&p.key("k0"), k0)?;
            let z = finite(&p.key("z_surface"), z_surface)?;
            Some((gamma, k0, z))
        }
        None => None,
    })
}

/// Checks what the model is built from, in the order of the scene's sections: materials (and
/// the 2D section stiffness), supports, loads, their names, the initial stress and the ties.
pub(super) fn validate<const D: usize>(
    scene: &Scene,
    functions: &BTreeMap<String, TimeFunction>,
    phases: &[Phase],
    options: <Dim<D> as SceneDim<D>>::Options,
) -> CliResult<ModelPlan<D>>
where
    Dim<D>: SceneDim<D>,
{
    let (materials, any_weight) = validate_materials(scene)?;
    if let Some(idealization) = Dim::<D>::idealization(&options) {
        check_section(&materials, idealization)?;
    }
    let supports = validate_supports(scene, functions, phases, D)?;
    let loads = validate_loads::<D>(scene, functions, phases, any_weight)?;
    let names: Vec<Option<String>> = loads.iter().map(|l| l.rt.name.clone()).collect();
    validate_names(scene, &names, functions, phases)?;
    Ok(ModelPlan {
        options,
        materials,
        supports,
        loads,
        initial_stress: validate_initial_stress(scene)?,
        ties: validate_ties(scene, D)?,
        solves: Solves::Factorised,
    })
}

/// Who solves the model's `K x = b`: its own Cholesky factorisation, or a solver set after
/// the build (a distributed run's), for which the model is built without a factorisation
/// (`ElasticModel::unfactored`: a rank holds `K`, not a factor).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Solves {
    /// The model factorises `K` when it is built.
    Factorised,
    /// `K` is assembled, not factorised: the run sets the model's solver.
    External,
}

/// What the model is built from.
pub(super) struct ModelPlan<const D: usize>
where
    Dim<D>: SceneDim<D>,
{
    /// What the dimension builds the model in (2D: the idealisation and `floating`).
    pub(super) options: <Dim<D> as SceneDim<D>>::Options,
    pub(super) materials: Vec<MaterialPlan>,
    pub(super) supports: Vec<SupportPlan>,
    pub(super) loads: Vec<LoadPlan<D>>,
    pub(super) initial_stress: InitialStressPlan,
    /// `[[ties]]`.
    pub(super) ties: Ties,
    /// Who solves `K x = b` ([`Solves::Factorised`] unless the study sets it).
    pub(super) solves: Solves,
}

/// `[[ties]]`: (key path of the set, set, components).
pub(super) type Ties = Vec<(KeyPath, String, Vec<Component>)>;

/// Checks `[[ties]]` (the sets are looked up in the mesh at build).
fn validate_ties(scene: &Scene, dim: usize) -> CliResult<Ties> {
    scene
        .ties
        .iter()
        .enumerate()
        .map(|(i, t)| {
            let p = KeyPath::root().key("ties").index(i);
            Ok((
                p.key("set"),
                t.set.clone(),
                components(&p.key("component"), t.component, dim)?,
            ))
        })
        .collect()
}

/// The components a support or tie names, in a scene of dimension `dim` (2 or 3).
pub(super) fn components(
    path: &KeyPath,
    c: ComponentSpec,
    dim: usize,
) -> CliResult<Vec<Component>> {
    Ok(match (c, dim) {
        (ComponentSpec::X, _) => vec![Component::X],
        (ComponentSpec::Y, _) => vec![Component::Y],
        (ComponentSpec::Both, 2) => vec![Component::X, Component::Y],
        (ComponentSpec::Z, 3) => vec![Component::Z],
        (ComponentSpec::All, 3) => vec![Component::X, Component::Y, Component::Z],
        (ComponentSpec::Both, _) => {
            bail!(
                path,
                "`{path}` = \"both\" is x and y of a 2D scene; a 3D scene takes \"x\", \
                     \"y\", \"z\" or \"all\""
            );
        }
        (ComponentSpec::Z | ComponentSpec::All, _) => {
            bail!(
                path,
                "`{path}`: components \"z\" and \"all\" are for a 3D scene ([analysis] \
                     type = \"3d\"); a 2D scene takes \"x\", \"y\" or \"both\""
            );
        }
    })
}

/// The materials on the mesh's regions (every region exactly one), the supports' and loads'
/// sets, and the model with the supports of the first phase at t = 0 (the others are added and
/// released between phases by the run).
pub(super) fn build<const D: usize>(
    mesh: Mesh<D>,
    plan: ModelPlan<D>,
    functions: &BTreeMap<String, TimeFunction>,
    phases: &[Phase],
) -> CliResult<(ElasticModel<D>, Vec<SupportRt>, Vec<LoadRt<D>>)>
where
    Dim<D>: SceneDim<D>,
{
    let root = KeyPath::root();
    let young_keys = young_keys(&plan.materials);
    let materials = regions(mesh.regions(), plan.materials)?;
    let mut supports = Vec::new();
    let mut paths = Vec::new();
    for s in plan.supports {
        let mut rt = s.rt;
        rt.nodes = node_set(&s.path, &mesh, &s.set)?;
        supports.push(rt);
        paths.push(s.path.parent());
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
        let (sp, mut rt) = (l.path.key("set"), l.rt);
        let set = l.set.unwrap_or_default();
        rt.kind = match rt.kind {
            LoadKind::Traction(_, v) => {
                Dim::<D>::boundary_set(&sp, &mesh, &set)?;
                LoadKind::Traction(set, v)
            }
            LoadKind::Pressure(_, v) => {
                Dim::<D>::boundary_set(&sp, &mesh, &set)?;
                LoadKind::Pressure(set, v)
            }
            LoadKind::Nodal(_, v) => LoadKind::Nodal(node_set(&sp, &mesh, &set)?, v),
            LoadKind::Resultant(_, v) => {
                let nodes = node_set(&sp, &mesh, &set)?;
                for (c, comp) in Component::all::<D>().into_iter().enumerate() {
                    if v[c] != 0.0 && nodes.iter().any(|&n| !tied.contains(&(n, comp))) {
                        bail!(
                            sp,
                            "`{sp}` = \"{set}\": a resultant force along {comp} needs the set \
                                 tied along {comp} (a [[ties]] entry with set = \"{set}\"), so \
                                 that it has one point of application; for a force on each node \
                                 use type = \"nodal_force\""
                        );
                    }
                }
                let Some(&first) = nodes.first() else {
                    bail!(sp, "`{sp}` = \"{set}\" is empty");
                };
                LoadKind::Resultant(first, v)
            }
            kind => kind,
        };
        loads.push(rt);
    }
    for s in supports.iter().filter(|s| s.phases[0]) {
        let f = function_value(&phases[0], &s.name, &s.function, functions, 0.0);
        for &c in &s.components {
            sup.prescribe(&s.nodes, c, s.value * f)
                .map_err(|e| fem(&root.key("supports"), e))?;
        }
    }
    let mut model =
        Dim::<D>::model(mesh, &plan.options, &materials, sup, plan.solves).map_err(|e| {
            let at = match &e {
                FemError::NonFiniteStiffness { region, .. } => young_keys.get(region).cloned(),
                FemError::InvalidParameter {
                    name: "thickness", ..
                } => Some(root.key("analysis").key("thickness")),
                FemError::InvalidTie { .. } => Some(root.key("ties")),
                _ => None,
            };
            fem(&at.unwrap_or_else(|| root.key("supports")), e)
        })?;
    if let Some((gamma, k0, z)) = plan.initial_stress {
        model
            .set_initial_stress(Dim::<D>::geostatic(gamma, k0, z))
            .map_err(|e| fem(&root.key("initial_stress"), e))?;
    }
    Ok((model, supports, loads))
}

/// Each material on its regions: every region must exist in the mesh, have one material only,
/// and every region of the mesh must have one.
pub(super) fn regions(
    element_regions: &[u32],
    plans: Vec<MaterialPlan>,
) -> CliResult<Vec<(u32, Material)>> {
    let mesh_regions: BTreeSet<u32> = element_regions.iter().copied().collect();
    let mut materials: Vec<(u32, Material)> = Vec::new();
    for m in plans {
        for (rp, r) in m.regions {
            if !mesh_regions.contains(&r) {
                bail!(
                    rp,
                    "`{rp}` = {r}: the mesh has no element in region {r} (regions: {})",
                    join(&mesh_regions)
                );
            }
            if materials.iter().any(|(q, _)| *q == r) {
                bail!(rp, "`{rp}` = {r}: region {r} already has a material");
            }
            materials.push((r, m.material));
        }
    }
    if let Some(r) = mesh_regions
        .iter()
        .find(|r| !materials.iter().any(|(q, _)| q == *r))
    {
        bail!(
            KeyPath::root().key("materials"),
            "region {r} of the mesh has no material (add a [[materials]] with region = {r})"
        );
    }
    Ok(materials)
}

/// The key path of each region's Young's modulus (an element stiffness that overflows is the
/// material's fault, not the supports').
pub(super) fn young_keys(materials: &[MaterialPlan]) -> BTreeMap<u32, KeyPath> {
    materials
        .iter()
        .flat_map(|m| m.regions.iter().map(|(_, r)| (*r, m.young.clone())))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn components_by_dimension_works() {
        let p = KeyPath::root().key("supports").index(0).key("component");
        assert_eq!(
            components(&p, ComponentSpec::Both, 2).unwrap(),
            [Component::X, Component::Y]
        );
        assert_eq!(
            components(&p, ComponentSpec::All, 3).unwrap(),
            [Component::X, Component::Y, Component::Z]
        );
        assert_eq!(components(&p, ComponentSpec::Z, 3).unwrap(), [Component::Z]);
        assert_eq!(components(&p, ComponentSpec::X, 3).unwrap(), [Component::X]);
    }

    #[test]
    fn components_rejects_the_other_dimension() {
        let p = KeyPath::root().key("supports").index(0).key("component");
        for (c, dim) in [
            (ComponentSpec::Both, 3),
            (ComponentSpec::Z, 2),
            (ComponentSpec::All, 2),
        ] {
            let e = components(&p, c, dim).unwrap_err();
            assert_eq!(e.path.as_ref().unwrap(), &p, "{c:?} in {dim}D");
        }
    }
}
