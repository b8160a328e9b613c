//! The exact answer of a one-contact Coulomb problem `x = W r + q` (issue 37): no iteration,
//! whatever the scaling of the `d × d` block `W` (a condensed global problem may have
//! `W = diag(1e4, 1, 1e-4)`, where one `ρ` per contact makes every sweep crawl).
//!
//! The three cases of Coulomb's law, tried in turn (`μ` the friction coefficient, `e_n` the
//! normal, sign conventions of `contact-laws`):
//!
//! ```text
//! open    r = 0                          when q_n ≥ 0
//! stick   W r = −q                       when r_n > 0 and ‖r_t‖ ≤ μ r_n
//! slip    r = r_n (1, −μ e),  x = s (0, e),  r_n > 0, s ≥ 0, ‖e‖ = 1
//! ```
//! In 2D the slip direction is `e = ±1` (two linear cases). In 3D `e = (cos φ, sin φ)`, and
//! `W d(φ) r_n − s (0, e) = −q` with `d(φ) = (1, −μ e)` has a solution only where
//!
//! ```text
//! f(φ) = det[W d(φ), (0, e), q] = a c + b s − μ (p c² + t c s + g s²) = 0,   c = cos φ, s = sin φ
//! ```
//! (the coefficients are dot products of the columns of `W` with `q`). The roots are
//! bracketed on a grid of `GRID` angles and refined by a safeguarded Newton; each gives
//! `r_n = −q_n / (W d)_n` (the first row, where `(0, e)` has no entry) and
//! `s = e · ((W d)_t r_n + q_t)`. Every candidate is returned; the caller keeps the first whose
//! natural residual meets its tolerance (a double root, tangent to zero, is not bracketed:
//! the caller then solves iteratively, as without this module).

/// Angles of the grid that brackets the roots of `f(φ)` (a trigonometric polynomial of
/// degree 2: at most 4 roots, so a grid of 32 separates them but for near-double roots).
const GRID: usize = 32;

/// Newton–bisection steps refining one bracketed root (each at least halves the bracket:
/// 60 take `2π/32` below `1e-17`).
const REFINE: usize = 60;

/// Candidate answers `r` (`d` entries used of 3) of one contact with block `w` (row-major,
/// `d × d` in the top-left corner), `q` (`d` entries) and friction `mu ≥ 0`, in the order
/// open, stick, slip. Candidates only: the caller checks each on its own residual.
pub(crate) fn candidates(w: &[[f64; 3]; 3], q: &[f64], mu: f64) -> Vec<[f64; 3]> {
    let d = q.len();
    let mut out = Vec::with_capacity(4);
    if q[0] >= 0.0 {
        out.push([0.0; 3]);
        return out;
    }
    if let Some(r) = stick(w, q)
        && r[0] > 0.0
        && r[1..d].iter().map(|t| t * t).sum::<f64>().sqrt() <= mu * r[0]
    {
        out.push(r);
        return out;
    }
    if mu == 0.0 {
        // frictionless: r_t = 0, x_n = 0
        let rn = -q[0] / w[0][0];
        if rn > 0.0 && rn.is_finite() {
            out.push([rn, 0.0, 0.0]);
        }
        return out;
    }
    if d == 2 {
        for sigma in [1.0, -1.0] {
            let wd0 = w[0][0] - sigma * mu * w[0][1];
            let rn = -q[0] / wd0;
            let s = sigma * (rn * (w[1][0] - sigma * mu * w[1][1]) + q[1]);
            if rn > 0.0 && rn.is_finite() && s >= 0.0 {
                out.push([rn, -sigma * mu * rn, 0.0]);
            }
        }
        return out;
    }
    slips_3d(w, q, mu, &mut out);
    out
}

/// `W r = −q` by Gaussian elimination with partial pivoting (`None` when singular).
fn stick(w: &[[f64; 3]; 3], q: &[f64]) -> Option<[f64; 3]> {
    let d = q.len();
    let mut a = *w;
    let mut b = [0.0; 3];
    for (k, v) in b.iter_mut().enumerate().take(d) {
        *v = -q[k];
    }
    for col in 0..d {
        let piv = (col..d).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if a[piv][col] == 0.0 || !a[piv][col].is_finite() {
            return None;
        }
        a.swap(col, piv);
        b.swap(col, piv);
        let pivot = a[col];
        for row in col + 1..d {
            let f = a[row][col] / pivot[col];
            for (v, p) in a[row][col..d].iter_mut().zip(&pivot[col..d]) {
                *v -= f * p;
            }
            b[row] -= f * b[col];
        }
    }
    let mut r = [0.0; 3];
    for row in (0..d).rev() {
        let s: f64 = (row + 1..d).map(|k| a[row][k] * r[k]).sum();
        r[row] = (b[row] - s) / a[row][row];
    }
    r.iter().all(|v| v.is_finite()).then_some(r)
}

/// The slip candidates of a 3D contact (see the module docs), appended to `out`.
fn slips_3d(w: &[[f64; 3]; 3], q: &[f64], mu: f64, out: &mut Vec<[f64; 3]>) {
    let col = |j: usize| [w[0][j], w[1][j], w[2][j]];
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    // (0, c, s) × q = c A + s B
    let big_a = [q[2], 0.0, -q[0]];
    let big_b = [-q[1], q[0], 0.0];
    let (w0, w1, w2) = (col(0), col(1), col(2));
    let (a, b) = (dot(w0, big_a), dot(w0, big_b));
    let (p, t, g) = (
        dot(w1, big_a),
        dot(w1, big_b) + dot(w2, big_a),
        dot(w2, big_b),
    );
    let f = |phi: f64| {
        let (s, c) = phi.sin_cos();
        a * c + b * s - mu * (p * c * c + t * c * s + g * s * s)
    };
    let df = |phi: f64| {
        let (s, c) = phi.sin_cos();
        -a * s + b * c - mu * (-2.0 * p * c * s + t * (c * c - s * s) + 2.0 * g * s * c)
    };
    let step = std::f64::consts::TAU / GRID as f64;
    let (sin_step, cos_step) = step.sin_cos();
    let f_at = |c: f64, s: f64| a * c + b * s - mu * (p * c * c + t * c * s + g * s * s);
    // the grid's (cos, sin) by rotation (each step exact to round-off: 32 steps lose ~1e-14,
    // far inside the bracket the refinement then narrows with sin_cos itself)
    let (mut c, mut s) = (1.0, 0.0);
    let mut lo = 0.0;
    let mut f_lo = f_at(c, s);
    for k in 1..=GRID {
        let hi = step * k as f64;
        (c, s) = (c * cos_step - s * sin_step, s * cos_step + c * sin_step);
        let f_hi = f_at(c, s);
        let root = if f_lo == 0.0 {
            Some(lo)
        } else if f_lo * f_hi < 0.0 {
            Some(refine(&f, &df, lo, hi, f_lo))
        } else {
            None
        };
        if let Some(phi) = root
            && let Some(r) = slip_answer(w, q, mu, phi)
        {
            out.push(r);
        }
        (lo, f_lo) = (hi, f_hi);
    }
}

/// The root of `f` in `[lo, hi]` (`f(lo)` of the other sign than `f(hi)`): Newton steps kept
/// inside the bracket, bisection where a step would leave it.
fn refine(f: &impl Fn(f64) -> f64, df: &impl Fn(f64) -> f64, lo: f64, hi: f64, f_lo: f64) -> f64 {
    let (mut lo, mut hi) = (lo, hi);
    let sign_lo = f_lo.signum();
    let mut x = 0.5 * (lo + hi);
    for _ in 0..REFINE {
        let fx = f(x);
        if fx == 0.0 {
            return x;
        }
        if fx.signum() == sign_lo {
            lo = x;
        } else {
            hi = x;
        }
        let newton = x - fx / df(x);
        let next = if newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        if (next - x).abs() <= 4.0 * f64::EPSILON * x.abs().max(1.0) || hi - lo <= f64::EPSILON {
            return next;
        }
        x = next;
    }
    x
}

/// The answer of the slip case at angle `phi`, when `r_n > 0` and `s ≥ 0` there.
fn slip_answer(w: &[[f64; 3]; 3], q: &[f64], mu: f64, phi: f64) -> Option<[f64; 3]> {
    let (s, c) = phi.sin_cos();
    let dir = [1.0, -mu * c, -mu * s];
    let wd = |k: usize| w[k][0] * dir[0] + w[k][1] * dir[1] + w[k][2] * dir[2];
    let rn = -q[0] / wd(0);
    let speed = c * (wd(1) * rn + q[1]) + s * (wd(2) * rn + q[2]);
    (rn > 0.0 && rn.is_finite() && speed >= 0.0).then(|| [rn, dir[1] * rn, dir[2] * rn])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `x = W r + q` of one contact.
    fn x_of(w: &[[f64; 3]; 3], q: &[f64], r: &[f64; 3]) -> Vec<f64> {
        (0..q.len())
            .map(|k| q[k] + (0..q.len()).map(|l| w[k][l] * r[l]).sum::<f64>())
            .collect()
    }

    /// Open, stick and both 2D slips of `W = I`: the closed forms `r = −q` (stick) and
    /// `r = (−q_n, ∓μ q_n)` with `x_t = q_t ± μ q_n` (slip).
    #[test]
    fn candidates_2d_works() {
        let w = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0; 3]];
        assert_eq!(candidates(&w, &[1.0, 0.3], 0.5), vec![[0.0; 3]]);
        assert_eq!(candidates(&w, &[-1.0, 0.3], 0.5), vec![[1.0, -0.3, 0.0]]);
        // slip forward: r_t = −μ r_n, x_t = 0.8 − 0.5 = 0.3 ≥ 0
        assert_eq!(candidates(&w, &[-1.0, 0.8], 0.5), vec![[1.0, -0.5, 0.0]]);
        assert_eq!(candidates(&w, &[-1.0, -0.8], 0.5), vec![[1.0, 0.5, 0.0]]);
    }

    /// A 3D slip of a badly scaled block `diag(1e4, 1, 1e-4)` with a coupling between the
    /// normal and a tangent: the candidate found satisfies `x_n = 0`, `r` on the cone and
    /// `x_t` opposite to `r_t`, each to round-off (1e-12 relative: a few operations on
    /// numbers of the block's scale).
    #[test]
    fn candidates_3d_slip_badly_scaled_works() {
        let w = [[1e4, 0.5, 0.0], [0.5, 1.0, 0.0], [0.0, 0.0, 1e-4]];
        let q = [-1e4, 3.0, 1e-3];
        let mu = 0.3;
        let found = candidates(&w, &q, mu);
        assert!(!found.is_empty());
        let r = found[0];
        let x = x_of(&w, &q, &r);
        let rt = (r[1] * r[1] + r[2] * r[2]).sqrt();
        let xt = (x[1] * x[1] + x[2] * x[2]).sqrt();
        assert!(x[0].abs() <= 1e-12 * q[0].abs());
        assert!((rt - mu * r[0]).abs() <= 1e-12 * r[0]);
        // x_t ∥ −r_t: the cosine of their angle is −1
        let cos = (r[1] * x[1] + r[2] * x[2]) / (rt * xt);
        assert!((cos + 1.0).abs() <= 1e-12);
    }

    /// Frictionless: `r_n = −q_n / W_nn`, `r_t = 0`, whatever `q_t`.
    #[test]
    fn candidates_frictionless_works() {
        let w = [[2.0, 1.0, 0.0], [1.0, 2.0, 0.0], [0.0, 0.0, 1.0]];
        assert_eq!(
            candidates(&w, &[-1.0, 5.0, 1.0], 0.0),
            vec![[0.5, 0.0, 0.0]]
        );
    }
}
