//! Writes seeded random reduced problems as FCLIB HDF5 files, with our solution in
//! `solution/r` (and `u = W r + q`), for the Siconos check of `docs/validation.md`.
//!
//! ```text
//! cargo run --release -p contact-solver --features fclib --example fclib_export -- [OUT_DIR]
//! /usr/bin/python3 crates/contact-solver/examples/compare_siconos_fclib.py OUT_DIR/random_100.hdf5
//! /usr/bin/python3 crates/contact-solver/examples/compare_siconos_fclib.py OUT_DIR/random_3d_100.hdf5
//! ```
//! 2D files are `random_<n_c>.hdf5`, 3D files (`spacedim` 3) `random_3d_<n_c>.hdf5`.
//! Each file is read back (`read_fclib`) and checked to be the problem written.

use contact_solver::local::fclib::{read_fclib, write_fclib};
use contact_solver::local::generate::random_problem_in;
use contact_solver::{UzawaSettings, solve_coulomb};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "target/reduced_problems".to_string());
    std::fs::create_dir_all(&out)?;
    let cases = [
        (2, 10, 1),
        (2, 100, 3),
        (2, 300, 5),
        (3, 10, 1),
        (3, 100, 3),
        (3, 300, 5),
    ];
    for (dim, nc, seed) in cases {
        let p = random_problem_in(dim, nc, seed);
        let sol = solve_coulomb(&p, &UzawaSettings::default().with_tol(1e-12))?;
        let tag = if dim == 3 { "3d_" } else { "" };
        let path = format!("{out}/random_{tag}{nc}.hdf5");
        write_fclib(&path, &p, Some(&sol.r))?;
        assert_eq!(
            read_fclib(&path)?.problem,
            p,
            "the file reads back as written"
        );
        println!(
            "{path}: n_c = {nc}, {:?}, {} iterations, residual {:.1e}",
            sol.report.algorithm, sol.report.iterations, sol.report.residual
        );
    }
    Ok(())
}
