//! The primal active-set path (`FlexibilityMode::ActiveSet`, no `F*`) against the dense `F*`
//! path on the same scenes: reactions, gaps and statuses agree to the solver tolerance;
//! its scope is enforced with typed errors, and `Auto` falls back where it does not apply.

#![cfg(feature = "fe")]

use crate::support::hertz_scene::HertzScene;
use contact_laws::{BetaScheme, Coulomb, Rccm, RccmParams, Signorini, StandardLaw};
use contact_solver::{
    ContactSimulation, ContactZone, FlexibilityMode, InterfaceStatus, RigidLine,
    SimulationSettings, SolverError, StepResult,
};
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::{
    Component, ElementKind, Idealization, LinearElasticModel, Material, Mesh, Supports,
};

fn block(kind: ElementKind, nx: usize, ny: usize) -> (Mesh, Vec<usize>, Vec<usize>) {
    let mut spec = RectangleSpec::new([0.0, 2.0], [0.0, 1.0], nx, ny);
    spec.kind = kind;
    let mesh = rectangle(&spec).unwrap();
    let top = mesh.node_set("top").unwrap().to_vec();
    let bottom = mesh.node_set("bottom").unwrap().to_vec();
    (mesh, top, bottom)
}

fn model(mesh: Mesh, top: &[usize]) -> LinearElasticModel {
    let mut supports = Supports::new();
    supports.prescribe(top, Component::Y, 0.0).unwrap();
    supports.prescribe(top, Component::X, 0.0).unwrap();
    LinearElasticModel::new(
        mesh,
        Idealization::PlaneStrain,
        &[(0, Material::new(1000.0, 0.3, 0.0).unwrap())],
        supports,
    )
    .unwrap()
}

/// A P2 block pressed on a tilted LINE, then pushed sideways in two steps (Coulomb μ = 0.3):
/// stick, slip and separation all occur, and the tangential history carries over.
fn pushed_block<L: contact_laws::ContactLaw + Clone>(
    mode: FlexibilityMode,
    law: L,
    tol: f64,
) -> (Vec<StepResult>, contact_solver::Counters) {
    let (mesh, top, bottom) = block(ElementKind::Tri6, 16, 8);
    let model = model(mesh, &top);
    let ground = RigidLine::new([-1.0, -0.01], [3.0, -0.03]).unwrap();
    let zone = ContactZone::rigid("base", bottom, ground, law, 0.1);
    let mut settings = SimulationSettings::default().with_flexibility(mode);
    settings.solver.tol = tol;
    let mut sim = ContactSimulation::new(model, vec![zone], settings).unwrap();
    let mut out = Vec::new();
    for (k, (dy, dx)) in [(-0.02, 0.0), (-0.03, 0.002), (-0.03, 0.02), (-0.03, 0.02)]
        .into_iter()
        .enumerate()
    {
        sim.structure_mut()
            .set_prescribed(&top, Component::Y, dy)
            .unwrap();
        sim.structure_mut()
            .set_prescribed(&top, Component::X, dx)
            .unwrap();
        out.push(sim.step(k as f64 + 1.0, 1.0).unwrap());
    }
    (out, sim.counters())
}

/// Largest difference of the reactions, gaps and slip increments of two runs, relative to the
/// largest reaction and the largest gap.
fn compare(a: &[StepResult], b: &[StepResult]) -> (f64, f64) {
    let r_scale = a
        .iter()
        .flat_map(|s| &s.contacts)
        .fold(0.0_f64, |m, c| m.max(c.r.n.abs()));
    let g_scale = a.iter().flat_map(|s| &s.contacts).fold(0.0_f64, |m, c| {
        m.max(c.gap.abs()).max(c.slip_increment.abs())
    });
    let (mut dr, mut dg) = (0.0_f64, 0.0_f64);
    for (sa, sb) in a.iter().zip(b) {
        for (x, y) in sa.contacts.iter().zip(&sb.contacts) {
            dr = dr
                .max((x.r.n - y.r.n).abs())
                .max((x.r.t[0] - y.r.t[0]).abs());
            dg = dg
                .max((x.gap - y.gap).abs())
                .max((x.slip_increment - y.slip_increment).abs());
            // a closed contact whose slip increment is below the solver tolerance in both runs
            // (1e-8 of the largest gap or slip, against a tolerance of 1e-11) is on the cone's
            // boundary: sticking and sliding are the same state there, and which one a path
            // reports depends on the last guess
            let closed =
                |s: InterfaceStatus| matches!(s, InterfaceStatus::Stick | InterfaceStatus::Slip);
            let boundary = closed(x.status)
                && closed(y.status)
                && x.slip_increment.abs().max(y.slip_increment.abs()) <= 1e-8 * g_scale;
            if x.r.n > 1e-6 * r_scale && !boundary {
                assert_eq!(x.status, y.status, "{x:?} vs {y:?}");
            }
        }
    }
    (dr / r_scale, dg / g_scale)
}

#[test]
fn coulomb_block_matches_dense() {
    let law = Coulomb::new(0.3).unwrap();
    let (dense, cd) = pushed_block(FlexibilityMode::Dense, law, 1e-11);
    let (active, ca) = pushed_block(FlexibilityMode::ActiveSet, law, 1e-11);
    assert_eq!(cd.active_set_steps, 0);
    assert_eq!(ca.active_set_steps, 4);
    assert_eq!(ca.flexibility_builds, 0);
    assert_eq!(ca.flexibility_columns, 0);
    let (dr, dg) = compare(&dense, &active);
    let statuses: std::collections::HashSet<_> = active
        .iter()
        .flat_map(|s| s.contacts.iter().map(|c| c.status))
        .collect();
    eprintln!(
        "Coulomb: max |Δr| / max r = {dr:.1e}, max |Δgap| / max gap = {dg:.1e}; \
         active set: {} factorisations, {} solves, {} iterations ({} on the correction \
         columns); dense: {} F* columns",
        ca.active_set_factorizations,
        ca.active_set_solves,
        ca.contact_iterations,
        ca.active_set_inner_iterations,
        cd.flexibility_columns
    );
    assert!(statuses.len() >= 3, "{statuses:?}");
    // the fronts moved on the correction columns too (21 of 49 iterations when written)
    assert!(ca.active_set_inner_iterations > 0);
    assert!(dr <= 1e-8, "{dr}");
    assert!(dg <= 1e-7, "{dg}");
}

#[test]
fn signorini_block_matches_dense_and_reuses_the_factorisation() {
    let (dense, _) = pushed_block(FlexibilityMode::Dense, Signorini, 1e-11);
    let (active, ca) = pushed_block(FlexibilityMode::ActiveSet, Signorini, 1e-11);
    let (dr, dg) = compare(&dense, &active);
    eprintln!(
        "Signorini: max |Δr| / max r = {dr:.1e}, max |Δgap| / max gap = {dg:.1e}; {} \
         factorisations, {} solves",
        ca.active_set_factorizations, ca.active_set_solves
    );
    assert!(dr <= 1e-9 && dg <= 1e-9, "{dr} {dg}");
    // frictionless: steps 3 and 4 have the same closed set as step 2 (the push is tangential)
    // and the stiffness does not change with prescribed values, so the factorisation of the
    // constrained stiffness is reused
    assert!(
        ca.active_set_factorizations < ca.active_set_solves,
        "{} factorisations for {} solves",
        ca.active_set_factorizations,
        ca.active_set_solves
    );
}

#[test]
fn hertz_axisymmetric_matches_dense_including_the_axis_node() {
    // the axis node has one free dof (u_r = 0 prescribed): it is handled as a scalar frame
    let scene = HertzScene::new(Idealization::Axisymmetric, ElementKind::Tri6, 4);
    let run = |mode| {
        let mut settings = SimulationSettings::default().with_flexibility(mode);
        settings.solver.tol = 1e-11;
        let mut sim = scene.simulation(settings);
        let res = sim.step(1.0, 1.0).unwrap();
        let m = scene.measure(&sim, &res);
        (res, m, sim.counters())
    };
    let (dense, md, _) = run(FlexibilityMode::Dense);
    let (active, ma, ca) = run(FlexibilityMode::ActiveSet);
    assert_eq!(ca.active_set_steps, 1);
    let (dr, dg) = compare(std::slice::from_ref(&dense), std::slice::from_ref(&active));
    eprintln!(
        "Hertz axisymmetric: P {} vs {}, a {} vs {}; |Δr| {dr:.1e}, |Δgap| {dg:.1e}; {} \
         factorisations",
        md.p_total, ma.p_total, md.a_fe, ma.a_fe, ca.active_set_factorizations
    );
    assert!(dr <= 1e-9 && dg <= 1e-9, "{dr} {dg}");
    assert!((md.a_fe - ma.a_fe).abs() <= 1e-9 * md.a_fe);
}

fn glue() -> StandardLaw {
    StandardLaw::from(
        Rccm::new(RccmParams {
            c_n: 1e3,
            c_t: 1e3,
            w: 1e-3,
            alpha: 0.0,
            mu: 0.3,
            m: 1,
            beta_0: 1.0,
            scheme: BetaScheme::ImplicitEuler,
        })
        .unwrap(),
    )
}

#[test]
fn auto_uses_the_active_set_past_the_limit_and_keeps_dense_for_adhesion() {
    let law = Coulomb::new(0.3).unwrap();
    let (dense, _) = pushed_block(FlexibilityMode::Dense, law, 1e-11);
    let (auto, c) = pushed_block(FlexibilityMode::Auto { dense_limit: 10 }, law, 1e-11);
    assert_eq!(c.active_set_steps, 4);
    let (dr, _) = compare(&dense, &auto);
    assert!(dr <= 1e-8, "{dr}");

    // an intact RCCM interface is adhesive: Auto keeps the dense F* (faster on every
    // adhesive scene measured, docs/benchmarks.md), MatrixFree refuses it
    let (_, c) = pushed_block(FlexibilityMode::Auto { dense_limit: 10 }, glue(), 1e-9);
    assert_eq!(c.active_set_steps, 0);
    assert!(c.flexibility_builds > 0);
    let (mesh, top, bottom) = block(ElementKind::Tri6, 8, 4);
    let ground = RigidLine::new([-1.0, -0.01], [3.0, -0.03]).unwrap();
    let zone = ContactZone::rigid("base", bottom, ground, glue(), 0.1);
    let settings = SimulationSettings::default().with_flexibility(FlexibilityMode::MatrixFree);
    let mut sim = ContactSimulation::new(model(mesh, &top), vec![zone], settings).unwrap();
    match sim.step(1.0, 1.0) {
        Err(SolverError::InvalidSetting { what, .. }) => assert_eq!(what, "flexibility"),
        other => panic!("expected InvalidSetting, got {other:?}"),
    }
}

/// Largest difference of β between two runs.
fn beta_difference(a: &[StepResult], b: &[StepResult]) -> f64 {
    a.iter()
        .zip(b)
        .flat_map(|(sa, sb)| sa.contacts.iter().zip(&sb.contacts))
        .fold(0.0_f64, |m, (x, y)| m.max((x.beta - y.beta).abs()))
}

#[test]
fn adhesive_block_matches_dense() {
    // the glued block pressed on the tilted line and pushed: the glue softens and breaks
    // under the push (u₀ = √(w/C) = 1e-3 against slips of 2e-2), the springs sit in the
    // stiffness of the primal solve. Both paths stop the adhesion iteration at a β change of
    // 1e-8, from different iterates (Newton dense, the fixed point here): reactions within
    // 1e-6 of the largest, β within 1e-6
    let (dense, _) = pushed_block(FlexibilityMode::Dense, glue(), 1e-11);
    let (active, c) = pushed_block(FlexibilityMode::ActiveSet, glue(), 1e-11);
    assert_eq!(c.active_set_steps, 4);
    assert_eq!(c.flexibility_columns, 0);
    assert!(c.adhesion_iterations > 4, "{c:?}");
    let betas: Vec<f64> = active
        .iter()
        .flat_map(|s| s.contacts.iter().map(|c| c.beta))
        .collect();
    let weakest = betas.iter().fold(1.0_f64, |m, &b| m.min(b));
    assert!(weakest < 0.1, "the glue breaks somewhere: β ≥ {weakest}");
    let (dr, dg) = compare(&dense, &active);
    let db = beta_difference(&dense, &active);
    eprintln!(
        "adhesive block: max |Δr| / max r = {dr:.1e}, max |Δgap| / max gap = {dg:.1e}, max \
         |Δβ| = {db:.1e}; {} adhesion iterations, {} factorisations",
        c.adhesion_iterations, c.active_set_factorizations
    );
    assert!(dr <= 1e-6 && dg <= 1e-6 && db <= 1e-6, "{dr} {dg} {db}");
}

/// Two blocks, the upper one's bottom nodes against the lower one's top: node-to-segment on
/// non-matching meshes (4 against 3 cells) or node pairs on matching ones; the lower block is
/// clamped at its bottom, the upper one's top pressed down by `press` and moved sideways by
/// `push`, in two steps. `hold`: the upper block's bottom-left node (a contactor) is held
/// horizontally, so that its pair's target is renamed instead.
fn two_blocks<L: contact_laws::ContactLaw + Clone>(
    mode: FlexibilityMode,
    law: L,
    pairs: bool,
    hold: bool,
) -> (Vec<StepResult>, contact_solver::Counters) {
    let (nx_low, nx_up) = if pairs { (6, 6) } else { (8, 6) };
    let mut low_spec = RectangleSpec::new([0.0, 2.0], [0.0, 1.0], nx_low, 3);
    low_spec.kind = ElementKind::Tri6;
    let mut up_spec = RectangleSpec::new([0.0, 2.0], [1.0, 2.0], nx_up, 3);
    up_spec.kind = ElementKind::Tri6;
    let low = rectangle(&low_spec).unwrap();
    let up = rectangle(&up_spec).unwrap();
    let off = low.node_count();
    let mut nodes = low.nodes().to_vec();
    nodes.extend_from_slice(up.nodes());
    let mut conn = low.connectivity().to_vec();
    conn.extend(up.connectivity().iter().map(|n| n + off));
    let regions = vec![0; low.element_count() + up.element_count()];
    let mesh = Mesh::new(nodes, ElementKind::Tri6, conn, regions).unwrap();
    let shift = |v: &[usize]| v.iter().map(|n| n + off).collect::<Vec<_>>();
    let up_bottom = shift(up.node_set("bottom").unwrap());
    let up_top = shift(up.node_set("top").unwrap());
    let low_top = low.node_set("top").unwrap().to_vec();
    let low_bottom = low.node_set("bottom").unwrap().to_vec();
    let mut supports = Supports::new();
    supports
        .fix(&low_bottom, Component::X)
        .fix(&low_bottom, Component::Y);
    supports.prescribe(&up_top, Component::X, 0.0).unwrap();
    supports.prescribe(&up_top, Component::Y, 0.0).unwrap();
    if hold {
        let corner = *up_bottom
            .iter()
            .min_by(|&&a, &&b| mesh.nodes()[a][0].total_cmp(&mesh.nodes()[b][0]))
            .unwrap();
        supports.fix(&[corner], Component::X);
    }
    let model = LinearElasticModel::new(
        mesh,
        Idealization::PlaneStrain,
        &[(0, Material::new(1000.0, 0.3, 0.0).unwrap())],
        supports,
    )
    .unwrap();
    let zone = if pairs {
        // the same x on both sides: pair them by position
        let mut by_x = low_top.clone();
        by_x.sort_by(|&a, &b| model.mesh().nodes()[a][0].total_cmp(&model.mesh().nodes()[b][0]));
        let mut contactor = up_bottom.clone();
        contactor
            .sort_by(|&a, &b| model.mesh().nodes()[a][0].total_cmp(&model.mesh().nodes()[b][0]));
        ContactZone::node_pairs("interface", contactor, by_x, Some([0.0, 1.0]), law, 0.1)
    } else {
        ContactZone::node_to_segment("interface", up_bottom, low_top, law, 0.1)
    };
    let mut settings = SimulationSettings::default().with_flexibility(mode);
    settings.solver.tol = 1e-11;
    let mut sim = ContactSimulation::new(model, vec![zone], settings).unwrap();
    // the top's left part pressed, its right part lifted: the interface opens on the right
    let x_of = |n: usize| sim.structure().mesh().nodes()[n][0];
    let (left, right): (Vec<usize>, Vec<usize>) = up_top.iter().partition(|&&n| x_of(n) < 1.2);
    let mut out = Vec::new();
    for (k, (dy, dx)) in [(-0.01, 0.0), (-0.01, 0.02)].into_iter().enumerate() {
        let s = sim.structure_mut();
        s.set_prescribed(&left, Component::Y, dy).unwrap();
        s.set_prescribed(&right, Component::Y, 0.01).unwrap();
        s.set_prescribed(&up_top, Component::X, dx).unwrap();
        out.push(sim.step(k as f64 + 1.0, 1.0).unwrap());
    }
    (out, sim.counters())
}

#[test]
fn two_bodies_match_dense_node_to_segment_and_node_pairs() {
    // the contactor's dofs carry its target's motion (u_a = Pᵀ x + Σ w_k u_k): the same
    // answer as the dense F* to the tolerance (1e-11; 1e-8 of the largest reaction allowed)
    for pairs in [false, true] {
        let coulomb = Coulomb::new(0.6).unwrap();
        let (dense, cd) = two_blocks(FlexibilityMode::Dense, coulomb, pairs, false);
        let (active, ca) = two_blocks(FlexibilityMode::ActiveSet, coulomb, pairs, false);
        assert_eq!(cd.active_set_steps, 0);
        assert_eq!(ca.active_set_steps, 2, "pairs {pairs}");
        assert_eq!(ca.flexibility_columns, 0);
        let (dr, dg) = compare(&dense, &active);
        let statuses: std::collections::HashSet<_> = active
            .iter()
            .flat_map(|s| s.contacts.iter().map(|c| c.status))
            .collect();
        eprintln!(
            "two bodies (pairs {pairs}), Coulomb: max |Δr| / max r = {dr:.1e}, max |Δgap| / \
             max gap = {dg:.1e}; statuses {statuses:?}; {} iterations",
            ca.contact_iterations
        );
        assert!(statuses.len() >= 3, "{statuses:?}");
        assert!(dr <= 1e-8, "pairs {pairs}: {dr}");
        assert!(dg <= 1e-7, "pairs {pairs}: {dg}");
        let (dense, _) = two_blocks(FlexibilityMode::Dense, Signorini, pairs, false);
        let (active, ca) = two_blocks(FlexibilityMode::ActiveSet, Signorini, pairs, false);
        assert_eq!(ca.active_set_steps, 2);
        let (dr, dg) = compare(&dense, &active);
        assert!(
            dr <= 1e-8 && dg <= 1e-7,
            "pairs {pairs}, Signorini: {dr} {dg}"
        );
    }
}

#[test]
fn node_pairs_with_a_held_contactor_rename_the_target_and_match_dense() {
    // the upper block's bottom-left node is held horizontally (as a pile head lifted by a
    // prescribed displacement): its pair's jump cannot be carried by it, the target node
    // (free) is renamed instead; with Coulomb, and with the RCCM glue (β compared too)
    let coulomb = Coulomb::new(0.6).unwrap();
    let (dense, _) = two_blocks(FlexibilityMode::Dense, coulomb, true, true);
    let (active, ca) = two_blocks(FlexibilityMode::ActiveSet, coulomb, true, true);
    assert_eq!(ca.active_set_steps, 2);
    let (dr, dg) = compare(&dense, &active);
    assert!(dr <= 1e-8 && dg <= 1e-7, "Coulomb: {dr} {dg}");
    let (dense, _) = two_blocks(FlexibilityMode::Dense, glue(), true, true);
    let (active, ca) = two_blocks(FlexibilityMode::ActiveSet, glue(), true, true);
    assert_eq!(ca.active_set_steps, 2);
    assert_eq!(ca.flexibility_columns, 0);
    let (dr, dg) = compare(&dense, &active);
    let db = beta_difference(&dense, &active);
    eprintln!(
        "glued pairs, held contactor: max |Δr| / max r = {dr:.1e}, max |Δgap| / max gap = \
         {dg:.1e}, max |Δβ| = {db:.1e}; {} adhesion iterations",
        ca.adhesion_iterations
    );
    assert!(
        dr <= 1e-6 && dg <= 1e-6 && db <= 1e-6,
        "RCCM: {dr} {dg} {db}"
    );
}

#[test]
fn a_chain_of_contacts_is_out_of_scope_with_a_reason() {
    // a node that is both a contactor and another contact's target: refused, with the reason
    let (mesh, top, bottom) = block(ElementKind::Tri3, 4, 2);
    let model = model(mesh, &top);
    let (a, b, c) = (bottom[0], bottom[1], bottom[2]);
    let zone = ContactZone::node_pairs(
        "chain",
        vec![a, b],
        vec![b, c],
        Some([0.0, 1.0]),
        Signorini,
        10.0,
    );
    let settings = SimulationSettings::default().with_flexibility(FlexibilityMode::ActiveSet);
    let mut sim = ContactSimulation::new(model, vec![zone], settings).unwrap();
    match sim.step(1.0, 1.0) {
        Err(SolverError::Unsupported(why)) => {
            assert!(why.contains("chain"), "{why}");
        }
        other => panic!("expected Unsupported, got {other:?}"),
    }
}

#[test]
fn auto_falls_back_when_the_active_set_does_not_converge() {
    let run = |mode: FlexibilityMode| -> Result<(Vec<StepResult>, contact_solver::Counters), SolverError> {
        let (mesh, top, bottom) = block(ElementKind::Tri3, 8, 4);
        let mut supports = Supports::new();
        supports.prescribe(&top, Component::Y, 0.0).unwrap();
        supports.prescribe(&top, Component::X, 0.0).unwrap();
        let model = LinearElasticModel::new(
            mesh,
            Idealization::PlaneStrain,
            &[(0, Material::new(1000.0, 0.0, 0.0).unwrap())],
            supports,
        )
        .unwrap();
        let ground = RigidLine::new([-1.0, 0.0], [3.0, 0.0]).unwrap();
        let zone = ContactZone::rigid("base", bottom, ground, Coulomb::new(10.0).unwrap(), 0.1);
        let mut settings = SimulationSettings::default().with_flexibility(mode);
        settings.solver.max_iterations = 100_000;
        let mut sim = ContactSimulation::new(model, vec![zone], settings).unwrap();
        let mut out = Vec::new();
        for (k, (dy, dx)) in [(-0.01, 0.0), (-0.01, 0.05)].into_iter().enumerate() {
            sim.structure_mut().set_prescribed(&top, Component::Y, dy).unwrap();
            sim.structure_mut().set_prescribed(&top, Component::X, dx).unwrap();
            out.push(sim.step(k as f64 + 1.0, 1.0)?);
        }
        Ok((out, sim.counters()))
    };
    match run(FlexibilityMode::ActiveSet) {
        Err(SolverError::NotConverged {
            iterations,
            history,
            ..
        }) => {
            assert_eq!(
                iterations,
                contact_solver::coupling::primal::PRIMAL_MAX_ITERATIONS
            );
            assert_eq!(history.len(), iterations);
        }
        other => panic!("expected NotConverged, got {other:?}"),
    }
    let (dense, _) = run(FlexibilityMode::Dense).unwrap();
    let (auto, c) = run(FlexibilityMode::Auto { dense_limit: 0 }).unwrap();
    assert_eq!(c.active_set_fallbacks, 1);
    assert_eq!(c.active_set_steps, 1); // the press
    // the press was solved by the other path (each to tol 1e-10); μ = 10 amplifies the
    // difference of the starting states in the push (measured 7.7e-8)
    let (dr, _) = compare(&dense, &auto);
    assert!(dr <= 1e-6, "{dr}");
}
