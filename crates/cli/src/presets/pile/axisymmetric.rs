//! The axisymmetric scene ([`PulloutSpec::build`]): the meridian section meshed as is, P2 in
//! `(r, z)`, forces per radian, the tributary areas consistent along the lines of nodes.

use super::meridian::Meridian;
use super::{Parts, PulloutScene, PulloutSpec, ZonePairs};
use contact_laws::Rccm;
use contact_solver::SolverError;
use contact_solver::coupling::simulation::SimulationSettings;
use contact_solver::coupling::zone::PairNormals;
use fem_core::{
    Component, ElementKind, Idealization, LinearElasticModel, Material, Mesh, Supports,
};

impl PulloutSpec {
    /// Builds the axisymmetric scene: mesh (with the tip detached), model with self-weight and
    /// initial stress, the three contact zones (shaft, tip corner, tip), and the installation
    /// forces for a unit `δ`. With [`BetaCoupling::Staggered`](super::BetaCoupling::Staggered)
    /// the settings' adhesion fixed point is cut to one iteration and accepted unconverged (the
    /// scene then checks each contact solve's residual against `settings.solver.tol`).
    ///
    /// # Errors
    /// [`SolverError::Structure`] for invalid geometry or materials; [`SolverError::Law`] for
    /// invalid interface parameters; [`SolverError::InvalidSetting`] for a non-finite or
    /// negative installation, `k0`, head displacement or alert distance, zero steps, or
    /// [`TipCorner::Shared`](fem_core::generate::TipCorner::Shared).
    pub fn build(&self, settings: SimulationSettings) -> Result<PulloutScene, SolverError> {
        self.check()?;
        let parts = self.axisymmetric_parts()?;
        self.assemble(parts, settings)
    }

    /// The axisymmetric model, zones and installation calibration ([`Self::build`] less the
    /// simulation), the spec checked by the caller.
    pub(super) fn axisymmetric_parts<L: From<Rccm>>(&self) -> Result<Parts<2, L>, SolverError> {
        let (radius, length) = (self.radius(), self.mesh.length);
        let Meridian {
            mesh,
            shaft_pile,
            shaft_soil,
            tip_pile,
            tip_soil,
        } = self.meridian()?;
        let kind = mesh.kind();
        let head = mesh.node_set("pile_head")?.to_vec();

        let mut supports = Supports::new();
        supports
            .fix(mesh.node_set("axis")?, Component::X)
            .fix(mesh.node_set("outer")?, Component::X)
            .fix(mesh.node_set("base")?, Component::Y);
        let mut held = supports.clone();
        held.fix(&head, Component::Y);
        if self.head_force.is_some() {
            supports.tie(&head, Component::Y)?;
        } else {
            supports = held.clone();
        }
        let materials = self.materials()?;

        // the installation's calibration with the head held (a unit solve of the bonded soil)
        let unit_forces = unit_installation_forces(&mesh, &materials, &held, &shaft_soil)?;

        let mut model = if self.head_force.is_some() {
            LinearElasticModel::floating(mesh, Idealization::Axisymmetric, &materials, supports)?
        } else {
            LinearElasticModel::new(mesh, Idealization::Axisymmetric, &materials, supports)?
        };
        model.add_self_weight()?;
        model.set_initial_stress(self.initial_stress())?;

        // Zones: shaft (all pairs but the tip corner), tip corner (Coulomb), tip (Signorini).
        let positions = |nodes: &[usize], axis: usize| -> Vec<f64> {
            nodes
                .iter()
                .map(|&n| model.mesh().nodes()[n][axis])
                .collect()
        };
        let shaft_z = positions(&shaft_pile, 1);
        if shaft_z
            .first()
            .is_none_or(|z| (z + length).abs() > 1e-9 * length)
        {
            return Err(SolverError::InvalidGeometry(
                "the lowest shaft pair is not the tip corner".into(),
            ));
        }
        let shaft_areas: Vec<f64> = consistent_weights(&shaft_z, kind, |_| radius)?;
        let tip_r = positions(&tip_pile, 0);
        // the tip's last side ends at the corner (r = R), which belongs to the shaft zone
        let mut tip_line = tip_r.clone();
        tip_line.push(radius);
        let mut tip_areas = consistent_weights(&tip_line, kind, |r| r)?;
        tip_areas.pop();
        let geostatic_normal =
            self.shaft_normal_at_rest(shaft_z.iter().copied().zip(shaft_areas.iter().copied()));

        let inward = PairNormals::Fixed([-1.0, 0.0]);
        let zones = self.zones([
            ZonePairs {
                pile: shaft_pile[1..].to_vec(),
                soil: shaft_soil[1..].to_vec(),
                normals: inward.clone(),
                areas: shaft_areas[1..].to_vec(),
            },
            ZonePairs {
                pile: vec![shaft_pile[0]],
                soil: vec![shaft_soil[0]],
                normals: inward,
                areas: vec![shaft_areas[0]],
            },
            ZonePairs {
                pile: tip_pile.clone(),
                soil: tip_soil,
                normals: PairNormals::Fixed([0.0, 1.0]),
                areas: tip_areas,
            },
        ])?;
        // candidates in zone order: shaft above the corner (n − 1), corner, tip
        let n_shaft = shaft_pile.len();
        let parts = Parts {
            model,
            zones,
            head,
            shaft_candidates: std::iter::once(n_shaft - 1).chain(0..n_shaft - 1).collect(),
            tip_candidates: (n_shaft..n_shaft + tip_pile.len()).collect(),
            geostatic_normal,
            unit_normal: unit_forces.iter().sum(),
            unit_forces: shaft_soil
                .iter()
                .zip(&unit_forces)
                .map(|(&n, &f)| (n, [f, 0.0]))
                .collect(),
        };
        Ok(parts)
    }
}

/// The soil's radial reactions per unit installation displacement `δ` at its interface nodes
/// (`shaft_soil`): the soil alone (the pile is detached and held at its head, so `K` stays
/// definite) with `u_r = δ₁` prescribed on those nodes, divided by `δ₁`.
fn unit_installation_forces(
    mesh: &Mesh,
    materials: &[(u32, Material)],
    supports: &Supports,
    shaft_soil: &[usize],
) -> Result<Vec<f64>, SolverError> {
    let unit_delta = 1e-3;
    let mut inst_supports = supports.clone();
    inst_supports.prescribe(shaft_soil, Component::X, unit_delta)?;
    let inst_model = LinearElasticModel::new(
        mesh.clone(),
        Idealization::Axisymmetric,
        materials,
        inst_supports,
    )?;
    let u_unit = inst_model.solve(1.0)?;
    let reactions = inst_model.reactions(&u_unit, 1.0)?;
    Ok(shaft_soil
        .iter()
        .map(|&n| {
            reactions
                .iter()
                .find(|((node, c), _)| *node == n && *c == Component::X)
                .map_or(0.0, |(_, r)| r / unit_delta)
        })
        .collect())
}

/// Consistent nodal weights `∫ N_i(s) w(s) ds` of a line of nodes at increasing coordinates
/// `s` (P1: 2-node sides; P2: 3-node sides, corner–mid–corner), for a weight `w` that is
/// linear in `s` (`r` along the tip, the constant `R` along the shaft): Simpson's rule is exact
/// for P2 (`N_i w` is cubic), the two-point closed form for P1.
fn consistent_weights(
    s: &[f64],
    kind: ElementKind,
    weight: impl Fn(f64) -> f64,
) -> Result<Vec<f64>, SolverError> {
    let per_side = if kind.is_quadratic() { 2 } else { 1 };
    if s.len() < per_side + 1 || !(s.len() - 1).is_multiple_of(per_side) {
        return Err(SolverError::InvalidGeometry(format!(
            "a line of {} nodes is not made of whole {kind:?} sides",
            s.len()
        )));
    }
    let mut a = vec![0.0; s.len()];
    for k in (0..s.len() - 1).step_by(per_side) {
        let h = s[k + per_side] - s[k];
        if per_side == 1 {
            let (wa, wb) = (weight(s[k]), weight(s[k + 1]));
            a[k] += h * (2.0 * wa + wb) / 6.0;
            a[k + 1] += h * (wa + 2.0 * wb) / 6.0;
        } else {
            a[k] += h / 6.0 * weight(s[k]);
            a[k + 1] += 4.0 * h / 6.0 * weight(s[k + 1]);
            a[k + 2] += h / 6.0 * weight(s[k + 2]);
        }
    }
    Ok(a)
}

#[cfg(test)]
mod tests {
    use super::*;
    use fem_core::generate::TipCorner;

    #[test]
    fn consistent_weights_works() {
        // P2 side of length 2 at constant weight 1: 1/3, 4/3, 1/3.
        let a = consistent_weights(&[0.0, 1.0, 2.0], ElementKind::Tri6, |_| 1.0).unwrap();
        assert!((a[0] - 1.0 / 3.0).abs() < 1e-15 && (a[1] - 4.0 / 3.0).abs() < 1e-15);
        // ∫ N_i r dr over [0, 1] with P1: (0·2 + 1)/6 = 1/6 and (0 + 2)/6 = 1/3.
        let b = consistent_weights(&[0.0, 1.0], ElementKind::Tri3, |r| r).unwrap();
        assert!((b[0] - 1.0 / 6.0).abs() < 1e-15 && (b[1] - 1.0 / 3.0).abs() < 1e-15);
        // Σ = ∫ r dr = 1/2 for P2 too.
        let c = consistent_weights(&[0.0, 0.25, 0.5, 0.75, 1.0], ElementKind::Tri6, |r| r).unwrap();
        assert!((c.iter().sum::<f64>() - 0.5).abs() < 1e-15);
    }

    #[test]
    fn consistent_weights_rejects_partial_sides() {
        let err = consistent_weights(&[0.0, 1.0], ElementKind::Tri6, |_| 1.0).unwrap_err();
        assert!(matches!(err, SolverError::InvalidGeometry(_)), "{err:?}");
    }

    #[test]
    fn build_rejects_a_shared_tip_corner() {
        let mut spec = PulloutSpec::default();
        spec.mesh.tip_corner = TipCorner::Shared;
        let err = spec.build(SimulationSettings::default()).err().unwrap();
        assert!(matches!(
            err,
            SolverError::InvalidSetting {
                what: "mesh.tip_corner",
                ..
            }
        ));
    }
}
