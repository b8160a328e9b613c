//! The stall detector (issue 14: "symmetric positive semidefinite and rank-deficient W — solve
//! when a solution exists, say plainly when the iteration stalls"), `src/local/stall.rs`.
//!
//! - A problem with no solution: two contacts on one rigid dof `u`, pressed from opposite
//!   sides (`H = [1, −1]` on the normals, so `W_nn = H M⁻¹ Hᵀ = [[1, −1], [−1, 1]]`, rank 1),
//!   both gaps closed (`q_n = −1`). Then `x_n1 + x_n2 = q_n1 + q_n2 = −2` whatever `r`, so
//!   `x_n ≥ 0` cannot hold: the reactions grow without bound and the relative residual decays
//!   like `1/k`. Every algorithm must end with `SolverError::Stalled` well before
//!   `max_iterations` (100 000; it stops after 12 000 to 17 000), with its history; Uzawa and
//!   its accelerated variant bring the relative residual to 0 as `r` grows, and the
//!   penetration check calls that a stall.
//! - A slowly converging problem that has a solution: `W_nn = K⁻¹` for a string on a weak
//!   foundation (`K = tridiag(−1, 2 + ε, −1)`, condition number ≈ 160), every contact
//!   closed: the detector must not change a single iteration of any algorithm.

use contact_solver::local::stall::MIN_STALL_WINDOW;
use contact_solver::{
    Algorithm, ReducedProblem, SolverError, UzawaSettings, UzawaSolver, UzawaTuning,
};

/// The default window of the stall detector (a tuning value, read from its `Default`).
fn default_stall_window() -> usize {
    UzawaTuning::default().stall_window
}

const ALL: [Algorithm; 6] = [
    Algorithm::Newton,
    Algorithm::AndersonGaussSeidel,
    Algorithm::GaussSeidel,
    Algorithm::Uzawa,
    Algorithm::AndersonUzawa,
    Algorithm::ClassicRccm,
];

/// Two contacts on one rigid dof in opposite senses, both pressed: no solution.
pub(crate) fn opposed_contacts() -> ReducedProblem {
    #[rustfmt::skip]
    let w = vec![
         1.0, 0.0, -1.0, 0.0,
         0.0, 1.0,  0.0, 0.0,
        -1.0, 0.0,  1.0, 0.0,
         0.0, 0.0,  0.0, 1.0,
    ];
    ReducedProblem::new(w, vec![-1.0, 0.1, -1.0, -0.1], vec![0.3, 0.3]).unwrap()
}

/// `n_c` contacts whose normals see `W_nn = K⁻¹`, `K = tridiag(−1, 2 + ε, −1)` (tangents: 1 on
/// the diagonal, uncoupled), all closed and pushed sideways.
fn string_problem(n_c: usize, epsilon: f64) -> ReducedProblem {
    // K⁻¹ column by column (Gauss elimination of the tridiagonal system, Thomas algorithm)
    let n = n_c;
    let mut inv = vec![0.0; n * n];
    for col in 0..n {
        let (mut c, mut d) = (vec![0.0; n], vec![0.0; n]);
        let b = 2.0 + epsilon;
        for i in 0..n {
            let rhs = if i == col { 1.0 } else { 0.0 };
            let (den, prev_d) = if i == 0 {
                (b, 0.0)
            } else {
                (b + c[i - 1], d[i - 1])
            };
            c[i] = -1.0 / den;
            d[i] = (rhs + prev_d) / den;
        }
        let mut x = vec![0.0; n];
        x[n - 1] = d[n - 1];
        for i in (0..n - 1).rev() {
            x[i] = d[i] - c[i] * x[i + 1];
        }
        for i in 0..n {
            inv[i * n + col] = x[i];
        }
    }
    let m = 2 * n;
    let mut w = vec![0.0; m * m];
    for i in 0..n {
        for j in 0..n {
            w[2 * i * m + 2 * j] = inv[i * n + j];
        }
        w[(2 * i + 1) * m + 2 * i + 1] = 1.0;
    }
    let q: Vec<f64> = (0..m)
        .map(|k| {
            if k % 2 == 0 {
                -1.0
            } else {
                0.2 * ((k / 2) as f64).sin()
            }
        })
        .collect();
    ReducedProblem::new(w, q, vec![0.3; n]).unwrap()
}

/// Uzawa's global factor `θ` grows by 1.5 per easy step, `r` reaches 1e154 in 873 steps and
/// the *relative* residual `‖·‖/‖r‖` (and the relative Signorini–Coulomb check) reads 0 while
/// `x_n = −1`: it used to be reported as converged. The penetration check
/// (`CHECK_FACTOR`: `max(−x_n)⁺ ≤ 1e3 tol max(‖q‖∞, ‖W r‖∞)`) now calls it a stall, at the
/// same iteration, and the fallback stalls too; `accept_non_converged` returns it flagged.
const UZAWA_RELATIVE_RESIDUAL_VANISHES: [Algorithm; 2] =
    [Algorithm::Uzawa, Algorithm::AndersonUzawa];

#[test]
fn issue_15_uzawa_no_longer_converges_wrongly_on_the_unsolvable_problem() {
    let p = opposed_contacts();
    for algorithm in UZAWA_RELATIVE_RESIDUAL_VANISHES {
        for fallback in [false, true] {
            let st = UzawaSettings::default()
                .with_algorithm(algorithm)
                .with_fallback(fallback)
                .with_max_iterations(100_000);
            match UzawaSolver::new(st).solve(&p, &p.coulomb_laws()) {
                Err(SolverError::Stalled {
                    algorithm: name,
                    fallback_from,
                    iterations,
                    ..
                }) => {
                    if fallback {
                        assert_eq!(
                            (name, fallback_from),
                            ("ClassicRccm", Some(algorithm.name()))
                        );
                    } else {
                        assert_eq!((name, fallback_from), (algorithm.name(), None));
                        assert!(iterations < 5000, "{algorithm:?}: {iterations}");
                    }
                }
                other => {
                    panic!("{algorithm:?} (fallback {fallback}): expected Stalled, got {other:?}")
                }
            }
        }
        let st = UzawaSettings::default()
            .with_algorithm(algorithm)
            .with_fallback(false)
            .with_accept_non_converged(true);
        let sol = UzawaSolver::new(st).solve(&p, &p.coulomb_laws()).unwrap();
        assert!(!sol.report.converged && sol.report.stalled, "{algorithm:?}");
        assert_eq!(sol.x[0], -1.0);
    }
}

#[test]
fn issue_14_unsolvable_problem_stalls_for_every_algorithm() {
    let p = opposed_contacts();
    // the detector fires after about 3 windows on a residual ~ 1/k (src/local/stall.rs)
    let max = 100_000;
    for algorithm in ALL {
        if UZAWA_RELATIVE_RESIDUAL_VANISHES.contains(&algorithm) {
            continue;
        }
        // the algorithm alone, then with the fallback to the classical solver (the default)
        for fallback in [false, true] {
            let st = UzawaSettings::default()
                .with_algorithm(algorithm)
                .with_fallback(fallback)
                .with_max_iterations(max);
            match UzawaSolver::new(st).solve(&p, &p.coulomb_laws()) {
                Err(e @ SolverError::Stalled { .. }) => {
                    let text = e.to_string();
                    let SolverError::Stalled {
                        algorithm: name,
                        fallback_from,
                        iterations,
                        residual,
                        best_residual,
                        history,
                        ..
                    } = e
                    else {
                        unreachable!()
                    };
                    let runs = if fallback && algorithm != Algorithm::ClassicRccm {
                        assert_eq!(name, "ClassicRccm", "{algorithm:?}");
                        assert_eq!(fallback_from, Some(algorithm.name()));
                        // Newton falls back to the accelerated sweep, then to the classic
                        if algorithm == Algorithm::Newton { 3 } else { 2 }
                    } else {
                        assert_eq!((name, fallback_from), (algorithm.name(), None));
                        1
                    };
                    // well before max_iterations: the detector fires after a few windows
                    assert!(
                        iterations <= runs * 4 * default_stall_window(),
                        "{algorithm:?} (fallback {fallback}): {iterations} iterations"
                    );
                    assert!(!history.is_empty() && history.len() <= iterations);
                    assert_eq!(history.last(), Some(&residual));
                    assert!(best_residual <= residual && best_residual > 1e-10);
                    assert!(text.contains("stalled"), "{text}");
                    assert!(
                        text.contains(&format!("after {iterations} iterations")),
                        "{text}"
                    );
                    assert!(text.contains(&format!("residual {residual:e}")), "{text}");
                }
                other => {
                    panic!("{algorithm:?} (fallback {fallback}): expected Stalled, got {other:?}")
                }
            }
        }
        // accepted: the report says it stalled
        let st = UzawaSettings::default()
            .with_algorithm(algorithm)
            .with_max_iterations(max)
            .with_accept_non_converged(true);
        let rep = UzawaSolver::new(st)
            .solve(&p, &p.coulomb_laws())
            .unwrap()
            .report;
        assert!(rep.stalled && !rep.converged, "{algorithm:?}");
        assert!(rep.iterations < max);
        // with the detector off, the same run goes to max_iterations
        let st = st.with_stall_window(0).with_max_iterations(3000);
        let rep = UzawaSolver::new(st)
            .solve(&p, &p.coulomb_laws())
            .unwrap()
            .report;
        assert!(!rep.stalled && !rep.converged, "{algorithm:?}");
        assert_eq!(rep.iterations, 3000, "{algorithm:?}");
    }
}

#[test]
fn issue_14_slow_convergence_is_not_cut() {
    let p = string_problem(20, 1e-3);
    for algorithm in ALL {
        let run = |window: usize| {
            let st = UzawaSettings::default()
                .with_algorithm(algorithm)
                .with_fallback(false)
                .with_max_iterations(200_000)
                .with_stall_window(window);
            UzawaSolver::new(st).solve(&p, &p.coulomb_laws()).unwrap()
        };
        let (off, on) = (run(0), run(default_stall_window()));
        // 7 (Newton) to 693 (Uzawa) iterations: slow for the sweeps, steady
        assert!(off.report.iterations >= 7, "{algorithm:?}");
        assert!(on.report.converged && !on.report.stalled);
        assert_eq!(on.report.iterations, off.report.iterations, "{algorithm:?}");
        assert_eq!(on.r, off.r, "{algorithm:?}");
    }
}

#[test]
fn stall_window_captures_errors() {
    let p = opposed_contacts();
    for window in [1, MIN_STALL_WINDOW - 1] {
        let st = UzawaSettings::default().with_stall_window(window);
        let e = UzawaSolver::new(st).solve(&p, &p.coulomb_laws());
        assert!(
            matches!(
                e,
                Err(SolverError::InvalidSetting {
                    what: "stall_window",
                    ..
                })
            ),
            "{e:?}"
        );
    }
}

/// The matrix-free iteration has the same guards as the dense solvers: on the problem with no
/// solution its global factor `θ` grows like Uzawa's and the relative residual vanishes as `r`
/// grows; the penetration check calls it a stall (`Stalled`, algorithm `MatrixFree`) well
/// before its 100 000 iterations, with or without the stall detector, never "converged".
#[test]
fn matrix_free_stalls_on_the_unsolvable_problem() {
    use contact_laws::Coulomb;
    use contact_solver::local::matrix_free::solve_matrix_free;
    let p = opposed_contacts();
    let apply = |r: &[f64], x: &mut [f64]| {
        p.displacement_into(r, x);
        Ok(())
    };
    let laws = [Coulomb::new(0.3).unwrap(), Coulomb::new(0.3).unwrap()];
    let st = UzawaSettings::default().with_max_iterations(100_000);
    for window in [default_stall_window(), 0] {
        let (mut r, mut x) = (vec![0.0; 4], vec![0.0; 4]);
        let err = solve_matrix_free(
            apply,
            &laws,
            &[(), ()],
            &[1.0, 1.0],
            &st.with_stall_window(window),
            &mut r,
            &mut x,
        )
        .expect_err("no solution");
        let SolverError::Stalled {
            algorithm,
            iterations,
            history,
            ..
        } = err
        else {
            panic!("expected Stalled, got {err:?}");
        };
        assert_eq!(algorithm, "MatrixFree");
        assert!(iterations < 50_000, "{iterations}");
        assert_eq!(history.len(), iterations);
        assert_eq!(x[0], -1.0, "the penetration it refused");
    }
    // accepted, the report says so
    let (mut r, mut x) = (vec![0.0; 4], vec![0.0; 4]);
    let st = st.with_accept_non_converged(true);
    let rep = solve_matrix_free(apply, &laws, &[(), ()], &[1.0, 1.0], &st, &mut r, &mut x).unwrap();
    assert!(rep.stalled && !rep.converged);
}
