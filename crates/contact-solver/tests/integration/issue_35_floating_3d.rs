//! Issue 35: floating bodies, skip rules and counters in 3D, through `ContactSimulation<_, _, 3>`.
//!
//! **Force-controlled Hertz in 3D.** The quarter model of `solid_contact.rs`'s coarse Hertz
//! scene (a block `[0, 4]² × [−4, 0]`, P2 tetrahedra graded towards the contact, a rigid ball
//! `R = 10` touching the top at the origin, `E = 1000`, `ν = 0.3`, frictionless), but the
//! bottom is not supported: a uniform traction pushes it up with the quarter's share `P/4` of
//! the load `P`. Held only by its symmetry planes (`u_x = 0` on `x = 0`, `u_y = 0` on `y = 0`),
//! the block keeps one rigid-body mode, the vertical translation, and contact alone holds it:
//! the floating stage solves for its amplitude with the block's vertical equilibrium.
//!
//! Source: H. Hertz (1882); K. L. Johnson, *Contact Mechanics*, 1985, §4.2: a rigid sphere on
//! an elastic half-space, `a = (3PR/(4E*))^(1/3)`, `E* = E/(1 − ν²)` (the same as an elastic
//! sphere on a rigid flat).
//!
//! What is asserted, and why:
//! - **balance**: the vertical resultant `4 |Σ r_n n_z| = P` to `1e-10` relative (the equilibrium is solved to
//!   `equilibrium_tol = 1e-11` of the forces involved);
//! - **contact radius**: from the second moment of the vertical reactions about the axis,
//!   `a² = 5/2 Σ f_z ρ² / Σ f_z` (Hertz's `∫ p ρ² dA / P = 2a²/5`; exact for the P2 nodal
//!   forces of a pressure on the flat top, whose P2 space holds `ρ² = x² + y²`; the estimate of
//!   the axisymmetric `hertz.rs`), within the issue's 1 % of Hertz's (measured +0.085 %);
//! - **the contact edge**: on this mesh the node spacing near the contact edge is `0.15`, a
//!   quarter of `a`, so the edge is only known between the farthest closed node and the nearest
//!   open one: Hertz's `a` must lie in that bracket (1 % slack, as `examples/hertz_3d.rs`, for
//!   the load's own discretisation and the block's finite size, 6.5 `a` wide). The bracket is
//!   what the mesh allows: measured `[0.6047, 0.6408]` for `a_Hertz = 0.6022` (+0.4 % / +6.4 %
//!   of it, the nodes on the top lie at several radii between grid lines); bounding the edge
//!   itself to 1 % would need a node spacing near 1 % of `a` (the moment above does not). The
//!   farthest closed node is also held within 5 % of `a`, as the displacement-controlled coarse
//!   test (measured here +0.41 %, there −2.0 %);
//! - **the same answer displacement-controlled**: the bottom prescribed, node by node, to the
//!   vertical displacement the floating run found (its shear traction is zero in both), gives
//!   the same reactions to `1e-8` of the largest (both solve the same reduced problem to
//!   `1e-10`);
//! - **counters and a skip rule in 3D**: one step, contact iterations and equilibrium solves
//!   counted; frictionless, so `frictionless_normal_only` builds only the normal columns of
//!   `F*` (one structure solve per active contact, not three).

#![cfg(feature = "fe")]

use contact_laws::{Coulomb, Signorini};
use contact_solver::coupling::solid::{RigidPlane, RigidSphere, Side3};
use contact_solver::{ContactSimulation, ContactZone, SimulationSettings, SolverError, StepResult};
use fem_core::solid::generate::{box_mesh, lines};
use fem_core::solid::{SolidKind, SolidMesh, SolidModel};
use fem_core::{Component, Material, RigidMotion, Supports};
use std::time::Instant;

const E: f64 = 1000.0;
const NU: f64 = 0.3;
const RADIUS: f64 = 10.0;

/// The graded block of `solid_contact.rs`'s coarse Hertz scene.
fn block() -> SolidMesh {
    let graded = |l: f64, n_fine: usize, fine: f64, n_coarse: usize| -> Vec<f64> {
        let mut v = lines(0.0, fine, n_fine);
        let r = (l / fine).powf(1.0 / n_coarse as f64);
        for k in 1..=n_coarse {
            v.push(fine * r.powi(k as i32));
        }
        v
    };
    let xy = graded(4.0, 6, 0.9, 4);
    let mut z: Vec<f64> = graded(4.0, 4, 0.6, 4).iter().map(|v| -v).collect();
    z.reverse();
    box_mesh(&xy, &xy, &z, SolidKind::Tet10).unwrap()
}

/// The simulation of the block (symmetry planes held), its top facing the ball: the bottom
/// pushed up by the traction `bottom_load`, or prescribed node by node to `bottom_uz`.
fn simulation(
    mesh: SolidMesh,
    bottom_load: Option<f64>,
    bottom_uz: Option<&[(usize, f64)]>,
) -> ContactSimulation<SolidModel, Signorini, 3> {
    let m = Material::new(E, NU, 0.0).unwrap();
    let mut s = Supports::new();
    s.fix(mesh.node_set("x0").unwrap(), Component::X)
        .fix(mesh.node_set("y0").unwrap(), Component::Y);
    for &(node, uz) in bottom_uz.unwrap_or(&[]) {
        s.prescribe(&[node], Component::Z, uz).unwrap();
    }
    let (nodes, areas) = mesh.nodal_areas("z1").unwrap();
    let model = match bottom_load {
        Some(t) => {
            let mut model = SolidModel::floating(mesh, &[(0, m)], s).unwrap();
            model.add_face_traction("z0", |_, _| [0.0, 0.0, t]).unwrap();
            model
        }
        None => SolidModel::new(mesh, &[(0, m)], s).unwrap(),
    };
    let ball = RigidSphere::new([0.0, 0.0, RADIUS], RADIUS, Side3::Outside).unwrap();
    let zone = ContactZone::<_, 3>::rigid("top", nodes, ball, Signorini, 0.5).with_areas(areas);
    ContactSimulation::new(model, vec![zone], SimulationSettings::for_dimension::<3>()).unwrap()
}

/// The farthest closed node and the nearest open one (distance to the axis).
fn edge(res: &StepResult<3>, p_total: f64) -> (f64, f64) {
    let (mut inside, mut outside) = (0.0_f64, f64::INFINITY);
    for c in &res.contacts {
        let r = c.position[0].hypot(c.position[1]);
        if c.reaction()[0] > 1e-9 * p_total {
            inside = inside.max(r);
        } else if c.area > 0.0 && c.gap > 0.0 {
            outside = outside.min(r);
        }
    }
    (inside, outside)
}

/// The contact radius from the second moment of the vertical reactions about the axis:
/// Hertz's `p = p0 √(1 − ρ²/a²)` has `∫ p ρ² dA / P = 2a²/5`, so `a² = 5/2 Σ f_z ρ² / Σ f_z`
/// (the axisymmetric estimate of `tests/support/hertz_scene.rs`); exact for P2 nodal forces
/// consistent with a pressure on the flat top, whose P2 space holds `ρ² = x² + y²`.
fn moment_radius(res: &StepResult<3>) -> f64 {
    let (mut f, mut m2) = (0.0, 0.0);
    for c in &res.contacts {
        let fz = c.force()[2];
        f += fz;
        m2 += fz * (c.position[0].powi(2) + c.position[1].powi(2));
    }
    (2.5 * m2 / f).sqrt()
}

#[test]
fn issue_35_floating_3d() {
    let start = Instant::now();
    // P = 32: a_Hertz ≈ 0.60, four fine cells across it
    let p = 32.0;
    let mesh = block();
    let mut sim = simulation(mesh.clone(), Some(p / 4.0 / 16.0), None);
    assert_eq!(
        sim.structure()
            .rigid_body_modes()
            .map(|m| m.len())
            .unwrap_or(0),
        1,
        "the symmetry planes leave the vertical translation alone"
    );
    let res = sim.step(1.0, 1.0).expect("the floating 3D Hertz step");
    // the vertical resultant (the ball's normals tilt off z away from the axis: `Σ r_n` alone
    // exceeds `P` by 7e-4 here)
    let total: f64 = (4.0 * res.contacts.iter().map(|c| c.force()[2]).sum::<f64>()).abs();
    let e_star = E / (1.0 - NU * NU);
    let a_hertz = (3.0 * p * RADIUS / (4.0 * e_star)).cbrt();
    let (inside, outside) = edge(&res, p);
    let a_moment = moment_radius(&res);
    eprintln!(
        "second-moment radius {a_moment:.6} vs Hertz {a_hertz:.6}: {:+.3} %",
        100.0 * (a_moment / a_hertz - 1.0)
    );
    let counters = sim.counters();
    eprintln!(
        "3D floating Hertz: P = {p} -> {total:.15} ({:+.2e}); a_Hertz = {a_hertz:.4}, edge in \
         [{inside:.4}, {outside:.4}] ({:+.2} %, {:+.2} %); α = {:?}; {} closed / {} active, \
         {} contact iterations, {} equilibrium iterations, {} solves, {} F* columns",
        (total - p) / p,
        100.0 * (inside / a_hertz - 1.0),
        100.0 * (outside / a_hertz - 1.0),
        sim.rigid_body_amplitudes(),
        res.report.closed_contacts,
        res.report.active_contacts,
        res.report.contact_iterations,
        res.report.equilibrium_iterations,
        res.report.equilibrium_solves,
        counters.flexibility_columns,
    );
    assert!((total - p).abs() <= 1e-10 * p, "balance {total} vs {p}");
    // Hertz's radius from the reactions' second moment, to the issue's 1 % (measured +0.085 %:
    // the moment averages over every closed node, the bracket below only sees two)
    assert!(
        (a_moment / a_hertz - 1.0).abs() < 0.01,
        "second-moment radius {a_moment} vs Hertz {a_hertz}"
    );
    assert!(
        0.99 * inside <= a_hertz && a_hertz <= 1.01 * outside,
        "a_Hertz {a_hertz} outside [{inside}, {outside}]"
    );
    assert!((inside / a_hertz - 1.0).abs() < 0.05, "{inside} {a_hertz}");
    // the one mode is the vertical translation, named so; the block moved up
    let modes = sim.structure().rigid_body_modes().unwrap().modes().to_vec();
    assert_eq!(
        modes[0].motion,
        RigidMotion::SpaceTranslation {
            direction: [0.0, 0.0, 1.0]
        }
    );
    let alpha = sim.rigid_body_amplitudes().to_vec();
    assert!(alpha.len() == 1 && alpha[0] > 0.0, "{alpha:?}");
    // counters: one step, the reduced solves and the equilibrium iterations counted
    assert_eq!(counters.steps, 1);
    assert!(counters.contact_iterations > 0 && res.report.contact_iterations > 0);
    assert!(counters.equilibrium_solves >= 1 && res.report.equilibrium_solves >= 1);
    assert_eq!(counters.equilibrium_solves, res.report.equilibrium_solves);
    // frictionless: one column of F* per active contact (normal only), not three
    assert_eq!(counters.flexibility_columns, res.report.active_contacts);

    // displacement-controlled at the bottom displacement the floating run found
    let u = sim.nodal_displacements();
    let bottom: Vec<(usize, f64)> = mesh
        .node_set("z0")
        .unwrap()
        .iter()
        .map(|&n| (n, u[n][2]))
        .collect();
    let mut fixed = simulation(mesh, None, Some(&bottom));
    assert!(
        fixed
            .structure()
            .rigid_body_modes()
            .is_none_or(|m| m.is_empty())
    );
    let res_fixed = fixed
        .step(1.0, 1.0)
        .expect("the displacement-controlled step");
    assert_eq!(res_fixed.contacts.len(), res.contacts.len());
    let scale = res
        .contacts
        .iter()
        .fold(0.0_f64, |m, c| m.max(c.reaction()[0].abs()));
    let worst = res
        .contacts
        .iter()
        .zip(&res_fixed.contacts)
        .fold(0.0_f64, |m, (a, b)| {
            m.max((a.reaction()[0] - b.reaction()[0]).abs())
        });
    eprintln!(
        "displacement-controlled at the floating displacement: reactions differ by {:.2e} of the \
         largest; {:.2?}",
        worst / scale,
        start.elapsed()
    );
    assert!(worst <= 1e-8 * scale, "{worst} vs {scale}");
    assert_eq!(fixed.counters().equilibrium_solves, 0);
}

/// A free block (no support at all: six rigid-body modes) on a frictionless rigid plane,
/// pressed down and pushed sideways by a uniform traction on its top: contact resists the
/// vertical translation and the two tilts, nothing resists the slide, and the step fails with
/// [`SolverError::Unbalanced`] naming the body, the direction of the slide and the load (the
/// top's area `2 × 1.5` times the sideways traction; nothing balances it, so the imbalance is
/// the whole load).
#[test]
fn issue_35_floating_3d_unbalanced_names_the_direction() {
    for (t, want) in [
        ([0.2, 0.0], [1.0, 0.0, 0.0]),
        ([0.2, 0.2], [0.5_f64.sqrt(), 0.5_f64.sqrt(), 0.0]),
        ([0.0, -0.3], [0.0, 1.0, 0.0]),
    ] {
        let mesh = box_mesh(
            &lines(0.0, 2.0, 2),
            &lines(0.0, 1.5, 2),
            &lines(0.0, 1.0, 1),
            SolidKind::Tet10,
        )
        .unwrap();
        let (nodes, areas) = mesh.nodal_areas("z0").unwrap();
        let m = Material::new(E, NU, 0.0).unwrap();
        let mut model = SolidModel::floating(mesh, &[(0, m)], Supports::new()).unwrap();
        assert_eq!(model.rigid_body_modes().map(|m| m.len()), Some(6));
        model
            .add_face_traction("z1", |_, _| [t[0], t[1], -1.0])
            .unwrap();
        let plane = RigidPlane::new([0.0; 3], [0.0, 0.0, 1.0]).unwrap();
        let zone =
            ContactZone::<_, 3>::rigid("base", nodes, plane, Signorini, 0.1).with_areas(areas);
        let mut sim =
            ContactSimulation::new(model, vec![zone], SimulationSettings::for_dimension::<3>())
                .unwrap();
        let err = sim.step(1.0, 1.0).unwrap_err();
        eprintln!("push {t:?}: {err}");
        let SolverError::Unbalanced {
            body,
            motion: RigidMotion::SpaceTranslation { direction },
            imbalance,
            load,
        } = err
        else {
            panic!("push {t:?}: {err:?}");
        };
        assert_eq!(body, 0);
        // the load along the direction named (along a mode's own axis it keeps the mode's
        // sign, as in 2D; a slanted direction is oriented along the force)
        let force = 3.0 * (t[0] * want[0] + t[1] * want[1]);
        for a in 0..3 {
            assert!(
                (direction[a] - want[a]).abs() < 1e-9,
                "{direction:?} vs {want:?}"
            );
        }
        // the sideways load is the whole imbalance (the traction is integrated exactly)
        assert!(
            (load - force).abs() < 1e-12 * force.abs(),
            "{load} vs {force}"
        );
        assert!(
            (imbalance - force).abs() < 1e-9 * force.abs(),
            "{imbalance} vs {force}"
        );
    }
}

/// The free block of [`issue_35_floating_3d_unbalanced_names_the_direction`] on a plane with
/// Coulomb friction `μ = 0.3` (the 3D form of `floating_block.rs`), pressed by `N = 3` (a unit
/// downward traction on the `2 × 1.5` top) and pushed slantwise along `(0.6, 0.8)` by `T`.
/// Returns the step's outcome: the total contact force and the equilibrium iterations, or the
/// error.
fn coulomb_block(push: f64) -> Result<([f64; 3], usize), SolverError> {
    let mesh = box_mesh(
        &lines(0.0, 2.0, 2),
        &lines(0.0, 1.5, 2),
        &lines(0.0, 1.0, 1),
        SolidKind::Tet10,
    )
    .unwrap();
    let (nodes, areas) = mesh.nodal_areas("z0").unwrap();
    let m = Material::new(E, NU, 0.0).unwrap();
    let mut model = SolidModel::floating(mesh, &[(0, m)], Supports::new()).unwrap();
    model
        .add_face_traction("z1", |_, _| [0.6 * push, 0.8 * push, -1.0])
        .unwrap();
    let plane = RigidPlane::new([0.0; 3], [0.0, 0.0, 1.0]).unwrap();
    let law = Coulomb::new(MU).unwrap();
    let zone = ContactZone::<_, 3>::rigid("base", nodes, plane, law, 0.1).with_areas(areas);
    let mut sim =
        ContactSimulation::new(model, vec![zone], SimulationSettings::for_dimension::<3>())
            .unwrap();
    let res = sim.step(1.0, 1.0)?;
    assert!(sim.counters().equilibrium_solves > 0);
    eprintln!(
        "T = {}: {} equilibrium iterations, {} solves",
        3.0 * push,
        res.report.equilibrium_iterations,
        res.report.equilibrium_solves
    );
    let force = res.contacts.iter().fold([0.0; 3], |s, c| {
        let f = c.force();
        [s[0] + f[0], s[1] + f[1], s[2] + f[2]]
    });
    Ok((force, res.report.equilibrium_iterations))
}

const MU: f64 = 0.3;

/// Below `μ N` the block sticks and the contact force balances the load exactly: `N` and the
/// push `T` to `1e-10` of `N` (the equilibrium is solved to `1e-11` of the forces, the reduced
/// problem to `1e-10`). Pressed alone (`T = 0`) and pushed by `T = 0.06 = μN/15`, in a few
/// equilibrium iterations, as the 2D block (measured 4 and 5; 25 and 34 before the slipping
/// contacts' reactions were let turn with their slip in the linearisation, 2D takes 2–3).
#[test]
fn issue_35_floating_3d_coulomb_sticks() {
    let n = 3.0;
    for push in [0.0, 0.02] {
        let t = 3.0 * push;
        let (f, iterations) = coulomb_block(push).unwrap_or_else(|e| panic!("T = {t}: {e}"));
        eprintln!("T = {t}: Σ f = {f:?}");
        assert!((f[2] - n).abs() < 1e-10 * n, "{f:?}");
        assert!((f[0] + 0.6 * t).abs() < 1e-10 * n, "{f:?}");
        assert!((f[1] + 0.8 * t).abs() < 1e-10 * n, "{f:?}");
        assert!(iterations <= 10, "T = {t}: {iterations} iterations");
    }
}

/// Issue 35 regression: pushed by `T = 0.6 = 2μN/3` the block sticks, the reactions balancing
/// `N` and `T` to `1e-10` of `N` (before: `Unbalanced` along a rotation, imbalance −0.128 for a
/// load 0). The floating stage linearised a slipping contact with its reaction's direction
/// frozen (`r_t/r_n`), which in 3D leaves every motion across the slip unresisted: with its
/// edge nodes slipping, the block's twist about `z` looked free. A slipping reaction turns with
/// its slip, stiffness `μ r_n/|s|` across it (`floating/linearized.rs`).
///
/// Pushed by `T = 1.5 > μN = 0.9` it slides off: as the 2D block above `μW`
/// (`floating_block.rs`), [`SolverError::Unbalanced`] names body 0 and a translation in the
/// plane of the base along the push, out of balance by `T − μN = 0.6`. In 3D the slips turn
/// and no direction is free at any finite slide; the force left is that of the slide's limit
/// (`floating/slide.rs`: friction opposing every contact's slide, the direction that leaves
/// the largest force). Measured: along `(0.60031, 0.79977, 0)`, out of balance by
/// `0.60000025`, the load along it `1.49999989`. The limit may turn the block a little about
/// `z` as it slides (the tilted normal reactions give the friction a moment about the centre
/// of a non-square base), which would explain the 3.1e-4 off the push and the force left
/// 4.2e-7 above the straight slide's. Before: along `(0.286, 0.958, 0)` by 0.672 (the force
/// left at the iteration where the frozen linearisation found the slide).
#[test]
fn issue_35_floating_3d_coulomb_sticks_then_slides() {
    let n = 3.0;
    let (f, _) = coulomb_block(0.2).unwrap_or_else(|e| panic!("T = 0.6 < μN should stick: {e}"));
    assert!((f[2] - n).abs() < 1e-10 * n, "{f:?}");
    assert!(
        (f[0] + 0.36).abs() < 1e-10 * n && (f[1] + 0.48).abs() < 1e-10 * n,
        "{f:?}"
    );
    let t = 1.5;
    let err = coulomb_block(t / 3.0).unwrap_err();
    eprintln!("T = {t}: {err:?}");
    let SolverError::Unbalanced {
        body,
        motion: RigidMotion::SpaceTranslation { direction },
        imbalance,
        load,
    } = err
    else {
        panic!("{err:?}");
    };
    assert_eq!(body, 0);
    // in the plane of the base, along the push to 1e-3 (measured 3.1e-4: the slide's limit
    // may carry a twist, see the doc)
    let cos = direction[0] * 0.6 + direction[1] * 0.8;
    assert!(direction[2].abs() < 1e-9, "{direction:?}");
    assert!(
        (direction[0] - 0.6).abs() < 1e-3 && (direction[1] - 0.8).abs() < 1e-3,
        "{direction:?}"
    );
    // the load along the direction named is the load's component along it (exact integration;
    // the direction's round-off `z` takes a share of `−N`)
    let along = t * cos - n * direction[2];
    assert!((load - along).abs() < 1e-12 * t, "{load} vs {along}");
    // T − μN to 1e-5 (measured +4.2e-7), and not below it: the largest force left over the
    // slides is at least the straight slide's (1e-9: the normal reactions' balance)
    let expected = t - MU * n;
    assert!(
        (imbalance - expected).abs() < 1e-5 * expected && imbalance > expected - 1e-9,
        "{imbalance} vs {expected}"
    );
}
