//! The library half of `bipo`: the studies it runs by name (`[preset]` in a scene file), ready
//! to step from Rust.
//!
//! They are studies, not library: each one builds a mesh with `fem_core::generate`, a model,
//! contact zones and a [`contact_solver::ContactSimulation`], with the seed's data as defaults
//! (the seed is Terfaya's thesis, mapped in `docs/theory.md`). The examples and the seed's
//! validation tests use them; a user writing a study of their own can read them as templates.

#![warn(missing_docs)]

pub mod app;
mod app_dynamic;
mod app_local;
mod app_mpi;
mod app_plastic;
mod build;
mod error;
mod out;
mod plot;
pub mod presets;
mod raw;
mod run;
mod scene;
mod spec;
mod templates;
