//! "Skip what a scene does not need": time and counters on the seed scenes and on a
//! frictionless pressed block, with every skip rule on and with each rule switched off.
//!
//! `cargo run --release --example skip_savings` (`BIPO_QUICK=1`: 21 steps of the seed scenes, a
//! 40 × 5 block).

#[path = "common/mod.rs"]
mod common;

use bipo::presets::{DelaminationSpec, ShearSpec};
use bipotential::contact_laws::Signorini;
use bipotential::contact_solver::{
    ContactSimulation, ContactZone, Counters, RigidLine, SimulationSettings, SkipRules,
};
use bipotential::fem_core::generate::{RectangleSpec, rectangle};
use bipotential::fem_core::{
    Component, ElementKind, Idealization, LinearElasticModel, Material, Supports,
};
use std::error::Error;
use std::time::Instant;

type Outcome = (f64, Counters);

fn seed_scene(delamination: bool, skip: SkipRules) -> Result<Outcome, Box<dyn Error>> {
    let settings = SimulationSettings::default().with_skip(skip);
    let steps = if common::quick() { 21 } else { 210 };
    let mut scene = if delamination {
        DelaminationSpec {
            steps,
            ..DelaminationSpec::default()
        }
        .build(settings)?
    } else {
        ShearSpec {
            steps,
            ..ShearSpec::default()
        }
        .build(settings)?
    };
    let start = Instant::now();
    for k in 1..=scene.steps {
        scene.step(k)?;
    }
    Ok((start.elapsed().as_secs_f64(), scene.simulation.counters()))
}

/// A 4 × 1 P2 block whose bottom 0.001 above a LINE is pressed in 20 steps; only the middle
/// half of the bottom can touch (the LINE spans x ∈ [1, 3]), so half the candidates never do.
fn block(skip: SkipRules) -> Result<Outcome, Box<dyn Error>> {
    let (nx, ny) = if common::quick() { (40, 5) } else { (160, 20) };
    let mut spec = RectangleSpec::new([0.0, 4.0], [0.001, 1.001], nx, ny);
    spec.kind = ElementKind::Tri6;
    let mesh = rectangle(&spec)?;
    let top = mesh.node_set("top")?.to_vec();
    let bottom = mesh.node_set("bottom")?.to_vec();
    let mut supports = Supports::new();
    supports
        .prescribe(&top, Component::Y, 0.0)?
        .fix(&top, Component::X);
    let model = LinearElasticModel::new(
        mesh,
        Idealization::PlaneStrain,
        &[(0, Material::new(200.0, 0.3, 0.0)?)],
        supports,
    )?;
    // the outer quarters face a LINE 0.5 lower: out of reach
    let (mid, outer): (Vec<usize>, Vec<usize>) = bottom.iter().partition(|&&n| {
        let x = model.mesh().nodes()[n][0];
        (1.0..=3.0).contains(&x)
    });
    let zones = vec![
        ContactZone::rigid(
            "middle",
            mid,
            RigidLine::new([0.9, 0.0], [3.1, 0.0])?,
            Signorini,
            0.01,
        ),
        ContactZone::rigid(
            "outer",
            outer,
            RigidLine::new([-1.0, -0.5], [5.0, -0.5])?,
            Signorini,
            0.01,
        ),
    ];
    let settings = SimulationSettings::default().with_skip(skip);
    let mut sim = ContactSimulation::new(model, zones, settings)?;
    let start = Instant::now();
    for k in 1..=20 {
        sim.structure_mut()
            .set_prescribed(&top, Component::Y, -0.002 * k as f64)?;
        sim.step(k as f64, 1.0)?;
    }
    Ok((start.elapsed().as_secs_f64(), sim.counters()))
}

fn main() -> Result<(), Box<dyn Error>> {
    let on = SkipRules::default();
    let variants = [
        ("all rules on", on),
        ("reuse F* off", on.with_reuse_flexibility(false)),
        ("alert distance off", on.with_alert_distance(false)),
        (
            "normal-only F* off",
            on.with_frictionless_normal_only(false),
        ),
        (
            "adhesion loop always",
            on.with_adhesion_loop_only_when_adhesive(false),
        ),
    ];
    println!(
        "| scene | rules | time (s) | F* builds | F* columns solved | β iterations | contact iterations |"
    );
    println!("|---|---|---|---|---|---|---|");
    for scene in [
        "5.6.1 delamination",
        "5.6.2 shear",
        "frictionless block (P2, 20 steps)",
    ] {
        for (name, skip) in variants {
            let (t, c) = match scene {
                "5.6.1 delamination" => seed_scene(true, skip)?,
                "5.6.2 shear" => seed_scene(false, skip)?,
                _ => block(skip)?,
            };
            println!(
                "| {scene} | {name} | {t:.3} | {} | {} | {} | {} |",
                c.flexibility_builds,
                c.flexibility_columns,
                c.adhesion_iterations,
                c.contact_iterations
            );
        }
    }
    Ok(())
}
