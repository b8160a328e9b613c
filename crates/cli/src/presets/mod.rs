//! The seed's studies, ready to step:
//! - [`seed`]: the validation scenes of §5.6, the delamination of a thin aluminium layer
//!   (5.6.1, [`DelaminationSpec`]) and the shear of a compressed block (5.6.2, [`ShearSpec`]);
//! - [`pile`]: the pull-out of a driven steel pile (chapter 6, [`PulloutSpec`]).
//!
//! Each spec defaults to the seed's data; the choices the seed leaves open are documented on the
//! fields and in `docs/validation.md` ("Reproducing the seed").

pub mod pile;
pub mod seed;

pub use pile::{
    BetaCoupling, Installation, PileSpace, PlasticPullout, PulloutRun, PulloutScene, PulloutSpec,
    PulloutStep, ShaftPoint,
};
pub use seed::{DelaminationSpec, Scene, ShearSpec};
