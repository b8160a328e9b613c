//! Seeded random reduced problems (2D or 3D), for tests, benchmarks and peer comparisons.
//!
//! ```text
//! W = A Aᵀ + δ I,   A_ij ~ U(−1, 1)/√m,   δ = 0.1      (SPD, condition number ≈ 40)
//! q_n ~ U(−1, 0.5)  (about two thirds pressed, one third open),  q_t ~ U(−1, 1),  μ ~ U(0, 1)
//! ```
//! The generator is SplitMix64, so a seed gives the same problem on every platform.
//! Problems of other kinds: [`multibody`] (a pile of rigid spheres, rank-deficient Delassus
//! operator) and [`half_space`] (Boussinesq–Cerruti flexibility under an indenter).

use super::problem::ReducedProblem;

pub mod half_space;
pub mod multibody;

/// SplitMix64 (Steele, Lea, Flood 2014): a tiny seeded generator of `u64`.
#[derive(Clone, Debug)]
pub struct SplitMix64(u64);

impl SplitMix64 {
    /// A generator started at `seed`.
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }

    /// The next `u64`.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A uniform `f64` in `[lo, hi)`.
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        let u = (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        lo + (hi - lo) * u
    }
}

/// A random SPD reduced problem with `n_c` contacts (see the [module docs](self)).
///
/// # Examples
/// ```
/// let p = contact_solver::local::generate::random_problem(10, 42);
/// assert_eq!(p.contact_count(), 10);
/// ```
pub fn random_problem(n_c: usize, seed: u64) -> ReducedProblem {
    random_problem_in(2, n_c, seed)
}

/// A random SPD reduced problem of dimension `dim` (2 or 3, clamped to them) with `n_c`
/// contacts, drawn as in the [module docs](self); `dim = 2` is [`random_problem`].
///
/// # Examples
/// ```
/// let p = contact_solver::local::generate::random_problem_in(3, 10, 42);
/// assert_eq!((p.dimension(), p.size()), (3, 30));
/// ```
pub fn random_problem_in(dim: usize, n_c: usize, seed: u64) -> ReducedProblem {
    let dim = dim.clamp(2, 3);
    let m = dim * n_c;
    let mut g = SplitMix64::new(seed);
    let s = 1.0 / (m as f64).sqrt();
    let a: Vec<f64> = (0..m * m).map(|_| s * g.uniform(-1.0, 1.0)).collect();
    let mut w = vec![0.0; m * m];
    for i in 0..m {
        for j in 0..=i {
            let v: f64 = (0..m).map(|k| a[i * m + k] * a[j * m + k]).sum();
            w[i * m + j] = v;
            w[j * m + i] = v;
        }
        w[i * m + i] += 0.1;
    }
    let q = (0..m)
        .map(|k| {
            if k % dim == 0 {
                g.uniform(-1.0, 0.5)
            } else {
                g.uniform(-1.0, 1.0)
            }
        })
        .collect();
    let mu = (0..n_c).map(|_| g.uniform(0.0, 1.0)).collect();
    ReducedProblem::with_dimension(dim, w, q, mu)
        .unwrap_or_else(|e| unreachable!("a generated problem is valid: {e}"))
}
