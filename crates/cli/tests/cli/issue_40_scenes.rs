//! Issue 40, scenes: a plastic material (`type = "drucker-prager"`) run by `bipo` through the
//! global Newton around contact, its collapse load against Prandtl, and its bad input refused
//! at its key.
//!
//! - `examples/scenes/footing_dp.toml`: a rigid rough strip footing (a tied set under a resultant
//!   force) on a weightless soil resting on a rigid base (the contact), with
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
        &[
            "materials[0].dilatancy_angle",
            "must not exceed the friction angle",
        ],
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
        &[
            "materials[0].cohesion",
            "is not a key of a material of type \"elastic\"",
        ],
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
    assert!(
        s["max_equivalent_plastic_strain"].as_f64().unwrap() > 0.0,
        "{s}"
    );
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

/// Prandtl's `(2 + π) c` within 3 % (module docs): the shipped scene loads the footing to
/// `5.2 c b`, `+1.1 %` over Prandtl and below the mesh's own collapse load (`5.245 c b`, `+2.0 %`,
/// fem-core's `issue_40_strip_footing_prandtl_works` on this mesh), and the soil carries it at
/// the knee of its load–settlement curve: the last step settles at least 15 times more per unit
/// load than the first, elastic, one (measured 22 times). Raising the force to `5.4 c b` (same
/// 20 steps, 8 halvings) stops the run at `5.13 c b` (`−0.2 %`, measured once): with steps of
/// `0.27 c b` the Newton stops converging just before the collapse load, so that run bounds
/// nothing and the test keeps the completed one. Every step's Newton meets its tolerance.
#[test]
fn issue_40_footing_collapse_works() {
    let out = tmp("footing_dp");
    let o = bipo_on("run", &scenes().join("footing_dp.toml"), Some(&out));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let s = summary(&out);
    assert_eq!(s["status"], "completed");
    for r in s["step_reports"].as_array().unwrap() {
        let last = r["residuals"]
            .as_array()
            .unwrap()
            .last()
            .unwrap()
            .as_f64()
            .unwrap();
        assert!(last <= 1e-9, "{r}");
    }
    let rows = csv(&out.join("curves.csv"));
    let n = rows.len();
    assert_eq!(n, 20);
    let q = 5.2 * num(&rows[n - 1], "load_factor");
    let prandtl = 2.0 + std::f64::consts::PI;
    let settle = |k: usize| -num(&rows[k], "footing u_y");
    let load = |k: usize| 5.2 * num(&rows[k], "load_factor");
    let first = settle(0) / load(0);
    let last = (settle(n - 1) - settle(n - 2)) / (load(n - 1) - load(n - 2));
    eprintln!(
        "footing: q/c = {q:.4} ({:+.2} %) carried, settlement {:.3e}, compliance {:.1} × the elastic",
        100.0 * (q / prandtl - 1.0),
        settle(n - 1),
        last / first
    );
    assert!((q - prandtl).abs() < 0.03 * prandtl, "q/c = {q}");
    assert!(last > 15.0 * first, "{last} vs {first}");
    assert!(out.join("mesh.pvd").exists());
}

/// Measured (why `footing_dp.toml` is load-controlled): fem-core's own Newton
/// (`plastic::newton`) on the footing mesh with the footing's nodes prescribed, each step
/// started from the last converged state without a predictor (as the contact-solver's Newton
/// starts its steps). At `δ = 0.001 b` (ν = 0.3 or 0.49, `NU=…`) it diverges: relative
/// residuals 0.97, 3.4e-4, 7.1e-4, 3.8e-3, 0.077, 0.999, then a tangent that is not positive
/// definite (fem-core's `issue_40_strip_footing` predicts each step from the last increment).
#[test]
#[ignore]
fn issue_40_footing_displacement_control_measured() {
    use fem_core::plastic::newton::{self, NewtonSettings};
    use fem_core::plastic::{ConstitutivePoint, DruckerPrager, PlasticModel};
    use fem_core::{Component, Idealization, LinearElasticModel, Material, Supports};
    use std::sync::Arc;
    let mesh = fem_core::gmsh::read_msh(&scenes().join("footing_dp.msh")).unwrap();
    let set = |n: &str| mesh.node_set(n).unwrap().to_vec();
    let footing = set("footing");
    let mut s = Supports::new();
    s.fix(&set("left"), Component::X)
        .fix(&set("right"), Component::X)
        .fix(&set("bottom"), Component::X)
        .fix(&set("bottom"), Component::Y)
        .fix(&footing, Component::X)
        .fix(&footing, Component::Y);
    let nu: f64 = std::env::var("NU").map_or(0.3, |v| v.parse().unwrap());
    let m = Material::new(1e4, nu, 0.0).unwrap();
    let el = LinearElasticModel::new(mesh, Idealization::PlaneStrain, &[(1, m)], s).unwrap();
    let law: Arc<dyn ConstitutivePoint> = Arc::new(DruckerPrager::von_mises(1e4, nu, 1.0).unwrap());
    let mut body = PlasticModel::new(el, &[(1, law)]).unwrap();
    let mut u = vec![0.0; fem_core::Structure::dof_count(&body)];
    let settings = NewtonSettings {
        steps: 1,
        max_iterations: 30,
        max_cuts: 0,
        tolerance: 1e-9,
    };
    for k in 1..=20 {
        let d = 0.001 * k as f64;
        body.set_prescribed(&footing, Component::Y, -d).unwrap();
        match newton::solve(&mut body, &mut u, 0.0, 0.0, &settings) {
            Ok(r) => eprintln!(
                "δ = {d}: {:?}, R = {}",
                r.steps.last().unwrap().residuals,
                body.reaction(&footing, Component::Y).unwrap()
            ),
            Err(fem_core::FemError::NotConverged { report, .. }) => {
                eprintln!("δ = {d}: {:?}", report.steps.last().unwrap().residuals);
                break;
            }
            Err(e) => panic!("{e}"),
        }
    }
}

/// 3D and axisymmetric limit loads through `bipo` (issue 40). `tests/solid/plastic_block_vm.toml`:
/// a von Mises block of 48 P2 tetrahedra (`σ_y = 1`, `E = 100`, yield at `δ = 0.01`), its top
/// lowered by 0.05 in 4 steps onto a frictionless rigid plane, lateral faces free: uniaxial
/// stress, so every step past yield carries `σ_y A = 1`. `tests/scenes/plastic_block_axi.toml`:
/// a Drucker–Prager cylinder (`φ = θ = 30°`, `c = 0.1`, radius and height 1, P2) pressed the
/// same way: unconfined compression, `q = c / (√(2/3) / k_d − tan φ / 3) = 0.19943`, per
/// radian `q / 2`. Before the Newton's springs on the closed contacts (`newton_springs.rs` in
/// contact-solver) both runs stopped at their first yield (the tangent of a body at its limit
/// load is singular but for the contact). 1e-7: the scenes' Newton tolerance (1e-8 of the
/// forces) over the base's reactions.
#[test]
fn issue_40_plastic_blocks_reach_their_limit_load_3d_and_axisymmetric() {
    let phi = 30f64.to_radians();
    let k_d = (6.0 / (3.0 + 4.0 * phi.tan().powi(2))).sqrt();
    let q = 0.1 / ((2.0f64 / 3.0).sqrt() / k_d - phi.tan() / 3.0);
    for (name, scene, limit) in [
        ("plastic_3d", "tests/solid/plastic_block_vm.toml", 1.0),
        (
            "plastic_axi",
            "tests/scenes/plastic_block_axi.toml",
            0.5 * q,
        ),
    ] {
        let out = tmp(name);
        let scene = super::support::manifest(scene);
        let o = bipo_on("run", &scene, Some(&out));
        assert!(
            o.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        let s = summary(&out);
        assert_eq!(s["status"], "completed", "{name}");
        assert_eq!(s["steps"], 4, "{name}");
        let rows = csv(&out.join("curves.csv"));
        let force = num(rows.last().unwrap(), "force_n (base)");
        eprintln!("{name}: F = {force:.12} against {limit:.12}");
        assert!(
            (force - limit).abs() <= 1e-7 * limit,
            "{name}: {force} vs {limit}"
        );
    }
}
