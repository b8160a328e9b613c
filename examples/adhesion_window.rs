//! Adhesion fixed point: iterations and time for several Anderson windows on the seed scenes
//! 5.6.1 (delamination) and 5.6.2 (shear), 210 steps each.
//!
//! `cargo run --release --example adhesion_window` (`BIPO_QUICK=1`: windows 0 and 3, 21 steps).

#[path = "common/mod.rs"]
mod common;

use bipo::presets::{DelaminationSpec, Scene, ShearSpec};
use bipotential::contact_solver::SimulationSettings;
use std::time::Instant;

fn measure(mut scene: Scene) -> Result<(usize, usize, usize, f64), Box<dyn std::error::Error>> {
    let start = Instant::now();
    let mut max = 0;
    for k in 1..=scene.steps {
        max = max.max(scene.step(k)?.report.adhesion_iterations);
    }
    let c = scene.simulation.counters();
    Ok((
        c.adhesion_iterations,
        max,
        c.contact_iterations,
        start.elapsed().as_secs_f64(),
    ))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    println!(
        "| scene | Anderson window | β iterations (total) | max per step | contact iterations | time (s) |"
    );
    println!("|---|---|---|---|---|---|");
    let quick = common::quick();
    let windows: &[usize] = if quick { &[0, 3] } else { &[0, 1, 2, 3, 5, 8] };
    let steps = if quick { 21 } else { 210 };
    let delamination = DelaminationSpec {
        steps,
        ..DelaminationSpec::default()
    };
    let shear = ShearSpec {
        steps,
        ..ShearSpec::default()
    };
    for &window in windows {
        let settings = SimulationSettings::default().with_adhesion_anderson_window(window);
        for (name, scene) in [
            ("5.6.1 delamination", delamination.build(settings)?),
            (
                "5.6.1, 1 s",
                DelaminationSpec {
                    duration: 1.0,
                    ..delamination.clone()
                }
                .build(settings)?,
            ),
            ("5.6.2 shear", shear.build(settings)?),
        ] {
            let (total, max, contact, t) = measure(scene)?;
            println!("| {name} | {window} | {total} | {max} | {contact} | {t:.3} |");
        }
    }
    Ok(())
}
