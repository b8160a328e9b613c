//! One contact against a rigid obstacle with an isotropic flexibility `W = diag(f, f)`.
//!
//! Reference: closed forms of Signorini–Coulomb for a single node (Wriggers, *Computational
//! Contact Mechanics*, 2006, §5.1; seed §4.2). With `x = f r + q`, `q = (−1, 0.5)`:
//! - Signorini (μ = 0): `x_n = 0` ⇒ `r = (1/f, 0)`;
//! - stick (μ = 0.8, `|q_t| = 0.5 < μ |q_n|`): `x = 0` ⇒ `r = (1/f, −0.5/f)`;
//! - slip (μ = 0.2): `x_n = 0`, `r_t = −μ r_n`, `r_n = 1/f`;
//! - separation (`q_n > 0`): `r = 0`, `x = q`.
//!
//! The solver stops at a relative residual of 1e-10; one contact with an isotropic block
//! converges in a handful of steps to (nearly) exact values, so the checks use 1e-9 relative.

use approx::assert_relative_eq;
use contact_solver::contact_laws::ContactStatus;
use contact_solver::{Algorithm, ReducedProblem, UzawaSettings, solve_coulomb};

const F: f64 = 2.5e-3; // a flexibility in mm/N: ρ⁰ = 400 N/mm, far from 1

fn solve(q: [f64; 2], mu: f64, algorithm: Algorithm) -> contact_solver::Solution {
    let p = ReducedProblem::new(vec![F, 0.0, 0.0, F], q.to_vec(), vec![mu]).unwrap();
    let settings = UzawaSettings::default().with_algorithm(algorithm);
    solve_coulomb(&p, &settings).unwrap()
}

const BOTH: [Algorithm; 2] = [Algorithm::Uzawa, Algorithm::GaussSeidel];

#[test]
fn signorini_works() {
    for alg in BOTH {
        let s = solve([-1.0, 0.5], 0.0, alg);
        // 1e-9 relative: ten times the solver's tolerance.
        assert_relative_eq!(s.r[0], 1.0 / F, max_relative = 1e-9);
        assert_eq!(s.r[1], 0.0); // μ = 0 projects r_t to exactly 0
        assert_relative_eq!(s.x[1], 0.5, max_relative = 1e-12);
        assert_eq!(s.report.statuses, vec![ContactStatus::Slip]);
    }
}

#[test]
fn coulomb_stick_works() {
    for alg in BOTH {
        let s = solve([-1.0, 0.5], 0.8, alg);
        assert_relative_eq!(s.r[0], 1.0 / F, max_relative = 1e-9);
        assert_relative_eq!(s.r[1], -0.5 / F, max_relative = 1e-9);
        assert_eq!(s.report.statuses, vec![ContactStatus::Stick]);
    }
}

#[test]
fn coulomb_slip_works() {
    for alg in BOTH {
        let s = solve([-1.0, 0.5], 0.2, alg);
        assert_relative_eq!(s.r[0], 1.0 / F, max_relative = 1e-9);
        assert_relative_eq!(s.r[1], -0.2 * s.r[0], max_relative = 1e-9);
        assert_eq!(s.report.statuses, vec![ContactStatus::Slip]);
    }
}

#[test]
fn separation_works() {
    for alg in BOTH {
        let s = solve([0.3, 0.5], 0.5, alg);
        assert_eq!(s.r, vec![0.0, 0.0]);
        assert_eq!(s.x, vec![0.3, 0.5]);
        assert_eq!(s.report.iterations, 0); // r = 0 is exact when every gap is open: no sweep
        assert_eq!(s.report.statuses, vec![ContactStatus::Separation]);
    }
}
