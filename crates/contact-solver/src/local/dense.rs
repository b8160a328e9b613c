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
pub const SEQUENTIAL_BELOW_FLOPS: usize = 1 << 26;

/// faer's parallelism for a dense operation of about `flops` operations: sequential below
/// [`SEQUENTIAL_BELOW_FLOPS`], faer's global setting above.
pub(crate) fn dense_parallelism(flops: usize) -> faer::Par {
    if flops < SEQUENTIAL_BELOW_FLOPS {
        faer::Par::Seq
    } else {
        faer::get_global_parallelism()
    }
}
