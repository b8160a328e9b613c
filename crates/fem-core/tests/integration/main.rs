//! The integration tests of `fem-core`, one test binary (each module was a test file of its own:
//! one binary instead of 7 saves the links and, at `opt-level = 3` for this package in debug
//! builds, compile time of `cargo test`). Each module keeps its name, its tests and its doc; the
//! shared mesh helpers stay in `tests/common/` and are reached as `crate::common`.

#[path = "../common/mod.rs"]
mod common;

mod boundary_mass;
mod convergence;
mod exact_solutions;
mod fuzz_corpus;
mod gmsh_curves;
mod hostile_input;
mod issue_35_capabilities;
mod issue_35_one_element_kind;
mod issue_40_footing_non_associated;
mod issue_40_hill_cylinder;
mod issue_40_strip_footing;
mod mesh_io;
mod patch;
mod quad_hex;
mod quad_hex_io;
mod quad_hex_rates;
mod revolve;
mod solid;
mod solid_io;
mod structure_paths;
