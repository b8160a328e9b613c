//! The local layer alone, on a host code's problem: closed forms where they exist, the Coulomb
//! conditions where they do not, every algorithm.

use contact_solver::{Algorithm, ReducedProblem, UzawaSettings, solve_coulomb};
use standalone_local::spring_chain;

const ALGORITHMS: [Algorithm; 6] = [
    Algorithm::Newton,
    Algorithm::AndersonGaussSeidel,
    Algorithm::GaussSeidel,
    Algorithm::Uzawa,
    Algorithm::AndersonUzawa,
    Algorithm::ClassicRccm,
];

fn settings(algorithm: Algorithm) -> UzawaSettings {
    UzawaSettings::default()
        .with_algorithm(algorithm)
        .with_tol(1e-12)
        .with_max_iterations(100_000)
}

/// Decoupled contacts (diagonal `W`): each one has a closed form. Contact 0 is open
/// (`q_n > 0`), 1 sticks (`|q_t|/a_t ≤ μ r_n`), 2 slips forwards, 3 slips backwards.
/// Tolerance 1e-9 relative: the stopping rule is a relative residual of 1e-12 on a problem
/// whose entries are O(1).
#[test]
fn decoupled_contacts_match_their_closed_forms_with_every_algorithm() {
    let (a_n, a_t) = ([2.0, 1.0, 0.5, 4.0], [3.0, 2.0, 1.0, 0.25]);
    let q = [0.3, 0.1, -1.0, 0.2, -2.0, 5.0, -0.5, -3.0];
    let mu = [0.4, 0.6, 0.2, 0.9];
    let mut w = vec![0.0; 64];
    for i in 0..4 {
        w[(2 * i) * 8 + 2 * i] = a_n[i];
        w[(2 * i + 1) * 8 + 2 * i + 1] = a_t[i];
    }
    let problem = ReducedProblem::new(w, q.to_vec(), mu.to_vec()).unwrap();
    let mut expected = [0.0; 8];
    for i in 0..4 {
        let (qn, qt) = (q[2 * i], q[2 * i + 1]);
        if qn >= 0.0 {
            continue;
        }
        let rn = -qn / a_n[i];
        let stick = -qt / a_t[i];
        expected[2 * i] = rn;
        expected[2 * i + 1] = if stick.abs() <= mu[i] * rn {
            stick
        } else {
            -mu[i] * rn * qt.signum()
        };
    }
    // The cases are what the doc says.
    assert_eq!(expected[0..2], [0.0, 0.0]);
    assert!(expected[3].abs() < mu[1] * expected[2]);
    assert_eq!(expected[5], -mu[2] * expected[4]);
    assert_eq!(expected[7], mu[3] * expected[6]);
    for algorithm in ALGORITHMS {
        let sol = solve_coulomb(&problem, &settings(algorithm)).unwrap();
        for (got, want) in sol.r.iter().zip(&expected) {
            assert!(
                (got - want).abs() <= 1e-9 * (1.0 + want.abs()),
                "{algorithm:?}: {:?} against {expected:?}",
                sol.r
            );
        }
    }
}

/// The coupled spring chain (dense `W`): no closed form, so the solution must satisfy the
/// Coulomb conditions (`r_n ≥ 0`, `x_n ≥ 0`, `r_n x_n = 0`, `|r_t| ≤ μ r_n`, stick ⇒ `x_t = 0`,
/// slip ⇒ `r_t x_t ≤ 0` at the cone's edge) to 1e-8 of the problem's scale, and every
/// algorithm must find the same reactions (the solution is unique for SPD `W` and this `μ`,
/// to 1e-7 relative).
#[test]
fn a_coupled_problem_satisfies_coulomb_and_every_algorithm_agrees() {
    let n = 8;
    let d: Vec<f64> = (0..n).map(|i| 1e-3 * (1.0 + 0.1 * i as f64)).collect();
    let problem = spring_chain(n, 1e-4, 50.0, &d, 2e-3, 0.3).unwrap();
    let reference = solve_coulomb(&problem, &settings(Algorithm::Newton)).unwrap();
    let scale_r = reference.r.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let scale_x = d.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let (r, x) = (&reference.r, &reference.x);
    let mut slipping = 0;
    for i in 0..n {
        let (rn, rt, xn, xt) = (r[2 * i], r[2 * i + 1], x[2 * i], x[2 * i + 1]);
        assert!(rn >= -1e-8 * scale_r && xn >= -1e-8 * scale_x);
        assert!((rn * xn).abs() <= 1e-8 * scale_r * scale_x);
        assert!(rt.abs() <= 0.3 * rn + 1e-8 * scale_r);
        if rt.abs() < 0.3 * rn - 1e-6 * scale_r {
            assert!(
                xt.abs() <= 1e-8 * scale_x,
                "contact {i} sticks but slides by {xt}"
            );
        } else {
            slipping += 1;
            assert!(
                rt * xt <= 1e-8 * scale_r * scale_x,
                "contact {i}: r_t x_t = {}",
                rt * xt
            );
        }
    }
    // The pull at node 0 must make some contacts slip and leave others stuck.
    assert!(slipping > 0 && slipping < n, "{slipping} of {n} slip");
    for algorithm in ALGORITHMS {
        let sol = solve_coulomb(&problem, &settings(algorithm)).unwrap();
        for (a, b) in sol.r.iter().zip(r) {
            assert!(
                (a - b).abs() <= 1e-7 * scale_r,
                "{algorithm:?}: {a} against {b}"
            );
        }
    }
}
