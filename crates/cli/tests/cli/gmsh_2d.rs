//! `bipo run` and `bipo check` on genuine 2D Gmsh meshes (issue 36): node sets of physical
//! curves ordered along the curve, and the targets' geometry checked.
//!
//! - tests/gmsh/two_blocks.toml (node-to-segment) and two_blocks_pairs.toml (node pairs): the
//!   two P2 blocks of crates/contact-solver/tests/data/gmsh/two_blocks_p2.msh (made by Gmsh,
//!   script beside it), E = 100, ν = 0, the upper pressed by δ = 0.01 over the two heights 2
//!   on the lower, through an RCCM interface: uniaxial strain, so `Σ r_n = E δ / 2 · 2 = 1`
//!   (the P2 elements hold the linear field exactly: the solver tolerance 1e-12 and round-off
//!   are left, 1e-8 relative), and the contactor's areas sum to the interface length 2
//!   (1e-12). On the old code the sets sorted by tag made the target a zig-zag: the run failed.
//! - Refusals of `bipo check`, each naming the key and the node: a target that doubles back
//!   (a set sorted by tag), pairs whose normal faces away from the contactor, a target curve
//!   of two disjoint pieces and one that branches.

use super::support::{bipo, csv, manifest, num, tmp};

#[test]
fn issue_36_gmsh_two_blocks_run() {
    for scene in ["two_blocks", "two_blocks_pairs"] {
        let out = tmp(scene);
        let path = manifest(&format!("tests/gmsh/{scene}.toml"));
        let o = bipo(&[
            "run".as_ref(),
            path.as_os_str(),
            "--quiet".as_ref(),
            "--out".as_ref(),
            out.as_os_str(),
        ]);
        assert!(
            o.status.success(),
            "{scene}: bipo failed:\n{}\n{}",
            String::from_utf8_lossy(&o.stdout),
            String::from_utf8_lossy(&o.stderr)
        );
        let text = std::fs::read_to_string(out.join("summary.json")).unwrap();
        let summary: serde_json::Value = serde_json::from_str(&text).unwrap();
        let force = summary["zones"][0]["final_force_n"].as_f64().unwrap();
        // uniaxial strain, exact in P2: the solver tolerance and round-off
        assert!((force - 1.0).abs() < 1e-8, "{scene}: Σ r_n = {force}");
        let contacts = csv(&out.join("contacts.csv"));
        let last: Vec<_> = contacts.iter().filter(|r| r["step"] == "2").collect();
        assert_eq!(last.len(), 9, "{scene}: the 9 nodes of the P2 interface");
        let areas: f64 = last.iter().map(|r| num(r, "area")).sum();
        // lumped along the curve: round-off on the length 2
        assert!((areas - 2.0).abs() < 1e-12, "{scene}: Σ areas = {areas}");
        let _ = std::fs::remove_dir_all(&out);
    }
}

/// `bipo check` on `scene` fails with a message holding every one of `needles`.
fn refused(scene: &str, needles: &[&str]) {
    let path = manifest(&format!("tests/gmsh/{scene}.toml"));
    let o = bipo(&["check".as_ref(), path.as_os_str()]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{scene}: accepted");
    for n in needles {
        assert!(stderr.contains(n), "{scene}: `{n}` not in\n{stderr}");
    }
}

#[test]
fn issue_36_check_refuses_bad_targets() {
    refused(
        "doubles_back",
        &[
            "contact[0].target.set",
            "doubles back at node",
            "lower_top_tagged",
        ],
    );
    refused(
        "facing_away",
        &[
            "contact[0].target",
            "contactor node",
            "faces away from its target",
        ],
    );
    refused(
        "square",
        &["contact[0].target.set", "`ends`", "2 disjoint pieces"],
    );
    refused(
        "square_tee",
        &["contact[0].target.set", "`tee`", "branches at node"],
    );
}

/// Issue 35: the nine-node quadrilaterals of tests/gmsh/quad_block.msh (quad_block.toml) pressed
/// on a rigid line, E = 100, ν = 0, by δ = 0.01 over the height 1: uniaxial strain, so
/// `Σ r_n = E δ A / H = 1` (the Q9 elements hold the linear field exactly: the solver tolerance
/// 1e-12 and round-off are left, 1e-8 relative); the 9 nodes of the bottom carry it, their
/// areas summing to the width 1 (1e-12); the mesh written to VTK.
#[test]
fn issue_35_gmsh_quadrilateral_block_works() {
    let out = tmp("quad_block");
    let path = manifest("tests/gmsh/quad_block.toml");
    let o = bipo(&[
        "run".as_ref(),
        path.as_os_str(),
        "--quiet".as_ref(),
        "--out".as_ref(),
        out.as_os_str(),
    ]);
    assert!(
        o.status.success(),
        "bipo failed:\n{}\n{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    let text = std::fs::read_to_string(out.join("summary.json")).unwrap();
    let summary: serde_json::Value = serde_json::from_str(&text).unwrap();
    let force = summary["zones"][0]["final_force_n"].as_f64().unwrap();
    assert!((force - 1.0).abs() < 1e-8, "Σ r_n = {force}");
    let contacts = csv(&out.join("contacts.csv"));
    let half: f64 = contacts
        .iter()
        .filter(|r| r["step"] == "1")
        .map(|r| num(r, "r_n"))
        .sum();
    assert!((half - 0.5).abs() < 1e-8, "Σ r_n at t = 1/2: {half}");
    let last: Vec<_> = contacts.iter().filter(|r| r["step"] == "2").collect();
    assert_eq!(last.len(), 9, "the 9 nodes of the bottom");
    let areas: f64 = last.iter().map(|r| num(r, "area")).sum();
    assert!((areas - 1.0).abs() < 1e-12, "Σ areas = {areas}");
    let vtu = std::fs::read_to_string(out.join("mesh_0001.vtu")).unwrap();
    // VTK_BIQUADRATIC_QUAD, the only cell type
    assert!(
        vtu.contains(r#"Name="types" format="binary" RangeMin="28" RangeMax="28""#),
        "the mesh output's cells are not all of type 28"
    );
    let _ = std::fs::remove_dir_all(&out);
}
