//! Replays the scene fuzz corpus (`fuzz/corpus/scene`: the example scenes, the broken-scene
//! corpus and what `fuzz/run.sh` added) through `bipo::app::check_scene`, the function the
//! fuzz target calls, on the stable toolchain. Every input must give `Ok` or a message that
//! names a key or the file (an error of `bipo check`); a panic fails the test.

use std::path::Path;

#[test]
fn every_scene_corpus_input_is_checked_or_refused_with_a_message() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fuzz/corpus/scene");
    let scene_path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fuzz/scene.toml");
    let (mut count, mut valid) = (0, 0);
    for entry in std::fs::read_dir(&dir).expect("fuzz/corpus/scene exists") {
        let path = entry.unwrap().path();
        let bytes = std::fs::read(&path).unwrap();
        let Ok(text) = std::str::from_utf8(&bytes) else {
            continue;
        };
        count += 1;
        let checked = std::panic::catch_unwind(|| bipo::app::check_scene(text, &scene_path))
            .unwrap_or_else(|_| panic!("{} panicked", path.display()));
        match checked {
            Ok(_) => valid += 1,
            Err(message) => assert!(!message.trim().is_empty(), "{}", path.display()),
        }
    }
    assert!(count >= 100, "only {count} inputs in {}", dir.display());
    eprintln!("{count} scenes, {valid} valid");
}
