//! Issue 36, the outputs a contact engineer looks for: "active" means closed (the candidates of
//! the reduced problem counted apart), support reactions in 3D that balance the body, the
//! counters of every path, progress into a log, global-axis forces and frames in 2D, the
//! floating bodies' rigid motions, `r, z` in axisymmetry.
//!
//! Scenes: the Signorini block of `examples/scenes/block.toml` (E = 100, ν = 0, pressed by
//! 0.01) on a ground line turned so that only part of the base closes; a P2 box
//! (tests/solid/patch_box.toml's block, E = 1000, ν = 0) pressed on a plane turned the same way;
//! the floating block of `examples/scenes/block_force.toml`.

use super::support::{csv, num, scenes, summary, tmp};
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

/// `bipo run scene --out out` (`--quiet` when `quiet`), stderr piped (not a terminal);
/// returns (stdout, stderr).
fn run(scene: &Path, out: &Path, quiet: bool) -> (String, String) {
    let mut args: Vec<&std::ffi::OsStr> = vec![
        "run".as_ref(),
        scene.as_os_str(),
        "--out".as_ref(),
        out.as_os_str(),
    ];
    if quiet {
        args.push("--quiet".as_ref());
    }
    let o: Output = Command::new(env!("CARGO_BIN_EXE_bipo"))
        .args(&args)
        .stderr(Stdio::piped())
        .stdout(Stdio::piped())
        .output()
        .unwrap();
    let (stdout, stderr) = (
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    );
    assert!(o.status.success(), "bipo failed:\n{stdout}\n{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    (stdout, stderr)
}

/// The block scene with `edits` (from, to) applied, written as `dir/name.toml`.
fn block_scene(dir: &Path, name: &str, edits: &[(&str, &str)]) -> PathBuf {
    let mut text = std::fs::read_to_string(scenes().join("block.toml")).unwrap();
    for (from, to) in edits {
        assert!(text.contains(from), "{from}");
        text = text.replacen(from, to, 1);
    }
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, text).unwrap();
    path
}

/// The block's ground turned: `y = −0.015 x`, so the left of the base closes and the right
/// (gap up to 0.015 > the press 0.01) stays open, within the alert distance 0.1.
const TURNED_GROUND: (&str, &str) = (
    "target = { type = \"line\", a = [-1.0, 0.0], b = [2.0, 0.0] }",
    "target = { type = \"line\", a = [-1.0, 0.015], b = [2.0, -0.03] }",
);

/// A P2 box 1 × 1 × 0.5 (E = 1000, ν = 0), its top pressed by 1e-3 and held in x and y, on a
/// plane through the origin turned about y (`z = −0.0015 x`: the side x = 1 stays open), with
/// `law`, a body force `body` and the `[solver]` lines `solver`.
fn box_scene(dir: &Path, name: &str, law: &str, body: [f64; 3], solver: &str) -> PathBuf {
    let text = format!(
        r#"title = "issue 36 box"
[mesh]
generator = "box"
element = "P2"
x = [0.0, 1.0]
nx = 4
y = [0.0, 1.0]
ny = 2
z = [0.0, 0.5]
nz = 1
[analysis]
type = "3d"
[[materials]]
region = 0
young = 1000.0
poisson = 0.0
[functions]
ramp = [[0.0, 0.0], [1.0, 1.0]]
[[supports]]
set = "z1"
component = "z"
value = -1e-3
function = "ramp"
[[supports]]
set = "z1"
component = "x"
[[supports]]
set = "z1"
component = "y"
[[loads]]
type = "body_force"
value = [{}, {}, {}]
[[contact]]
name = "floor"
contactor = "z0"
target = {{ type = "plane", point = [0.0, 0.0, 0.0], normal = [0.0015, 0.0, 1.0] }}
law = {law}
alert_distance = 0.1
[solver]
tol = 1e-12
{solver}
[steps]
count = 2
duration = 1.0
[output]
vtk = false
"#,
        body[0], body[1], body[2]
    );
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, text).unwrap();
    path
}

/// 2D: `active_contacts` of steps.csv counts the closed contacts (stick or slip in
/// contacts.csv), `candidates` those of the reduced problem; summary.json and the printed
/// summary say the same. Fails on the old code: `active_contacts` was the reduced problem's
/// size and there was no `candidates` column.
#[test]
fn issue_36_active_means_closed_in_2d() {
    let dir = tmp("closed_2d");
    let scene = block_scene(&dir, "turned", &[TURNED_GROUND]);
    let out = dir.join("out");
    let (stdout, _) = run(&scene, &out, true);
    let steps = csv(&out.join("steps.csv"));
    let contacts = csv(&out.join("contacts.csv"));
    for row in &steps {
        let step = &row["step"];
        let mine: Vec<_> = contacts.iter().filter(|c| &c["step"] == step).collect();
        let closed = mine
            .iter()
            .filter(|c| ["stick", "slip", "closed"].contains(&c["status"].as_str()))
            .count();
        let within = mine.iter().filter(|c| c["status"] != "inactive").count();
        assert_eq!(num(row, "active_contacts") as usize, closed, "step {step}");
        assert_eq!(num(row, "candidates") as usize, within, "step {step}");
    }
    let last = steps.last().unwrap();
    let (closed, within) = (num(last, "active_contacts"), num(last, "candidates"));
    // part of the base open: the count that matters differs from the candidates'
    assert!(closed > 0.0 && closed < within, "{closed} of {within}");
    let s = summary(&out);
    assert_eq!(s["zones"][0]["final_active"], closed as u64);
    assert_eq!(s["zones"][0]["final_within_alert"], within as u64);
    assert!(
        stdout.contains(&format!(
            "{} active = closed, {} within the alert distance",
            closed, within
        )),
        "{stdout}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// 3D: the same meaning. `active` in contacts.csv is 1 where `r_n > 0` (Signorini: no
/// adhesion, `r = r̄`), `candidate` where the contact was in the reduced problem.
#[test]
fn issue_36_active_means_closed_in_3d() {
    let dir = tmp("closed_3d");
    let scene = box_scene(&dir, "box", "{ type = \"signorini\" }", [0.0; 3], "");
    let out = dir.join("out");
    let (stdout, _) = run(&scene, &out, true);
    let steps = csv(&out.join("steps.csv"));
    let contacts = csv(&out.join("contacts.csv"));
    let last = steps.last().unwrap();
    let mine: Vec<_> = contacts
        .iter()
        .filter(|c| c["step"] == last["step"])
        .collect();
    let closed = mine.iter().filter(|c| c["active"] == "1").count();
    assert!(
        mine.iter()
            .all(|c| (c["active"] == "1") == (num(c, "r_n") > 0.0))
    );
    let within = mine.iter().filter(|c| c["candidate"] == "1").count();
    assert_eq!(num(last, "active_contacts") as usize, closed);
    assert_eq!(num(last, "candidates") as usize, within);
    assert!(closed > 0 && closed < within, "{closed} of {within}");
    let s = summary(&out);
    assert_eq!(s["zones"][0]["final_active"], closed as u64);
    assert_eq!(s["zones"][0]["final_within_alert"], within as u64);
    assert!(
        stdout.contains(&format!(
            "({closed} active = closed, {within} within the alert distance)"
        )),
        "{stdout}"
    );
    // the frame appended: unit normal and tangents, the force r_n n + r_t1 t1 + r_t2 t2
    for c in &mine {
        let v = |k: &str| [0, 1, 2].map(|a| num(c, &format!("{k}_{}", ["x", "y", "z"][a])));
        let (n, t1, t2) = (v("n"), v("t1"), v("t2"));
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        assert!((dot(n, n) - 1.0).abs() < 1e-12 && dot(n, t1).abs() < 1e-12);
        assert!(dot(t1, t2).abs() < 1e-12 && (dot(t2, t2) - 1.0).abs() < 1e-12);
        let f = v("f");
        let r = [num(c, "r_n"), num(c, "r_t1"), num(c, "r_t2")];
        for a in 0..3 {
            let g = r[0] * n[a] + r[1] * t1[a] + r[2] * t2[a];
            assert!((f[a] - g).abs() <= 1e-12 * (1.0 + g.abs()), "{f:?}");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// 3D support reactions balance the applied loads and the contact forces: `Σ R + ∫ b dV +
/// Σ f_contact = 0` at every step, to 1e-8 of the body force (the solver tolerance is 1e-12;
/// the sums gather O(100) terms). The body force is known: `b` times the volume 0.5. Fails on
/// the old code: no `reaction_*` columns.
#[test]
fn issue_36_support_reactions_balance_the_body_in_3d() {
    let dir = tmp("reactions_3d");
    let b = [0.5, -0.3, -2.0];
    let scene = box_scene(&dir, "box", "{ type = \"coulomb\", mu = 0.3 }", b, "");
    let out = dir.join("out");
    run(&scene, &out, true);
    let steps = csv(&out.join("steps.csv"));
    assert_eq!(steps.len(), 2);
    let scale = (b[0] * b[0] + b[1] * b[1] + b[2] * b[2]).sqrt() * 0.5;
    for row in &steps {
        let mut worst: f64 = 0.0;
        for (a, axis) in ["x", "y", "z"].iter().enumerate() {
            let sum = num(row, &format!("reaction_{axis}"))
                + b[a] * 0.5
                + num(row, &format!("force_{axis}"));
            worst = worst.max(sum.abs());
        }
        assert!(worst <= 1e-8 * scale, "step {}: {worst:e}", row["step"]);
        // the contact carries load: the check is not 0 = 0
        assert!(num(row, "force_z").abs() > 0.1);
    }
    let s = summary(&out);
    let last = steps.last().unwrap();
    assert_eq!(
        s["final_reaction"][2].as_f64().unwrap(),
        num(last, "reaction_z")
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// 3D counters on every path: the active set factorises (old code: `factorizations` 0), each
/// step's path and counts in steps.csv, summary.json's `counters` as 2D's; progress lines in a
/// log (stderr not a terminal) on the active set and matrix-free paths, as on the dense one.
#[test]
fn issue_36_counters_and_progress_on_every_3d_path() {
    let dir = tmp("counters_3d");
    let law = "{ type = \"coulomb\", mu = 0.3 }";
    for (flexibility, column) in [
        ("active-set", "active_set"),
        ("matrix-free", "matrix_free"),
        ("dense", ""),
    ] {
        let solver = format!("flexibility = \"{flexibility}\"");
        let scene = box_scene(&dir, flexibility, law, [0.0; 3], &solver);
        let out = dir.join(flexibility);
        let (_, stderr) = run(&scene, &out, false);
        assert!(stderr.contains("progress: step 1/2"), "{stderr}");
        assert!(stderr.contains("progress: step 2/2"), "{stderr}");
        let steps = csv(&out.join("steps.csv"));
        let s = summary(&out);
        let c = &s["counters"];
        assert_eq!(c["steps"], 2);
        let per_step: f64 = steps.iter().map(|r| num(r, "factorizations")).sum();
        assert_eq!(s["factorizations"].as_f64().unwrap(), per_step);
        match column {
            "active_set" => {
                assert!(steps.iter().all(|r| r["active_set"] == "1"));
                assert_eq!(c["active_set_steps"], 2);
                assert!(c["active_set_factorizations"].as_u64().unwrap() > 0);
                assert!(s["factorizations"].as_u64().unwrap() > 0);
                assert!(stderr.contains("active set"), "{stderr}");
            }
            "matrix_free" => {
                assert!(steps.iter().all(|r| r["matrix_free"] == "1"));
                assert_eq!(c["matrix_free_steps"], 2);
                assert!(stderr.contains("matrix-free"), "{stderr}");
            }
            _ => {
                assert_eq!(c["active_set_steps"], 0);
                assert_eq!(c["matrix_free_steps"], 0);
                assert!(stderr.contains("dense"), "{stderr}");
            }
        }
        assert_eq!(
            c["contact_iterations"].as_f64().unwrap(),
            steps
                .iter()
                .map(|r| num(r, "contact_iterations"))
                .sum::<f64>()
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// 2D progress into a log on the dense, active-set and matrix-free paths.
#[test]
fn issue_36_progress_into_a_log_on_every_2d_path() {
    let dir = tmp("progress_2d");
    for flexibility in ["dense", "active-set", "matrix-free"] {
        let key = format!("[solver]\nflexibility = \"{flexibility}\"\n");
        let scene = block_scene(&dir, flexibility, &[("[solver]\n", &key)]);
        let (_, stderr) = run(&scene, &dir.join(flexibility), false);
        for k in 1..=4 {
            assert!(
                stderr.contains(&format!("progress: step {k}/4")),
                "{stderr}"
            );
        }
        let path = match flexibility {
            "active-set" => "active set",
            other => other,
        };
        assert!(stderr.contains(path), "{flexibility}: {stderr}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// 2D contacts.csv: the force in global axes `f = r_n n + r_t t` and the frame `n, t`
/// (appended after `area`); its Σ f_y is steps' Σ r_n on a flat ground. Fails on the old code:
/// no such columns.
#[test]
fn issue_36_global_forces_and_frames_in_2d() {
    let dir = tmp("frames_2d");
    let scene = block_scene(&dir, "turned", &[TURNED_GROUND]);
    let out = dir.join("out");
    run(&scene, &out, true);
    let text = std::fs::read_to_string(out.join("contacts.csv")).unwrap();
    assert!(
        text.lines()
            .next()
            .unwrap()
            .ends_with(",area,f_x,f_y,n_x,n_y,t_x,t_y")
    );
    let rows = csv(&out.join("contacts.csv"));
    // the turned ground: n = (0.015, 1) / |.|, t = (n_y, −n_x)
    let len = (1.0f64 + 0.015 * 0.015).sqrt();
    for c in &rows {
        let (n, t) = (
            [num(c, "n_x"), num(c, "n_y")],
            [num(c, "t_x"), num(c, "t_y")],
        );
        assert!((n[0] - 0.015 / len).abs() < 1e-12 && (n[1] - 1.0 / len).abs() < 1e-12);
        assert_eq!(t, [n[1], -n[0]]);
        let (rn, rt) = (num(c, "r_n"), num(c, "r_t"));
        for a in 0..2 {
            let f = num(c, ["f_x", "f_y"][a]);
            assert!((f - (rn * n[a] + rt * t[a])).abs() <= 1e-15 * (1.0 + rn.abs()));
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Axisymmetric CSVs label the axes `r, z`. Fails on the old code (`x, y`).
#[test]
fn issue_36_axisymmetric_csv_labels_r_z() {
    let dir = tmp("axisym");
    let scene = block_scene(
        &dir,
        "axi",
        &[("type = \"plane_strain\"", "type = \"axisymmetric\"")],
    );
    let out = dir.join("out");
    run(&scene, &out, true);
    let text = std::fs::read_to_string(out.join("contacts.csv")).unwrap();
    let head = text.lines().next().unwrap();
    assert!(
        head.starts_with("step,time,load_factor,zone,node,r,z,status,"),
        "{head}"
    );
    assert!(head.ends_with(",area,f_r,f_z,n_r,n_z,t_r,t_z"), "{head}");
    let plane = block_scene(&dir, "plane", &[]);
    let out_plane = dir.join("plane_out");
    run(&plane, &out_plane, true);
    let text = std::fs::read_to_string(out_plane.join("contacts.csv")).unwrap();
    assert!(text.starts_with("step,time,load_factor,zone,node,x,y,status,"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// The floating block's rigid-body motions: one row per step and mode in rigid_motions.csv
/// (its translations along x and y: the library keeps the modes the contact cannot hold by
/// itself), the last step's in summary.json. Fails on the old code: no such file.
#[test]
fn issue_36_rigid_motions_of_a_floating_body() {
    let dir = tmp("rigid");
    let out = dir.join("out");
    run(&scenes().join("block_force.toml"), &out, true);
    let rows = csv(&out.join("rigid_motions.csv"));
    let s = summary(&out);
    let steps = s["steps"].as_u64().unwrap() as usize;
    let motions = s["rigid_motions"].as_array().unwrap();
    let names: Vec<&str> = motions
        .iter()
        .map(|m| m["motion"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["translation x", "translation y"]);
    assert_eq!(rows.len(), motions.len() * steps);
    let last = &rows[rows.len() - motions.len()..];
    for (row, m) in last.iter().zip(motions) {
        assert_eq!(row["motion"], "translation");
        assert_eq!(num(row, "amplitude"), m["amplitude"].as_f64().unwrap());
        assert!(num(row, "amplitude").is_finite());
    }
    // a translation moves the block by its amplitude along its direction
    assert_eq!(num(&last[0], "u_x"), num(&last[0], "amplitude"));
    assert_eq!(last[0]["u_y"], "0e0");
    assert_eq!(num(&last[1], "u_y"), num(&last[1], "amplitude"));
    // pressed down by its cap: the block moves down; sheared along +x in the last phase
    assert!(num(&last[1], "u_y") < 0.0 && num(&last[0], "u_x") > 0.0);
    assert!(
        s["files"]
            .as_array()
            .unwrap()
            .iter()
            .any(|f| f == "rigid_motions.csv")
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// `examples/scenes/pile.toml` on a coarse mesh (4 cells along the shaft and the soil radius,
/// 3 below the tip) in `steps` pull-out increments, with `extra` `[output]` lines.
fn pile_scene(dir: &Path, name: &str, steps: usize, extra: &str) -> PathBuf {
    let mut text = std::fs::read_to_string(scenes().join("pile.toml")).unwrap();
    for (from, to) in [
        ("steps = 50", format!("steps = {steps}")),
        (
            "every = 5\nvtk = true",
            format!("every = 1\nvtk = false\n{extra}"),
        ),
        (
            "# [preset.mesh]",
            "[preset.mesh]\ncells_shaft = 4\ncells_soil_r = 4\ncells_below_tip = 3\n#".into(),
        ),
    ] {
        assert!(text.contains(from), "{from}");
        text = text.replacen(from, &to, 1);
    }
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, text).unwrap();
    path
}

/// The pile's shaft profiles against depth: by default the first pull-out step (3: after the
/// geostatic and installation steps), the peak head load's and the last, in profiles.csv
/// (σ_n and τ are contacts.csv's `r / area` of the shaft, bit for bit in their text) and one
/// SVG per quantity; the soil mesh series by default. `profile_steps` chooses the steps, and
/// is refused outside the pile preset or out of range. Fails on the old code: no profiles, no
/// mesh VTK.
#[test]
fn issue_36_pile_profiles_against_depth() {
    let dir = tmp("pile_profiles");
    let out = dir.join("out");
    run(&pile_scene(&dir, "pile", 4, ""), &out, true);
    let rows = csv(&out.join("profiles.csv"));
    let s = summary(&out);
    let curve: Vec<(u64, f64)> = csv(&out.join("curves.csv"))
        .iter()
        .map(|r| (num(r, "step") as u64, num(r, "Q (kN)")))
        .collect();
    let peak = curve
        .iter()
        .filter(|(k, _)| *k >= 3)
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap()
        .0;
    let mut steps: Vec<u64> = rows.iter().map(|r| num(r, "step") as u64).collect();
    steps.dedup();
    let mut expected = vec![3, peak, 6];
    expected.dedup();
    assert_eq!(steps, expected);
    let contacts = csv(&out.join("contacts.csv"));
    for &k in &steps {
        let mine: Vec<_> = rows.iter().filter(|r| num(r, "step") as u64 == k).collect();
        let mut shaft: Vec<_> = contacts
            .iter()
            // zones `shaft` (0) and `tip_corner` (1): the shaft from the tip corner up
            .filter(|c| num(c, "step") as u64 == k && (c["zone"] == "0" || c["zone"] == "1"))
            .collect();
        shaft.sort_by(|a, b| num(a, "z").total_cmp(&num(b, "z")));
        assert_eq!(mine.len(), shaft.len());
        for (p, c) in mine.iter().zip(&shaft) {
            assert_eq!(num(p, "depth"), -num(c, "z"));
            let area = num(c, "area");
            for (q, r) in [("sigma_n", "r_n"), ("tau", "r_t")] {
                let want = num(c, r) / area;
                assert!((num(p, q) - want).abs() <= 1e-12 * (1.0 + want.abs()));
            }
            assert_eq!(num(p, "beta"), num(c, "beta"));
            assert_eq!(num(p, "u_t"), num(c, "u_t"));
        }
    }
    let files = s["files"].as_array().unwrap();
    for f in [
        "profiles.csv",
        "profile_sigma_n.svg",
        "profile_tau.svg",
        "profile_beta.svg",
        "profile_slip.svg",
        "mesh.pvd",
    ] {
        assert!(files.iter().any(|g| g == f), "{f}");
        assert!(out.join(f).exists(), "{f}");
    }
    // chosen steps
    let out2 = dir.join("chosen");
    run(
        &pile_scene(&dir, "chosen", 4, "profile_steps = [5]\nmesh_vtk = false"),
        &out2,
        true,
    );
    let rows = csv(&out2.join("profiles.csv"));
    assert!(!rows.is_empty() && rows.iter().all(|r| r["step"] == "5"));
    assert!(!out2.join("mesh.pvd").exists());
    // refused: out of range, and outside the pile preset
    for (scene, fragment) in [
        (
            pile_scene(&dir, "far", 4, "profile_steps = [7]"),
            "`output.profile_steps`: step 7 is not a step of the run (1 to 6)",
        ),
        (
            block_scene(
                &dir,
                "block",
                &[("[output]\n", "[output]\nprofile_steps = [1]\n")],
            ),
            "`output.profile_steps`: shaft profiles are written by the pile preset only",
        ),
        (
            {
                let b = box_scene(&dir, "box", "{ type = \"signorini\" }", [0.0; 3], "");
                let text = std::fs::read_to_string(&b).unwrap();
                std::fs::write(
                    &b,
                    text.replace("[output]\n", "[output]\nprofile_steps = [1]\n"),
                )
                .unwrap();
                b
            },
            "`output.profile_steps`: shaft profiles are written by the 2D pile preset only",
        ),
    ] {
        let o = Command::new(env!("CARGO_BIN_EXE_bipo"))
            .args(["check".as_ref(), scene.as_os_str()])
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{stderr}");
        assert!(stderr.contains(fragment), "{stderr}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// 3D `[[plots]]`: the turned box's Σ r_n, closed contacts and contact iterations against
/// time, written as in 2D (`curves.csv`, one SVG, the extremes in `summary.json`). The values
/// are steps.csv's columns of the same step (`force_n`, `active_contacts`,
/// `contact_iterations`), to 1e-12 relative (both are printed round-trip). Fails on the old
/// code: 3D scenes refused `[[plots]]`.
#[test]
fn issue_36_plots_in_3d_match_steps_csv() {
    let dir = tmp("plots_3d");
    let scene = box_scene(&dir, "box", "{ type = \"signorini\" }", [0.0; 3], "");
    let text = std::fs::read_to_string(&scene).unwrap()
        + "[[plots]]\nfile = \"force.svg\"\nx = \"time\"\ncurves = [\
           { quantity = \"force_n\", label = \"sum r_n\" }, { quantity = \"closed\" }, \
           { quantity = \"contact_iterations\" }]\n";
    std::fs::write(&scene, text).unwrap();
    let out = dir.join("out");
    run(&scene, &out, true);
    let steps = csv(&out.join("steps.csv"));
    let curves = csv(&out.join("curves.csv"));
    assert_eq!(curves.len(), steps.len());
    assert_eq!(steps.len(), 2);
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * (1.0 + b.abs());
    for (c, s) in curves.iter().zip(&steps) {
        assert!(close(num(c, "time"), num(s, "time")), "{c:?}");
        assert!(close(num(c, "sum r_n"), num(s, "force_n")), "{c:?} {s:?}");
        assert_eq!(num(c, "closed"), num(s, "active_contacts"), "{c:?}");
        assert_eq!(
            num(c, "contact_iterations"),
            num(s, "contact_iterations"),
            "{c:?}"
        );
    }
    let last = num(steps.last().unwrap(), "force_n");
    assert!(last > 0.0);
    let svg = std::fs::read_to_string(out.join("force.svg")).unwrap();
    assert!(svg.contains("<svg") && svg.contains("sum r_n"), "{svg}");
    let s = summary(&out);
    let files: Vec<&str> = s["files"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f.as_str().unwrap())
        .collect();
    assert!(
        files.contains(&"curves.csv") && files.contains(&"force.svg"),
        "{files:?}"
    );
    let c = &s["curves"][0];
    assert_eq!(c["label"], "sum r_n");
    assert!(close(c["last"].as_f64().unwrap(), last), "{c}");
    let first = num(&steps[0], "force_n");
    assert!(
        close(c["max"]["value"].as_f64().unwrap(), last.max(first)),
        "{c}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// 3D `contacts.csv`'s `status` (appended last), named as 2D's: on the turned box, Signorini
/// gives `closed` where `active` = 1 and `open` where the candidate is not closed (both occur);
/// Coulomb (μ = 0.3) names its closed contacts `stick` or `slip`, never `closed`. Fails on the
/// old code: no `status` column.
#[test]
fn issue_36_status_column_in_3d() {
    let dir = tmp("status_3d");
    for (law, closed_names) in [
        ("{ type = \"signorini\" }", &["closed"][..]),
        ("{ type = \"coulomb\", mu = 0.3 }", &["stick", "slip"][..]),
    ] {
        let scene = box_scene(&dir, "box", law, [0.0; 3], "");
        let out = dir.join("out");
        let _ = std::fs::remove_dir_all(&out);
        run(&scene, &out, true);
        let text = std::fs::read_to_string(out.join("contacts.csv")).unwrap();
        assert!(text.lines().next().unwrap().ends_with(",t2_z,status"));
        let contacts = csv(&out.join("contacts.csv"));
        let (mut closed, mut open) = (0, 0);
        for c in &contacts {
            let status = c["status"].as_str();
            match (c["candidate"].as_str(), c["active"].as_str()) {
                ("0", _) => assert_eq!(status, "inactive", "{c:?}"),
                (_, "1") => {
                    assert!(closed_names.contains(&status), "{law}: {c:?}");
                    closed += 1;
                }
                _ => {
                    assert_eq!(status, "open", "{c:?}");
                    open += 1;
                }
            }
        }
        assert!(
            closed > 0 && open > 0,
            "{law}: {closed} closed, {open} open"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
