//! FCLIB's global problem condensed to the local one.
//!
//! ```text
//! global (fclib.h, Siconos' GlobalFrictionContactProblem):
//!   M v = H r + f,        u = Hᵀ v + w,        M: n × n SPD,  H: n × m,  m = d n_c
//! eliminating v = M⁻¹ (H r + f):
//!   u = W r + q,          W = Hᵀ M⁻¹ H,        q = Hᵀ M⁻¹ f + w
//! ```
//! (Siconos' `globalFrictionContact_reformulation_FrictionContact` does the same.) When `M`
//! falls into several diagonal blocks (the connected components of its graph: rigid bodies,
//! several FE bodies) the condensation goes block by block and `W` comes out sparse when it
//! is ([`blocks`](super::blocks)). When `M` is one block (one FE body) it is factorised sparse
//! with faer: Cholesky when it is symmetric, LU otherwise or when Cholesky finds a
//! non-positive pivot; `M⁻¹ H` is then `m` dense columns and `W` dense.

use super::blocks::{self, Blocks};
use super::mass::{Condensed, CondensedW, is_symmetric, solve_mass};
use super::sparse::zeroed;
use faer::Mat;

/// `(W, q)` of the local problem: block by block when `M` has more than one diagonal block,
/// else dense. `W` is exactly symmetric when `M` is symmetric.
///
/// `entries_m`, `entries_h` are the checked entries of `M` (`n × n`) and `H` (`n × m`);
/// `f` has `n` entries and `w` has `m` (the caller checked the sizes). The error is the reason
/// in the file's terms.
pub(super) fn condense(
    n: usize,
    entries_m: &[(usize, usize, f64)],
    entries_h: &[(usize, usize, f64)],
    m: usize,
    f: &[f64],
    w: &[f64],
) -> Result<Condensed, String> {
    let symmetric = is_symmetric(entries_m);
    let parts = Blocks::of(n, entries_m);
    if parts.count() > 1 {
        return blocks::condense(&parts, entries_m, entries_h, m, f, w, symmetric);
    }
    let (wmat, q) = condense_dense(n, entries_m, entries_h, m, f, w, symmetric)?;
    Ok(Condensed {
        w: CondensedW::Dense(wmat),
        q,
    })
}

/// The dense route: `[X | y] = M⁻¹ [H | f]` with `m + 1` dense right-hand sides, then `W`
/// (dense row-major `m × m`) and `q` by [`lower_products`].
pub(super) fn condense_dense(
    n: usize,
    entries_m: &[(usize, usize, f64)],
    entries_h: &[(usize, usize, f64)],
    m: usize,
    f: &[f64],
    w: &[f64],
    symmetric: bool,
) -> Result<(Vec<f64>, Vec<f64>), String> {
    let mut wmat = zeroed(m, m, "fclib_global/H")?;
    zeroed(n, m + 1, "fclib_global/H")?; // the dense right-hand sides below, refused early
    // right-hand sides [H | f], n × (m + 1)
    let mut rhs = Mat::<f64>::zeros(n, m + 1);
    for &(k, a, h) in entries_h {
        rhs[(k, a)] += h;
    }
    for (k, &fk) in f.iter().enumerate() {
        rhs[(k, m)] = fk;
    }
    solve_mass(n, entries_m, &mut rhs)?;
    let q = lower_products(n, entries_h, m, &rhs, w, &mut wmat, symmetric);
    if let Some(k) = wmat.iter().chain(&q).position(|v| !v.is_finite()) {
        return Err(format!(
            "`fclib_global/M` is singular: the condensed {} is not finite",
            if k < m * m { "W" } else { "q" }
        ));
    }
    Ok((wmat, q))
}

/// `W = Hᵀ X` (with `symmetric`, exactly so: the lower triangle, mirrored; else both
/// triangles) and `q = Hᵀ y + w` from
/// `[X | y] = M⁻¹ [H | f]` (`rhs`, column-major `n × (m + 1)`), `W` into `wmat` (row-major
/// `m × m`, zeroed). `H` is gathered by columns once, so that each entry `W_ab` is a sparse
/// dot product of column `a` of `H` with the contiguous column `b` of `X`: `nnz(H) · m / 2`
/// multiply-adds in all, reading `X` in order (the entry-by-entry product it replaces read
/// `X` across its rows, a cache miss per multiply-add, and computed both triangles).
fn lower_products(
    n: usize,
    entries_h: &[(usize, usize, f64)],
    m: usize,
    rhs: &Mat<f64>,
    w: &[f64],
    wmat: &mut [f64],
    symmetric: bool,
) -> Vec<f64> {
    // H by columns: start[a]..start[a + 1] indexes the (row, value) pairs of column a
    let mut start = vec![0usize; m + 1];
    for &(_, a, _) in entries_h {
        start[a + 1] += 1;
    }
    for a in 0..m {
        start[a + 1] += start[a];
    }
    let mut next = start.clone();
    let mut by_col = vec![(0usize, 0.0); entries_h.len()];
    for &(k, a, h) in entries_h {
        by_col[next[a]] = (k, h);
        next[a] += 1;
    }
    let column = |a: usize| &by_col[start[a]..start[a + 1]];
    let dot = |a: usize, xb: &[f64]| column(a).iter().map(|&(k, h)| h * xb[k]).sum::<f64>();
    for b in 0..m {
        let xb = &rhs.col_as_slice(b)[..n];
        if symmetric {
            for a in b..m {
                let v = dot(a, xb);
                wmat[a * m + b] = v;
                wmat[b * m + a] = v;
            }
        } else {
            for a in 0..m {
                wmat[a * m + b] = dot(a, xb);
            }
        }
    }
    let y = &rhs.col_as_slice(m)[..n];
    // q_a = w_a + Σ h y_k, summed in the order of the file's entries
    (0..m)
        .map(|a| column(a).iter().fold(w[a], |s, &(k, h)| s + h * y[k]))
        .collect()
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::local::fclib::sparse::{RawSparse, SparseForm};

    /// `W` dense row-major `m × m`, whichever way it was condensed.
    pub(in crate::local::fclib) fn dense(w: CondensedW, m: usize) -> Vec<f64> {
        match w {
            CondensedW::Dense(w) => w,
            CondensedW::Triplets { rows, cols, vals } => {
                let mut out = vec![0.0; m * m];
                for ((r, c), v) in rows.into_iter().zip(cols).zip(vals) {
                    out[r * m + c] += v;
                }
                out
            }
        }
    }

    #[test]
    fn condense_works_on_one_mass() {
        // M = diag(4, 16), H = I (one 2D contact), f = (1, 2), w = (0.5, 0):
        // W = M⁻¹ = diag(0.25, 0.0625), q = M⁻¹ f + w = (0.75, 0.125), all exact in binary
        let m_dense = [4.0, 0.0, 0.0, 16.0];
        let m_mat = RawSparse::from_dense(&m_dense, 2, 2, SparseForm::CompressedColumn);
        let em = m_mat.entries("M").unwrap();
        let eh = vec![(0, 0, 1.0), (1, 1, 1.0)];
        let c = condense(2, &em, &eh, 2, &[1.0, 2.0], &[0.5, 0.0]).unwrap();
        let (w, q) = (dense(c.w, 2), c.q);
        assert_eq!(w, vec![0.25, 0.0, 0.0, 0.0625]);
        assert_eq!(q, vec![0.75, 0.125]);
    }

    /// A global problem of `bodies` rigid bodies (6 dofs each, `M` diagonal and positive)
    /// and `contacts` 3D contacts between random pairs of them (`H`: 6 entries per body and
    /// contact row, 12 per column), `f` and `w` random.
    #[allow(clippy::type_complexity)]
    pub(in crate::local::fclib) fn rigid_bodies(
        bodies: usize,
        contacts: usize,
    ) -> (
        usize,
        Vec<(usize, usize, f64)>,
        Vec<(usize, usize, f64)>,
        usize,
    ) {
        let mut g = crate::local::generate::SplitMix64::new(3);
        let n = 6 * bodies;
        let em = (0..n).map(|k| (k, k, g.uniform(1.0, 2.0))).collect();
        let mut eh = Vec::new();
        for c in 0..contacts {
            let a = (g.uniform(0.0, bodies as f64) as usize).min(bodies - 1);
            let b = (a + 1 + (g.uniform(0.0, (bodies - 1) as f64) as usize)) % bodies;
            for col in 3 * c..3 * c + 3 {
                for body in [a, b] {
                    for k in 6 * body..6 * body + 6 {
                        eh.push((k, col, g.uniform(-1.0, 1.0)));
                    }
                }
            }
        }
        (n, em, eh, 3 * contacts)
    }

    /// The entry-by-entry product the column form replaced: `W_ab += h X_kb` for each entry
    /// `(k, a, h)` of `H`, then `(W + Wᵀ)/2`, and `q_a += h y_k` from `w`.
    fn products_by_entries(
        entries_h: &[(usize, usize, f64)],
        m: usize,
        rhs: &Mat<f64>,
        w: &[f64],
    ) -> (Vec<f64>, Vec<f64>) {
        let mut wmat = vec![0.0; m * m];
        let mut q = w.to_vec();
        for &(k, a, h) in entries_h {
            for b in 0..m {
                wmat[a * m + b] += h * rhs[(k, b)];
            }
            q[a] += h * rhs[(k, m)];
        }
        for a in 0..m {
            for b in (a + 1)..m {
                let s = 0.5 * (wmat[a * m + b] + wmat[b * m + a]);
                (wmat[a * m + b], wmat[b * m + a]) = (s, s);
            }
        }
        (wmat, q)
    }

    /// `W` and `q` of the column form match the entry-by-entry product to round-off
    /// (`1e-14` of `max|W|`: the two differ only in `(W_ab + W_ba)/2` against `W_ab`, each a
    /// sum of at most 12 products in the same order), and `q` bit for bit (the same sums in
    /// the same order). `FCLIB_TIMING=1` prints both times (`--release` to measure).
    #[test]
    fn issue_37_column_products_match_the_entry_products() {
        let (bodies, contacts) = if std::env::var_os("FCLIB_TIMING").is_some() {
            (1000, 1500)
        } else {
            (30, 40)
        };
        let (n, em, eh, m) = rigid_bodies(bodies, contacts);
        let mut g = crate::local::generate::SplitMix64::new(4);
        let f: Vec<f64> = (0..n).map(|_| g.uniform(-1.0, 1.0)).collect();
        let w: Vec<f64> = (0..m).map(|_| g.uniform(-1.0, 1.0)).collect();
        let mut rhs = Mat::<f64>::zeros(n, m + 1);
        for &(k, a, h) in &eh {
            rhs[(k, a)] += h;
        }
        for (k, &fk) in f.iter().enumerate() {
            rhs[(k, m)] = fk;
        }
        solve_mass(n, &em, &mut rhs).unwrap();
        let t0 = std::time::Instant::now();
        let (w_old, q_old) = products_by_entries(&eh, m, &rhs, &w);
        let t1 = std::time::Instant::now();
        let mut w_new = vec![0.0; m * m];
        let q_new = lower_products(n, &eh, m, &rhs, &w, &mut w_new, true);
        let t2 = std::time::Instant::now();
        if std::env::var_os("FCLIB_TIMING").is_some() {
            let t = condense_dense(n, &em, &eh, m, &f, &w, true).map(|_| t2.elapsed());
            let t3 = std::time::Instant::now();
            let b = condense(n, &em, &eh, m, &f, &w).map(|_| t3.elapsed());
            println!(
                "n = {n}, m = {m}: by entries {:?}, by columns {:?}, whole dense route {t:?}, \
                 block route {b:?}",
                t1 - t0,
                t2 - t1
            );
        }
        let scale = w_old.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
        for (a, b) in w_old.iter().zip(&w_new) {
            assert!((a - b).abs() <= 1e-14 * scale, "{a} against {b}");
        }
        assert_eq!(q_old, q_new);
    }

    #[test]
    fn condense_rejects_a_singular_mass() {
        let m_dense = [1.0, 1.0, 1.0, 1.0];
        let m_mat = RawSparse::from_dense(&m_dense, 2, 2, SparseForm::CompressedColumn);
        let em = m_mat.entries("M").unwrap();
        let eh = vec![(0, 0, 1.0), (1, 1, 1.0)];
        let e = condense(2, &em, &eh, 2, &[1.0, 2.0], &[0.0, 0.0])
            .err()
            .unwrap();
        assert!(e.starts_with("`fclib_global/M` is singular"), "{e}");
    }
}
