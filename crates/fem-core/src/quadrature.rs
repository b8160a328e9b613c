//! Quadrature rules on the reference triangle `{ξ ≥ 0, η ≥ 0, ξ + η ≤ 1}` (area ½) and on
//! the reference segment `[−1, 1]`.
//!
//! Every triangle point is interior, so no point ever sits on the axis `r = 0` in
//! axisymmetry.

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

/// Gauss–Legendre rule with 3 points on `[−1, 1]` (exact to degree 5).
pub const GAUSS_3: [(f64, f64); 3] = [
    (-0.774_596_669_241_483_4, 5.0 / 9.0),
    (0.0, 8.0 / 9.0),
    (0.774_596_669_241_483_4, 5.0 / 9.0),
];

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
