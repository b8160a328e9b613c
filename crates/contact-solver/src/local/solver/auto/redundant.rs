//! Redundant contacts (issue 37, eighth part): a multibody `W = H M⁻¹ Hᵀ` where every contact
//! shares its pair of bodies with another (a face resting on a face at four corners: Siconos'
//! `KaplasTower-i1061-4`, `BoxesStack1-i100000-32`). Two contacts between the same bodies
//! couple to the same contacts, so their block rows of `W` have the same pattern; `W` is then
//! rank-deficient by construction (at least `d` rows a face beyond the 6 freedoms a body
//! pair leaves), Newton's plain steps fail on it and each is retried with the proximal `η`.
//!
//! Measured (`docs/benchmarks.md`, "Auto on redundant contacts"), Siconos' 3D `.dat` files:
//! the share of contacts whose block-row pattern repeats is 1.00 on the kapla tower and the
//! box stack, 0.90 on `Confeti-ex13-Fc3D-SBM`, 0.71–0.77 on the capsules (kept
//! non-symmetric), 0.00–0.22 on the sphere piles (`NESpheres_*`; spheres touch once, as in
//! the shaken pile of 805 contacts where Newton wins 4×). On the kapla tower Newton's
//! sparse LU costs about 60 ms a factorisation against the whole sweep's 31 ms; on the box
//! stack every sweep and Newton stall and only the classical solver converges.

use crate::local::csr::CsrMatrix;
use crate::local::problem::ReducedProblem;

/// Whether `W` is stored sparse, is symmetric, and every contact's block-row pattern (the
/// contacts it couples to) is also another contact's, the pattern not being the whole
/// problem (on a fully coupled `W` every pattern repeats trivially). Two contacts of the same
/// pattern couple to each other, so a contact's twin is looked for among the contacts of its
/// own pattern; the first contact without one ends the test (no allocation).
pub(in crate::local::solver) fn redundant_contacts(problem: &ReducedProblem) -> bool {
    let Some(a) = problem.w_sparse() else {
        return false;
    };
    let (nc, d) = (problem.contact_count(), problem.dimension());
    if nc < 2 || !problem.is_symmetric() {
        return false;
    }
    (0..nc).all(|i| {
        let blocks = block_columns(a.row(d * i).0, d);
        blocks.clone().count() < nc
            && blocks
                .filter(|&j| j != i)
                .any(|j| (0..d).all(|k| same_blocks(a, d, d * i + k, d * j + k)))
    })
}

/// The block columns (contacts) of a row's sorted column indices, each once.
fn block_columns(cols: &[u32], d: usize) -> impl Iterator<Item = usize> + Clone + '_ {
    let block = move |c: &u32| *c as usize / d;
    cols.iter()
        .enumerate()
        .filter(move |&(k, c)| k == 0 || block(&cols[k - 1]) != block(c))
        .map(move |(_, c)| block(c))
}

/// Whether rows `x` and `y` of `a` couple to the same contacts.
fn same_blocks(a: &CsrMatrix, d: usize, x: usize, y: usize) -> bool {
    block_columns(a.row(x).0, d).eq(block_columns(a.row(y).0, d))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::local::Asymmetry;

    /// Block pattern of `n` contacts in pairs (contacts `2k`, `2k+1` between the same two
    /// bodies, pair `k` coupled to pair `k±1` through a shared body): a stack of blocks, each
    /// face resting at two points.
    fn stack(pairs: usize, d: usize, extra: Option<(usize, usize)>) -> ReducedProblem {
        let nc = 2 * pairs;
        let coupled = |i: usize, j: usize| {
            (i / 2).abs_diff(j / 2) <= 1
                || extra.is_some_and(|(a, b)| (i, j) == (a, b) || (j, i) == (a, b))
        };
        let (mut rows, mut cols, mut vals) = (vec![], vec![], vec![]);
        for i in 0..nc {
            for j in (0..nc).filter(|&j| coupled(i, j)) {
                for a in 0..d {
                    for b in 0..d {
                        rows.push(d * i + a);
                        cols.push(d * j + b);
                        vals.push(if i == j && a == b {
                            4.0
                        } else if a == b {
                            0.5
                        } else {
                            0.0
                        });
                    }
                }
            }
        }
        ReducedProblem::from_triplets(d, &rows, &cols, &vals, vec![-1.0; d * nc], vec![0.3; nc])
            .unwrap()
    }

    /// Pairs of contacts that share their bodies are redundant; one extra coupling that makes a
    /// contact's pattern unique is not; a fully coupled `W`, a dense one and one contact are
    /// not.
    #[test]
    fn issue_37_redundant_contacts_works() {
        assert!(redundant_contacts(&stack(10, 3, None)));
        assert!(redundant_contacts(&stack(10, 2, None)));
        assert!(!redundant_contacts(&stack(10, 3, Some((0, 9)))));
        // two pairs, all coupled: every pattern is the whole problem
        assert!(!redundant_contacts(&stack(2, 3, None)));
        let w = vec![
            2.0, 0.5, 0.0, 0.0, //
            0.5, 2.0, 0.0, 0.0, //
            0.0, 0.0, 2.0, 0.0, //
            0.0, 0.0, 0.0, 2.0,
        ];
        let dense =
            ReducedProblem::with_asymmetry(2, w, vec![-1.0; 4], vec![0.3; 2], Asymmetry::Keep);
        assert!(!redundant_contacts(&dense.unwrap()));
        let sparse = crate::local::generate::random_sparse_problem(3, 50, 0, 2);
        assert!(!redundant_contacts(&sparse));
    }

    /// A stack of `b` blocks on the ground (3 translations each, unit mass), each face
    /// resting at two points with the same `H` rows: `W = H Hᵀ`, rank-deficient by `3b`;
    /// body `k` falls at free speed `k` (`q = H v_free`: every face closes at speed 1). Known
    /// answer (every body stopped, `v_free,k + R_k − R_{k+1} = 0`): the two normal reactions of
    /// face `k` (from the ground, `k = 1`) carry `R_k = Σ_{j=k..b} j` together, no friction.
    fn block_stack(b: usize) -> ReducedProblem {
        let nc = 2 * b;
        // contact c (face k = c / 2 + 1) presses body k up and body k − 1 down (0: ground)
        let h = |c: usize, body: usize| -> f64 {
            let k = c / 2 + 1;
            if body == k {
                1.0
            } else if body + 1 == k {
                -1.0
            } else {
                0.0
            }
        };
        let (mut rows, mut cols, mut vals) = (vec![], vec![], vec![]);
        let mut q = vec![0.0; 3 * nc];
        for i in 0..nc {
            q[3 * i] = -1.0; // body k falls at speed k: every face closes at speed 1
            for j in 0..nc {
                let wij: f64 = (1..=b).map(|body| h(i, body) * h(j, body)).sum();
                if wij != 0.0 {
                    for a in 0..3 {
                        rows.push(3 * i + a);
                        cols.push(3 * j + a);
                        vals.push(wij);
                    }
                }
            }
        }
        ReducedProblem::from_triplets(3, &rows, &cols, &vals, q, vec![0.5; nc]).unwrap()
    }

    /// Issue 37, eighth part: `Auto` on a stack of blocks with redundant contacts takes the
    /// classical solver at 20 contacts and the accelerated sweep at 140 (where it took Newton
    /// before), and both answers carry the known loads: each face's pair of normal reactions
    /// sums to the known load `R_k` within 1e-5 relative (the residual tolerance 1e-8 times the
    /// conditioning of the stack's chain, about `b²`), the friction forces within 1e-5.
    #[test]
    fn issue_37_redundant_stack_auto_choice() {
        use crate::local::{Algorithm, UzawaSettings, UzawaSolver};
        for (b, picked) in [
            (10, Algorithm::ClassicRccm),
            (70, Algorithm::AndersonGaussSeidel),
        ] {
            let p = block_stack(b);
            assert!(redundant_contacts(&p), "{b}");
            let st = UzawaSettings::default().with_algorithm(Algorithm::Auto);
            let sol = UzawaSolver::new(st).solve(&p, &p.coulomb_laws()).unwrap();
            assert!(sol.report.converged, "{b}");
            assert_eq!(sol.report.algorithm, picked, "{b}");
            for k in 1..=b {
                let c = 2 * (k - 1);
                let load = sol.r[3 * c] + sol.r[3 * c + 3];
                let weight = (k..=b).sum::<usize>() as f64;
                assert!(
                    (load - weight).abs() <= 1e-5 * weight,
                    "{b} {k}: {load} {weight}"
                );
                let tangential = [1, 2, 4, 5].map(|a| sol.r[3 * c + a].abs());
                assert!(tangential.iter().all(|&t| t <= 1e-5 * weight), "{b} {k}");
            }
        }
    }
}
