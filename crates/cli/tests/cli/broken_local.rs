//! Bad reduced problems (issue 15): every file of `tests/broken_local/` is a problem
//! `{"dim", "W", "q", "mu"}` with one mistake, listed in `tests/broken_local/expect.txt` with
//! the fragment of the message `bipo solve-local` must print (`-`: only an error is required;
//! no file uses it since the JSON reader's messages were made specific). For each: exit code
//! 2, the file named, the
//! fragment, no panic; and the same text through `ReducedProblem::from_json` is an `Err`, never
//! a panic. Then bad problems built in code through `ReducedProblem::new`.

use contact_solver::ReducedProblem;
use std::path::Path;
use std::process::Command;

fn manifest() -> Vec<(String, Option<String>)> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/broken_local");
    let text = std::fs::read_to_string(dir.join("expect.txt")).expect("expect.txt exists");
    text.lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| {
            let (file, fragment) = l.split_once('\t').expect("`<file>\\t<fragment>`");
            let fragment = (fragment != "-").then(|| fragment.to_string());
            (file.to_string(), fragment)
        })
        .collect()
}

#[test]
fn every_problem_file_is_listed() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/broken_local");
    let listed: Vec<String> = manifest().into_iter().map(|(f, _)| f).collect();
    let mut files: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|f| f.ends_with(".json"))
        .collect();
    files.sort();
    assert_eq!(files, listed);
    assert!(files.len() >= 40, "{} bad problems", files.len());
}

#[test]
fn bad_reduced_problems_fail_with_their_message() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/broken_local");
    let mut failures = Vec::new();
    for (file, fragment) in manifest() {
        let path = dir.join(&file);
        let out = Command::new(env!("CARGO_BIN_EXE_bipo"))
            .arg("solve-local")
            .arg(&path)
            .output()
            .expect("bipo runs");
        let stderr = String::from_utf8_lossy(&out.stderr);
        let mut problems = Vec::new();
        if out.status.code() != Some(2) {
            problems.push(format!("exit code {:?}, not 2", out.status.code()));
        }
        if stderr.contains("panicked") || stderr.contains("internal error") {
            problems.push("a panic".to_string());
        }
        if !stderr.contains(&file) {
            problems.push("the file is not named".to_string());
        }
        if let Some(f) = &fragment
            && !stderr.contains(f.as_str())
        {
            problems.push(format!("no `{f}`"));
        }
        // the library on the same text: an error (or, for the empty problem, no contact)
        if let Ok(text) = std::fs::read_to_string(&path) {
            match std::panic::catch_unwind(|| ReducedProblem::from_json(&text)) {
                Err(_) => problems.push("ReducedProblem::from_json panicked".to_string()),
                Ok(Ok(p)) if p.contact_count() > 0 => {
                    problems.push("ReducedProblem::from_json accepted it".to_string())
                }
                Ok(_) => {}
            }
        }
        if !problems.is_empty() {
            failures.push(format!(
                "{file}: {}\n  stderr: {}",
                problems.join(", "),
                stderr.trim()
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn a_directory_is_not_a_problem_file() {
    let dir = std::env::temp_dir().join(format!("bipo_local_dir_{}.json", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_bipo"))
        .arg("solve-local")
        .arg(&dir)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("cannot read the problem file"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

#[test]
fn a_byte_order_mark_is_skipped() {
    let dir = std::env::temp_dir().join(format!("bipo_local_bom_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("bom.json");
    std::fs::write(
        &file,
        "\u{feff}{\"W\": [[1, 0], [0, 1]], \"q\": [-1, 0.5], \"mu\": [0.2]}",
    )
    .unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_bipo"))
        .arg("solve-local")
        .arg(&file)
        .output()
        .unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Bad problems built in code: each is an `Err`, never a panic or an `Ok`.
#[test]
fn reduced_problem_new_captures_errors() {
    let ok_w = || vec![2.0, 0.0, 0.0, 2.0];
    // (what, W, q, mu)
    type Case = (&'static str, Vec<f64>, Vec<f64>, Vec<f64>);
    let cases: Vec<Case> = vec![
        ("W too short", vec![1.0], vec![-1.0, 0.5], vec![0.3]),
        ("q odd", ok_w(), vec![-1.0], vec![0.3]),
        ("mu too long", ok_w(), vec![-1.0, 0.5], vec![0.3, 0.3]),
        ("mu empty", ok_w(), vec![-1.0, 0.5], vec![]),
        (
            "NaN in W",
            vec![f64::NAN, 0.0, 0.0, 1.0],
            vec![-1.0, 0.5],
            vec![0.3],
        ),
        ("inf in q", ok_w(), vec![f64::INFINITY, 0.5], vec![0.3]),
        ("NaN mu", ok_w(), vec![-1.0, 0.5], vec![f64::NAN]),
        ("negative mu", ok_w(), vec![-1.0, 0.5], vec![-0.3]),
        (
            "asymmetric",
            vec![2.0, 0.5, 0.0, 2.0],
            vec![-1.0, 0.5],
            vec![0.3],
        ),
        (
            "indefinite",
            vec![1.0, 2.0, 2.0, 1.0],
            vec![-1.0, 0.5],
            vec![0.3],
        ),
        ("zero W", vec![0.0; 4], vec![-1.0, 0.5], vec![0.3]),
        ("W empty, q not", vec![], vec![-1.0, 0.5], vec![0.3]),
    ];
    for (what, w, q, mu) in cases {
        match std::panic::catch_unwind(|| ReducedProblem::new(w, q, mu)) {
            Err(_) => panic!("{what}: ReducedProblem::new panicked"),
            Ok(Ok(_)) => panic!("{what}: ReducedProblem::new accepted it"),
            Ok(Err(_)) => {}
        }
    }
}
