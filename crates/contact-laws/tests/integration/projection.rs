//! Property tests of the projection onto the Coulomb cone `K_μ` (seed 5.26b, 5.38).
//!
//! Reference: convex analysis (Moreau 1962, decomposition onto a cone and its polar);
//! the three closed-form cases of seed eq. 5.38. Each property runs 10 000 cases over
//! magnitudes 1e-6..1e6 (with exact zeros mixed in), for 2D (`DT = 1`) and 3D (`DT = 2`)
//! local frames. Tolerances are relative: `TOL` times the magnitudes involved.

use contact_laws::strategies::{local_vec, non_negative, signed};
use contact_laws::{ContactLaw, ContactStatus, CoulombCone, LocalVec, Signorini};
use nalgebra::SVector;
use proptest::prelude::*;

const TOL: f64 = 1e-12;

fn cone() -> impl Strategy<Value = CoulombCone> {
    non_negative().prop_map(|mu| CoulombCone::new(mu).unwrap())
}

/// A point of `K_μ`: `r_n ≥ 0`, `r_t = s μ r_n d` with `s ∈ [0, 1]`, `‖d‖ = 1`.
fn point_in<const DT: usize>(mu: f64) -> impl Strategy<Value = LocalVec<DT>> {
    (
        non_negative(),
        0.0f64..=1.0,
        proptest::array::uniform::<_, DT>(signed()),
    )
        .prop_map(move |(r_n, s, d)| {
            let d = SVector::<f64, DT>::from(d);
            let norm = d.norm();
            let dir = if norm > 0.0 {
                d / norm
            } else {
                SVector::zeros()
            };
            LocalVec::new(r_n, dir * (s * mu * r_n))
        })
}

/// Projection onto the polar cone `K*_μ = {μ‖v_t‖ + v_n ≤ 0}` computed independently of
/// Moreau: `K*_μ` is `K_{1/μ}` mirrored in the normal direction (a half-space if μ = 0).
fn polar_projection_reference<const DT: usize>(mu: f64, tau: &LocalVec<DT>) -> LocalVec<DT> {
    if mu == 0.0 {
        return LocalVec::new(tau.n.min(0.0), tau.t);
    }
    let mirrored = CoulombCone::new(1.0 / mu).unwrap();
    let p = mirrored.project(&LocalVec::new(-tau.n, tau.t));
    LocalVec::new(-p.n, p.t)
}

fn check_projection<const DT: usize>(
    cone: CoulombCone,
    a: LocalVec<DT>,
    b: LocalVec<DT>,
) -> Result<(), TestCaseError> {
    let (pa, status) = cone.project_with_status(&a);
    let pb = cone.project(&b);
    prop_assert!(pa.is_finite(), "NaN or infinity: P({a:?}) = {pa:?}");
    // Lands in the cone.
    prop_assert!(
        cone.contains(&pa),
        "P({a:?}) = {pa:?} is not in K_{}",
        cone.mu()
    );
    // Status consistency (the three cases of 5.38).
    match status {
        ContactStatus::Separation => prop_assert_eq!(pa, LocalVec::zeros()),
        ContactStatus::Stick => prop_assert_eq!(pa, a),
        ContactStatus::Slip => {
            let scale = TOL * (pa.t_norm() + cone.mu() * pa.n);
            prop_assert!(pa.n > 0.0);
            prop_assert!((pa.t_norm() - cone.mu() * pa.n).abs() <= scale);
        }
    }
    // Idempotent.
    let ppa = cone.project(&pa);
    prop_assert!(
        (ppa - pa).norm() <= TOL * a.norm(),
        "P(P(τ)) ≠ P(τ): {ppa:?} vs {pa:?}"
    );
    // Non-expansive.
    prop_assert!(
        (pa - pb).norm() <= (a - b).norm() + TOL * (a.norm() + b.norm()),
        "‖P(a) − P(b)‖ > ‖a − b‖"
    );
    // Moreau: the remainder is the projection onto the polar cone, orthogonal to P(τ).
    let q = cone.project_polar(&a);
    let q_ref = polar_projection_reference(cone.mu(), &a);
    prop_assert!(
        cone.polar_contains(&q),
        "τ − P(τ) = {q:?} not in the polar cone"
    );
    prop_assert!(
        (q - q_ref).norm() <= 1e-10 * a.norm(),
        "Moreau: τ − P_K(τ) = {q:?} but P_K*(τ) = {q_ref:?}"
    );
    prop_assert!(
        (pa + q - a).norm() <= TOL * a.norm(),
        "P_K(τ) + P_K*(τ) ≠ τ"
    );
    prop_assert!(pa.dot(&q).abs() <= TOL * a.norm() * a.norm());
    Ok(())
}

fn check_variational_inequality<const DT: usize>(
    cone: CoulombCone,
    tau: LocalVec<DT>,
    r_prime: LocalVec<DT>,
) -> Result<(), TestCaseError> {
    // (τ − P(τ)) · (r' − P(τ)) ≤ 0 for every r' ∈ K.
    // τ − P(τ) is taken from the closed-form polar projection (Moreau), which keeps its
    // digits when τ is close to the cone.
    let p = cone.project(&tau);
    let q = cone.project_polar(&tau);
    prop_assert!((p + q - tau).norm() <= TOL * tau.norm());
    let lhs = q.dot(&(r_prime - p));
    let scale = TOL * q.norm() * (r_prime.norm() + p.norm());
    prop_assert!(lhs <= scale, "VI violated: {lhs} > {scale}");
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(10_000))]

    #[test]
    fn projection_properties_hold_2d(cone in cone(), a in local_vec::<1>(), b in local_vec::<1>()) {
        check_projection(cone, a, b)?;
    }

    #[test]
    fn projection_properties_hold_3d(cone in cone(), a in local_vec::<2>(), b in local_vec::<2>()) {
        check_projection(cone, a, b)?;
    }

    #[test]
    fn variational_inequality_holds_2d(
        (cone, r_prime) in non_negative().prop_flat_map(|mu| (Just(CoulombCone::new(mu).unwrap()), point_in::<1>(mu))),
        tau in local_vec::<1>(),
    ) {
        prop_assert!(cone.contains(&r_prime));
        check_variational_inequality(cone, tau, r_prime)?;
    }

    #[test]
    fn variational_inequality_holds_3d(
        (cone, r_prime) in non_negative().prop_flat_map(|mu| (Just(CoulombCone::new(mu).unwrap()), point_in::<2>(mu))),
        tau in local_vec::<2>(),
    ) {
        prop_assert!(cone.contains(&r_prime));
        check_variational_inequality(cone, tau, r_prime)?;
    }

    #[test]
    fn points_of_the_cone_are_fixed(
        (cone, r) in non_negative().prop_flat_map(|mu| (Just(CoulombCone::new(mu).unwrap()), point_in::<2>(mu))),
    ) {
        let p = cone.project(&r);
        prop_assert!((p - r).norm() <= TOL * r.norm());
    }

    #[test]
    fn zero_friction_reduces_to_signorini(tau in local_vec::<2>()) {
        // P_{K_0}(τ) = (max(τ_n, 0), 0), the same through the Signorini law.
        let p = CoulombCone::new(0.0).unwrap().project(&tau);
        prop_assert_eq!(p, LocalVec::new(tau.n.max(0.0), SVector::zeros()));
        prop_assert_eq!(Signorini.project(&tau, &()), p);
    }

    #[test]
    fn projection_is_positively_homogeneous(cone in cone(), tau in local_vec::<1>(), s in 1e-3f64..1e3) {
        // K is a cone: P(s τ) = s P(τ) for s > 0.
        let lhs = cone.project(&(tau * s));
        let rhs = cone.project(&tau) * s;
        prop_assert!((lhs - rhs).norm() <= TOL * s * tau.norm());
    }
}
