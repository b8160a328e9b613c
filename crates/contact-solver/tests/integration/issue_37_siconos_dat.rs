//! Siconos' numerics `.dat` friction-contact files (issue 37): the files of `tests/data/siconos/`
//! were written by Siconos' own writers (`frictionContact_printInFilename`,
//! `globalFrictionContact_printInFileName`, see `make.py` there) from problems of ours, so the
//! expected `W`, `q`, `μ` are the numbers handed to Siconos; round trips through our writer
//! are bit-identical; hostile files are errors naming the line, never panics.

use contact_solver::local::generate::{random_problem_in, random_sparse_problem};
use contact_solver::local::siconos_dat::{DatSource, read_siconos_dat, write_siconos_dat};
use contact_solver::{ReducedProblem, SolverError, UzawaSettings, solve_coulomb};
use proptest::prelude::*;

fn data(name: &str) -> String {
    let path = format!("{}/tests/data/siconos/{name}", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// `W[i][j]` of a problem, whatever its storage.
fn w(p: &ReducedProblem, i: usize, j: usize) -> f64 {
    let m = p.size();
    match (p.w_dense(), p.w_sparse()) {
        (Some(a), _) => a[i * m + j],
        (_, Some(s)) => s.get(i, j),
        _ => unreachable!(),
    }
}

fn line_of(e: &SolverError) -> usize {
    match e {
        SolverError::SiconosDat { line, .. } => *line,
        other => panic!("expected SiconosDat, got {other:?}"),
    }
}

#[test]
fn issue_37_reads_siconos_written_dense_3d_as_given() {
    let d = read_siconos_dat(&data("dense_3d.dat")).unwrap();
    let p = &d.problem;
    assert_eq!(d.source, DatSource::Local);
    assert_eq!((p.dimension(), p.contact_count()), (3, 2));
    // exact: Siconos prints 25 significant digits, more than f64 needs
    assert_eq!((w(p, 0, 2), w(p, 2, 0), w(p, 2, 5)), (0.2, 0.3, 0.5));
    assert_eq!(p.q(), &[-1.0, 0.5, 0.25, -2.0, 0.0, 1.0]);
    assert_eq!(p.mu(), &[0.3, 0.5]);
    assert!(
        !p.is_symmetric(),
        "W[0][2] = 0.2 but W[2][0] = 0.3: kept as given"
    );
}

/// A local file whose `q` holds integers one to a line, as Siconos' `FrictionContact3D_1c.dat`
/// does: its first value after `W` looks like a global file's storage type, and the reader
/// took it for one ("the storage type of `H` = -1 is out of range"). The values left (exactly
/// `q` and `mu`) say it is local.
#[test]
fn issue_37_integer_q_one_per_line_is_local() {
    let text = "3\n1\n\n0\n3\n3\n\n3\n3\n\n15\n-1\n-2\n\n-1\n14\n1\n\n-2\n1\n16\n\n\
                -1\n2\n3\n\n0.1\n";
    let d = read_siconos_dat(text).unwrap();
    assert_eq!(d.source, DatSource::Local);
    let p = &d.problem;
    assert_eq!((p.dimension(), p.contact_count()), (3, 1));
    // exact: small integers; dense storage is column by column, this W is symmetric
    assert_eq!(
        (w(p, 0, 0), w(p, 0, 1), w(p, 2, 0), w(p, 2, 2)),
        (15.0, -1.0, -2.0, 16.0)
    );
    assert_eq!(p.q(), &[-1.0, 2.0, 3.0]);
    assert_eq!(p.mu(), &[0.1]);
    // the older files' trailing flag after `mu` is still skipped
    let d = read_siconos_dat(&format!("{text}\n1\n")).unwrap();
    assert_eq!(d.source, DatSource::Local);
}

/// Siconos' test folders also hold files that are not friction-contact problems (a lone sparse
/// block matrix, an MLCP, the arguments of a function test): each is refused on line 1 with a
/// reason that says so, never read as a problem.
#[test]
fn issue_37_files_that_are_not_problems_are_refused_by_name() {
    for (text, says) in [
        ("1000\n0.0\n0.0\n-0.67\n", "not a friction-contact problem"),
        ("4\n2\n2\n3\t6\n3\t6\n", "not a friction-contact problem"),
        ("1\n1\n3\n4\n0 3 7\n", "MLCPs"),
    ] {
        let e = read_siconos_dat(text).unwrap_err();
        assert!(matches!(e, SolverError::SiconosDat { line: 1, .. }), "{e}");
        assert!(e.to_string().contains(says), "{e}");
    }
}

#[test]
fn issue_37_reads_siconos_written_dense_2d() {
    let p = read_siconos_dat(&data("dense_2d.dat")).unwrap().problem;
    assert_eq!((p.dimension(), p.contact_count()), (2, 3));
    assert_eq!(
        (w(&p, 0, 1), w(&p, 1, 0), w(&p, 4, 5), w(&p, 5, 4)),
        (0.3, 0.2, 0.25, 0.0)
    );
    assert_eq!(p.mu(), &[0.3, 0.5, 0.1]);
}

#[test]
fn issue_37_reads_sparse_blocks_column_by_column() {
    // blocks_3d_in.dat by hand and blocks_3d.dat as Siconos wrote it back: the same W. Each
    // block is stored column-major (Siconos' NM_get_value on the hand-written file gives
    // W[1][0] = 0.1 and W[0][1] = 0.5 for the block 4, 0.1, 0.3 | 0.5, 3, 0 | 0.2, 0, 2).
    let a = read_siconos_dat(&data("blocks_3d_in.dat")).unwrap().problem;
    let b = read_siconos_dat(&data("blocks_3d.dat")).unwrap().problem;
    assert_eq!(a, b);
    assert_eq!(
        (w(&a, 1, 0), w(&a, 0, 1), w(&a, 0, 2), w(&a, 2, 0)),
        (0.1, 0.5, 0.2, 0.3)
    );
    // the off-diagonal block (0, 1) and the empty block (1, 0)
    assert_eq!(
        (w(&a, 0, 3), w(&a, 1, 4), w(&a, 2, 5), w(&a, 3, 0)),
        (0.5, 0.25, -0.125, 0.0)
    );
    assert_eq!((w(&a, 4, 5), w(&a, 5, 5)), (0.5, 2.0));
}

#[test]
fn issue_37_global_problem_condenses_to_the_hand_computed_w() {
    // M = diag(2, 2, 2, 1, 1, 1), H = [I; diag(−1, −0.5, 0.25)], q = (0, 0, −1, 0.5, 0, 0.25),
    // b = (−0.1, 0, 0): W = Hᵀ M⁻¹ H = diag(1.5, 0.75, 0.5625), q_loc = Hᵀ M⁻¹ q + b
    // = (−0.6, 0, −0.4375) (numpy gives the same, make.py prints it)
    let d = read_siconos_dat(&data("global_3d.dat")).unwrap();
    assert_eq!(d.source, DatSource::Global { dofs: 6 });
    let p = &d.problem;
    let expected_w = [1.5, 0.75, 0.5625];
    for (i, &diagonal) in expected_w.iter().enumerate() {
        for j in 0..3 {
            let e = if i == j { diagonal } else { 0.0 };
            // one LU solve of a diagonal M: round-off only
            assert!(
                (w(p, i, j) - e).abs() < 1e-15,
                "W[{i}][{j}] = {}",
                w(p, i, j)
            );
        }
    }
    for (got, e) in p.q().iter().zip([-0.6, 0.0, -0.4375]) {
        assert!((got - e).abs() < 1e-15, "q = {:?}", p.q());
    }
    assert_eq!(p.mu(), &[0.4]);
}

#[test]
fn issue_37_round_trip_is_bit_identical_dense_and_sparse() {
    for (dim, nc, seed) in [(2, 7, 1), (3, 5, 2), (3, 1, 3)] {
        let p = random_problem_in(dim, nc, seed);
        let back = read_siconos_dat(&write_siconos_dat(&p)).unwrap();
        assert_eq!(back.problem, p, "dense, dim {dim}");
    }
    for (dim, nc, seed) in [(2, 40, 4), (3, 30, 5)] {
        let p = random_sparse_problem(dim, nc, 2, seed);
        assert!(p.is_sparse());
        let text = write_siconos_dat(&p);
        assert!(text.lines().nth(2) == Some("1"), "written in sparse blocks");
        let back = read_siconos_dat(&text).unwrap().problem;
        assert!(back.is_sparse());
        assert_eq!(back, p, "sparse, dim {dim}");
    }
}

#[test]
fn issue_37_a_read_problem_solves() {
    // frictionless check on the 2D file is not closed-form; the answer is judged by the
    // solver's own residual at 1e-10 and by x = W r + q ≥ 0 where r_n = 0
    let p = read_siconos_dat(&data("dense_2d.dat")).unwrap().problem;
    let sol = solve_coulomb(&p, &UzawaSettings::default()).unwrap();
    assert!(sol.report.converged);
    assert!(sol.r.iter().step_by(2).all(|&rn| rn >= 0.0));
}

/// The file with token `k` (counted over the whole file) replaced by `by`.
fn with_token(text: &str, k: usize, by: &str) -> String {
    let mut n = 0;
    let mut out = String::new();
    for line in text.lines() {
        let toks: Vec<String> = line
            .split_whitespace()
            .map(|t| {
                n += 1;
                if n - 1 == k {
                    by.to_string()
                } else {
                    t.to_string()
                }
            })
            .collect();
        out.push_str(&toks.join(" "));
        out.push('\n');
    }
    out
}

#[test]
fn issue_37_read_siconos_dat_captures_errors() {
    let good = data("dense_3d.dat");
    let reason = |text: &str| read_siconos_dat(text).unwrap_err().to_string();
    // dimension 5: rolling friction, by name, line 1
    let e = read_siconos_dat(&with_token(&good, 0, "5")).unwrap_err();
    assert_eq!(line_of(&e), 1);
    assert!(e.to_string().contains("rolling"), "{e}");
    assert!(reason(&with_token(&good, 0, "4")).contains("dimension 4"));
    // wrong contact count: W is 6 x 6, 3 contacts need 9 x 9
    assert!(reason(&with_token(&good, 1, "3")).contains("need 9 x 9"));
    // one contact: W (6 x 6) does not match 3 x 3
    assert!(reason(&with_token(&good, 1, "1")).contains("need 3 x 3"));
    // NaN and garbage in W (token 8 is W[0][0], on line 7)
    let e = read_siconos_dat(&with_token(&good, 8, "NaN")).unwrap_err();
    assert_eq!(line_of(&e), 7);
    assert!(e.to_string().contains("not finite"), "{e}");
    assert!(reason(&with_token(&good, 8, "1.0.0")).contains("not a number"));
    // storage type 2 and 7
    assert!(reason(&with_token(&good, 2, "2")).contains("CSparse"));
    assert!(reason(&with_token(&good, 2, "7")).contains("storage type 7"));
    // the repeated dense header disagrees
    assert!(reason(&with_token(&good, 5, "5")).contains("dense header says 5 x 6"));
    // truncated: the last line (mu) cut
    let cut: String = good
        .lines()
        .take(good.lines().count() - 1)
        .collect::<Vec<_>>()
        .join("\n");
    assert!(reason(&cut).contains("`mu` needs 2 values"));
    // a rolling problem's mu_r line after mu
    let rolling = format!("{good} 0.1 0.1\n");
    assert!(reason(&rolling).contains("mu_r"));
    // Siconos' trailing flag is accepted
    assert!(read_siconos_dat(&format!("{good}0\n")).is_ok());
    // a huge size fails on the count of values left, before anything is allocated
    let huge = "3\n1\n0\n3000000000\n3000000000\n3000000000\t3000000000\n1\n";
    assert!(reason(huge).contains("out of range") || reason(huge).contains("left"));
    // a negative μ: the problem's own check
    assert!(matches!(
        read_siconos_dat(&good.replace("2.999999999999999888977698e-01", "-0.3")),
        Err(SolverError::InvalidLaw { contact: 0, .. })
    ));
    assert!(read_siconos_dat("").is_err());
}

#[test]
fn issue_37_sparse_block_errors_name_the_line() {
    let good = data("blocks_3d_in.dat");
    let reason = |text: &str| read_siconos_dat(text).unwrap_err().to_string();
    // tokens: 0 dim, 1 nc, 2 storage, 3-4 sizes, 5 nbblocks, 6-7 block rows/cols,
    // 8-9 blocksize0, 10-11 blocksize1, 12 filled1, 13 filled2, 14-16 index1, 17-19 index2,
    // 20 the label of block 0
    assert!(reason(&with_token(&good, 9, "5")).contains("not at the matrix size 6"));
    assert!(reason(&with_token(&good, 9, "3")).contains("must increase"));
    assert!(reason(&with_token(&good, 12, "4")).contains("filled1 = 4"));
    assert!(reason(&with_token(&good, 15, "4")).contains("index1"));
    assert!(reason(&with_token(&good, 18, "2")).contains("index2[1]"));
    let e = read_siconos_dat(&with_token(&good, 20, "1")).unwrap_err();
    assert!(e.to_string().contains("labelled 1"), "{e}");
    assert_eq!(line_of(&e), 15);
    // the same block twice: (0, 1) and (0, 1)
    assert!(reason(&with_token(&good, 17, "1")).contains("twice"));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]
    /// Any token replaced by a hostile one, or the file cut anywhere: an answer or an error,
    /// never a panic, and an error names a line of the file.
    #[test]
    fn issue_37_fuzzed_files_never_panic(
        file in 0..3usize,
        k in 0..200usize,
        by in prop::sample::select(vec![
            "-1", "0", "1", "2", "3", "5", "99999999999", "1e308", "-1e308", "nan", "inf",
            "-0", "0.5", "x", "18446744073709551616", "-9223372036854775808",
        ]),
        cut in 0..2000usize,
    ) {
        let text = data(["dense_3d.dat", "blocks_3d_in.dat", "global_3d.dat"][file]);
        let lines = text.lines().count();
        let mutated = with_token(&text, k, by);
        let truncated: String = text.chars().take(cut).collect();
        for t in [mutated, truncated] {
            if let Err(SolverError::SiconosDat { line, .. }) = read_siconos_dat(&t) {
                prop_assert!(line >= 1 && line <= lines.max(1));
            }
        }
    }
}
