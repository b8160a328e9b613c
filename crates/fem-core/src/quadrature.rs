//! Quadrature rules on the reference triangle `{ξ ≥ 0, η ≥ 0, ξ + η ≤ 1}` (area ½), the
//! reference tetrahedron (volume ⅙), the reference segment `[−1, 1]` and its tensor products
//! (the square and the cube of the quadrilaterals and hexahedra).
//!
//! Every triangle point is interior, so no point ever sits on the axis `r = 0` in
//! axisymmetry.

use std::any::Any;
use std::sync::OnceLock;

/// A point `(ξ, η)` and weight of a triangle rule; weights sum to ½.
pub type TriPoint = ([f64; 2], f64);

/// Degree 1: the centroid.
pub const TRI_1: [TriPoint; 1] = [([1.0 / 3.0, 1.0 / 3.0], 0.5)];

/// Degree 2: three interior points (Strang–Fix).
pub const TRI_3: [TriPoint; 3] = [
    ([1.0 / 6.0, 1.0 / 6.0], 1.0 / 6.0),
    ([2.0 / 3.0, 1.0 / 6.0], 1.0 / 6.0),
    ([1.0 / 6.0, 2.0 / 3.0], 1.0 / 6.0),
];

const A4: f64 = 0.445_948_490_915_965;
const B4: f64 = 0.091_576_213_509_771;
const WA4: f64 = 0.223_381_589_678_011 / 2.0;
const WB4: f64 = 0.109_951_743_655_322 / 2.0;

/// Degree 4: six interior points (Dunavant 1985).
pub const TRI_6: [TriPoint; 6] = [
    ([A4, A4], WA4),
    ([1.0 - 2.0 * A4, A4], WA4),
    ([A4, 1.0 - 2.0 * A4], WA4),
    ([B4, B4], WB4),
    ([1.0 - 2.0 * B4, B4], WB4),
    ([B4, 1.0 - 2.0 * B4], WB4),
];

const C7: f64 = 0.225 / 2.0;
const A7: f64 = 0.059_715_871_789_770;
const B7: f64 = 0.470_142_064_105_115;
const WA7: f64 = 0.132_394_152_788_506 / 2.0;
const D7: f64 = 0.797_426_985_353_087;
const E7: f64 = 0.101_286_507_323_456;
const WD7: f64 = 0.125_939_180_544_827 / 2.0;

/// Degree 5: seven interior points (Dunavant 1985), for the consistent mass of a 6-node
/// triangle in axisymmetry (`N_i N_j r` is of degree 5).
#[rustfmt::skip]
pub const TRI_7: [TriPoint; 7] = [
    ([1.0 / 3.0, 1.0 / 3.0], C7),
    ([A7, B7], WA7), ([B7, A7], WA7), ([B7, B7], WA7),
    ([D7, E7], WD7), ([E7, D7], WD7), ([E7, E7], WD7),
];

/// The `n`-point Gauss–Legendre rule on `[−1, 1]` (exact to degree `2n − 1`), nodes by
/// Newton on the Legendre polynomial `P_n`, ascending.
///
/// # Panics
/// If `n == 0`.
#[track_caller]
pub fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    assert!(n > 0, "at least one Gauss point");
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        // Chebyshev-like first guess, then Newton on P_n(x) = 0
        let mut x = -(std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=n {
                let k = k as f64;
                let p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
            let dx = p1 / dp;
            x -= dx;
            if dx.abs() < 1e-16 {
                break;
            }
        }
        if n % 2 == 1 && i == n / 2 {
            x = 0.0; // the middle node exactly
        }
        out.push((x, 2.0 / ((1.0 - x * x) * dp * dp)));
    }
    out
}

/// The tensor-product Gauss rule with `n` points per direction on `[−1, 1]^D` (exact to
/// degree `2n − 1` in each variable); `ξ_0` varies fastest.
///
/// # Panics
/// If `n == 0`.
#[track_caller]
pub fn gauss_tensor<const D: usize>(n: usize) -> Vec<([f64; D], f64)> {
    let g = gauss_legendre(n);
    let total = n.pow(D as u32);
    (0..total)
        .map(|mut k| {
            let (mut xi, mut w) = ([0.0; D], 1.0);
            for x in xi.iter_mut() {
                let (p, wp) = g[k % n];
                *x = p;
                w *= wp;
                k /= n;
            }
            (xi, w)
        })
        .collect()
}

/// [`gauss_tensor`] with `n ∈ {2, 3, 4}` points per direction on the square (`D = 2`) or the
/// cube (`D = 3`), built once and kept.
///
/// # Panics
/// If `n ∉ {2, 3, 4}`, or `D ∉ {2, 3}`.
#[track_caller]
pub(crate) fn tensor_rule<const D: usize>(n: usize) -> &'static [([f64; D], f64)] {
    type Rules<const D: usize> = [OnceLock<Vec<([f64; D], f64)>>; 3];
    static SQUARE: Rules<2> = [OnceLock::new(), OnceLock::new(), OnceLock::new()];
    static CUBE: Rules<3> = [OnceLock::new(), OnceLock::new(), OnceLock::new()];
    let rules: &'static dyn Any = if D == 2 { &SQUARE } else { &CUBE };
    let rules: &'static Rules<D> = rules.downcast_ref().expect("a square or a cube");
    rules[n - 2].get_or_init(|| gauss_tensor::<D>(n))
}

/// Gauss–Legendre rule with 3 points on `[−1, 1]` (exact to degree 5).
pub const GAUSS_3: [(f64, f64); 3] = [
    (-0.774_596_669_241_483_4, 5.0 / 9.0),
    (0.0, 8.0 / 9.0),
    (0.774_596_669_241_483_4, 5.0 / 9.0),
];

// Tetrahedra: the reference tetrahedron `{ξ, η, ζ ≥ 0, ξ + η + ζ ≤ 1}` (volume ⅙); every
// point is interior.

/// A point `(ξ, η, ζ)` and weight of a tetrahedron rule; weights sum to ⅙.
pub type TetPoint = ([f64; 3], f64);

/// Degree 1: the centroid.
pub const TET_1: [TetPoint; 1] = [([0.25, 0.25, 0.25], 1.0 / 6.0)];

const A: f64 = 0.585_410_196_624_968_5; // (5 + 3√5) / 20
const B: f64 = 0.138_196_601_125_010_5; // (5 − √5) / 20

/// Degree 2: four interior points (Keast's rule 1), exact for the stiffness of a straight-sided
/// P2 tetrahedron.
pub const TET_4: [TetPoint; 4] = [
    ([B, B, B], 1.0 / 24.0),
    ([A, B, B], 1.0 / 24.0),
    ([B, A, B], 1.0 / 24.0),
    ([B, B, A], 1.0 / 24.0),
];

/// The `n`-point Gauss–Legendre rule on `[0, 1]`, ascending: [`gauss_legendre`] mapped by
/// `u = (1 + x)/2` (bit for bit the rule Newton gives on `[0, 1]` directly, checked to `n = 40`).
fn gauss_legendre_01(n: usize) -> Vec<(f64, f64)> {
    let g = gauss_legendre(n).into_iter();
    g.map(|(x, w)| (0.5 * (1.0 + x), 0.5 * w)).collect()
}

/// A conical-product (collapsed Gauss) rule with `n³` points, exact for polynomials of degree
/// `2n − 3` on the tetrahedron: Gauss–Legendre on the unit cube mapped by
/// `ξ = u, η = v (1 − u), ζ = w (1 − u)(1 − v)` (Jacobian `(1 − u)² (1 − v)`). For error
/// norms and loads that are not polynomials.
///
/// # Panics
/// If `n == 0`.
#[track_caller]
pub fn conical_rule(n: usize) -> Vec<TetPoint> {
    assert!(n > 0, "at least one point per direction");
    let g = gauss_legendre_01(n);
    let mut out = Vec::with_capacity(n * n * n);
    for &(u, wu) in &g {
        for &(v, wv) in &g {
            for &(w, ww) in &g {
                let xi = [u, v * (1.0 - u), w * (1.0 - u) * (1.0 - v)];
                out.push((xi, wu * wv * ww * (1.0 - u) * (1.0 - u) * (1.0 - v)));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// ∫ ξ^a η^b over the reference triangle = a! b! / (a + b + 2)!.
    fn exact(a: i32, b: i32) -> f64 {
        let f = |n: i32| (1..=n).map(f64::from).product::<f64>();
        f(a) * f(b) / f(a + b + 2)
    }

    fn check(rule: &[TriPoint], degree: i32) {
        for a in 0..=degree {
            for b in 0..=(degree - a) {
                let q: f64 = rule
                    .iter()
                    .map(|(p, w)| w * p[0].powi(a) * p[1].powi(b))
                    .sum();
                assert!(
                    (q - exact(a, b)).abs() < 1e-14,
                    "ξ^{a} η^{b}: {q} vs {}",
                    exact(a, b)
                );
            }
        }
    }

    #[test]
    fn triangle_rules_are_exact_to_their_degree_works() {
        check(&TRI_1, 1);
        check(&TRI_3, 2);
        check(&TRI_6, 4);
    }

    #[test]
    fn tri_7_is_exact_to_degree_5_works() {
        check(&TRI_7, 5);
    }

    #[test]
    fn gauss_tensor_is_exact_to_its_degree_works() {
        for n in 1..6 {
            let g = gauss_legendre(n);
            for k in 0..2 * n {
                let q: f64 = g.iter().map(|(x, w)| w * x.powi(k as i32)).sum();
                let exact = if k % 2 == 0 {
                    2.0 / (k as f64 + 1.0)
                } else {
                    0.0
                };
                // round-off of n terms
                assert!((q - exact).abs() < 1e-14, "n = {n}, x^{k}");
            }
            // and not beyond: x^(2n) is missed
            let q: f64 = g.iter().map(|(x, w)| w * x.powi(2 * n as i32)).sum();
            assert!((q - 2.0 / (2.0 * n as f64 + 1.0)).abs() > 1e-6);
        }
        let cube = gauss_tensor::<3>(2);
        assert_eq!(cube.len(), 8);
        let v: f64 = cube
            .iter()
            .map(|(x, w)| w * x[0] * x[0] * x[1] * x[1])
            .sum();
        assert!((v - 8.0 / 9.0).abs() < 1e-14); // ∫ x² y² over [−1,1]³ = (2/3)(2/3)(2)
    }

    #[test]
    fn gauss_3_is_exact_to_degree_5_works() {
        for k in 0..=5 {
            let q: f64 = GAUSS_3.iter().map(|(x, w)| w * x.powi(k)).sum();
            let exact = if k % 2 == 0 {
                2.0 / (k as f64 + 1.0)
            } else {
                0.0
            };
            assert!((q - exact).abs() < 1e-14);
        }
    }
}
