//! The broken-scene corpus: every file of `tests/broken/` is a scene with one mistake. Its first
//! line `# expect: <fragment>` gives a fragment of the message `bipo` must print; an optional
//! second line `# command: run` runs the scene instead of checking it (errors that only a solve
//! finds). For each file: a non-zero exit, the fragment on stderr, the file's name in the
//! message, and never a panic or an internal error.

use std::path::{Path, PathBuf};
use std::process::Command;

fn corpus() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/broken");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("tests/broken exists")
        .map(|e| e.expect("readable entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    files
}

#[test]
fn broken_scenes_fail_with_their_message() {
    let files = corpus();
    assert!(
        files.len() >= 40,
        "the corpus has {} scenes, expected at least 40",
        files.len()
    );
    let out_dir = std::env::temp_dir().join(format!("bipo_broken_{}", std::process::id()));
    let mut failures = Vec::new();
    for file in &files {
        let text = std::fs::read_to_string(file).expect("readable scene");
        let mut lines = text.lines();
        let expect = lines
            .next()
            .and_then(|l| l.strip_prefix("# expect: "))
            .unwrap_or_else(|| panic!("{}: first line must be `# expect: ...`", file.display()));
        let run = lines.next() == Some("# command: run");
        let mut cmd = Command::new(env!("CARGO_BIN_EXE_bipo"));
        if run {
            cmd.arg("run")
                .arg(file)
                .arg("--quiet")
                .arg("--out")
                .arg(&out_dir);
        } else {
            cmd.arg("check").arg(file);
        }
        let out = cmd.output().expect("bipo runs");
        let stderr = String::from_utf8_lossy(&out.stderr);
        let name = file.file_name().unwrap().to_string_lossy();
        let mut problems = Vec::new();
        if out.status.success() {
            problems.push("exit code 0".to_string());
        }
        if out.status.code() == Some(101)
            || stderr.contains("panicked")
            || stderr.contains("internal error")
        {
            problems.push("a panic".to_string());
        }
        if stderr.contains("RUST_BACKTRACE") || stderr.contains("stack backtrace") {
            problems.push("a backtrace".to_string());
        }
        if !stderr.contains(expect) {
            problems.push(format!("no `{expect}`"));
        }
        if !run && !stderr.contains(name.as_ref()) {
            problems.push("the file is not named".to_string());
        }
        if !problems.is_empty() {
            failures.push(format!(
                "{name}: {}\n  stderr: {}",
                problems.join(", "),
                stderr.trim()
            ));
        }
    }
    let _ = std::fs::remove_dir_all(&out_dir);
    assert!(
        failures.is_empty(),
        "{} of {} broken scenes misbehave:\n{}",
        failures.len(),
        files.len(),
        failures.join("\n")
    );
}

#[test]
fn toml_errors_give_line_and_column() {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/broken/wrong_type.toml");
    let out = Command::new(env!("CARGO_BIN_EXE_bipo"))
        .arg("check")
        .arg(&file)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    // `nx = "two"` is line 8 (the `# expect` line is line 1), its value at column 6
    assert!(
        stderr.contains("wrong_type.toml:8:6: `mesh.nx`: invalid type: string \"two\""),
        "{stderr}"
    );
    assert!(
        stderr.contains("nx = \"two\""),
        "the source line is quoted: {stderr}"
    );
}

#[test]
fn a_missing_scene_file_is_named() {
    let out = Command::new(env!("CARGO_BIN_EXE_bipo"))
        .args(["run", "no/such/scene.toml"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr.contains("no/such/scene.toml: cannot read the scene file"),
        "{stderr}"
    );
}

#[test]
fn a_malformed_reduced_problem_is_an_error() {
    let dir = std::env::temp_dir().join(format!("bipo_local_bad_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("bad.json");
    std::fs::write(
        &file,
        r#"{"dim": 2, "W": [1, 0, 0], "q": [-1, 0.5], "mu": [0.2]}"#,
    )
    .unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_bipo"))
        .arg("solve-local")
        .arg(&file)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        stderr.contains("bad.json")
            && stderr.contains("W given as a flat list has 3 numbers: expected m² = 4"),
        "{stderr}"
    );
    assert!(!stderr.contains("panicked"));
    let _ = std::fs::remove_dir_all(&dir);
}
