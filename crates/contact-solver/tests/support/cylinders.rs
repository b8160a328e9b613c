//! Two elastic cylinders in contact (plane strain), shared by `tests/integration/two_cylinders.rs`: an
//! upper body whose bottom is an arc of radius `R₁`, pressed by a resultant force on its flat
//! top, onto a lower body whose top is an arc of radius `R₂` and whose flat bottom is fixed.
//!
//! ```text
//!   y = H   ═══════════════  rigid cap: the top nodes tied along x and y (one "pilot" dof
//!           │   upper      │  each), loaded by (Q, −P); the body floats (contact holds it)
//!           ╰──___________─╯  y = R₁ − √(R₁² − x²)            contactor: "up.bottom"
//!           ╭──‾‾‾‾‾‾‾‾‾‾‾─╮  y = −(R₂ − √(R₂² − x²))          target:    "low.top"
//!           │   lower      │
//!   y = −H  ▨▨▨▨▨▨▨▨▨▨▨▨▨▨▨▨  fixed
//! ```
//! Each body is a rectangle `[−L, L] × [0, H]` (or `[0, L]` for a half model with `u_x = 0`
//! on `x = 0`) meshed as `tests/support/hertz_scene.rs` does: a uniform fine zone of
//! `fine_cells` cells over `[0, b]` (and `[−b, 0]`), cells growing by 1.5 beyond, then mapped
//! onto the arc (P2 sides on the arc are curved). The bodies are joined with
//! [`Mesh::join`] (prefixes `up.` and `low.`).
//!
//! Closed forms (K. L. Johnson, *Contact Mechanics*, Cambridge 1985, §4.2 and §7.1; Hertz
//! 1882; Cattaneo 1938; Mindlin 1949; Mindlin & Deresiewicz 1953), for two cylinders pressed by
//! `P` per unit length, plane strain:
//! ```text
//! 1/E* = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂,   1/R = 1/R₁ + 1/R₂
//! a = √(4PR/(πE*)),   p(x) = p0 √(1 − x²/a²),   p0 = 2P/(πa)
//! Q < μP (identical bodies, β = 0):   stick zone |x| < c,  c/a = √(1 − Q/(μP))
//!   q(x) = μ p0 √(1 − x²/a²) − μ p0 (c/a) √(1 − x²/c²)   (|x| < c; without the second term beyond)
//! ```
//! Measured from the contact reactions (nodal forces `f_i`, per unit thickness; `x²` is in the
//! P2 space along the edge, so the moments are exact for forces consistent with a traction):
//! ```text
//! P = Σ f_n,i (× 2 for the half model),   a² = 4 Σ f_n,i x_i² / Σ f_n,i
//! the stick deficit d_i = μ f_n,i − s f_t,i (s the sign of the total friction force) is
//! μ p0 (c/a) √(1 − x²/c²) on |x| < c:     c² = 4 Σ d_i x_i² / Σ d_i
//! ```
#![allow(dead_code)] // each user takes what it needs

use super::hertz_scene::{GAUSS4, arc_mesh, edge_shapes, graded_lines, project_on_edge};
use contact_laws::StandardLaw;
use contact_solver::{ContactSimulation, ContactZone, SimulationSettings, StepResult};
use fem_core::{
    Component, ElementKind, Idealization, LinearElasticModel, Material, Mesh, Supports,
};

/// One body's data.
#[derive(Clone, Copy, Debug)]
pub struct Body {
    /// Radius of the arc.
    pub radius: f64,
    /// Young's modulus.
    pub young: f64,
    /// Poisson's ratio.
    pub poisson: f64,
    /// Cells across the fine zone `[0, b]`.
    pub fine_cells: usize,
}

/// How the contactor nodes of the upper body meet the lower body.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pairing {
    /// Node to node with the fixed normal `+y` (matching meshes: same `fine_cells`).
    NodePairs,
    /// Node to segment on the lower body's arc, taken as the polyline of its nodes.
    Segments,
}

/// The scene.
#[derive(Clone, Copy, Debug)]
pub struct Cylinders {
    /// Upper body (the contactor).
    pub upper: Body,
    /// Lower body (the target).
    pub lower: Body,
    /// Half model `x ≥ 0` (`u_x = 0` on `x = 0`, frictionless only) or the full width.
    pub half: bool,
    /// Element kind.
    pub kind: ElementKind,
    /// Half-width `L`.
    pub width: f64,
    /// Height `H` of each body.
    pub height: f64,
    /// Extent `b` of the uniform fine zone.
    pub fine_extent: f64,
    /// Growth of the cells beyond the fine zone.
    pub growth: f64,
    /// How the two surfaces are paired.
    pub pairing: Pairing,
    /// Alert distance.
    pub alert: f64,
}

impl Cylinders {
    /// `L = H = 20`, `b = 1.5`, growth 1.5, P2, alert distance 0.01 (the loads used give
    /// `a ≈ 1`).
    pub fn new(upper: Body, lower: Body, half: bool, pairing: Pairing) -> Self {
        Self {
            upper,
            lower,
            half,
            kind: ElementKind::Tri6,
            width: 20.0,
            height: 20.0,
            fine_extent: 1.5,
            growth: 1.5,
            pairing,
            alert: 0.01,
        }
    }

    /// `E*` of the pair.
    pub fn e_star(&self) -> f64 {
        let c = |b: &Body| (1.0 - b.poisson * b.poisson) / b.young;
        1.0 / (c(&self.upper) + c(&self.lower))
    }

    /// The relative radius `R = (1/R₁ + 1/R₂)⁻¹`.
    pub fn relative_radius(&self) -> f64 {
        1.0 / (1.0 / self.upper.radius + 1.0 / self.lower.radius)
    }

    /// Hertz's `(a, p0)` for `P` per unit length (the whole contact).
    pub fn hertz(&self, p: f64) -> (f64, f64) {
        let a = (4.0 * p * self.relative_radius() / (std::f64::consts::PI * self.e_star())).sqrt();
        (a, 2.0 * p / (std::f64::consts::PI * a))
    }

    /// Grid lines over `[0, end]`: the fine zone, then geometric growth
    /// (`hertz_scene::graded_lines`).
    fn lines(&self, cells: usize, end: f64) -> Vec<f64> {
        graded_lines(self.fine_extent, cells, self.growth, end)
    }

    /// One body above its arc (`hertz_scene::arc_mesh`), over `[−L, L]` or `[0, L]`.
    fn body_mesh(&self, body: &Body) -> Mesh {
        let half = self.lines(body.fine_cells, self.width);
        let xs: Vec<f64> = if self.half {
            half
        } else {
            half.iter()
                .rev()
                .map(|x| -x)
                .chain(half[1..].iter().copied())
                .collect()
        };
        let ys = self.lines(body.fine_cells, self.height);
        arc_mesh(self.kind, &xs, &ys, body.radius, self.height)
    }

    /// The mirror image `y → −y` of `mesh` (elements reordered to stay counter-clockwise,
    /// sets `top` and `bottom` swapped), so that two identical bodies are exact mirror images
    /// down to the diagonals of their triangles (β = 0 holds for the discrete problem too).
    fn mirrored(mesh: &Mesh, region: u32) -> Mesh {
        let nodes = mesh.nodes().iter().map(|&[x, y]| [x, -y]).collect();
        let npe = mesh.kind().node_count();
        let order: &[usize] = if npe == 3 {
            &[0, 2, 1]
        } else {
            &[0, 2, 1, 5, 4, 3]
        };
        let conn = mesh
            .connectivity()
            .chunks(npe)
            .flat_map(|e| order.iter().map(move |&k| e[k]))
            .collect();
        let regions = vec![region; mesh.element_count()];
        let mut out = Mesh::new(nodes, mesh.kind(), conn, regions).unwrap();
        let rename = |name: &str| match name {
            "top" => "bottom".to_string(),
            "bottom" => "top".to_string(),
            other => other.to_string(),
        };
        for name in mesh.node_set_names() {
            out.add_node_set(&rename(name), mesh.node_set(name).unwrap().to_vec())
                .unwrap();
        }
        for name in mesh.edge_set_names() {
            // side s joins local corners (s, s + 1); with corners 1 and 2 swapped it is 2 − s
            let sides = mesh
                .edge_set(name)
                .unwrap()
                .iter()
                .map(|s| fem_core::Side {
                    element: s.element,
                    side: 2 - s.side,
                })
                .collect();
            out.add_edge_set(&rename(name), sides).unwrap();
        }
        out
    }

    /// The joined mesh: the upper body (region 0, sets `up.*`) then the lower (region 1,
    /// sets `low.*`), the lower one built as the upper is and mirrored.
    pub fn mesh(&self) -> Mesh {
        let up = self.body_mesh(&self.upper);
        let low = Self::mirrored(&self.body_mesh(&self.lower), 1);
        Mesh::join(&[("up.", &up), ("low.", &low)]).unwrap()
    }

    /// The nodes of a set sorted by `x`.
    pub fn sorted(mesh: &Mesh, set: &str) -> Vec<usize> {
        let mut nodes = mesh.node_set(set).unwrap().to_vec();
        nodes.sort_by(|&a, &b| mesh.nodes()[a][0].total_cmp(&mesh.nodes()[b][0]));
        nodes
    }

    /// The simulation, pressed by nothing yet: the upper body's top is a cap tied along `y`
    /// (and `x` for the full model) that floats; [`Self::load`] sets its force.
    pub fn simulation(
        &self,
        law: StandardLaw,
        settings: SimulationSettings,
    ) -> ContactSimulation<LinearElasticModel, StandardLaw> {
        let mesh = self.mesh();
        let cap = mesh.node_set("up.top").unwrap().to_vec();
        let base = mesh.node_set("low.bottom").unwrap().to_vec();
        let mut supports = Supports::new();
        supports.fix(&base, Component::X).fix(&base, Component::Y);
        supports.tie(&cap, Component::Y).unwrap();
        if self.half {
            for set in ["up.left", "low.left"] {
                supports.fix(mesh.node_set(set).unwrap(), Component::X);
            }
        } else {
            supports.tie(&cap, Component::X).unwrap();
        }
        let mat = |b: &Body| Material::new(b.young, b.poisson, 0.0).unwrap();
        let model = LinearElasticModel::floating(
            mesh,
            Idealization::PlaneStrain,
            &[(0, mat(&self.upper)), (1, mat(&self.lower))],
            supports,
        )
        .unwrap();
        let contactor = Self::sorted(model.mesh(), "up.bottom");
        let surface = Self::sorted(model.mesh(), "low.top");
        let zone = match self.pairing {
            Pairing::NodePairs => {
                assert_eq!(contactor.len(), surface.len(), "matching meshes");
                ContactZone::node_pairs(
                    "interface",
                    contactor,
                    surface,
                    Some([0.0, 1.0]),
                    law,
                    self.alert,
                )
            }
            Pairing::Segments => {
                ContactZone::node_to_segment("interface", contactor, surface, law, self.alert)
            }
        };
        ContactSimulation::new(model, vec![zone], settings).unwrap()
    }

    /// Sets the cap's force to `(q, −p)` per unit length (`p` over the half model is halved).
    pub fn load(
        sim: &mut ContactSimulation<LinearElasticModel, StandardLaw>,
        half: bool,
        q: f64,
        p: f64,
    ) {
        let model = sim.structure_mut();
        let cap = model.mesh().node_set("up.top").unwrap()[0];
        model.clear_loads();
        let share = if half { 0.5 } else { 1.0 };
        model.add_nodal_force(cap, [q, -p * share]).unwrap();
    }

    /// The cap's displacement `[u_x, u_y]`.
    pub fn cap_displacement(sim: &ContactSimulation<LinearElasticModel, StandardLaw>) -> [f64; 2] {
        let cap = sim.structure().mesh().node_set("up.top").unwrap()[0];
        sim.nodal_displacements()[cap]
    }

    /// `P`, `a`, `p0` and the stick half-width `c` (for friction coefficient `mu`) of a step.
    pub fn measure(
        &self,
        sim: &ContactSimulation<LinearElasticModel, StandardLaw>,
        res: &StepResult,
        mu: f64,
    ) -> Measured {
        let mesh = sim.structure().mesh();
        // the reactions in the global frame (a segment's normal tilts with the arc)
        let global: Vec<(f64, [f64; 2])> = res
            .contacts
            .iter()
            .map(|c| {
                let k = sim
                    .candidates()
                    .iter()
                    .find(|k| k.node == c.node && k.zone == c.zone)
                    .unwrap();
                let (n, t) = (k.normal(), k.tangent());
                let f = [
                    c.r.n * n[0] + c.r.t[0] * t[0],
                    c.r.n * n[1] + c.r.t[0] * t[1],
                ];
                (c.position[0], f)
            })
            .collect();
        let (mut s0, mut s2, mut t0) = (0.0, 0.0, 0.0);
        let mut normal = vec![0.0; mesh.node_count()];
        let mut tangential = vec![0.0; mesh.node_count()];
        for (c, &(x, f)) in res.contacts.iter().zip(&global) {
            s0 += f[1];
            s2 += f[1] * x * x;
            t0 += f[0];
            normal[c.node] = f[1];
            tangential[c.node] = f[0];
        }
        let sign = if t0 < 0.0 { -1.0 } else { 1.0 };
        let (mut d0, mut d2) = (0.0, 0.0);
        for &(x, f) in &global {
            let d = mu * f[1] - sign * f[0];
            d0 += d;
            d2 += d * x * x;
        }
        let p_total = if self.half { 2.0 * s0 } else { s0 };
        // p0 from the mean pressure over |x| < x_w, x_w the corner of the upper mesh nearest
        // a/2: the nodal forces inside, half the force at ±x_w, over Hertz's shape there
        let a_fe = (4.0 * s2 / s0).sqrt();
        let x_w = self
            .lines(self.upper.fine_cells, self.width)
            .into_iter()
            .min_by(|u, v| (u - a_fe / 2.0).abs().total_cmp(&(v - a_fe / 2.0).abs()))
            .unwrap();
        let tol = 1e-9 * x_w;
        let window: f64 = global
            .iter()
            .map(|&(x, f)| {
                if x.abs() < x_w - tol {
                    f[1]
                } else if x.abs() <= x_w + tol {
                    0.5 * f[1]
                } else {
                    0.0
                }
            })
            .sum();
        let sw = (x_w / a_fe).min(1.0);
        let shape = 0.5 * a_fe * (sw * (1.0 - sw * sw).sqrt() + sw.asin());
        let p0_window = window / if self.half { shape } else { 2.0 * shape };
        let p = project(mesh, "up.bottom", &normal);
        let origin = p
            .iter()
            .min_by(|a, b| a.0.abs().total_cmp(&b.0.abs()))
            .unwrap()
            .1;
        Measured {
            p_total,
            q_total: t0,
            a: a_fe,
            p0: p0_window,
            p0_projected: origin,
            c: if d0 > 0.0 {
                (4.0 * d2 / d0).max(0.0).sqrt()
            } else {
                0.0
            },
            pressure: p,
            traction: project(mesh, "up.bottom", &tangential),
        }
    }
}

/// What [`Cylinders::measure`] finds.
#[derive(Clone, Debug)]
pub struct Measured {
    /// Total normal load from the reactions (per unit length, the whole contact).
    pub p_total: f64,
    /// Total tangential reaction on the upper body (the model's side).
    pub q_total: f64,
    /// Half-width from the second moment of the normal reactions.
    pub a: f64,
    /// Peak pressure from the mean pressure over `|x| < x_w ≈ a/2` (`x_w` a corner of the
    /// upper mesh): the nodal forces inside, half of those at `±x_w`, divided by
    /// `∫ √(1 − x²/a²) dx` over the window (with the measured `a`). Unlike a pointwise
    /// value it does not see the node-to-node oscillation of the nodal forces (a few % with
    /// P1 or non-matching meshes).
    pub p0: f64,
    /// Pressure at `x = 0` from the L2 projection of the nodal forces (pointwise: it sees
    /// that oscillation).
    pub p0_projected: f64,
    /// Stick half-width from the second moment of the stick deficit.
    pub c: f64,
    /// `(x, p)` at the edge's nodes (L2 projection of the normal reactions).
    pub pressure: Vec<(f64, f64)>,
    /// `(x, q)` at the edge's nodes (L2 projection of the tangential reactions).
    pub traction: Vec<(f64, f64)>,
}

/// The L2 projection of nodal forces on the edge set `set` (`hertz_scene::project_on_edge`,
/// plane): `(x, v)` at every node of the edge, in `x` order.
pub fn project(mesh: &Mesh, set: &str, force: &[f64]) -> Vec<(f64, f64)> {
    project_on_edge(mesh, set, force, false)
}

/// For every node of the edge set `set`: `(node, x, ∫ g N_i dx, ∫ N_i dx)` with the edge's
/// shape functions in the abscissa, by composite Gauss quadrature (8 sub-intervals of 4 points
/// per side, for a `g` with kinks such as Mindlin's traction). `∫ g N_i / ∫ N_i` is the nodal
/// value that a traction `g` gives when lumped the way the nodal forces are.
pub fn consistent(mesh: &Mesh, set: &str, g: impl Fn(f64) -> f64) -> Vec<(usize, f64, f64, f64)> {
    let sides = mesh.edge_set(set).unwrap();
    let mut acc: std::collections::BTreeMap<usize, (f64, f64)> = std::collections::BTreeMap::new();
    let sub = 8;
    for &side in sides {
        let local: Vec<usize> = mesh.side_nodes(side).collect();
        let (xa, xb) = (mesh.nodes()[local[0]][0], mesh.nodes()[local[1]][0]);
        for k in 0..sub {
            for (t, w) in GAUSS4 {
                let s = (k as f64 + t) / sub as f64;
                let shape = edge_shapes(local.len(), s);
                let x = xa + s * (xb - xa);
                let weight = w * (xb - xa).abs() / sub as f64;
                let gx = g(x);
                for (i, &n) in local.iter().enumerate() {
                    let e = acc.entry(n).or_insert((0.0, 0.0));
                    e.0 += weight * gx * shape[i];
                    e.1 += weight * shape[i];
                }
            }
        }
    }
    acc.into_iter()
        .map(|(n, (gn, w))| (n, mesh.nodes()[n][0], gn, w))
        .collect()
}
