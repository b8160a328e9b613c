//! Issue 35: one [`ContactSimulation`] for both dimensions.
//!
//! - **One generic function, two dimensions**: [`press`] builds a simulation, steps it and
//!   checks the Signorini patch (a block on a frictionless rigid floor, its top pushed down by
//!   `δ`, `ν = 0`: the state is uniaxial and the total reaction is `E δ / H` times the
//!   contact area, exact for linear and quadratic elements) on a 2D and a 3D problem.
//! - **Parity with the 3D simulation**: the 3D integration scenes (the Signorini patch on P1
//!   and P2, a block pressed then sheared with Coulomb friction, a rigid sphere on a block,
//!   node-to-face between two deformable blocks, an RCCM glued block pulled off over several
//!   steps, the primal active-set and the matrix-free paths) are run through
//!   [`SolidContactSimulation`] and `ContactSimulation<_, _, 3>` and the reactions and
//!   displacements compared. Both solve the same reduced problem to the solver's tolerance
//!   (`UzawaSettings::tol`, 1e-10 relative on the natural-map residual), by different routes
//!   where the 3D copy had its own rules (a plain reduced solve instead of the adhesion loop's
//!   single pass, another initial active set): the tolerance is that `1e-10` of the largest
//!   reaction (resp. displacement) of the scene. Measured: 0 on the frictionless scenes,
//!   ≤ 6e-15 with friction (dense, active set, matrix-free), 9e-13 on the RCCM glue (its
//!   adhesion fixed point stops at `adhesion_tol`). Those figures were measured against the
//!   former 3D copy (commit `05901b0`); `SolidContactSimulation` is now the generic simulation
//!   itself (an alias), and the test runs it with the 3D defaults
//!   (`for_dimension::<3>()`: 96 right-hand sides per solve, 20 detection passes) against the
//!   2D defaults with the 3D dense limit (64, 5), which must agree to the same tolerance (the
//!   blocking of the `F*` solves changes no answer beyond round-off).

#![cfg(feature = "fe")]

use crate::solid_interfaces::{supports, two_blocks};
use contact_laws::{BetaScheme, ContactLaw, Coulomb, Rccm, RccmParams, Signorini, StandardLaw};
use contact_solver::coupling::obstacle::RigidLine;
use contact_solver::coupling::solid::{
    ContactZone3, RigidPlane, RigidSphere, Side3, SolidContactSimulation, TriSurface,
};
use contact_solver::coupling::space::ContactSpace;
use contact_solver::{ContactSimulation, ContactZone, FlexibilityMode, SimulationSettings};
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::solid::generate::{box_mesh, lines};
use fem_core::solid::{SolidKind, SolidModel};
use fem_core::{Component, Dim, Idealization, LinearElasticModel, Material, Structure, Supports};

/// Builds the simulation of `structure` and `zone`, steps it once and checks the patch: the
/// total normal reaction is `expected`, every contact is closed and carries no tangential
/// force. Returns the total reaction. The same code for `D = 2` and `D = 3`.
fn press<S: Structure<D>, L: ContactLaw + Clone, const D: usize>(
    structure: S,
    zone: ContactZone<L, D>,
    expected: f64,
) -> f64
where
    Dim<D>: ContactSpace<D>,
{
    let settings = SimulationSettings::for_dimension::<D>();
    let mut sim = ContactSimulation::new(structure, vec![zone], settings).unwrap();
    let res = sim.step(1.0, 1.0).unwrap();
    let total: f64 = res.contacts.iter().map(|c| c.reaction()[0]).sum();
    // the solver's tolerance (1e-10 relative) on the total
    assert!(
        (total - expected).abs() < 1e-8 * expected,
        "D = {D}: {total} vs {expected}"
    );
    for c in &res.contacts {
        let r = c.reaction();
        assert!(
            c.gap.abs() < 1e-9,
            "D = {D}: node {} gap {:e}",
            c.node,
            c.gap
        );
        assert!(
            r[1..].iter().all(|t| *t == 0.0),
            "D = {D}: frictionless {r:?}"
        );
    }
    assert_eq!(sim.counters().steps, 1);
    total
}

#[test]
fn issue_35_one_generic_function_presses_2d_and_3d() {
    let (e, delta) = (1000.0, 1e-3);
    let m = Material::new(e, 0.0, 0.0).unwrap();
    // 2D: a unit square, plane strain, on a rigid line
    let mesh = rectangle(&RectangleSpec::new([0.0, 1.0], [0.0, 1.0], 4, 4)).unwrap();
    let (top, bottom) = (
        mesh.node_set("top").unwrap().to_vec(),
        mesh.node_set("bottom").unwrap().to_vec(),
    );
    let mut s = Supports::new();
    s.prescribe(&top, Component::Y, -delta)
        .unwrap()
        .fix(&top, Component::X);
    let model = LinearElasticModel::new(mesh, Idealization::PlaneStrain, &[(0, m)], s).unwrap();
    let ground = RigidLine::new([-1.0, 0.0], [2.0, 0.0]).unwrap();
    let zone = ContactZone::rigid("base", bottom, ground, Signorini, 0.1);
    press(model, zone, e * delta);
    // 3D: a block 2 × 1.5 × 1 (P2) on a rigid plane, the same generic function
    let mesh = box_mesh(
        &lines(0.0, 2.0, 3),
        &lines(0.0, 1.5, 2),
        &lines(0.0, 1.0, 2),
        SolidKind::Tet10,
    )
    .unwrap();
    let mut s = Supports::new();
    s.fix(mesh.node_set("x0").unwrap(), Component::X)
        .fix(mesh.node_set("y0").unwrap(), Component::Y)
        .prescribe(mesh.node_set("z1").unwrap(), Component::Z, -delta)
        .unwrap();
    let (nodes, areas) = mesh.nodal_areas("z0").unwrap();
    let model = SolidModel::new(mesh, &[(0, m)], s).unwrap();
    let plane = RigidPlane::new([0.0; 3], [0.0, 0.0, 1.0]).unwrap();
    let zone = ContactZone::<_, 3>::rigid("base", nodes, plane, Signorini, 0.1).with_areas(areas);
    press(model, zone, e * delta * 3.0);
}

/// A 3D scene: the structure, its zone, and the prescribed values of each step (nodes,
/// component, value).
struct Scene {
    model: SolidModel,
    zone: ContactZone3<StandardLaw>,
    steps: Vec<Vec<(Vec<usize>, Component, f64)>>,
    flexibility: Option<FlexibilityMode>,
}

/// Runs `scene` through both simulations, step by step, and compares the reactions and the
/// nodal displacements (module docs for the tolerance). Returns the largest relative
/// differences seen (reaction, displacement).
fn parity(label: &str, make: impl Fn() -> Scene) -> (f64, f64) {
    let scene = make();
    let mut solid_settings = SimulationSettings::for_dimension::<3>();
    let mut settings = SimulationSettings::default().with_flexibility(solid_settings.flexibility);
    if let Some(f) = scene.flexibility {
        solid_settings.flexibility = f;
        settings = settings.with_flexibility(f);
    }
    let mut old = SolidContactSimulation::new(scene.model, vec![scene.zone], solid_settings)
        .unwrap_or_else(|e| panic!("{label}: {e}"));
    let scene = make();
    let mut new = ContactSimulation::new(scene.model, vec![scene.zone], settings)
        .unwrap_or_else(|e| panic!("{label}: {e}"));
    let (mut worst_r, mut worst_u) = (0.0_f64, 0.0_f64);
    for (k, step) in scene.steps.iter().enumerate() {
        for (nodes, c, v) in step {
            old.structure_mut().set_prescribed(nodes, *c, *v).unwrap();
            new.structure_mut().set_prescribed(nodes, *c, *v).unwrap();
        }
        let t = (k + 1) as f64;
        let a = old.step(t, 1.0).unwrap_or_else(|e| panic!("{label}: {e}"));
        let b = new.step(t, 1.0).unwrap_or_else(|e| panic!("{label}: {e}"));
        assert_eq!(a.contacts.len(), b.contacts.len(), "{label}");
        let r_scale = a
            .contacts
            .iter()
            .flat_map(|c| c.reaction())
            .fold(0.0_f64, |m, v| m.max(v.abs()))
            .max(1e-300);
        for (ca, cb) in a.contacts.iter().zip(&b.contacts) {
            assert_eq!(ca.node, cb.node, "{label}");
            let (ra, rb) = (ca.reaction(), cb.reaction());
            for d in 0..3 {
                let diff = (ra[d] - rb[d]).abs() / r_scale;
                worst_r = worst_r.max(diff);
                assert!(
                    diff < 1e-10,
                    "{label}, step {}: node {} r {ra:?} vs {rb:?}",
                    k + 1,
                    ca.node,
                );
            }
        }
        let ub = new.nodal_displacements();
        let u_scale = ub
            .iter()
            .flatten()
            .fold(0.0_f64, |m, v| m.max(v.abs()))
            .max(1e-300);
        for (n, u) in ub.iter().enumerate() {
            let ua = old.nodal_displacement(n);
            for d in 0..3 {
                let diff = (ua[d] - u[d]).abs() / u_scale;
                worst_u = worst_u.max(diff);
                assert!(
                    diff < 1e-10,
                    "{label}, step {}: node {n} u {ua:?} vs {u:?}",
                    k + 1
                );
            }
        }
    }
    eprintln!("issue 35 parity, {label}: reactions {worst_r:.1e}, displacements {worst_u:.1e}");
    (worst_r, worst_u)
}

/// The Signorini patch (`solid_contact.rs`), or with `mu` a block pressed then sheared.
fn block(kind: SolidKind, mu: Option<f64>, flexibility: Option<FlexibilityMode>) -> Scene {
    let m = Material::new(1000.0, 0.3, 0.0).unwrap();
    let mesh = box_mesh(
        &lines(0.0, 2.0, 3),
        &lines(0.0, 1.5, 2),
        &lines(0.0, 1.0, 2),
        kind,
    )
    .unwrap();
    let top = mesh.node_set("z1").unwrap().to_vec();
    let mut s = Supports::new();
    let steps = if mu.is_some() {
        s.prescribe(&top, Component::Z, 0.0)
            .unwrap()
            .prescribe(&top, Component::X, 0.0)
            .unwrap()
            .prescribe(&top, Component::Y, 0.0)
            .unwrap();
        vec![
            vec![(top.clone(), Component::Z, -1e-3)],
            vec![
                (top.clone(), Component::X, 6e-4),
                (top.clone(), Component::Y, 3e-4),
            ],
            vec![(top.clone(), Component::X, 3e-3)],
        ]
    } else {
        s.fix(mesh.node_set("x0").unwrap(), Component::X)
            .fix(mesh.node_set("y0").unwrap(), Component::Y)
            .prescribe(&top, Component::Z, 0.0)
            .unwrap();
        vec![vec![(top.clone(), Component::Z, -1e-3)]]
    };
    let (nodes, areas) = mesh.nodal_areas("z0").unwrap();
    let model = SolidModel::new(mesh, &[(0, m)], s).unwrap();
    let plane = RigidPlane::new([0.0; 3], [0.0, 0.0, 1.0]).unwrap();
    let law: StandardLaw = match mu {
        Some(mu) => Coulomb::new(mu).unwrap().into(),
        None => Signorini.into(),
    };
    let zone = ContactZone3::rigid("base", nodes, plane, law, 0.1).with_areas(areas);
    Scene {
        model,
        zone,
        steps,
        flexibility,
    }
}

#[test]
fn issue_35_parity_with_the_3d_simulation_on_rigid_obstacles() {
    parity("Signorini patch P1", || block(SolidKind::Tet4, None, None));
    parity("Signorini patch P2", || block(SolidKind::Tet10, None, None));
    parity("Coulomb block pressed, sheared, sliding", || {
        block(SolidKind::Tet10, Some(0.3), None)
    });
    parity("active set, Coulomb", || {
        block(
            SolidKind::Tet10,
            Some(0.3),
            Some(FlexibilityMode::ActiveSet),
        )
    });
    parity("matrix-free, Coulomb", || {
        block(
            SolidKind::Tet4,
            Some(0.3),
            Some(FlexibilityMode::MatrixFree),
        )
    });
    parity("rigid sphere (Hertz-like)", || {
        let m = Material::new(1000.0, 0.3, 0.0).unwrap();
        let xy = lines(0.0, 2.0, 5);
        let z = lines(-2.0, 0.0, 3);
        let mesh = box_mesh(&xy, &xy, &z, SolidKind::Tet10).unwrap();
        let bottom = mesh.node_set("z0").unwrap().to_vec();
        let mut s = Supports::new();
        s.fix(mesh.node_set("x0").unwrap(), Component::X)
            .fix(mesh.node_set("y0").unwrap(), Component::Y)
            .prescribe(&bottom, Component::Z, 0.0)
            .unwrap();
        let (nodes, areas) = mesh.nodal_areas("z1").unwrap();
        let model = SolidModel::new(mesh, &[(0, m)], s).unwrap();
        let ball = RigidSphere::new([0.0, 0.0, 10.0], 10.0, Side3::Outside).unwrap();
        let zone = ContactZone3::rigid("top", nodes, ball, Signorini.into(), 0.5).with_areas(areas);
        Scene {
            model,
            zone,
            steps: vec![
                vec![(bottom.clone(), Component::Z, 0.02)],
                vec![(bottom.clone(), Component::Z, 0.04)],
            ],
            flexibility: None,
        }
    });
}

#[test]
fn issue_35_parity_with_the_3d_simulation_between_bodies() {
    // node-to-face on non-matching grids, both blocks deformable (`solid_interfaces.rs`)
    for kind in [SolidKind::Tet4, SolidKind::Tet10] {
        parity(&format!("node-to-face {kind:?}"), || {
            let m = Material::new(1000.0, 0.3, 0.0).unwrap();
            let mesh = two_blocks(kind, 2, 3);
            let (nodes, areas) = mesh.nodal_areas("b.z0").unwrap();
            let surface = TriSurface::from_face_set(&mesh, "a.z1").unwrap();
            let zone = ContactZone3::node_to_face("i", nodes, surface, Signorini.into(), 0.1)
                .with_areas(areas);
            let top = mesh.node_set("b.z1").unwrap().to_vec();
            let s = supports(&mesh, &[(Component::Z, 0.0)]);
            let model = SolidModel::new(mesh, &[(0, m), (1, m)], s).unwrap();
            Scene {
                model,
                zone,
                steps: vec![vec![(top, Component::Z, -1e-3)]],
                flexibility: None,
            }
        });
    }
    // RCCM glue pulled off a rigid plane over several steps: elastic, then damaging
    parity("RCCM glued block pulled off", || {
        let law = Rccm::new(RccmParams {
            c_n: 100.0,
            c_t: 100.0,
            w: 1e-4,
            alpha: 0.0,
            mu: 0.3,
            m: 1,
            beta_0: 1.0,
            scheme: BetaScheme::ImplicitEuler,
        })
        .unwrap();
        let m = Material::new(1000.0, 0.0, 0.0).unwrap();
        let mesh = two_blocks(SolidKind::Tet10, 2, 2);
        let (nodes, areas) = mesh.nodal_areas("b.z0").unwrap();
        let plane = RigidPlane::new([0.0, 0.0, 1.0], [0.0, 0.0, 1.0]).unwrap();
        let zone = ContactZone3::rigid("glue", nodes, plane, law.into(), 0.1).with_areas(areas);
        let mut s = Supports::new();
        for c in [Component::X, Component::Y, Component::Z] {
            s.fix(mesh.node_set("a.z0").unwrap(), c)
                .fix(mesh.node_set("a.z1").unwrap(), c);
        }
        s.fix(mesh.node_set("b.x0").unwrap(), Component::X)
            .fix(mesh.node_set("b.y0").unwrap(), Component::Y);
        let top = mesh.node_set("b.z1").unwrap().to_vec();
        s.prescribe(&top, Component::Z, 0.0).unwrap();
        let model = SolidModel::new(mesh, &[(0, m), (1, m)], s).unwrap();
        Scene {
            model,
            zone,
            steps: (1..=4)
                .map(|k| vec![(top.clone(), Component::Z, 4e-4 * k as f64)])
                .collect(),
            flexibility: None,
        }
    });
}
