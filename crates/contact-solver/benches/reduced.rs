//! Criterion benches of the local (reduced-problem) solvers: every [`Algorithm`] at tol 1e-10,
//! cold start, on a seeded random problem (`generate::random_problem(100, 3)`) and on the
//! FE-like reduced problems of the plane-strain Hertz scene (`tests/support/hertz_scene.rs`,
//! P2, 8 × 8 fine cells, 21 contacts): frictionless as exported (`hertz_8`), and with
//! `μ = 0.3` and the flat shifted by `q_t + 10⁻⁴` (`hertz_8_slide`, partial slip).
//!
//! Run: `cargo bench -p contact-solver --bench reduced`
//!
//! One thread (`faer::Par::Seq`), so the Newton factorisations do not compete with the other
//! builds of the machine. A solve allocates its result (`r`, `x`, the report's history and
//! statuses); the solver's scratch buffers are reused across iterations, as in a simulation.
//! The work–precision study (`examples/work_precision_local.rs`, `docs/benchmarks.md`) sweeps
//! the tolerance and compares with Siconos.

#[path = "../tests/support/hertz_scene.rs"]
mod hertz_scene;

use contact_solver::local::generate::random_problem;
use contact_solver::{Algorithm, ReducedProblem, SimulationSettings, UzawaSettings, UzawaSolver};
use criterion::{Criterion, criterion_group, criterion_main};
use fem_core::{ElementKind, Idealization};
use hertz_scene::HertzScene;
use std::hint::black_box;

const ALGORITHMS: [Algorithm; 6] = [
    Algorithm::Uzawa,
    Algorithm::GaussSeidel,
    Algorithm::ClassicRccm,
    Algorithm::AndersonGaussSeidel,
    Algorithm::AndersonUzawa,
    Algorithm::Newton,
];

fn hertz() -> [(&'static str, ReducedProblem); 2] {
    let scene = HertzScene::new(Idealization::PlaneStrain, ElementKind::Tri6, 8);
    let mut sim = scene.simulation(SimulationSettings::default());
    sim.step(1.0, 1.0).expect("the Hertz step converges");
    let p = sim
        .last_reduced_problem()
        .expect("a reduced problem")
        .clone();
    let q = (p.q().iter().enumerate())
        .map(|(k, &a)| if k % 2 == 1 { a + 1e-4 } else { a })
        .collect();
    let slide = ReducedProblem::new(
        p.w_dense().unwrap().to_vec(),
        q,
        vec![0.3; p.contact_count()],
    )
    .unwrap();
    [("hertz_8", p), ("hertz_8_slide", slide)]
}

fn bench_reduced(c: &mut Criterion) {
    faer::set_global_parallelism(faer::Par::Seq);
    let mut problems = vec![("random_100", random_problem(100, 3))];
    problems.extend(hertz());
    for (name, p) in &problems {
        let laws = p.coulomb_laws();
        let mut g = c.benchmark_group(format!("solver/reduced_{name}"));
        for algorithm in ALGORITHMS {
            let mut solver = UzawaSolver::new(
                UzawaSettings::default()
                    .with_algorithm(algorithm)
                    .with_tol(1e-10)
                    .with_max_iterations(1_000_000),
            );
            g.bench_function(format!("{algorithm:?}"), |b| {
                b.iter(|| black_box(solver.solve(black_box(p), &laws).unwrap()))
            });
        }
        g.finish();
    }
}

criterion_group!(benches, bench_reduced);
criterion_main!(benches);
