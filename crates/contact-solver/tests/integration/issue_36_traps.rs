//! Issue 36, the silent traps of the simulation API (each test fails on the code before it):
//!
//! - `step(time, force_factor)` scales applied forces only: a factor other than 1 on a
//!   structure driven by prescribed displacements alone (a user's first 3D run gave four
//!   identical steps) is refused, in 2D and 3D alike; prescribed displacements are ramped
//!   through the structure and the factor 1;
//! - closed contacts under a frictionless law are `Closed`, not `Stick` (CSV and VTK too);
//! - a floating body with an adhesive interface counts its adhesion iterations;
//! - a block sliding down a frictionless (or not rough enough) inclined LINE under gravity
//!   along −y: `Unbalanced` names the slope's direction and the load along it, not
//!   "translation x … the load along it is 0".
//!
//! Source of the statics: a rigid block on an incline (Meriam & Kraige, *Engineering
//! Mechanics: Statics*, ch. 6): with weight `W` on a slope of angle `θ`, the force left along
//! the slope is `W (sin θ − μ cos θ)` when `μ < tan θ`, and the weight's own share `W sin θ`.
//!
//! ```text
//!                  ┌────┐    block [0, 2] × [0, 1] rotated by θ = 30° about the origin,
//!              ┌───┘  W ↓   body force (0, −1): W = 2; no support (floating)
//!   ══════════/══════        rigid LINE through the origin along (cos θ, sin θ)
//! ```

#![cfg(feature = "fe")]

use contact_laws::{Coulomb, Rccm, RccmParams, Signorini, StandardLaw};
use contact_solver::coupling::output::{HistoryWriter, status_code};
use contact_solver::coupling::solid::{ContactZone3, RigidPlane, SolidContactSimulation};
use contact_solver::{
    ContactSimulation, ContactZone, InterfaceStatus, RigidLine, SimulationSettings, SolverError,
};
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::solid::generate::{box_mesh, lines};
use fem_core::solid::{SolidKind, SolidModel};
use fem_core::{
    Component, ElementKind, Idealization, LinearElasticModel, Material, Mesh, RigidMotion, Supports,
};

/// A unit P1 block pressed on a rigid LINE by the prescribed displacement `push` of its top
/// (E = 100, ν = 0), with `law`; with a body force `(0, −weight)` when not 0.
fn pressed_block(
    law: StandardLaw,
    push: f64,
    weight: f64,
) -> ContactSimulation<LinearElasticModel, StandardLaw> {
    let mesh = rectangle(&RectangleSpec::new([0.0, 1.0], [0.0, 1.0], 4, 4)).unwrap();
    let (top, bottom) = (
        mesh.node_set("top").unwrap().to_vec(),
        mesh.node_set("bottom").unwrap().to_vec(),
    );
    let mut supports = Supports::new();
    supports.fix(&top, Component::X);
    supports.prescribe(&top, Component::Y, push).unwrap();
    let mut model = LinearElasticModel::new(
        mesh,
        Idealization::PlaneStrain,
        &[(0, Material::new(100.0, 0.0, 0.0).unwrap())],
        supports,
    )
    .unwrap();
    if weight != 0.0 {
        model.add_body_force(|_| [0.0, -weight]).unwrap();
    }
    let ground = RigidLine::new([-1.0, 0.0], [2.0, 0.0]).unwrap();
    let zone = ContactZone::rigid("base", bottom, ground, law, 0.1);
    ContactSimulation::new(model, vec![zone], SimulationSettings::default()).unwrap()
}

fn total_n(res: &contact_solver::StepResult) -> f64 {
    res.contacts.iter().map(|c| c.r.n).sum()
}

#[test]
fn issue_36_force_factor_does_not_scale_prescribed_displacements_2d() {
    // the trap: a user ramps the factor of a displacement-driven run
    let mut sim = pressed_block(Signorini.into(), -0.01, 0.0);
    let err = sim.step(1.0, 0.25).unwrap_err();
    assert!(
        matches!(
            err,
            SolverError::InvalidSetting {
                what: "force_factor",
                ..
            }
        ),
        "{err:?}"
    );
    assert!(err.to_string().contains("structure_mut"), "{err}");
    // nothing was stepped; the displacement ramped through the structure gives the ramp:
    // Σ r_n = E δ / H × width = 100 δ (uniaxial strain, ν = 0), to the solver tolerance
    let top = sim.structure().mesh().node_set("top").unwrap().to_vec();
    for k in 1..=4 {
        let delta = 0.0025 * k as f64;
        sim.structure_mut()
            .set_prescribed(&top, Component::Y, -delta)
            .unwrap();
        let res = sim.step(k as f64, 1.0).unwrap();
        // 1e-9: the solver's tolerance on a force of order 1
        assert!(
            (total_n(&res) - 100.0 * delta).abs() < 1e-9,
            "step {k}: Σ r_n = {}",
            total_n(&res)
        );
    }
    // the factor does scale applied forces: a block hanging from its top onto the LINE (gap
    // 0) under a body force takes half the contact force at factor 0.5 (the answer is
    // homogeneous of degree 1 in the load from zero); 1e-9 relative: the solver tolerance
    let full = total_n(
        &pressed_block(Signorini.into(), 0.0, 1.0)
            .step(1.0, 1.0)
            .unwrap(),
    );
    let half = total_n(
        &pressed_block(Signorini.into(), 0.0, 1.0)
            .step(1.0, 0.5)
            .unwrap(),
    );
    assert!(full > 0.1, "Σ r_n = {full}");
    assert!((half - 0.5 * full).abs() < 1e-9 * full, "{half} vs {full}");
}

#[test]
fn issue_36_force_factor_does_not_scale_prescribed_displacements_3d() {
    let mesh = box_mesh(
        &lines(0.0, 1.0, 2),
        &lines(0.0, 1.0, 2),
        &lines(0.0, 0.5, 1),
        SolidKind::Tet4,
    )
    .unwrap();
    let top = mesh.node_set("z1").unwrap().to_vec();
    let mut s = Supports::new();
    s.prescribe(&top, Component::Z, -1e-3)
        .unwrap()
        .fix(&top, Component::X)
        .fix(&top, Component::Y);
    let (nodes, areas) = mesh.nodal_areas("z0").unwrap();
    let model = SolidModel::new(mesh, &[(0, Material::new(1000.0, 0.0, 0.0).unwrap())], s).unwrap();
    let floor = RigidPlane::new([0.0; 3], [0.0, 0.0, 1.0]).unwrap();
    let zone = ContactZone3::rigid("base", nodes, floor, Signorini, 0.1).with_areas(areas);
    let mut sim =
        SolidContactSimulation::new(model, vec![zone], SimulationSettings::for_dimension::<3>())
            .unwrap();
    let err = sim.step(1.0, 0.25).unwrap_err();
    assert!(
        matches!(
            err,
            SolverError::InvalidSetting {
                what: "force_factor",
                ..
            }
        ),
        "{err:?}"
    );
    assert_eq!(sim.counters().steps, 0);
    for k in 1..=2 {
        let delta = 1e-3 * k as f64;
        sim.structure_mut()
            .set_prescribed(&top, Component::Z, -delta)
            .unwrap();
        let res = sim.step(k as f64, 1.0).unwrap();
        let total: f64 = res.contacts.iter().map(|c| c.r.n).sum();
        // σ = E δ / H on a unit area (ν = 0); 1e-8 of the solver's tolerance on a force ~2
        assert!((total - 2000.0 * delta).abs() < 1e-8, "step {k}: {total}");
    }
}

#[test]
fn issue_36_frictionless_closed_contacts_are_closed_not_stick() {
    let mut sim = pressed_block(Signorini.into(), -0.01, 0.0);
    let res = sim.step(1.0, 1.0).unwrap();
    assert!(
        res.contacts
            .iter()
            .all(|c| c.status == InterfaceStatus::Closed),
        "{:?}",
        res.contacts.iter().map(|c| c.status).collect::<Vec<_>>()
    );
    // the CSV names it, the VTK codes it apart from stick (2)
    let mut csv = HistoryWriter::new(Vec::new()).unwrap();
    csv.write_step(&res).unwrap();
    let text = String::from_utf8(csv.finish().unwrap()).unwrap();
    assert!(
        text.lines().skip(1).all(|l| l.contains(",closed,")),
        "{text}"
    );
    assert_eq!(status_code(InterfaceStatus::Closed), 4);
    // friction keeps stick and slip: the same press with Coulomb sticks
    let mut rough = pressed_block(Coulomb::new(0.3).unwrap().into(), -0.01, 0.0);
    let res = rough.step(1.0, 1.0).unwrap();
    assert!(
        res.contacts
            .iter()
            .all(|c| c.status == InterfaceStatus::Stick)
    );
}

#[test]
fn issue_36_floating_adhesive_step_counts_adhesion_iterations() {
    // a floating block glued to a LINE (RCCM), pulled by 1: the adhesion loop runs in every
    // equilibrium solve of the floating stage; it reported 0 iterations
    let mesh = rectangle(&RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 6, 3)).unwrap();
    let bottom = mesh.node_set("bottom").unwrap().to_vec();
    let mut model = LinearElasticModel::floating(
        mesh,
        Idealization::PlaneStrain,
        &[(0, Material::new(1e5, 0.0, 0.0).unwrap())],
        Supports::new(),
    )
    .unwrap();
    model.add_edge_traction("top", |_| [0.0, 0.5]).unwrap();
    let law = Rccm::new(RccmParams {
        c_n: 100.0,
        c_t: 100.0,
        w: 0.01,
        alpha: 0.0,
        mu: 0.2,
        m: 1,
        beta_0: 1.0,
        scheme: contact_laws::BetaScheme::ImplicitEuler,
    })
    .unwrap();
    let base = RigidLine::new([-1.0, 0.0], [3.0, 0.0]).unwrap();
    let zone = ContactZone::rigid("glue", bottom, base, law, 1e-3);
    let mut sim = ContactSimulation::new(model, vec![zone], SimulationSettings::default()).unwrap();
    let res = sim.step(1.0, 1.0).unwrap();
    assert!(res.report.equilibrium_solves > 0);
    assert!(
        res.report.adhesion_iterations > 0,
        "{} adhesion iterations",
        res.report.adhesion_iterations
    );
    assert_eq!(
        sim.counters().adhesion_iterations,
        res.report.adhesion_iterations
    );
}

/// The block `[0, 2] × [0, 1]` (P1, E = 1000, ν = 0.3) rotated by `theta` about the origin,
/// floating, under the body force `(0, −1)`, on the LINE through the origin along the slope.
fn block_on_incline(
    theta: f64,
    law: StandardLaw,
) -> ContactSimulation<LinearElasticModel, StandardLaw> {
    let flat = rectangle(&RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 8, 4)).unwrap();
    let (c, s) = (theta.cos(), theta.sin());
    let nodes: Vec<[f64; 2]> = flat
        .nodes()
        .iter()
        .map(|p| [c * p[0] - s * p[1], s * p[0] + c * p[1]])
        .collect();
    let mut mesh = Mesh::new(
        nodes,
        ElementKind::Tri3,
        flat.connectivity().to_vec(),
        flat.regions().to_vec(),
    )
    .unwrap();
    let bottom = flat.node_set("bottom").unwrap().to_vec();
    mesh.add_node_set("bottom", bottom.clone()).unwrap();
    let mut model = LinearElasticModel::floating(
        mesh,
        Idealization::PlaneStrain,
        &[(0, Material::new(1000.0, 0.3, 0.0).unwrap())],
        Supports::new(),
    )
    .unwrap();
    model.add_body_force(|_| [0.0, -1.0]).unwrap();
    let slope = RigidLine::new([-2.0 * c, -2.0 * s], [4.0 * c, 4.0 * s]).unwrap();
    let zone = ContactZone::rigid("slope", bottom, slope, law, 0.01);
    ContactSimulation::new(model, vec![zone], SimulationSettings::default()).unwrap()
}

#[test]
fn issue_36_unbalanced_on_an_incline_names_the_slope() {
    let theta = 30f64.to_radians();
    let weight = 2.0;
    let down = [-theta.cos(), -theta.sin()];
    for (law, mu) in [
        (StandardLaw::from(Signorini), 0.0),
        (Coulomb::new(0.3).unwrap().into(), 0.3),
    ] {
        let mut sim = block_on_incline(theta, law);
        let err = sim.step(1.0, 1.0).unwrap_err();
        let text = err.to_string();
        eprintln!("μ = {mu}: {text}");
        let SolverError::Unbalanced {
            body,
            motion,
            imbalance,
            load,
        } = err
        else {
            panic!("expected Unbalanced, got {err:?}");
        };
        assert_eq!(body, 0);
        let RigidMotion::Translation { direction } = motion else {
            panic!("expected a translation, got {motion:?}");
        };
        // down the slope, to round-off of the equilibrium solve (1e-9 as floating_block.rs)
        assert!(
            (direction[0] - down[0]).abs() < 1e-9 && (direction[1] - down[1]).abs() < 1e-9,
            "{direction:?}"
        );
        // the weight's share along the slope, W sin θ; out of balance by W (sin θ − μ cos θ)
        // (slip reactions μ r_n exactly, Σ r_n = W cos θ); 1e-9 W as floating_block.rs
        assert!(
            (load - weight * theta.sin()).abs() < 1e-9 * weight,
            "load {load}"
        );
        let expected = weight * (theta.sin() - mu * theta.cos());
        assert!(
            (imbalance - expected).abs() < 1e-9 * weight,
            "imbalance {imbalance} vs {expected}"
        );
        assert!(
            text.contains("translation along (-0.866, -0.500)"),
            "{text}"
        );
        assert_eq!(
            text.matches("add a support or a contact").count(),
            1,
            "{text}"
        );
    }
}
