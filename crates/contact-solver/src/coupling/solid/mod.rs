//! 3D contact: rigid obstacles ([`obstacle`]), target surfaces of deformable bodies
//! ([`surface`]), the 3D names of the generic zones and candidates ([`zone`]), and the
//! quasi-static simulation of a [`Structure<3>`](fem_core::Structure) ([`simulation`]) with
//! the local solver in 3D (dense `F*`, matrix-free or the primal active set), RCCM adhesion
//! included.

pub mod obstacle;
pub mod output;
pub mod simulation;
pub mod surface;
pub mod zone;

pub use obstacle::{ObstaclePoint3, RigidCylinder, RigidPlane, RigidSphere, Side3, tangent_frame};
pub use output::write_interface_vtu_3d;
pub use simulation::{
    DEFAULT_DENSE_LIMIT_3D, SolidContactRecord, SolidContactSimulation, SolidSettings,
    SolidStepResult,
};
pub use surface::TriSurface;
pub use zone::{
    Candidate3, ContactZone3, PairNormals3, Target3, recognize_3d, supported_contactors_3d,
};
