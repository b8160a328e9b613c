//! Replays the Gmsh fuzz corpus (`fuzz/corpus/gmsh`, grown by `fuzz/run.sh`; the crashes it
//! found are in it) through `parse_msh` and `solid::gmsh::parse_msh_3d` on the stable toolchain: every input must give a mesh
//! or a `FemError`. A panic fails the test; there is no tolerance.

use std::path::Path;

#[test]
fn every_gmsh_corpus_input_gives_a_mesh_or_an_error() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fuzz/corpus/gmsh");
    let mut count = 0;
    for entry in std::fs::read_dir(&dir).expect("fuzz/corpus/gmsh exists") {
        let path = entry.unwrap().path();
        let bytes = std::fs::read(&path).unwrap();
        // an Err is the expected answer to most of the corpus; only a panic is a failure
        std::panic::catch_unwind(|| fem_core::gmsh::parse_msh(&bytes).map(|_| ()))
            .unwrap_or_else(|_| panic!("{} panicked", path.display()))
            .ok();
        std::panic::catch_unwind(|| fem_core::solid::gmsh::parse_msh_3d(&bytes).map(|_| ()))
            .unwrap_or_else(|_| panic!("{} panicked in the 3D reader", path.display()))
            .ok();
        count += 1;
    }
    assert!(count >= 10, "only {count} inputs in {}", dir.display());
}
