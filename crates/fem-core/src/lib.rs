//! Finite-element core of `bipotential`: P1/P2 triangles, plane strain, plane stress,
//! axisymmetry and sparse assembly.
//!
//! This crate is intentionally empty for now: it will hold the `Structure` trait and the
//! linear-elastic model (see issue 4). It knows nothing about contact.
