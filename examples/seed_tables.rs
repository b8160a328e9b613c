//! The seed's scenes (5.6.1, 5.6.2, the Plancoët pile) with each way of solving adhesion and
//! contact: contact iterations per step (min / median / max), β iterations, total time, and
//! the largest difference of the answer (reactions, β) from the seed's fixed point.
//!
//! - `newton`: [`AdhesionMethod::Newton`] (the default): one loose reduced solve finds the
//!   contact set, then Newton on the reactions with β eliminated;
//! - `fixed point`: the seed's fixed point around the reduced solve (`Algorithm::Auto`);
//! - `classic`: the fixed point around the classical RCCM solver.
//!
//! The runs alternate, `repeats` times each (default 5); times are medians.
//!
//! `cargo run --release --example seed_tables [repeats]` (figures in `docs/benchmarks.md`);
//! `WAYS=newton` or `WAYS=fixed` runs one way, `SCENE=5.6.1` one scene, `FAER=default` leaves
//! faer's parallelism at its default (every core) instead of sequential; `BIPO_QUICK=1` runs 21
//! steps of 5.6.1 and 5.6.2 and 5 of the pile, once. A way that fails, or whose answer is off
//! the fixed point's by more than 1e-6 (reactions relative to the largest, and β), makes the
//! run end in an error after the table.

#[path = "common/mod.rs"]
mod common;

use bipo::presets::{DelaminationSpec, PulloutSpec, ShearSpec};
use bipotential::contact_solver::local::adhesion::AdhesionMethod;
use bipotential::contact_solver::{Algorithm, SimulationSettings, StepResult};
use std::error::Error;
use std::time::Instant;

#[derive(Clone, Copy, PartialEq)]
enum Way {
    Newton,
    FixedPoint,
    Classic,
}

impl Way {
    fn name(self) -> &'static str {
        match self {
            Way::Newton => "newton",
            Way::FixedPoint => "fixed point",
            Way::Classic => "classic",
        }
    }

    fn settings(self) -> SimulationSettings {
        let s = SimulationSettings::default();
        match self {
            Way::Newton => s.with_adhesion_method(AdhesionMethod::Newton),
            Way::FixedPoint => s.with_adhesion_method(AdhesionMethod::FixedPoint),
            Way::Classic => {
                let mut s = s.with_adhesion_method(AdhesionMethod::FixedPoint);
                s.solver.algorithm = Algorithm::ClassicRccm;
                s
            }
        }
    }
}

/// The steps of one run, its wall time, and its Newton fallbacks and warm starts (solved,
/// failed).
type Run = (Vec<StepResult>, f64, [usize; 4]);

/// One run of a scene in one way ([`Run`]).
fn run(scene: &str, way: Way) -> Result<Run, Box<dyn Error>> {
    let settings = way.settings();
    let start = Instant::now();
    let (steps, counters) = match scene {
        "5.6.1" | "5.6.2" => {
            // quick: a tenth of the steps (the same code)
            let steps = if common::quick() { 21 } else { 210 };
            let (mut s, n) = if scene == "5.6.1" {
                let spec = DelaminationSpec {
                    steps,
                    ..DelaminationSpec::default()
                };
                (spec.build(settings)?, spec.steps)
            } else {
                let spec = ShearSpec {
                    steps,
                    ..ShearSpec::default()
                };
                (spec.build(settings)?, spec.steps)
            };
            let steps = (1..=n).map(|k| s.step(k)).collect::<Result<Vec<_>, _>>()?;
            (steps, s.simulation.counters())
        }
        _ => {
            let mut spec = PulloutSpec::plancoet();
            if common::quick() {
                spec.steps = 5;
            }
            let mut s = spec.build(settings)?;
            let r = s.run()?;
            let steps = r.steps.into_iter().map(|p| p.result).collect();
            (steps, s.simulation.counters())
        }
    };
    let seconds = start.elapsed().as_secs_f64();
    let c = counters;
    let newton = [
        c.adhesion_newton_fallbacks,
        c.adhesion_warm_starts,
        c.adhesion_warm_start_failures,
        c.adhesion_factorizations,
    ];
    Ok((steps, seconds, newton))
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() -> Result<(), Box<dyn Error>> {
    // sequential faer (the scenes are small); `FAER=default` leaves faer's default, every
    // core, as the criterion bench `benches/scenes.rs` and a dependent do
    if std::env::var("FAER").as_deref() != Ok("default") {
        faer::set_global_parallelism(faer::Par::Seq);
    }
    let repeats: usize = std::env::args()
        .nth(1)
        .map(|s| s.parse())
        .transpose()?
        .unwrap_or(if common::quick() { 1 } else { 5 });
    let ways = match std::env::var("WAYS").as_deref() {
        Ok("fixed") => vec![Way::FixedPoint],
        Ok("newton") => vec![Way::Newton],
        _ => vec![Way::Newton, Way::FixedPoint, Way::Classic],
    };
    println!(
        "| scene | way | contact iterations per step (min / median / max) | total | β iterations | Newton fallbacks | warm starts (failed) | Jacobians factorised | time (median of {repeats}) | max abs Δr / max abs r | max abs Δβ |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    let only = std::env::var("SCENE").ok();
    // what misses its reference: a way that fails, or an answer off the fixed point's
    let mut misses = Vec::new();
    for scene in ["5.6.1", "5.6.2", "pile"] {
        if only.as_deref().is_some_and(|o| o != scene) {
            continue;
        }
        let mut times = vec![Vec::new(); ways.len()];
        let mut results = vec![Vec::new(); ways.len()];
        let mut failed: Vec<Option<String>> = vec![None; ways.len()];
        let mut fallbacks = vec![[0; 4]; ways.len()];
        for _ in 0..repeats {
            for (w, &way) in ways.iter().enumerate() {
                match run(scene, way) {
                    Ok((steps, t, f)) => {
                        times[w].push(t);
                        results[w] = steps;
                        fallbacks[w] = f;
                    }
                    Err(e) => failed[w] = Some(e.to_string().chars().take(60).collect()),
                }
            }
        }
        let reference = &results[if results.len() > 1 { 1 } else { 0 }];
        let scale = reference
            .iter()
            .flat_map(|s| s.contacts.iter().map(|c| c.r.n.abs().max(c.r.t[0].abs())))
            .fold(0.0, f64::max);
        for (w, &way) in ways.iter().enumerate() {
            if let Some(e) = &failed[w] {
                println!("| {scene} | {} | fails: {e}… | | | | | | | | |", way.name());
                misses.push(format!("{scene} {} fails", way.name()));
                continue;
            }
            let mut per_step: Vec<f64> = results[w]
                .iter()
                .map(|s| s.report.contact_iterations as f64)
                .collect();
            let total: f64 = per_step.iter().sum();
            let beta: usize = results[w]
                .iter()
                .map(|s| s.report.adhesion_iterations)
                .sum();
            let (mut dr, mut db) = (0.0_f64, 0.0_f64);
            for (a, b) in results[w].iter().zip(reference) {
                for (x, y) in a.contacts.iter().zip(&b.contacts) {
                    dr = dr
                        .max((x.r.n - y.r.n).abs())
                        .max((x.r.t[0] - y.r.t[0]).abs());
                    db = db.max((x.beta - y.beta).abs());
                }
            }
            // every way solves the same steps: the fixed point stops on a β change of 1e-8,
            // so the answers differ by ~1e-8 (measured at most 7.7e-8, docs/benchmarks.md)
            for (what, value) in [
                ("max abs Δr / max abs r", dr / scale.max(f64::MIN_POSITIVE)),
                ("max abs Δβ", db),
            ] {
                if let Err(e) = common::check(what, value, 1e-6) {
                    misses.push(format!("{scene} {}: {e}", way.name()));
                }
            }
            let min = per_step.iter().copied().fold(f64::INFINITY, f64::min);
            let max = per_step.iter().copied().fold(0.0, f64::max);
            let med = median(&mut per_step);
            println!(
                "| {scene} | {} | {min} / {med} / {max} | {total} | {beta} | {} | {} ({}) | {} | {:.1} ms | {:.1e} | {db:.1e} |",
                way.name(),
                fallbacks[w][0],
                fallbacks[w][1],
                fallbacks[w][2],
                fallbacks[w][3],
                1e3 * median(&mut times[w]),
                dr / scale.max(f64::MIN_POSITIVE),
            );
        }
    }
    if !misses.is_empty() {
        return Err(misses.join("; ").into());
    }
    Ok(())
}
