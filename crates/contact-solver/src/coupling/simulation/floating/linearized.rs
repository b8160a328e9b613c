//! The floating stage's linearisation of the reduced problem at a solution (the parent's
//! module docs): on the closed contacts, the reaction directions `E` and the held rows `P`,
//! `dr/dα = −E (Pᵀ F E − C)⁻¹ Pᵀ G`, and the rigid ray along a direction no contact resists.
//!
//! A slipping contact in 3D holds its gap and, across the slip, a compliant row: its
//! reaction `r_t = −μ r_n ŝ` turns with the slip direction `ŝ = s/|s|`, which resists a
//! motion across the slip with the stiffness `μ r_n / |s|` (stuck across while `|s| = 0`).
//! In the plane the reaction cannot turn, and the rows are those of a held gap.

use super::{Floating, NULL_TOL};
use crate::error::SolverError;
use crate::local::adhesion::AdhesiveSolution;
use crate::local::norm;
use contact_laws::ContactStatus;
use faer::Mat;
use faer::linalg::solvers::Solve;

/// The reduced problem linearised at a solution, on its closed contacts (module docs).
pub(super) struct Linearized {
    pub(super) nm: usize,
    /// The reaction directions `E`: per column, `(row, coefficient)` pairs.
    e_cols: Vec<Vec<(usize, f64)>>,
    /// The rows `P` of the held gaps: per row, `(row, coefficient)` pairs (one pair, except
    /// across a slip in 3D).
    p_rows: Vec<Vec<(usize, f64)>>,
    /// `Z = (Pᵀ F E − C)⁻¹ Pᵀ G` (`p × nm`).
    z: Mat<f64>,
    /// `J = −Gᵀ E Z`.
    pub(super) jac: Mat<f64>,
    /// Closed contacts.
    closed: Vec<bool>,
    /// Closed contacts that slip (with a tangential unknown).
    pub(super) slipping: Vec<bool>,
    /// Whether a slipping reaction turns with its slip (3D; built by [`Self::new`]).
    pub(super) turns: bool,
    /// `G` row-major.
    pub(super) g: Vec<f64>,
}

impl Linearized {
    pub(super) fn new<T, const D: usize>(
        w: &[f64],
        m: usize,
        fl: &Floating,
        sol: &AdhesiveSolution<T>,
        tangent: &[bool],
    ) -> Result<Self, SolverError> {
        Self::build::<T, D>(w, m, fl, sol, tangent, true)
    }

    /// [`Self::new`] with every slipping reaction's direction frozen (`r_t/r_n`): what the
    /// contacts resist once the body slides far (the turning stiffness `μ r_n/|s|` is gone).
    pub(super) fn frozen<T, const D: usize>(
        w: &[f64],
        m: usize,
        fl: &Floating,
        sol: &AdhesiveSolution<T>,
        tangent: &[bool],
    ) -> Result<Self, SolverError> {
        Self::build::<T, D>(w, m, fl, sol, tangent, false)
    }

    fn build<T, const D: usize>(
        w: &[f64],
        m: usize,
        fl: &Floating,
        sol: &AdhesiveSolution<T>,
        tangent: &[bool],
        turning: bool,
    ) -> Result<Self, SolverError> {
        let na = m / D;
        let nm = fl.nm;
        let mut e_cols = Vec::with_capacity(m);
        let mut p_rows = Vec::with_capacity(m);
        // per held row, its compliance `C` (0 for a held gap): the row holds `Pᵀ x = C β`,
        // `β` its column's amplitude (the reaction across a slip turns with the slip)
        let mut compliance = Vec::with_capacity(m);
        let mut closed = vec![false; na];
        let mut slipping = vec![false; na];
        let mut turns = false;
        for k in 0..na {
            let n = D * k;
            let rn = sol.r[n];
            let status = sol.report.statuses[k];
            if status == ContactStatus::Separation && rn <= 0.0 {
                continue;
            }
            closed[k] = true;
            let ts = n + 1..n + D;
            if !tangent[k] {
                e_cols.push(once(n, 1.0, ts.map(|t| (t, 0.0))));
                p_rows.push(vec![(n, 1.0)]);
                compliance.push(0.0);
            } else if status == ContactStatus::Slip {
                slipping[k] = true;
                let ratio = |t: usize| if rn > 0.0 { sol.r[t] / rn } else { 0.0 };
                e_cols.push(once(n, 1.0, ts.map(|t| (t, ratio(t)))));
                p_rows.push(vec![(n, 1.0)]);
                compliance.push(0.0);
                let across = across_slip::<D>(&sol.r[n..n + D], &sol.x[n..n + D]);
                if let Some((across, c)) = across.filter(|_| turning) {
                    turns = true;
                    let pairs: Vec<(usize, f64)> = across
                        .iter()
                        .enumerate()
                        .map(|(d, &a)| (n + 1 + d, a))
                        .collect();
                    e_cols.push(pairs.clone());
                    p_rows.push(pairs);
                    compliance.push(c);
                }
            } else {
                e_cols.push(once(n, 1.0, ts.clone().map(|t| (t, 0.0))));
                p_rows.push(vec![(n, 1.0)]);
                compliance.push(0.0);
                for t in ts {
                    e_cols.push(vec![(t, 1.0), (n, 0.0)]);
                    p_rows.push(vec![(t, 1.0)]);
                    compliance.push(0.0);
                }
            }
        }
        let p = p_rows.len();
        let fe = |row: usize, c: usize| -> f64 {
            e_cols[c]
                .iter()
                .map(|&(col, a)| if a == 0.0 { 0.0 } else { w[row * m + col] * a })
                .sum()
        };
        // (one pair of coefficient 1, every held row in 2D, gives `F E` and `G` exactly)
        let held = |i: usize, of: &dyn Fn(usize) -> f64| -> f64 {
            p_rows[i].iter().map(|&(row, a)| a * of(row)).sum()
        };
        let a = Mat::<f64>::from_fn(p, p, |i, c| {
            let v = held(i, &|row| fe(row, c));
            if i == c && compliance[i] != 0.0 {
                v - compliance[i]
            } else {
                v
            }
        });
        let b = Mat::<f64>::from_fn(p, nm, |i, j| held(i, &|row| fl.g[row * nm + j]));
        let z = if p == 0 {
            Mat::zeros(0, nm)
        } else {
            a.partial_piv_lu().solve(&b)
        };
        if z.col_iter().any(|c| c.iter().any(|v| !v.is_finite())) {
            return Err(SolverError::Unsupported(
                "floating structure: the closed contacts' flexibility is singular, the rigid \
                 motion cannot be linearised"
                    .into(),
            ));
        }
        // J = −(Gᵀ E) Z
        let mut jac = Mat::<f64>::zeros(nm, nm);
        for (c, col) in e_cols.iter().enumerate() {
            for i in 0..nm {
                let ge: f64 = col.iter().map(|&(row, a)| fl.g[row * nm + i] * a).sum();
                if ge != 0.0 {
                    for j in 0..nm {
                        jac[(i, j)] -= ge * z[(c, j)];
                    }
                }
            }
        }
        Ok(Self {
            nm,
            e_cols,
            p_rows,
            z,
            jac,
            closed,
            slipping,
            turns,
            g: fl.g.clone(),
        })
    }

    /// The split of the amplitudes into the directions the closed contacts resist (`V_S`,
    /// right singular vectors of `J` with a non-zero singular value) and the free ones (`V_N`).
    /// Returns the Newton step on the resisted ones, `d = V_S (V_Sᵀ J V_S)⁻¹ (−V_Sᵀ res)`
    /// (each resisted direction balanced, whatever is left along the free ones), the projector
    /// `V_S` (`nm × s`, for the line search's merit `‖V_Sᵀ res‖`) and the free part of the
    /// force, `V_N V_Nᵀ res`.
    pub(super) fn directions(&self, res: &[f64]) -> (Vec<f64>, Mat<f64>, Vec<f64>) {
        let nm = self.nm;
        let Ok(svd) = self.jac.svd() else {
            return (vec![0.0; nm], Mat::zeros(nm, 0), res.to_vec());
        };
        let (s, v) = (svd.S().column_vector(), svd.V());
        let top = if nm > 0 { s[0] } else { 0.0 };
        let stiff: Vec<usize> = (0..nm)
            .filter(|&c| top > 0.0 && s[c] > NULL_TOL * top)
            .collect();
        let vs = Mat::<f64>::from_fn(nm, stiff.len(), |i, c| v[(i, stiff[c])]);
        let mut free = res.to_vec();
        for c in 0..vs.ncols() {
            let d: f64 = (0..nm).map(|i| vs[(i, c)] * res[i]).sum();
            for i in 0..nm {
                free[i] -= d * vs[(i, c)];
            }
        }
        let mut newton = vec![0.0; nm];
        if vs.ncols() > 0 {
            let reduced = vs.transpose() * &self.jac * &vs;
            let rhs = Mat::<f64>::from_fn(vs.ncols(), 1, |c, _| {
                -(0..nm).map(|i| vs[(i, c)] * res[i]).sum::<f64>()
            });
            let y = reduced.partial_piv_lu().solve(&rhs);
            if (0..vs.ncols()).all(|c| y[(c, 0)].is_finite()) {
                for c in 0..vs.ncols() {
                    for i in 0..nm {
                        newton[i] += vs[(i, c)] * y[(c, 0)];
                    }
                }
            }
        }
        (newton, vs, free)
    }

    /// How far to move along the free direction `d` before a contact changes what it resists:
    /// an open contact closes (its gap reaches 0) or a slipping one sticks (its slip increment
    /// returns to 0), plus the gap or slip a lone contact needs to carry the force; `None` if
    /// none does.
    pub(super) fn ray_length<const D: usize>(
        &self,
        d: &[f64],
        x: &[f64],
        res: &[f64],
        w: &[f64],
        m: usize,
    ) -> Option<f64> {
        let nm = self.nm;
        // dx = G d − F E Z d
        let zd: Vec<f64> = (0..self.p_rows.len())
            .map(|c| (0..nm).map(|j| self.z[(c, j)] * d[j]).sum())
            .collect();
        let dx = |row: usize| -> f64 {
            let mut v: f64 = (0..nm).map(|j| self.g[row * nm + j] * d[j]).sum();
            for (c, col) in self.e_cols.iter().enumerate() {
                for &(r, a) in col {
                    if a != 0.0 {
                        v -= w[row * m + r] * a * zd[c];
                    }
                }
            }
            v
        };
        let mut best: Option<(f64, usize, f64)> = None;
        // rates below this are round-off of a direction that does not move the contact
        let tiny = 1e-9 * norm(d);
        let mut consider = |t: f64, row: usize, rate: f64| {
            if best.is_none_or(|(b, _, _)| t < b) {
                best = Some((t, row, rate));
            }
        };
        for k in 0..self.closed.len() {
            let n = D * k;
            if !self.closed[k] {
                let rate = dx(n);
                if rate < -tiny {
                    consider(x[n].max(0.0) / -rate, n, rate);
                }
            } else if self.slipping[k] && D == 2 {
                let rate = dx(n + 1);
                if rate.abs() > tiny && rate * x[n + 1] < 0.0 {
                    consider(x[n + 1].abs() / rate.abs(), n + 1, rate);
                }
            } else if self.slipping[k] {
                // the slip shrinks along the ray: it reaches its closest to 0 at
                // t = −(x_t · ẋ_t) / |ẋ_t|² (the rate named is the slip's speed)
                let (mut along, mut speed2) = (0.0, 0.0);
                for (t, xt) in x.iter().enumerate().take(n + D).skip(n + 1) {
                    let rate = dx(t);
                    along += rate * xt;
                    speed2 += rate * rate;
                }
                let speed = speed2.sqrt();
                if speed > tiny && along < 0.0 {
                    consider(-along / speed2, n + 1, speed);
                }
            }
        }
        let (t, row, rate) = best?;
        // the force along d̂ and the gap (or slip) one contact needs to carry it:
        // extra = W_rr f / (|G_r d̂| |dx_r/dt|)
        let dn = norm(d);
        let force = res.iter().zip(d).map(|(a, b)| a * b).sum::<f64>().abs() / dn;
        let lever = ((0..nm).map(|j| self.g[row * nm + j] * d[j]).sum::<f64>() / dn).abs();
        let extra = if lever > 0.0 {
            w[row * m + row] * force / (lever * rate.abs())
        } else {
            0.0
        };
        Some(t + extra)
    }
}

/// Across a slip in 3D: the unit tangent `p` normal to the reaction `r_t` (`D − 1`
/// components) and the compliance `C = |s|² / (r_t · s)` of the reaction along it, `s = x_t`
/// the slip. The slipping reaction `r_t = κ r_n ŝ` (`κ = −μ`, it opposes the slip) turns with
/// the slip: `p · dr_t = κ r_n (p · ds) / |s|`, so the row `p · dx_t = C β` holds, with `β`
/// the reaction's amplitude along `p` (0 while the slip is 0: stuck across). In the plane the
/// reaction cannot turn: `None`, as when `r_t` is 0 or nearly normal to the slip.
fn across_slip<const D: usize>(r: &[f64], x: &[f64]) -> Option<([f64; 2], f64)> {
    if D != 3 {
        return None;
    }
    let (rt, s) = ([r[1], r[2]], [x[1], x[2]]);
    let size = rt[0].hypot(rt[1]);
    if size == 0.0 || !size.is_finite() {
        return None;
    }
    let across = [-rt[1] / size, rt[0] / size];
    let s2 = s[0] * s[0] + s[1] * s[1];
    let c = if s2 == 0.0 {
        0.0
    } else {
        s2 / (rt[0] * s[0] + rt[1] * s[1])
    };
    c.is_finite().then_some((across, c))
}

/// A reaction direction: `(first, a)` then the rest.
fn once(first: usize, a: f64, rest: impl Iterator<Item = (usize, f64)>) -> Vec<(usize, f64)> {
    std::iter::once((first, a)).chain(rest).collect()
}

#[cfg(test)]
mod tests {
    use super::across_slip;

    /// The compliance across a slip against finite differences of the slipping reaction
    /// `r_t(s) = −μ r_n s/|s|`: moving the slip by `ε p` across it turns the reaction by
    /// `β = p · dr_t`, and `p · ds = C β` (to `1e-6`: forward differences of a unit-size
    /// turn, step `1e-7 |s|`). In the plane: no row.
    #[test]
    fn across_slip_works() {
        let (mu, rn) = (0.3, 2.0);
        let s: [f64; 3] = [0.0, 3e-3, -4e-3];
        let size = s[1].hypot(s[2]);
        let rt = |s: [f64; 3]| -> [f64; 2] {
            let n = s[1].hypot(s[2]);
            [-mu * rn * s[1] / n, -mu * rn * s[2] / n]
        };
        let r0 = rt(s);
        let r = [rn, r0[0], r0[1]];
        let (p, c) = across_slip::<3>(&r, &s).unwrap();
        assert!((p[0] * r0[0] + p[1] * r0[1]).abs() < 1e-15, "p ⟂ r_t");
        assert!((p[0].hypot(p[1]) - 1.0).abs() < 1e-15);
        let eps = 1e-7 * size;
        let r1 = rt([s[0], s[1] + eps * p[0], s[2] + eps * p[1]]);
        let beta = p[0] * (r1[0] - r0[0]) + p[1] * (r1[1] - r0[1]);
        assert!((eps - c * beta).abs() < 1e-6 * eps, "{eps} vs {}", c * beta);
        // |s| / (κ r_n), κ = −μ
        assert!((c + size / (mu * rn)).abs() < 1e-15);
        // no slip yet: stuck across; in the plane, no row
        assert_eq!(across_slip::<3>(&r, &[0.0; 3]).map(|x| x.1), Some(0.0));
        assert!(across_slip::<2>(&[rn, r0[0]], &[0.0, 1.0]).is_none());
        assert!(across_slip::<3>(&[rn, 0.0, 0.0], &s).is_none());
    }
}
