//! Local contact laws of the bipotential method (De Saxcé), with RCCM adhesion.
//!
//! This crate is the local part of `bipotential`: the Coulomb cone and its polar, the
//! closed-form projection onto `K_μ̄`, De Saxcé's modified velocity, the contact bipotential
//! `b_c`, the adhesion bipotential `b_β`, the RCCM law and its β update — and the
//! [`ContactLaw`] trait through which a contact solver consumes them. It depends only on
//! `nalgebra` and `thiserror`, allocates nothing, and never fails after construction.
//!
//! Equation numbers `(3.x)`, `(4.x)`, `(5.x)` refer to the seed thesis (Terfaya 2019); the
//! full derivation and the list of the seed's typos are in `docs/theory.md`.
//!
//! # Sign conventions
//! Stated once here and used by every item of the crate:
//! - `n` is the unit outward normal of the obstacle (or of the target body), pointing towards
//!   the contactor; `t` spans the tangent plane. A [`LocalVec`] holds `(n, t)` components.
//! - The normal jump `u_n ≥ 0` is an **opening** (separation); the gap `x_n = g + u_n ≥ 0`.
//! - The reaction `r` is the force the obstacle exerts on the contactor; `r_n ≥ 0` is
//!   **compression**. Friction opposes slip: in slip `u̇_t = −λ r_t / ‖r_t‖`, `λ ≥ 0`.
//! - The adhesive reaction `r_adh = −β² (C_n u_n, C_t u_t)` **resists opening and slip**: an
//!   opened glued interface is in tension (`r_adh,n < 0`).
//! - The bipotential pairs `−u̇` with `r`: `b(−u̇, r) ≥ −u̇ · r` (Fenchel), with equality
//!   exactly on the pairs that obey the law.
//!
//! # Glossary (seed symbol → code)
//! | seed | code | seed | code |
//! |---|---|---|---|
//! | `r_n, r_t` | `r.n`, `r.t` | `u_n, u_t`, `u̇`, `Δu` | `u.n`, `u.t`, `du` |
//! | `μ`, `μ̄ = μ f(β)` | `mu`, [`CoulombCone::scaled`] | `β`, `β̇` | `beta`, `beta_dot` |
//! | `C_n, C_t` | `c_n`, `c_t` | `w`, `α` | `w`, `alpha` |
//! | `K_μ`, `K*_μ` | [`CoulombCone`] | `τ` (augmented reaction) | `tau` |
//! | `v` (modified velocity) | [`modified_velocity`] | `G_β` | [`Rccm::g_beta`] |
//! | `b_c` | [`contact_bipotential`] | `b_β` | [`adhesion_bipotential`] |
//!
//! # Examples
//! ```
//! use contact_laws::{ContactLaw, Coulomb, LocalVec2};
//! let law = Coulomb::new(0.3)?;
//! // An augmented reaction outside the cone is projected onto its surface (slip, 5.38).
//! let r = law.project(&LocalVec2::planar(1.0, 2.0), &());
//! assert!((r.t[0] - 0.3 * r.n).abs() < 1e-15);
//! # Ok::<(), contact_laws::LawError>(())
//! ```

#![warn(missing_docs)]

pub mod cone;
pub mod coulomb;
pub mod de_saxce;
pub mod error;
pub mod law;
pub mod local;
pub mod rccm;
pub mod standard;
#[cfg(feature = "proptest")]
pub mod strategies;

pub use cone::{ContactStatus, CoulombCone, FEASIBILITY_TOL};
pub use coulomb::{Coulomb, Signorini};
pub use de_saxce::{contact_bipotential, contact_fenchel_gap, modified_velocity};
pub use error::LawError;
pub use law::ContactLaw;
pub use local::{LocalVec, LocalVec2, LocalVec3};
pub use rccm::{
    BetaScheme, Rccm, RccmParams, RccmState, adhesion_bipotential, beta_implicit_euler,
    beta_rate_independent, beta_theta,
};
pub use standard::StandardLaw;
