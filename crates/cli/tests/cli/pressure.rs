//! The recovered contact pressure of `bipo run` (issue 36): `pressure.csv`, the VTK point data
//! and `pressure.svg` of the two Hertz scenes, against Johnson (1985): a cylinder on a flat
//! (§ 5.6, `a = √(4PR/(πE*))`, `p0 = 2P/(πa)`, plane strain, half model) and a sphere on a
//! flat (§ 4.2, `a = (3PR/(4E*))^⅓`, `p0 = 3P/(2πa²)`, quarter model), each for the measured
//! load `P`.
//!
//! The trap: in 3D, `pressure = r_n / area` of `contacts.csv` is 0 at the corners of the P2
//! faces (their consistent area is 0), the centre of the contact included; the field of
//! `pressure.csv` (`M_Γ p = r_n`) is not.

use super::support::{csv, num};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

fn scene(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/scenes")
        .join(name)
}

fn run(scene: &Path, name: &str) -> PathBuf {
    let out = std::env::temp_dir().join(format!("bipo_pressure_{name}_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let o = Command::new(env!("CARGO_BIN_EXE_bipo"))
        .arg("run")
        .arg(scene)
        .arg("-q")
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    out
}

#[test]
fn issue_36_hertz_cylinder_pressure_field_follows_the_ellipse() {
    let out = run(&scene("hertz.toml"), "cylinder");
    let rows = csv(&out.join("pressure.csv"));
    let last: Vec<_> = rows.iter().filter(|r| r["step"] == "2").collect();
    assert!(!last.is_empty());
    // P from the reactions: the field's consistent forces sum to Σ r_n (half model)
    let contacts = csv(&out.join("contacts.csv"));
    let sum_rn: f64 = contacts
        .iter()
        .filter(|r| r["step"] == "2")
        .map(|r| num(r, "r_n"))
        .sum();
    let p = 2.0 * sum_rn;
    let (radius, e_star) = (100.0, 1000.0 / (1.0 - 0.09));
    let a = (4.0 * p * radius / (std::f64::consts::PI * e_star)).sqrt();
    let p0 = 2.0 * p / (std::f64::consts::PI * a);
    let centre = last
        .iter()
        .min_by(|u, v| num(u, "x").abs().total_cmp(&num(v, "x").abs()))
        .unwrap();
    assert!(num(centre, "x").abs() < 1e-12, "a node on the axis");
    let ratio = num(centre, "p") / p0;
    println!(
        "hertz.toml: p(0) = {}, p0 = {p0}, ratio {ratio}",
        num(centre, "p")
    );
    // 3 %: the arc's P2 nodes are 0.094 apart, a ≈ 1 spans 5 quadratic sides, and the
    // recovery is exact for a quadratic: what is left is the ellipse's curvature at the centre
    assert!((ratio - 1.0).abs() < 0.03, "p(0)/p0 = {ratio}");
    // inside the contact the field follows the ellipse; outside, it is small
    for r in &last {
        let x = num(r, "x");
        let hertz = p0 * (1.0 - (x / a).powi(2)).max(0.0).sqrt();
        if x < 0.5 * a {
            assert!((num(r, "p") - hertz).abs() < 0.05 * p0, "x = {x}: {r:?}");
        }
        if x > 2.0 * a {
            assert!(num(r, "p").abs() < 0.02 * p0, "x = {x}: {r:?}");
        }
    }
    let vtu = std::fs::read_to_string(out.join("interface_0001.vtu")).unwrap();
    assert!(vtu.contains("pressure_field") && vtu.contains("shear_field"));
    let svg = std::fs::read_to_string(out.join("pressure.svg")).unwrap();
    assert!(svg.contains("Hertz: a = "), "the ellipse is drawn");
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn issue_36_sphere_pressure_field_is_not_zero_at_p2_corners() {
    let out = run(&scene("sphere_3d.toml"), "sphere");
    let contacts = csv(&out.join("contacts.csv"));
    let at_origin = |r: &&BTreeMap<String, String>| {
        r["step"] == "2" && ["x", "y", "z"].iter().all(|k| num(r, k).abs() < 1e-12)
    };
    let centre = contacts
        .iter()
        .find(at_origin)
        .expect("a contact at the origin");
    // the old trap: a P2 corner, its consistent area 0, its per-node pressure 0
    assert_eq!(num(centre, "area"), 0.0);
    assert_eq!(num(centre, "pressure"), 0.0);
    let sum_rn: f64 = contacts
        .iter()
        .filter(|r| r["step"] == "2")
        .map(|r| num(r, "r_n"))
        .sum();
    let p = 4.0 * sum_rn;
    let e_star = 1000.0 / (1.0 - 0.09);
    let a = (3.0 * p * 1.0 / (4.0 * e_star)).cbrt();
    let p0 = 3.0 * p / (2.0 * std::f64::consts::PI * a * a);
    let field = csv(&out.join("pressure.csv"));
    let centre = field
        .iter()
        .find(at_origin)
        .expect("the origin is on the face");
    let ratio = num(centre, "p") / p0;
    println!(
        "sphere_3d.toml: p(0) = {}, p0 = {p0}, ratio {ratio}",
        num(centre, "p")
    );
    // 10 %: a = 0.05 spans 1.4 of the graded P2 cells at the centre (0.035 wide), and the
    // L² projection of the ellipse onto so few quadratic cells flattens its peak (measured
    // −8.5 %); on the finer grids of examples/hertz_3d.rs the same recovery gives −4.0 %
    // (3.7 cells across a) and −0.7 % (7 cells): docs/validation.md
    assert!((ratio - 1.0).abs() < 0.10, "p(0)/p0 = {ratio}");
    let mesh = std::fs::read_to_string(out.join("mesh_0001.vtu")).unwrap();
    assert!(mesh.contains("pressure_field"));
    let vtu = std::fs::read_to_string(out.join("interface_0001.vtu")).unwrap();
    assert!(vtu.contains("pressure_field") && vtu.contains("shear_field"));
    assert!(out.join("pressure.svg").exists());
    let _ = std::fs::remove_dir_all(&out);
}
