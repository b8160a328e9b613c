//! The seed's tables 5.1 and 5.2 (`examples/delamination.rs`, `examples/shear.rs`,
//! `examples/seed_tables.rs`) and `bipo` solve the same studies (issue 36): the scenes
//! `examples/scenes/{delamination,shear}.toml` run by `bipo` (default settings: the
//! accelerated sweep, Newton on β) and the presets stepped through the library with the
//! examples' settings (`bipo::presets::seed::table_settings`: the seed's fixed point on β
//! around the bipotential Gauss–Seidel sweep, and around the classical RCCM solver) give the
//! same reactions and β at the last step, 21 steps instead of 210 (the same code, a tenth of
//! the time).
//!
//! Tolerance: the fixed point stops on a β change of 1e-8 (`adhesion_tol`) and the reduced
//! solves on a relative residual of 1e-10, so the answers differ by ~1e-9 of the largest
//! reaction (measured 1.4e-9 on the shear, 1.7e-11 on the delamination); 1e-6 leaves room for
//! rounding across machines and fails on any real disagreement (a wrong side of the Coulomb
//! cone, as the classical solver gave on the shear before this issue, moves r_t by 2 μ r_n).

use bipo::presets::seed::table_settings;
use bipo::presets::{DelaminationSpec, Scene, ShearSpec};
use contact_solver::{Algorithm, StepResult};
use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;

const STEPS: usize = 21;

/// Runs `bipo run` on the scene `name` of `examples/scenes/` with `STEPS` steps; the rows of
/// its `contacts.csv` at the last step, by node.
fn scene_last_step(name: &str) -> BTreeMap<usize, BTreeMap<String, f64>> {
    let scenes = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/scenes");
    let dir = std::env::temp_dir().join(format!("bipo_issue_36_{name}_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let text = std::fs::read_to_string(scenes.join(format!("{name}.toml"))).unwrap();
    assert!(
        text.contains("\nsteps = 210"),
        "{name}.toml gives 210 steps"
    );
    let scene = dir.join(format!("{name}.toml"));
    std::fs::write(
        &scene,
        text.replace("\nsteps = 210", &format!("\nsteps = {STEPS}")),
    )
    .unwrap();
    let out = dir.join("out");
    let run = Command::new(env!("CARGO_BIN_EXE_bipo"))
        .arg("run")
        .arg(&scene)
        .arg("-q")
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "bipo run {name}.toml failed: {}",
        String::from_utf8_lossy(&run.stderr)
    );
    let csv = std::fs::read_to_string(out.join("contacts.csv")).unwrap();
    let mut lines = csv.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    let mut rows = BTreeMap::new();
    for line in lines {
        let row: BTreeMap<&str, &str> = head.iter().copied().zip(line.split(',')).collect();
        if row["step"] != STEPS.to_string() {
            continue;
        }
        let values = ["r_n", "r_t", "beta"]
            .iter()
            .map(|&c| (c.to_string(), row[c].parse::<f64>().unwrap()))
            .collect();
        rows.insert(row["node"].parse::<usize>().unwrap(), values);
    }
    let _ = std::fs::remove_dir_all(&dir);
    rows
}

/// The last step of `scene` stepped `STEPS` times.
fn library_last_step(mut scene: Scene) -> StepResult {
    (1..=STEPS).map(|k| scene.step(k).unwrap()).last().unwrap()
}

/// Compares the library's last step with the scene's rows (module doc: tolerance).
fn assert_same(what: &str, lib: &StepResult, scene: &BTreeMap<usize, BTreeMap<String, f64>>) {
    assert_eq!(lib.contacts.len(), scene.len(), "{what}: contacts");
    let scale = lib
        .contacts
        .iter()
        .map(|c| c.r.n.abs().max(c.r.t[0].abs()))
        .fold(0.0, f64::max);
    assert!(scale > 0.0, "{what}: no reaction");
    for c in &lib.contacts {
        let row = &scene[&c.node];
        for (col, v) in [("r_n", c.r.n), ("r_t", c.r.t[0])] {
            assert!(
                (row[col] - v).abs() <= 1e-6 * scale,
                "{what}, node {}: {col} {v} against the scene's {}",
                c.node,
                row[col]
            );
        }
        assert!(
            (row["beta"] - c.beta).abs() <= 1e-6,
            "{what}, node {}: β {} against the scene's {}",
            c.node,
            c.beta,
            row["beta"]
        );
    }
}

#[test]
fn issue_36_shear_examples_agree_with_the_bipo_scene() {
    let scene = scene_last_step("shear");
    let spec = ShearSpec {
        steps: STEPS,
        ..ShearSpec::default()
    };
    for algorithm in [Algorithm::GaussSeidel, Algorithm::ClassicRccm] {
        // the classical solver stopped at step 1 before issue 36 (NotConverged)
        let lib = library_last_step(spec.build(table_settings(algorithm)).unwrap());
        assert_same(&format!("shear, {algorithm:?}"), &lib, &scene);
    }
}

#[test]
fn issue_36_delamination_examples_agree_with_the_bipo_scene() {
    let scene = scene_last_step("delamination");
    let spec = DelaminationSpec {
        steps: STEPS,
        ..DelaminationSpec::default()
    };
    for algorithm in [Algorithm::GaussSeidel, Algorithm::ClassicRccm] {
        let lib = library_last_step(spec.build(table_settings(algorithm)).unwrap());
        assert_same(&format!("delamination, {algorithm:?}"), &lib, &scene);
    }
}
