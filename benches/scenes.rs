//! End-to-end benches of whole scenes, so a regression anywhere on the path (mesh, assembly,
//! factorisation, recognition, `F*`, the local solve, the adhesion loop, the reports) shows up
//! as a change of wall time:
//! - `seed_5_6_1_delamination`: seed 5.6.1 as the seed runs it (`DelaminationSpec::default()`:
//!   160 × 8 P1, 210 steps of the RCCM interface), build and every step;
//! - `seed_5_6_2_shear`: seed 5.6.2 (`ShearSpec::default()`), build and every step;
//! - `pile_plancoet`: seed chapter 6 at Plancoët (`PulloutSpec::plancoet()`: geostatic,
//!   installation, 50 pull-out increments with the implicit β fixed point), build and run;
//! - `hertz_p2_8`: the plane-strain Hertz scene of
//!   `crates/contact-solver/tests/integration/hertz.rs` (P2, 8 × 8 fine cells), build and one step.
//!
//! Run: `cargo bench -p bipotential --bench scenes` (figures in `docs/benchmarks.md`). Ten
//! samples each: the scenes take 0.05–5 s, so criterion's default hundred would take minutes.

#[path = "../crates/contact-solver/tests/support/hertz_scene.rs"]
mod hertz_scene;

use bipo::presets::{DelaminationSpec, PulloutSpec, ShearSpec};
use contact_solver::SimulationSettings;
use criterion::{Criterion, criterion_group, criterion_main};
use fem_core::{ElementKind, Idealization};
use hertz_scene::HertzScene;
use std::hint::black_box;

fn seed_scenes(c: &mut Criterion) {
    let mut group = c.benchmark_group("scenes");
    group.sample_size(10);
    group.bench_function("seed_5_6_1_delamination", |b| {
        let spec = DelaminationSpec::default();
        b.iter(|| {
            let mut scene = spec.build(SimulationSettings::default()).unwrap();
            for k in 1..=spec.steps {
                black_box(scene.step(k).unwrap());
            }
        });
    });
    group.bench_function("seed_5_6_2_shear", |b| {
        let spec = ShearSpec::default();
        b.iter(|| {
            let mut scene = spec.build(SimulationSettings::default()).unwrap();
            for k in 1..=spec.steps {
                black_box(scene.step(k).unwrap());
            }
        });
    });
    group.bench_function("pile_plancoet", |b| {
        let spec = PulloutSpec::plancoet();
        b.iter(|| {
            let mut scene = spec.build(SimulationSettings::default()).unwrap();
            black_box(scene.run().unwrap());
        });
    });
    group.bench_function("hertz_p2_8", |b| {
        let scene = HertzScene::new(Idealization::PlaneStrain, ElementKind::Tri6, 8);
        b.iter(|| {
            let mut sim = scene.simulation(SimulationSettings::default());
            black_box(sim.step(1.0, 1.0).unwrap());
        });
    });
    group.finish();
}

criterion_group!(benches, seed_scenes);
criterion_main!(benches);
