//! The seed's pile pull-out (chapter 6, Plancoët) on the PETSc structure against the direct
//! path: `petsc_check pile [mumps] [seed] [plane]`.
//!
//! Built as contact-solver's `tests/support/pile_plastic.rs` builds it for its elastic soil,
//! through the library (fem-core's pile generator, contact-solver's zones; not through the
//! bipo crate, which would make a dependency cycle): the axisymmetric P2 pile-in-soil mesh
//! with the tip detached, both bodies linear elastic, self-weight with the geostatic K0
//! stress of seed eq. 6.1 in the soil (the pile unstressed), the RCCM shaft of table 6.3
//! (Coulomb at the tip corner, frictionless at the tip).
//!
//! ```text
//! step 0        geostatic: self-weight and σ₀, head held at u_z = 0
//! steps 1..=n   the head lifted by v₀ k / n (v₀ = 15 mm)
//! reading       the head load Q = 2π (W_p − Σ_pile f_c,z) (kN, full ring) of the pile's
//!               equilibrium, and every contact's (r_n, r_t) and node displacement
//! ```
//! Coarse (8 shaft cells, 4 increments) by default, for CI; `seed` runs the seed's mesh
//! (32 shaft cells, the 65 shaft pairs) with 50 increments. `plane` solves the same meridian
//! in plane strain (not the pile, a check of the other 2D setting through the same path).
//! Units kN, m, kPa.

use super::{Answer, Res, relative};
use bipotential_petsc::{LinearSolver, Petsc, PetscStructure};
use contact_laws::{BetaScheme, Rccm, RccmParams};
use contact_solver::coupling::zone::PairNormals;
use contact_solver::{ContactSimulation, ContactZone, SimulationSettings};
use fem_core::generate::{PILE, PileSpec, SOIL, pile_in_soil};
use fem_core::{
    Component, FemError, Idealization, LinearElasticModel, Material, Mesh, Structure, Supports,
    geostatic,
};
use std::collections::HashMap;
use std::f64::consts::PI;
use std::time::Instant;

/// Soil `E` (kPa), `ν`, `γ` (kN/m³) and `K0` (seed ch. 6).
const SOIL_YOUNG: f64 = 3e4;
const SOIL_POISSON: f64 = 0.33;
const SOIL_WEIGHT: f64 = 20.0;
const K0: f64 = 0.43;
/// Pile `E` (Plancoët, kPa), `ν`, `γ`.
const PILE_YOUNG: f64 = 3e7;
const PILE_POISSON: f64 = 0.3;
const PILE_WEIGHT: f64 = 78.0;
/// Head displacement `v₀` (m).
const HEAD_DISPLACEMENT: f64 = 0.015;

/// The pull-out's data, the same for both paths.
struct Scene {
    mesh: Mesh,
    supports: Supports,
    zones: Vec<ContactZone<Rccm>>,
    head: Vec<usize>,
    pile_nodes: Vec<usize>,
}

fn materials() -> Res<[(u32, Material); 2]> {
    Ok([
        (SOIL, Material::new(SOIL_YOUNG, SOIL_POISSON, SOIL_WEIGHT)?),
        (PILE, Material::new(PILE_YOUNG, PILE_POISSON, PILE_WEIGHT)?),
    ])
}

fn scene(cells: [usize; 3]) -> Res<Scene> {
    let spec = PileSpec {
        cells_shaft: cells[0],
        cells_soil_r: cells[1],
        cells_below_tip: cells[2],
        ..PileSpec::default()
    };
    let radius = 0.5 * spec.diameter;
    let (mesh, tip_pile, tip_soil) = detach_tip(pile_in_soil(&spec)?, radius, spec.length)?;
    let shaft_pile = mesh.node_set("interface_pile")?.to_vec();
    let shaft_soil = mesh.node_set("interface_soil")?.to_vec();
    let head = mesh.node_set("pile_head")?.to_vec();
    let mut pile_nodes: Vec<usize> = (0..mesh.element_count())
        .filter(|&e| mesh.regions()[e] == PILE)
        .flat_map(|e| mesh.element(e).to_vec())
        .collect();
    pile_nodes.sort_unstable();
    pile_nodes.dedup();
    let mut supports = Supports::new();
    supports
        .fix(mesh.node_set("axis")?, Component::X)
        .fix(mesh.node_set("outer")?, Component::X)
        .fix(mesh.node_set("base")?, Component::Y)
        .prescribe(&head, Component::Y, 0.0)?;
    let shaft_z: Vec<f64> = shaft_pile.iter().map(|&n| mesh.nodes()[n][1]).collect();
    let shaft_areas = simpson(&shaft_z, |_| radius);
    let mut tip_line: Vec<f64> = tip_pile.iter().map(|&n| mesh.nodes()[n][0]).collect();
    tip_line.push(radius);
    let mut tip_areas = simpson(&tip_line, |r| r);
    tip_areas.pop();
    // table 6.3, Plancoët
    let shaft_law = RccmParams {
        c_n: 10500.0,
        c_t: 10500.0,
        w: 3e-3,
        alpha: 0.0,
        mu: 0.46,
        m: 1,
        beta_0: 1.0,
        scheme: BetaScheme::ImplicitEuler,
    };
    let corner = RccmParams {
        beta_0: 0.0,
        ..shaft_law
    };
    let tip = RccmParams {
        mu: 0.0,
        beta_0: 0.0,
        ..shaft_law
    };
    let alert = 1e-3;
    let zones = vec![
        ContactZone::node_pairs(
            "shaft",
            shaft_pile[1..].to_vec(),
            shaft_soil[1..].to_vec(),
            PairNormals::Fixed([-1.0, 0.0]),
            Rccm::new(shaft_law)?,
            alert,
        )
        .with_areas(shaft_areas[1..].to_vec()),
        ContactZone::node_pairs(
            "tip_corner",
            vec![shaft_pile[0]],
            vec![shaft_soil[0]],
            PairNormals::Fixed([-1.0, 0.0]),
            Rccm::new(corner)?,
            alert,
        )
        .with_areas(vec![shaft_areas[0]]),
        ContactZone::node_pairs(
            "tip",
            tip_pile,
            tip_soil,
            PairNormals::Fixed([0.0, 1.0]),
            Rccm::new(tip)?,
            alert,
        )
        .with_areas(tip_areas),
    ];
    Ok(Scene {
        mesh,
        supports,
        zones,
        head,
        pile_nodes,
    })
}

/// One increment: the head displacement, the head load, the contacts.
struct Increment {
    v: f64,
    q: f64,
    answer: Answer,
}

/// The geostatic step and `steps` pull-out increments on `body`; what `after` reads of the
/// body at the end.
fn pull<S: Structure<2>, R>(
    body: S,
    scene: &Scene,
    steps: usize,
    set: impl Fn(&mut S, &[usize], f64) -> Res<()>,
    after: impl FnOnce(&S) -> R,
) -> Res<(Vec<Increment>, R)> {
    let mut sim = ContactSimulation::new(body, scene.zones.clone(), SimulationSettings::default())?;
    let spec = PileSpec::default();
    let r = 0.5 * spec.diameter;
    // per radian: γ_p ∫ r dr dz = γ_p R² L / 2
    let weight = PILE_WEIGHT * r * r * spec.length / 2.0;
    let mut out = Vec::with_capacity(steps + 1);
    for k in 0..=steps {
        let v = HEAD_DISPLACEMENT * k as f64 / steps as f64;
        if k > 0 {
            set(sim.structure_mut(), &scene.head, v)?;
        }
        let res = sim.step(1.0 + k as f64, 1.0)?;
        let mut contact_on_pile = 0.0;
        let mut answer = Answer::default();
        for (c, rec) in sim.candidates().iter().zip(&res.contacts) {
            if scene.pile_nodes.binary_search(&c.node).is_ok() {
                contact_on_pile += rec.force()[1];
            }
            answer.reactions.push([rec.r.n, rec.r.t[0], 0.0]);
            let u = sim.nodal_displacement(c.node);
            answer.displacements.push([u[0], u[1], 0.0]);
        }
        out.push(Increment {
            v,
            q: 2.0 * PI * (weight - contact_on_pile),
            answer,
        });
    }
    Ok((out, after(sim.structure())))
}

/// The pull-out on the PETSc structure and (rank 0) on fem-core's `LinearElasticModel`: the
/// head load–displacement curve and every increment's contacts within 1e-8 relative.
pub fn compare(petsc: &Petsc, seed: bool, plane: bool, solver: LinearSolver) -> Res<()> {
    let (idealization, name) = if plane {
        (Idealization::PlaneStrain, "pile plane strain")
    } else {
        (Idealization::Axisymmetric, "pile")
    };
    let (cells, steps) = if seed {
        ([32, 20, 16], 50)
    } else {
        ([8, 6, 4], 4)
    };
    let scene = scene(cells)?;
    let sigma_0 = [(SOIL, geostatic(SOIL_WEIGHT, K0, 0.0))];
    let serial = if petsc.rank() == 0 {
        let start = Instant::now();
        let mut model = LinearElasticModel::new(
            scene.mesh.clone(),
            idealization,
            &materials()?,
            scene.supports.clone(),
        )?;
        model.add_self_weight()?;
        model.set_initial_stress_by_region(&sigma_0)?;
        let (curve, ()) = pull(
            model,
            &scene,
            steps,
            |m, head, v| Ok(m.set_prescribed(head, Component::Y, v)?),
            |_| (),
        )?;
        Some((curve, start.elapsed().as_secs_f64()))
    } else {
        None
    };
    let start = Instant::now();
    let mut body = PetscStructure::plane(
        petsc,
        scene.mesh.clone(),
        idealization,
        &materials()?,
        scene.supports.clone(),
        solver,
    )?;
    body.add_self_weight()?;
    body.set_initial_stress_by_region(&sigma_0)?;
    let dofs = body.dof_count();
    let (distributed, (solves, iterations)) = pull(
        body,
        &scene,
        steps,
        |s, head, v| Ok(s.set_prescribed(head, Component::Y, v)?),
        PetscStructure::solve_counts,
    )?;
    let seconds = start.elapsed().as_secs_f64();
    let Some((serial, serial_seconds)) = serial else {
        return Ok(());
    };
    let q_scale = serial.iter().fold(0.0_f64, |m, i| m.max(i.q.abs()));
    let (mut worst_q, mut worst_r, mut worst_u) = (0.0_f64, 0.0_f64, 0.0_f64);
    for (d, s) in distributed.iter().zip(&serial) {
        if d.answer.reactions.len() != s.answer.reactions.len() {
            return Err(format!("{name} v = {}: the contact lists differ", s.v).into());
        }
        worst_q = worst_q.max((d.q - s.q).abs() / q_scale);
        worst_r = worst_r.max(relative(&d.answer.reactions, &s.answer.reactions));
        worst_u = worst_u.max(relative(&d.answer.displacements, &s.answer.displacements));
    }
    let last = serial.last().ok_or("no increment")?;
    let closed = last.answer.reactions.iter().filter(|r| r[0] > 0.0).count();
    println!(
        "{name} ({} ranks, {dofs} dofs, {} contacts, {closed} closed at the end, {steps} increments): \
         head load Q({:.4} m) = {:.3} kN; curve {worst_q:.2e}, reactions {worst_r:.2e}, \
         displacements {worst_u:.2e} relative to the direct path",
        petsc.size(),
        last.answer.reactions.len(),
        last.v,
        last.q,
    );
    // the contacts must carry the pile: a curve of zeros would compare equal
    if closed == 0 || last.q.is_nan() || last.q <= 0.0 {
        return Err(format!("{name}: no load carried (Q = {}, {closed} closed)", last.q).into());
    }
    // the test's promise: the serial answer to 1e-8 relative
    if !(worst_q <= 1e-8 && worst_r <= 1e-8 && worst_u <= 1e-8) {
        return Err(format!(
            "{name}: differs from the direct path ({worst_q:e}, {worst_r:e}, {worst_u:e})"
        )
        .into());
    }
    println!(
        "{name}: OK ({seconds:.2} s distributed: {solves} solves, {iterations} Krylov iterations; \
         {serial_seconds:.2} s direct)"
    );
    Ok(())
}

/// Consistent nodal weights `∫ N_i w ds` of a line of P2 nodes at increasing `s` (Simpson,
/// exact for a linear weight `w`).
fn simpson(s: &[f64], weight: impl Fn(f64) -> f64) -> Vec<f64> {
    let mut a = vec![0.0; s.len()];
    for k in (0..s.len() - 1).step_by(2) {
        let h = s[k + 2] - s[k];
        a[k] += h / 6.0 * weight(s[k]);
        a[k + 1] += 4.0 * h / 6.0 * weight(s[k + 1]);
        a[k + 2] += h / 6.0 * weight(s[k + 2]);
    }
    a
}

/// The preset's `detach_tip` (as contact-solver's `tests/support/pile_plastic.rs`): the
/// pile's tip nodes at `r < R` duplicated so the tip can lift off; returns the mesh and the
/// paired tip nodes (pile copies, soil originals), sorted by `r`; the pile copy of the axis
/// node joins `"axis"`.
fn detach_tip(
    mesh: Mesh,
    radius: f64,
    length: f64,
) -> Result<(Mesh, Vec<usize>, Vec<usize>), FemError> {
    let tol = 1e-9 * radius.max(length);
    let npe = mesh.kind().node_count();
    let in_pile = |n: usize| {
        (0..mesh.element_count()).any(|e| mesh.regions()[e] == PILE && mesh.element(e).contains(&n))
    };
    let mut on_tip: Vec<usize> = (0..mesh.node_count())
        .filter(|&n| {
            let p = mesh.nodes()[n];
            (p[1] + length).abs() <= tol && p[0] < radius - tol && in_pile(n)
        })
        .collect();
    on_tip.sort_by(|a, b| mesh.nodes()[*a][0].total_cmp(&mesh.nodes()[*b][0]));
    let mut nodes = mesh.nodes().to_vec();
    let mut copy = HashMap::new();
    for &n in &on_tip {
        copy.insert(n, nodes.len());
        nodes.push(nodes[n]);
    }
    let mut connectivity = mesh.connectivity().to_vec();
    for (cell, &region) in connectivity.chunks_exact_mut(npe).zip(mesh.regions()) {
        if region == PILE {
            for node in cell.iter_mut() {
                if let Some(&c) = copy.get(node) {
                    *node = c;
                }
            }
        }
    }
    let mut out = Mesh::new(nodes, mesh.kind(), connectivity, mesh.regions().to_vec())?;
    for name in mesh.edge_set_names() {
        out.add_edge_set(name, mesh.edge_set(name)?.to_vec())?;
    }
    for name in mesh.node_set_names() {
        let mut set = mesh.node_set(name)?.to_vec();
        if name == "axis" {
            let extra: Vec<usize> = set.iter().filter_map(|n| copy.get(n)).copied().collect();
            set.extend(extra);
        }
        out.add_node_set(name, set)?;
    }
    let tip_pile = on_tip.iter().map(|n| copy[n]).collect();
    Ok((out, tip_pile, on_tip))
}

/// `petsc_check errors`: the 2D constructor and the loads refuse bad data with fem-core's
/// variants, naming the parameter, before any PETSc call that could hang a rank.
pub fn errors(petsc: &Petsc) -> Res<()> {
    let scene = scene([2, 2, 2])?;
    let build = |mesh: Mesh, idealization, supports: Supports| {
        PetscStructure::plane(
            petsc,
            mesh,
            idealization,
            &materials()?,
            supports,
            LinearSolver::default(),
        )
        .map_err(Box::<dyn std::error::Error>::from)
    };
    let mut checks: Vec<(&str, bool)> = Vec::new();
    // a node at r < 0 in axisymmetry
    let mut nodes = scene.mesh.nodes().to_vec();
    nodes[3][0] = -1.0;
    let moved = Mesh::new(
        nodes,
        scene.mesh.kind(),
        scene.mesh.connectivity().to_vec(),
        scene.mesh.regions().to_vec(),
    )?;
    let e = build(moved, Idealization::Axisymmetric, scene.supports.clone()).unwrap_err();
    checks.push((
        "negative radius",
        matches!(
            e.downcast_ref(),
            Some(bipotential_petsc::PetscError::Fem(
                FemError::NegativeRadius { node: 3, .. }
            ))
        ),
    ));
    let e = build(
        scene.mesh.clone(),
        Idealization::PlaneStress {
            thickness: f64::NAN,
        },
        scene.supports.clone(),
    )
    .unwrap_err();
    checks.push((
        "thickness",
        e.to_string().contains("thickness")
            && matches!(
                e.downcast_ref(),
                Some(bipotential_petsc::PetscError::Fem(
                    FemError::InvalidParameter {
                        name: "thickness",
                        ..
                    }
                ))
            ),
    ));
    let e = PetscStructure::plane(
        petsc,
        scene.mesh.clone(),
        Idealization::Axisymmetric,
        &materials()?[..1],
        scene.supports.clone(),
        LinearSolver::default(),
    )
    .unwrap_err();
    checks.push((
        "missing material",
        matches!(
            e,
            bipotential_petsc::PetscError::Fem(FemError::MissingMaterial { region: PILE, .. })
        ),
    ));
    let mut tied = scene.supports.clone();
    tied.tie(&scene.head, Component::X)?;
    let e = build(scene.mesh.clone(), Idealization::Axisymmetric, tied).unwrap_err();
    checks.push((
        "tie",
        matches!(
            e.downcast_ref(),
            Some(bipotential_petsc::PetscError::Unsupported { .. })
        ),
    ));
    // the loads, on a structure that builds
    let mut body = build(
        scene.mesh.clone(),
        Idealization::Axisymmetric,
        scene.supports.clone(),
    )?;
    let e = body.add_body_force(|_| [0.0, f64::NAN]);
    checks.push((
        "body force",
        matches!(
            e,
            Err(bipotential_petsc::PetscError::Fem(
                FemError::InvalidParameter {
                    name: "body force",
                    ..
                }
            ))
        ),
    ));
    let e = body.set_initial_stress_by_region(&[(7, geostatic(SOIL_WEIGHT, K0, 0.0))]);
    checks.push((
        "unknown region",
        matches!(
            e,
            Err(bipotential_petsc::PetscError::Fem(
                FemError::UnknownRegion { region: 7 }
            ))
        ),
    ));
    let e = body.add_nodal_force(body.mesh().node_count(), [1.0, 0.0]);
    checks.push((
        "unknown node",
        matches!(
            e,
            Err(bipotential_petsc::PetscError::Fem(
                FemError::UnknownNode { .. }
            ))
        ),
    ));
    let failed: Vec<&str> = checks.iter().filter(|c| !c.1).map(|c| c.0).collect();
    if !failed.is_empty() {
        return Err(format!("errors not reported as documented: {failed:?}").into());
    }
    if petsc.rank() == 0 {
        println!("errors: OK ({} cases)", checks.len());
    }
    Ok(())
}
