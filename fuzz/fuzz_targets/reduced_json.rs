//! A reduced problem's JSON through `ReducedProblem::from_json` and, when it is valid, a
//! bounded solve: an error, or an answer whose every number is finite.
#![no_main]
use contact_solver::{ReducedProblem, UzawaSettings, solve_coulomb};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(problem) = ReducedProblem::from_json(text) else {
        return;
    };
    let settings = UzawaSettings::default().with_max_iterations(500);
    if let Ok(sol) = solve_coulomb(&problem, &settings) {
        assert!(
            sol.r.iter().chain(&sol.x).all(|v| v.is_finite()),
            "a solve returned a non-finite number"
        );
    }
});
