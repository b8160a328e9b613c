//! Quadrature rules on the reference tetrahedron `{ξ, η, ζ ≥ 0, ξ + η + ζ ≤ 1}` (volume ⅙),
//! kept in [`crate::quadrature`] (with the triangle, segment, square and cube rules) and
//! re-exported here.
//!
//! Every point is interior.

pub use crate::quadrature::{TET_1, TET_4, TetPoint, conical_rule};

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
