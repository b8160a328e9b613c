//! The integration tests of `contact-laws`, one test binary (each module was a test file of its
//! own; one binary links once). Each module keeps its name, its tests and its doc; the proptest
//! regression files sit beside their modules.

mod beta_update;
mod derivatives;
mod fenchel;
mod projection;
mod single_spring;
mod user_law;
