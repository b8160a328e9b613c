//! Seeded random reduced problems (2D or 3D), for tests, benchmarks and peer comparisons.
//!
//! ```text
//! W = A Aᵀ + δ I,   A_ij ~ U(−1, 1)/√m,   δ = 0.1      (SPD, condition number ≈ 40)
//! q_n ~ U(−1, 0.5)  (about two thirds pressed, one third open),  q_t ~ U(−1, 1),  μ ~ U(0, 1)
//! ```
//! Sparse problems ([`random_sparse_problem`]) are block-sparse, built sparse (never a dense
//! `m × m` array), as a sum of coupling terms like a multibody Delassus operator `H M⁻¹ Hᵀ`:
//!
//! ```text
//! W = Σ_e B_eᵀ B_e + δ I,   B_e = [… A_e (block i) … C_e (block j) …]   (d × m, e = (i, j))
//! A_e, C_e: d × d, entries ~ U(−1, 1) s,   s² = 3/(2 d k),   δ = 0.1
//! ```
//! with `k` couplings per contact on average (each contact starts `k/2` of them towards random
//! others; `k = 0` is block diagonal). Each term is positive semidefinite, so
//! `λ_min(W) ≥ δ`, and `s` makes the mean diagonal entry about 1 (`λ_max` a few units):
//! a condition number of a few tens, like the dense generator's. About `k + 1` blocks of
//! `d × d` per block row.
//!
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

/// A random block-sparse SPD reduced problem of dimension `dim` (2 or 3, clamped to them) with
/// `n_c` contacts and about `couplings` off-diagonal blocks per block row, stored sparse (see
/// the [module docs](self)); `q` and `μ` are drawn as for [`random_problem_in`].
///
/// # Examples
/// ```
/// use contact_solver::local::generate::random_sparse_problem;
/// let p = random_sparse_problem(3, 1000, 4, 7);
/// assert!(p.is_sparse() && p.size() == 3000);
/// // about (4 + 1) blocks of 3 × 3 per row of blocks: far below the dense 9·10⁶ entries
/// assert!(p.w_sparse().unwrap().stored() < 60_000);
/// ```
#[allow(clippy::needless_range_loop)] // B_eᵀ B_e by its index formula, on 3×3 arrays
pub fn random_sparse_problem(
    dim: usize,
    n_c: usize,
    couplings: usize,
    seed: u64,
) -> ReducedProblem {
    let dim = dim.clamp(2, 3);
    let m = dim * n_c;
    let mut g = SplitMix64::new(seed);
    let s = (3.0 / (2.0 * dim as f64 * couplings.max(1) as f64)).sqrt();
    let per_contact = couplings.div_ceil(2);
    let terms = if n_c > 1 { n_c * per_contact } else { 0 };
    let len = terms * 4 * dim * dim + m;
    let (mut rows, mut cols, mut vals) = (
        Vec::with_capacity(len),
        Vec::with_capacity(len),
        Vec::with_capacity(len),
    );
    let mut a = [[0.0; 3]; 3];
    let mut c = [[0.0; 3]; 3];
    for i in 0..n_c {
        for _ in 0..per_contact {
            if n_c < 2 {
                break;
            }
            // j uniform among the other contacts
            let mut j = (g.next_u64() % (n_c as u64 - 1)) as usize;
            if j >= i {
                j += 1;
            }
            for row in a.iter_mut().chain(c.iter_mut()).take(2 * 3) {
                for v in row.iter_mut() {
                    *v = s * g.uniform(-1.0, 1.0);
                }
            }
            // B_eᵀ B_e: blocks (i,i) AᵀA, (i,j) AᵀC, (j,i) CᵀA, (j,j) CᵀC
            for (bi, x) in [(i, &a), (j, &c)] {
                for (bj, y) in [(i, &a), (j, &c)] {
                    for k in 0..dim {
                        for l in 0..dim {
                            let v: f64 = (0..dim).map(|t| x[t][k] * y[t][l]).sum();
                            rows.push(dim * bi + k);
                            cols.push(dim * bj + l);
                            vals.push(v);
                        }
                    }
                }
            }
        }
    }
    for k in 0..m {
        rows.push(k);
        cols.push(k);
        vals.push(0.1);
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
    ReducedProblem::from_triplets(dim, &rows, &cols, &vals, q, mu)
        .unwrap_or_else(|e| unreachable!("a generated problem is valid: {e}"))
}
