//! The pull-out test in 3D: the axisymmetric scene's meridian mesh (tip detached) revolved into
//! a quarter ([`fem_core::solid::revolve`], `sectors` sectors of `90° / sectors`), with the
//! same materials, phases and interface, so that the 3D head load–displacement curve can be
//! compared with the axisymmetric one ([`PulloutSpec::build_3d`]).
//!
//! The 3D scene mirrors the axisymmetric one piece by piece:
//! - **Supports.** The axis and the outer side `u_x = u_y = 0` (the axisymmetric `u_r = 0`,
//!   and `u_θ = 0`, which holds by symmetry), the base `u_z = 0`, the symmetry planes `θ = 0`
//!   (`u_y = 0`) and `θ = 90°` (`u_x = 0`), the head's `u_z` prescribed.
//! - **Loads.** Self-weight; the initial stress of phase 1 in Cartesian components
//!   (`σ_xx = σ_yy = σ_rr = σ_θθ`, no shear).
//! - **Interface.** Every axisymmetric pair is copied at each node layer of the sector, with
//!   its normal turned to the layer's angle (`−e_r` on the shaft, `+e_z` at the tip); the tip
//!   pair on the axis is one pair. The tributary areas are the consistent `∫ N_i dA` of the
//!   pile's shaft faces and of its tip faces (the tip corner keeps its shaft area only, as in
//!   2D).
//! - **Installation.** The radial displacement `δ` of the soil's interface nodes, solved on the
//!   soil alone in 3D; its reactions, scaled to `δ`, are added as nodal forces (the
//!   axisymmetric scene's method). `δ` is calibrated as in 2D, or given
//!   ([`Installation::RadialDisplacement`]) to run both models with the same `δ`.
//! - **Head load.** `Q = 4 Σ R_z` over the head nodes (quarter to full ring), the contact
//!   forces on the head's prescribed `u_z` taken out as in 2D.

use super::{Installation, PulloutSpec, detach_tip};
use contact_laws::Rccm;
use contact_solver::coupling::solid::{
    ContactZone3, PairNormals3, SolidContactSimulation, SolidStepResult,
};
use contact_solver::{SimulationSettings, SolverError};
use fem_core::generate::{PILE, SOIL, pile_in_soil};
use fem_core::solid::{Face, SolidMesh, SolidModel, Stress3, StressField3, revolve};
use fem_core::{Component, Material, Supports};
use std::collections::HashMap;
use std::f64::consts::FRAC_PI_2;
use std::sync::Arc;

/// Where a [`SolidPulloutScene`] is in the seed's sequence.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Phase {
    Start,
    Geostatic,
    Installed,
}

/// One pull-out increment of the 3D scene.
#[derive(Clone, Debug)]
pub struct SolidPulloutStep {
    /// Increment `k` (1-based).
    pub increment: usize,
    /// Head displacement `v` (m, upwards).
    pub head_displacement: f64,
    /// Head load `Q` (kN, full ring, upwards).
    pub head_load: f64,
    /// The step.
    pub result: SolidStepResult,
}

/// The pull-out test on a 3D quarter (module docs).
pub struct SolidPulloutScene {
    /// The simulation.
    pub simulation: SolidContactSimulation<SolidModel, Rccm>,
    /// The spec it was built from.
    pub spec: PulloutSpec,
    /// Sectors of the quarter.
    pub sectors: usize,
    /// The head nodes (sorted; their `u_z` is the head displacement).
    pub head: Vec<usize>,
    /// Candidate indices of the shaft pairs (the tip corner's included).
    pub shaft_candidates: Vec<usize>,
    /// Candidate indices of the tip pairs.
    pub tip_candidates: Vec<usize>,
    /// Installation nodal forces `(soil node, force)` added in phase 2.
    pub installation_forces: Vec<(usize, [f64; 3])>,
    /// The installation displacement `δ` used (m).
    pub installation_displacement: f64,
    phase: Phase,
}

/// The supports of the quarter: axis and outer side `u_x = u_y = 0`, base `u_z = 0`, the
/// symmetry planes, the head's `u_z = 0`; with `radial = Some((nodes, δ))`, those nodes get
/// `u = δ e_r` instead of their symmetry-plane support.
fn quarter_supports(
    mesh: &SolidMesh,
    radial: Option<(&[usize], f64)>,
) -> Result<Supports, SolverError> {
    let mut s = Supports::new();
    let set = |name: &str| mesh.node_set(name).map(<[usize]>::to_vec);
    let moved: Vec<usize> = radial.map(|(n, _)| n.to_vec()).unwrap_or_default();
    let keep = |v: Vec<usize>| -> Vec<usize> {
        v.into_iter()
            .filter(|n| moved.binary_search(n).is_err())
            .collect()
    };
    for name in ["axis", "outer"] {
        s.fix(&set(name)?, Component::X)
            .fix(&set(name)?, Component::Y);
    }
    s.fix(&set("base")?, Component::Z)
        .fix(&keep(set("theta0")?), Component::Y)
        .fix(&keep(set("theta1")?), Component::X)
        .fix(&set("pile_head")?, Component::Z);
    if let Some((nodes, delta)) = radial {
        for &n in nodes {
            let x = mesh.nodes()[n];
            let t = x[1].atan2(x[0]);
            s.prescribe(&[n], Component::X, delta * t.cos())?
                .prescribe(&[n], Component::Y, delta * t.sin())?;
        }
    }
    Ok(s)
}

impl PulloutSpec {
    /// The 3D scene on a quarter of `sectors` sectors (module docs of `presets::pile::solid`),
    /// with the contact solver's `settings`.
    ///
    /// # Errors
    /// As [`PulloutSpec::build`]; [`SolverError::Unsupported`] for force control (a floating
    /// pile is not supported in 3D); [`SolverError::InvalidSetting`] for zero sectors.
    pub fn build_3d(
        &self,
        sectors: usize,
        settings: SimulationSettings,
    ) -> Result<SolidPulloutScene, SolverError> {
        self.check()?;
        if self.head_force.is_some() {
            return Err(SolverError::Unsupported(
                "force control of the pile head in 3D (a floating pile)".into(),
            ));
        }
        if sectors == 0 {
            return Err(SolverError::InvalidSetting {
                what: "sectors",
                value: 0.0,
                expected: "at least one sector",
            });
        }
        let (radius, length) = (self.radius(), self.mesh.length);
        let (meridian, tip_pile, tip_soil) = detach_tip(pile_in_soil(&self.mesh)?, radius, length)?;
        let shaft_pile = meridian.node_set("interface_pile")?.to_vec();
        let shaft_soil = meridian.node_set("interface_soil")?.to_vec();
        let rev = revolve(&meridian, FRAC_PI_2, sectors)?;
        let mut mesh = rev.mesh;
        let layers = &rev.layers;
        // the pile's tip faces: boundary faces whose corners are pile tip nodes or the corner
        let mut on_tip = vec![false; mesh.node_count()];
        for &n in tip_pile.iter().chain(std::iter::once(&shaft_pile[0])) {
            for &m in &layers[n] {
                on_tip[m] = true;
            }
        }
        let tip_faces: Vec<Face> = mesh
            .boundary_facets()
            .into_iter()
            .filter(|f| mesh.face_node_ids(*f).all(|n| on_tip[n]))
            .collect();
        mesh.add_face_set("tip_pile", tip_faces)?;
        let areas = |mesh: &SolidMesh, set: &str| -> Result<HashMap<usize, f64>, SolverError> {
            let (nodes, a) = mesh.nodal_areas(set)?;
            Ok(nodes.into_iter().zip(a).collect())
        };
        let shaft_area = areas(&mesh, "interface_pile")?;
        let tip_area = areas(&mesh, "tip_pile")?;
        let head = mesh.node_set("pile_head")?.to_vec();

        let supports = quarter_supports(&mesh, None)?;
        let materials = [
            (
                SOIL,
                Material::new(self.soil_young, self.soil_poisson, self.soil_unit_weight)?,
            ),
            (
                PILE,
                Material::new(self.pile_young, self.pile_poisson, self.pile_unit_weight)?,
            ),
        ];
        // the installation's unit solve: the soil alone, its interface moved by δ₁ e_r
        let mut soil_interface: Vec<usize> = shaft_soil
            .iter()
            .flat_map(|&n| layers[n].iter().copied())
            .collect();
        soil_interface.sort_unstable();
        soil_interface.dedup();
        let unit_delta = 1e-3;
        let unit = SolidModel::new(
            mesh.clone(),
            &materials,
            quarter_supports(&mesh, Some((&soil_interface, unit_delta)))?,
        )?;
        let reactions = unit.reactions(&unit.solve(1.0)?, 1.0)?;
        let mut unit_force: HashMap<usize, [f64; 3]> = HashMap::new();
        for ((n, c), r) in reactions {
            if soil_interface.binary_search(&n).is_ok() && c != Component::Z {
                unit_force.entry(n).or_insert([0.0; 3])[c as usize] = r / unit_delta;
            }
        }

        let mut model = SolidModel::new(mesh, &materials, supports)?;
        model.add_self_weight()?;
        // phase 1's initial stress (module docs of `presets::pile`), by region: a position
        // test would put quadrature points of curved soil elements inside the pile
        let (gamma_s, gamma_p, k0) = (self.soil_unit_weight, self.pile_unit_weight, self.k0);
        let soil: StressField3 = Arc::new(move |x: [f64; 3]| -> Stress3 {
            let z = x[2].min(0.0);
            let s = k0 * gamma_s * z;
            [s, s, gamma_s * z, 0.0, 0.0, 0.0]
        });
        let pile: StressField3 = Arc::new(move |x: [f64; 3]| -> Stress3 {
            let z = x[2].min(0.0);
            let s = k0 * gamma_s * z;
            [
                s,
                s,
                -gamma_s * length + gamma_p * (z + length),
                0.0,
                0.0,
                0.0,
            ]
        });
        model.set_initial_stress_by_region(&[(SOIL, soil), (PILE, pile)])?;

        // zones: shaft pairs above the corner, the corner, the tip (one pair on the axis)
        let pairs = |pile: &[usize], soil: &[usize]| {
            let mut c = Vec::new();
            let mut t = Vec::new();
            let mut angle = Vec::new();
            let mut seen = std::collections::HashSet::new();
            for (&p, &s) in pile.iter().zip(soil) {
                for ((&cp, &ts), &a) in layers[p].iter().zip(&layers[s]).zip(&rev.angles) {
                    // a node on the axis is the same at every layer: one pair
                    if seen.insert(cp) {
                        c.push(cp);
                        t.push(ts);
                        angle.push(a);
                    }
                }
            }
            (c, t, angle)
        };
        let radial_zone = |name: &str, pile: &[usize], soil: &[usize], law: Rccm| {
            let (c, t, angle) = pairs(pile, soil);
            let normals = angle.iter().map(|a| [-a.cos(), -a.sin(), 0.0]).collect();
            let a = c.iter().map(|n| shaft_area[n]).collect();
            ContactZone3::node_pairs(
                name,
                c,
                t,
                PairNormals3::PerPair(normals),
                law,
                self.alert_distance,
            )
            .with_areas(a)
        };
        let (shaft_law, corner_law, tip_law) = self.zone_laws()?;
        let shaft = radial_zone("shaft", &shaft_pile[1..], &shaft_soil[1..], shaft_law);
        let corner = radial_zone("tip_corner", &shaft_pile[..1], &shaft_soil[..1], corner_law);
        let (c, t, _) = pairs(&tip_pile, &tip_soil);
        let a = c
            .iter()
            .map(|n| tip_area.get(n).copied().unwrap_or(0.0))
            .collect();
        let tip = ContactZone3::node_pairs(
            "tip",
            c,
            t,
            PairNormals3::Fixed([0.0, 0.0, 1.0]),
            tip_law,
            self.alert_distance,
        )
        .with_areas(a);
        let (n_shaft, n_corner, n_tip) = (
            shaft.contactor.len(),
            corner.contactor.len(),
            tip.contactor.len(),
        );

        // δ for the requested installation (quarter sums on both sides)
        let geostatic_normal: f64 = shaft
            .contactor
            .iter()
            .chain(&corner.contactor)
            .map(|n| {
                let z = model.mesh().nodes()[*n][2];
                self.k0 * self.soil_unit_weight * (-z).max(0.0) * shaft_area[n]
            })
            .sum();
        let unit_normal: f64 = unit_force
            .iter()
            .map(|(n, f)| {
                let x = model.mesh().nodes()[*n];
                let r = x[0].hypot(x[1]);
                (f[0] * x[0] + f[1] * x[1]) / r
            })
            .sum();
        if !(unit_normal > 0.0 && unit_normal.is_finite()) {
            return Err(SolverError::InvalidGeometry(format!(
                "the installation's unit radial displacement gives a shaft normal force of \
                 {unit_normal}, not a compression"
            )));
        }
        let delta = match self.installation {
            Installation::None => 0.0,
            Installation::RadialDisplacement(d) => d,
            Installation::NormalForceRatio(k) => (k - 1.0) * geostatic_normal / unit_normal,
        };
        let mut installation_forces: Vec<(usize, [f64; 3])> = unit_force
            .into_iter()
            .map(|(n, f)| (n, f.map(|v| -v * delta)))
            .collect();
        installation_forces.sort_unstable_by_key(|(n, _)| *n);
        let simulation = SolidContactSimulation::new(model, vec![shaft, corner, tip], settings)?;
        Ok(SolidPulloutScene {
            simulation,
            spec: self.clone(),
            sectors,
            head,
            shaft_candidates: (0..n_shaft + n_corner).collect(),
            tip_candidates: (n_shaft + n_corner..n_shaft + n_corner + n_tip).collect(),
            installation_forces,
            installation_displacement: delta,
            phase: Phase::Start,
        })
    }
}

impl SolidPulloutScene {
    /// Phase 1: the geostatic step.
    ///
    /// # Errors
    /// As [`SolidContactSimulation::step`]; [`SolverError::InvalidSetting`] if called twice.
    pub fn geostatic(&mut self) -> Result<SolidStepResult, SolverError> {
        self.expect(Phase::Start)?;
        let res = self.simulation.step(1.0, 1.0)?;
        self.phase = Phase::Geostatic;
        Ok(res)
    }

    /// Phase 2: the installation forces, then a step (head still at `u_z = 0`).
    ///
    /// # Errors
    /// As [`SolidContactSimulation::step`]; [`SolverError::InvalidSetting`] unless phase 1 ran.
    pub fn install(&mut self) -> Result<SolidStepResult, SolverError> {
        self.expect(Phase::Geostatic)?;
        for &(node, f) in &self.installation_forces {
            self.simulation.structure_mut().add_nodal_force(node, f)?;
        }
        let res = self.simulation.step(2.0, 1.0)?;
        self.phase = Phase::Installed;
        Ok(res)
    }

    /// Phase 3, increment `k` (1-based): the head's `u_z = v₀ k / steps` (one step; call the
    /// increments in order).
    ///
    /// # Errors
    /// As [`SolidContactSimulation::step`]; [`SolverError::InvalidSetting`] unless phase 2 ran.
    pub fn pull(&mut self, k: usize) -> Result<SolidPulloutStep, SolverError> {
        self.expect(Phase::Installed)?;
        let v = self.spec.head_displacement * k as f64 / self.spec.steps as f64;
        self.simulation
            .structure_mut()
            .set_prescribed(&self.head, Component::Z, v)?;
        let result = self.simulation.step(2.0 + k as f64, 1.0)?;
        Ok(SolidPulloutStep {
            increment: k,
            head_displacement: v,
            head_load: self.head_load(&result)?,
            result,
        })
    }

    /// The three phases; returns the load–displacement curve `(v, Q)` from the installed state
    /// (`v = 0`) through every increment.
    ///
    /// # Errors
    /// As for the phases.
    pub fn run(&mut self) -> Result<Vec<(f64, f64)>, SolverError> {
        self.geostatic()?;
        let installed = self.install()?;
        let mut curve = vec![(0.0, self.head_load(&installed)?)];
        for k in 1..=self.spec.steps {
            let s = self.pull(k)?;
            curve.push((s.head_displacement, s.head_load));
        }
        Ok(curve)
    }

    /// The head load `Q` (kN, full ring, upwards) at the end of `result`, the step just solved:
    /// `4 Σ R_z` over the head nodes, less the contact forces on the head's prescribed `u_z`.
    ///
    /// # Errors
    /// [`SolverError::Structure`] if the displacements do not match the model.
    pub fn head_load(&self, result: &SolidStepResult) -> Result<f64, SolverError> {
        let model = self.simulation.structure();
        let u: Vec<[f64; 3]> = (0..model.mesh().node_count())
            .map(|n| self.simulation.nodal_displacement(n))
            .collect();
        let mut q: f64 = model
            .reactions(&u, 1.0)?
            .iter()
            .filter(|((n, c), _)| *c == Component::Z && self.head.binary_search(n).is_ok())
            .map(|(_, r)| r)
            .sum();
        for (rec, candidate) in result.contacts.iter().zip(self.simulation.candidates()) {
            let f_z = rec.force()[2];
            if self.head.binary_search(&rec.node).is_ok() {
                q -= f_z;
            }
            for &(t, w) in candidate.targets.iter().flatten() {
                if self.head.binary_search(&t).is_ok() {
                    q += w * f_z;
                }
            }
        }
        Ok(4.0 * q)
    }

    /// The shaft friction `−4 Σ r·e_z` (kN, positive when it resists the pull-out).
    pub fn shaft_friction(&self, result: &SolidStepResult) -> f64 {
        -4.0 * self
            .shaft_candidates
            .iter()
            .map(|&i| result.contacts[i].force()[2])
            .sum::<f64>()
    }

    fn expect(&self, phase: Phase) -> Result<(), SolverError> {
        if self.phase == phase {
            Ok(())
        } else {
            Err(SolverError::InvalidSetting {
                what: "phase",
                value: f64::NAN,
                expected: "the phases in order: geostatic, install, then pull(1 ..= steps)",
            })
        }
    }
}
