//! Issue 37, "a best-effort answer": `bipo solve-local --write-best` prints the best iterate of
//! a solve that does not reach its tolerance, flagged `"converged": false` with its residual,
//! and still fails (exit status 1); without the flag nothing is printed on standard output.

use std::process::Command;

#[test]
fn issue_37_write_best_prints_the_best_iterate_and_fails() {
    let dir = std::env::temp_dir().join(format!("bipo_write_best_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("coupled.json");
    // two coupled contacts, both pressed: one sweep does not solve it
    std::fs::write(
        &file,
        r#"{"W": [[2, 0, 1, 0], [0, 2, 0, 0.5], [1, 0, 2, 0], [0, 0.5, 0, 2]],
            "q": [-1, 0.5, -1, -0.3], "mu": [0.3, 0.3]}"#,
    )
    .unwrap();
    let run = |extra: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_bipo"))
            .args([
                "solve-local",
                "--algorithm",
                "gauss-seidel",
                "--max-iterations",
                "1",
            ])
            .args(extra)
            .arg(&file)
            .output()
            .unwrap()
    };
    let out = run(&["--write-best"]);
    let without = run(&[]);
    let _ = std::fs::remove_dir_all(&dir);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("did not converge"), "{stderr}");
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON on stdout");
    assert_eq!(v["converged"], false);
    assert_eq!(v["r"].as_array().unwrap().len(), 4);
    assert_eq!(v["x"].as_array().unwrap().len(), 4);
    let residual = v["residual"].as_f64().unwrap();
    assert!(residual.is_finite() && residual > 1e-10, "{residual}");
    assert_eq!(without.status.code(), Some(1));
    assert!(without.stdout.is_empty());
}
