//! Criterion bench of one Moreau–Jean step (issue 39) on a 2D body of about 1e5 dofs with
//! 1 000 contacts: a P2 strip `50 × 2.5` (500 × 25 cells, 102 102 dofs, plane strain,
//! `E = 1e4`, `ν = 0.3`, `ρ = 1`, its own weight `ρ g = 10`) resting on a rigid line, its
//! 1 001 bottom nodes the candidates, dropped at `v0 = 0.01` from contact (`θ = 1/2`, `e = 0`,
//! `h = 1e-3`, consistent mass, Gauss–Seidel as set by default).
//!
//! Run: `cargo bench -p contact-solver --bench dynamics` (or, sharing the release build of
//! the examples, `cargo bench --profile release -p contact-solver --bench dynamics`).
//!
//! Before the timed loop the bench steps 10 times (the first builds `F* = H M̂⁻¹ Hᵀ`), then
//! counts the back-substitutions with `M̂` of 20 more steps
//! ([`DynamicModel::solve_count`](fem_core::dynamic::DynamicModel::solve_count)) and prints
//! their mean per step: the bound is 3 (the free velocity, the recovery
//! `M̂⁻¹ Hᵀ r`, and one spare). One thread (`faer::Par::Seq`). Each iteration is a whole
//! step (`ContactSimulation::advance`: free response, detection, local solve, recovery,
//! energy balance); a step allocates its report.

use contact_laws::Signorini;
use contact_solver::coupling::simulation::MoreauJean;
use contact_solver::{ContactSimulation, ContactZone, RigidLine, SimulationSettings};
use criterion::{Criterion, criterion_group, criterion_main};
use fem_core::dynamic::{DynamicModel, MassKind, Rayleigh};
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::{ElementKind, Idealization, LinearElasticModel, Material, Structure, Supports};
use std::hint::black_box;
use std::time::Instant;

type Sim = ContactSimulation<DynamicModel<2>, Signorini, 2, MoreauJean>;

/// The strip of the module docs, not yet stepped.
fn strip() -> Sim {
    let spec = RectangleSpec {
        kind: ElementKind::Tri6,
        ..RectangleSpec::new([0.0, 50.0], [0.0, 2.5], 500, 25)
    };
    let mesh = rectangle(&spec).expect("a valid strip");
    let bottom = mesh.node_set("bottom").expect("named").to_vec();
    let m = Material::new(1e4, 0.3, 10.0)
        .and_then(|m| m.with_density(1.0))
        .expect("valid material");
    let mut model =
        LinearElasticModel::floating(mesh, Idealization::PlaneStrain, &[(0, m)], Supports::new())
            .expect("a body held by contact");
    model.add_self_weight().expect("a unit weight");
    let body = DynamicModel::new(model, MassKind::Consistent, Rayleigh::default()).expect("mass");
    let scheme = MoreauJean::new(0.5)
        .and_then(|s| s.with_velocity_field(&body, |_| [0.0, -0.01]))
        .expect("valid scheme");
    let ground = RigidLine::new([-1.0, 0.0], [51.0, 0.0]).expect("a line"); // normal +y
    let zone = ContactZone::rigid("ground", bottom, ground, Signorini, 0.01);
    ContactSimulation::with_scheme(body, vec![zone], SimulationSettings::default(), scheme)
        .expect("valid scene")
}

fn bench_dynamics(c: &mut Criterion) {
    faer::set_global_parallelism(faer::Par::Seq);
    let h = 1e-3;
    let start = Instant::now();
    let mut sim = strip();
    let built = start.elapsed();
    let start = Instant::now();
    let first = sim.advance(h).expect("a step");
    let first_time = start.elapsed();
    let after_first = sim.structure().solve_count();
    for _ in 0..9 {
        sim.advance(h).expect("a step");
    }
    let (before, start) = (sim.structure().solve_count(), Instant::now());
    let mut active = 0;
    for _ in 0..20 {
        active = sim.advance(h).expect("a step").report.active_contacts;
    }
    let per_step = (sim.structure().solve_count() - before) as f64 / 20.0;
    eprintln!(
        "moreau_jean_step: {} dofs, {} candidates, {active} active; model + M̂ {built:.2?}, \
         first step {first_time:.2?} ({after_first} back-substitutions, F* included), then \
         {per_step:.2} back-substitutions per step, {:.2?} per step",
        sim.structure().dof_count(),
        first.contacts.len(),
        start.elapsed() / 20
    );
    let mut g = c.benchmark_group("solver/moreau_jean_step");
    g.sample_size(10);
    g.bench_function("strip_1e5_dofs_1000_contacts", |b| {
        b.iter(|| black_box(sim.advance(h).expect("a step")))
    });
    g.finish();
}

criterion_group!(benches, bench_dynamics);
criterion_main!(benches);
