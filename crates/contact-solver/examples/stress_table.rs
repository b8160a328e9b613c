//! Runs the numerical-stability stress suite of `tests/integration/stress.rs` and prints its table
//! (markdown) for `docs/validation.md`: per case the steps, the solver sweeps summed over the
//! steps, the adhesion fixed-point iterations, the largest final residual of its steps, the
//! outcome and what the checks measured.
//!
//! ```text
//! cargo run --release -p contact-solver --example stress_table
//! ```
//! A case that panics is reported as such (the suite itself would fail). Cases with a known
//! bug are run too and marked.

#[path = "../tests/support/hertz_scene.rs"]
mod hertz_scene;
#[path = "../tests/support/stress_cases/mod.rs"]
mod stress_cases;

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::time::Instant;
use stress_cases::{Outcome, Record, all_cases};

fn main() {
    let start = Instant::now();
    // keep the table clean: a panicking case is reported in its row
    std::panic::set_hook(Box::new(|_| {}));
    println!(
        "| group | case | steps | sweeps | adh. it. | max residual | outcome | checks (measured) |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    let mut bad = 0;
    for case in all_cases() {
        let record = catch_unwind(AssertUnwindSafe(|| case.run())).unwrap_or_else(|p| {
            let msg = p
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            Record {
                group: case.group,
                case: case.name.clone(),
                steps: 0,
                iterations: 0,
                adhesion_iterations: 0,
                residual: f64::NAN,
                note: String::new(),
                outcome: Outcome::Panic(msg),
                time: Default::default(),
            }
        });
        bad += usize::from(!record.ok());
        let mut outcome = record.outcome_cell();
        if case.bug.is_some() {
            outcome = format!("known bug — {outcome}");
        }
        println!(
            "| {} | {} | {} | {} | {} | {:.1e} | {} | {} |",
            record.group,
            record.case.trim_start(),
            record.steps,
            record.iterations,
            record.adhesion_iterations,
            record.residual,
            outcome.replace('|', "\\|"),
            record.note.replace('|', "\\|"),
        );
    }
    eprintln!(
        "{} cases not converged correctly; wall time {:.2?}",
        bad,
        start.elapsed()
    );
}
