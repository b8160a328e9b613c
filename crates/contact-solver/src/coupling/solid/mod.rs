//! 3D contact: rigid obstacles ([`obstacle`]), target surfaces of deformable bodies
//! ([`surface`]) and the 3D names of the generic types: zones and candidates ([`zone`]), the
//! simulation of a [`Structure<3>`](fem_core::Structure) and what its steps return (aliases of
//! [`ContactSimulation<S, L, 3>`], [`StepResult<3>`] and [`ContactRecord<3>`]: one simulation
//! for both dimensions, issue 35).

pub mod obstacle;
pub mod surface;
pub mod zone;

pub use crate::coupling::output::write_interface_vtu_3d;
use crate::coupling::simulation::{ContactRecord, ContactSimulation, StepResult};
pub use obstacle::{ObstaclePoint3, RigidCylinder, RigidPlane, RigidSphere, Side3, tangent_frame};
pub use surface::TriSurface;
pub use zone::{Candidate3, ContactZone3, PairNormals3, Target3};

/// A quasi-static 3D contact simulation: [`ContactSimulation<S, L, 3>`]. Its default settings
/// are [`SimulationSettings::for_dimension`](crate::SimulationSettings::for_dimension)`::<3>()`.
///
/// # Examples
/// A P2 block pressed on a rigid floor with friction: the force is uniform and no contact
/// slips.
/// ```
/// use contact_laws::Coulomb;
/// use contact_solver::SimulationSettings;
/// use contact_solver::coupling::solid::{ContactZone3, RigidPlane, SolidContactSimulation};
/// use fem_core::solid::{SolidModel, generate::{box_mesh, lines}};
/// use fem_core::{Component, ElementKind, Material, Supports};
///
/// let mesh = box_mesh(&lines(0.0, 1.0, 2), &lines(0.0, 1.0, 2), &lines(0.0, 0.5, 1), ElementKind::Tet10)?;
/// let top = mesh.node_set("z1")?.to_vec();
/// let mut s = Supports::new();
/// s.prescribe(&top, Component::Z, -1e-3)?.fix(&top, Component::X).fix(&top, Component::Y);
/// let (nodes, areas) = mesh.nodal_areas("z0")?;
/// let model = SolidModel::new(mesh, &[(0, Material::new(1000.0, 0.0, 0.0)?)], s)?;
/// let floor = RigidPlane::new([0.0; 3], [0.0, 0.0, 1.0])?;
/// let zone = ContactZone3::rigid("base", nodes, floor, Coulomb::new(0.3)?, 0.1).with_areas(areas);
/// let settings = SimulationSettings::for_dimension::<3>();
/// let mut sim = SolidContactSimulation::new(model, vec![zone], settings)?;
/// let res = sim.step(1.0, 1.0)?;
/// let total: f64 = res.contacts.iter().map(|c| c.r.n).sum();
/// assert!((total - 2.0).abs() < 1e-8); // σ = E δ / H = 2 on a unit area (ν = 0)
/// assert!(res.contacts.iter().all(|c| c.slip_increment.iter().all(|s| s.abs() < 1e-12)));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub type SolidContactSimulation<S, L> = ContactSimulation<S, L, 3>;

/// The result of a 3D step: [`StepResult<3>`].
pub type SolidStepResult = StepResult<3>;

/// One contact at the end of a 3D step: [`ContactRecord<3>`].
pub type SolidContactRecord = ContactRecord<3>;
