//! Criterion benches of fem-core's pipeline on P2 plane-strain squares of about 1e4, 1e5 and
//! 1e6 dofs (bottom side clamped, traction on top): model build (sparsity pattern, assembly,
//! symbolic analysis, numeric Cholesky), the symbolic analysis alone, the numeric
//! factorisation alone (the refactorisation cost when K changes), and one solve.
//!
//! Run: `cargo bench -p fem-core --bench pipeline` (the 1e6 case takes a few minutes; filter
//! with e.g. `-- 100000`). Figures: docs/benchmarks.md.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::{
    Component, ElementKind, Idealization, LinearElasticModel, Material, Mesh, SpdSolver, Structure,
    Supports,
};
use std::hint::black_box;
use std::time::Duration;

fn square(target_dofs: usize) -> (Mesh, Supports) {
    let n = (((target_dofs as f64 / 2.0).sqrt() - 1.0) / 2.0).round() as usize;
    let spec = RectangleSpec {
        kind: ElementKind::Tri6,
        ..RectangleSpec::new([0.0, 1.0], [0.0, 1.0], n, n)
    };
    let mesh = rectangle(&spec).unwrap();
    let bottom = mesh.node_set("bottom").unwrap().to_vec();
    let mut supports = Supports::new();
    supports
        .fix(&bottom, Component::X)
        .fix(&bottom, Component::Y);
    (mesh, supports)
}

fn build(mesh: &Mesh, supports: &Supports) -> LinearElasticModel {
    let material = Material::new(1000.0, 0.3, 0.0).unwrap();
    LinearElasticModel::new(
        mesh.clone(),
        Idealization::PlaneStrain,
        &[(0, material)],
        supports.clone(),
    )
    .unwrap()
}

fn bench_pipeline(c: &mut Criterion) {
    let mut g = c.benchmark_group("p2_plane_strain");
    for target in [10_000usize, 100_000, 1_000_000] {
        if target >= 1_000_000 {
            g.sample_size(10).measurement_time(Duration::from_secs(60));
        } else {
            g.sample_size(10).measurement_time(Duration::from_secs(10));
        }
        let (mesh, supports) = square(target);
        let mut model = build(&mesh, &supports);
        model.add_edge_traction("top", |_| [0.1, -1.0]).unwrap();
        g.bench_with_input(BenchmarkId::new("build", target), &target, |b, _| {
            b.iter(|| black_box(build(&mesh, &supports)))
        });
        g.bench_with_input(BenchmarkId::new("symbolic", target), &target, |b, _| {
            b.iter(|| black_box(SpdSolver::new(model.stiffness().symbolic()).unwrap()))
        });
        let mut solver = SpdSolver::new(model.stiffness().symbolic()).unwrap();
        g.bench_with_input(BenchmarkId::new("numeric", target), &target, |b, _| {
            b.iter(|| solver.factor(model.stiffness()).unwrap())
        });
        let mut u = vec![0.0; model.dof_count()];
        g.bench_with_input(BenchmarkId::new("solve", target), &target, |b, _| {
            b.iter(|| model.free_response_into(1.0, black_box(&mut u)).unwrap())
        });
    }
    g.finish();
}

criterion_group!(benches, bench_pipeline);
criterion_main!(benches);
