//! Time and size of fem-core's pipeline on P2 plane-strain rectangles: mesh generation,
//! model build (pattern + assembly + symbolic + numeric Cholesky), and one solve, for a list of
//! target DOF counts (default 1e4, 1e5, 1e6).
//!
//! Run: `cargo run --release --example fem_scaling -- 10000 100000 1000000` (`BIPO_QUICK=1`
//! and no sizes: 2000 DOF).
//! Peak memory: `/usr/bin/time -v target/release/examples/fem_scaling 1000000`.

use bipotential::fem_core::generate::{RectangleSpec, rectangle};
use bipotential::fem_core::{
    Component, ElementKind, Idealization, LinearElasticModel, Material, SpdSolver, Structure,
    Supports,
};
use std::error::Error;
use std::time::Instant;

fn main() -> Result<(), Box<dyn Error>> {
    let targets: Vec<usize> = std::env::args()
        .skip(1)
        .map(|a| a.parse())
        .collect::<Result<_, _>>()?;
    let targets = if targets.is_empty() && std::env::var_os("BIPO_QUICK").is_some_and(|v| v != "0")
    {
        vec![2_000]
    } else if targets.is_empty() {
        vec![10_000, 100_000, 1_000_000]
    } else {
        targets
    };
    println!(
        "| target DOF | free DOF | nnz(L of K) | mesh (s) | build (s) | of which symbolic (s) | numeric (s) | solve (s) | build + solve (s) |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    for target in targets {
        // P2 square with n × n cells has (2n + 1)² nodes, 2 (2n + 1)² dofs.
        let n = (((target as f64 / 2.0).sqrt() - 1.0) / 2.0)
            .round()
            .max(1.0) as usize;
        let t = Instant::now();
        let spec = RectangleSpec {
            kind: ElementKind::Tri6,
            ..RectangleSpec::new([0.0, 1.0], [0.0, 1.0], n, n)
        };
        let mesh = rectangle(&spec)?;
        let t_mesh = t.elapsed().as_secs_f64();
        let bottom = mesh.node_set("bottom")?.to_vec();
        let mut supports = Supports::new();
        supports
            .fix(&bottom, Component::X)
            .fix(&bottom, Component::Y);
        let material = Material::new(1000.0, 0.3, 0.0)?;
        let t = Instant::now();
        let mut model =
            LinearElasticModel::new(mesh, Idealization::PlaneStrain, &[(0, material)], supports)?;
        let t_build = t.elapsed().as_secs_f64();
        model.add_edge_traction("top", |_| [0.1, -1.0])?;
        // Phases of the factorisation, measured again on their own.
        let t = Instant::now();
        let pattern_solver = SpdSolver::new(model.stiffness().symbolic())?;
        let t_sym = t.elapsed().as_secs_f64();
        let mut solver = pattern_solver;
        let t = Instant::now();
        solver.factor(model.stiffness())?;
        let t_num = t.elapsed().as_secs_f64();
        let mut u = vec![0.0; model.dof_count()];
        let t = Instant::now();
        model.free_response_into(1.0, &mut u)?;
        let t_solve = t.elapsed().as_secs_f64();
        println!(
            "| {target} | {} | {} | {t_mesh:.3} | {t_build:.3} | {t_sym:.3} | {t_num:.3} | {t_solve:.3} | {:.3} |",
            model.dof_count(),
            model.nnz(),
            t_build + t_solve
        );
    }
    Ok(())
}
