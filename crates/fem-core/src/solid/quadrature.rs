//! Quadrature rules on the reference tetrahedron `{ξ, η, ζ ≥ 0, ξ + η + ζ ≤ 1}` (volume ⅙).
//!
//! Every point is interior.

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

/// The `n`-point Gauss–Legendre rule on `[0, 1]` (nodes by Newton on `P_n`).
fn gauss_legendre_01(n: usize) -> Vec<(f64, f64)> {
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        // Chebyshev-like first guess, then Newton on P_n(x) = 0
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=n {
                let k = k as f64;
                let p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            let p = if n == 0 { 1.0 } else { p1 };
            dp = n as f64 * (x * p - p0) / (x * x - 1.0);
            let dx = p / dp;
            x -= dx;
            if dx.abs() < 1e-16 {
                break;
            }
        }
        let w = 2.0 / ((1.0 - x * x) * dp * dp);
        out.push((0.5 * (1.0 - x), 0.5 * w));
    }
    out
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

    /// ∫ ξ^a η^b ζ^c over the reference tetrahedron = a! b! c! / (a + b + c + 3)!.
    fn exact(a: u32, b: u32, c: u32) -> f64 {
        let f = |n: u32| (1..=n).map(f64::from).product::<f64>();
        f(a) * f(b) * f(c) / f(a + b + c + 3)
    }

    fn integrate(rule: &[TetPoint], a: u32, b: u32, c: u32) -> f64 {
        rule.iter()
            .map(|(x, w)| w * x[0].powi(a as i32) * x[1].powi(b as i32) * x[2].powi(c as i32))
            .sum()
    }

    fn check_degree(rule: &[TetPoint], degree: u32) {
        for a in 0..=degree {
            for b in 0..=degree - a {
                for c in 0..=degree - a - b {
                    let (got, want) = (integrate(rule, a, b, c), exact(a, b, c));
                    // round-off of a few dozen terms
                    assert!((got - want).abs() < 1e-14, "{a} {b} {c}: {got} vs {want}");
                }
            }
        }
    }

    #[test]
    fn tet_rules_are_exact_to_their_degree_works() {
        check_degree(&TET_1, 1);
        check_degree(&TET_4, 2);
        for n in 2..6 {
            check_degree(&conical_rule(n), 2 * n as u32 - 3);
        }
        // and not beyond: the degree-2 rule misses ξ³ (so the test above can fail)
        assert!((integrate(&TET_4, 3, 0, 0) - exact(3, 0, 0)).abs() > 1e-6);
    }
}
