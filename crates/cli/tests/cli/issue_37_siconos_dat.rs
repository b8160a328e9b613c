//! Issue 37: `bipo solve-local` reads Siconos' `.dat` problems (by extension, or by content: a
//! text that starts with a number), local and global; a bad one is exit status 2 with the file
//! and the line named.

use std::path::PathBuf;
use std::process::Command;

fn siconos(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../contact-solver/tests/data/siconos")
        .join(name)
}

fn solve(path: &std::path::Path) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_bipo"))
        .args(["solve-local", "--json"])
        .arg(path)
        .output()
        .unwrap()
}

#[test]
fn issue_37_solve_local_reads_dat_files() {
    for name in [
        "dense_2d.dat",
        "dense_3d.dat",
        "blocks_3d.dat",
        "global_3d.dat",
    ] {
        let out = solve(&siconos(name));
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(0), "{name}: {stderr}");
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON on stdout");
        assert_eq!(v["converged"], true, "{name}");
    }
}

#[test]
fn issue_37_solve_local_names_the_file_and_line_of_a_bad_dat() {
    let dir = std::env::temp_dir().join(format!("bipo_dat_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let text = std::fs::read_to_string(siconos("dense_2d.dat")).unwrap();
    // no extension: recognised by its content
    let file = dir.join("problem");
    std::fs::write(
        &file,
        text.replacen("2.000000000000000000000000e+00", "nan", 1),
    )
    .unwrap();
    let out = solve(&file);
    let _ = std::fs::remove_dir_all(&dir);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("problem") && stderr.contains("line 7"),
        "{stderr}"
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
}
