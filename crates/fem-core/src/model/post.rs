//! Recovery from a solution: stresses at the quadrature points, smoothed nodal stresses and
//! support reactions; strains in 2D, error norms against an exact solution in 3D.

use super::{ElasticModel, ModelSpace, Reaction, StressPoint};
use crate::element::kernel::{field_at3, hooke, lame};
use crate::element::{Stress3, VoigtStress};
use crate::error::FemError;
use crate::idealization::Idealization;
use crate::space::Dim;

impl<const D: usize> ElasticModel<D>
where
    Dim<D>: ModelSpace<D>,
{
    /// Stresses `σ₀ + D B u` at the quadrature points of every element, with their positions,
    /// element by element.
    ///
    /// # Errors
    /// [`FemError::LengthMismatch`] if `displacements` does not have one entry per node.
    pub fn stresses(
        &self,
        displacements: &[[f64; D]],
    ) -> Result<Vec<Vec<StressPoint<D>>>, FemError> {
        let mut out = self.elastic_stresses(displacements)?;
        let regions = self.mesh.regions();
        for (e, points) in out.iter_mut().enumerate() {
            if let Some((_, s0)) = self.initial_stress.iter().find(|(r, _)| *r == regions[e]) {
                for (x, s) in points {
                    let s_0 = s0(*x);
                    for (s, s_0) in s.as_mut().iter_mut().zip(s_0.as_ref()) {
                        *s += s_0;
                    }
                }
            }
        }
        Ok(out)
    }

    /// Stresses `D B u` at the quadrature points, without the initial stress (as
    /// [`ElasticModel::stresses`] otherwise).
    ///
    /// # Errors
    /// As for [`ElasticModel::stresses`].
    pub fn elastic_stresses(
        &self,
        displacements: &[[f64; D]],
    ) -> Result<Vec<Vec<StressPoint<D>>>, FemError> {
        if displacements.len() != self.mesh.node_count() {
            return Err(FemError::LengthMismatch {
                what: "nodal displacements",
                expected: self.mesh.node_count(),
                got: displacements.len(),
            });
        }
        let mut out = Vec::with_capacity(self.mesh.element_count());
        let mut coords = Vec::new();
        let mut u_e = Vec::new();
        for e in 0..self.mesh.element_count() {
            let cell = self.mesh.element(e);
            self.mesh.element_coords_into(e, &mut coords);
            u_e.clear();
            u_e.extend(cell.iter().flat_map(|&n| displacements[n]));
            let material = &self.materials[&self.mesh.regions()[e]];
            let mut pts = Vec::new();
            let element = self.element_at(e);
            element.stresses_into(e, &coords, material, &self.setting, &u_e, &mut pts)?;
            out.push(pts);
        }
        Ok(out)
    }

    /// Nodal stresses: the average over the elements around each node of the element's mean
    /// quadrature-point stress (a simple, robust smoothing for plots).
    ///
    /// # Errors
    /// As for [`ElasticModel::stresses`].
    pub fn nodal_stresses(
        &self,
        displacements: &[[f64; D]],
    ) -> Result<Vec<VoigtStress<D>>, FemError> {
        let per_element = self.stresses(displacements)?;
        let mut sum = vec![VoigtStress::<D>::default(); self.mesh.node_count()];
        let mut count = vec![0usize; self.mesh.node_count()];
        for (e, pts) in per_element.iter().enumerate() {
            let mut mean = VoigtStress::<D>::default();
            for (_, s) in pts {
                for (m, s) in mean.as_mut().iter_mut().zip(s.as_ref()) {
                    *m += s / pts.len() as f64;
                }
            }
            for &n in self.mesh.element(e) {
                for (s, m) in sum[n].as_mut().iter_mut().zip(mean.as_ref()) {
                    *s += m;
                }
                count[n] += 1;
            }
        }
        for (s, c) in sum.iter_mut().zip(count) {
            if c > 0 {
                s.as_mut().iter_mut().for_each(|v| *v /= c as f64);
            }
        }
        Ok(sum)
    }

    /// Support reactions `R = K u − f` at every prescribed dof, for the displacements
    /// `displacements` (from [`ElasticModel::solve`]) at `load_factor`:
    /// `((node, component), reaction)`.
    ///
    /// # Errors
    /// [`FemError::LengthMismatch`] if `displacements` does not have one entry per node.
    pub fn reactions(
        &self,
        displacements: &[[f64; D]],
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

impl ElasticModel<2> {
    /// Strains `ε = B u` at the quadrature points of every element (the same points as
    /// [`ElasticModel::stresses`]), components `(xx, yy, γ_xy, zz)` with engineering
    /// shear `γ = 2ε`; `zz` is `0` in plane strain, `−ν/(1−ν)(ε_xx + ε_yy)` in plane stress,
    /// and the hoop strain `u_r/r` in axisymmetry (order `(rr, zz, γ_rz, θθ)`).
    ///
    /// # Errors
    /// As for [`ElasticModel::stresses`].
    pub fn strains(&self, displacements: &[[f64; 2]]) -> Result<Vec<Vec<StressPoint>>, FemError> {
        let elastic = self.elastic_stresses(displacements)?;
        let m = self.setting.strain_size();
        Ok(elastic
            .into_iter()
            .enumerate()
            .map(|(e, pts)| {
                let material = &self.materials[&self.mesh.regions()[e]];
                let d = material.elasticity(&self.setting);
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
                        if let Idealization::PlaneStress { .. } = self.setting {
                            let nu = material.poisson();
                            eps[3] = -nu / (1.0 - nu) * (eps[0] + eps[1]);
                        }
                        (x, eps)
                    })
                    .collect()
            })
            .collect())
    }
}

impl ElasticModel<3> {
    /// The errors of a displacement field against an exact one, `exact(x) = (u, ∇u)`
    /// (`∇u[i][j] = ∂u_i/∂x_j`), integrated with a 64-point rule per element:
    /// `(‖u − u*‖_L2, ‖u − u*‖_E)` with the energy norm `‖v‖_E² = ∫ ε(v) : C : ε(v) dV`.
    ///
    /// # Errors
    /// [`FemError::LengthMismatch`] if `displacements` has not one entry per node;
    /// [`FemError::InvertedElement`].
    pub fn error_norms(
        &self,
        displacements: &[[f64; 3]],
        exact: impl Fn([f64; 3]) -> ([f64; 3], [[f64; 3]; 3]),
    ) -> Result<(f64, f64), FemError> {
        if displacements.len() != self.mesh.node_count() {
            return Err(FemError::LengthMismatch {
                what: "displacements",
                expected: self.mesh.node_count(),
                got: displacements.len(),
            });
        }
        let (mut l2, mut energy) = (0.0, 0.0);
        let mut coords = Vec::with_capacity(10);
        let mut u_e = Vec::with_capacity(30);
        for e in 0..self.mesh.element_count() {
            let cell = self.mesh.element(e);
            self.mesh.element_coords_into(e, &mut coords);
            u_e.clear();
            u_e.extend(cell.iter().flat_map(|&n| displacements[n]));
            let (lambda, mu) = lame(self.material(e));
            let element = self.element_at(e);
            for &q in element.load_rule(&()) {
                let (x, u, eps, w) = field_at3(element, e, &coords, &u_e, q)?;
                let (ue, g) = exact(x);
                let de: Stress3 = [
                    eps[0] - g[0][0],
                    eps[1] - g[1][1],
                    eps[2] - g[2][2],
                    eps[3] - 0.5 * (g[0][1] + g[1][0]),
                    eps[4] - 0.5 * (g[1][2] + g[2][1]),
                    eps[5] - 0.5 * (g[2][0] + g[0][2]),
                ];
                let s = hooke(lambda, mu, de);
                let inner = s[0] * de[0]
                    + s[1] * de[1]
                    + s[2] * de[2]
                    + 2.0 * (s[3] * de[3] + s[4] * de[4] + s[5] * de[5]);
                energy += w * inner;
                l2 += w * (0..3).map(|i| (u[i] - ue[i]).powi(2)).sum::<f64>();
            }
        }
        Ok((l2.sqrt(), energy.sqrt()))
    }
}
