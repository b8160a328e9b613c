//! A scene file's text through `bipo check`'s parser and validator (values, mesh, model,
//! contact zones). Any input must give `Ok` or an error message: never a panic or an abort.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        // mesh files named by the scene are looked up beside this (missing) file
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scene.toml");
        let _ = bipo::app::check_scene(text, &path);
    }
});
