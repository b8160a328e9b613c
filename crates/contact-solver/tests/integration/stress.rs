//! Numerical stability under stress (issue 8): every case must converge to the solver's
//! tolerance (`1e-10`) and pass its physics checks, or end in a typed error it declares —
//! never a NaN, a panic or a silent wrong answer. The cases are in
//! `tests/support/stress_cases/`; `cargo run --release -p contact-solver --example
//! stress_table` prints the table of `docs/validation.md` ("Numerical stability under stress").
//!
//! References for the checks: series springs for stacked blocks; uniaxial plane strain
//! `σ = E δ/(h(1 − ν²))` (any elasticity text); Hertz for a cylinder and a sphere on a rigid
//! flat (K. L. Johnson, *Contact Mechanics*, 1985, ch. 4); RCCM peak `√(w C)` and the β update
//! (Raous–Cangémi–Cocou 1999; seed 4.31–4.51, 5.47–5.48); Coulomb's law and De Saxcé's cone
//! (seed 4.20–4.28).
//!
//! ```text
//!   contrast    ┌──E_up──┐ u_y = −δ      rccm_c, alpha  ┌──E──┐ u = d(t) (pulled)
//!               ├──E_low─┤ pairs/segments               └─────┘ glued (RCCM) on a rigid base
//!               ╧════════╧ fixed
//!   friction, rho  ┌─────┐ (push, −δ)   load_steps ╤═════╤ fixed top, body force (0.2, −1) λ
//!                  └─────┘ Coulomb μ              └─────┘ on a rigid LINE, Coulomb 0.3
//!   poisson: P2 pressed block, Hertz P2;  geometry: gap 0, gap just beyond Δx, ARC endpoints
//! ```
//! Cost: 0.2–0.5 s of test time in the debug build (contact-solver and fem-core are optimised
//! in debug builds), about 250 000 solver sweeps in all. Run with `--nocapture` for the records,
//! `--ignored` for the two known bugs (issue 8, see `docs/validation.md`).

#![cfg(feature = "fe")]

use crate::support::stress_cases::{
    Case, alpha_cases, contrast_cases, friction_cases, geometry_cases, load_step_cases,
    poisson_cases, rccm_c_cases, rho_cases,
};

/// Runs every case of a group (known bugs apart), prints its record, and fails with the list
/// of the cases that did not converge correctly.
fn run_group(cases: Vec<Case>) {
    let mut failures = Vec::new();
    for case in cases {
        if let Some(bug) = case.bug {
            eprintln!("skipped, known bug ({bug}): {}", case.name);
            continue;
        }
        let record = case.run();
        eprintln!("{record}");
        if !record.ok() {
            failures.push(record.to_string());
        }
    }
    assert!(
        failures.is_empty(),
        "{} case(s) failed:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// Runs the cases of a group that carry a known bug, and fails unless they all converge.
fn run_known_bugs(cases: Vec<Case>) {
    let records: Vec<_> = cases
        .into_iter()
        .filter(|c| c.bug.is_some())
        .map(|c| c.run())
        .collect();
    assert!(
        !records.is_empty(),
        "no known-bug case left: remove this test"
    );
    for r in &records {
        eprintln!("{r}");
    }
    assert!(
        records.iter().all(|r| r.ok()),
        "known bug still there:\n{}",
        records
            .iter()
            .map(|r| r.to_string())
            .collect::<Vec<_>>()
            .join("\n")
    );
}

#[test]
fn stiffness_contrast_works() {
    run_group(contrast_cases());
}

/// Issue 8: a stiff contactor (E_up/E_low = 1e8) on coarser soft segments. The natural-map
/// residual is below `tol` (6.7e-11) from ~100 sweeps on, but `r` keeps moving along the
/// near-null space of `W` (eigenvalues 4e-11 against 5e-2) by 6e-10 per Gauss–Seidel sweep, so
/// the relative-change half of the stopping rule never passed with plain Gauss–Seidel
/// (`NotConverged` after 10 000 sweeps). The default Anderson-accelerated sweep converges in
/// about 40.
#[test]
fn issue_8_stiff_contactor_on_soft_segments_converges() {
    run_known_bugs(contrast_cases());
}

#[test]
fn rccm_stiffness_range_works() {
    run_group(rccm_c_cases());
}

/// Issue 8: one elastic step of a glued block (RCCM, `C = 1e12`, body `E = 1e5`, `h = 1`) pulled
/// by `d`: the reactions match `C u`, `u = E d/(E + C h)`, to 5e-9, but the recorded openings
/// (`ContactRecord::gap`) were off by up to 4.2 % and not uniform when they were recomputed from
/// `u = u_free + K⁻¹ Hᵀ r`, and `r = A C x` carries the rounding of `x` (an ulp of `d`)
/// multiplied by `C h/E = 1e7`; they now come from the reduced solution `x` (fixed).
#[test]
fn issue_8_recorded_jumps_of_stiff_glue_are_accurate() {
    run_known_bugs(rccm_c_cases());
}

#[test]
fn friction_range_works() {
    run_group(friction_cases());
}

#[test]
fn rho_scale_range_works() {
    run_group(rho_cases());
}

#[test]
fn load_step_range_works() {
    run_group(load_step_cases());
}

#[test]
fn viscosity_range_works() {
    run_group(alpha_cases());
}

#[test]
fn nearly_incompressible_p2_works() {
    run_group(poisson_cases());
}

#[test]
fn contact_geometry_edge_cases_work() {
    run_group(geometry_cases());
}
