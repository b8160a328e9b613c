//! One `bipo run` for 2D and 3D scenes (issue 35): the study, the driver, the recorder and the
//! summary are written once over the dimension, and each dimension's `summary.json` keeps the
//! keys, in the order, that it had when the two runs were separate (the file is a contract:
//! scripts read it). A 2D scene (examples/scenes/block.toml) and a 3D one
//! (tests/solid/patch_box.toml) go through the same generic run; a 3D scene that would write
//! too many files is refused by the check 2D scenes have (tests/broken/solid_huge_files.toml).

use super::support::{bipo, manifest, scenes, tmp};
use std::path::Path;

/// The keys of the JSON object that opens after the first line containing `after` (the whole
/// file: `None`), at `indent` spaces, in the order of the pretty-printed file.
fn keys(text: &str, after: Option<&str>, indent: usize) -> Vec<String> {
    let mut lines = text.lines();
    if let Some(a) = after {
        lines
            .find(|l| l.contains(a))
            .expect("the key is in the file");
    }
    let close = format!("{}}}", " ".repeat(indent - 2));
    lines
        .take_while(|l| !l.starts_with(&close))
        .filter_map(|l| {
            let rest = l.strip_prefix(&" ".repeat(indent))?;
            let key = rest.strip_prefix('"')?.split('"').next()?;
            Some(key.to_string())
        })
        .collect()
}

/// Runs `scene` into a fresh directory; returns its `summary.json`.
fn summary(scene: &Path, name: &str) -> String {
    let out = tmp(name);
    let o = bipo(&[
        "run".as_ref(),
        scene.as_os_str(),
        "--quiet".as_ref(),
        "--out".as_ref(),
        out.as_os_str(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    std::fs::read_to_string(out.join("summary.json")).expect("summary.json written")
}

#[test]
fn issue_35_one_run_keeps_each_dimensions_summary_keys() {
    let plane = summary(&scenes().join("block.toml"), "issue_35_plane");
    assert_eq!(
        keys(&plane, None, 2),
        [
            "bipo_version",
            "scene",
            "title",
            "units",
            "status",
            "error",
            "steps",
            "time",
            "wall_time_s",
            "mesh",
            "counters",
            "stages",
            "phases",
            "zones",
            "curves",
            "files",
            "rigid_motions",
            "warnings",
            "path",
            "path_reason"
        ]
    );
    assert_eq!(
        keys(&plane, Some("\"phases\""), 6),
        [
            "name",
            "steps",
            "t_start",
            "t_end",
            "contact_iterations",
            "adhesion_iterations",
            "flexibility_builds",
            "stiffness_changes",
            "wall_time_s"
        ]
    );
    assert_eq!(
        keys(&plane, Some("\"zones\""), 6),
        [
            "name",
            "law",
            "candidates",
            "max_force_n",
            "min_force_n",
            "max_abs_force_t",
            "min_beta",
            "final_force_n",
            "final_force_t",
            "final_status",
            "final_active",
            "final_within_alert",
            "laws"
        ]
    );
    let solid = summary(&manifest("tests/solid/patch_box.toml"), "issue_35_solid");
    assert_eq!(
        keys(&solid, None, 2),
        [
            "bipo_version",
            "scene",
            "title",
            "dimension",
            "units",
            "status",
            "error",
            "steps",
            "time",
            "wall_time_s",
            "mesh",
            "contact_iterations",
            "passes",
            "factorizations",
            "counters",
            "final_reaction",
            "phases",
            "zones",
            "files",
            "warnings",
            "curves",
            "path",
            "path_reason"
        ]
    );
    assert_eq!(
        keys(&solid, Some("\"counters\""), 4),
        [
            "steps",
            "contact_iterations",
            "adhesion_iterations",
            "passes",
            "stiffness_factorizations",
            "matrix_free_steps",
            "active_set_steps",
            "active_set_factorizations"
        ]
    );
    assert_eq!(
        keys(&solid, Some("\"phases\""), 6),
        [
            "name",
            "steps",
            "t_start",
            "t_end",
            "contact_iterations",
            "passes",
            "adhesion_iterations",
            "factorizations",
            "wall_time_s"
        ]
    );
    assert_eq!(
        keys(&solid, Some("\"zones\""), 6),
        [
            "name",
            "law",
            "candidates",
            "max_force_n",
            "final_force_n",
            "final_force",
            "final_active",
            "final_within_alert",
            "laws"
        ]
    );
    // the 3D summary's totals are its phases' (one phase, two steps)
    let v: serde_json::Value = serde_json::from_str(&solid).expect("JSON");
    assert_eq!(v["dimension"], 3);
    assert_eq!(v["counters"]["steps"], 2);
    assert_eq!(
        v["contact_iterations"],
        v["phases"][0]["contact_iterations"]
    );
    assert_eq!(v["passes"], v["counters"]["passes"]);
}
