//! [proptest] strategies for the types of this crate (feature `proptest`).
//!
//! Magnitudes span `1e-6 .. 1e6` on a log scale, with exact zeros mixed in, so that
//! property tests exercise both the wide dynamic range of FE contact problems and the
//! degenerate cases (`μ = 0`, `τ_t = 0`, `β ∈ {0, 1}`).

use crate::local::LocalVec;
use crate::rccm::{BetaScheme, RccmParams};
use nalgebra::SVector;
use proptest::prelude::*;

/// A positive magnitude `10^x`, `x` uniform in `[-6, 6]`.
pub fn magnitude() -> impl Strategy<Value = f64> + Clone {
    (-6.0f64..=6.0).prop_map(|x| 10f64.powf(x))
}

/// A real of either sign with magnitude in `1e-6 .. 1e6`, or exactly zero (one case in ten).
pub fn signed() -> impl Strategy<Value = f64> + Clone {
    prop_oneof![
        1 => Just(0.0),
        9 => (any::<bool>(), magnitude()).prop_map(|(neg, m)| if neg { -m } else { m }),
    ]
}

/// A non-negative parameter (stiffness, energy, viscosity, friction): zero or a magnitude.
pub fn non_negative() -> impl Strategy<Value = f64> + Clone {
    prop_oneof![1 => Just(0.0), 9 => magnitude()]
}

/// An adhesion intensity in `[0, 1]`, with the end points mixed in.
pub fn beta() -> impl Strategy<Value = f64> + Clone {
    prop_oneof![1 => Just(0.0), 1 => Just(1.0), 8 => 0.0f64..=1.0]
}

/// A local vector whose components follow [`signed`].
pub fn local_vec<const DT: usize>() -> impl Strategy<Value = LocalVec<DT>> + Clone {
    (signed(), proptest::array::uniform::<_, DT>(signed()))
        .prop_map(|(n, t)| LocalVec::new(n, SVector::from(t)))
}

/// Valid RCCM parameters over wide magnitudes, with `m ∈ {1, 2}`, implicit Euler or a
/// θ-scheme.
pub fn rccm_params() -> impl Strategy<Value = RccmParams> + Clone {
    (
        (non_negative(), non_negative(), non_negative()),
        (non_negative(), non_negative(), 1u32..=2, beta()),
        prop_oneof![
            Just(BetaScheme::ImplicitEuler),
            (0.0f64..=1.0).prop_map(BetaScheme::Theta)
        ],
    )
        .prop_map(
            |((c_n, c_t, w), (alpha, mu, m, beta_0), scheme)| RccmParams {
                c_n,
                c_t,
                w,
                alpha,
                mu,
                m,
                beta_0,
                scheme,
            },
        )
}
