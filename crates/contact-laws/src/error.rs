//! Errors raised when a law is built from invalid parameters.
//!
//! Laws validate once, at construction; the hot path (projection, bipotential, β update)
//! takes validated types and never fails.

/// Error of `contact-laws`: a parameter was rejected when a law or a state was built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum LawError {
    /// A real parameter is NaN, infinite or outside its admissible range.
    #[error("invalid parameter `{name}` = {value}: expected {expected}")]
    InvalidParameter {
        /// Name of the parameter, as in the seed's notation spelled in ASCII (`mu`, `c_n`, …).
        name: &'static str,
        /// The rejected value.
        value: f64,
        /// What was expected, in words (e.g. "a finite value >= 0").
        expected: &'static str,
    },
    /// The damage exponent `m` of `f(β) = 1 − β^m` (seed eq. 4.33) is neither 1 nor 2.
    #[error("damage exponent m = {m} is not supported: f(beta) = 1 - beta^m needs m = 1 or m = 2")]
    InvalidExponent {
        /// The rejected exponent.
        m: u32,
    },
}

/// Checks that `value` is finite and `>= 0`.
pub(crate) fn non_negative(name: &'static str, value: f64) -> Result<f64, LawError> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(LawError::InvalidParameter {
            name,
            value,
            expected: "a finite value >= 0",
        })
    }
}

/// Checks that `value` is finite and lies in `[0, 1]`.
pub(crate) fn unit_interval(name: &'static str, value: f64) -> Result<f64, LawError> {
    if (0.0..=1.0).contains(&value) {
        Ok(value)
    } else {
        Err(LawError::InvalidParameter {
            name,
            value,
            expected: "a value in [0, 1]",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn non_negative_rejects_nan_infinite_and_negative() {
        for v in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, -1e-300] {
            assert!(matches!(
                non_negative("mu", v),
                Err(LawError::InvalidParameter { name: "mu", .. })
            ));
        }
        assert_eq!(non_negative("mu", 0.0), Ok(0.0));
    }

    #[test]
    fn unit_interval_rejects_outside_values() {
        for v in [f64::NAN, -0.1, 1.0 + 1e-12] {
            assert!(unit_interval("beta", v).is_err());
        }
        assert_eq!(unit_interval("beta", 1.0), Ok(1.0));
    }

    #[test]
    fn errors_display_name_value_and_expectation() {
        let e = non_negative("c_n", -2.0).unwrap_err();
        assert_eq!(
            e.to_string(),
            "invalid parameter `c_n` = -2: expected a finite value >= 0"
        );
        assert!(
            LawError::InvalidExponent { m: 3 }
                .to_string()
                .contains("m = 3")
        );
    }
}
