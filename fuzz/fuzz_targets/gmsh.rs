//! Bytes through the Gmsh `.msh` reader (ASCII and binary 4.1): a mesh or a `FemError`, never
//! a panic or an abort.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = fem_core::gmsh::parse_msh(data);
});
