//! The seed's pile pull-out (chapter 6, Plancoët; `bipo::presets::pile` builds the elastic
//! scene) with a soil that may yield, through the library: fem-core's pile-in-soil mesh
//! (axisymmetric P2, the tip detached as the preset does), a [`PlasticModel`] whose soil is
//! linear elastic or Drucker–Prager and whose pile is linear elastic, the RCCM shaft of table
//! 6.3 (Coulomb at the tip corner, frictionless at the tip), and the global Newton around
//! contact. Used by `tests/integration/issue_40_pile_plastic.rs` and
//! `examples/pile_plastic.rs`.
//!
//! Phases: geostatic (self-weight and the K0 stress of seed eq. 6.1 in the soil, the pile
//! unstressed, head held at `u_z = 0`), then the head lifted by `v₀` in `steps` increments.
//! No installation phase (the preset's imposed radial displacement is an elastic
//! calibration; here the shaft carries the geostatic K0 pressure). Units kN, m, kPa; forces
//! of the model per radian, head loads full ring (`2π`).

#![allow(dead_code)] // each user (test, example) reads part of it

use contact_solver::contact_laws::{BetaScheme, Rccm, RccmParams};
use contact_solver::coupling::zone::PairNormals;
use contact_solver::{
    ContactSimulation, ContactZone, NewtonSettings, SimulationSettings, StepResult,
};
use fem_core::generate::{PILE, PileSpec, SOIL, pile_in_soil};
use fem_core::plastic::{
    ConeMatch, ConstitutivePoint, DruckerPrager, DruckerPragerParameters, LinearElasticPoint,
    PlasticModel,
};
use fem_core::{Component, FemError, Idealization, LinearElasticModel, Material, Mesh, Supports};
use std::collections::HashMap;
use std::error::Error;
use std::f64::consts::PI;
use std::sync::Arc;

/// Soil `E` (kPa), `ν`, `γ` (kN/m³) and `K0` (seed ch. 6).
pub const SOIL_YOUNG: f64 = 3e4;
/// Soil Poisson's ratio.
pub const SOIL_POISSON: f64 = 0.33;
/// Soil unit weight.
pub const SOIL_WEIGHT: f64 = 20.0;
/// Coefficient of earth pressure at rest.
pub const K0: f64 = 0.43;
/// Pile `E` (Plancoët, kPa), `ν`, `γ`.
pub const PILE_YOUNG: f64 = 3e7;
/// Pile Poisson's ratio.
pub const PILE_POISSON: f64 = 0.3;
/// Pile unit weight (steel, as the seed's solid cylinder).
pub const PILE_WEIGHT: f64 = 78.0;

/// The soil's law.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Soil {
    /// Linear elastic (the preset's soil).
    Elastic,
    /// Drucker–Prager matched to Mohr–Coulomb in plane strain (the seed's `k_d`): friction
    /// and dilatancy angles in degrees, cohesion in kPa.
    DruckerPrager {
        /// φ (°).
        friction: f64,
        /// θ (°), `≤ φ`.
        dilatancy: f64,
        /// c (kPa).
        cohesion: f64,
    },
}

impl Soil {
    /// The seed's sand: φ = 35°, associated (θ = φ), c = 1 kPa (a little cohesion keeps the
    /// surface points off the apex). A realistic dilatancy (θ = 5°) makes the global Newton
    /// cycle between two iterates (relative residuals 1e-8 to 1e-6, the whole step and every
    /// cut of it): the non-associated Newton's stabilisation is not in yet.
    pub const SAND: Soil = Soil::DruckerPrager {
        friction: 35.0,
        dilatancy: 35.0,
        cohesion: 1.0,
    };

    fn point(self) -> Result<Arc<dyn ConstitutivePoint>, FemError> {
        Ok(match self {
            Soil::Elastic => Arc::new(LinearElasticPoint::new(SOIL_YOUNG, SOIL_POISSON)?),
            Soil::DruckerPrager {
                friction,
                dilatancy,
                cohesion,
            } => Arc::new(DruckerPrager::new(DruckerPragerParameters {
                young: SOIL_YOUNG,
                poisson: SOIL_POISSON,
                friction_angle: friction,
                dilatancy_angle: dilatancy,
                cohesion,
                cone: ConeMatch::PlaneStrain,
            })?),
        })
    }
}

/// What a pull-out is built from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PileCase {
    /// The soil.
    pub soil: Soil,
    /// Shaft cells (32: the seed's 65 pairs), soil cells outward, cells below the tip.
    pub cells: [usize; 3],
    /// Head displacement `v₀` (m).
    pub head_displacement: f64,
    /// Increments.
    pub steps: usize,
    /// The Newton's settings.
    pub newton: NewtonSettings,
}

impl PileCase {
    /// Plancoët on the seed's mesh, 15 mm in 50 increments.
    pub fn plancoet(soil: Soil) -> Self {
        Self {
            soil,
            cells: [32, 20, 16],
            head_displacement: 0.015,
            steps: 50,
            newton: NewtonSettings::default(),
        }
    }

    /// The coarse mesh of `BIPO_QUICK` (8 shaft cells).
    pub fn coarse(mut self) -> Self {
        self.cells = [8, 6, 4];
        self
    }
}

/// The built pull-out.
pub struct Pile {
    /// The simulation.
    pub sim: ContactSimulation<PlasticModel<2>, Rccm, 2>,
    /// The `pile_head` nodes, sorted.
    pub head: Vec<usize>,
    /// Every pile node (elements of region [`PILE`]), sorted.
    pub pile_nodes: Vec<usize>,
    /// `−f_z` of the self-weight on each head node (per radian; the weight is downwards).
    head_weight: Vec<f64>,
    /// The case.
    pub case: PileCase,
}

/// One pull-out increment's readings (full ring).
#[derive(Clone, Copy, Debug)]
pub struct Reading {
    /// Head displacement `v` (m).
    pub v: f64,
    /// Head load from the head's support reaction (kN).
    pub q_reaction: f64,
    /// Head load from the pile's equilibrium: its weight less the interface's `z` force on it
    /// (kN).
    pub q_interface: f64,
    /// Quadrature points yielding at the end of the increment.
    pub yielding: usize,
}

impl Pile {
    /// Builds the case (module docs).
    ///
    /// # Errors
    /// The mesh's, the model's (a geostatic state outside the yield surface, named), the
    /// zones'.
    pub fn build(case: PileCase) -> Result<Self, Box<dyn Error>> {
        let spec = PileSpec {
            cells_shaft: case.cells[0],
            cells_soil_r: case.cells[1],
            cells_below_tip: case.cells[2],
            ..PileSpec::default()
        };
        let radius = 0.5 * spec.diameter;
        let (mesh, tip_pile, tip_soil) = detach_tip(pile_in_soil(&spec)?, radius, spec.length)?;
        let shaft_pile = mesh.node_set("interface_pile")?.to_vec();
        let shaft_soil = mesh.node_set("interface_soil")?.to_vec();
        let head = mesh.node_set("pile_head")?.to_vec();
        let mut pile_nodes: Vec<usize> = (0..mesh.element_count())
            .filter(|&e| mesh.regions()[e] == PILE)
            .flat_map(|e| mesh.element(e).to_vec())
            .collect();
        pile_nodes.sort_unstable();
        pile_nodes.dedup();
        let mut supports = Supports::new();
        supports
            .fix(mesh.node_set("axis")?, Component::X)
            .fix(mesh.node_set("outer")?, Component::X)
            .fix(mesh.node_set("base")?, Component::Y)
            .prescribe(&head, Component::Y, 0.0)?;
        let materials = [
            (SOIL, Material::new(SOIL_YOUNG, SOIL_POISSON, SOIL_WEIGHT)?),
            (PILE, Material::new(PILE_YOUNG, PILE_POISSON, PILE_WEIGHT)?),
        ];
        let shaft_z: Vec<f64> = shaft_pile.iter().map(|&n| mesh.nodes()[n][1]).collect();
        let shaft_areas = simpson(&shaft_z, |_| radius);
        let mut tip_line: Vec<f64> = tip_pile.iter().map(|&n| mesh.nodes()[n][0]).collect();
        tip_line.push(radius);
        let mut tip_areas = simpson(&tip_line, |r| r);
        tip_areas.pop();

        let mut elastic =
            LinearElasticModel::new(mesh, Idealization::Axisymmetric, &materials, supports)?;
        elastic.add_self_weight()?;
        // −f at the head's prescribed u_z: the weight there (R = K u − f at u = 0)
        let zero = vec![[0.0; 2]; elastic.mesh().node_count()];
        let reactions = elastic.reactions(&zero, 1.0)?;
        let head_weight = head
            .iter()
            .map(|&n| {
                reactions
                    .iter()
                    .find(|((m, c), _)| *m == n && *c == Component::Y)
                    .map_or(0.0, |(_, r)| *r)
            })
            .collect();
        let laws = [
            (SOIL, case.soil.point()?),
            (
                PILE,
                Arc::new(LinearElasticPoint::new(PILE_YOUNG, PILE_POISSON)?) as Arc<_>,
            ),
        ];
        let mut body = PlasticModel::new(elastic, &laws)?;
        body.set_geostatic(0.0, &[(SOIL, K0)])?;

        // table 6.3, Plancoët
        let shaft_law = RccmParams {
            c_n: 10500.0,
            c_t: 10500.0,
            w: 3e-3,
            alpha: 0.0,
            mu: 0.46,
            m: 1,
            beta_0: 1.0,
            scheme: BetaScheme::ImplicitEuler,
        };
        let corner = RccmParams {
            beta_0: 0.0,
            ..shaft_law
        };
        let tip = RccmParams {
            mu: 0.0,
            beta_0: 0.0,
            ..shaft_law
        };
        let alert = 1e-3;
        let zones = vec![
            ContactZone::node_pairs(
                "shaft",
                shaft_pile[1..].to_vec(),
                shaft_soil[1..].to_vec(),
                PairNormals::Fixed([-1.0, 0.0]),
                Rccm::new(shaft_law)?,
                alert,
            )
            .with_areas(shaft_areas[1..].to_vec()),
            ContactZone::node_pairs(
                "tip_corner",
                vec![shaft_pile[0]],
                vec![shaft_soil[0]],
                PairNormals::Fixed([-1.0, 0.0]),
                Rccm::new(corner)?,
                alert,
            )
            .with_areas(vec![shaft_areas[0]]),
            ContactZone::node_pairs(
                "tip",
                tip_pile,
                tip_soil,
                PairNormals::Fixed([0.0, 1.0]),
                Rccm::new(tip)?,
                alert,
            )
            .with_areas(tip_areas),
        ];
        let sim = ContactSimulation::new(body, zones, SimulationSettings::default())?
            .with_newton(case.newton)?;
        Ok(Self {
            sim,
            head,
            pile_nodes,
            head_weight,
            case,
        })
    }

    /// The geostatic step (phase 1).
    ///
    /// # Errors
    /// The step's.
    pub fn geostatic(&mut self) -> Result<(StepResult<2>, Reading), Box<dyn Error>> {
        let res = self.sim.step(1.0, 1.0)?;
        let reading = self.reading(&res, 0.0)?;
        Ok((res, reading))
    }

    /// Increment `k` (1-based) of the pull-out.
    ///
    /// # Errors
    /// The step's.
    pub fn pull(&mut self, k: usize) -> Result<(StepResult<2>, Reading), Box<dyn Error>> {
        let v = self.case.head_displacement * k as f64 / self.case.steps as f64;
        self.sim
            .structure_mut()
            .set_prescribed(&self.head, Component::Y, v)?;
        let res = self.sim.step(1.0 + k as f64, 1.0)?;
        let reading = self.reading(&res, v)?;
        Ok((res, reading))
    }

    /// The head load two ways (full ring): the head's support reaction, `Σ_head (Bᵀσ − f_w −
    /// f_c)_z`, and the pile's equilibrium, `W_p − Σ f_c,z` over the pile's contact forces.
    fn reading(&self, res: &StepResult<2>, v: f64) -> Result<Reading, Box<dyn Error>> {
        let body = self.sim.structure();
        let mut q_reaction = body.reaction(&self.head, Component::Y)?;
        q_reaction += self.head_weight.iter().sum::<f64>();
        let mut contact_on_pile = 0.0;
        for (c, rec) in self.sim.candidates().iter().zip(&res.contacts) {
            // global force on the contactor (the pile node), −w times it on each target
            let f_z = rec.force()[1];
            if self.head.binary_search(&c.node).is_ok() {
                q_reaction -= f_z;
            }
            if self.pile_nodes.binary_search(&c.node).is_ok() {
                contact_on_pile += f_z;
            }
            for &(t, w) in c.targets.iter().flatten() {
                if self.head.binary_search(&t).is_ok() {
                    q_reaction += w * f_z;
                }
            }
        }
        let spec = PileSpec::default();
        let r = 0.5 * spec.diameter;
        // per radian: γ_p ∫ r dr dz = γ_p R² L / 2
        let weight = PILE_WEIGHT * r * r * spec.length / 2.0;
        let yielding = body
            .committed_states()
            .iter()
            .filter(|s| s.yielding)
            .count();
        Ok(Reading {
            v,
            q_reaction: 2.0 * PI * q_reaction,
            q_interface: 2.0 * PI * (weight - contact_on_pile),
            yielding,
        })
    }
}

/// Consistent nodal weights `∫ N_i w ds` of a line of P2 nodes at increasing `s` (Simpson,
/// exact for a linear weight `w`).
fn simpson(s: &[f64], weight: impl Fn(f64) -> f64) -> Vec<f64> {
    let mut a = vec![0.0; s.len()];
    for k in (0..s.len() - 1).step_by(2) {
        let h = s[k + 2] - s[k];
        a[k] += h / 6.0 * weight(s[k]);
        a[k + 1] += 4.0 * h / 6.0 * weight(s[k + 1]);
        a[k + 2] += h / 6.0 * weight(s[k + 2]);
    }
    a
}

/// The preset's `detach_tip` (bipo `presets::pile::meridian`): the pile's tip nodes at
/// `r < R` duplicated so the tip can lift off; returns the mesh and the paired tip nodes (pile
/// copies, soil originals), sorted by `r`; the pile copy of the axis node joins `"axis"`.
fn detach_tip(
    mesh: Mesh,
    radius: f64,
    length: f64,
) -> Result<(Mesh, Vec<usize>, Vec<usize>), FemError> {
    let tol = 1e-9 * radius.max(length);
    let npe = mesh.kind().node_count();
    let in_pile = |n: usize| {
        (0..mesh.element_count()).any(|e| mesh.regions()[e] == PILE && mesh.element(e).contains(&n))
    };
    let mut on_tip: Vec<usize> = (0..mesh.node_count())
        .filter(|&n| {
            let p = mesh.nodes()[n];
            (p[1] + length).abs() <= tol && p[0] < radius - tol && in_pile(n)
        })
        .collect();
    on_tip.sort_by(|a, b| mesh.nodes()[*a][0].total_cmp(&mesh.nodes()[*b][0]));
    let mut nodes = mesh.nodes().to_vec();
    let mut copy = HashMap::new();
    for &n in &on_tip {
        copy.insert(n, nodes.len());
        nodes.push(nodes[n]);
    }
    let mut connectivity = mesh.connectivity().to_vec();
    for (cell, &region) in connectivity.chunks_exact_mut(npe).zip(mesh.regions()) {
        if region == PILE {
            for node in cell.iter_mut() {
                if let Some(&c) = copy.get(node) {
                    *node = c;
                }
            }
        }
    }
    let mut out = Mesh::new(nodes, mesh.kind(), connectivity, mesh.regions().to_vec())?;
    for name in mesh.edge_set_names() {
        out.add_edge_set(name, mesh.edge_set(name)?.to_vec())?;
    }
    for name in mesh.node_set_names() {
        let mut set = mesh.node_set(name)?.to_vec();
        if name == "axis" {
            let extra: Vec<usize> = set.iter().filter_map(|n| copy.get(n)).copied().collect();
            set.extend(extra);
        }
        out.add_node_set(name, set)?;
    }
    let tip_pile = on_tip.iter().map(|n| copy[n]).collect();
    Ok((out, tip_pile, on_tip))
}
