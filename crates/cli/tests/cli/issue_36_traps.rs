//! Issue 36, the silent traps of `bipo` (each test fails on the code before it):
//!
//! - after `[[phases]] laws` switches a law, `summary.json` and the printed summary named the
//!   first law: now each phase's law with its steps, and the law in force at the end (2D:
//!   examples/scenes/block_force.toml, Signorini then Coulomb; 3D: the patch of
//!   tests/solid/patch_box.toml pressed without friction, then with it);
//! - closed frictionless contacts were reported as `stick` (summary, contacts.csv);
//! - the floating pile pulled by a force (`pile_force`) reported 0 adhesion iterations while
//!   its interface damaged;
//! - `solve-local --help` described 2D only;
//! - contactor nodes that a support holds along the normal were refused without their list:
//!   `supported_contactors = "refuse"` (default) lists them and the key, `"leave_out"` drops
//!   them with a warning (printed, and in `summary.json`), 2D and 3D;
//! - the floating block pushed off its ground said "add a support or a contact" twice.
//!
//! The numbers checked are statics: the Signorini block of block.toml (E = 100, ν = 0, pressed
//! by 0.01 over a width 1: Σ r_n = 1), the patch (E δ A / H = 2).

use super::support::{bipo, csv, scenes, summary, tmp};
use bipo::presets::PulloutSpec;
use contact_solver::SimulationSettings;
use std::path::{Path, PathBuf};

/// `bipo run SCENE --quiet --out OUT`: (success, stdout, stderr).
fn run(scene: &Path, out: &Path) -> (bool, String, String) {
    let o = bipo(&[
        "run".as_ref(),
        scene.as_os_str(),
        "--quiet".as_ref(),
        "--out".as_ref(),
        out.as_os_str(),
    ]);
    (
        o.status.success(),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// `scene` with `from` replaced by `to` (each must occur), written to `dir/name`.
fn edited(scene: &str, edits: &[(&str, &str)], dir: &Path, name: &str) -> PathBuf {
    let mut text = scene.to_string();
    for (from, to) in edits {
        assert!(text.contains(from), "`{from}` is not in the scene");
        text = text.replacen(from, to, 1);
    }
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn issue_36_phase_law_switch_is_reported_2d() {
    let out = tmp("laws_2d");
    let (ok, stdout, stderr) = run(&scenes().join("block_force.toml"), &out);
    assert!(ok, "{stdout}\n{stderr}");
    let s = summary(&out);
    let zone = &s["zones"][0];
    assert_eq!(zone["law"], "coulomb", "{zone}");
    let laws: Vec<(String, String, u64, u64)> = zone["laws"]
        .as_array()
        .unwrap()
        .iter()
        .map(|l| {
            (
                l["phase"].as_str().unwrap().to_string(),
                l["law"].as_str().unwrap().to_string(),
                l["first_step"].as_u64().unwrap(),
                l["last_step"].as_u64().unwrap(),
            )
        })
        .collect();
    assert_eq!(
        laws,
        [
            ("press".into(), "signorini".into(), 1, 1),
            ("shear".into(), "coulomb".into(), 2, 3)
        ]
    );
    assert!(
        stdout.contains(
            "zone `ground` (signorini in `press` (step 1), coulomb in `shear` (steps 2–3)"
        ),
        "{stdout}"
    );
    assert!(
        stdout.contains("laws from here: `ground` coulomb"),
        "{stdout}"
    );
    // the press phase is frictionless: its contacts are closed; the shear phase sticks
    let rows = csv(&out.join("contacts.csv"));
    let status = |step: &str| -> Vec<String> {
        rows.iter()
            .filter(|r| r["step"] == step && r["status"] != "open" && r["status"] != "inactive")
            .map(|r| r["status"].clone())
            .collect()
    };
    assert!(!status("1").is_empty());
    assert!(
        status("1").iter().all(|v| v == "closed"),
        "{:?}",
        status("1")
    );
    // with friction: stick, or slip at the edges (partial slip)
    assert!(
        status("3").iter().all(|v| v == "stick" || v == "slip"),
        "{:?}",
        status("3")
    );
}

const PATCH: &str = "\
title = \"patch\"
[mesh]
generator = \"box\"
element = \"P1\"
x = [0.0, 1.0]
nx = 2
y = [0.0, 1.0]
ny = 2
z = [0.0, 0.5]
nz = 1
[analysis]
type = \"3d\"
[[materials]]
region = 0
young = 1000.0
poisson = 0.0
[functions]
ramp = [[0.0, 0.0], [1.0, 1.0]]
[[supports]]
set = \"z1\"
component = \"z\"
value = -1e-3
function = \"ramp\"
[[supports]]
set = \"z1\"
component = \"x\"
[[supports]]
set = \"z1\"
component = \"y\"
[[contact]]
name = \"floor\"
contactor = \"z0\"
target = { type = \"plane\", point = [0.0, 0.0, 0.0], normal = [0.0, 0.0, 1.0] }
law = { type = \"signorini\" }
alert_distance = 0.1
[solver]
tol = 1e-12
[[phases]]
name = \"press\"
steps = 1
duration = 1.0
[[phases]]
name = \"hold\"
steps = 1
duration = 1.0
laws.floor = { type = \"coulomb\", mu = 0.3 }
[output]
vtk = false
";

#[test]
fn issue_36_phase_law_switch_is_reported_3d() {
    let out = tmp("laws_3d");
    let scene = out.join("patch.toml");
    std::fs::write(&scene, PATCH).unwrap();
    let (ok, stdout, stderr) = run(&scene, &out.join("out"));
    assert!(ok, "{stdout}\n{stderr}");
    let s = summary(&out.join("out"));
    let zone = &s["zones"][0];
    assert_eq!(zone["law"], "coulomb", "{zone}");
    assert_eq!(zone["laws"][0]["law"], "signorini");
    assert_eq!(zone["laws"][1]["law"], "coulomb");
    assert_eq!(zone["laws"][1]["first_step"], 2);
    assert!(
        stdout.contains("signorini in `press` (step 1), coulomb in `hold` (step 2)"),
        "{stdout}"
    );
}

#[test]
fn issue_36_frictionless_contacts_are_closed_in_the_summary() {
    let out = tmp("closed");
    let (ok, stdout, stderr) = run(&scenes().join("block.toml"), &out);
    assert!(ok, "{stdout}\n{stderr}");
    let status = &summary(&out)["zones"][0]["final_status"];
    // 8 P1 cells along the bottom: 9 contactor nodes, all pressed
    assert_eq!(status["closed"], 9, "{status}");
    assert_eq!(status["stick"], 0, "{status}");
    let rows = csv(&out.join("contacts.csv"));
    assert!(rows.iter().all(|r| r["status"] == "closed"), "{rows:?}");
}

/// The pile pulled by a force on its head (the preset of examples/scenes/pile_force.toml) on
/// the coarse mesh of tests/cli/pile.rs: its shaft interface damages (β < 1), and the
/// adhesion iterations of the floating stage are counted (they read 0).
#[test]
fn issue_36_floating_pile_counts_adhesion_iterations() {
    let mut spec = PulloutSpec::plancoet();
    spec.mesh.cells_shaft = 8;
    spec.mesh.cells_soil_r = 8;
    spec.mesh.cells_below_tip = 6;
    spec.steps = 3;
    // below the coarse pile's capacity (~200 kN measured in pile.rs's force-control test)
    spec.head_force = Some(150.0);
    let mut scene = spec.build(SimulationSettings::default()).unwrap();
    scene.run().unwrap();
    let sim = &scene.simulation;
    let beta_min = sim
        .states()
        .iter()
        .map(|s| s.beta())
        .fold(f64::INFINITY, f64::min);
    let adhesion = sim.counters().adhesion_iterations;
    eprintln!("β min {beta_min}, {adhesion} adhesion iterations");
    assert!(
        beta_min < 1.0,
        "the interface did not damage: β min {beta_min}"
    );
    assert!(adhesion > 0, "{adhesion} adhesion iterations");
}

#[test]
fn issue_36_solve_local_help_describes_2d_and_3d() {
    let o = bipo(&["solve-local".as_ref(), "--help".as_ref()]);
    assert!(o.status.success());
    let help = String::from_utf8_lossy(&o.stdout);
    for part in [
        "\"dim\": 2 or 3",
        "2D (dim 2): per contact (normal, tangent); m = 2 n_c",
        "3D (dim 3): per contact (normal, tangent 1, tangent 2); m = 3 n_c",
        "r_t1",
        "Closed for a frictionless contact",
    ] {
        assert!(help.contains(part), "`{part}` is not in:\n{help}");
    }
    assert!(!help.contains("q has m = 2 n_c"), "{help}");
}

/// block.toml with its bottom-left corner (the generator's single-node set) held along y: a
/// contactor node held along the contact normal.
fn held_corner(dir: &Path, choice: Option<&str>) -> PathBuf {
    let text = std::fs::read_to_string(scenes().join("block.toml")).unwrap();
    let key = choice
        .map(|c| format!("alert_distance = 0.1\nsupported_contactors = \"{c}\""))
        .unwrap_or_else(|| "alert_distance = 0.1".into());
    edited(
        &text,
        &[
            (
                "[[contact]]",
                "[[supports]]\nset = \"bottom_left\"\ncomponent = \"y\"\n\n[[contact]]",
            ),
            ("alert_distance = 0.1", &key),
        ],
        dir,
        "held.toml",
    )
}

#[test]
fn issue_36_supported_contactors_refused_with_their_list_2d() {
    let out = tmp("held_refuse");
    let scene = held_corner(&out, None);
    let o = bipo(&["check".as_ref(), scene.as_os_str()]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("contact[0].contactor"), "{err}");
    assert!(err.contains("1 of its nodes carry a support"), "{err}");
    assert!(err.contains(" at (0, 0)"), "{err}");
    assert!(
        err.contains("contact[0].supported_contactors = \"leave_out\""),
        "{err}"
    );
}

#[test]
fn issue_36_supported_contactors_left_out_with_a_warning_2d() {
    let out = tmp("held_leave");
    let scene = held_corner(&out, Some("leave_out"));
    let o = bipo(&["check".as_ref(), scene.as_os_str()]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(
        stdout.contains("warning: zone `ground`: 1 contactor node(s)"),
        "{stdout}"
    );
    let (ok, stdout, stderr) = run(&scene, &out.join("out"));
    assert!(ok, "{stdout}\n{stderr}");
    assert!(stdout.contains("at (0, 0)"), "{stdout}");
    let s = summary(&out.join("out"));
    assert_eq!(
        s["warnings"].as_array().unwrap().len(),
        1,
        "{}",
        s["warnings"]
    );
    assert_eq!(s["zones"][0]["candidates"], 8);
    // the other 8 nodes carry the press: the corner's share is gone, the rest is as before
    let total: f64 = csv(&out.join("out").join("contacts.csv"))
        .iter()
        .filter(|r| r["step"] == "4")
        .map(|r| r["r_n"].parse::<f64>().unwrap())
        .sum();
    assert!(total > 0.8 && total < 1.0, "Σ r_n = {total}");
}

/// A P1 box pressed on a rigid floor by a pressure on its top, held by its side `x0` along z
/// and x (and its top along x and y): the floor's contactor nodes on `x0` are held along the
/// normal.
const HELD_3D: &str = "\
title = \"held\"
[mesh]
generator = \"box\"
element = \"P1\"
x = [0.0, 1.0]
nx = 2
y = [0.0, 1.0]
ny = 2
z = [0.0, 0.5]
nz = 1
[analysis]
type = \"3d\"
[[materials]]
region = 0
young = 1000.0
poisson = 0.0
[[supports]]
set = \"x0\"
component = \"z\"
[[supports]]
set = \"x0\"
component = \"x\"
[[supports]]
set = \"z1\"
component = \"x\"
[[supports]]
set = \"z1\"
component = \"y\"
[[loads]]
type = \"pressure\"
set = \"z1\"
value = 1.0
[[contact]]
name = \"floor\"
contactor = \"z0\"
target = { type = \"plane\", point = [0.0, 0.0, 0.0], normal = [0.0, 0.0, 1.0] }
law = { type = \"signorini\" }
alert_distance = 0.1
[steps]
count = 1
duration = 1.0
[output]
vtk = false
";

#[test]
fn issue_36_supported_contactors_refused_or_left_out_3d() {
    let out = tmp("held_3d");
    let refuse = edited(HELD_3D, &[], &out, "refuse.toml");
    let o = bipo(&["check".as_ref(), refuse.as_os_str()]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("contact[0].contactor"), "{err}");
    assert!(err.contains("3 of its nodes carry a support"), "{err}");
    assert!(err.contains(" at (0, 0, 0)"), "{err}");
    let leave = edited(
        HELD_3D,
        &[(
            "alert_distance = 0.1",
            "alert_distance = 0.1\nsupported_contactors = \"leave_out\"",
        )],
        &out,
        "leave.toml",
    );
    let (ok, stdout, stderr) = run(&leave, &out.join("out"));
    assert!(ok, "{stdout}\n{stderr}");
    assert!(
        stdout.contains("warning: zone `floor`: 3 contactor node(s)"),
        "{stdout}"
    );
    let s = summary(&out.join("out"));
    assert_eq!(s["warnings"].as_array().unwrap().len(), 1);
    assert_eq!(s["zones"][0]["candidates"], 6);
}

#[test]
fn issue_36_unbalanced_says_its_advice_once() {
    let out = tmp("unbalanced");
    let text = std::fs::read_to_string(scenes().join("block_force.toml")).unwrap();
    // a push of 0.5 > μ P = 0.3: the block slides off
    let scene = edited(
        &text,
        &[("value = [0.2, 0.0]", "value = [0.5, 0.0]")],
        &out,
        "push.toml",
    );
    let (ok, stdout, stderr) = run(&scene, &out.join("out"));
    assert!(!ok, "{stdout}");
    assert!(
        stderr.contains("contact cannot balance the load"),
        "{stderr}"
    );
    assert_eq!(
        stderr.matches("support or a contact").count(),
        1,
        "{stderr}"
    );
}
