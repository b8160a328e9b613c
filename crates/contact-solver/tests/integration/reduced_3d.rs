//! 3D reduced problems (`dim = 3`: per contact the normal, then two tangents): every algorithm
//! against known solutions and against each other, checked by an independent test of the
//! Signorini–Coulomb conditions (not the solver's own residual).
//!
//! Tolerances: the solves run to `tol = 1e-11` (relative natural residual); the problems have
//! condition numbers below ~1e3, so the reactions agree to ~1e-8 relative, and the known
//! solutions are met to 1e-8 (the error bound of the stopping rule times the condition number,
//! with a margin).

#![allow(clippy::needless_range_loop)] // index arithmetic on flat per-contact vectors reads best as is

use contact_solver::local::generate::{SplitMix64, random_problem_in};
use contact_solver::{Algorithm, ReducedProblem, Solution, UzawaSettings, UzawaSolver};

const ALGORITHMS: [Algorithm; 7] = [
    Algorithm::Uzawa,
    Algorithm::GaussSeidel,
    Algorithm::AndersonGaussSeidel,
    Algorithm::AndersonUzawa,
    Algorithm::ClassicRccm,
    Algorithm::Newton,
    Algorithm::Auto,
];

fn solve(p: &ReducedProblem, algorithm: Algorithm) -> Solution {
    let st = UzawaSettings::default()
        .with_algorithm(algorithm)
        .with_tol(1e-11)
        .with_max_iterations(200_000)
        .with_fallback(false);
    UzawaSolver::new(st)
        .solve(p, &p.coulomb_laws())
        .unwrap_or_else(|e| panic!("{algorithm:?}: {e}"))
}

/// The largest violation of the Signorini–Coulomb conditions at `(r, x)`, relative to `‖r‖∞`
/// and `max(‖x‖∞, ‖q‖∞)`: `r_n ≥ 0`, `x_n ≥ 0`, `r_n x_n = 0`, `‖r_t‖ ≤ μ r_n`, and where `x_t ≠ 0`:
/// `r_t = −μ r_n x_t/‖x_t‖` with `x_n = 0`.
fn coulomb_violation(p: &ReducedProblem, r: &[f64], x: &[f64]) -> f64 {
    let d = p.dimension();
    let rs = r.iter().fold(f64::MIN_POSITIVE, |a, v| a.max(v.abs()));
    // x is scaled by q's size: at a sticking answer x itself is round-off
    let xs = x
        .iter()
        .chain(p.q())
        .fold(f64::MIN_POSITIVE, |a, v| a.max(v.abs()));
    let mut worst = 0.0_f64;
    for (i, &mu) in p.mu().iter().enumerate() {
        let (rn, xn) = (r[d * i], x[d * i]);
        let rt = &r[d * i + 1..d * i + d];
        let xt = &x[d * i + 1..d * i + d];
        let norm = |v: &[f64]| v.iter().map(|a| a * a).sum::<f64>().sqrt();
        worst = worst
            .max(-rn / rs)
            .max(-xn / xs)
            .max((rn / rs) * (xn / xs))
            .max((norm(rt) - mu * rn) / rs);
        let (xt_norm, rt_norm) = (norm(xt), norm(rt));
        if xt_norm > 1e-7 * xs && rn > 1e-7 * rs {
            // slip: on the cone's edge, against the slip, in contact
            worst = worst.max((rt_norm - mu * rn).abs() / rs);
            for k in 0..d - 1 {
                worst = worst.max((rt[k] + mu * rn * xt[k] / xt_norm).abs() / rs);
            }
            worst = worst.max(xn.abs() / xs);
        }
    }
    worst
}

#[test]
fn every_algorithm_solves_random_3d_problems_and_they_agree() {
    for (nc, seed) in [(1, 1), (5, 2), (30, 3), (100, 4)] {
        let p = random_problem_in(3, nc, seed);
        let reference = solve(&p, Algorithm::Newton);
        let scale = reference.r.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
        for algorithm in ALGORITHMS {
            let sol = solve(&p, algorithm);
            assert!(sol.report.converged, "{algorithm:?} n_c={nc}");
            let v = coulomb_violation(&p, &sol.r, &sol.x);
            assert!(v < 1e-8, "{algorithm:?} n_c={nc}: violation {v:e}");
            let diff = sol
                .r
                .iter()
                .zip(&reference.r)
                .fold(0.0_f64, |a, (x, y)| a.max((x - y).abs()));
            assert!(
                diff <= 1e-7 * scale,
                "{algorithm:?} n_c={nc}: {diff:e} from Newton"
            );
        }
    }
}

/// A block on compliant supports: normals coupled by a random SPD `A`, tangents by `b I`,
/// pressed by `q_n = −1` and pushed by `q_t = s ŝ` hard enough to slide. The answer is
/// `r_n = A⁻¹ 1` and `r_t = −μ r_n ŝ` at every contact, whatever the direction `ŝ`.
#[test]
fn a_pushed_block_slides_along_the_push_in_any_direction() {
    let nc = 4;
    let mut g = SplitMix64::new(7);
    let a: Vec<f64> = (0..nc * nc).map(|_| g.uniform(-0.3, 0.3)).collect();
    // A = B Bᵀ + I (SPD, diagonal ~1)
    let mut amat = vec![0.0; nc * nc];
    for i in 0..nc {
        for j in 0..nc {
            amat[i * nc + j] = (0..nc).map(|k| a[i * nc + k] * a[j * nc + k]).sum::<f64>()
                + if i == j { 1.0 } else { 0.0 };
        }
    }
    // r_n = A⁻¹ 1 by Gaussian elimination (4×4, well conditioned)
    let mut m = amat.clone();
    let mut rn = vec![1.0; nc];
    for k in 0..nc {
        for i in k + 1..nc {
            let f = m[i * nc + k] / m[k * nc + k];
            for j in k..nc {
                m[i * nc + j] -= f * m[k * nc + j];
            }
            rn[i] -= f * rn[k];
        }
    }
    for k in (0..nc).rev() {
        let s: f64 = (k + 1..nc).map(|j| m[k * nc + j] * rn[j]).sum();
        rn[k] = (rn[k] - s) / m[k * nc + k];
    }
    assert!(rn.iter().all(|&v| v > 0.0));
    let (b, mu, push) = (0.5, 0.3, 2.0);
    let n = 3 * nc;
    let mut w = vec![0.0; n * n];
    for i in 0..nc {
        for j in 0..nc {
            w[3 * i * n + 3 * j] = amat[i * nc + j];
        }
        w[(3 * i + 1) * n + 3 * i + 1] = b;
        w[(3 * i + 2) * n + 3 * i + 2] = b;
    }
    for angle in [0.0_f64, 0.7, 2.0, -2.5] {
        let s = [angle.cos(), angle.sin()];
        let q: Vec<f64> = (0..nc)
            .flat_map(|_| [-1.0, push * s[0], push * s[1]])
            .collect();
        let p = ReducedProblem::new_3d(w.clone(), q, vec![mu; nc]).unwrap();
        for algorithm in ALGORITHMS {
            let sol = solve(&p, algorithm);
            for i in 0..nc {
                let expected = [rn[i], -mu * rn[i] * s[0], -mu * rn[i] * s[1]];
                for k in 0..3 {
                    let got = sol.r[3 * i + k];
                    assert!(
                        (got - expected[k]).abs() < 1e-8,
                        "{algorithm:?} angle {angle}: r[{}] = {got}, expected {}",
                        3 * i + k,
                        expected[k]
                    );
                }
                // it slides along the push: x_t ∥ ŝ, x_n = 0
                let (xt, xs) = (sol.x[3 * i + 1], sol.x[3 * i + 2]);
                assert!((xt * s[1] - xs * s[0]).abs() < 1e-8 && xt * s[0] + xs * s[1] > 0.0);
                assert!(sol.x[3 * i].abs() < 1e-8);
            }
        }
    }
}

#[test]
fn one_contact_sticks_slips_or_opens() {
    let eye = vec![1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
    // (q, μ, expected r): stick, slip, open, frictionless
    let cases = [
        ([-1.0, 0.1, -0.2], 0.5, [1.0, -0.1, 0.2]),
        ([-1.0, 0.6, 0.8], 0.5, [1.0, -0.3, -0.4]),
        ([0.5, 0.6, 0.8], 0.5, [0.0, 0.0, 0.0]),
        ([-2.0, 0.6, 0.8], 0.0, [2.0, 0.0, 0.0]),
    ];
    for (q, mu, expected) in cases {
        let p = ReducedProblem::new_3d(eye.clone(), q.to_vec(), vec![mu]).unwrap();
        for algorithm in ALGORITHMS {
            let sol = solve(&p, algorithm);
            for k in 0..3 {
                assert!(
                    (sol.r[k] - expected[k]).abs() < 1e-9,
                    "{algorithm:?} q={q:?}: {:?}",
                    sol.r
                );
            }
        }
    }
}

/// `W = H M⁻¹ Hᵀ` of a rigid cube (6 dofs) resting on its 4 bottom corners (12 contact
/// unknowns): rank 6, so `r` is not unique (statically indeterminate), but the cube's motion
/// is. One time step `u = H v`, `v = v_free + M⁻¹ Hᵀ r`, `v_free = h M⁻¹ f`, under gravity
/// and a horizontal force `F`: below `μ m g` it sticks (`v = 0`), above it slides at
/// `v_x = h (F − μ m g)/m` without lifting or turning.
#[test]
fn a_rigid_cube_on_four_corners_rank_deficient_w() {
    let (mass, half, g, h, mu) = (2.0, 0.5, 9.81, 0.01, 0.4);
    let inertia = mass * (2.0 * half) * (2.0 * half) / 6.0;
    let inv_m = [
        1.0 / mass,
        1.0 / mass,
        1.0 / mass,
        1.0 / inertia,
        1.0 / inertia,
        1.0 / inertia,
    ];
    // rows of H: for direction e at corner p, [eᵀ, (p × e)ᵀ]; frame (n = z, t1 = x, t2 = y)
    let mut hm = Vec::new();
    for (sx, sy) in [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)] {
        let p = [sx * half, sy * half, -half];
        for e in [[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] {
            let c = [
                p[1] * e[2] - p[2] * e[1],
                p[2] * e[0] - p[0] * e[2],
                p[0] * e[1] - p[1] * e[0],
            ];
            hm.push([e[0], e[1], e[2], c[0], c[1], c[2]]);
        }
    }
    let n = hm.len();
    let mut w = vec![0.0; n * n];
    for i in 0..n {
        for j in 0..n {
            w[i * n + j] = (0..6).map(|k| hm[i][k] * inv_m[k] * hm[j][k]).sum();
        }
    }
    for force in [0.5 * mu * mass * g, 2.0 * mu * mass * g] {
        let f = [force, 0.0, -mass * g, 0.0, 0.0, 0.0];
        let v_free: Vec<f64> = (0..6).map(|k| h * inv_m[k] * f[k]).collect();
        let q: Vec<f64> = hm
            .iter()
            .map(|row| (0..6).map(|k| row[k] * v_free[k]).sum())
            .collect();
        let p = ReducedProblem::new_3d(w.clone(), q, vec![mu; 4]).unwrap();
        for algorithm in ALGORITHMS {
            let sol = solve(&p, algorithm);
            let v: Vec<f64> = (0..6)
                .map(|k| v_free[k] + inv_m[k] * (0..n).map(|i| hm[i][k] * sol.r[i]).sum::<f64>())
                .collect();
            let expected_vx = if force < mu * mass * g {
                0.0
            } else {
                h * (force - mu * mass * g) / mass
            };
            let scale = h * g;
            assert!(
                (v[0] - expected_vx).abs() < 1e-8 * scale,
                "{algorithm:?} F={force}: v = {v:?}"
            );
            for (k, vk) in v.iter().enumerate().skip(1) {
                assert!(
                    vk.abs() < 1e-8 * scale,
                    "{algorithm:?} F={force}: v[{k}] = {vk}"
                );
            }
            let total_n: f64 = (0..4).map(|i| sol.r[3 * i]).sum();
            assert!((total_n - h * mass * g).abs() < 1e-8 * h * mass * g);
            let viol = coulomb_violation(&p, &sol.r, &sol.x);
            assert!(viol < 1e-7, "{algorithm:?} F={force}: violation {viol:e}");
        }
    }
}

/// Scale invariance in 3D: `solve(s W, s q)` gives `r` and `x = s x₁` for `s` from 1e-200 to
/// 1e200 (internal rescaling by powers of two: the same answer to round-off).
#[test]
fn a_3d_problem_is_scale_invariant() {
    let p = random_problem_in(3, 8, 11);
    let base = solve(&p, Algorithm::Auto);
    for s in [1e-200, 1e-120, 1e120, 1e200] {
        let w = p.w_dense().unwrap().iter().map(|v| v * s).collect();
        let q = p.q().iter().map(|v| v * s).collect();
        let ps = ReducedProblem::new_3d(w, q, p.mu().to_vec()).unwrap();
        let sol = solve(&ps, Algorithm::Auto);
        assert!(sol.report.rescaled);
        for (a, b) in sol.r.iter().zip(&base.r) {
            assert!((a - b).abs() < 1e-8, "s = {s:e}: {a} against {b}");
        }
    }
}
