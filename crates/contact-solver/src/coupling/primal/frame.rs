//! The local frame of each active contact for the primal active set: which of its contactor
//! node's dofs carry the local normal and tangents, the rotation, and for a contact between
//! two bodies (node pairs, node-to-segment, node-to-face) the target dofs whose motion the
//! contactor's carries.

use fem_core::Structure;

/// One active contact as the primal solve sees it: the dofs of its node that carry the local
/// normal and tangential components, and the rotation (2D: `n, t`; 3D: `n, t1, t2`; unused
/// slots `None`). Against a deformable target the local jump is `x = P (u_a − Σ_k w_k u_k)`:
/// the contactor's dofs are renamed as the jump's components, and its displacement becomes
/// `u_a = Pᵀ x + Σ_k w_k u_k` (`carry`).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct LocalFrame {
    /// Global dof renamed as local component `c` (`[0]` the normal); `None` for a direction
    /// the node cannot move along (every component along it prescribed, e.g. across a
    /// symmetry plane), and for the third slot in 2D.
    pub dofs: [Option<usize>; 3],
    /// `p[c][e]`: coefficient of original dof `dofs[e]` in local component `c`.
    pub p: [[f64; 3]; 3],
    /// 3D: the rotation of the tangent plane from the candidate's tangents `(t1, t2)` to the
    /// frame's (`turn · (a1, a2)`); chosen so that a node held along one direction of its
    /// tangent plane has that direction as its second tangent, with no dof. The identity in
    /// 2D and for a node with three free dofs (an isotropic friction law does not depend on
    /// the choice of the tangents).
    pub turn: [[f64; 2]; 2],
    /// `(e, j, w)`: the contactor's dof `dofs[e]` moves with `w` times target dof `j` (its
    /// component `e`, weight `w_k` of its node); empty against a rigid obstacle.
    pub carry: Vec<(usize, usize, f64)>,
}

/// The rows of `H` on a node's free dofs that are closer to zero than this are empty.
const ROW_ZERO: f64 = 1e-10;

/// The frames of the active contacts (`N` rows of `H` per candidate), or why the primal
/// solve does not apply. `node_of(i)` is candidate `i`'s contactor node. The rows
/// on those dofs must be a rotation of them (with the normal among them, not along a
/// prescribed component); on any other dof `j` (a target node's component `e`), the rows must
/// be `−w` times their coefficients on the contactor's component `e` (which must then be
/// free: a target may not move along a prescribed component of its contactor). When that
/// fails for a node pair, the target node is renamed instead (its coefficients are `−P`, the
/// contactor's the carried ones). A renamed dof may belong to one candidate only and may not
/// be another candidate's target (no chains).
pub(crate) fn frames<S: Structure<N> + ?Sized, const N: usize>(
    structure: &S,
    h_rows: &[Vec<(usize, f64)>],
    candidates: &[usize],
    node_of: &dyn Fn(usize) -> usize,
) -> Result<Vec<LocalFrame>, String> {
    let dim = N;
    let mut owner = vec![false; structure.dof_count()];
    let mut out = Vec::with_capacity(candidates.len());
    let dofs_of =
        |node: usize| -> Vec<usize> { structure.node_dofs(node).into_iter().flatten().collect() };
    // the node of each dof, built when a pair needs its target renamed
    let mut node_of_dof: Vec<usize> = Vec::new();
    for &i in candidates {
        let rows = &h_rows[dim * i..dim * (i + 1)];
        let own = dofs_of(node_of(i));
        let frame = match frame_of(rows, i, &own) {
            Ok(f) => f,
            Err(e) => {
                // a contactor that cannot carry the jump (a prescribed component along which
                // its target moves, as a pile head lifted by a prescribed displacement): the
                // target's dofs are renamed instead when the target is one node (a node pair)
                if node_of_dof.is_empty() {
                    node_of_dof = vec![usize::MAX; structure.dof_count()];
                    for node in 0..structure.node_count() {
                        for d in dofs_of(node) {
                            if let Some(slot) = node_of_dof.get_mut(d) {
                                *slot = node;
                            }
                        }
                    }
                }
                let mut nodes: Vec<usize> = rows
                    .iter()
                    .flat_map(|r| r.iter().map(|&(d, _)| d))
                    .filter(|d| !own.contains(d))
                    .filter_map(|d| node_of_dof.get(d).copied())
                    .collect();
                nodes.sort_unstable();
                nodes.dedup();
                match nodes[..] {
                    [target] if target != usize::MAX => {
                        frame_of(rows, i, &dofs_of(target)).map_err(|_| e)?
                    }
                    _ => return Err(e),
                }
            }
        };
        for d in frame.dofs.into_iter().flatten() {
            if std::mem::replace(&mut owner[d], true) {
                return Err(format!("dof {d} belongs to two contact candidates"));
            }
        }
        out.push(frame);
    }
    for (f, &i) in out.iter().zip(candidates) {
        if let Some(&(_, j, _)) = f.carry.iter().find(|c| owner[c.1]) {
            return Err(format!(
                "candidate {i}: its target dof {j} is another candidate's contactor dof \
                 (a chain of contacts)"
            ));
        }
    }
    Ok(out)
}

/// The frame of candidate `i` from its rows of `H` (see [`frames`]).
fn frame_of(rows: &[Vec<(usize, f64)>], i: usize, own: &[usize]) -> Result<LocalFrame, String> {
    let dim = rows.len();
    let mut all: Vec<usize> = rows
        .iter()
        .flat_map(|r| r.iter().map(|&(d, _)| d))
        .collect();
    all.sort_unstable();
    all.dedup();
    let (dofs, targets): (Vec<usize>, Vec<usize>) = all.into_iter().partition(|d| own.contains(d));
    let s = dofs.len();
    let not_rotation = || {
        format!(
            "candidate {i}: its rows of H on its contactor node are not a rotation of its \
             displacement"
        )
    };
    if s > dim || s == 0 {
        return Err(not_rotation());
    }
    // a[c][e]: coefficient of dofs[e] in row c
    let mut a = [[0.0; 3]; 3];
    // h[t][c]: coefficient of target dof targets[t] in row c
    let mut h = vec![[0.0; 3]; targets.len()];
    for (c, row) in rows.iter().enumerate() {
        for &(d, v) in row {
            match dofs.binary_search(&d) {
                Ok(e) => a[c][e] += v,
                Err(_) => {
                    let t = targets.binary_search(&d).map_err(|_| not_rotation())?;
                    h[t][c] += v;
                }
            }
        }
    }
    let norm2 = |v: &[f64; 3]| v[..s].iter().map(|x| x * x).sum::<f64>();
    if (norm2(&a[0]) - 1.0).abs() > 1e-10 {
        return Err(format!(
            "candidate {i}: its normal is not a unit combination of its node's free dofs \
             (a normal along a prescribed component)"
        ));
    }
    let mut turn = [[1.0, 0.0], [0.0, 1.0]];
    // the frame's rows on the free dofs: the normal first, then the tangents that move
    let mut basis: Vec<(usize, [f64; 3])> = vec![(0, a[0])];
    if s == dim {
        basis.extend((1..dim).map(|c| (c, a[c])));
    } else if s == 2 && dim == 3 {
        // the tangent rows are t = g bᵀ (rank one) with b ⊥ n in the free dofs' plane: turn
        // the tangent plane so that g is the first tangent, the second one is held
        let b = [-a[0][1], a[0][0], 0.0];
        let g = [
            a[1][0] * b[0] + a[1][1] * b[1],
            a[2][0] * b[0] + a[2][1] * b[1],
        ];
        let gn = g[0].hypot(g[1]);
        let rank_one = (0..2).all(|e| {
            (a[1][e] - g[0] * b[e]).abs() < ROW_ZERO && (a[2][e] - g[1] * b[e]).abs() < ROW_ZERO
        });
        if (gn - 1.0).abs() > 1e-10 || !rank_one {
            return Err(not_rotation());
        }
        turn = [[g[0], g[1]], [-g[1], g[0]]];
        basis.push((1, b));
    } else if (1..dim).any(|c| norm2(&a[c]) > ROW_ZERO * ROW_ZERO) {
        // one free dof along the normal: the tangents must not move it
        return Err(not_rotation());
    }
    let mut frame = LocalFrame {
        dofs: [None; 3],
        p: [[0.0; 3]; 3],
        turn,
        carry: Vec::new(),
    };
    for (&(c, _), &d) in basis.iter().zip(&dofs) {
        frame.dofs[c] = Some(d);
    }
    for &(c, row) in &basis {
        for (e, &(ce, _)) in basis.iter().enumerate() {
            frame.p[c][ce] = row[e];
        }
    }
    let mut orth = 0.0;
    for (k, &(_, u)) in basis.iter().enumerate() {
        for (l, &(_, v)) in basis.iter().enumerate() {
            let dot: f64 = u[..s].iter().zip(&v[..s]).map(|(x, y)| x * y).sum();
            orth += (dot - if k == l { 1.0 } else { 0.0 }).abs();
        }
    }
    if orth > 1e-10 {
        return Err(not_rotation());
    }
    // each target dof's column of H is −w times the contactor's column of one component e
    // (the columns of a rotation are orthonormal)
    for (&j, hj) in targets.iter().zip(&h) {
        let dot = |e: usize| (0..dim).map(|c| a[c][e] * hj[c]).sum::<f64>();
        let e = (0..dim)
            .max_by(|&x, &y| dot(x).abs().total_cmp(&dot(y).abs()))
            .unwrap_or(0);
        let w = -dot(e);
        let off: f64 = (0..dim).map(|c| (hj[c] + w * a[c][e]).abs()).sum();
        if off > 1e-10 * w.abs().max(1.0) || w.abs() <= ROW_ZERO {
            return Err(if s < dim {
                format!(
                    "candidate {i}: a contact with a deformable target whose contactor node has \
                     a prescribed component along which the target moves (dof {j})"
                )
            } else {
                format!(
                    "candidate {i}: its rows of H on dof {j} are not a multiple of the \
                     contactor's (the jump is not a contactor's displacement minus a \
                     combination of target nodes' displacements)"
                )
            });
        }
        frame.carry.push((e, j, w));
    }
    Ok(frame)
}
