//! Time, fill and size of fem-core's 3D pipeline on P2 (or P1) tetrahedral cubes: mesh
//! generation, model build (pattern + assembly + symbolic analysis with faer's AMD ordering +
//! numeric Cholesky), one numeric refactorisation alone, and one solve, for a list of target
//! DOF counts (default 1e4, 1e5, 3e5).
//!
//! Run: `cargo run --release --example solid_scaling -- p2 10000 100000 300000` (`BIPO_QUICK=1`
//! and no sizes: 3000 DOF).
//! Peak memory, one size per process: `/usr/bin/time -v target/release/examples/solid_scaling p2 300000`.
//! The first argument is `p1`/`p2` (nested dissection, the default) or `p1-amd`/`p2-amd`
//! (faer's AMD ordering).

use bipotential::fem_core::ordering::FillOrdering;
use bipotential::fem_core::solid::generate::{box_mesh, lines};
use bipotential::fem_core::solid::{SolidKind, SolidModel};
use bipotential::fem_core::{Component, Material, Structure, Supports};
use std::error::Error;
use std::time::Instant;

fn main() -> Result<(), Box<dyn Error>> {
    let mut args = std::env::args().skip(1).peekable();
    let mode = args.next().unwrap_or_else(|| "p2".into());
    let targets: Vec<usize> = args.map(|a| a.parse()).collect::<Result<_, _>>()?;
    let targets = if targets.is_empty() && std::env::var_os("BIPO_QUICK").is_some_and(|v| v != "0")
    {
        vec![3_000]
    } else if targets.is_empty() {
        vec![10_000, 100_000, 300_000]
    } else {
        targets
    };
    let ordering = if mode.ends_with("amd") {
        FillOrdering::Amd
    } else {
        FillOrdering::NestedDissection
    };
    let kind = if mode.starts_with("p1") {
        SolidKind::Tet4
    } else {
        SolidKind::Tet10
    };
    println!(
        "| target DOF | free DOF | nnz(lower K) | nnz(L) | fill nnz(L)/nnz(K) | mesh (s) | build (s) | numeric (s) | solve (s) | build + solve (s) |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for target in targets {
        // P2 cube with n³ cells has (2n + 1)³ nodes; P1 (n + 1)³
        let per_side = (target as f64 / 3.0).cbrt();
        let n = match kind {
            SolidKind::Tet4 => (per_side - 1.0).round().max(1.0) as usize,
            _ => ((per_side - 1.0) / 2.0).round().max(1.0) as usize,
        };
        let t = Instant::now();
        let g = lines(0.0, 1.0, n);
        let mesh = box_mesh(&g, &g, &g, kind)?;
        let t_mesh = t.elapsed().as_secs_f64();
        let bottom = mesh.node_set("z0")?.to_vec();
        let mut supports = Supports::new();
        for c in Component::all::<3>() {
            supports.fix(&bottom, c);
        }
        let material = Material::new(1000.0, 0.3, 0.0)?;
        let t = Instant::now();
        let mut model = SolidModel::with_ordering(mesh, &[(0, material)], supports, ordering)?;
        let t_build = t.elapsed().as_secs_f64();
        let nnz_l = model.factor_nnz();
        model.add_face_traction("z1", |_, _| [0.1, 0.0, -1.0])?;
        // one numeric refactorisation alone (what a new stiffness costs)
        let t = Instant::now();
        model.refactor()?;
        let t_num = t.elapsed().as_secs_f64();
        let mut u = vec![0.0; model.dof_count()];
        let t = Instant::now();
        model.free_response_into(1.0, &mut u)?;
        let t_solve = t.elapsed().as_secs_f64();
        println!(
            "| {target} | {} | {} | {nnz_l} | {:.1} | {t_mesh:.3} | {t_build:.3} | {t_num:.3} | {t_solve:.3} | {:.3} |",
            model.dof_count(),
            model.nnz(),
            nnz_l as f64 / model.nnz() as f64,
            t_build + t_solve
        );
    }
    Ok(())
}
