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
//!
//! At most `AUTO_CLASSIC_MAX_CONTACTS` contacts `Auto` runs the accelerated sweep first,
//! until it converges or its stall detector ends it at the window
//! `AUTO_REDUNDANT_STALL_WINDOW` ([`sweep_before_classic`]), then the classical solver with
//! its whole budget from the start (issue 37, ninth part). Measured on the three such files
//! of Siconos' collection: the sweep converges in 36 and 103 sweeps on FCLIB's
//! `Box_Stacks-i0122-82-5` and `LMGC_100_PR_PerioBox-i00361-60-03000`, where the classical
//! solver's first Signorini sub-problem never ends (5 026 and 10 000 sweeps at residual
//! 3e-2 and 7e-2); on `BoxesStack1-i100000-32` it plateaus at 2.7e-5 from sweep 75 and the
//! detector ends it at sweep 147, before the classical solver's 3 781 sweeps.

use crate::local::csr::CsrMatrix;
use crate::local::problem::ReducedProblem;
use crate::local::settings::{Algorithm, UzawaSettings};

/// The stall window of the accelerated sweep that [`Algorithm::Auto`] runs before the
/// classical solver on redundant contacts ([`sweep_before_classic`]; the detector's rule in
/// `local/stall.rs`: no halving over `max(window, k/2)` sweeps). 50, measured on the sweep's
/// histories: `LMGC_100_PR_PerioBox` and `Box_Stacks` converge under any window from 10 up
/// (the longest plateau, 18 sweeps, comes after sweep 60); on `BoxesStack1` the `k/2` term
/// ends the sweep at sweep 147 under any window up to 74; over the generated stacks of the
/// tests (5–40 blocks, lighter or heavier upwards, pushed sideways; 96 problems), every
/// sweep that converges within 100 sweeps passes a window of 41, the slower ones need 52 to
/// 3 076 (those `Auto` hands to the classical solver, as it did before this rule).
const AUTO_REDUNDANT_STALL_WINDOW: usize = 50;

/// The settings of the accelerated sweep that [`Algorithm::Auto`] runs first on a small `W`
/// of redundant contacts ([module docs](self)): `st`'s, the accelerated Gauss–Seidel sweep,
/// the stall detector's window at most `AUTO_REDUNDANT_STALL_WINDOW` (also where the user
/// switched the detector off: the window is part of `Auto`'s rule).
pub(in crate::local::solver) fn sweep_before_classic(st: UzawaSettings) -> UzawaSettings {
    let window = match st.tuning.stall_window {
        0 => AUTO_REDUNDANT_STALL_WINDOW,
        w => w.min(AUTO_REDUNDANT_STALL_WINDOW),
    };
    UzawaSettings {
        algorithm: Algorithm::AndersonGaussSeidel,
        tuning: st.tuning.with_stall_window(window),
        ..st
    }
}

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
        block_stack_with(b, 1.0, 0.0)
    }

    /// [`block_stack`] with body `k`'s inverse mass `g^k` (`g < 1`: heavier upwards, `W`
    /// worse conditioned) and a tangential free velocity at each face, `push` at its first
    /// point and `0.3 push` at its second (`μ = 0.5`).
    fn block_stack_with(b: usize, g: f64, push: f64) -> ReducedProblem {
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
            q[3 * i + 1] = if i % 2 == 0 { push } else { 0.3 * push };
            for j in 0..nc {
                let wij: f64 = (1..=b)
                    .map(|body| h(i, body) * h(j, body) * g.powi(body as i32))
                    .sum();
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

    /// Each face's pair of normal reactions of `block_stack(b)`'s answer `r` sums to the known
    /// load `R_k` within 1e-5 relative (the residual tolerance 1e-8 times the conditioning of
    /// the stack's chain, about `b²`), the friction forces vanish within 1e-5.
    fn assert_known_loads(b: usize, r: &[f64]) {
        for k in 1..=b {
            let c = 2 * (k - 1);
            let load = r[3 * c] + r[3 * c + 3];
            let weight = (k..=b).sum::<usize>() as f64;
            assert!(
                (load - weight).abs() <= 1e-5 * weight,
                "{b} {k}: {load} {weight}"
            );
            let tangential = [1, 2, 4, 5].map(|a| r[3 * c + a].abs());
            assert!(tangential.iter().all(|&t| t <= 1e-5 * weight), "{b} {k}");
        }
    }

    /// Issue 37, eighth part: `Auto` on a stack of blocks with redundant contacts takes the
    /// accelerated sweep at 140 contacts (where it took Newton before), and (ninth part) at
    /// 20 too, where the eighth part's rule ran the classical solver (785 sweeps against the
    /// sweep's 11); both answers carry the known loads ([`assert_known_loads`]).
    #[test]
    fn issue_37_redundant_stack_auto_choice() {
        use crate::local::{Algorithm, UzawaSettings, UzawaSolver};
        for b in [10, 70] {
            let p = block_stack(b);
            assert!(redundant_contacts(&p), "{b}");
            let st = UzawaSettings::default().with_algorithm(Algorithm::Auto);
            let sol = UzawaSolver::new(st).solve(&p, &p.coulomb_laws()).unwrap();
            assert!(sol.report.converged, "{b}");
            assert_eq!(sol.report.algorithm, Algorithm::AndersonGaussSeidel, "{b}");
            assert_known_loads(b, &sol.r);
        }
    }

    /// Issue 37, ninth part: on redundant contacts at most `AUTO_CLASSIC_MAX_CONTACTS`,
    /// `Auto` runs the accelerated sweep first. On a stack of 30 blocks (60 contacts) it is the
    /// sweep alone (the same sweeps, the known loads), where the eighth part's rule ran the
    /// classical solver's whole budget first (6 250 sweeps; the test fails there on the
    /// algorithm). On a stack heavier upwards and pushed sideways, where the sweep stalls
    /// (at sweep 59; it would converge at 273) and the classical solver converges (8 560
    /// sweeps), `Auto` hands over to the classical solver from the start: its answer is the
    /// classical solver's alone, exactly, after the sweep's stalled sweeps.
    #[test]
    fn issue_37_redundant_stack_sweeps_first() {
        use crate::local::{Algorithm, UzawaSettings, UzawaSolver};
        let solve = |p: &ReducedProblem, st: UzawaSettings| {
            UzawaSolver::new(st).solve(p, &p.coulomb_laws())
        };
        let alone = |algorithm| {
            UzawaSettings::default()
                .with_algorithm(algorithm)
                .with_fallback(false)
        };
        let auto = UzawaSettings::default().with_algorithm(Algorithm::Auto);
        let p = block_stack(30);
        let sol = solve(&p, auto).unwrap();
        let sweep = solve(&p, alone(Algorithm::AndersonGaussSeidel)).unwrap();
        let classic = solve(&p, alone(Algorithm::ClassicRccm)).unwrap();
        assert_eq!(sol.report.algorithm, Algorithm::AndersonGaussSeidel);
        assert_eq!(sol.report.iterations, sweep.report.iterations);
        // the premise: the classical solver is the slow one here (6 250 sweeps against 31)
        assert!(classic.report.iterations > 100 * sweep.report.iterations);
        assert_known_loads(30, &sol.r);

        let p = block_stack_with(5, 0.3, 0.45);
        assert!(redundant_contacts(&p));
        let sol = solve(&p, auto).unwrap();
        let stalled = UzawaSolver::new(sweep_before_classic(auto).with_accept_non_converged(true))
            .solve(&p, &p.coulomb_laws())
            .unwrap();
        assert!(stalled.report.stalled && !stalled.report.converged);
        let classic = solve(&p, alone(Algorithm::ClassicRccm)).unwrap();
        assert_eq!(sol.report.algorithm, Algorithm::ClassicRccm);
        let spent = stalled.report.iterations + classic.report.iterations;
        assert_eq!(sol.report.iterations, spent);
        assert_eq!(sol.r, classic.r);
    }
}
