//! 3D contact: rigid obstacles ([`obstacle`]), zones of nodes against them ([`zone`]), and the
//! quasi-static simulation of a [`Structure<3>`](fem_core::Structure) ([`simulation`]) on the
//! dense `F*` path with the local solver in 3D.

pub mod obstacle;
pub mod simulation;
pub mod zone;

pub use obstacle::{
    Obstacle3, ObstaclePoint3, RigidCylinder, RigidPlane, RigidSphere, Side3, tangent_frame,
};
pub use simulation::{SolidContactRecord, SolidContactSimulation, SolidSettings, SolidStepResult};
pub use zone::{Candidate3, ContactZone3, recognize_3d};
