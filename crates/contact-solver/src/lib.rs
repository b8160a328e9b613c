//! Contact solver of `bipotential`: obstacle recognition, the flexibility matrix
//! `F* = H K⁻¹ Hᵀ`, the bipotential Uzawa loop with RCCM adhesion, and load stepping.
//!
//! This crate is intentionally empty for now (see issue 5). The local laws it will solve
//! live in [`contact_laws`].

pub use contact_laws;
