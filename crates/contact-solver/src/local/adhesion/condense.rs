//! The exact condensation of the adhesive springs on the reduced problem.

use super::{AdhesiveStep, check_len};
use crate::error::SolverError;
use crate::local::ReducedProblem;
use crate::local::dense::{dense_parallelism, symmetrize};
use contact_laws::ContactLaw;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt;
use faer::linalg::matmul::matmul;
use faer::{Accum, Conj, Mat};
use std::sync::Arc;

/// The condensed problem `x = W̃ r̄ + q̃` (springs of `states` condensed, `μ̄` of `states` per
/// contact) of an adhesive step: the reduced problem whose solution is the step's `r̄` when
/// `states` are the step's final states.
///
/// # Errors
/// [`SolverError::SizeMismatch`] for inconsistent lengths; [`SolverError::NotPositiveDefinite`]
/// when the condensation fails; the reduced problem's validation errors.
pub fn condensed_problem<L: ContactLaw, const D: usize>(
    step: &AdhesiveStep<'_, L, D>,
    states: &[L::State],
) -> Result<ReducedProblem, SolverError> {
    let m = step.q.len();
    let na = m / D;
    check_len("q", D * na, m)?;
    check_len("laws", na, step.laws.len())?;
    check_len("states", na, states.len())?;
    check_len("u_start", na, step.u_start.len())?;
    check_len("areas", na, step.areas.len())?;
    let offset = start_offset(step.u_start);
    Ok(condensed_with_springs(step, states, &offset, None)?.0)
}

/// The condensed problem of `states` and the nodal springs `A k(state)` per contact. Without
/// springs the problem is `W` itself: held shared when `shared` holds `step.w` (no copy).
pub(super) fn condensed_with_springs<L: ContactLaw, const D: usize>(
    step: &AdhesiveStep<'_, L, D>,
    states: &[L::State],
    offset: &[f64],
    shared: Option<&Arc<Vec<f64>>>,
) -> Result<(ReducedProblem, Vec<[f64; 2]>), SolverError> {
    // nodal springs: the law's per-area stiffness times the tributary area
    let stiff: Vec<[f64; 2]> = step
        .laws
        .iter()
        .zip(states)
        .zip(step.areas)
        .map(|((l, s), &a)| l.adhesive_stiffness(s).map(|k| k * a))
        .collect();
    let condensed = condense_springs(step.w, step.q, offset, &stiff, step.q.len())?;
    let mu = step
        .laws
        .iter()
        .zip(states)
        .map(|(l, s)| l.friction_coefficient(s).unwrap_or(0.0))
        .collect();
    let problem = match (condensed, shared) {
        (Some((w_eff, q_eff)), _) => ReducedProblem::with_dimension(D, w_eff, q_eff, mu)?,
        (None, Some(w)) if std::ptr::eq(w.as_slice(), step.w) => {
            ReducedProblem::from_shared(D, Arc::clone(w), step.q.to_vec(), mu)?
        }
        (None, _) => ReducedProblem::with_dimension(D, step.w.to_vec(), step.q.to_vec(), mu)?,
    };
    Ok((problem, stiff))
}

/// The springs act on the total tangential displacement: the offset of the jumps from `x`,
/// their tangential values at the start of the step (`u_start`, `D` per contact).
pub(crate) fn start_offset<const D: usize>(u_start: &[[f64; D]]) -> Vec<f64> {
    u_start
        .iter()
        .flat_map(|u| (0..D).map(move |d| if d == 0 { 0.0 } else { u[d] }))
        .collect()
}

/// Exact condensation (public so that an FE code with its own coupling can reuse it) of the adhesive springs `r_adh = −B (x + o)`:
/// `W̃ = W − W S G⁻¹ S W`, `q̃ = z − W S G⁻¹ S z`, `z = q − W B o`, `G = I + S W S`, `S = √B`,
/// restricted to the dofs with a spring. Returns `(W, q)` unchanged without springs.
///
/// `stiff[k] = [k_n, k_t]` per contact; the dimension per contact is `m / stiff.len()`
/// (2 or 3: `k_t` acts on every tangential component).
///
/// # Errors
/// [`SolverError::SizeMismatch`] when `m` is not 2 or 3 times `stiff.len()`;
/// [`SolverError::NotPositiveDefinite`] when `I + S W S` is not (an indefinite `W`).
pub fn condense(
    w: &[f64],
    q: &[f64],
    offset: &[f64],
    stiff: &[[f64; 2]],
    m: usize,
) -> Result<(Vec<f64>, Vec<f64>), SolverError> {
    Ok(condense_springs(w, q, offset, stiff, m)?.unwrap_or_else(|| (w.to_vec(), q.to_vec())))
}

/// A condensed `(W̃, q̃)`, both row-major.
type Condensed = (Vec<f64>, Vec<f64>);

/// [`condense`], `None` (nothing copied) when no contact has a spring.
fn condense_springs(
    w: &[f64],
    q: &[f64],
    offset: &[f64],
    stiff: &[[f64; 2]],
    m: usize,
) -> Result<Option<Condensed>, SolverError> {
    let dim = if stiff.is_empty() { 2 } else { m / stiff.len() };
    if !(stiff.is_empty() || (dim * stiff.len() == m && (dim == 2 || dim == 3))) {
        return Err(SolverError::SizeMismatch {
            what: "stiff (2 or 3 unknowns per contact)",
            expected: m / 2,
            found: stiff.len(),
        });
    }
    check_len("W", m * m, w.len())?;
    check_len("q", m, q.len())?;
    check_len("offset", m, offset.len())?;
    let springs: Vec<(usize, f64)> = stiff
        .iter()
        .enumerate()
        .flat_map(|(k, s)| (0..dim).map(move |d| (dim * k + d, if d == 0 { s[0] } else { s[1] })))
        .filter(|&(_, b)| b > 0.0)
        .collect();
    if springs.is_empty() {
        return Ok(None);
    }
    let na = springs.len();
    let sqrt: Vec<f64> = springs.iter().map(|&(_, b)| b.sqrt()).collect();
    // z = q − W (B o), by rows of W
    let mut bo = vec![0.0; m];
    for &(j, b) in &springs {
        bo[j] = b * offset[j];
    }
    let mut z = q.to_vec();
    if bo.iter().any(|&v| v != 0.0) {
        for (zi, row) in z.iter_mut().zip(w.chunks_exact(m)) {
            *zi -= row.iter().zip(&bo).map(|(a, b)| a * b).sum::<f64>();
        }
    }
    // rhs = [ (W S)ᵀ | S z ] (na × (m + 1), column-major): column i < m is row i of W at the
    // springs' columns, scaled
    let mut rhs = Mat::<f64>::zeros(na, m + 1);
    for (i, row) in w.chunks_exact(m).enumerate() {
        let col = rhs.col_as_slice_mut(i);
        for (a, &(j, _)) in springs.iter().enumerate() {
            col[a] = row[j] * sqrt[a];
        }
    }
    for (a, &(j, _)) in springs.iter().enumerate() {
        rhs[(a, m)] = sqrt[a] * z[j];
    }
    let ws_t = rhs.subcols(0, m).to_owned();
    // G = I + S W S on the springs: column c is column j_c of (W S)ᵀ, scaled
    let mut g = Mat::<f64>::zeros(na, na);
    for (c, &(j, _)) in springs.iter().enumerate() {
        let src = rhs.col_as_slice(j);
        let col = g.col_as_slice_mut(c);
        for (a, v) in col.iter_mut().enumerate() {
            *v = src[a] * sqrt[c];
        }
        col[c] += 1.0;
    }
    let par = dense_parallelism(m * na * (m + 1));
    let mut stack = MemBuffer::new(llt::factor::cholesky_in_place_scratch::<f64>(
        na,
        par,
        Default::default(),
    ));
    llt::factor::cholesky_in_place(
        g.as_mut(),
        Default::default(),
        par,
        MemStack::new(&mut stack),
        Default::default(),
    )
    .map_err(|_| SolverError::NotPositiveDefinite { contact: 0 })?;
    // Y = G⁻¹ [ (WS)ᵀ | S z ]
    llt::solve::solve_in_place_with_conj(
        g.as_ref(),
        Conj::No,
        rhs.as_mut(),
        par,
        MemStack::new(&mut []),
    );
    // the correction W S Y, transposed ((m + 1) × m, column-major): column i is row i of
    // W S Y, contiguous as row i of the row-major W̃
    let mut correction = Mat::<f64>::zeros(m + 1, m);
    matmul(
        correction.as_mut(),
        Accum::Replace,
        rhs.transpose(),
        ws_t.as_ref(),
        1.0,
        par,
    );
    let mut w_eff = w.to_vec();
    for (i, row) in w_eff.chunks_exact_mut(m).enumerate() {
        let col = correction.col_as_slice(i);
        for (v, c) in row.iter_mut().zip(col) {
            *v -= c;
        }
        z[i] -= col[m];
    }
    symmetrize(&mut w_eff, m);
    Ok(Some((w_eff, z)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::Mat;
    use faer::linalg::solvers::Solve;

    #[test]
    fn condensation_matches_the_direct_formula() {
        // W̃ = (W⁻¹ + B)⁻¹ on a 2-contact problem, checked against (I + W B)⁻¹ W.
        let w = vec![
            2.0, 0.3, 0.5, 0.1, //
            0.3, 1.5, 0.2, 0.4, //
            0.5, 0.2, 3.0, 0.6, //
            0.1, 0.4, 0.6, 2.5,
        ];
        let q = vec![0.1, -0.2, 0.3, 0.05];
        let o = vec![0.0, 0.7, 0.0, -0.3];
        let stiff = [[4.0, 0.0], [1.0, 2.0]];
        let (we, qe) = condense(&w, &q, &o, &stiff, 4).unwrap();
        let b = [4.0, 0.0, 1.0, 2.0];
        let wm = faer::MatRef::from_row_major_slice(&w, 4, 4);
        let mut a = Mat::<f64>::identity(4, 4);
        for i in 0..4 {
            for j in 0..4 {
                a[(i, j)] += wm[(i, j)] * b[j];
            }
        }
        let lu = a.partial_piv_lu();
        let expect_w = lu.solve(wm);
        let zq = Mat::<f64>::from_fn(4, 1, |i, _| {
            q[i] - (0..4).map(|j| wm[(i, j)] * b[j] * o[j]).sum::<f64>()
        });
        let expect_q = lu.solve(&zq);
        for i in 0..4 {
            for j in 0..4 {
                assert!((we[i * 4 + j] - expect_w[(i, j)]).abs() < 1e-13);
            }
            assert!((qe[i] - expect_q[(i, 0)]).abs() < 1e-13);
        }
    }
}
