//! The seed's validation scenes (§5.6), ready to step: the delamination of a thin aluminium
//! layer (5.6.1) and the shear of a compressed block (5.6.2). Each spec defaults to the seed's
//! data; the choices the seed leaves open are documented on the fields and in
//! `docs/validation.md` ("Reproducing the seed").

use contact_laws::{BetaScheme, Rccm, RccmParams};
use contact_solver::coupling::obstacle::RigidLine;
use contact_solver::coupling::simulation::{ContactSimulation, SimulationSettings, StepResult};
use contact_solver::coupling::zone::ContactZone;
use contact_solver::local::adhesion::AdhesionMethod;
use contact_solver::{Algorithm, SolverError};
use fem_core::Mesh;
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::{Component, ElementKind, Idealization, LinearElasticModel, Material, Supports};

/// Seed 5.6.1: a layer `length × height` glued on a rigid support (`y = 0`), lifted at point A
/// (the top right corner) by `u_y = lift · t / duration`, plane strain. Units: mm, MPa, s, N.
#[derive(Clone, Debug, PartialEq)]
pub struct DelaminationSpec {
    /// `L` (50 mm).
    pub length: f64,
    /// `h` (2.5 mm).
    pub height: f64,
    /// Young's modulus (5.9e4 MPa).
    pub young: f64,
    /// Poisson's ratio (0.333).
    pub poisson: f64,
    /// Elements along the interface (32: 33 interface nodes with P1).
    pub nx: usize,
    /// Elements through the thickness (4, our choice).
    pub ny: usize,
    /// Element kind (P1, our choice; the seed does not say).
    pub kind: ElementKind,
    /// Imposed `u_y` at A at the end (0.3 mm).
    pub lift: f64,
    /// Loading time (10 s; 1 s in the rate study).
    pub duration: f64,
    /// Load steps (210).
    pub steps: usize,
    /// The interface: `C_n = C_t = 2e5` MPa/mm, `w = 1e-6` mJ/mm², `α = 1` N·s/mm, `μ = 0.2`.
    pub interface: RccmParams,
}

impl Default for DelaminationSpec {
    fn default() -> Self {
        Self {
            length: 50.0,
            height: 2.5,
            young: 5.9e4,
            poisson: 0.333,
            nx: 32,
            ny: 4,
            kind: ElementKind::Tri3,
            lift: 0.3,
            duration: 10.0,
            steps: 210,
            interface: RccmParams {
                c_n: 2e5,
                c_t: 2e5,
                w: 1e-6,
                alpha: 1.0,
                mu: 0.2,
                m: 1,
                beta_0: 1.0,
                scheme: BetaScheme::ImplicitEuler,
            },
        }
    }
}

/// A seed scene: the simulation and how to drive it.
pub struct Scene {
    /// The simulation, at time 0.
    pub simulation: ContactSimulation<LinearElasticModel, Rccm>,
    /// Node of point A.
    pub point_a: usize,
    /// The nodes whose prescribed value the loading drives, with the component.
    pub driven: Vec<(Vec<usize>, Component, f64)>,
    /// Load steps.
    pub steps: usize,
    /// Loading time.
    pub duration: f64,
}

impl Scene {
    /// Runs step `k` (1-based) of the scene's linear loading: sets each driven component to
    /// `value · k / steps` and solves at `t = duration · k / steps`.
    ///
    /// # Errors
    /// As for [`ContactSimulation::step`]; a structure error if a prescribed value is refused.
    pub fn step(&mut self, k: usize) -> Result<StepResult, SolverError> {
        let f = k as f64 / self.steps as f64;
        for (nodes, c, value) in &self.driven {
            self.simulation
                .structure_mut()
                .set_prescribed(nodes, *c, value * f)?;
        }
        self.simulation.step(self.duration * f, 1.0)
    }
}

/// The settings of the seed's tables 5.1 and 5.2 (`examples/delamination.rs`,
/// `examples/shear.rs`): the seed's fixed point on β around the reduced solve by `algorithm`
/// (the bipotential [`Algorithm::GaussSeidel`] sweep or the classical
/// [`Algorithm::ClassicRccm`]), so that both count their contact iterations the same way; the
/// rest is [`SimulationSettings::default`]. The answer is the `bipo` scene's
/// (`examples/scenes/{delamination,shear}.toml`, default settings) to the solvers' tolerances
/// (`crates/cli/tests/cli/seed_tables.rs`).
///
/// # Examples
/// ```
/// use bipo::presets::seed::table_settings;
/// use contact_solver::Algorithm;
/// let s = table_settings(Algorithm::ClassicRccm);
/// assert_eq!(s.solver.algorithm, Algorithm::ClassicRccm);
/// ```
pub fn table_settings(algorithm: Algorithm) -> SimulationSettings {
    let mut settings =
        SimulationSettings::default().with_adhesion_method(AdhesionMethod::FixedPoint);
    settings.solver.algorithm = algorithm;
    settings
}

/// The simulation of a plane-strain layer `[length, height, young, poisson]` whose bottom edge
/// adheres by `interface` to the rigid line `y = 0` (alert distance `height / 10`).
fn glued(
    mesh: Mesh,
    supports: Supports,
    [length, height, young, poisson]: [f64; 4],
    interface: RccmParams,
    settings: SimulationSettings,
) -> Result<ContactSimulation<LinearElasticModel, Rccm>, SolverError> {
    let bottom = mesh.node_set("bottom")?.to_vec();
    let material = Material::new(young, poisson, 0.0)?;
    let model =
        LinearElasticModel::new(mesh, Idealization::PlaneStrain, &[(0, material)], supports)?;
    let base = RigidLine::new([-length, 0.0], [2.0 * length, 0.0])?;
    let law = Rccm::new(interface)?;
    let zone = ContactZone::rigid("interface", bottom, base, law, 0.1 * height);
    ContactSimulation::new(model, vec![zone], settings)
}

impl DelaminationSpec {
    /// Builds the scene. Supports (our choice, the seed's figure 5.6 is not in the text): the
    /// left face has `u_x = 0` (without it the layer would float on its springs and `K` would
    /// be singular) and A the imposed `u_y`.
    ///
    /// # Errors
    /// Invalid dimensions or parameters.
    pub fn build(&self, settings: SimulationSettings) -> Result<Scene, SolverError> {
        let mut spec = RectangleSpec::new([0.0, self.length], [0.0, self.height], self.nx, self.ny);
        spec.kind = self.kind;
        let mesh = rectangle(&spec)?;
        let left = mesh.node_set("left")?.to_vec();
        let a = mesh.node_set("top_right")?[0];
        let mut supports = Supports::new();
        supports.fix(&left, Component::X);
        supports.prescribe(&[a], Component::Y, 0.0)?;
        let layer = [self.length, self.height, self.young, self.poisson];
        Ok(Scene {
            simulation: glued(mesh, supports, layer, self.interface, settings)?,
            point_a: a,
            driven: vec![(vec![a], Component::Y, self.lift)],
            steps: self.steps,
            duration: self.duration,
        })
    }
}

/// Seed 5.6.2: a block `length × height` adhering to a rigid plane, its top pressed by
/// `u_y = press` and its left face pushed by `u_x = push`, both linear in time, plane strain.
#[derive(Clone, Debug, PartialEq)]
pub struct ShearSpec {
    /// `L` (50 mm).
    pub length: f64,
    /// `h` (25 mm).
    pub height: f64,
    /// Young's modulus (5.9e4 MPa).
    pub young: f64,
    /// Poisson's ratio (0.333).
    pub poisson: f64,
    /// Elements along the interface (32: 33 interface nodes with P1).
    pub nx: usize,
    /// Elements through the height (16, our choice).
    pub ny: usize,
    /// Element kind (P1).
    pub kind: ElementKind,
    /// Imposed `u_y` on the top face at the end (−0.5 mm).
    pub press: f64,
    /// Imposed `u_x` on the left face at the end (20 mm).
    pub push: f64,
    /// Loading time (10 s).
    pub duration: f64,
    /// Load steps (210).
    pub steps: usize,
    /// The interface: `C_n = C_t = 1.64` MPa/mm, `w = 1e-3` mJ/mm², `α = 1`, `μ = 0.2`.
    pub interface: RccmParams,
}

impl Default for ShearSpec {
    fn default() -> Self {
        Self {
            length: 50.0,
            height: 25.0,
            young: 5.9e4,
            poisson: 0.333,
            nx: 32,
            ny: 16,
            kind: ElementKind::Tri3,
            press: -0.5,
            push: 20.0,
            duration: 10.0,
            steps: 210,
            interface: RccmParams {
                c_n: 1.64,
                c_t: 1.64,
                w: 1e-3,
                alpha: 1.0,
                mu: 0.2,
                m: 1,
                beta_0: 1.0,
                scheme: BetaScheme::ImplicitEuler,
            },
        }
    }
}

impl ShearSpec {
    /// Builds the scene: top face `u_y` imposed, left face `u_x` imposed (the bottom left
    /// corner, an interface node, then has a prescribed slip), point A = bottom left corner.
    ///
    /// # Errors
    /// Invalid dimensions or parameters.
    pub fn build(&self, settings: SimulationSettings) -> Result<Scene, SolverError> {
        let mut spec = RectangleSpec::new([0.0, self.length], [0.0, self.height], self.nx, self.ny);
        spec.kind = self.kind;
        let mesh = rectangle(&spec)?;
        let left = mesh.node_set("left")?.to_vec();
        let top = mesh.node_set("top")?.to_vec();
        let a = mesh.node_set("bottom_left")?[0];
        let mut supports = Supports::new();
        supports.prescribe(&top, Component::Y, 0.0)?;
        supports.prescribe(&left, Component::X, 0.0)?;
        let layer = [self.length, self.height, self.young, self.poisson];
        Ok(Scene {
            simulation: glued(mesh, supports, layer, self.interface, settings)?,
            point_a: a,
            driven: vec![
                (top, Component::Y, self.press),
                (left, Component::X, self.push),
            ],
            steps: self.steps,
            duration: self.duration,
        })
    }
}
