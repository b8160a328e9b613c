//! The primal active set in 3D (`FlexibilityMode::ActiveSet`, no `F*`) against the dense `F*`
//! path and against exact answers:
//!
//! - the Signorini patch (uniform pressure `E δ / H`, exact), with rollers, so that the nodes
//!   on the symmetry planes have two free dofs and the corner one (the frame's tangent plane is
//!   turned so that the held direction is a tangent without a dof);
//! - Coulomb's law on a block pressed and sheared along `(cos θ, sin θ)`, in full slip and in
//!   partial slip: the same reactions as the dense path to the solver's tolerance, every
//!   sliding contact on the cone with its force opposite to its slip;
//! - the coarse 3D Hertz quarter, frictionless and with friction (the nodes on the symmetry
//!   planes under a curved obstacle): the dense path's reactions;
//! - its scope: node pairs and adhesion refused with the reason, `Auto` choosing it past its
//!   limit for rigid obstacles only.

#![cfg(feature = "fe")]

use crate::solid_interfaces::{matching, supports, two_blocks};
use contact_laws::{BetaScheme, ContactLaw, Coulomb, Rccm, RccmParams, Signorini};
use contact_solver::coupling::solid::{
    ContactZone3, PairNormals3, RigidPlane, RigidSphere, Side3, SolidContactSimulation,
    SolidStepResult,
};
use contact_solver::{FlexibilityMode, SimulationSettings};
use fem_core::solid::generate::{box_mesh, lines};
use fem_core::solid::{SolidKind, SolidModel};
use fem_core::{Component, Material, Supports};

fn settings(mode: FlexibilityMode) -> SimulationSettings {
    SimulationSettings::for_dimension::<3>().with_flexibility(mode)
}

/// Largest difference of the reactions of two runs, relative to the largest normal reaction.
fn max_difference(a: &[SolidStepResult], b: &[SolidStepResult]) -> f64 {
    let mut scale = 0.0_f64;
    let mut diff = 0.0_f64;
    for (sa, sb) in a.iter().zip(b) {
        assert_eq!(sa.contacts.len(), sb.contacts.len());
        for (ca, cb) in sa.contacts.iter().zip(&sb.contacts) {
            let (ra, rb) = (ca.reaction(), cb.reaction());
            scale = scale.max(ra[0].abs());
            for d in 0..3 {
                diff = diff.max((ra[d] - rb[d]).abs());
            }
        }
    }
    diff / scale
}

/// A block `[0, 2] × [0, 1.5] × [0, 1]` on a rigid floor, rollers on `x = 0` and `y = 0`
/// (when `rollers`), its top pressed down by `1e-3`, then (with `shear`) moved by `d` along
/// `(cos θ, sin θ)`.
fn pressed_block<L: ContactLaw + Clone>(
    kind: SolidKind,
    law: L,
    rollers: bool,
    shear: Option<(f64, f64)>,
    mode: FlexibilityMode,
) -> Vec<SolidStepResult> {
    let mesh = box_mesh(
        &lines(0.0, 2.0, 3),
        &lines(0.0, 1.5, 2),
        &lines(0.0, 1.0, 2),
        kind,
    )
    .unwrap();
    let top = mesh.node_set("z1").unwrap().to_vec();
    let mut s = Supports::new();
    if rollers {
        s.fix(mesh.node_set("x0").unwrap(), Component::X)
            .fix(mesh.node_set("y0").unwrap(), Component::Y);
    } else {
        s.fix(&top, Component::X).fix(&top, Component::Y);
    }
    s.prescribe(&top, Component::Z, -1e-3).unwrap();
    let (nodes, areas) = mesh.nodal_areas("z0").unwrap();
    let model = SolidModel::new(mesh, &[(0, Material::new(1000.0, 0.3, 0.0).unwrap())], s).unwrap();
    let floor = RigidPlane::new([0.0; 3], [0.0, 0.0, 1.0]).unwrap();
    let zone = ContactZone3::rigid("base", nodes, floor, law, 0.1).with_areas(areas);
    let mut sim = SolidContactSimulation::new(model, vec![zone], settings(mode)).unwrap();
    let mut out = vec![sim.step(1.0, 1.0).unwrap()];
    if let Some((theta, d)) = shear {
        for (c, v) in [
            (Component::X, d * theta.cos()),
            (Component::Y, d * theta.sin()),
        ] {
            sim.structure_mut().set_prescribed(&top, c, v).unwrap();
        }
        out.push(sim.step(2.0, 1.0).unwrap());
    }
    out
}

#[test]
fn signorini_patch_is_exact_with_rollers() {
    for kind in [SolidKind::Tet4, SolidKind::Tet10] {
        let res = pressed_block(kind, Signorini, true, None, FlexibilityMode::ActiveSet);
        let res = &res[0];
        assert!(res.report.active_set && !res.report.matrix_free);
        // σ = E δ / H = 1 on an area of 3, to the solver's tolerance (1e-10 relative)
        let total: f64 = res.contacts.iter().map(|c| c.r.n).sum();
        assert!((total - 3.0).abs() < 1e-8, "{kind:?}: {total}");
        for c in &res.contacts {
            if c.area > 0.0 {
                assert!(
                    (c.pressure() - 1.0).abs() < 1e-7,
                    "{kind:?}: {}",
                    c.pressure()
                );
            }
            assert!(c.gap.abs() < 1e-12, "closed: {}", c.gap);
            assert!(c.r.t[0] == 0.0 && c.r.t[1] == 0.0, "frictionless");
        }
        eprintln!(
            "{kind:?} patch: {} iterations",
            res.report.contact_iterations
        );
    }
}

#[test]
fn coulomb_with_rollers_matches_dense() {
    // ν = 0.3: the base spreads outwards from the rollers' corner, held by friction near it
    // and sliding away from it; the nodes on the rollers' planes are held along one tangent
    for kind in [SolidKind::Tet4, SolidKind::Tet10] {
        let law = Coulomb::new(0.1).unwrap();
        let active = pressed_block(kind, law, true, None, FlexibilityMode::ActiveSet);
        let dense = pressed_block(kind, law, true, None, FlexibilityMode::Dense);
        let diff = max_difference(&active, &dense);
        eprintln!("{kind:?} rollers, μ = 0.1: difference {diff:e}");
        assert!(active[0].report.active_set);
        // both paths to the solver's tolerance (1e-10 on the natural-map residual)
        assert!(diff < 1e-7, "{kind:?}: {diff:e}");
    }
}

#[test]
fn sheared_block_matches_dense_in_full_and_partial_slip() {
    let mu = 0.3;
    let theta = 0.6;
    // d = 0.05: every contact slides; d = 2e-4: stick in the middle, slip at the border
    for (d, label) in [(0.05, "full slip"), (2e-4, "partial slip")] {
        for kind in [SolidKind::Tet4, SolidKind::Tet10] {
            let law = Coulomb::new(mu).unwrap();
            let shear = Some((theta, d));
            let active = pressed_block(kind, law, false, shear, FlexibilityMode::ActiveSet);
            let dense = pressed_block(kind, law, false, shear, FlexibilityMode::Dense);
            let diff = max_difference(&active, &dense);
            let last = &active[1];
            let sliding = last
                .contacts
                .iter()
                .filter(|c| c.r.n > 1e-9 && c.slip_increment[0].hypot(c.slip_increment[1]) > 1e-12)
                .count();
            let closed = last.contacts.iter().filter(|c| c.r.n > 1e-9).count();
            eprintln!(
                "{kind:?} {label}: {sliding}/{closed} sliding, {} iterations, \
                 difference {diff:e}",
                last.report.contact_iterations
            );
            assert!(last.report.active_set);
            assert!(diff < 1e-6, "{kind:?} {label}: {diff:e}");
            if label == "full slip" {
                assert_eq!(sliding, closed);
            } else {
                assert!(sliding > 0 && sliding < closed, "{sliding}/{closed}");
            }
            // the solver's tolerance is relative to the whole reaction: checked against the
            // largest one (a P2 corner node carries a small force)
            let rmax = last.contacts.iter().fold(0.0_f64, |m, c| m.max(c.r.n));
            for c in last.contacts.iter().filter(|c| c.r.n > 1e-9) {
                let rt = c.r.t[0].hypot(c.r.t[1]);
                let s = c.slip_increment[0].hypot(c.slip_increment[1]);
                assert!(rt <= mu * c.r.n + 1e-6 * rmax, "inside the cone");
                if s > 1e-6 * d {
                    // sliding: on the cone, the force opposite to the slip
                    assert!((rt - mu * c.r.n).abs() < 1e-6 * rmax, "{rt}");
                    let opposed = (c.r.t[0] * c.slip_increment[0] + c.r.t[1] * c.slip_increment[1])
                        / (rt * s);
                    assert!((opposed + 1.0).abs() < 1e-4, "{opposed}");
                }
            }
        }
    }
}

/// The coarse Hertz quarter of `solid_contact.rs`: a rigid ball (R = 10) pressed into a graded
/// block, symmetry on `x = 0` and `y = 0`.
fn hertz_quarter<L: ContactLaw + Clone>(law: L, mode: FlexibilityMode) -> SolidStepResult {
    let graded = |l: f64, n_fine: usize, fine: f64, n_coarse: usize| -> Vec<f64> {
        let mut v = lines(0.0, fine, n_fine);
        let r = (l / fine).powf(1.0 / n_coarse as f64);
        v.extend((1..=n_coarse).map(|k| fine * r.powi(k as i32)));
        v
    };
    let xy = graded(4.0, 6, 0.9, 4);
    let mut z: Vec<f64> = graded(4.0, 4, 0.6, 4).iter().map(|v| -v).collect();
    z.reverse();
    let mesh = box_mesh(&xy, &xy, &z, SolidKind::Tet10).unwrap();
    let mut s = Supports::new();
    s.fix(mesh.node_set("x0").unwrap(), Component::X)
        .fix(mesh.node_set("y0").unwrap(), Component::Y)
        .prescribe(mesh.node_set("z0").unwrap(), Component::Z, 0.04)
        .unwrap();
    let (nodes, areas) = mesh.nodal_areas("z1").unwrap();
    let model = SolidModel::new(mesh, &[(0, Material::new(1000.0, 0.3, 0.0).unwrap())], s).unwrap();
    let ball = RigidSphere::new([0.0, 0.0, 10.0], 10.0, Side3::Outside).unwrap();
    let zone = ContactZone3::rigid("top", nodes, ball, law, 0.5).with_areas(areas);
    let mut sim = SolidContactSimulation::new(model, vec![zone], settings(mode)).unwrap();
    sim.step(1.0, 1.0).unwrap()
}

#[test]
fn hertz_quarter_matches_dense_with_and_without_friction() {
    let frictionless = [
        hertz_quarter(Signorini, FlexibilityMode::ActiveSet),
        hertz_quarter(Signorini, FlexibilityMode::Dense),
    ];
    let law = Coulomb::new(0.2).unwrap();
    let frictional = [
        hertz_quarter(law, FlexibilityMode::ActiveSet),
        hertz_quarter(law, FlexibilityMode::Dense),
    ];
    for (label, [a, d]) in [("frictionless", frictionless), ("μ = 0.2", frictional)] {
        let diff = max_difference(std::slice::from_ref(&a), std::slice::from_ref(&d));
        let closed = a.contacts.iter().filter(|c| c.r.n > 0.0).count();
        eprintln!(
            "Hertz quarter {label}: {closed} closed of {}, {} iterations, difference {diff:e}",
            a.report.active_contacts, a.report.contact_iterations
        );
        assert!(a.report.active_set);
        // both paths stop at the natural-map residual 1e-10 relative; with friction the
        // contacts near the stick/slip border amplify it in the reactions (8.5e-7 measured)
        let tol = if label == "frictionless" { 1e-7 } else { 1e-5 };
        assert!(diff < tol, "{label}: {diff:e}");
        // the same contact set
        for (ca, cd) in a.contacts.iter().zip(&d.contacts) {
            assert_eq!(ca.r.n > 1e-9, cd.r.n > 1e-9, "{label}: node {}", ca.node);
        }
    }
}

#[test]
fn scope_is_enforced_and_auto_falls_back() {
    let (m, delta) = (Material::new(1000.0, 0.3, 0.0).unwrap(), 1e-3);
    let pairs = |mode: FlexibilityMode| {
        let mesh = two_blocks(SolidKind::Tet4, 2, 2);
        let (nodes, areas) = mesh.nodal_areas("b.z0").unwrap();
        let targets = matching(&mesh, &nodes, mesh.node_set("a.z1").unwrap());
        let n = PairNormals3::Fixed([0.0, 0.0, 1.0]);
        let zone =
            ContactZone3::node_pairs("glue", nodes, targets, n, Signorini, 0.1).with_areas(areas);
        let s = supports(&mesh, &[(Component::Z, -delta)]);
        let model = SolidModel::new(mesh, &[(0, m), (1, m)], s).unwrap();
        SolidContactSimulation::new(model, vec![zone], settings(mode))
            .unwrap()
            .step(1.0, 1.0)
    };
    // node pairs whose contactors lie on the roller planes (a prescribed component): their
    // targets lie on the same planes, held along the same directions, so the contactor
    // carries the jump in the directions it moves; the dense answer
    let active = pairs(FlexibilityMode::ActiveSet).unwrap();
    let dense = pairs(FlexibilityMode::Dense).unwrap();
    assert!(active.report.active_set);
    let diff = max_difference(&[active], std::slice::from_ref(&dense));
    assert!(diff < 1e-9, "{diff:e}");
    // Auto past its limit takes the active set for them
    let auto = pairs(FlexibilityMode::Auto { dense_limit: 0 }).unwrap();
    assert!(auto.report.active_set && !auto.report.matrix_free);
    let diff = max_difference(&[auto], &[dense]);
    assert!(diff < 1e-9, "{diff:e}");
    // adhesion: the active set when asked, the dense F* under Auto
    let rccm = Rccm::new(RccmParams {
        c_n: 1e4,
        c_t: 1e4,
        w: 1e-3,
        alpha: 0.0,
        mu: 0.3,
        m: 1,
        beta_0: 1.0,
        scheme: BetaScheme::ImplicitEuler,
    })
    .unwrap();
    let glued = |mode| {
        let mesh = box_mesh(
            &lines(0.0, 1.0, 2),
            &lines(0.0, 1.0, 2),
            &lines(0.0, 1.0, 1),
            SolidKind::Tet4,
        )
        .unwrap();
        let top = mesh.node_set("z1").unwrap().to_vec();
        let mut s = Supports::new();
        s.prescribe(&top, Component::Z, -delta).unwrap();
        s.fix(&top, Component::X).fix(&top, Component::Y);
        let (nodes, areas) = mesh.nodal_areas("z0").unwrap();
        let model = SolidModel::new(mesh, &[(0, m)], s).unwrap();
        let floor = RigidPlane::new([0.0; 3], [0.0, 0.0, 1.0]).unwrap();
        let zone = ContactZone3::rigid("glue", nodes, floor, rccm, 0.1).with_areas(areas);
        SolidContactSimulation::new(model, vec![zone], settings(mode))
            .unwrap()
            .step(1.0, 1.0)
    };
    // adhesion: the active set when asked (the springs on the stiffness), the dense F* under
    // Auto, the same answer
    let active = glued(FlexibilityMode::ActiveSet).unwrap();
    assert!(active.report.active_set);
    let auto = glued(FlexibilityMode::Auto { dense_limit: 0 }).unwrap();
    assert!(!auto.report.active_set && !auto.report.matrix_free);
    let diff = max_difference(&[active], &[auto]);
    assert!(diff < 1e-7, "{diff:e}");
    // rigid obstacles past the limit: the active set, with the dense answer
    let law = Coulomb::new(0.3).unwrap();
    let auto = pressed_block(
        SolidKind::Tet10,
        law,
        true,
        None,
        FlexibilityMode::Auto { dense_limit: 0 },
    );
    let dense = pressed_block(SolidKind::Tet10, law, true, None, FlexibilityMode::Dense);
    assert!(auto[0].report.active_set);
    assert!(max_difference(&auto, &dense) < 1e-7);
}

#[test]
fn issue_38_step_report_names_the_path_and_why() {
    use contact_solver::{PathChoice, PathReason, SolvePath};
    let path = |mode| hertz_quarter(Signorini, mode).report;
    let dense = path(FlexibilityMode::Dense);
    assert_eq!(
        dense.path,
        PathChoice {
            path: SolvePath::Dense,
            reason: PathReason::Requested
        }
    );
    let n = dense.active_contacts;
    let within = path(FlexibilityMode::Auto { dense_limit: n });
    assert_eq!(within.path.path, SolvePath::Dense);
    assert_eq!(
        within.path.reason,
        PathReason::WithinDenseLimit {
            active: n,
            limit: n
        }
    );
    let above = path(FlexibilityMode::Auto { dense_limit: n - 1 });
    assert!(above.active_set);
    assert_eq!(above.path.path, SolvePath::ActiveSet);
    assert_eq!(
        above.path.to_string(),
        format!(
            "active set (auto: {n} active contacts > dense limit {})",
            n - 1
        )
    );
    let free = path(FlexibilityMode::MatrixFree);
    assert!(free.matrix_free);
    assert_eq!(free.path.path, SolvePath::MatrixFree);
    assert_eq!(free.path.reason, PathReason::Requested);
}
