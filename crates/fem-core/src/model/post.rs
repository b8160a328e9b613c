//! Recovery from a solution: stresses and strains at the quadrature points, smoothed nodal
//! stresses and support reactions.

use super::{LinearElasticModel, Reaction, StressPoint};
use crate::element::Stress;
use crate::error::FemError;
use crate::idealization::Idealization;

impl LinearElasticModel {
    /// Stresses `σ₀ + D B u` at the quadrature points of every element, with their positions,
    /// element by element.
    ///
    /// # Errors
    /// [`FemError::LengthMismatch`] if `displacements` does not have one entry per node.
    pub fn stresses(&self, displacements: &[[f64; 2]]) -> Result<Vec<Vec<StressPoint>>, FemError> {
        let mut out = self.elastic_stresses(displacements)?;
        if let Some(s0) = &self.initial_stress {
            for (x, s) in out.iter_mut().flatten() {
                let s_0 = s0(*x);
                for k in 0..4 {
                    s[k] += s_0[k];
                }
            }
        }
        Ok(out)
    }

    /// `D B u` at the quadrature points, without the initial stress.
    fn elastic_stresses(
        &self,
        displacements: &[[f64; 2]],
    ) -> Result<Vec<Vec<StressPoint>>, FemError> {
        if displacements.len() != self.mesh.node_count() {
            return Err(FemError::LengthMismatch {
                what: "nodal displacements",
                expected: self.mesh.node_count(),
                got: displacements.len(),
            });
        }
        let mut out = Vec::with_capacity(self.mesh.element_count());
        let mut coords = Vec::with_capacity(6);
        let mut u_e = Vec::with_capacity(12);
        for e in 0..self.mesh.element_count() {
            let cell = self.mesh.element(e);
            coords.clear();
            coords.extend(cell.iter().map(|&n| self.mesh.nodes()[n]));
            u_e.clear();
            u_e.extend(cell.iter().flat_map(|&n| displacements[n]));
            let material = &self.materials[&self.mesh.regions()[e]];
            let mut pts = Vec::new();
            let element = self.element_at(e);
            element.stresses_into(e, &coords, material, &self.idealization, &u_e, &mut pts)?;
            out.push(pts);
        }
        Ok(out)
    }

    /// Strains `ε = B u` at the quadrature points of every element (the same points as
    /// [`LinearElasticModel::stresses`]), components `(xx, yy, γ_xy, zz)` with engineering
    /// shear `γ = 2ε`; `zz` is `0` in plane strain, `−ν/(1−ν)(ε_xx + ε_yy)` in plane stress,
    /// and the hoop strain `u_r/r` in axisymmetry (order `(rr, zz, γ_rz, θθ)`).
    ///
    /// # Errors
    /// As for [`LinearElasticModel::stresses`].
    pub fn strains(&self, displacements: &[[f64; 2]]) -> Result<Vec<Vec<StressPoint>>, FemError> {
        let elastic = self.elastic_stresses(displacements)?;
        let m = self.idealization.strain_size();
        Ok(elastic
            .into_iter()
            .enumerate()
            .map(|(e, pts)| {
                let material = &self.materials[&self.mesh.regions()[e]];
                let d = material.elasticity(&self.idealization);
                // D is SPD on its m × m block: ε = D⁻¹ σ.
                let compliance = d
                    .view((0, 0), (m, m))
                    .into_owned()
                    .cholesky()
                    .map(|c| c.inverse())
                    .unwrap_or_else(|| nalgebra::DMatrix::zeros(m, m));
                pts.into_iter()
                    .map(|(x, s)| {
                        let mut eps = [0.0; 4];
                        for (r, er) in eps.iter_mut().enumerate().take(m) {
                            *er = (0..m).map(|k| compliance[(r, k)] * s[k]).sum();
                        }
                        if let Idealization::PlaneStress { .. } = self.idealization {
                            let nu = material.poisson();
                            eps[3] = -nu / (1.0 - nu) * (eps[0] + eps[1]);
                        }
                        (x, eps)
                    })
                    .collect()
            })
            .collect())
    }

    /// Nodal stresses: the average over the elements around each node of the element's mean
    /// quadrature-point stress (a simple, robust smoothing for plots).
    ///
    /// # Errors
    /// As for [`LinearElasticModel::stresses`].
    pub fn nodal_stresses(&self, displacements: &[[f64; 2]]) -> Result<Vec<Stress>, FemError> {
        let per_element = self.stresses(displacements)?;
        let mut sum = vec![[0.0; 4]; self.mesh.node_count()];
        let mut count = vec![0usize; self.mesh.node_count()];
        for (e, pts) in per_element.iter().enumerate() {
            let mut mean = [0.0; 4];
            for (_, s) in pts {
                for k in 0..4 {
                    mean[k] += s[k] / pts.len() as f64;
                }
            }
            for &n in self.mesh.element(e) {
                for k in 0..4 {
                    sum[n][k] += mean[k];
                }
                count[n] += 1;
            }
        }
        Ok(sum
            .into_iter()
            .zip(count)
            .map(|(s, c)| if c == 0 { s } else { s.map(|v| v / c as f64) })
            .collect())
    }

    /// Support reactions `R = K u − f` at every prescribed dof, for the displacements
    /// `displacements` (from [`LinearElasticModel::solve`]) at `load_factor`:
    /// `((node, component), reaction)`.
    ///
    /// # Errors
    /// [`FemError::LengthMismatch`] if `displacements` does not have one entry per node.
    pub fn reactions(
        &self,
        displacements: &[[f64; 2]],
        load_factor: f64,
    ) -> Result<Vec<Reaction>, FemError> {
        if displacements.len() != self.mesh.node_count() {
            return Err(FemError::LengthMismatch {
                what: "nodal displacements",
                expected: self.mesh.node_count(),
                got: displacements.len(),
            });
        }
        Ok(self.coupling.reactions(
            &self.dofs,
            displacements,
            &self.load,
            &self.initial_force,
            load_factor,
        ))
    }
}
