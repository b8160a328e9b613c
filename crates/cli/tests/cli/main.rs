//! The integration tests of `bipo` (the CLI and its presets), one test binary (each module was a
//! test file of its own; one binary links once). Each module keeps its name, its tests and its
//! doc; the scene files stay in `tests/broken/`, `tests/broken_local/` and `tests/scenes/`.

mod broken;
mod broken_local;
mod cli;
mod delamination;
mod fuzz_corpus;
mod gmsh_2d;
mod issue_35_one_run;
mod issue_36_outputs;
mod issue_36_traps;
mod issue_37_siconos_dat;
mod issue_37_write_best;
mod issue_38_path;
mod issue_39_scenes;
mod issue_40_pile_3d;
mod issue_40_pile_dp;
mod issue_40_scenes;
mod local_algorithms_scenes;
mod pile;
mod pile_3d;
mod pressure;
mod seed_studies;
mod seed_tables;
mod solid;
mod support;
