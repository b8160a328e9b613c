//! With the `petsc` feature: finds the system PETSc through pkg-config (module `PETSc`),
//! checks its version and its index width, and links it and MPI. Without the feature: nothing
//! (the crate is then pure Rust).

use std::process::Command;

const PACKAGES: &str = "install the Debian packages `libpetsc-real-dev` (PETSc 3.18) and \
                        `libopenmpi-dev` (MPI): `apt-get install libpetsc-real-dev libopenmpi-dev`";

fn pkg_config(args: &[&str]) -> Option<String> {
    let out = Command::new("pkg-config").args(args).output().ok()?;
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).trim().to_string())
}

fn main() {
    println!("cargo::rustc-check-cfg=cfg(petsc_int64)");
    println!("cargo::rerun-if-changed=build.rs");
    println!("cargo::rerun-if-env-changed=PKG_CONFIG_PATH");
    if std::env::var_os("CARGO_FEATURE_PETSC").is_none() {
        return;
    }
    let Some(version) = pkg_config(&["--modversion", "PETSc"]) else {
        panic!(
            "bipotential-petsc (feature `petsc`): pkg-config finds no `PETSc` module; {PACKAGES}"
        );
    };
    let mut parts = version.split('.').map(|p| p.parse::<u32>().unwrap_or(0));
    let (major, minor) = (parts.next().unwrap_or(0), parts.next().unwrap_or(0));
    // the functions bound in src/ffi.rs keep these signatures from 3.18 through 3.2x
    if major != 3 || minor < 18 {
        panic!("bipotential-petsc: PETSc {version} found, 3.18 or newer 3.x needed; {PACKAGES}");
    }
    let include = pkg_config(&["--variable=includedir", "PETSc"]).unwrap_or_default();
    let conf = std::fs::read_to_string(format!("{include}/petscconf.h")).unwrap_or_default();
    if conf.contains("#define PETSC_USE_64BIT_INDICES 1") {
        println!("cargo::rustc-cfg=petsc_int64");
    }
    if conf.contains("PETSC_USE_COMPLEX 1") || !conf.contains("PETSC_USE_REAL_DOUBLE 1") {
        panic!(
            "bipotential-petsc: PETSc {version} is not built with real double scalars; {PACKAGES}"
        );
    }
    let libs = pkg_config(&["--libs", "PETSc"]).unwrap_or_default();
    for flag in libs.split_whitespace() {
        if let Some(dir) = flag.strip_prefix("-L") {
            println!("cargo::rustc-link-search=native={dir}");
            // the tests and examples run without LD_LIBRARY_PATH
            println!("cargo::rustc-link-arg=-Wl,-rpath,{dir}");
        } else if let Some(lib) = flag.strip_prefix("-l") {
            println!("cargo::rustc-link-lib={lib}");
        }
    }
    // MPI_Comm_rank, MPI_Comm_size and MPI_Abort are called directly: link libmpi itself
    let Some(mpi) = pkg_config(&["--libs", "mpi"]).or_else(|| pkg_config(&["--libs", "ompi-c"]))
    else {
        panic!("bipotential-petsc (feature `petsc`): pkg-config finds no `mpi` module; {PACKAGES}");
    };
    for flag in mpi.split_whitespace() {
        if let Some(dir) = flag.strip_prefix("-L") {
            println!("cargo::rustc-link-search=native={dir}");
        } else if let Some(lib) = flag.strip_prefix("-l") {
            println!("cargo::rustc-link-lib={lib}");
        }
    }
}
