//! The pull-out test in 3D: the axisymmetric scene's meridian mesh (tip detached) revolved into
//! a quarter ([`fem_core::solid::revolve`], `sectors` sectors of `90° / sectors`), with the
//! same materials, phases and interface, so that the 3D head load–displacement curve can be
//! compared with the axisymmetric one ([`PulloutSpec::build_3d`]). The scene is the same type,
//! [`PulloutScene<3>`]: its phases and readings are the axisymmetric scene's, written once;
//! this file builds what is 3D (the mesh, the supports, the zones, the installation's solve).
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
//!   ([`Installation::RadialDisplacement`](super::Installation::RadialDisplacement)) to run
//!   both models with the same `δ`.
//! - **Head load.** `Q = 4 Σ R_z` over the head nodes (quarter to full ring,
//!   [`PileSpace::RING`](super::PileSpace::RING)), the contact forces on the head's prescribed
//!   `u_z` taken out as in 2D.
//! - **Coupling.** [`BetaCoupling`](super::BetaCoupling) and
//!   [`PulloutSpec::substeps`] as in 2D; force control ([`PulloutSpec::head_force`]) is not
//!   supported.

use super::meridian::Meridian;
use super::{Parts, PulloutScene, PulloutSpec, ZonePairs};
use contact_laws::Rccm;
use contact_solver::coupling::zone::PairNormals;
use contact_solver::{SimulationSettings, SolverError};
use fem_core::generate::{PILE, SOIL};
use fem_core::solid::{Face, SolidMesh, SolidModel, Stress3, StressField3, revolve};
use fem_core::{Component, Supports};
use std::collections::HashMap;
use std::f64::consts::FRAC_PI_2;
use std::sync::Arc;

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
    /// with the contact solver's `settings` (those of
    /// [`SimulationSettings::for_dimension`]`::<3>()` unless tuned).
    ///
    /// # Errors
    /// As [`PulloutSpec::build`]; [`SolverError::Unsupported`] for force control (a floating
    /// pile is not supported in 3D); [`SolverError::InvalidSetting`] for zero sectors.
    pub fn build_3d(
        &self,
        sectors: usize,
        settings: SimulationSettings,
    ) -> Result<PulloutScene<3>, SolverError> {
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
        let parts = self.quarter_parts(sectors, true)?;
        self.assemble(parts, settings)
    }

    /// The quarter's model, zones and (with `installation`) the installation's unit solve
    /// ([`Self::build_3d`] less the simulation), the spec and `sectors ≥ 1` checked by the
    /// caller. Without `installation` the unit solve is skipped (`unit_normal = 1`, no
    /// forces): the plastic pull-out has no installation phase.
    pub(super) fn quarter_parts<L: From<Rccm>>(
        &self,
        sectors: usize,
        installation: bool,
    ) -> Result<Parts<3, L>, SolverError> {
        let Meridian {
            mesh: meridian,
            shaft_pile,
            shaft_soil,
            tip_pile,
            tip_soil,
        } = self.meridian()?;
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
        let materials = self.materials()?;
        // the installation's unit solve: the soil alone, its interface moved by δ₁ e_r
        let mut soil_interface: Vec<usize> = shaft_soil
            .iter()
            .flat_map(|&n| layers[n].iter().copied())
            .collect();
        soil_interface.sort_unstable();
        soil_interface.dedup();
        let unit_delta = 1e-3;
        let mut unit_force: HashMap<usize, [f64; 3]> = HashMap::new();
        if installation {
            let unit = SolidModel::new(
                mesh.clone(),
                &materials,
                quarter_supports(&mesh, Some((&soil_interface, unit_delta)))?,
            )?;
            let reactions = unit.reactions(&unit.solve(1.0)?, 1.0)?;
            for ((n, c), r) in reactions {
                if soil_interface.binary_search(&n).is_ok() && c != Component::Z {
                    unit_force.entry(n).or_insert([0.0; 3])[c as usize] = r / unit_delta;
                }
            }
        }

        let mut model = SolidModel::new(mesh, &materials, supports)?;
        model.add_self_weight()?;
        // phase 1's initial stress (module docs of `presets::pile`), by region: a position
        // test would put quadrature points of curved soil elements inside the pile
        let stress = self.geostatic_stress();
        let field = |in_pile: bool| -> StressField3 {
            Arc::new(move |x: [f64; 3]| -> Stress3 {
                let (s, s_zz) = stress(x[2], in_pile);
                [s, s, s_zz, 0.0, 0.0, 0.0]
            })
        };
        let (soil, pile) = (field(false), field(true));
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
        let radial = |pile: &[usize], soil: &[usize]| {
            let (c, t, angle) = pairs(pile, soil);
            ZonePairs {
                normals: PairNormals::PerPair(
                    angle.iter().map(|a| [-a.cos(), -a.sin(), 0.0]).collect(),
                ),
                areas: c.iter().map(|n| shaft_area[n]).collect(),
                pile: c,
                soil: t,
            }
        };
        let (c, t, _) = pairs(&tip_pile, &tip_soil);
        let tip = ZonePairs {
            areas: c
                .iter()
                .map(|n| tip_area.get(n).copied().unwrap_or(0.0))
                .collect(),
            pile: c,
            soil: t,
            normals: PairNormals::Fixed([0.0, 0.0, 1.0]),
        };
        let zones = self.zones([
            radial(&shaft_pile[1..], &shaft_soil[1..]),
            radial(&shaft_pile[..1], &shaft_soil[..1]),
            tip,
        ])?;
        let (n_shaft, n_corner, n_tip) = (
            zones[0].contactor.len(),
            zones[1].contactor.len(),
            zones[2].contactor.len(),
        );

        // δ for the requested installation (quarter sums on both sides)
        let geostatic_normal = self.shaft_normal_at_rest(
            zones[0]
                .contactor
                .iter()
                .chain(&zones[1].contactor)
                .map(|n| (model.mesh().nodes()[*n][2], shaft_area[n])),
        );
        let mut unit_forces: Vec<(usize, [f64; 3])> = unit_force.into_iter().collect();
        unit_forces.sort_unstable_by_key(|(n, _)| *n);
        let unit_normal: f64 = if installation {
            unit_forces
                .iter()
                .map(|(n, f)| {
                    let x = model.mesh().nodes()[*n];
                    let r = x[0].hypot(x[1]);
                    (f[0] * x[0] + f[1] * x[1]) / r
                })
                .sum()
        } else {
            1.0
        };
        let parts = Parts {
            model,
            zones,
            head,
            shaft_candidates: (0..n_shaft + n_corner).collect(),
            tip_candidates: (n_shaft + n_corner..n_shaft + n_corner + n_tip).collect(),
            geostatic_normal,
            unit_forces,
            unit_normal,
        };
        Ok(parts)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::presets::PileSpace;
    use fem_core::Dim;

    /// A small Plancoët: 4 shaft cells, one increment.
    fn small() -> PulloutSpec {
        let mut spec = PulloutSpec::plancoet();
        (
            spec.mesh.cells_shaft,
            spec.mesh.cells_soil_r,
            spec.mesh.cells_below_tip,
        ) = (4, 3, 2);
        spec.steps = 1;
        spec
    }

    fn out_of_order<const D: usize>(scene: &mut PulloutScene<D>)
    where
        Dim<D>: PileSpace<D>,
    {
        let what = |e: SolverError| match e {
            SolverError::InvalidSetting { what, .. } => what,
            e => panic!("{e:?}"),
        };
        assert_eq!(what(scene.pull(1).unwrap_err()), "pull");
        assert_eq!(what(scene.install().unwrap_err()), "install");
    }

    #[test]
    fn issue_35_both_dimensions_keep_the_phase_order() {
        let spec = small();
        out_of_order(&mut spec.build(SimulationSettings::default()).unwrap());
        let settings = SimulationSettings::for_dimension::<3>();
        out_of_order(&mut spec.build_3d(1, settings).unwrap());
    }

    #[test]
    fn issue_35_the_quarter_captures_errors() {
        let mut spec = small();
        let settings = SimulationSettings::for_dimension::<3>();
        let err = spec.build_3d(0, settings).err().unwrap();
        assert!(matches!(
            err,
            SolverError::InvalidSetting {
                what: "sectors",
                ..
            }
        ));
        spec.head_force = Some(100.0);
        let err = spec.build_3d(2, settings).err().unwrap();
        assert!(matches!(err, SolverError::Unsupported(_)), "{err:?}");
    }
}
