//! Writes seeded random reduced problems as FCLIB HDF5 files, with our solution in
//! `solution/r` (and `u = W r + q`), for the Siconos check of `docs/validation.md`.
//!
//! ```text
//! cargo run --release -p contact-solver --features fclib --example fclib_export -- [OUT_DIR]
//! /usr/bin/python3 crates/contact-solver/examples/compare_siconos_fclib.py OUT_DIR/random_100.hdf5
//! ```
//! Each file is read back (`read_fclib`) and checked to be the problem written.

use contact_solver::local::fclib::{read_fclib, write_fclib};
use contact_solver::local::generate::random_problem;
use contact_solver::{UzawaSettings, solve_coulomb};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "target/reduced_problems".to_string());
    std::fs::create_dir_all(&out)?;
    for (nc, seed) in [(10, 1), (100, 3), (300, 5)] {
        let p = random_problem(nc, seed);
        let sol = solve_coulomb(&p, &UzawaSettings::default().with_tol(1e-12))?;
        let path = format!("{out}/random_{nc}.hdf5");
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
