//! The scene file: the TOML format read by `bipo`, as serde types.
//!
//! Every table denies unknown keys, so a typo is an error with its line and column. The
//! *meaning* of the values (positive moduli, existing node sets, increasing time tables, …) is
//! checked afterwards by [`crate::build`], which names the key path of the offending value.
//! The tables with a `type` key are read flat by [`crate::raw`] and resolved into the typed
//! values of [`crate::spec`].
//! The format is documented key by key in `docs/guide.md` ("Scene files and the `bipo`
//! command").

use crate::raw::{RawAnalysis, RawInitialStress, RawLaw, RawLoad, RawMesh, RawPreset, RawTarget};
use crate::spec::Pair;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// A whole scene file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    pub title: Option<String>,
    /// Free-text note of the unit system (the code needs only consistency).
    pub units: Option<Units>,
    /// A seed study built by the library (`delamination`, `shear`, `pile`).
    pub preset: Option<RawPreset>,
    pub mesh: Option<RawMesh>,
    /// The 2D idealisation, or `type = "3d"` for a solid of tetrahedra.
    pub analysis: Option<RawAnalysis>,
    #[serde(default)]
    pub materials: Vec<MaterialSpec>,
    pub initial_stress: Option<RawInitialStress>,
    /// Piecewise linear time functions, by name.
    #[serde(default)]
    pub functions: BTreeMap<String, Vec<Pair>>,
    /// Supports (prescribed displacements).
    #[serde(default)]
    pub supports: Vec<SupportSpec>,
    /// Ties: node sets that share one displacement component (rigid caps, pilot nodes).
    #[serde(default)]
    pub ties: Vec<TieSpec>,
    #[serde(default)]
    pub loads: Vec<RawLoad>,
    #[serde(default)]
    pub contact: Vec<ZoneSpec>,
    /// The reduced solver and the adhesion loop.
    #[serde(default)]
    pub solver: SolverSpec,
    /// One phase of load steps.
    pub steps: Option<StepsSpec>,
    /// Several phases of load steps.
    #[serde(default)]
    pub phases: Vec<PhaseSpec>,
    /// Which outputs, where.
    #[serde(default)]
    pub output: OutputSpec,
    #[serde(default)]
    pub plots: Vec<PlotSpec>,
    /// The recovered contact pressure against Hertz's (an SVG at the last written step).
    pub hertz: Option<HertzSpec>,
}

/// `[hertz]`: plot a zone's recovered contact pressure against the Hertz ellipse of a
/// cylinder (plane problems) or a sphere (axisymmetry, 3D) on a flat, at the last written step.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct HertzSpec {
    /// The zone (optional with a single zone).
    pub zone: Option<String>,
    /// Radius of the curved body.
    pub radius: f64,
    /// The first point of contact, reference configuration (default: the origin).
    pub center: Option<Vec<f64>>,
    /// The whole contact's force over the zone's `Σ r_n` (2 for a half model, 4 for a
    /// quarter model; default 1).
    pub symmetry: Option<f64>,
    /// The contact modulus `E*` (default: from the scene's only material).
    pub e_star: Option<f64>,
    /// The SVG file (default `pressure.svg`).
    pub file: Option<String>,
}

/// Units note (written back as `summary.json`'s `units`).
#[derive(Debug, Deserialize, Serialize, Clone, Default)]
#[serde(deny_unknown_fields)]
pub struct Units {
    /// e.g. "mm".
    pub length: Option<String>,
    /// e.g. "N".
    pub force: Option<String>,
    /// e.g. "s".
    pub time: Option<String>,
    /// e.g. "MPa".
    pub stress: Option<String>,
}

/// A material on one or several regions.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    /// A name, for the reader of the scene only.
    #[allow(dead_code)]
    pub name: Option<String>,
    pub region: Option<u32>,
    pub regions: Option<Vec<u32>>,
    pub young: f64,
    pub poisson: f64,
    /// Unit weight (for gravity loads).
    #[serde(default)]
    pub unit_weight: f64,
    /// Mass density (required in a dynamic scene; > 0).
    pub density: Option<f64>,
    /// The velocity of the material's regions at t = 0 (a dynamic scene; two or three
    /// numbers by dimension).
    pub initial_velocity: Option<crate::spec::Coords>,
    /// `type`: `"elastic"` (the default), `"drucker-prager"` or `"von-mises"` (issue 40; the
    /// plastic keys below are read by [`crate::raw::plastic_law`]).
    #[serde(rename = "type", default)]
    pub kind: crate::raw::MaterialKind,
    /// Drucker–Prager: the friction angle φ in degrees.
    pub friction_angle: Option<f64>,
    /// Drucker–Prager: the dilatancy angle θ in degrees (default φ: associated).
    pub dilatancy_angle: Option<f64>,
    /// Drucker–Prager: the cohesion c.
    pub cohesion: Option<f64>,
    /// Drucker–Prager: how the cone matches Mohr–Coulomb.
    pub cone: Option<crate::raw::ConeSpec>,
    /// Von Mises: the uniaxial yield stress σ_y.
    pub yield_stress: Option<f64>,
}

/// Which displacement components a support constrains.
#[derive(Debug, Deserialize, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum ComponentSpec {
    /// `u_x` (or `u_r`).
    X,
    /// `u_y` (or `u_z`).
    Y,
    /// Both `x` and `y` (2D).
    Both,
    /// `u_z` (3D).
    Z,
    /// `x`, `y` and `z` (3D).
    All,
}

/// A support: prescribed displacement on a node set.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct SupportSpec {
    /// A name (phases may override its function by this name).
    pub name: Option<String>,
    pub set: String,
    pub component: ComponentSpec,
    /// Prescribed value (times the function).
    #[serde(default)]
    pub value: f64,
    /// Time function (default: constant 1).
    pub function: Option<String>,
    /// Phases in which the support acts (default: all).
    pub phases: Option<Vec<String>>,
}

/// A tie: the nodes of a set share one displacement component (`fem_core::Supports::tie`).
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct TieSpec {
    pub set: String,
    pub component: ComponentSpec,
}

#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct ZoneSpec {
    pub name: String,
    /// Contactor node set.
    pub contactor: String,
    /// What the contactor faces.
    pub target: RawTarget,
    pub law: RawLaw,
    /// Alert distance Δx.
    pub alert_distance: f64,
    /// What to do with contactor nodes that a support holds along their contact normal (they
    /// cannot take part in contact): `refuse` (default: an error listing them) or `leave_out`
    /// (dropped from the zone, with a warning naming them).
    #[serde(default)]
    pub supported_contactors: SupportedContactors,
}

/// `[[contact]] supported_contactors`: contactor nodes held along their contact normal by a
/// support.
#[derive(Debug, Deserialize, Clone, Copy, PartialEq, Eq, Default)]
pub enum SupportedContactors {
    /// An error listing the nodes (ids and positions) and this key (the default).
    #[default]
    #[serde(rename = "refuse")]
    Refuse,
    /// The nodes are left out of the zone, with a warning naming them.
    #[serde(rename = "leave_out", alias = "leave-out")]
    LeaveOut,
}

/// Solver settings (all optional).
#[derive(Debug, Deserialize, Clone, Default)]
#[serde(deny_unknown_fields)]
pub struct SolverSpec {
    /// `bipotential` (Gauss–Seidel), `uzawa` (Jacobi) or `rccm-classic`.
    pub algorithm: Option<AlgorithmSpec>,
    /// Tolerance.
    pub tol: Option<f64>,
    /// Factor on ρ⁰.
    pub rho_scale: Option<f64>,
    /// Maximum sweeps.
    pub max_iterations: Option<usize>,
    /// SOR factor of the classical solver.
    pub omega: Option<f64>,
    /// Adhesion fixed-point tolerance.
    pub adhesion_tol: Option<f64>,
    /// How adhesion and contact are solved together: `newton` (default) or `fixed-point`.
    pub adhesion_method: Option<AdhesionMethodSpec>,
    /// Newton adhesion: try Newton from the previous step's reactions first (default true).
    pub adhesion_warm_start: Option<bool>,
    pub max_adhesion_iterations: Option<usize>,
    /// Maximum penetration-check passes.
    pub max_detection_passes: Option<usize>,
    pub accept_non_converged: Option<bool>,
    /// Window of the stall detector (0: off).
    pub stall_window: Option<usize>,
    /// Fall back to another algorithm when the chosen one fails.
    pub fallback: Option<bool>,
    /// How a step is solved: `auto` (default), `dense`, `active-set` or `matrix-free`.
    pub flexibility: Option<FlexibilitySpec>,
    /// `auto`'s largest active set solved with a dense `F*` (default 500).
    pub dense_limit: Option<usize>,
}

/// How a step's contact problem is solved (`contact_solver::FlexibilityMode`).
#[derive(Debug, Deserialize, Clone, Copy, PartialEq, Eq)]
pub enum FlexibilitySpec {
    /// Dense `F*` up to `dense_limit` contacts, the active set beyond.
    #[serde(rename = "auto")]
    Auto,
    /// Always a dense `F*`.
    #[serde(rename = "dense")]
    Dense,
    /// The primal active set (no `F*`).
    #[serde(rename = "active-set", alias = "active_set")]
    ActiveSet,
    /// One structure solve per product `F* r`.
    #[serde(rename = "matrix-free", alias = "matrix_free")]
    MatrixFree,
}

/// How adhesion and contact are solved together (`AdhesionMethod`).
#[derive(Debug, Deserialize, Clone, Copy, PartialEq, Eq)]
pub enum AdhesionMethodSpec {
    /// Newton on the reactions with the states eliminated (default).
    #[serde(rename = "newton")]
    Newton,
    /// The seed's fixed point around the reduced solve.
    #[serde(rename = "fixed-point", alias = "fixed_point")]
    FixedPoint,
}

#[derive(Debug, Deserialize, Clone, Copy, PartialEq, Eq)]
pub enum AlgorithmSpec {
    /// Projected Gauss–Seidel bipotential sweeps (default).
    #[serde(rename = "bipotential", alias = "gauss-seidel", alias = "gauss_seidel")]
    Bipotential,
    /// Jacobi / projected-gradient bipotential sweeps.
    #[serde(rename = "uzawa")]
    Uzawa,
    /// The classical RCCM solver.
    #[serde(rename = "rccm-classic", alias = "rccm_classic", alias = "classic")]
    RccmClassic,
}

/// A single phase.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct StepsSpec {
    /// Number of steps.
    pub count: usize,
    pub duration: f64,
}

#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct PhaseSpec {
    pub name: String,
    pub steps: usize,
    pub duration: f64,
    /// Function overrides for named loads and supports during this phase.
    #[serde(default)]
    pub functions: BTreeMap<String, String>,
    /// Reset displacements (keeping law states) at the end of the phase.
    #[serde(default)]
    pub reset_displacements: bool,
    /// Laws from this phase on, by zone name (the states carry over).
    #[serde(default)]
    pub laws: BTreeMap<String, crate::raw::RawLaw>,
}

#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields, default)]
pub struct OutputSpec {
    /// Output directory (relative to the working directory); `--out` overrides.
    pub dir: Option<String>,
    /// Write every k-th step (and the last of each phase).
    pub every: usize,
    /// Write these global steps only (1-based) instead of `every`.
    pub steps: Option<Vec<usize>>,
    /// `contacts.csv`.
    pub history: bool,
    /// `steps.csv`.
    pub report: bool,
    /// Interface `.vtu` series + `.pvd`.
    pub vtk: bool,
    /// Whole-mesh `.vtu` series + `.pvd` (displacement, stress); by default only for the pile
    /// preset (the soil).
    pub mesh_vtk: Option<bool>,
    /// Restrict the contact history and VTK to these zones.
    pub zones: Option<Vec<String>>,
    /// Restrict the contact history to these contactor nodes.
    pub nodes: Option<Vec<usize>>,
    /// The pile preset: the global steps whose shaft profiles against depth
    /// (`profiles.csv` and SVGs) are written; by default the first pull-out step, the step of
    /// the peak head load and the last step.
    pub profile_steps: Option<Vec<usize>>,
    /// `pressure.csv`, and the recovered pressure in the interface VTK.
    pub pressure: bool,
    /// A dynamic scene: node sets whose mean velocity `dynamics.csv` writes against time.
    pub velocity_sets: Option<Vec<String>>,
}

impl OutputSpec {
    /// Whether the whole-mesh series is written (`mesh_vtk`, false unless set; the pile
    /// preset sets it when the scene does not).
    pub fn writes_mesh_vtk(&self) -> bool {
        self.mesh_vtk.unwrap_or(false)
    }
}

impl Default for OutputSpec {
    fn default() -> Self {
        Self {
            dir: None,
            every: 1,
            steps: None,
            history: true,
            report: true,
            vtk: true,
            mesh_vtk: None,
            zones: None,
            nodes: None,
            profile_steps: None,
            pressure: true,
            velocity_sets: None,
        }
    }
}

/// Abscissa of a plot.
#[derive(Debug, Deserialize, Clone, Copy, Default, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum XAxis {
    #[default]
    Time,
    /// Global step number.
    Step,
    LoadFactor,
}

/// One plot.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct PlotSpec {
    /// File name (`.svg`) in the output directory.
    pub file: String,
    pub title: Option<String>,
    /// Abscissa.
    #[serde(default)]
    pub x: XAxis,
    /// A recorded quantity as abscissa instead of `x` (e.g. a displacement).
    pub x_quantity: Option<CurveSpec>,
    pub curves: Vec<CurveSpec>,
}

/// One curve.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct CurveSpec {
    /// Quantity name (see the guide).
    pub quantity: String,
    /// Zone (zone quantities; node quantities when a node is in several zones).
    pub zone: Option<String>,
    pub node: Option<usize>,
    /// Node set (reactions, displacements).
    pub set: Option<String>,
    /// Legend.
    pub label: Option<String>,
}
