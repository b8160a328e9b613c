//! The loads of an [`ElasticModel`]: reference nodal forces, tractions on a boundary set, body
//! forces and self-weight (scaled by the load factor), and the initial stress (not scaled).

use super::{ElasticModel, ModelSpace, StressField};
use crate::element::{Element, Setting};
use crate::error::{FemError, finite};
use crate::quadrature::GAUSS_3;
use crate::space::Dim;
use std::collections::BTreeSet;

impl<const D: usize> ElasticModel<D>
where
    Dim<D>: ModelSpace<D>,
{
    /// Adds a reference nodal force (`D` components; in 2D per unit thickness, thickness, or
    /// radian as the idealisation says).
    ///
    /// # Errors
    /// [`FemError::UnknownNode`] or [`FemError::InvalidParameter`] for non-finite values.
    pub fn add_nodal_force(&mut self, node: usize, force: [f64; D]) -> Result<(), FemError> {
        self.check_nodes(&[node], "a nodal force")?;
        for f in force {
            finite("nodal force", f)?;
        }
        for (c, f) in force.into_iter().enumerate() {
            self.load[D * node + c] += f;
        }
        Ok(())
    }

    /// Adds the self-weight of every region (unit weight of its material, along the last
    /// coordinate downwards: `−y` in 2D, `−z` in 3D) to the reference loads.
    ///
    /// # Errors
    /// [`FemError::InvertedElement`] for a curved element with a non-positive Jacobian.
    pub fn add_self_weight(&mut self) -> Result<(), FemError> {
        let force = self.element_forces(|element, e, coords, setting, f_e| {
            let gamma = self.material(e).unit_weight();
            let mut g = [0.0; D];
            g[D - 1] = -gamma;
            element.body_force_into(e, coords, setting, &|_| g, f_e)
        })?;
        self.load.iter_mut().zip(force).for_each(|(l, f)| *l += f);
        Ok(())
    }

    /// Adds a body force `b(x)` (force per volume, global frame) over the whole mesh to the
    /// reference loads, integrated with the element's load rule.
    ///
    /// # Errors
    /// [`FemError::InvertedElement`] for a curved element with a non-positive Jacobian;
    /// [`FemError::InvalidParameter`] if `b` returns a non-finite value.
    pub fn add_body_force(&mut self, b: impl Fn([f64; D]) -> [f64; D]) -> Result<(), FemError> {
        let force = self.element_forces(|element, e, coords, setting, f_e| {
            element.body_force_into(e, coords, setting, &b, f_e)
        })?;
        if let Some(&value) = force.iter().find(|v| !v.is_finite()) {
            return Err(FemError::InvalidParameter {
                name: "body force",
                value,
                expected: "a finite body force",
            });
        }
        self.load.iter_mut().zip(force).for_each(|(l, f)| *l += f);
        Ok(())
    }

    /// Sets the initial stress field `σ₀` (replacing any previous one) and its internal forces
    /// `−∫ Bᵀ σ₀ w dV`, which enter every free response; the recovered stresses include it.
    ///
    /// # Errors
    /// [`FemError::InvertedElement`]; [`FemError::InvalidParameter`] if `σ₀` is not finite at
    /// a quadrature point.
    pub fn set_initial_stress(&mut self, sigma_0: StressField<D>) -> Result<(), FemError> {
        let regions: BTreeSet<u32> = self.mesh.regions().iter().copied().collect();
        let fields: Vec<_> = regions.into_iter().map(|r| (r, sigma_0.clone())).collect();
        self.set_initial_stress_by_region(&fields)
    }

    /// Sets one initial stress field per region (replacing any previous one); elements of
    /// regions not listed start unstressed. For fields that jump across a curved interface
    /// between regions (a pile in soil), where a position test would misclassify the
    /// quadrature points of curved P2 elements near the interface.
    ///
    /// # Errors
    /// [`FemError::UnknownRegion`] for a region no element has; as
    /// [`ElasticModel::set_initial_stress`].
    pub fn set_initial_stress_by_region(
        &mut self,
        fields: &[(u32, StressField<D>)],
    ) -> Result<(), FemError> {
        let regions = self.mesh.regions();
        if let Some((region, _)) = fields.iter().find(|(r, _)| !regions.contains(r)) {
            return Err(FemError::UnknownRegion { region: *region });
        }
        let force = self.element_forces(|element, e, coords, setting, f_e| {
            match fields.iter().find(|(r, _)| *r == regions[e]) {
                Some((_, sigma_0)) => {
                    element.initial_stress_force_into(e, coords, setting, &**sigma_0, f_e)
                }
                None => Ok(()),
            }
        })?;
        if let Some(&value) = force.iter().find(|v| !v.is_finite()) {
            return Err(FemError::InvalidParameter {
                name: "initial stress",
                value,
                expected: "a finite stress field",
            });
        }
        self.initial_force = force;
        self.initial_stress = fields.to_vec();
        Ok(())
    }

    /// Removes every reference load (nodal forces, tractions, body forces, self-weight).
    pub fn clear_loads(&mut self) {
        self.load.fill(0.0);
    }

    /// Integrates an element-level force over every element and scatters it into a vector of
    /// nodal components (`D × node_count`); `f_e` is zeroed before each element.
    fn element_forces(
        &self,
        integrate: impl Fn(
            &dyn Element<D>,
            usize,
            &[[f64; D]],
            &Setting<D>,
            &mut [f64],
        ) -> Result<(), FemError>,
    ) -> Result<Vec<f64>, FemError> {
        let mut force = vec![0.0; D * self.mesh.node_count()];
        let mut coords = Vec::with_capacity(self.mesh.built_in_element().node_count());
        let mut f_e = Vec::new();
        for e in 0..self.mesh.element_count() {
            let cell = self.mesh.element(e);
            self.mesh.element_coords_into(e, &mut coords);
            f_e.resize(D * cell.len(), 0.0);
            f_e.fill(0.0);
            integrate(self.element_at(e), e, &coords, &self.setting, &mut f_e)?;
            for (a, &n) in cell.iter().enumerate() {
                for c in 0..D {
                    force[D * n + c] += f_e[D * a + c];
                }
            }
        }
        Ok(force)
    }
}

impl ElasticModel<2> {
    /// Adds a reference traction `t(x)` (force per area, global frame) on the sides of an edge
    /// set, integrated with 3 Gauss points per side (exact for P2 sides in axisymmetry).
    ///
    /// # Errors
    /// [`FemError::UnknownSet`]; [`FemError::InvalidParameter`] if `t` returns a non-finite
    /// value.
    pub fn add_edge_traction(
        &mut self,
        edge_set: &str,
        traction: impl Fn([f64; 2]) -> [f64; 2],
    ) -> Result<(), FemError> {
        let sides = self.mesh.edge_set(edge_set)?.to_vec();
        for side in sides {
            let nodes: Vec<usize> = self.mesh.side_nodes(side).collect();
            let xs: Vec<[f64; 2]> = nodes.iter().map(|&n| self.mesh.nodes()[n]).collect();
            for &(s, w) in &GAUSS_3 {
                // 1D shapes on [−1, 1]: P1 (a, b); P2 (a, b, mid).
                let (n, dn): (Vec<f64>, Vec<f64>) = if nodes.len() == 2 {
                    (vec![(1.0 - s) / 2.0, (1.0 + s) / 2.0], vec![-0.5, 0.5])
                } else {
                    (
                        vec![s * (s - 1.0) / 2.0, s * (s + 1.0) / 2.0, 1.0 - s * s],
                        vec![s - 0.5, s + 0.5, -2.0 * s],
                    )
                };
                let mut x = [0.0; 2];
                let mut dx = [0.0; 2];
                for i in 0..nodes.len() {
                    for a in 0..2 {
                        x[a] += n[i] * xs[i][a];
                        dx[a] += dn[i] * xs[i][a];
                    }
                }
                let jac = dx[0].hypot(dx[1]);
                let t = traction(x);
                finite("traction", t[0])?;
                finite("traction", t[1])?;
                let wt = w * jac * self.setting.weight(x[0]);
                for i in 0..nodes.len() {
                    self.load[2 * nodes[i]] += n[i] * t[0] * wt;
                    self.load[2 * nodes[i] + 1] += n[i] * t[1] * wt;
                }
            }
        }
        Ok(())
    }
}

impl ElasticModel<3> {
    /// Adds a reference traction `t(x, n)` (force per area, global frame; `n` the unit outward
    /// normal of the face at `x`) on the faces of a face set, integrated with a degree-4 rule
    /// on each face (exact for a uniform traction or pressure on P2 faces). A pressure `p` is
    /// `|_, n| [−p n_x, −p n_y, −p n_z]`.
    ///
    /// # Errors
    /// [`FemError::UnknownSet`]; [`FemError::InvalidParameter`] if `t` returns a non-finite
    /// value.
    pub fn add_face_traction(
        &mut self,
        face_set: &str,
        traction: impl Fn([f64; 3], [f64; 3]) -> [f64; 3],
    ) -> Result<(), FemError> {
        let faces = self.mesh.face_set(face_set)?;
        let mut load = self.load.clone();
        for &face in faces {
            self.mesh.face_points(face, |nodes, p| {
                let t = traction(p.x, p.normal);
                for v in t {
                    finite("traction", v)?;
                }
                for (i, node) in nodes.iter().enumerate() {
                    for (a, ta) in t.iter().enumerate() {
                        load[3 * node + a] += p.n[i] * ta * p.weight;
                    }
                }
                Ok(())
            })?;
        }
        self.load = load;
        Ok(())
    }
}
