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
