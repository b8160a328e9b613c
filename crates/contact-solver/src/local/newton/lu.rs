//! The plain in-crate LU of the small Newton systems (up to `SMALL_SYSTEM` unknowns, where
//! faer's fixed cost dominates).

/// Solves `a y = b` in place (`y` into `b`) by Gaussian elimination with partial pivoting;
/// `a` is column-major `p × p` and is overwritten by its LU factors. Returns `false` on a zero
/// pivot.
///
/// # Panics
/// If `a.len() != p²` or `b.len() != p`.
#[track_caller]
pub(super) fn lu_solve_in_place(a: &mut [f64], b: &mut [f64]) -> bool {
    let p = b.len();
    assert_eq!(a.len(), p * p, "a must be p × p");
    for k in 0..p {
        let (mut pivot, mut best) = (k, a[k * p + k].abs());
        for i in k + 1..p {
            if a[k * p + i].abs() > best {
                (pivot, best) = (i, a[k * p + i].abs());
            }
        }
        if best == 0.0 || !best.is_finite() {
            return false;
        }
        if pivot != k {
            for j in 0..p {
                a.swap(j * p + k, j * p + pivot);
            }
            b.swap(k, pivot);
        }
        let inv = 1.0 / a[k * p + k];
        a[k * p + k + 1..(k + 1) * p]
            .iter_mut()
            .for_each(|l| *l *= inv);
        let (left, right) = a.split_at_mut((k + 1) * p);
        let col_k = &left[k * p..];
        for col in right.chunks_exact_mut(p) {
            let a_kj = col[k];
            if a_kj != 0.0 {
                for (c, l) in col[k + 1..].iter_mut().zip(&col_k[k + 1..]) {
                    *c -= l * a_kj;
                }
            }
        }
        let b_k = b[k];
        for (c, l) in b[k + 1..].iter_mut().zip(&col_k[k + 1..]) {
            *c -= l * b_k;
        }
    }
    for k in (0..p).rev() {
        b[k] /= a[k * p + k];
        let b_k = b[k];
        for (c, u) in b[..k].iter_mut().zip(&a[k * p..k * p + k]) {
            *c -= u * b_k;
        }
    }
    true
}
