//! The scene file: the TOML format read by `bipo`, as serde types.
//!
//! Every table denies unknown keys, so a typo is an error with its line and column. The
//! *meaning* of the values (positive moduli, existing node sets, increasing time tables, …) is
//! checked afterwards by [`crate::build`], which names the key path of the offending value.
//! The format is documented key by key in `docs/guide.md` ("Scene files and the `bipo`
//! command").

use serde::{Deserialize, Deserializer};
use std::collections::BTreeMap;

/// Two numbers `[a, b]` (a point, a vector, a `[time, value]` row): exactly two, so that a
/// third value is an error rather than silently dropped.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pair(pub [f64; 2]);

impl<'de> Deserialize<'de> for Pair {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let v = Vec::<f64>::deserialize(d)?;
        match v[..] {
            [a, b] => Ok(Pair([a, b])),
            _ => Err(serde::de::Error::invalid_length(
                v.len(),
                &"two numbers [a, b]",
            )),
        }
    }
}

/// A whole scene file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// A title for reports.
    pub title: Option<String>,
    /// Free-text note of the unit system (the code needs only consistency).
    pub units: Option<Units>,
    /// A seed study built by the library (`delamination`, `shear`, `pile`).
    pub preset: Option<crate::raw::RawPreset>,
    /// The mesh.
    pub mesh: Option<crate::raw::RawMesh>,
    /// The 2D idealisation.
    pub analysis: Option<crate::raw::RawAnalysis>,
    /// Materials per region.
    #[serde(default)]
    pub materials: Vec<MaterialSpec>,
    /// Initial stress field.
    pub initial_stress: Option<crate::raw::RawInitialStress>,
    /// Piecewise linear time functions, by name.
    #[serde(default)]
    pub functions: BTreeMap<String, Vec<Pair>>,
    /// Supports (prescribed displacements).
    #[serde(default)]
    pub supports: Vec<SupportSpec>,
    /// Loads.
    #[serde(default)]
    pub loads: Vec<crate::raw::RawLoad>,
    /// Contact zones.
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
    /// SVG plots.
    #[serde(default)]
    pub plots: Vec<PlotSpec>,
}

/// Units note.
#[derive(Debug, Deserialize, Clone, Default)]
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

/// P1 or P2 triangles.
#[derive(Debug, Deserialize, Clone, Copy, PartialEq, Eq)]
pub enum Element {
    /// 3-node triangles.
    #[serde(alias = "p1", alias = "tri3")]
    P1,
    /// 6-node triangles.
    #[serde(alias = "p2", alias = "tri6")]
    P2,
}

/// Geometric grading of a 1D subdivision.
#[derive(Debug, Clone, Copy)]
pub enum GradingSpec {
    /// Equal cells.
    Uniform {},
    /// Last cell over first cell = `ratio`.
    Geometric {
        /// h_last / h_first.
        ratio: f64,
    },
    /// Refined toward both ends, `ratio` = h_middle / h_end.
    BothEnds {
        /// h_middle / h_end.
        ratio: f64,
    },
}

impl Default for GradingSpec {
    fn default() -> Self {
        Self::Uniform {}
    }
}

/// One layer of a rectangle.
#[derive(Debug, Clone)]
pub struct LayerSpec {
    /// Upper edge.
    pub top: f64,
    /// Cells across.
    pub ny: usize,
    /// Grading upward.
    pub grading: GradingSpec,
    /// Region id.
    pub region: u32,
}

/// The mesh: a generator or a Gmsh file.
#[derive(Debug, Clone)]
pub enum MeshSpec {
    /// `fem_core::generate::rectangle`.
    Rectangle {
        /// P1 / P2.
        element: Element,
        /// `[x0, x1]`.
        x: Pair,
        /// Cells along x.
        nx: usize,
        /// Grading along x.
        grading_x: GradingSpec,
        /// `[y0, y1]` (one layer; or `y0` and `layers`).
        y: Option<Pair>,
        /// Cells along y for the one-layer form.
        ny: Option<usize>,
        /// Grading along y for the one-layer form.
        grading_y: Option<GradingSpec>,
        /// Region of the one-layer form.
        region: Option<u32>,
        /// Bottom edge (layered form).
        y0: Option<f64>,
        /// Layers from bottom to top (layered form).
        layers: Option<Vec<LayerSpec>>,
    },
    /// `fem_core::generate::pile_in_soil` (axisymmetric).
    Pile {
        /// P1 / P2 (default P2).
        element: Option<Element>,
        /// Pile diameter.
        diameter: Option<f64>,
        /// Embedded length.
        length: Option<f64>,
        /// Radial extent of the soil.
        width: Option<f64>,
        /// Depth of the soil.
        depth: Option<f64>,
        /// Cells across the pile radius.
        cells_pile_r: Option<usize>,
        /// Cells in the soil, radially.
        cells_soil_r: Option<usize>,
        /// Cells along the shaft.
        cells_shaft: Option<usize>,
        /// Cells below the tip.
        cells_below_tip: Option<usize>,
        /// Grading across the pile radius.
        grading_pile_r: Option<GradingSpec>,
        /// Grading of the soil, outward.
        grading_soil_r: Option<GradingSpec>,
        /// Grading along the shaft, upward.
        grading_shaft: Option<GradingSpec>,
        /// Grading below the tip, upward.
        grading_below_tip: Option<GradingSpec>,
        /// `split` or `shared`.
        tip_corner: Option<TipCornerSpec>,
    },
    /// A Gmsh `.msh` 4.1 file.
    Gmsh {
        /// Path, relative to the scene file.
        file: String,
        /// Expected element order (checked against the file).
        element: Option<Element>,
    },
}

/// Pile tip corner.
#[derive(Debug, Deserialize, Clone, Copy)]
#[serde(rename_all = "snake_case")]
pub enum TipCornerSpec {
    /// Duplicated, first interface pair.
    Split,
    /// Shared by pile and soil.
    Shared,
}

/// The idealisation.
#[derive(Debug, Clone, Copy)]
pub enum Analysis {
    /// Plane strain (per unit thickness).
    PlaneStrain {},
    /// Plane stress with a thickness.
    PlaneStress {
        /// Thickness.
        thickness: f64,
    },
    /// Axisymmetric `(r, z)`, per radian.
    Axisymmetric {},
}

/// A material on one or several regions.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    /// A name, for the reader of the scene only.
    #[allow(dead_code)]
    pub name: Option<String>,
    /// One region.
    pub region: Option<u32>,
    /// Several regions.
    pub regions: Option<Vec<u32>>,
    /// Young's modulus.
    pub young: f64,
    /// Poisson's ratio.
    pub poisson: f64,
    /// Unit weight (for gravity loads).
    #[serde(default)]
    pub unit_weight: f64,
}

/// Initial stress.
#[derive(Debug, Clone, Copy)]
pub enum InitialStress {
    /// `fem_core::geostatic(gamma, k0, z_surface)`.
    Geostatic {
        /// Unit weight.
        gamma: f64,
        /// Earth pressure coefficient at rest.
        k0: f64,
        /// Ground surface elevation.
        z_surface: f64,
    },
}

/// Which displacement components a support constrains.
#[derive(Debug, Deserialize, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum ComponentSpec {
    /// `u_x` (or `u_r`).
    X,
    /// `u_y` (or `u_z`).
    Y,
    /// Both.
    Both,
}

/// A support: prescribed displacement on a node set.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct SupportSpec {
    /// A name (phases may override its function by this name).
    pub name: Option<String>,
    /// Node set.
    pub set: String,
    /// Component(s).
    pub component: ComponentSpec,
    /// Prescribed value (times the function).
    #[serde(default)]
    pub value: f64,
    /// Time function (default: constant 1).
    pub function: Option<String>,
    /// Phases in which the support acts (default: all).
    pub phases: Option<Vec<String>>,
}

/// A load.
#[derive(Debug, Clone)]
pub enum LoadSpec {
    /// Traction (force per area, global frame) on an edge set.
    Traction {
        /// A name.
        name: Option<String>,
        /// Edge set.
        set: String,
        /// `[t_x, t_y]`.
        value: Pair,
        /// Time function.
        function: Option<String>,
        /// Phases (default: all).
        phases: Option<Vec<String>>,
    },
    /// A force on every node of a node set.
    NodalForce {
        /// A name.
        name: Option<String>,
        /// Node set.
        set: String,
        /// `[f_x, f_y]` per node.
        value: Pair,
        /// Time function.
        function: Option<String>,
        /// Phases (default: all).
        phases: Option<Vec<String>>,
    },
    /// A uniform body force (force per volume) over the whole mesh.
    BodyForce {
        /// A name.
        name: Option<String>,
        /// `[b_x, b_y]`.
        value: Pair,
        /// Time function.
        function: Option<String>,
        /// Phases (default: all).
        phases: Option<Vec<String>>,
    },
    /// The self-weight of every region (its material's `unit_weight`, along −y), in full.
    Gravity {
        /// A name.
        name: Option<String>,
        /// Phases (default: all).
        phases: Option<Vec<String>>,
    },
}

/// A contact zone.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct ZoneSpec {
    /// Zone name.
    pub name: String,
    /// Contactor node set.
    pub contactor: String,
    /// What the contactor faces.
    pub target: crate::raw::RawTarget,
    /// Interface law.
    pub law: crate::raw::RawLaw,
    /// Alert distance Δx.
    pub alert_distance: f64,
}

/// Side of an ARC.
#[derive(Debug, Deserialize, Clone, Copy)]
#[serde(rename_all = "snake_case")]
pub enum ArcSideSpec {
    /// Contactor outside the circle.
    Outside,
    /// Contactor inside the circle.
    Inside,
}

/// Target of a zone.
#[derive(Debug, Clone)]
pub enum TargetSpec {
    /// Rigid segment a → b, contactor on its left.
    Line {
        /// Start.
        a: Pair,
        /// End.
        b: Pair,
    },
    /// Rigid circular arc.
    Arc {
        /// Centre.
        center: Pair,
        /// Radius.
        radius: f64,
        /// Start angle (radians, counter-clockwise from +x).
        start_angle: f64,
        /// Sweep (radians, default 2π).
        sweep: Option<f64>,
        /// `outside` or `inside`.
        side: ArcSideSpec,
    },
    /// Node-to-node pairs with a node set of the same length.
    NodePairs {
        /// Target node set.
        set: String,
        /// Fixed normal.
        normal: Option<Pair>,
    },
    /// Node-to-segment on the polyline of a node set.
    Segments {
        /// Target node set (in order).
        set: String,
    },
}

/// β time integration.
#[derive(Debug, Deserialize, Clone, Copy, Default, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum SchemeSpec {
    /// Implicit Euler.
    #[default]
    ImplicitEuler,
    /// θ-method (with `theta`).
    Theta,
}

/// Interface law.
#[derive(Debug, Clone, Copy)]
pub enum LawSpec {
    /// Frictionless unilateral contact.
    Signorini {},
    /// Coulomb friction.
    Coulomb {
        /// Friction coefficient.
        mu: f64,
    },
    /// RCCM adhesion.
    Rccm(RccmSpec),
}

/// RCCM parameters (all required except `m`, `beta_0`, `scheme`, `theta`).
#[derive(Debug, Clone, Copy)]
pub struct RccmSpec {
    /// Normal stiffness.
    pub c_n: f64,
    /// Tangential stiffness.
    pub c_t: f64,
    /// Dupré's energy.
    pub w: f64,
    /// Viscosity.
    pub alpha: f64,
    /// Friction coefficient.
    pub mu: f64,
    /// Exponent of f(β).
    pub m: u32,
    /// Initial β.
    pub beta_0: f64,
    /// β scheme.
    pub scheme: SchemeSpec,
    /// θ of the θ-scheme.
    pub theta: Option<f64>,
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
    /// Maximum adhesion iterations.
    pub max_adhesion_iterations: Option<usize>,
    /// Maximum penetration-check passes.
    pub max_detection_passes: Option<usize>,
    /// Accept non-converged steps.
    pub accept_non_converged: Option<bool>,
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

/// Algorithm names.
#[derive(Debug, Deserialize, Clone, Copy)]
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
    /// Duration.
    pub duration: f64,
}

/// One phase of several.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct PhaseSpec {
    /// Name.
    pub name: String,
    /// Number of steps.
    pub steps: usize,
    /// Duration.
    pub duration: f64,
    /// Function overrides for named loads and supports during this phase.
    #[serde(default)]
    pub functions: BTreeMap<String, String>,
    /// Reset displacements (keeping law states) at the end of the phase.
    #[serde(default)]
    pub reset_displacements: bool,
}

/// Outputs.
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
    /// Whole-mesh `.vtu` series + `.pvd` (displacement, stress).
    pub mesh_vtk: bool,
    /// Restrict the contact history and VTK to these zones.
    pub zones: Option<Vec<String>>,
    /// Restrict the contact history to these contactor nodes.
    pub nodes: Option<Vec<usize>>,
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
            mesh_vtk: false,
            zones: None,
            nodes: None,
        }
    }
}

/// Abscissa of a plot.
#[derive(Debug, Deserialize, Clone, Copy, Default, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum XAxis {
    /// Time.
    #[default]
    Time,
    /// Global step number.
    Step,
    /// Load factor.
    LoadFactor,
}

/// One plot.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct PlotSpec {
    /// File name (`.svg`) in the output directory.
    pub file: String,
    /// Title.
    pub title: Option<String>,
    /// Abscissa.
    #[serde(default)]
    pub x: XAxis,
    /// A recorded quantity as abscissa instead of `x` (e.g. a displacement).
    pub x_quantity: Option<CurveSpec>,
    /// Curves.
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
    /// Node.
    pub node: Option<usize>,
    /// Node set (reactions, displacements).
    pub set: Option<String>,
    /// Legend.
    pub label: Option<String>,
}

/// A seed study built by the library.
#[derive(Debug, Clone)]
pub enum Preset {
    /// Seed 5.6.1.
    Delamination {
        /// Length.
        length: Option<f64>,
        /// Height.
        height: Option<f64>,
        /// Young's modulus.
        young: Option<f64>,
        /// Poisson's ratio.
        poisson: Option<f64>,
        /// Cells along the interface.
        nx: Option<usize>,
        /// Cells across.
        ny: Option<usize>,
        /// P1 / P2.
        element: Option<Element>,
        /// Lift of point A.
        lift: Option<f64>,
        /// Duration.
        duration: Option<f64>,
        /// Steps.
        steps: Option<usize>,
        /// Interface law parameters (each optional).
        interface: Option<RccmOverride>,
    },
    /// Seed 5.6.2.
    Shear {
        /// Length.
        length: Option<f64>,
        /// Height.
        height: Option<f64>,
        /// Young's modulus.
        young: Option<f64>,
        /// Poisson's ratio.
        poisson: Option<f64>,
        /// Cells along the interface.
        nx: Option<usize>,
        /// Cells across.
        ny: Option<usize>,
        /// P1 / P2.
        element: Option<Element>,
        /// Top `u_y` at the end.
        press: Option<f64>,
        /// Left `u_x` at the end.
        push: Option<f64>,
        /// Duration.
        duration: Option<f64>,
        /// Steps.
        steps: Option<usize>,
        /// Interface law parameters (each optional).
        interface: Option<RccmOverride>,
    },
    /// Seed chapter 6: pile pull-out (geostatic, installation, pull-out phases).
    Pile {
        /// `plancoet` (default) or `cran`.
        site: Option<Site>,
        /// Plain Coulomb interface (β₀ = 0) instead of RCCM.
        coulomb: bool,
        /// Pile Young's modulus (kPa).
        pile_young: Option<f64>,
        /// Pile Poisson's ratio.
        pile_poisson: Option<f64>,
        /// Pile unit weight (kN/m³).
        pile_unit_weight: Option<f64>,
        /// Soil Young's modulus (kPa).
        soil_young: Option<f64>,
        /// Soil Poisson's ratio.
        soil_poisson: Option<f64>,
        /// Soil unit weight (kN/m³).
        soil_unit_weight: Option<f64>,
        /// K0.
        k0: Option<f64>,
        /// Phase 2.
        installation: Option<InstallationSpec>,
        /// Final head displacement (m).
        head_displacement: Option<f64>,
        /// Pull-out increments.
        steps: Option<usize>,
        /// Alert distance (m).
        alert_distance: Option<f64>,
        /// Interface law parameters (each optional).
        interface: Option<RccmOverride>,
        /// Mesh overrides.
        mesh: Option<PileMeshOverride>,
    },
}

/// Which pile of the seed a pile preset starts from.
#[derive(Debug, Deserialize, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Site {
    /// Plancoët (L_p = 13 m).
    #[serde(alias = "plancoët")]
    Plancoet,
    /// Cran (L_p = 17 m).
    Cran,
}

/// Phase 2 of the pile preset.
#[derive(Debug, Clone, Copy)]
pub enum InstallationSpec {
    /// No installation.
    None {},
    /// Imposed radial displacement δ of the soil's interface nodes.
    RadialDisplacement {
        /// δ (m).
        value: f64,
    },
    /// δ such that the shaft normal force is this multiple of the geostatic one.
    NormalForceRatio {
        /// Ratio (>= 1).
        value: f64,
    },
}

/// Mesh overrides of the pile preset.
#[derive(Debug, Deserialize, Clone, Copy, Default)]
#[serde(deny_unknown_fields)]
pub struct PileMeshOverride {
    /// P1 / P2.
    pub element: Option<Element>,
    /// Pile diameter.
    pub diameter: Option<f64>,
    /// Embedded length.
    pub length: Option<f64>,
    /// Radial extent.
    pub width: Option<f64>,
    /// Depth.
    pub depth: Option<f64>,
    /// Cells across the pile radius.
    pub cells_pile_r: Option<usize>,
    /// Cells in the soil, radially.
    pub cells_soil_r: Option<usize>,
    /// Cells along the shaft.
    pub cells_shaft: Option<usize>,
    /// Cells below the tip.
    pub cells_below_tip: Option<usize>,
}

/// Optional overrides of RCCM parameters.
#[derive(Debug, Deserialize, Clone, Copy, Default)]
#[serde(deny_unknown_fields)]
pub struct RccmOverride {
    /// Normal stiffness.
    pub c_n: Option<f64>,
    /// Tangential stiffness.
    pub c_t: Option<f64>,
    /// Dupré's energy.
    pub w: Option<f64>,
    /// Viscosity.
    pub alpha: Option<f64>,
    /// Friction.
    pub mu: Option<f64>,
    /// Exponent.
    pub m: Option<u32>,
    /// Initial β.
    pub beta_0: Option<f64>,
    /// Scheme.
    pub scheme: Option<SchemeSpec>,
    /// θ.
    pub theta: Option<f64>,
}
