//! Issue 40, `examples/scenes/pile_dp.toml`: the seed's pile pull-out (chapter 6) in a
//! Drucker–Prager sand (φ = θ = 35°, c = 1 kPa), run by `bipo` through the plastic path, on the
//! quick mesh (8 shaft cells, as contact-solver's `issue_40_pile_plastic`) for its geostatic
//! step and 3 pull-out increments (0.9 mm).
//!
//! The check (the pile's vertical equilibrium, a closed form): the head's support reaction
//! `R` (`reaction_y` over `pile_head`: `Bᵀσ − f − f_c` at the prescribed dofs, the head's
//! share of the self-weight and the contact force on its corner node taken off) balances the
//! pile's weight `W = γ_p R_p² L / 2` (per radian) and the contact forces the soil puts on it,
//! the shaft's tangential (along +z: the tangent of the normal `(−1, 0)` is `(0, 1)`) and the
//! tip's normal (along +z):
//!
//! ```text
//! R + Σ r_t(shaft) + Σ r_n(tip) − W = 0
//! ```
//!
//! to 1e-8 of `R`: the Newton's tolerance is 1e-11 of the largest force (the soil's geostatic
//! forces, ~1e4 kN per radian), which leaves ~1e-8 of the head load over the pile's free dofs
//! (contact-solver's test measures the same readings the same way; measured here: 1e-13).
//! Fails on the reaction before issue 40's pile scene (`Bᵀσ` alone: off by the head's weight
//! and its corner's contact force, 2e-3 to 2e-2 kN/rad).

use super::support::{bipo, csv, num, scenes, summary, tmp};

/// The pile's unit weight (kN/m³), radius and length (m): `pile_dp.toml`'s.
const PILE: (f64, f64, f64) = (78.0, 0.135, 13.0);

#[test]
fn issue_40_pile_dp_reaction_balances_the_interface() {
    let dir = tmp("pile_dp");
    let text = std::fs::read_to_string(scenes().join("pile_dp.toml")).unwrap();
    let quick = text
        .replace("cells_shaft = 32", "cells_shaft = 8")
        .replace("cells_soil_r = 20", "cells_soil_r = 6")
        .replace("cells_below_tip = 16", "cells_below_tip = 4")
        .replace("tol = 1e-9", "tol = 1e-11")
        .replace("steps = 50\nduration = 50.0", "steps = 3\nduration = 3.0");
    assert_ne!(quick, text);
    let scene = dir.join("pile_dp.toml");
    std::fs::write(&scene, quick).unwrap();
    let out = dir.join("out");
    let o = bipo(&[
        "run".as_ref(),
        scene.as_os_str(),
        "--quiet".as_ref(),
        "--out".as_ref(),
        out.as_os_str(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let s = summary(&out);
    assert_eq!(s["status"], "completed");
    assert_eq!(s["steps"], 4);
    let rows = csv(&out.join("curves.csv"));
    assert_eq!(rows.len(), 4);
    let (gamma, radius, length) = PILE;
    let weight = gamma * radius * radius * length / 2.0;
    let mut last = 0.0;
    for row in &rows {
        let r = num(row, "head reaction (kN/rad)");
        let shaft = num(row, "sum r_t");
        let tip = num(row, "tip r_n");
        let balance = r + shaft + tip - weight;
        eprintln!(
            "pile_dp: v = {:.3e} m, R = {r:.6} kN/rad, shaft {shaft:.6}, tip {tip:.6}, \
             balance {balance:.3e}",
            num(row, "head displacement v (m)")
        );
        assert!(
            balance.abs() <= 1e-8 * r.abs().max(1.0),
            "{row:?}: {balance:e}"
        );
        last = r;
    }
    // the shaft carries the pull: the check is not 0 = 0 (R grows past the pile's weight)
    assert!(last > weight + 1.0, "R = {last}, W = {weight}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A `[preset]` in a scene with a plastic material is refused at `preset` (a preset builds a
/// linear elastic body), pointing at the scene written out key by key.
#[test]
fn issue_40_plastic_preset_is_refused_at_its_key() {
    let dir = tmp("pile_dp_preset");
    let scene = dir.join("preset.toml");
    std::fs::write(
        &scene,
        "[preset]\nkind = \"pile\"\n\n[[materials]]\nregion = 0\ntype = \"drucker-prager\"\n\
         young = 3e4\npoisson = 0.33\nfriction_angle = 35.0\ncohesion = 1.0\n",
    )
    .unwrap();
    let o = bipo(&["check".as_ref(), scene.as_os_str()]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    for f in ["`preset`", "linear elastic", "pile_dp.toml"] {
        assert!(err.contains(f), "{f} not in {err}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
