//! Issue 39, scenes: dynamic scenes (`[analysis] dynamic = true`) run by `bipo`, against closed
//! forms, with their energy balance, and their bad input refused at its key.
//!
//! - `tests/dynamic/bar.toml`: an elastic bar (plane stress P2 strip, ν = 0: a 1D bar, 100 cells
//!   along L = 1, h = 0.005, consistent mass) hits a rigid wall at v0 = 0.1 with e = 0 and
//!   θ = 1/2. One-dimensional wave theory (Graff 1975 §2.1, "Wave motion in elastic solids"):
//!   the contact lasts 2L/c = 2 (c = √(E/ρ) = 1), its force is ρ c A v0 = 0.01 and the bar
//!   leaves at v0. The library's own run of this bar is `issue_39_bar_impact_matches_wave_theory`
//!   (contact-solver); this one goes through the scene file, the CSV and the summary.
//! - `tests/dynamic/block_drop.toml`: a 3D column (P2 tetrahedra, 0.2 × 0.2 × 1, ν = 0, E = 100,
//!   ρ = 1: c = 10) falls at v0 = 1 from 0.05 above a rigid plane (Coulomb μ = 0.3): an exact
//!   free flight until the gap closes at t = 0.05, then the same wave as the bar (contact
//!   2L/c = 0.2, rebound v0).
//! - `examples/scenes/pile_hammer.toml`: a 2 ms force pulse (500 kN peak) on the head of the
//!   seed's pile (steel, 7.85 t/m³, c = √(E/ρ) ≈ 1955 m/s) in its soil, its shaft glued by the
//!   seed's RCCM interface: the head moves at σ/(ρ c) under the pulse (the impedance relation
//!   of a bar, Graff 1975 §2.1), the wave, reflected at the soft tip, is back at the head
//!   2 L_p / c ≈ 13.3 ms later, and the shaft debonds progressively.
//!
//! ```text
//!   wall |<- v0  [===== bar =====]            ┌─┐
//!                                             │ │ ↓ v0     column over a plane
//!                                             └─┘
//!                                           ═══════ z = 0
//! ```

use super::support::{bipo, csv, manifest, num, summary, tmp};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// `tests/dynamic/<name>`.
fn scene(name: &str) -> PathBuf {
    manifest("tests/dynamic").join(name)
}

/// Runs `scene` into a fresh directory; returns it and the rows of `dynamics.csv`.
fn run(scene: &Path, name: &str) -> (PathBuf, Vec<BTreeMap<String, String>>) {
    let out = tmp(name);
    let o = bipo(&[
        "run".as_ref(),
        scene.as_os_str(),
        "--quiet".as_ref(),
        "--out".as_ref(),
        out.as_os_str(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let rows = csv(&out.join("dynamics.csv"));
    (out, rows)
}

/// The first and last time with a normal force in `column`, and the number of such rows.
fn contact_span(rows: &[BTreeMap<String, String>], column: &str) -> (f64, f64, usize) {
    let on: Vec<f64> = rows
        .iter()
        .filter(|r| num(r, column) > 0.0)
        .map(|r| num(r, "time"))
        .collect();
    (on[0], *on.last().unwrap(), on.len())
}

/// The largest |balance_relative| over the rows.
fn worst_balance(rows: &[BTreeMap<String, String>]) -> f64 {
    rows.iter()
        .map(|r| num(r, "balance_relative").abs())
        .fold(0.0, f64::max)
}

#[test]
fn issue_39_bar_hits_a_wall_from_a_scene() {
    let (out, rows) = run(&scene("bar.toml"), "issue39_bar");
    let h = 0.005;
    let (first, last, n) = contact_span(&rows, "normal_force_wall");
    // one interval of contact (no release and re-impact)
    assert_eq!(n, ((last - first) / h).round() as usize + 1);
    let duration = n as f64 * h;
    // the plateau: the middle 80 % of the contact
    let forces: Vec<f64> = rows
        .iter()
        .map(|r| num(r, "normal_force_wall"))
        .filter(|&f| f > 0.0)
        .collect();
    let plateau = &forces[n / 10..n - n / 10];
    let mean = plateau.iter().sum::<f64>() / plateau.len() as f64;
    let rebound = num(rows.last().unwrap(), "v_body_x");
    eprintln!(
        "bar from a scene: contact {duration} (2L/c = 2), plateau {mean:.6e} (ρcAv0 = 0.01), \
         rebound {rebound:.5} (v0 = 0.1), balance {:.1e}",
        worst_balance(&rows)
    );
    // each within 2 % (the issue's bound; measured 0.5 %, 0.003 %, 1.05 %, the library's
    // figures for this mesh and step): the duration counts whole steps (one is 0.25 % of 2L/c)
    assert!((duration - 2.0).abs() < 0.02 * 2.0, "{duration}");
    assert!((mean - 0.01).abs() < 0.02 * 0.01, "{mean}");
    assert!((rebound - 0.1).abs() < 0.02 * 0.1, "{rebound}");
    // the balance closes to round-off at every step (measured 5e-13)
    assert!(worst_balance(&rows) <= 1e-8);
    // t = 0 is the initial state: T0 = ½ m v0² = ½ · 0.1 · 0.01
    let t0 = num(&rows[0], "kinetic");
    assert!((t0 - 5e-4).abs() < 1e-12 * 5e-4, "{t0}");
    assert_eq!(rows.len(), 521); // t = 0 and 520 steps
    let s = summary(&out);
    assert_eq!(s["status"], "completed");
    assert_eq!(s["analysis"]["dynamic"], true);
    assert_eq!(s["analysis"]["mass"], "consistent");
    assert_eq!(s["zones"][0]["restitution"], 0.0);
    assert!(s["max_residual_relative"].as_f64().unwrap() <= 1e-8);
    for f in [
        "energies.svg",
        "contact_force.svg",
        "velocity.svg",
        "mesh.pvd",
    ] {
        assert!(out.join(f).exists(), "{f}");
    }
    // the VTK series every 100 steps and the last (t = 0, 100, …, 500, 520): velocities in it
    let vtu = std::fs::read_to_string(out.join("mesh_0001.vtu")).unwrap();
    assert!(vtu.contains("Name=\"v\""), "no velocity field");
    assert!(out.join("mesh_0006.vtu").exists() && !out.join("mesh_0007.vtu").exists());
}

#[test]
fn issue_39_block_drops_on_a_plane_in_3d() {
    let (out, rows) = run(&scene("block_drop.toml"), "issue39_block");
    let h = 0.0025;
    // free flight until the gap closes at t = 0.05: v = −v0 exactly (a rigid translation is in
    // the kernel of K: round-off only, measured 5e-15)
    for r in rows.iter().filter(|r| num(r, "time") < 0.05 - 1e-9) {
        assert!((num(r, "v_body_z") + 1.0).abs() < 1e-12, "{r:?}");
        assert_eq!(num(r, "normal_force_ground"), 0.0);
    }
    let (first, last, n) = contact_span(&rows, "normal_force_ground");
    // Moreau's index set takes the contact in the step after the gap closes
    assert!((first - (0.05 + h)).abs() < 1e-9, "{first}");
    let duration = n as f64 * h;
    let rebound = num(rows.last().unwrap(), "v_body_z");
    eprintln!(
        "3D column: contact {first} → {last} ({duration}, 2L/c = 0.2), rebound {rebound:.4} \
         (v0 = 1), balance {:.1e}",
        worst_balance(&rows)
    );
    // the P2 column, 20 cells along L, h = L/(16 c): measured 2.5 % long and 3.2 % slow on
    // rebound (the bar of the issue reaches 2 % with 100 cells); 5 % says the wave is right
    assert!((duration - 0.2).abs() < 0.05 * 0.2, "{duration}");
    assert!(rebound > 0.95 && rebound <= 1.0, "{rebound}");
    // friction stays in Coulomb's cone: |Σ r_t| ≤ Σ |r_t| ≤ μ Σ r_n (the tetrahedra break the
    // column's symmetry a little: measured |Σ r_t| ≤ 0.8 % of the peak normal force)
    for r in &rows {
        let (f_n, f_t) = (
            num(r, "normal_force_ground"),
            num(r, "tangential_force_ground"),
        );
        assert!(f_t <= 0.3 * f_n * (1.0 + 1e-9) + 1e-15, "{r:?}");
    }
    assert!(worst_balance(&rows) <= 1e-8);
    assert_eq!(summary(&out)["status"], "completed");
}

#[test]
fn issue_39_pile_hammer_shows_the_wave_and_its_reflection() {
    let (out, rows) = run(
        &manifest("../../examples/scenes/pile_hammer.toml"),
        "issue39_pile",
    );
    let v = |r: &BTreeMap<String, String>| num(r, "v_pile_head_y");
    let at = |t0: f64, t1: f64| {
        rows.iter()
            .filter(|r| (t0..t1).contains(&num(r, "time")))
            .min_by(|a, b| v(a).total_cmp(&v(b)))
            .map(|r| (num(r, "time"), v(r)))
            .unwrap()
    };
    // the blow: σ = 8730 kPa at the pulse's peak (t = 1 ms), v = σ / (ρ c), c = √(E/ρ)
    let (rho, young, sigma) = (7.85_f64, 3e7_f64, 8730.0);
    let c = (young / rho).sqrt();
    let (t1, v1) = at(0.0, 0.003);
    // the return: the same peak 2 L_p / c later
    let (t2, v2) = at(0.005, 0.02);
    eprintln!(
        "pile hammer: head {v1:.4} m/s at {t1} s (σ/(ρc) = {:.4}), back {v2:.4} at {t2} s \
         (1 ms + 2L/c = {:.4} s), balance {:.1e}",
        -sigma / (rho * c),
        0.001 + 26.0 / c,
        worst_balance(&rows)
    );
    // within 3 %: the pile is a bar in 1D theory, but its soil and ν = 0.3 add a little
    // stiffness and mass at the head (measured 1.2 %)
    assert!(
        (v1 + sigma / (rho * c)).abs() < 0.03 * sigma / (rho * c),
        "{v1}"
    );
    assert!((t1 - 0.001).abs() < 1.5e-4, "{t1}");
    // the reflection at the soft tip keeps the velocity's sign; it is back after 2 L_p / c
    // within 5 % (the head's peak is sampled every 0.1 ms; measured 14.4 ms against 14.3)
    assert!(v2 < -0.5 * v1.abs(), "{v2}");
    assert!((t2 - (0.001 + 26.0 / c)).abs() < 0.05 * 26.0 / c, "{t2}");
    assert!(worst_balance(&rows) <= 1e-8);
    // the RCCM shaft debonds progressively as the waves pass: β never rises (damage is
    // irreversible), falls well below 1 (measured 0.33 at 40 ms), and the energy it releases
    // is in the balance (measured 3.8e-3 of the blow's 3.0e-2)
    let beta: Vec<f64> = rows.iter().map(|r| num(r, "beta_shaft")).collect();
    assert_eq!(beta[0], 1.0);
    assert!(beta.windows(2).all(|w| w[1] <= w[0] + 1e-12));
    assert!(*beta.last().unwrap() < 0.5, "{:?}", beta.last());
    assert!(num(rows.last().unwrap(), "damage") > 0.0);
    let s = summary(&out);
    assert_eq!(s["status"], "completed");
    assert!(s["zones"][0]["mean_beta"].as_f64().unwrap() < 0.5);
}

/// `block_drop.toml` with each `(from, to)` replaced, written to a fresh directory and run;
/// returns the output directory and the rows of `dynamics.csv`.
fn block_variant(edits: &[(&str, &str)], name: &str) -> (PathBuf, Vec<BTreeMap<String, String>>) {
    let mut text = std::fs::read_to_string(scene("block_drop.toml")).unwrap();
    for (from, to) in edits {
        assert!(text.contains(from), "{from}");
        text = text.replacen(from, to, 1);
    }
    let path = tmp(name).join("variant.toml");
    std::fs::write(&path, text).unwrap();
    run(&path, name)
}

#[test]
fn issue_39_loads_follow_their_curves_in_time() {
    // a body force b(t) = −10 t / 0.3 along z (ρ = 1): until the contact the column flies as a
    // rigid body, v(t) = −v0 − 10 t² / (2 · 0.3). The consistent body force of a uniform b is
    // M 1 b/ρ exactly, K 1 = 0, and the load taken at each step's midpoint t_k + h/2 (θ = 1/2)
    // sums a linear b exactly: the closed form holds to round-off.
    let (_, rows) = block_variant(
        &[(
            "[[contact]]",
            "[functions]\nramp = [[0.0, 0.0], [0.3, 1.0]]\n\n[[loads]]\ntype = \"body_force\"\n\
             value = [0.0, 0.0, -10.0]\nfunction = \"ramp\"\n\n[[contact]]",
        )],
        "issue39_ramp",
    );
    let mut checked = 0;
    for r in rows.iter().filter(|r| num(r, "time") < 0.045) {
        let t = num(r, "time");
        let exact = -1.0 - 10.0 * t * t / (2.0 * 0.3);
        // round-off of ≤ 18 steps of a 500-dof solve (measured 5e-15)
        assert!((num(r, "v_body_z") - exact).abs() < 1e-12, "{r:?}");
        checked += 1;
    }
    assert_eq!(checked, 18); // t = 0, 0.0025, …, 0.0425
    // the work of the loads (positive during the fall) enters the balance, which closes
    assert!(num(&rows[17], "external_work") > 0.0);
    assert!(worst_balance(&rows) <= 1e-8);
}

#[test]
fn issue_39_damped_balance_closes() {
    // Rayleigh damping, θ = 3/4 (numerical dissipation) and the lumped mass: every term of the
    // balance is at work, and it closes at every step
    let (out, rows) = block_variant(
        &[
            (
                "mass = \"consistent\"",
                "mass = \"lumped\"\ntheta = 0.75\nrayleigh_alpha = 2.0\nrayleigh_beta = 1e-4",
            ),
            (
                "law = { type = \"coulomb\", mu = 0.3 }",
                "law = { type = \"coulomb\", mu = 0.3, restitution = 0.5 }",
            ),
        ],
        "issue39_damped",
    );
    let last = rows.last().unwrap();
    for key in ["damping", "numerical"] {
        assert!(num(last, key) > 0.0, "{key}: {last:?}");
    }
    // the contacts' work is in the balance too; with e = 0.5 > (1 − θ)/θ = 1/3 the impacts'
    // v_θ,n = (1 − θ − θe) v_n,k has the sign of the rebound, so r_n v_θ,n > 0: the scheme's
    // impact law gives energy (measured 3e-4, against 3e-3 of numerical dissipation)
    assert!(num(last, "contact_dissipation") != 0.0);
    // round-off (measured 7e-14); what the balance leaves is not the dissipations' size (≥ 1e-3)
    assert!(worst_balance(&rows) <= 1e-8);
    let s = summary(&out);
    assert_eq!(s["analysis"]["mass"], "lumped");
    assert_eq!(s["analysis"]["theta"], 0.75);
    assert_eq!(s["zones"][0]["restitution"], 0.5);
    // the dissipations take energy out: T + V ends below T0
    let e = &s["energy"];
    let left = e["kinetic"].as_f64().unwrap() + e["strain"].as_f64().unwrap();
    assert!(left < e["initial"].as_f64().unwrap());
}

/// `bipo check` of `bar.toml` with `from` replaced by `to`: it must fail (status 2, bad input)
/// and name `key`.
fn refused(from: &str, to: &str, key: &str) {
    let text = std::fs::read_to_string(scene("bar.toml")).unwrap();
    assert!(text.contains(from), "{from}");
    let dir = tmp("issue39_bad");
    let path = dir.join("bad.toml");
    std::fs::write(&path, text.replacen(from, to, 1)).unwrap();
    let o = bipo(&["check".as_ref(), path.as_os_str()]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{to}: {stderr}");
    assert!(
        stderr.contains(&format!("`{key}`")),
        "{to}: expected `{key}` in {stderr}"
    );
}

#[test]
fn issue_39_scenes_captures_errors() {
    let theta = "theta = 0.5";
    refused(theta, "theta = 0.4", "analysis.theta");
    refused(theta, "theta = 1.2", "analysis.theta");
    let e = "restitution = 0.0";
    refused(e, "restitution = 1.5", "contact[0].law.restitution");
    refused(e, "restitution = -0.1", "contact[0].law.restitution");
    refused(e, "restitution = nan", "contact[0].law.restitution");
    let rho = "density = 1.0";
    refused(rho, "density = 0.0", "materials[0].density");
    refused(rho, "density = -7850.0", "materials[0].density");
    refused(rho, "", "materials[0]");
    let h = "time_step = 0.005";
    refused(h, "time_step = 3.0", "analysis.time_step");
    refused(h, "time_step = 0.0", "analysis.time_step");
    refused(h, "time_step = -0.005", "analysis.time_step");
    let v = "initial_velocity = [-0.1, 0.0]";
    refused(
        v,
        "initial_velocity = [nan, 0.0]",
        "materials[0].initial_velocity[0]",
    );
    refused(
        v,
        "initial_velocity = [-0.1, inf]",
        "materials[0].initial_velocity[1]",
    );
    refused(
        v,
        "initial_velocity = [-0.1, 0.0, 0.0]",
        "materials[0].initial_velocity",
    );
    // what the dynamic path does not serve, at its key
    let geostatic = "[initial_stress]\ntype = \"geostatic\"\ngamma = 1.0\nk0 = 0.5\n\n[output]";
    refused("[output]", geostatic, "initial_stress");
    refused(
        "[output]",
        "[[supports]]\nset = \"right\"\ncomponent = \"y\"\nvalue = 0.1\n\n[output]",
        "supports[0].value",
    );
    refused(
        "[output]",
        "[steps]\ncount = 2\nduration = 1.0\n\n[output]",
        "steps",
    );
    // and the dynamic keys in a static scene
    refused("dynamic = true", "dynamic = false", "analysis.time_step");
}
