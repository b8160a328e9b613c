//! Invalid reduced problems are rejected with the exact error variant (STYLE §4: user data
//! never panics), and the JSON form round-trips.

use contact_solver::contact_laws::LawError;
#[cfg(feature = "serde")]
use contact_solver::local::generate::random_problem;
use contact_solver::{ReducedProblem, SolverError};

fn eye() -> Vec<f64> {
    vec![1.0, 0.0, 0.0, 1.0]
}

#[test]
fn new_captures_wrong_sizes() {
    assert!(matches!(
        ReducedProblem::new(vec![1.0; 3], vec![-1.0, 0.0], vec![0.1]),
        Err(SolverError::SizeMismatch {
            what: "W",
            expected: 4,
            found: 3
        })
    ));
    assert!(matches!(
        ReducedProblem::new(eye(), vec![-1.0, 0.0], vec![0.1, 0.2]),
        Err(SolverError::SizeMismatch {
            what: "mu",
            expected: 1,
            found: 2
        })
    ));
    assert!(matches!(
        ReducedProblem::new(vec![1.0], vec![-1.0], vec![]),
        Err(SolverError::SizeMismatch { what: "q", .. })
    ));
}

#[test]
fn new_captures_nan() {
    let mut w = eye();
    w[3] = f64::NAN;
    assert!(matches!(
        ReducedProblem::new(w, vec![-1.0, 0.0], vec![0.1]),
        Err(SolverError::NonFinite {
            what: "W",
            index: 3,
            ..
        })
    ));
    assert!(matches!(
        ReducedProblem::new(eye(), vec![-1.0, f64::INFINITY], vec![0.1]),
        Err(SolverError::NonFinite {
            what: "q",
            index: 1,
            ..
        })
    ));
}

#[test]
fn new_captures_asymmetric_w() {
    let e = ReducedProblem::new(vec![1.0, 0.1, 0.0, 1.0], vec![-1.0, 0.0], vec![0.1]);
    assert!(matches!(
        e,
        Err(SolverError::NotSymmetric { row: 0, col: 1, .. })
    ));
    // A relative asymmetry of 1e-14 (rounding of H K⁻¹ Hᵀ) is accepted.
    let e = ReducedProblem::new(vec![1.0, 0.1, 0.1 + 1e-15, 1.0], vec![-1.0, 0.0], vec![0.1]);
    assert!(e.is_ok());
}

#[test]
fn new_captures_negative_mu() {
    let e = ReducedProblem::new(eye(), vec![-1.0, 0.0], vec![-0.1]).unwrap_err();
    assert!(matches!(
        e,
        SolverError::InvalidLaw {
            contact: 0,
            source: LawError::InvalidParameter { name: "mu", .. }
        }
    ));
    assert!(e.to_string().contains("contact 0"));
}

#[cfg(feature = "serde")]
#[test]
fn json_round_trip_works() {
    let p = random_problem(10, 7);
    let back = ReducedProblem::from_json(&p.to_json().unwrap()).unwrap();
    assert_eq!(back, p);
}

#[cfg(feature = "serde")]
#[test]
fn from_json_captures_errors() {
    assert!(matches!(
        ReducedProblem::from_json("{"),
        Err(SolverError::Json { .. })
    ));
    assert!(matches!(
        ReducedProblem::from_json(r#"{"W":[[1,0],[0,1]],"q":[-1,0],"mu":[-1]}"#),
        Err(SolverError::InvalidLaw { contact: 0, .. })
    ));
}
