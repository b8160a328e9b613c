//! Replays the reduced-problem fuzz corpus (`fuzz/corpus/reduced_json`, grown by
//! `fuzz/run.sh`) on the stable toolchain, as the fuzz target does: `from_json`, then a
//! solve capped at 500 iterations when the problem is valid. Every input must give an error
//! or an answer whose every number is finite (exact: no tolerance).
#![cfg(feature = "serde")]

use contact_solver::{ReducedProblem, UzawaSettings, solve_coulomb};
use std::path::Path;

#[test]
fn every_reduced_json_corpus_input_gives_an_error_or_a_finite_answer() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fuzz/corpus/reduced_json");
    let settings = UzawaSettings::default().with_max_iterations(500);
    let (mut count, mut solved) = (0, 0);
    for entry in std::fs::read_dir(&dir).expect("fuzz/corpus/reduced_json exists") {
        let path = entry.unwrap().path();
        let bytes = std::fs::read(&path).unwrap();
        count += 1;
        let Ok(text) = std::str::from_utf8(&bytes) else {
            continue;
        };
        let Ok(problem) = ReducedProblem::from_json(text) else {
            continue;
        };
        if let Ok(sol) = solve_coulomb(&problem, &settings) {
            assert!(
                sol.r.iter().chain(&sol.x).all(|v| v.is_finite()),
                "{}: a non-finite answer",
                path.display()
            );
            solved += 1;
        }
    }
    assert!(count >= 40, "only {count} inputs in {}", dir.display());
    eprintln!("{count} inputs, {solved} solved");
}
