//! Small dense-matrix helpers of the reduced layer (row-major `m × m` slices).

/// Replaces the row-major `m × m` matrix `w` by its symmetric part `(W + Wᵀ)/2`.
///
/// # Panics
/// If `w.len() < m²`.
pub(crate) fn symmetrize(w: &mut [f64], m: usize) {
    for i in 0..m {
        for j in 0..i {
            // halves first: the same bits as 0.5·(a + b), without overflow near f64::MAX
            let a = 0.5 * w[i * m + j] + 0.5 * w[j * m + i];
            w[i * m + j] = a;
            w[j * m + i] = a;
        }
    }
}

/// Below this many floating-point operations a dense faer operation of the reduced layer runs
/// sequentially whatever faer's global parallelism: on the seed's scenes (`m = 66`, about
/// 3·10⁵ flops per condensation) handing the work to rayon's threads costs more than the work
/// (`docs/benchmarks.md`, "Threads").
pub(crate) const SEQUENTIAL_BELOW_FLOPS: usize = 1 << 26;

/// faer's parallelism for a dense operation of about `flops` operations: sequential below
/// `SEQUENTIAL_BELOW_FLOPS`, faer's global setting above.
pub(crate) fn dense_parallelism(flops: usize) -> faer::Par {
    if flops < SEQUENTIAL_BELOW_FLOPS {
        faer::Par::Seq
    } else {
        faer::get_global_parallelism()
    }
}

/// The LU factors of a dense `m × m` matrix `J`, kept between Newton iterations and between
/// solves: a chord step (`J_kept Δ = −F` with the kept factors) costs two triangular solves,
/// against `2m³/3` flops for a new factorisation. `key` says what the factors were built for
/// (the size and a fingerprint of the problem's `W`); a caller checks it before reusing them.
#[derive(Clone, Debug, Default)]
pub(crate) struct KeptLu {
    /// `J` row-major while it is built; after [`factor`](Self::factor), the LU factors of
    /// `Jᵀ` (the same buffer read column-major).
    matrix: Vec<f64>,
    perm: Vec<usize>,
    perm_inv: Vec<usize>,
    m: usize,
    key: Option<u64>,
}

impl KeptLu {
    /// Whether the kept factors were built for a problem of size `m` with this key.
    pub(crate) fn matches(&self, m: usize, key: u64) -> bool {
        self.m == m && self.key == Some(key)
    }

    /// Drops the kept factors.
    pub(crate) fn forget(&mut self) {
        self.key = None;
    }

    /// A zeroed row-major `m × m` buffer to build `J` in; the kept factors are dropped.
    pub(crate) fn start(&mut self, m: usize) -> &mut [f64] {
        self.key = None;
        self.m = m;
        self.matrix.clear();
        self.matrix.resize(m * m, 0.0);
        self.perm.resize(m, 0);
        self.perm_inv.resize(m, 0);
        &mut self.matrix
    }

    /// Factorises the matrix built since [`start`](Self::start) and keeps it under `key`.
    pub(crate) fn factor(
        &mut self,
        key: u64,
        par: faer::Par,
        stack: &mut faer::dyn_stack::MemStack,
    ) {
        let m = self.m;
        faer::linalg::lu::partial_pivoting::factor::lu_in_place(
            faer::MatMut::from_column_major_slice_mut(&mut self.matrix, m, m),
            &mut self.perm,
            &mut self.perm_inv,
            par,
            stack,
            Default::default(),
        );
        self.key = Some(key);
    }

    /// Overwrites `rhs` (`m` entries) by `J⁻¹ rhs`, with the kept factors.
    ///
    /// # Panics
    /// If no factors are kept or `rhs` has not `m` entries.
    pub(crate) fn solve(
        &self,
        rhs: &mut [f64],
        par: faer::Par,
        stack: &mut faer::dyn_stack::MemStack,
    ) {
        assert!(self.key.is_some(), "no factors kept");
        let m = self.m;
        let lu = faer::MatRef::from_column_major_slice(&self.matrix, m, m);
        let p = faer::perm::PermRef::new_checked(&self.perm, &self.perm_inv, m);
        faer::linalg::lu::partial_pivoting::solve::solve_transpose_in_place(
            lu,
            lu,
            p,
            faer::MatMut::from_column_major_slice_mut(rhs, m, 1),
            par,
            stack,
        );
    }

    /// Scratch enough for [`factor`](Self::factor) with `par` and [`solve`](Self::solve) with
    /// `par` or sequentially, at size `m`.
    pub(crate) fn scratch(m: usize, par: faer::Par) -> faer::dyn_stack::StackReq {
        use faer::linalg::lu::partial_pivoting::{factor, solve};
        factor::lu_in_place_scratch::<usize, f64>(m, m, par, Default::default())
            .or(solve::solve_transpose_in_place_scratch::<usize, f64>(
                m, 1, par,
            ))
            .or(solve::solve_transpose_in_place_scratch::<usize, f64>(
                m,
                1,
                faer::Par::Seq,
            ))
    }
}

/// A fingerprint of a dense matrix's exact bits (its size and every entry), to tell whether
/// kept factors were built for it. Not cryptographic: a collision would only cost one chord
/// step, which is kept on its residual alone.
pub(crate) fn fingerprint(values: &[f64]) -> u64 {
    // four independent lanes (the loop vectorises), then mixed
    const K: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut lanes = [values.len() as u64, K, K.rotate_left(17), K.rotate_left(31)];
    let chunks = values.chunks_exact(4);
    let tail = chunks.remainder();
    for c in chunks {
        for l in 0..4 {
            lanes[l] = (lanes[l] ^ c[l].to_bits()).wrapping_mul(K).rotate_left(29);
        }
    }
    for (l, v) in tail.iter().enumerate() {
        lanes[l] = (lanes[l] ^ v.to_bits()).wrapping_mul(K).rotate_left(29);
    }
    lanes
        .iter()
        .fold(0u64, |h, &x| (h ^ x).wrapping_mul(K).rotate_left(23))
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::dyn_stack::{MemBuffer, MemStack};

    #[test]
    fn kept_factors_solve_the_matrix_built_row_major() {
        // a non-symmetric 3 × 3 J that needs pivoting (J[0][0] = 0)
        let j = [0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 3.0, 0.0, 4.0];
        let mut kept = KeptLu::default();
        kept.start(3).copy_from_slice(&j);
        assert!(!kept.matches(3, 7), "nothing kept before the factorisation");
        let mut scratch = MemBuffer::new(KeptLu::scratch(3, faer::Par::Seq));
        kept.factor(7, faer::Par::Seq, MemStack::new(&mut scratch));
        assert!(kept.matches(3, 7) && !kept.matches(3, 8) && !kept.matches(4, 7));
        let x = [1.0, -2.0, 0.5];
        let mut b: Vec<f64> = (0..3)
            .map(|i| (0..3).map(|k| j[3 * i + k] * x[k]).sum())
            .collect();
        kept.solve(&mut b, faer::Par::Seq, MemStack::new(&mut scratch));
        for (a, e) in b.iter().zip(x) {
            // a 3 × 3 solve with condition number about 10: rounding only
            assert!((a - e).abs() < 1e-14, "{a} vs {e}");
        }
        kept.forget();
        assert!(!kept.matches(3, 7));
    }

    #[test]
    fn the_fingerprint_sees_one_bit_and_the_size() {
        let w: Vec<f64> = (0..37).map(|i| (i as f64).sin()).collect();
        let base = fingerprint(&w);
        assert_eq!(base, fingerprint(&w.clone()));
        for i in [0, 5, 35, 36] {
            let mut v = w.clone();
            v[i] = f64::from_bits(v[i].to_bits() ^ 1);
            assert_ne!(base, fingerprint(&v), "entry {i}");
        }
        assert_ne!(fingerprint(&w[..36]), fingerprint(&w[..37]));
        assert_ne!(fingerprint(&[0.0; 4]), fingerprint(&[0.0; 8]));
    }
}
