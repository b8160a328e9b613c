//! The integration tests of `contact-solver`, one test binary (each module was a test file of
//! its own: one binary instead of 29 saves the link and, at `opt-level = 3` for this package
//! in debug builds, most of the compile time of `cargo test`). Each module keeps its name, its
//! tests and its doc; files that need the FE coupling carry `#![cfg(feature = "fe")]` (or
//! `serde`) as before, and `fclib.rs` (a binary of its own until CI's build time was cut)
//! carries `#![cfg(feature = "fclib")]`.
//!
//! The shared helpers stay in `tests/support/` (examples and benches include them with
//! `#[path]`) and are reached as `crate::support`.

#[path = "../support/mod.rs"]
mod support;

mod active_set;
mod block_on_foundation;
mod classic;
mod coulomb_block;
mod fclib;
mod finiteness;
mod floating_block;
mod floating_glued;
mod floating_two_bodies;
mod fuzz_corpus;
mod gmsh_two_blocks;
mod hertz;
mod hertz_force;
mod hertz_revolved;
mod invalid_input;
mod issue_35_floating_3d;
mod issue_35_generic_zones;
mod issue_35_one_simulation;
mod issue_35_penetration;
mod issue_35_time_scheme;
mod issue_36_traps;
mod issue_37_asymmetric;
mod issue_37_auto_multibody;
mod issue_37_auto_rule;
mod issue_37_fclib_wild;
mod issue_37_rank_deficient;
mod issue_37_semidefinite;
mod issue_37_siconos_dat;
mod issue_37_small;
mod issue_37_spheres_box;
mod issue_38_matrix_free_anderson;
mod issue_38_matrix_free_default;
mod issue_38_one_factor;
mod issue_38_pad;
mod issue_39_adhesion;
mod issue_39_contactors;
mod issue_39_dynamics;
mod issue_39_hertz_impact;
mod issue_39_incline;
mod issue_39_integrator;
mod issue_39_sliding_block;
mod issue_40_newton_chain;
mod issue_40_newton_elastic;
mod issue_40_newton_paths;
mod issue_40_newton_plastic;
mod issue_40_pile_plastic;
mod issue_40_plastic_limit;
mod issue_40_prescribed_cut;
mod local_algorithms;
mod matrix_free;
mod multibody_3d;
mod output;
mod random_spd;
mod rccm_opening;
mod real_world_inputs;
mod reduced_3d;
mod renumbering;
mod rigid_targets;
mod signorini_block;
mod single_contact;
mod skip_open;
mod skip_rules;
mod solid_active_set;
mod solid_contact;
mod solid_interfaces;
mod sparse;
mod stall;
mod stress;
mod stress_active_set;
mod two_bodies;
mod two_cylinders;
