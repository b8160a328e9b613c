//! The Hertz scene shared by `tests/integration/hertz.rs` and `examples/hertz_export.rs`: an
//! elastic body whose bottom is a circular arc of radius `R` (a cylinder in plane strain, a sphere
//! in axisymmetry), pressed by a prescribed displacement `−δ` of its flat top onto the rigid LINE
//! `y = 0`, frictionless (`Signorini`).
//!
//! ```text
//!   y = H  ───────────────  u_y = −δ (u_x free)
//!          │             │
//!  u_x = 0 │    body     │ free
//!  (x = 0) │             │
//!          ╰──_______────╯  y = R − √(R² − x²)   (contactor nodes: "bottom")
//!  ═══════════════════════ rigid LINE y = 0, normal +y
//! ```
//! Half model (`x ≥ 0`; `x = r` in axisymmetry). The mesh is a rectangle `[0, L] × [0, H]`
//! with a uniform fine zone `[0, b]²` around the contact (`b = 1.5 ≈ 1.5 a`) and cells growing
//! geometrically ([`Grading::Geometric`]) beyond it, mapped by
//! `y' = y + (R − √(R² − x²))(1 − y/H)`, mid-side nodes included, so P2 sides on the arc are
//! curved. The fine zone is uniform so that refining it halves `h` where the pressure is.
//!
//! Closed forms (K. L. Johnson, *Contact Mechanics*, Cambridge 1985, ch. 4, Hertz theory:
//! solids of revolution and two-dimensional contact of cylinders), with the rigid flat `E* = E/(1 − ν²)`:
//! ```text
//! cylinder, P per unit length:  a = √(4PR/(πE*)),      p(x) = p0 √(1 − x²/a²),  p0 = 2P/(πa)
//! sphere,   P total:            a = (3PR/(4E*))^(1/3), p(r) = p0 √(1 − r²/a²),  p0 = 3P/(2πa²)
//! ```
//! Measured from the contact reactions `f_i` (per unit thickness, or per radian):
//! ```text
//! plane strain:  P = 2 Σ f_i               a² = 4 Σ f_i x_i² / Σ f_i   (∫ s² √(1−s²) / ∫ √(1−s²) = 1/4)
//! axisymmetric:  P = 2π Σ f_i              a² = 5/2 Σ f_i r_i² / Σ f_i (f_i = ∫ p N_i r dr:
//!                                          ∫ s³ √(1−s²) / ∫ s √(1−s²) = (2/15)/(1/3) = 2/5)
//! ```
//! Both moments are exact for P2 nodal forces consistent with `p`, because `x²` is in the
//! P2 space along the edge (the bottom nodes keep their grid abscissae). `p0` is recovered by
//! the L2 projection of the nodal forces on the bottom edge, `M p = f` with
//! `M_ij = ∫ N_i N_j w dx` (`w = 1`, or `r` per radian), read at `x = 0`.
#![allow(dead_code)] // each user (test, example) takes what it needs

use contact_laws::Signorini;
use contact_solver::{ContactSimulation, ContactZone, RigidLine, SimulationSettings, StepResult};
use faer::Mat;
use faer::linalg::solvers::Solve;
use fem_core::generate::{Grading, RectangleSpec, graded_points, rectangle};
use fem_core::{
    Component, ElementKind, Idealization, LinearElasticModel, Material, Mesh, Supports,
};
use std::f64::consts::PI;

/// The scene's parameters.
#[derive(Clone, Copy, Debug)]
pub struct HertzScene {
    /// Plane strain (cylinder) or axisymmetric (sphere).
    pub idealization: Idealization,
    /// P1 or P2.
    pub kind: ElementKind,
    /// Radius `R` of the arc.
    pub radius: f64,
    /// Half-width `L` (radius of the body in axisymmetry).
    pub width: f64,
    /// Height `H`.
    pub height: f64,
    /// Extent of the uniform fine zone `[0, b] × [0, b]` around the contact.
    pub fine_extent: f64,
    /// Cells across the fine zone, in x and in y (size `h = b / cells`).
    pub fine_cells: usize,
    /// Growth of the cell size from one cell to the next outside the fine zone.
    pub growth: f64,
    /// Young's modulus `E`.
    pub young: f64,
    /// Poisson's ratio `ν`.
    pub poisson: f64,
    /// Prescribed downward displacement `δ` of the top.
    pub delta: f64,
    /// Alert distance of the contact zone.
    pub alert: f64,
}

impl HertzScene {
    /// `R = 100`, `L = H = 20`, `E = 1000`, `ν = 0.3`, and `δ` giving `a ≈ 1` (so
    /// `L/a = H/a ≈ 20`); a uniform fine zone `[0, 1.5]²` of `fine_cells²` cells, then cells
    /// growing by 1.5 out to `L` and `H`; alert distance `0.005` (every node with
    /// `g₀ ≤ δ + 0.005` is in the reduced problem, about twice the closed ones).
    pub fn new(idealization: Idealization, kind: ElementKind, fine_cells: usize) -> Self {
        let delta = match idealization {
            Idealization::Axisymmetric => 0.01,
            _ => 0.02,
        };
        Self {
            idealization,
            kind,
            radius: 100.0,
            width: 20.0,
            height: 20.0,
            fine_extent: 1.5,
            fine_cells,
            growth: 1.5,
            young: 1000.0,
            poisson: 0.3,
            delta,
            alert: 0.005,
        }
    }

    /// [`graded_lines`] from 0 to `end` with this scene's fine zone and growth.
    pub fn grid_lines(&self, end: f64) -> Vec<f64> {
        graded_lines(self.fine_extent, self.fine_cells, self.growth, end)
    }

    /// `E* = E/(1 − ν²)` (rigid flat).
    pub fn e_star(&self) -> f64 {
        self.young / (1.0 - self.poisson * self.poisson)
    }

    /// Hertz's `(a, p0)` for the total load `p_total` (per unit length in plane strain).
    pub fn hertz(&self, p_total: f64) -> (f64, f64) {
        let (r, e) = (self.radius, self.e_star());
        match self.idealization {
            Idealization::Axisymmetric => {
                let a = (3.0 * p_total * r / (4.0 * e)).cbrt();
                (a, 3.0 * p_total / (2.0 * PI * a * a))
            }
            _ => {
                let a = (4.0 * p_total * r / (PI * e)).sqrt();
                (a, 2.0 * p_total / (PI * a))
            }
        }
    }

    /// The mesh: [`arc_mesh`] on [`Self::grid_lines`] up to `L` and `H`.
    pub fn mesh(&self) -> Mesh {
        let xs = self.grid_lines(self.width);
        let ys = self.grid_lines(self.height);
        arc_mesh(self.kind, &xs, &ys, self.radius, self.height)
    }

    /// The simulation, not yet stepped.
    pub fn simulation(
        &self,
        settings: SimulationSettings,
    ) -> ContactSimulation<LinearElasticModel, Signorini> {
        let mesh = self.mesh();
        let top = mesh.node_set("top").unwrap().to_vec();
        let left = mesh.node_set("left").unwrap().to_vec();
        let bottom = mesh.node_set("bottom").unwrap().to_vec();
        let mut supports = Supports::new();
        supports.prescribe(&top, Component::Y, -self.delta).unwrap();
        supports.fix(&left, Component::X);
        let material = Material::new(self.young, self.poisson, 0.0).unwrap();
        let model = LinearElasticModel::new(mesh, self.idealization, &[(0, material)], supports)
            .expect("supported body");
        let ground = RigidLine::new([-1.0, 0.0], [self.width + 1.0, 0.0]).unwrap();
        let zone = ContactZone::rigid("arc", bottom, ground, Signorini, self.alert);
        ContactSimulation::new(model, vec![zone], settings).expect("valid scene")
    }

    /// The reduced problem of one step of the whole `δ` with a dense `F*`, frictionless (the
    /// FE rows of `docs/benchmarks.md` "Which algorithm, measured").
    pub fn dense_problem(&self) -> contact_solver::ReducedProblem {
        let dense = contact_solver::FlexibilityMode::Dense;
        let mut sim = self.simulation(SimulationSettings::default().with_flexibility(dense));
        sim.step(1.0, 1.0).expect("the Hertz step solves");
        sim.last_reduced_problem().expect("a problem").clone()
    }

    /// The force-controlled variant (issue 16): no support on the top, which carries a
    /// uniform traction whose resultant is the total load `p_total` (per unit length in plane
    /// strain, `P` over the whole sphere in axisymmetry); the body floats along `y` (its one
    /// rigid-body mode, the symmetry support `u_x = 0` on `x = 0` holds the others) and
    /// contact alone holds it ([`LinearElasticModel::floating`]).
    pub fn force_simulation(
        &self,
        p_total: f64,
        settings: SimulationSettings,
    ) -> ContactSimulation<LinearElasticModel, Signorini> {
        let mesh = self.mesh();
        let left = mesh.node_set("left").unwrap().to_vec();
        let bottom = mesh.node_set("bottom").unwrap().to_vec();
        let mut supports = Supports::new();
        supports.fix(&left, Component::X);
        let material = Material::new(self.young, self.poisson, 0.0).unwrap();
        let mut model =
            LinearElasticModel::floating(mesh, self.idealization, &[(0, material)], supports)
                .expect("a body held by contact");
        // half model: P/2 over the width L (plane strain); P/(2π) per radian over r ∈ [0, L]
        let traction = match self.idealization {
            Idealization::Axisymmetric => p_total / (PI * self.width * self.width),
            _ => p_total / (2.0 * self.width),
        };
        model
            .add_edge_traction("top", |_| [0.0, -traction])
            .unwrap();
        let ground = RigidLine::new([-1.0, 0.0], [self.width + 1.0, 0.0]).unwrap();
        let zone = ContactZone::rigid("arc", bottom, ground, Signorini, self.alert);
        ContactSimulation::new(model, vec![zone], settings).expect("valid scene")
    }

    /// Measures `P`, `a` and `p0` from a step's reactions.
    pub fn measure(
        &self,
        sim: &ContactSimulation<LinearElasticModel, Signorini>,
        res: &StepResult,
    ) -> Measured {
        let axisymmetric = matches!(self.idealization, Idealization::Axisymmetric);
        let (mut s0, mut s2) = (0.0, 0.0);
        let mut force = vec![0.0; sim.structure().mesh().node_count()];
        let mut closed = 0;
        for c in &res.contacts {
            let (f, x) = (c.r.n, c.position[0]);
            s0 += f;
            s2 += f * x * x;
            force[c.node] = f;
            closed += usize::from(f > 0.0);
        }
        let p_total = if axisymmetric {
            2.0 * PI * s0
        } else {
            2.0 * s0
        };
        let moment = if axisymmetric { 2.5 } else { 4.0 };
        let a_fe = (moment * s2 / s0).sqrt();
        let p0_fe = project_pressure_at_origin(sim.structure().mesh(), &force, axisymmetric);
        let (a_hertz, p0_hertz) = self.hertz(p_total);
        Measured {
            p_total,
            a_fe,
            a_hertz,
            p0_fe,
            p0_hertz,
            closed,
            active: res.report.active_contacts,
        }
    }
}

/// What [`HertzScene::measure`] finds.
#[derive(Clone, Copy, Debug)]
pub struct Measured {
    /// Total load `P` (per unit length in plane strain).
    pub p_total: f64,
    /// Half-width from the second moment of the reactions.
    pub a_fe: f64,
    /// Hertz's half-width for `p_total`.
    pub a_hertz: f64,
    /// Pressure at the centre from the L2 projection.
    pub p0_fe: f64,
    /// Hertz's peak pressure for `p_total`.
    pub p0_hertz: f64,
    /// Contacts with `r_n > 0`.
    pub closed: usize,
    /// Contacts in the reduced problem.
    pub active: usize,
}

impl Measured {
    /// Relative error of `a`.
    pub fn a_error(&self) -> f64 {
        (self.a_fe - self.a_hertz) / self.a_hertz
    }

    /// Relative error of `p0`.
    pub fn p0_error(&self) -> f64 {
        (self.p0_fe - self.p0_hertz) / self.p0_hertz
    }
}

/// Grid lines from 0 to `end`: `fine_cells` uniform cells over `[0, b]` (`b = fine_extent`),
/// then cells growing geometrically by about `growth` (a [`Grading::Geometric`] subdivision
/// of `[b, end]` whose first cell is close to `growth · h`).
pub fn graded_lines(fine_extent: f64, fine_cells: usize, growth: f64, end: f64) -> Vec<f64> {
    let (b, m) = (fine_extent, fine_cells);
    let h = b / m as f64;
    let mut lines: Vec<f64> = (0..=m).map(|i| b * i as f64 / m as f64).collect();
    let (g, rest) = (growth, end - b);
    // smallest k with Σ_{i=1..k} h gⁱ ≥ rest
    let k = ((1.0 + rest * (g - 1.0) / (h * g)).ln() / g.ln())
        .ceil()
        .max(1.0) as usize;
    let ratio = g.powi(k as i32 - 1);
    let outer = graded_points(b, end, k, Grading::Geometric { ratio }).unwrap();
    lines.extend_from_slice(&outer[1..]);
    lines
}

/// A body whose bottom is an arc of radius `radius`: a rectangle of unit cells whose grid
/// lines are moved to `xs` and `ys` (piecewise linear, so P2 mid-side nodes stay at the middle
/// of each cell), then mapped by `y' = y + (R − √(R² − x²))(1 − y/H)` (`H = height`, the top
/// stays flat); region 0, the rectangle's node and edge sets.
pub fn arc_mesh(kind: ElementKind, xs: &[f64], ys: &[f64], radius: f64, height: f64) -> Mesh {
    let (nx, ny) = (xs.len() - 1, ys.len() - 1);
    let mut spec = RectangleSpec::new([0.0, nx as f64], [0.0, ny as f64], nx, ny);
    spec.kind = kind;
    let grid = rectangle(&spec).expect("valid rectangle spec");
    let along = |lines: &[f64], s: f64| {
        let i = (s.floor() as usize).min(lines.len() - 2);
        lines[i] + (s - i as f64) * (lines[i + 1] - lines[i])
    };
    let (r, h) = (radius, height);
    let nodes = grid
        .nodes()
        .iter()
        .map(|&[s, t]| {
            let (x, y) = (along(xs, s), along(ys, t));
            [x, y + (r - (r * r - x * x).sqrt()) * (1.0 - y / h)]
        })
        .collect();
    let mesh = Mesh::new(
        nodes,
        grid.kind(),
        grid.connectivity().to_vec(),
        grid.regions().to_vec(),
    )
    .expect("the map keeps every element positive");
    with_sets_of(mesh, &grid)
}

/// `mesh` with every element in `region` (nodes, elements and sets kept).
pub fn with_region(mesh: &Mesh, region: u32) -> Mesh {
    let out = Mesh::new(
        mesh.nodes().to_vec(),
        mesh.kind(),
        mesh.connectivity().to_vec(),
        vec![region; mesh.element_count()],
    )
    .unwrap();
    with_sets_of(out, mesh)
}

/// `mesh` with the node and edge sets of `from` (same numbering).
fn with_sets_of(mut mesh: Mesh, from: &Mesh) -> Mesh {
    for name in from.node_set_names() {
        mesh.add_node_set(name, from.node_set(name).unwrap().to_vec())
            .unwrap();
    }
    for name in from.edge_set_names() {
        mesh.add_edge_set(name, from.edge_set(name).unwrap().to_vec())
            .unwrap();
    }
    mesh
}

/// 4-point Gauss–Legendre on `[0, 1]`, `(point, weight)`: exact to degree 7.
pub const GAUSS4: [(f64, f64); 4] = [
    (0.069_431_844_202_973_71, 0.173_927_422_568_726_9),
    (0.330_009_478_207_571_9, 0.326_072_577_431_273_1),
    (0.669_990_521_792_428_1, 0.326_072_577_431_273_1),
    (0.930_568_155_797_026_3, 0.173_927_422_568_726_9),
];

/// The shape functions of a side with `nodes` nodes (`[a, b]` or `[a, b, mid]`) at `s ∈ [0, 1]`.
pub fn edge_shapes(nodes: usize, s: f64) -> Vec<f64> {
    if nodes == 3 {
        vec![
            (1.0 - s) * (1.0 - 2.0 * s),
            s * (2.0 * s - 1.0),
            4.0 * s * (1.0 - s),
        ]
    } else {
        vec![1.0 - s, s]
    }
}

/// The L2 projection `M v = f` of nodal forces `force` (indexed by node) on the edge set
/// `set`, `M_ij = ∫ N_i N_j w dx` with `w = x` per radian in axisymmetry: `(x, v)` at every
/// node of the edge, in `x` order. Shape functions are taken in the abscissa `x` (the sides'
/// nodes keep their grid abscissae, so `x` is linear along each side and `ds/dx = 1 + O(x²/R²)`
/// is dropped).
pub fn project_on_edge(
    mesh: &Mesh,
    set: &str,
    force: &[f64],
    axisymmetric: bool,
) -> Vec<(f64, f64)> {
    let sides = mesh.edge_set(set).unwrap();
    let mut nodes: Vec<usize> = sides.iter().flat_map(|&s| mesh.side_nodes(s)).collect();
    nodes.sort_unstable();
    nodes.dedup();
    let index = |n: usize| nodes.binary_search(&n).unwrap();
    let m = nodes.len();
    let mut mass = Mat::<f64>::zeros(m, m);
    for &side in sides {
        let local: Vec<usize> = mesh.side_nodes(side).collect(); // [a, b] or [a, b, mid]
        let (xa, xb) = (mesh.nodes()[local[0]][0], mesh.nodes()[local[1]][0]);
        // N_i N_j x is degree 5 for P2: GAUSS4 is exact
        for (s, w) in GAUSS4 {
            let shape = edge_shapes(local.len(), s);
            let x = xa + s * (xb - xa);
            let weight = w * (xb - xa).abs() * if axisymmetric { x } else { 1.0 };
            for (i, &ni) in local.iter().enumerate() {
                for (j, &nj) in local.iter().enumerate() {
                    mass[(index(ni), index(nj))] += weight * shape[i] * shape[j];
                }
            }
        }
    }
    let rhs = Mat::<f64>::from_fn(m, 1, |i, _| force[nodes[i]]);
    let v = mass.partial_piv_lu().solve(&rhs);
    let mut out: Vec<(f64, f64)> = (0..m)
        .map(|i| (mesh.nodes()[nodes[i]][0], v[(i, 0)]))
        .collect();
    out.sort_by(|a, b| a.0.total_cmp(&b.0));
    out
}

/// [`project_on_edge`] on the bottom edge, read at its leftmost node (`x = 0`).
pub fn project_pressure_at_origin(mesh: &Mesh, force: &[f64], axisymmetric: bool) -> f64 {
    project_on_edge(mesh, "bottom", force, axisymmetric)[0].1
}
