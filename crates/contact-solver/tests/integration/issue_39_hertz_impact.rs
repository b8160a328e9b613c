//! Issue 39: an elastic sphere dropped on a rigid plane at `v0` against Hertz's impact
//! theory (Johnson 1985, *Contact Mechanics*, §11.4): contact duration
//! `t_c = 2.8682 (m²/(R E*² v0))^{1/5}` and peak force `P_max = (4/3) E* √R δ_max^{3/2}`,
//! `δ_max = (15 m v0²/(16 E* √R))^{2/5}`, with `m = 4/3 π R³ ρ` the whole sphere's mass and
//! `E* = E/(1 − ν²)` (rigid plane); the constant is derived in `tests/support/sphere_impact.rs`.
//!
//! Sketch (meridian plane; the axisymmetric model is the half-disk `r ≥ 0`, the 3D one its
//! quarter revolved through 90°, P2 tetrahedra, symmetry supports on both cut planes):
//! ```text
//!          z
//!          │  ╭──╮      R = 1, E = 1, ν = 0.3, ρ = 1 (c = 1), v0 downwards,
//!          │ (    )     Moreau–Jean θ = 1/2, e = 0, Signorini, consistent mass
//!          │  ╰──╯  ↓ v0
//!  ════════╧═══════════ rigid plane z = −R (touching the pole at t = 0)
//! ```
//! `v0 = 5.3e-5 c` gives `a_max = 0.025 R` and `t_c = 35 R/c`, `v0 = 3e-4 c` `a_max = 0.05 R`
//! and `t_c = 25 R/c` (many periods of the sphere's first modes: a quasi-static contact, as
//! Hertz assumes). The departure from Hertz is that of a finite sphere from the half-space
//! (`O(a/R)`): measured, mesh-converged, `t_c` −0.76 % and `P_max` +1.2 % at `a = 0.025 R`,
//! −1.76 % and +2.3 % at `0.05 R`, −3.4 % and +5.3 % at `0.1 R`.

#![cfg(feature = "fe")]

use crate::support::sphere_impact::{axisymmetric, drop, hertz, meridian, quarter};
use fem_core::dynamic::MassKind;
use std::f64::consts::PI;
use std::time::Instant;

#[test]
fn issue_39_sphere_impact_axisymmetric_matches_hertz() {
    // a_max = 0.025 R (v0 = 5.3e-5 c): 6 cells of 0.0088 (in u, v) at the pole, 2135 dofs,
    // h = 0.175 = t_c / 200. Measured: t_c −0.76 %, P_max +1.27 % (the finer 12 × 0.0044:
    // −0.76 %, +1.15 %: converged in the mesh).
    let (duration, peak) = study_case(2, 6, 0.0088, 5.3e-5, 0.175, 0);
    // the issue's 3 %: what is left is Hertz's half-space assumption, O(a/R) (below)
    assert!(
        duration.abs() < 0.03 && peak.abs() < 0.03,
        "{duration} {peak}"
    );
    // Hertz is the limit a/R → 0: at a_max = 0.05 R (v0 = 3e-4) the same scheme on a mesh of
    // the same cells per contact radius departs twice as far (measured −1.76 %, +2.51 %;
    // mesh-converged: 16 × 0.0044 gives −1.76 %, +2.25 %); the finite sphere is stiffer than
    // the half-space by about the half-space's displacement at distance R, 4a/(3πR) of δ.
    let (duration_2, peak_2) = study_case(2, 4, 0.0176, 3e-4, 0.125, 0);
    assert!(duration_2 < 1.5 * duration && peak_2 > 1.5 * peak);
}

#[test]
fn issue_39_sphere_impact_3d_matches_hertz() {
    // the quarter of 2 sectors (45°, P2 tetrahedra) of the meridian 4 × 0.0176, a_max =
    // 0.05 R, h = 0.25 (t_c / 100): 8289 dofs, about 6 s in a debug build. Measured: t_c
    // −2.26 % (whole steps: 1 step = 1 %), P_max +1.36 % (the axisymmetric model on the same
    // meridian: −1.76 %, +2.51 %). Finer (the study below): a_max = 0.025 R, 6 × 0.0088,
    // 13 475 dofs, h = 0.35: −2.26 %, +0.18 %.
    let (duration, peak) = study_case(3, 4, 0.0176, 3e-4, 0.25, 2);
    assert!(
        duration.abs() < 0.03 && peak.abs() < 0.03,
        "{duration} {peak}"
    );
}

/// One drop of the sphere: `dim` 2 (axisymmetric) or 3 (quarter in `sectors` sectors), the
/// meridian of `fine` cells of `size` at the pole, `v0`, `h`; prints one line and returns the
/// relative errors of `t_c` and `P_max` against Hertz.
fn study_case(dim: usize, fine: usize, size: f64, v0: f64, h: f64, sectors: usize) -> (f64, f64) {
    let start = Instant::now();
    let (t_c, p_max, a_max) = hertz(v0);
    let steps = (1.3 * t_c / h).ceil() as usize;
    let mesh = meridian(fine, size);
    let (run, dofs) = if dim == 2 {
        let (body, zone) = axisymmetric(mesh, MassKind::Consistent);
        let dofs = fem_core::Structure::dof_count(&body);
        (drop(body, zone, v0, h, steps, 2.0 * PI), dofs)
    } else {
        let (body, zone) = quarter(&mesh, sectors, MassKind::Consistent);
        let dofs = fem_core::Structure::dof_count(&body);
        (drop(body, zone, v0, h, steps, 4.0), dofs)
    };
    let (duration, peak) = run.duration_and_peak(h);
    let (de, pe) = (duration / t_c - 1.0, peak / p_max - 1.0);
    eprintln!(
        "| {dim}D | {fine} × {size} | {sectors} | {dofs} | {v0:.1e} | {a_max:.4} | {h} | \
         {duration:.3} / {t_c:.3} ({:+.2} %) | {peak:.4e} / {p_max:.4e} ({:+.2} %) | {:.4} | \
         {} runs | {} solves | {:.1?} |",
        100.0 * de,
        100.0 * pe,
        run.velocity.last().unwrap() / v0,
        run.contact_runs().len(),
        run.solves,
        start.elapsed()
    );
    (de, pe)
}

/// The study behind the two tests above and `docs/validation.md`: meshes, steps and speeds
/// (`SPHERE_IMPACT="dim fine size v0 h sectors; …"` runs other cases).
#[test]
#[ignore = "a study (minutes): cargo test … issue_39_sphere_impact_study -- --ignored --nocapture"]
fn issue_39_sphere_impact_study() {
    let cases = std::env::var("SPHERE_IMPACT").unwrap_or_else(|_| {
        "2 12 0.0044 5.3e-5 0.175 0; 2 16 0.0044 3e-4 0.0625 0; 2 8 0.0176 1.67e-3 0.1 0; \
         3 6 0.0088 5.3e-5 0.35 2"
            .into()
    });
    for case in cases.split(';').filter(|c| !c.trim().is_empty()) {
        let v: Vec<f64> = case
            .split_whitespace()
            .map(|x| x.parse().unwrap())
            .collect();
        study_case(
            v[0] as usize,
            v[1] as usize,
            v[2],
            v[3],
            v[4],
            v[5] as usize,
        );
    }
}
