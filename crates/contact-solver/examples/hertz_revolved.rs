//! Hertz in 3D against the axisymmetric model on the same meridian grid: the axisymmetric
//! scene of `tests/integration/hertz.rs` (P2, `m × m` fine cells, `a ≈ 1`) and its quarter
//! revolved in `S` sectors (`tests/support/hertz_revolved.rs`), side by side: total force `P`,
//! contact radius `a` (second moment of the nodal forces), both against Hertz for each model's
//! own `P`, the 3D model's size and time.
//!
//! ```text
//! cargo run --release -p contact-solver --example hertz_revolved -- [m ...] [--sectors S ...]
//! ```
//! Defaults: `m = 4 8`, `S = 3 6 12`.

#[path = "../tests/support/hertz_revolved.rs"]
mod hertz_revolved;
#[path = "../tests/support/hertz_scene.rs"]
mod hertz_scene;

use contact_solver::SimulationSettings;
use fem_core::{ElementKind, Idealization};
use hertz_revolved::{Params, measure, quarter};
use hertz_scene::HertzScene;
use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let split = args.iter().position(|a| a == "--sectors");
    let (ms, ss) = match split {
        Some(i) => (&args[..i], &args[i + 1..]),
        None => (&args[..], &[][..]),
    };
    let parse = |v: &[String], default: &[usize]| -> Result<Vec<usize>, std::num::ParseIntError> {
        if v.is_empty() {
            Ok(default.to_vec())
        } else {
            v.iter().map(|s| s.parse()).collect()
        }
    };
    let ms = parse(ms, &[4, 8])?;
    let ss = parse(ss, &[3, 6, 12])?;
    println!("| m | model | DOF | P | a | a / a_Hertz − 1 | P vs axisym. | a vs axisym. | time |");
    println!("|---|---|---|---|---|---|---|---|---|");
    for &m in &ms {
        let scene = HertzScene::new(Idealization::Axisymmetric, ElementKind::Tri6, m);
        let t = Instant::now();
        let mut axi = scene.simulation(SimulationSettings::default());
        let res = axi.step(1.0, 1.0)?;
        let m2 = scene.measure(&axi, &res);
        let t2 = t.elapsed().as_secs_f64();
        let (a_h, _) = scene.hertz(m2.p_total);
        println!(
            "| {m} | axisymmetric | {} | {:.5} | {:.5} | {:+.2} % | | | {:.3} s |",
            2 * axi.structure().mesh().node_count(),
            m2.p_total,
            m2.a_fe,
            100.0 * (m2.a_fe / a_h - 1.0),
            t2
        );
        let params = Params {
            delta: scene.delta,
            young: scene.young,
            poisson: scene.poisson,
            alert: scene.alert,
        };
        for &s in &ss {
            let t = Instant::now();
            let mut sim = quarter(&scene.mesh(), params, s);
            let res = sim.step(1.0, 1.0)?;
            let (p, a) = measure(&res);
            let t3 = t.elapsed().as_secs_f64();
            let (a_h, _) = scene.hertz(p);
            println!(
                "| {m} | 3D quarter, {s} sectors | {} | {p:.5} | {a:.5} | {:+.2} % | {:+.2} % | {:+.2} % | {t3:.2} s |",
                3 * sim.structure().mesh().node_count(),
                100.0 * (a / a_h - 1.0),
                100.0 * (p / m2.p_total - 1.0),
                100.0 * (a / m2.a_fe - 1.0),
            );
        }
    }
    Ok(())
}
