//! Helpers shared by the integration tests (`tests/integration/`); examples and benches include
//! single files of them with `#[path]`. The FE scenes need the `fe` feature.

pub mod box_stack;
#[cfg(feature = "fe")]
pub mod cylinders;
#[cfg(feature = "fe")]
pub mod hertz_revolved;
#[cfg(feature = "fe")]
pub mod hertz_scene;
#[cfg(feature = "fe")]
pub mod pile_plastic;
#[cfg(feature = "fe")]
pub mod sphere_impact;
#[cfg(feature = "fe")]
pub mod stress_cases;
pub mod twins;
