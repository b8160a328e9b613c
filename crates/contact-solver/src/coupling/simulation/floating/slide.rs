//! Whether a floating body slides off, in 3D: the limit of a slide.
//!
//! A slipping reaction turns with its slip (`linearized.rs`), so in 3D no direction is free
//! while the body slides off: moving it by `t d`, the slips turn towards the motion's own
//! tangential rates and the resistance across them fades as `1/t`, but never vanishes. The
//! slide's limit is taken instead. With the slipping reactions' directions frozen (their
//! resistance as `t → ∞`), let `V_N` span the amplitudes no contact resists, and `f` the force
//! left on the modes once the slipping contacts' friction is taken off (`f = Gᵀ r − e − Σ G_tᵀ
//! r_t` over the slipping contacts). Along `d = V_N c`, far out, each slipping contact `k`
//! slides along its rate `A_k c` (`A_k = G_t,k V_N`) and its friction `|r_t,k|` opposes it:
//! the force left along `d̂` is `φ(ĉ) = f·ĉ − Σ |r_t,k| |A_k ĉ|` (Coulomb's dissipation;
//! Drucker's limit analysis). The body slides off when `φ > 0` along some direction; the
//! minimiser of
//!
//! ```text
//! ψ(c) = ½ |c − V_Nᵀ f|² + Σ |r_t,k| |A_k c|
//! ```
//! (convex, solved by Newton) is then `c* = φ_max ĉ`, the direction that gives the largest
//! force left, `c* = V_Nᵀ f − Σ |r_t,k| A_kᵀ û_k`: the force left is along the motion. On a
//! plane, pushed by `T > μN`: along `T̂`, out of balance by `T − μN`, as in the plane where the
//! slip has one direction. `c* = 0` (`φ ≤ 0` everywhere): the contacts can hold the body.

use super::NULL_TOL;
use super::linearized::Linearized;
use faer::Mat;
use faer::linalg::solvers::Solve;

/// Newton iterations on `ψ`.
const LIMIT_ITERATIONS: usize = 100;

/// The minimiser must satisfy its own equation `c = V_Nᵀ f − Σ |r_t,k| A_kᵀ û_k` to this
/// fraction of `|c|` (a Newton run towards `c = 0`, where `ψ` has a kink, does not).
const LIMIT_CHECK: f64 = 1e-9;

impl Linearized {
    /// On the linearisation with frozen slip directions ([`Linearized::frozen`]) at the
    /// reactions `r` and the modes' force left `res`: `None` while the directions the contacts
    /// resist are not balanced to `balanced`, or when the contacts can hold the body (module
    /// docs); else `V_N c*` (in the modes' amplitudes), both the direction of the slide and
    /// the force left at its limit, whose size is above `tol`.
    pub(super) fn slide_off<const D: usize>(
        &self,
        r: &[f64],
        res: &[f64],
        balanced: f64,
        tol: f64,
    ) -> Option<Vec<f64>> {
        let nm = self.nm;
        let svd = self.jac.svd().ok()?;
        let (s, v) = (svd.S().column_vector(), svd.V());
        let top = if nm > 0 { s[0] } else { 0.0 };
        let (resisted, free): (Vec<usize>, Vec<usize>) =
            (0..nm).partition(|&c| top > 0.0 && s[c] > NULL_TOL * top);
        let along = |c: usize, x: &[f64]| -> f64 { (0..nm).map(|i| v[(i, c)] * x[i]).sum() };
        let merit = resisted
            .iter()
            .map(|&c| along(c, res).powi(2))
            .sum::<f64>()
            .sqrt();
        if free.is_empty() || merit > balanced {
            return None;
        }
        // the force left without the slipping contacts' friction, and per slipping contact
        // its friction |r_t| and A = G_t V_N ((D − 1) × n_free, row-major)
        let nf = free.len();
        let mut f = res.to_vec();
        let mut slips: Vec<(f64, Vec<f64>)> = Vec::new();
        for k in (0..self.slipping.len()).filter(|&k| self.slipping[k]) {
            let rows = D * k + 1..D * (k + 1);
            let mut a = Vec::with_capacity((D - 1) * nf);
            for t in rows.clone() {
                for (j, fj) in f.iter_mut().enumerate() {
                    *fj -= self.g[t * nm + j] * r[t];
                }
                let g_row = &self.g[t * nm..(t + 1) * nm];
                a.extend(free.iter().map(|&c| along(c, g_row)));
            }
            let friction = rows.map(|t| r[t] * r[t]).sum::<f64>().sqrt();
            slips.push((friction, a));
        }
        let f_c: Vec<f64> = free.iter().map(|&c| along(c, &f)).collect();
        let c = limit(&f_c, &slips, D - 1)?;
        let size = c.iter().map(|v| v * v).sum::<f64>().sqrt();
        if size <= tol {
            return None;
        }
        Some(
            (0..nm)
                .map(|i| (0..nf).map(|q| v[(i, free[q])] * c[q]).sum())
                .collect(),
        )
    }
}

/// The minimiser `c*` of `ψ(c) = ½ |c − f|² + Σ w_k |A_k c|` (`slips`: `(w_k, A_k)`, `A_k`
/// row-major with `rows` rows), by Newton with backtracking from `c = f`; `None` when it is 0
/// (or not found: the answer must satisfy `c = f − Σ w_k A_kᵀ û_k`, [`LIMIT_CHECK`]).
fn limit(f: &[f64], slips: &[(f64, Vec<f64>)], rows: usize) -> Option<Vec<f64>> {
    let n = f.len();
    let apply = |a: &[f64], c: &[f64]| -> Vec<f64> {
        (0..rows)
            .map(|i| (0..n).map(|j| a[i * n + j] * c[j]).sum())
            .collect()
    };
    let size = |y: &[f64]| y.iter().map(|v| v * v).sum::<f64>().sqrt();
    let psi = |c: &[f64]| -> f64 {
        0.5 * c.iter().zip(f).map(|(a, b)| (a - b).powi(2)).sum::<f64>()
            + slips
                .iter()
                .map(|(w, a)| w * size(&apply(a, c)))
                .sum::<f64>()
    };
    // c − Σ w_k A_kᵀ û_k for the terms with A_k c ≠ 0
    let friction = |c: &[f64]| -> Vec<f64> {
        let mut out = vec![0.0; n];
        for (w, a) in slips {
            let y = apply(a, c);
            let ny = size(&y);
            if ny > 0.0 {
                for (j, o) in out.iter_mut().enumerate() {
                    *o += w * (0..rows).map(|i| a[i * n + j] * y[i]).sum::<f64>() / ny;
                }
            }
        }
        out
    };
    let mut c = f.to_vec();
    let f_size = size(f);
    for _ in 0..LIMIT_ITERATIONS {
        if size(&c) <= 1e-12 * f_size {
            return None;
        }
        // gradient c − f + Σ w A_kᵀ û_k; Hessian I + Σ (w/|A_k c|) A_kᵀ (I − û ûᵀ) A_k
        let fr = friction(&c);
        let grad: Vec<f64> = (0..n).map(|j| c[j] - f[j] + fr[j]).collect();
        let mut h = Mat::<f64>::identity(n, n);
        for (w, a) in slips {
            let y = apply(a, &c);
            let ny = size(&y);
            if ny == 0.0 {
                continue;
            }
            let u: Vec<f64> = y.iter().map(|v| v / ny).collect();
            // P = I − û ûᵀ on the (rows)-space, then Aᵀ P A
            for i in 0..n {
                for j in 0..n {
                    let mut sum = 0.0;
                    for p in 0..rows {
                        for q in 0..rows {
                            let proj = f64::from(u8::from(p == q)) - u[p] * u[q];
                            sum += a[p * n + i] * proj * a[q * n + j];
                        }
                    }
                    h[(i, j)] += w / ny * sum;
                }
            }
        }
        let rhs = Mat::<f64>::from_fn(n, 1, |j, _| -grad[j]);
        let step = h.partial_piv_lu().solve(&rhs);
        let step: Vec<f64> = (0..n).map(|j| step[(j, 0)]).collect();
        if step.iter().any(|v| !v.is_finite()) {
            return None;
        }
        let slope: f64 = grad.iter().zip(&step).map(|(g, s)| g * s).sum();
        let base = psi(&c);
        let mut lambda = 1.0;
        let trial = loop {
            let trial: Vec<f64> = c.iter().zip(&step).map(|(a, s)| a + lambda * s).collect();
            if psi(&trial) <= base + 1e-4 * lambda * slope || lambda < 1e-10 {
                break trial;
            }
            lambda *= 0.5;
        };
        let moved = size(&step) * lambda;
        c = trial;
        if moved <= 1e-15 * size(&c) {
            break;
        }
    }
    let fr = friction(&c);
    let left: Vec<f64> = (0..n).map(|j| f[j] - fr[j]).collect();
    let gap = size(&left.iter().zip(&c).map(|(a, b)| a - b).collect::<Vec<_>>());
    (gap <= LIMIT_CHECK * size(&c)).then_some(left)
}

#[cfg(test)]
mod tests {
    use super::limit;

    /// A block sliding on a plane: the free amplitudes are the two translations, every contact
    /// slides at the rigid rate (`A_k = I`), friction `w_k` summing to `μN = 0.9`. Pushed by
    /// `T = 1.5` along `(0.6, 0.8)`: the force left is `(T − μN) T̂` (to `1e-12`: Newton from
    /// `c = f` lands on it in one step); pushed by `T = 0.6 < μN`: the contacts hold it.
    #[test]
    fn limit_of_a_straight_slide_works() {
        let identity = vec![1.0, 0.0, 0.0, 1.0];
        let slips: Vec<(f64, Vec<f64>)> = [0.2, 0.3, 0.4]
            .iter()
            .map(|&w| (w, identity.clone()))
            .collect();
        let left = limit(&[0.9, 1.2], &slips, 2).expect("slides off");
        assert!(
            (left[0] - 0.36).abs() < 1e-12 && (left[1] - 0.48).abs() < 1e-12,
            "{left:?}"
        );
        assert!(limit(&[0.36, 0.48], &slips, 2).is_none());
    }

    /// A twist joins the translations: two contacts at `±1` across the push, sliding at
    /// `t ± ω` along it; a moment-free push above their friction slides them straight
    /// (`ω = 0`), and the force left satisfies its own equation.
    #[test]
    fn limit_with_a_twist_works() {
        // amplitudes (t, ω); each contact's rate along the push is t + y ω, y = ±1
        let slips = vec![(0.45, vec![1.0, 1.0]), (0.45, vec![1.0, -1.0])];
        let left = limit(&[1.5, 0.0], &slips, 1).expect("slides off");
        assert!(
            (left[0] - 0.6).abs() < 1e-12 && left[1].abs() < 1e-12,
            "{left:?}"
        );
        assert!(limit(&[0.6, 0.0], &slips, 1).is_none());
    }
}
