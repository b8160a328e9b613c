//! The FE coupling (feature `fe`): a [`Structure`](fem_core::Structure), rigid obstacles and
//! contact zones, condensed onto the contact unknowns and solved with the [`local`](crate::local)
//! layer, one load step at a time.
//!
//! # The pipeline of a step ([`ContactSimulation::step`](simulation::ContactSimulation::step))
//! 1. **Detection** ([`simulation`]'s `detection` stage): the free response to the loads and
//!    the active set (alert distance, adhesion), from the candidates of [`zone::recognize`]
//!    against the [`obstacle`]s.
//! 2. **Path and operator** (`path`, `flexibility`): dense `F* = H K⁻¹ Hᵀ`, the matrix-free
//!    operator, or the primal active set ([`primal`]), chosen per step.
//! 3. **Local solve** (`solve`): the reduced problem with the adhesion loop
//!    ([`local::adhesion`](crate::local::adhesion)), or the matrix-free / active-set iteration.
//! 4. **Equilibrium and report** (`equilibrium`, `report`): `u = u_free + K⁻¹ Hᵀ r`, the
//!    penetration check (back to 2 if an inactive candidate penetrates), the accepted state and
//!    the [`StepResult`](simulation::StepResult); [`output`] writes it, and [`traction`]
//!    recovers the continuous contact pressure from its reactions.
//!
//! The free response, `q` and the acceptance are the time scheme's
//! ([`TimeScheme`](simulation::TimeScheme): quasi-static load steps by default).

mod flexibility;
mod force_factor;
pub mod obstacle;
pub mod output;
pub mod primal;
pub mod simulation;
pub mod solid;
pub mod space;
pub mod traction;
pub mod zone;
