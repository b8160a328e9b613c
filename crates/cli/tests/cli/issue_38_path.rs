//! Issue 38, "say which path": every run reports the path of its last step and why — the
//! settings' choice or `auto`'s rule with its numbers — in `summary.json` (`path`,
//! `path_reason`) and in its last lines, in 2D and in 3D.

use crate::support::{bipo, manifest, scenes, summary, tmp};
use std::ffi::OsStr;
use std::path::Path;

/// Runs `scene` into a fresh directory; its summary and standard output.
fn run(scene: &Path, name: &str) -> (serde_json::Value, String) {
    let dir = tmp(name);
    let out = bipo(&[
        OsStr::new("run"),
        scene.as_os_str(),
        OsStr::new("--out"),
        dir.as_os_str(),
        OsStr::new("--quiet"),
    ]);
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        out.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let s = summary(&dir);
    let _ = std::fs::remove_dir_all(&dir);
    (s, stdout)
}

#[test]
fn issue_38_report_names_the_path_and_why() {
    // 2D: 9 candidates of the block, auto within its dense limit (500)
    let (s, stdout) = run(&scenes().join("block.toml"), "issue_38_block");
    assert_eq!(s["path"], "dense");
    assert_eq!(
        s["path_reason"],
        "auto: 9 active contacts ≤ dense limit 500"
    );
    assert!(
        stdout.contains("path of the last step: dense (auto: 9 active contacts ≤ dense limit 500)"),
        "{stdout}"
    );
    // 3D: the Signorini patch under auto (25 candidates, dense limit 3000) ...
    let patch = manifest("tests/solid/patch_box.toml");
    let (s, stdout) = run(&patch, "issue_38_patch");
    assert_eq!(s["path"], "dense");
    assert_eq!(
        s["path_reason"],
        "auto: 25 active contacts ≤ dense limit 3000"
    );
    assert!(
        stdout.contains("path of the last step: dense (auto:"),
        "{stdout}"
    );
    // ... and past a dense limit of 10: the active set, and why
    let text = std::fs::read_to_string(&patch)
        .unwrap()
        .replace("[solver]\n", "[solver]\ndense_limit = 10\n");
    let dir = tmp("issue_38_patch_limit");
    let scene = dir.join("patch_limit.toml");
    std::fs::write(&scene, text).unwrap();
    let (s, stdout) = run(&scene, "issue_38_patch_limit_out");
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(s["path"], "active set");
    assert_eq!(
        s["path_reason"],
        "auto: 25 active contacts > dense limit 10"
    );
    assert!(
        stdout.contains(
            "path of the last step: active set (auto: 25 active contacts > dense limit 10)"
        ),
        "{stdout}"
    );
}
