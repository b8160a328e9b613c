//! Issue 40, scenes: a plastic material (`type = "drucker-prager"`) run by `bipo` through the
//! global Newton around contact, its collapse load against Prandtl, and its bad input refused
//! at its key.
//!
//! - `examples/scenes/footing_dp.toml`: a rigid rough strip footing (its nodes prescribed) on a
//!   weightless soil resting on a rigid base (the contact), with
//!   `φ = 0`, `c = 1` (von Mises, plane-strain cone: `k = c`), half model, the mesh of fem-core's
//!   `issue_40_strip_footing` (P2, 840 elements graded 40 : 1 towards the footing edge).
//!   Prandtl (1920): `q_u = (2 + π) c`; the mesh gives about +2 % (fem-core's measurement on the
//!   same mesh), so the bound is issue 40's 3 %.
//! - a small block pressed on a rigid line carries every refusal: θ > φ, φ ≥ 90°, a negative
//!   cohesion, a geostatic state outside the yield surface (named with its region, element and
//!   point), and a step that does not converge after its cuts (the last converged state kept
//!   and written, exit status 1).

use super::support::{bipo, csv, num, scenes, summary, tmp};
use std::path::{Path, PathBuf};
use std::process::Output;

/// A 1 × 1 P2 block (plane strain) of Drucker–Prager soil pressed by its top onto a rigid
/// line; `{material}` and `{analysis}` are filled in by the tests.
const BLOCK: &str = r#"
[mesh]
generator = "rectangle"
element = "P2"
x = [0.0, 1.0]
nx = 2
y = [0.0, 1.0]
ny = 2

[analysis]
type = "plane_strain"
{analysis}

[[materials]]
region = 0
young = 100.0
poisson = 0.3
{material}

[functions]
ramp = [[0.0, 0.0], [1.0, 1.0]]

[[supports]]
set = "left"
component = "x"

[[supports]]
name = "press"
set = "top"
component = "y"
value = -0.05
function = "ramp"

[[contact]]
name = "base"
contactor = "bottom"
target = { type = "line", a = [-1.0, 0.0], b = [2.0, 0.0] }
law = { type = "signorini" }
alert_distance = 0.01

[steps]
count = 4
duration = 1.0
"#;

/// The block with `material` keys and `analysis` keys, written to a fresh directory.
fn block(name: &str, material: &str, analysis: &str, extra: &str) -> (PathBuf, PathBuf) {
    let dir = tmp(name);
    let text = BLOCK
        .replace("{material}", material)
        .replace("{analysis}", analysis)
        + extra;
    let path = dir.join("block.toml");
    std::fs::write(&path, text).unwrap();
    (dir, path)
}

/// `bipo <cmd> scene [--quiet --out dir]`.
fn bipo_on(cmd: &str, scene: &Path, out: Option<&Path>) -> Output {
    let mut args = vec![cmd.as_ref(), scene.as_os_str()];
    if let Some(o) = out {
        args.extend(["--quiet".as_ref(), "--out".as_ref(), o.as_os_str()]);
    }
    bipo(&args)
}

/// `bipo check` fails with status 2 and a message holding each of `fragments`.
fn refused(name: &str, material: &str, extra: &str, fragments: &[&str]) {
    let (_, path) = block(name, material, "", extra);
    let o = bipo_on("check", &path, None);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{name}: {err}");
    for f in fragments {
        assert!(err.contains(f), "{name}: `{f}` not in {err}");
    }
}

const DP: &str = "type = \"drucker-prager\"\nfriction_angle = 30.0\ncohesion = 1.0";

#[test]
fn issue_40_bad_plastic_keys_are_refused_at_their_key() {
    refused(
        "dilatancy",
        &format!("{DP}\ndilatancy_angle = 35.0"),
        "",
        &["materials[0].dilatancy_angle", "must not exceed the friction angle"],
    );
    refused(
        "phi90",
        "type = \"drucker-prager\"\nfriction_angle = 90.0\ncohesion = 1.0",
        "",
        &["materials[0].friction_angle", "[0, 90)"],
    );
    refused(
        "cohesion",
        "type = \"drucker-prager\"\nfriction_angle = 30.0\ncohesion = -1.0",
        "",
        &["materials[0].cohesion", "c ≥ 0"],
    );
    refused(
        "elastic_keys",
        "cohesion = 1.0",
        "",
        &["materials[0].cohesion", "is not a key of a material of type \"elastic\""],
    );
    refused(
        "von_mises",
        "type = \"von-mises\"\nyield_stress = 0.0",
        "",
        &["materials[0].yield_stress", "> 0"],
    );
    // K0 = 0 under a deep surface: σ_h = 0, σ_v = −γ h far beyond the cone of c = 1
    refused(
        "geostatic",
        &format!("{DP}\nunit_weight = 20.0"),
        "\n[initial_stress]\ntype = \"geostatic\"\ngamma = 20.0\nk0 = 0.0\nz_surface = 10.0\n",
        &[
            "initial_stress",
            "outside the yield surface of region 0 (`materials[0]`) at element",
            "point",
        ],
    );
    // the Newton's keys belong to a plastic scene
    let (_, path) = block("newton_elastic", "", "newton = { tol = 1e-8 }", "");
    let o = bipo_on("check", &path, None);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("analysis.newton"), "{err}");
}

/// The block yields (c = 0.1, φ = θ = 30°: associated, the symmetric tangent the reduced
/// solver needs) and its Newton converges: the run writes the plastic
/// fields and every step's residuals, and the pressing force is the zone's.
#[test]
fn issue_40_plastic_block_runs_and_writes_its_fields() {
    let material = "type = \"drucker-prager\"\nfriction_angle = 30.0\n\
                    cohesion = 0.1";
    // 1e-8: the contact solve's tolerance (1e-10 of the reactions) leaves a floor near 1e-9
    // in the equilibrium residual once the block flows (measured 1.0e-9 to 1.7e-9)
    let (dir, path) = block("block_run", material, "newton = { tol = 1e-8 }", "");
    let out = dir.join("out");
    let o = bipo_on("run", &path, Some(&out));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let s = summary(&out);
    assert_eq!(s["status"], "completed");
    assert_eq!(s["steps"], 4);
    let reports = s["step_reports"].as_array().unwrap();
    assert_eq!(reports.len(), 4);
    for r in reports {
        let residuals = r["residuals"].as_array().unwrap();
        assert!(residuals.last().unwrap().as_f64().unwrap() <= 1e-8, "{r}");
    }
    assert!(s["max_equivalent_plastic_strain"].as_f64().unwrap() > 0.0, "{s}");
    let rows = csv(&out.join("steps.csv"));
    assert_eq!(rows.len(), 4);
    assert!(num(&rows[3], "newton_iterations") >= 1.0);
    let vtu = std::fs::read_to_string(out.join("mesh_0001.vtu")).unwrap();
    for field in [
        "equivalent_plastic_strain",
        "volumetric_plastic_strain",
        "yield_state",
        "stress",
    ] {
        assert!(vtu.contains(field), "{field}");
    }
}

/// A step that cannot converge (one Newton correction allowed, no cut, a block that yields):
/// the error names the Newton's keys, the run exits 1, and the last converged state is written.
#[test]
fn issue_40_step_that_does_not_converge_keeps_the_last_state() {
    let material = "type = \"drucker-prager\"\nfriction_angle = 30.0\ncohesion = 0.1";
    let analysis = "newton = { max_iterations = 1, max_cuts = 0 }";
    let (dir, path) = block("no_convergence", material, analysis, "");
    let out = dir.join("out");
    let o = bipo_on("run", &path, Some(&out));
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("did not converge"), "{err}");
    assert!(err.contains("max_cuts"), "{err}");
    let s = summary(&out);
    assert_eq!(s["status"], "failed");
    assert!(s["error"].as_str().unwrap().contains("did not converge"));
    assert!(out.join("mesh.pvd").exists());
    assert!(out.join("mesh_0000.vtu").exists());
}

/// Prandtl's `(2 + π) c` within 3 % (module docs), on the plateau: the last two steps' footing
/// forces within 1 % of each other.
#[test]
fn issue_40_footing_collapse_works() {
    let out = tmp("footing_dp");
    let o = bipo_on("run", &scenes().join("footing_dp.toml"), Some(&out));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let rows = csv(&out.join("curves.csv"));
    let n = rows.len();
    // the footing pushes down: its support's reaction is −q b (b = 1)
    let (q, q_before) = (
        -num(&rows[n - 1], "footing reaction"),
        -num(&rows[n - 2], "footing reaction"),
    );
    let prandtl = 2.0 + std::f64::consts::PI;
    eprintln!("footing: q/c = {q} ({:+.2} %)", 100.0 * (q / prandtl - 1.0));
    assert!((q - q_before).abs() < 1e-2 * q, "{q_before} → {q}");
    assert!((q - prandtl).abs() < 0.03 * prandtl, "q/c = {q}");
    // the rigid base carries the footing's force (the soil is weightless; tolerance: the
    // Newton's residual, 1e-9 of the forces, with margin)
    let base = num(&rows[n - 1], "base force");
    assert!((base - q).abs() < 1e-6 * q, "{base} against {q}");
}
