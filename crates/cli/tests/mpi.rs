//! `mpirun -n N bipo run scene.toml` (issue 41), spawned from the test (feature `petsc`; CI runs
//! it in its PETSc step, `crates/cli/tests/mpi.sh`).
//!
//! - **The serial answer.** `tests/mpi/block.toml` (a P2 block pressed on a rigid plane with
//!   Coulomb friction, then sheared until its contacts slide) on 1 and 2 ranks gives the
//!   numbers of `bipo run` of the same scene without `linear_solver` (the direct Cholesky path)
//!   to 1e-8 relative: every value of `steps.csv` and `contacts.csv`, each compared with the
//!   largest value of its kind (forces, displacements), except the wall times and the iteration
//!   counters (CG stops at a residual of 1e-12 relative; the contact solver's residual is its
//!   own rounding). The same for `tests/mpi/axi.toml` (2D: an axisymmetric P2 cylinder under
//!   self-weight on an RCCM floor, pressed then lifted until the adhesion is damaged). The outputs are written once (no file of another rank beside rank 0's), the
//!   mesh series as parallel pieces: `mesh.pvd` → `mesh_NNNN.pvtu` → one `.vtu` per rank.
//! - **Refusals.** A scene that does not ask for PETSc, run on 2 ranks, is refused at
//!   `analysis.linear_solver`, printed once; a floating 2D body that asks for it, at
//!   `analysis.floating`.
//! - **A failing run ends every rank** (CG limited to one iteration: PETSc's solver does not
//!   converge) with its message, not a hang.

#![cfg(feature = "petsc")]

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::Duration;

fn bipo() -> &'static str {
    env!("CARGO_BIN_EXE_bipo")
}

fn scene() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/mpi/block.toml")
}

fn axi_scene() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/mpi/axi.toml")
}

fn temp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("bipo_mpi_{}_{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `mpirun -n ranks bipo args`, killed after `limit`; `None` when it did not end.
fn mpirun(ranks: usize, args: &[&str], limit: Duration) -> Option<Output> {
    let mut cmd = Command::new("timeout");
    cmd.arg(limit.as_secs().to_string()).args([
        "mpirun",
        "--oversubscribe",
        "--mca",
        "mpi_yield_when_idle",
        "1",
    ]);
    let root = Command::new("id")
        .arg("-u")
        .output()
        .is_ok_and(|o| o.stdout.starts_with(b"0\n"));
    if root {
        cmd.arg("--allow-run-as-root");
    }
    cmd.env("OMPI_MCA_btl_vader_single_copy_mechanism", "none")
        .args(["-n", &ranks.to_string(), bipo()])
        .args(args);
    let out = cmd
        .output()
        .expect("mpirun runs (libopenmpi-dev installs it)");
    (out.status.code() != Some(124)).then_some(out)
}

fn text(o: &Output) -> String {
    format!(
        "{}\n{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

/// A CSV file as its header and rows of fields.
fn csv(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let body = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = body.lines();
    let head = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .map(|l| l.split(',').map(String::from).collect())
        .collect();
    (head, rows)
}

/// The kind a column's values are compared within (its scale: the largest of the kind).
fn kind(column: &str) -> Option<&str> {
    const SKIPPED: [&str; 5] = [
        "wall_time_s",
        "residual",
        "contact_iterations",
        "passes",
        "adhesion_iterations",
    ];
    if SKIPPED.contains(&column) {
        return None;
    }
    for (prefix, kind) in [
        ("r_", "force"),
        ("f_", "force"),
        ("force", "force"),
        ("reaction", "force"),
        ("gap", "length"),
        ("slip", "length"),
    ] {
        if column.starts_with(prefix) {
            return Some(kind);
        }
    }
    Some(column)
}

/// The largest difference of `a` and `b` (same header, same rows) relative to the largest
/// value of each kind in `a`; text fields must be equal.
fn difference(a: &Path, b: &Path) -> f64 {
    let ((ha, ra), (hb, rb)) = (csv(a), csv(b));
    assert_eq!(ha, hb, "{}: the columns", b.display());
    assert_eq!(ra.len(), rb.len(), "{}: the rows", b.display());
    let mut scale: BTreeMap<&str, f64> = BTreeMap::new();
    for row in &ra {
        for (c, v) in ha.iter().zip(row) {
            if let (Some(k), Ok(x)) = (kind(c), v.parse::<f64>()) {
                let s = scale.entry(k).or_insert(0.0);
                *s = s.max(x.abs());
            }
        }
    }
    let mut worst: f64 = 0.0;
    for (row_a, row_b) in ra.iter().zip(&rb) {
        for ((c, x), y) in ha.iter().zip(row_a).zip(row_b) {
            let Some(k) = kind(c) else { continue };
            match (x.parse::<f64>(), y.parse::<f64>()) {
                (Ok(x), Ok(y)) => {
                    let s = scale[k];
                    if s > 0.0 {
                        worst = worst.max((x - y).abs() / s);
                    } else {
                        assert_eq!(x, y, "{c}");
                    }
                }
                _ => assert_eq!(x, y, "{}: column {c}", b.display()),
            }
        }
    }
    worst
}

#[test]
fn issue_41_block_on_one_and_two_ranks_gives_the_serial_answer() {
    same_as_serial(&scene(), "block");
}

/// The 2D path: an axisymmetric cylinder under self-weight on an RCCM floor, pressed then
/// lifted until the adhesion is damaged (`tests/mpi/axi.toml`).
#[test]
fn issue_41_axisymmetric_rccm_on_one_and_two_ranks_gives_the_serial_answer() {
    same_as_serial(&axi_scene(), "axi");
}

/// `scene` (which asks for PETSc, CG at 1e-12) on 1 and 2 ranks against `bipo run` of the same
/// scene without the PETSc keys: the CSV files to 1e-8 relative, the files written once, the
/// mesh series as parallel pieces.
fn same_as_serial(scene: &Path, name: &str) {
    let dir = temp(name);
    // the serial scene: the same file without the PETSc keys
    let source = std::fs::read_to_string(scene).unwrap();
    let serial_scene = dir.join("serial.toml");
    let serial_text: String = source
        .lines()
        .filter(|l| {
            !(l.starts_with("linear_solver")
                || l.starts_with("[analysis.petsc]")
                || l.starts_with("method")
                || l.starts_with("rtol"))
        })
        .map(|l| format!("{l}\n"))
        .collect();
    std::fs::write(&serial_scene, serial_text).unwrap();
    let serial = dir.join("serial");
    let out = Command::new(bipo())
        .args(["run", "--quiet", "--out"])
        .arg(&serial)
        .arg(&serial_scene)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", text(&out));
    for ranks in [1, 2] {
        let run = dir.join(format!("ranks{ranks}"));
        let args = [
            "run",
            "--quiet",
            "--out",
            run.to_str().unwrap(),
            scene.to_str().unwrap(),
        ];
        let out = mpirun(ranks, &args, Duration::from_secs(300)).expect("mpirun ended");
        assert!(out.status.success(), "{ranks} ranks: {}", text(&out));
        let stdout = String::from_utf8_lossy(&out.stdout);
        // rank 0 prints, once
        assert_eq!(
            stdout.matches("distributed: PETSc on").count(),
            1,
            "{stdout}"
        );
        for file in ["steps.csv", "contacts.csv"] {
            let d = difference(&serial.join(file), &run.join(file));
            eprintln!("{name}, {ranks} rank(s), {file}: {d:.1e} relative to the serial run");
            // CG's residual 1e-12 relative, κ(K) ≲ 1e4: ~1e-9 at worst; the issue's bar 1e-8
            assert!(d <= 1e-8, "{ranks} ranks, {file}: {d:e} relative");
        }
        // the mesh series as parallel pieces; every other file as the serial run's
        let mut files: Vec<String> = std::fs::read_dir(&run)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        files.sort();
        let mut serial_files: Vec<String> = Vec::new();
        for f in std::fs::read_dir(&serial).unwrap() {
            let f = f.unwrap().file_name().to_string_lossy().into_owned();
            match f.strip_suffix(".vtu").filter(|s| s.starts_with("mesh_")) {
                // mesh_NNNN.vtu → mesh_NNNN.pvtu and one piece per rank
                Some(stem) => {
                    serial_files.push(format!("{stem}.pvtu"));
                    (0..ranks).for_each(|r| serial_files.push(format!("{stem}_{r}.vtu")));
                }
                None => serial_files.push(f),
            }
        }
        serial_files.sort();
        assert_eq!(files, serial_files, "{ranks} ranks");
        let pvd = std::fs::read_to_string(run.join("mesh.pvd")).unwrap();
        assert!(pvd.contains("file=\"mesh_0001.pvtu\""), "{pvd}");
        let pvtu = std::fs::read_to_string(run.join("mesh_0001.pvtu")).unwrap();
        assert_eq!(pvtu.matches("<Piece Source=").count(), ranks, "{pvtu}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn issue_41_refusals_name_the_key_once() {
    let dir = temp("refusals");
    // a serial scene on 2 ranks
    let serial = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/solid/phases.toml");
    let out_dir = dir.join("out");
    let args = [
        "run",
        "--quiet",
        "--out",
        out_dir.to_str().unwrap(),
        serial.to_str().unwrap(),
    ];
    let out = mpirun(2, &args, Duration::from_secs(120)).expect("mpirun ended");
    let all = text(&out);
    assert!(!out.status.success(), "{all}");
    assert!(
        all.contains("`analysis.linear_solver`: bipo runs under MPI on 2 ranks"),
        "{all}"
    );
    assert_eq!(all.matches("error:").count(), 1, "printed once: {all}");
    // a body that only contact holds (2D, `floating`): PETSc's K has no pinned modes
    let floating = dir.join("floating.toml");
    let source = std::fs::read_to_string(axi_scene())
        .unwrap()
        .replace(
            "type = \"axisymmetric\"\n",
            "type = \"axisymmetric\"\nfloating = true\n",
        )
        .replace(
            "[[supports]]\nset = \"top\"\ncomponent = \"y\"\nvalue = -0.01\nfunction = \"path\"\n",
            "",
        );
    assert!(
        !source.contains("set = \"top\""),
        "the top's support removed"
    );
    std::fs::write(&floating, source).unwrap();
    let out = Command::new(bipo())
        .args(["run", "--quiet", "--out"])
        .arg(&out_dir)
        .arg(&floating)
        .output()
        .unwrap();
    let all = text(&out);
    assert_eq!(out.status.code(), Some(2), "{all}");
    assert!(
        all.contains("`analysis.floating`: a body that only contact holds is not run distributed"),
        "{all}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn issue_41_a_failing_run_ends_every_rank() {
    let dir = temp("fail");
    let source = std::fs::read_to_string(scene())
        .unwrap()
        .replace("rtol = 1e-12", "rtol = 1e-12\nmax_iterations = 1");
    let failing = dir.join("failing.toml");
    std::fs::write(&failing, source).unwrap();
    let out_dir = dir.join("out");
    let args = [
        "run",
        "--quiet",
        "--out",
        out_dir.to_str().unwrap(),
        failing.to_str().unwrap(),
    ];
    let out = mpirun(2, &args, Duration::from_secs(120)).expect("no hang: mpirun ended");
    let all = text(&out);
    assert!(!out.status.success(), "{all}");
    assert!(all.contains("did not converge"), "{all}");
    std::fs::remove_dir_all(&dir).unwrap();
}
