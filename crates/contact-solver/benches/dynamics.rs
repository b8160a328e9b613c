//! Criterion bench of one Moreau–Jean step (issue 39) on a 2D body of about 1e5 dofs with
//! 1 000 contacts: a P2 strip `50 × 2.5` (500 × 25 cells, 102 102 dofs, plane strain,
//! `E = 1e4`, `ν = 0.3`, `ρ = 1`, its own weight `ρ g = 10`) resting on a rigid line, its
//! 1 001 bottom nodes the candidates, dropped at `v0 = 0.01` from contact (`θ = 1/2`, `e = 0`,
//! `h = 1e-3`, consistent mass), on two paths: `active_set` (the default `Auto`, which takes
//! the primal active set beyond 500 contacts: no `F*`, its own factorisations of `M̂` with the
//! closed contacts as Dirichlet rows) and `dense` (`FlexibilityMode::Dense`: `F*` built once
//! with one back-substitution per column, then Gauss–Seidel on it).
//!
//! Run: `cargo bench -p contact-solver --bench dynamics` (or, sharing the release build of
//! the examples, `cargo bench --profile release -p contact-solver --bench dynamics`).
//!
//! Before each timed loop the bench steps 10 times (the first builds `F* = H M̂⁻¹ Hᵀ` on the
//! dense path), then counts over 20 more steps the back-substitutions with `M̂`
//! ([`DynamicModel::solve_count`](fem_core::dynamic::DynamicModel::solve_count)) and the
//! path's own work ([`Counters`](contact_solver::Counters)) and prints their means per step:
//! the bound is 3 back-substitutions (the free velocity, the recovery `M̂⁻¹ Hᵀ r`, and
//! one spare) plus the local solve. One thread (`faer::Par::Seq`). Each iteration is a whole
//! step (`ContactSimulation::advance`: free response, detection, local solve, recovery,
//! energy balance); a step allocates its report.

use contact_laws::Signorini;
use contact_solver::coupling::simulation::MoreauJean;
use contact_solver::{
    ContactSimulation, ContactZone, FlexibilityMode, RigidLine, SimulationSettings,
};
use criterion::{Criterion, criterion_group, criterion_main};
use fem_core::dynamic::{DynamicModel, MassKind, Rayleigh};
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::{ElementKind, Idealization, LinearElasticModel, Material, Structure, Supports};
use std::hint::black_box;
use std::time::Instant;

type Sim = ContactSimulation<DynamicModel<2>, Signorini, 2, MoreauJean>;

/// The strip of the module docs with the flexibility path `mode`, not yet stepped.
fn strip(mode: FlexibilityMode) -> Sim {
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
    let settings = SimulationSettings::default().with_flexibility(mode);
    ContactSimulation::with_scheme(body, vec![zone], settings, scheme).expect("valid scene")
}

/// Steps `sim` 10 times, then prints the mean back-substitutions with `M̂` and the path's own
/// work (active-set factorisations and solves, `F*` columns) over 20 more.
fn count(name: &str, sim: &mut Sim, h: f64) {
    let start = Instant::now();
    let first = sim.advance(h).expect("a step");
    let first_time = start.elapsed();
    let after_first = sim.structure().solve_count();
    for _ in 0..9 {
        sim.advance(h).expect("a step");
    }
    let (before, counters, start) = (
        sim.structure().solve_count(),
        sim.counters(),
        Instant::now(),
    );
    let mut active = 0;
    for _ in 0..20 {
        active = sim.advance(h).expect("a step").report.active_contacts;
    }
    let elapsed = start.elapsed() / 20;
    let after = sim.counters();
    let per = |a: usize, b: usize| (a - b) as f64 / 20.0;
    eprintln!(
        "{name}: {} dofs, {} candidates, {active} active; first step {first_time:.2?} \
         ({after_first} back-substitutions with M̂, F* {} columns); then per step: \
         {:.2} back-substitutions with M̂, {:.2} active-set factorisations, {:.2} active-set \
         solves, {:.2} F* columns, {:.2} contact iterations; {elapsed:.2?} per step",
        sim.structure().dof_count(),
        first.contacts.len(),
        counters.flexibility_columns,
        per(sim.structure().solve_count(), before),
        per(
            after.active_set_factorizations,
            counters.active_set_factorizations
        ),
        per(after.active_set_solves, counters.active_set_solves),
        per(after.flexibility_columns, counters.flexibility_columns),
        per(after.contact_iterations, counters.contact_iterations),
    );
}

fn bench_dynamics(c: &mut Criterion) {
    faer::set_global_parallelism(faer::Par::Seq);
    let h = 1e-3;
    let mut g = c.benchmark_group("solver/moreau_jean_step");
    g.sample_size(10);
    for (name, mode) in [
        ("active_set", FlexibilityMode::Auto { dense_limit: 500 }),
        ("dense", FlexibilityMode::Dense),
    ] {
        let mut sim = strip(mode);
        count(name, &mut sim, h);
        g.bench_function(format!("strip_1e5_dofs_1000_contacts_{name}"), |b| {
            b.iter(|| black_box(sim.advance(h).expect("a step")))
        });
    }
    g.finish();
}

criterion_group!(benches, bench_dynamics);
criterion_main!(benches);
