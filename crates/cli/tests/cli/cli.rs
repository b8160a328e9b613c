//! `bipo run`, `new`, `check` and `solve-local` on the example scenes of `examples/scenes/`.
//!
//! - Signorini block (block.toml): an elastic block (E = 100, ν = 0) pressed by 0.01 on a rigid
//!   LINE: uniaxial strain, so Σ r_n = E · 0.01 · width = 1 (exact up to the solver tolerance).
//! - Seed 5.6.1 (delamination.toml): the preset scene must give the same numbers as
//!   `bipo::presets::DelaminationSpec` stepped through the library, bit for bit (the
//!   CSV floats are written with the shortest round-trip digits).
//! - Two phases (tests/scenes/phases.toml): a support released between phases, loads with
//!   their own functions and a phase override, gravity, plane stress, P2.
//! - Hertz (hertz.toml, Johnson 1985 ch. 4): half-width `a = √(4PR/(πE*))` against the last
//!   closed node.

use super::support::{bipo, csv, scenes, summary, tmp};
use bipo::presets::DelaminationSpec;
use contact_solver::SimulationSettings;
use fem_core::Component;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn ok(out: &Output) -> String {
    assert!(
        out.status.success(),
        "bipo failed:\n{}\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

#[test]
fn block_scene_runs_and_writes_every_output() {
    let out = tmp("block");
    let stdout = ok(&bipo(&[
        "run".as_ref(),
        scenes().join("block.toml").as_os_str(),
        "--out".as_ref(),
        out.as_os_str(),
    ]));
    for f in [
        "summary.json",
        "contacts.csv",
        "steps.csv",
        "interface.pvd",
        "interface_0003.vtu",
        "mesh.pvd",
        "mesh_0003.vtu",
        "force.svg",
        "curves.csv",
    ] {
        assert!(out.join(f).is_file(), "{f} is missing");
    }
    let s = summary(&out);
    assert_eq!(s["status"], "completed");
    assert_eq!(s["steps"], 4);
    assert_eq!(s["time"], 1.0);
    // Σ r_n = E ε width = 100 × 0.01 × 1; the solver stops at tol = 1e-10 relative
    let f = s["zones"][0]["final_force_n"].as_f64().unwrap();
    assert!((f - 1.0).abs() < 1e-8, "Σ r_n = {f}");
    // no adhesion, no friction: none of that work was done
    assert_eq!(s["counters"]["adhesion_iterations"], 0);
    assert_eq!(s["stages"]["adhesive_zones"], 0);
    assert_eq!(s["stages"]["friction_zones"], 0);
    assert_eq!(s["stages"]["steps_with_tangential_reaction"], 0);
    assert_eq!(s["counters"]["stiffness_changes"], 0);
    assert_eq!(s["counters"]["flexibility_builds"], 1); // same active set every step
    assert!(
        stdout.contains("adhesion iterations   0 (no adhesive zone"),
        "{stdout}"
    );
    // the support reaction on the top balances the contact force
    let r = s["curves"][1]["last"].as_f64().unwrap();
    assert!((r + f).abs() < 1e-8, "top reaction {r} against Σ r_n {f}");
    // 9 contact rows per step, 4 steps
    assert_eq!(csv(&out.join("contacts.csv")).len(), 36);
    let svg = std::fs::read_to_string(out.join("force.svg")).unwrap();
    assert!(svg.starts_with("<svg") && svg.contains("sum r_n"));
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn delamination_preset_gives_the_library_numbers() {
    // The whole seed study: 210 steps take 0.4 s in a debug build. (With 6 or 21 steps the
    // adhesion fixed point at the peak needs more than its default 200 iterations.)
    const STEPS: usize = 210;
    let dir = tmp("delamination");
    let text = std::fs::read_to_string(scenes().join("delamination.toml")).unwrap();
    assert!(text.contains(&format!("steps = {STEPS}")));
    let scene = dir.join("delamination.toml");
    std::fs::write(&scene, text).unwrap();
    let out = dir.join("out");
    ok(&bipo(&[
        "run".as_ref(),
        scene.as_os_str(),
        "-q".as_ref(),
        "--out".as_ref(),
        out.as_os_str(),
    ]));

    // the same study through the library
    let spec = DelaminationSpec {
        steps: STEPS,
        ..DelaminationSpec::default()
    };
    let mut lib = spec.build(SimulationSettings::default()).unwrap();
    let mut results = Vec::new();
    let mut force_a = Vec::new();
    for k in 1..=STEPS {
        results.push(lib.step(k).unwrap());
        let u = lib.simulation.nodal_displacements();
        let r = lib.simulation.structure().reactions(&u, 1.0).unwrap();
        force_a.push(
            r.iter()
                .filter(|((n, c), _)| *n == lib.point_a && *c == Component::Y)
                .map(|(_, v)| v)
                .sum::<f64>(),
        );
    }
    // contacts.csv holds the last step (the last of the phase; `every = 10`): bit for bit
    let rows = csv(&out.join("contacts.csv"));
    let last: Vec<_> = rows
        .iter()
        .filter(|r| r["step"] == STEPS.to_string())
        .collect();
    let expected = &results[STEPS - 1].contacts;
    assert_eq!(last.len(), expected.len());
    for (row, rec) in last.iter().zip(expected) {
        assert_eq!(row["node"].parse::<usize>().unwrap(), rec.node);
        for (col, v) in [
            ("r_n", rec.r.n),
            ("r_t", rec.r.t[0]),
            ("gap", rec.gap),
            ("u_t", rec.u_t),
            ("beta", rec.beta),
        ] {
            assert_eq!(
                row[col].parse::<f64>().unwrap(),
                v,
                "{col} at node {}",
                rec.node
            );
        }
    }
    // the force at A of every step (curves.csv), and the iteration counts (steps.csv)
    let curves = csv(&out.join("curves.csv"));
    assert_eq!(curves.len(), STEPS);
    let steps = csv(&out.join("steps.csv"));
    for k in 0..STEPS {
        let f: f64 = curves[k]["F_A (N per mm)"].parse().unwrap();
        assert_eq!(f, force_a[k], "F_A at step {}", k + 1);
        let rep = &results[k].report;
        assert_eq!(
            steps[k]["contact_iterations"],
            rep.contact_iterations.to_string()
        );
        assert_eq!(
            steps[k]["adhesion_iterations"],
            rep.adhesion_iterations.to_string()
        );
    }
    let s = summary(&out);
    assert_eq!(
        s["counters"]["contact_iterations"].as_u64().unwrap() as usize,
        lib.simulation.counters().contact_iterations
    );
    assert!(s["counters"]["adhesion_iterations"].as_u64().unwrap() > 0);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn hertz_scene_on_a_gmsh_p2_mesh_matches_the_contact_width() {
    let out = tmp("hertz");
    ok(&bipo(&[
        "run".as_ref(),
        scenes().join("hertz.toml").as_os_str(),
        "-q".as_ref(),
        "--out".as_ref(),
        out.as_os_str(),
    ]));
    let s = summary(&out);
    let p = 2.0 * s["zones"][0]["final_force_n"].as_f64().unwrap(); // half model
    let (r, e_star) = (100.0, 1000.0 / (1.0 - 0.09));
    let a = (4.0 * p * r / (std::f64::consts::PI * e_star)).sqrt();
    let rows = csv(&out.join("contacts.csv"));
    let x_closed = rows
        .iter()
        .filter(|r| r["step"] == "2" && r["status"] != "open" && r["status"] != "inactive")
        .map(|r| r["x"].parse::<f64>().unwrap())
        .fold(0.0, f64::max);
    // P2 nodes on the arc are 0.094 apart: the last closed node is within one spacing of a
    assert!(
        (x_closed - a).abs() < 0.1,
        "last closed node at x = {x_closed}, Hertz a = {a}"
    );
    assert_eq!(s["mesh"]["nodes"], 1225);
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn shear_and_pile_scenes_check() {
    for scene in [
        "shear.toml",
        "pile.toml",
        "hertz.toml",
        "delamination.toml",
        "block_force.toml",
        "pile_force.toml",
        "pile_refined.toml",
    ] {
        let stdout = ok(&bipo(&["check".as_ref(), scenes().join(scene).as_os_str()]));
        assert!(
            stdout.contains("ok: the scene is valid"),
            "{scene}: {stdout}"
        );
    }
}

#[test]
fn pile_preset_runs_its_three_phases() {
    let dir = tmp("pile");
    let text = std::fs::read_to_string(scenes().join("pile.toml")).unwrap();
    let scene = dir.join("pile.toml");
    std::fs::write(&scene, text.replace("steps = 50", "steps = 2")).unwrap();
    let out = dir.join("out");
    let stdout = ok(&bipo(&[
        "run".as_ref(),
        scene.as_os_str(),
        "--out".as_ref(),
        out.as_os_str(),
    ]));
    let s = summary(&out);
    let phases: Vec<&str> = s["phases"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["name"].as_str().unwrap())
        .collect();
    assert_eq!(phases, ["geostatic", "installation", "pullout"]);
    assert_eq!(s["steps"], 4);
    assert!(stdout.contains("phase `pullout`: 2 steps"), "{stdout}");
    // the adhesive Newton's factorisations, in summary.json and in the stage list
    let jacobians = s["counters"]["adhesion_factorizations"].as_u64().unwrap();
    assert!(jacobians > 0, "{}", s["counters"]);
    assert!(
        stdout.contains(&format!("Newton Jacobians      {jacobians} ")),
        "{stdout}"
    );
    assert!(out.join("pullout.svg").is_file());
    let q = s["curves"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["label"] == "Q (kN)")
        .unwrap();
    // the same study through the library: the same head load at the last increment
    let spec = bipo::presets::PulloutSpec {
        steps: 2,
        ..bipo::presets::PulloutSpec::plancoet()
    };
    let mut lib = spec.build(SimulationSettings::default()).unwrap();
    let run = lib.run().unwrap();
    let q_lib = run.steps.last().unwrap().head_load;
    let q_cli = q["last"].as_f64().unwrap();
    assert!(
        (q_cli - q_lib).abs() <= 1e-12 * q_lib.abs(),
        "bipo {q_cli} vs library {q_lib}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn new_writes_templates_that_check() {
    let dir = tmp("new");
    for kind in [
        "block",
        "hertz",
        "delamination",
        "shear",
        "pile",
        "sphere_3d",
    ] {
        let file = dir.join(format!("{kind}.toml"));
        let stdout = ok(&bipo(&[
            "new".as_ref(),
            kind.as_ref(),
            "-o".as_ref(),
            file.as_os_str(),
        ]));
        assert!(stdout.contains("wrote"), "{stdout}");
        let text = std::fs::read_to_string(&file).unwrap();
        assert_eq!(
            text,
            std::fs::read_to_string(scenes().join(format!("{kind}.toml"))).unwrap()
        );
        if kind != "pile" {
            ok(&bipo(&["check".as_ref(), file.as_os_str()]));
        }
    }
    assert!(dir.join("hertz_cylinder.msh").is_file());
    // no overwrite without --force
    let again = bipo(&[
        "new".as_ref(),
        "block".as_ref(),
        "-o".as_ref(),
        dir.join("block.toml").as_os_str(),
    ]);
    assert!(!again.status.success());
    assert!(String::from_utf8_lossy(&again.stderr).contains("exists already"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn solve_local_prints_the_solution() {
    let dir = tmp("local");
    let file = dir.join("p.json");
    // W = 2 I, q = (−1, 0.5), μ = 0.2: slip, r_n = 0.5, r_t = −0.1
    std::fs::write(
        &file,
        r#"{"dim": 2, "W": [[2, 0], [0, 2]], "q": [-1, 0.5], "mu": [0.2]}"#,
    )
    .unwrap();
    let stdout = ok(&bipo(&["solve-local".as_ref(), file.as_os_str()]));
    assert!(stdout.contains("converged in"), "{stdout}");
    let json = ok(&bipo(&[
        "solve-local".as_ref(),
        file.as_os_str(),
        "--json".as_ref(),
    ]));
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert!((v["r"][0].as_f64().unwrap() - 0.5).abs() < 1e-9);
    assert!((v["r"][1].as_f64().unwrap() + 0.1).abs() < 1e-9);
    assert_eq!(v["converged"], true);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 37: a non-symmetric `W` (a multibody problem with joints) is refused by default and
/// solved as given with `--keep-asymmetric`. W = [[1, 0.1], [0, 1]], q = (−1, 0.5), μ = 0.2:
/// the contact slips with r_t = −μ r_n and r_n + 0.1 r_t = 1, so r_n = 1/0.98 (the symmetrised
/// W would give 1/0.99: the two differ by 1e-2, the tolerance is the solver's 1e-9).
#[test]
fn issue_37_solve_local_keeps_a_non_symmetric_w_on_request() {
    let dir = tmp("local_asym");
    let file = dir.join("p.json");
    std::fs::write(
        &file,
        r#"{"W": [[1, 0.1], [0, 1]], "q": [-1, 0.5], "mu": [0.2]}"#,
    )
    .unwrap();
    let refused = bipo(&["solve-local".as_ref(), file.as_os_str()]);
    assert!(!refused.status.success());
    assert!(String::from_utf8_lossy(&refused.stderr).contains("W is not symmetric"));
    let json = ok(&bipo(&[
        "solve-local".as_ref(),
        file.as_os_str(),
        "--keep-asymmetric".as_ref(),
        "--json".as_ref(),
    ]));
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    let (rn, rt) = (v["r"][0].as_f64().unwrap(), v["r"][1].as_f64().unwrap());
    assert!((rn - 1.0 / 0.98).abs() < 1e-9, "r_n = {rn}");
    assert!((rt + 0.2 / 0.98).abs() < 1e-9, "r_t = {rt}");
    let uzawa = bipo(&[
        "solve-local".as_ref(),
        file.as_os_str(),
        "--keep-asymmetric".as_ref(),
        "--algorithm".as_ref(),
        "uzawa".as_ref(),
    ]);
    assert!(!uzawa.status.success(), "Uzawa needs a symmetric W");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn solve_local_reads_fclib_files_with_the_feature() {
    let file = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../contact-solver/tests/data/fclib_csc_h5py.hdf5");
    let out = bipo(&["solve-local".as_ref(), file.as_os_str()]);
    if cfg!(feature = "fclib") {
        let stdout = ok(&out);
        assert!(
            stdout.contains("2 contacts") && stdout.contains("converged in"),
            "{stdout}"
        );
    } else {
        assert!(!out.status.success());
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(stderr.contains("built with `--features fclib`"), "{stderr}");
    }
}

#[test]
fn help_has_examples_everywhere() {
    for args in [
        vec!["--help"],
        vec!["run", "--help"],
        vec!["check", "--help"],
        vec!["solve-local", "--help"],
        vec!["new", "--help"],
    ] {
        let a: Vec<&std::ffi::OsStr> = args.iter().map(|s| s.as_ref()).collect();
        let stdout = ok(&bipo(&a));
        assert!(stdout.contains("Examples:"), "{args:?}: {stdout}");
    }
}

#[test]
fn phases_release_supports_and_scale_loads() {
    // Plane stress, thickness 2, E = 100, ν = 0: the top pressed by 0.01·t gives
    // Σ r_n = E (0.01 t) · width · thickness; gravity (unit weight 1 on the 1 × 1 × 2 block)
    // splits equally between the top support and the ground, adding 1.
    let out = tmp("phases");
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scenes/phases.toml");
    ok(&bipo(&[
        "run".as_ref(),
        scene.as_os_str(),
        "-q".as_ref(),
        "--out".as_ref(),
        out.as_os_str(),
    ]));
    let s = summary(&out);
    assert_eq!(s["phases"].as_array().unwrap().len(), 2);
    // the right support ends with phase `press`: one refactorisation, one more F* build
    assert_eq!(s["counters"]["stiffness_changes"], 1);
    assert_eq!(s["phases"][1]["stiffness_changes"], 1);
    let curves = csv(&out.join("curves.csv"));
    let f = |k: usize| curves[k]["force_n"].parse::<f64>().unwrap();
    // tolerance: the solver stops at a relative 1e-10
    assert!((f(0) - 2.0).abs() < 1e-8, "{}", f(0));
    assert!((f(1) - 3.0).abs() < 1e-8, "{}", f(1));
    // in phase `slide` the block slides back (pushed by the right-face traction)
    assert!(curves[3]["u_x [top_right]"].parse::<f64>().unwrap() < 0.0);
    assert!(
        s["stages"]["steps_with_tangential_reaction"]
            .as_u64()
            .unwrap()
            >= 2
    );
    let _ = std::fs::remove_dir_all(&out);
}

/// `examples/scenes/block_force.toml` (issue 16): a block with no support, held by contact,
/// loaded by resultant forces on a tied cap, pressed frictionless then sheared with Coulomb
/// friction from the phase's `laws`. Statics: `Σ r_n = P = 1` at every step and
/// `Σ r_t = −Q` (0, −0.1, −0.2); tolerance 1e-8: the solver stops at 1e-10 relative and the
/// floating equilibrium at 1e-11 of the forces.
#[test]
fn floating_block_scene_with_caps_and_laws_by_phase_balances() {
    let out = tmp("block_force");
    ok(&bipo(&[
        "run".as_ref(),
        scenes().join("block_force.toml").as_os_str(),
        "-q".as_ref(),
        "--out".as_ref(),
        out.as_os_str(),
    ]));
    let curves = csv(&out.join("curves.csv"));
    assert_eq!(curves.len(), 3);
    for (k, q) in [0.0, 0.1, 0.2].into_iter().enumerate() {
        let n = curves[k]["sum r_n (= P)"].parse::<f64>().unwrap();
        let t = curves[k]["sum r_t (= -Q)"].parse::<f64>().unwrap();
        assert!((n - 1.0).abs() < 1e-8, "step {}: Σ r_n = {n}", k + 1);
        assert!((t + q).abs() < 1e-8, "step {}: Σ r_t = {t}", k + 1);
    }
    // a push above μ P is an error that names the motion, not a NaN
    let text = std::fs::read_to_string(scenes().join("block_force.toml"))
        .unwrap()
        .replace("value = [0.2, 0.0]", "value = [0.4, 0.0]");
    let dir = tmp("block_force_slide");
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("slide.toml");
    std::fs::write(&scene, text).unwrap();
    let res = bipo(&[
        "run".as_ref(),
        scene.as_os_str(),
        "-q".as_ref(),
        "--out".as_ref(),
        dir.join("out").as_os_str(),
    ]);
    let err = String::from_utf8_lossy(&res.stderr);
    assert!(!res.status.success());
    assert!(
        err.contains("cannot balance the load along its translation x"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&out);
    let _ = std::fs::remove_dir_all(&dir);
}

/// `[solver] flexibility = "active-set"` solves the block without `F*` and gives the dense
/// path's numbers.
#[test]
fn block_scene_with_the_active_set_matches_the_dense_path() {
    let text = std::fs::read_to_string(scenes().join("block.toml")).unwrap();
    let dir = tmp("block_active");
    let run = |flexibility: &str| -> serde_json::Value {
        let scene = dir.join(format!("{flexibility}.toml"));
        // the block scene's [solver] table gets the key
        assert!(text.contains("[solver]\n"));
        let s = text.replacen(
            "[solver]\n",
            &format!("[solver]\nflexibility = \"{flexibility}\"\n"),
            1,
        );
        std::fs::write(&scene, s).unwrap();
        let out = dir.join(flexibility);
        ok(&bipo(&[
            "run".as_ref(),
            scene.as_os_str(),
            "--out".as_ref(),
            out.as_os_str(),
        ]));
        summary(&out)
    };
    let dense = run("dense");
    let active = run("active-set");
    assert_eq!(active["status"], "completed");
    assert_eq!(active["counters"]["flexibility_builds"], 0);
    assert_eq!(active["counters"]["active_set_steps"], 4);
    assert_eq!(dense["counters"]["active_set_steps"], 0);
    assert_eq!(dense["counters"]["flexibility_builds"], 1);
    let f = |s: &serde_json::Value| s["zones"][0]["final_force_n"].as_f64().unwrap();
    assert!(
        (f(&dense) - f(&active)).abs() < 1e-10,
        "{} vs {}",
        f(&dense),
        f(&active)
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// `bipo … | head -1`: the reader closes the pipe after one line; bipo must end with status 0
/// and no "internal error" (a `println!` would panic on the closed pipe, exit 101).
#[test]
fn a_closed_pipe_ends_quietly() {
    use std::io::{BufRead, BufReader};
    use std::process::Stdio;
    let problem = std::env::temp_dir().join(format!("bipo_pipe_{}.json", std::process::id()));
    // 1000 open contacts: 1000 table rows (85 kB), more than a pipe buffer (64 kB) holds, so
    // bipo is still writing when the reader is gone
    let n = 1000;
    let m = 2 * n;
    let mut text = String::from("{\"dim\": 2, \"W\": [");
    for i in 0..m {
        let row: Vec<&str> = (0..m).map(|j| if i == j { "1" } else { "0" }).collect();
        text += &format!("{}[{}]", if i > 0 { "," } else { "" }, row.join(","));
    }
    let q: Vec<&str> = (0..m)
        .map(|k| if k % 2 == 0 { "1" } else { "0.5" })
        .collect();
    text += &format!(
        "], \"q\": [{}], \"mu\": [{}]}}",
        q.join(","),
        vec!["0.3"; n].join(",")
    );
    std::fs::write(&problem, text).unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_bipo"))
        .arg("solve-local")
        .arg(&problem)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut first)
        .unwrap();
    // the reader is dropped here: the pipe is closed
    let out = child.wait_with_output().unwrap();
    let _ = std::fs::remove_file(&problem);
    assert!(first.contains("1000 contacts"), "{first}");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{:?}: {stderr}", out.status);
    assert!(!stderr.contains("internal error"), "{stderr}");
}

/// `[solver] adhesion_warm_start` is read: off, no step tries Newton from the previous step's
/// reactions; on (the default), the delamination keeps it on most of its 210 steps (206 since
/// the Jacobian's chain rule through the projection and the springs in ρ); the answers agree
/// to the solvers' tolerances.
#[test]
fn the_warm_start_key_switches_the_warm_start() {
    let dir = tmp("warm_start_key");
    let text = std::fs::read_to_string(scenes().join("delamination.toml")).unwrap();
    let run = |name: &str, extra: &str| {
        let scene = dir.join(format!("{name}.toml"));
        std::fs::write(
            &scene,
            text.replace("[solver]\n", &format!("[solver]\n{extra}")),
        )
        .unwrap();
        let out = dir.join(name);
        ok(&bipo(&[
            "run".as_ref(),
            scene.as_os_str(),
            "-q".as_ref(),
            "--out".as_ref(),
            out.as_os_str(),
        ]));
        summary(&out)
    };
    let on = run("on", "");
    let off = run("off", "adhesion_warm_start = false\n");
    let tried = |s: &serde_json::Value| {
        s["counters"]["adhesion_warm_starts"].as_u64().unwrap()
            + s["counters"]["adhesion_warm_start_failures"]
                .as_u64()
                .unwrap()
    };
    assert!(tried(&on) >= 1, "{}", on["counters"]);
    let kept = on["counters"]["adhesion_warm_starts"].as_u64().unwrap();
    assert!(kept >= 150, "{}", on["counters"]);
    assert_eq!(tried(&off), 0, "{}", off["counters"]);
    let force = |s: &serde_json::Value| s["zones"][0]["final_force_n"].as_f64().unwrap();
    let (a, b) = (force(&on), force(&off));
    assert!((a - b).abs() <= 1e-6 * a.abs().max(b.abs()), "{a} vs {b}");
}
