//! Floating bodies: an [`ElasticModel`] whose supports may leave rigid-body modes, its modes
//! (`crate::rigid_modes`) and the generalized inverse `K⁺` factorised with one pinned dof per
//! mode.

use super::{ElasticModel, ModelSpace};
use crate::Supports;
use crate::error::FemError;
use crate::idealization::Idealization;
use crate::material::Material;
use crate::mesh::Mesh;
use crate::ordering::FillOrdering;
use crate::rigid_modes::{mesh_modes, project_out};
use crate::solid::SolidMesh;
use crate::space::Dim;
use faer::ColMut;

impl ElasticModel<2> {
    /// Builds a model whose supports may leave rigid-body modes: a body (or several, one per
    /// connected component of the mesh) that contact holds. The modes are found from the mesh
    /// and the supports (plane: the two translations and the rotation; axisymmetric: the axial
    /// translation; those the prescribed dofs do not see), and the solves of
    /// [`Structure`](crate::Structure) apply the generalized inverse `K⁺` (`K` factorised with
    /// one dof per mode pinned, `crate::rigid_modes`). Without modes this is
    /// [`LinearElasticModel::new`](super::LinearElasticModel::new).
    ///
    /// # Errors
    /// As [`LinearElasticModel::new`](super::LinearElasticModel::new), except that rigid-body
    /// modes are accepted; [`FemError::NotPositiveDefinite`] remains for a kernel that is not
    /// a rigid-body mode (a node no element connects, a mechanism).
    ///
    /// # Examples
    /// A block with no support at all: three modes, and `K K⁺ b = b` for a balanced `b`.
    /// ```
    /// use fem_core::generate::{RectangleSpec, rectangle};
    /// use fem_core::{Idealization, LinearElasticModel, Material, Structure, Supports};
    /// let mesh = rectangle(&RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 4, 2))?;
    /// let model = LinearElasticModel::floating(mesh, Idealization::PlaneStrain,
    ///     &[(0, Material::new(100.0, 0.3, 0.0)?)], Supports::new())?;
    /// assert_eq!(model.rigid_body_modes().map(|m| m.len()), Some(3));
    /// # Ok::<(), fem_core::FemError>(())
    /// ```
    pub fn floating(
        mesh: Mesh,
        idealization: Idealization,
        materials: &[(u32, Material)],
        supports: Supports,
    ) -> Result<Self, FemError> {
        Self::build(
            mesh,
            idealization,
            materials,
            supports,
            true,
            FillOrdering::Amd,
        )
    }
}

impl ElasticModel<3> {
    /// As [`LinearElasticModel::floating`](super::LinearElasticModel::floating) in 3D: the
    /// modes a body keeps are among its three translations and three rotations (about its
    /// centroid), those its supports do not see.
    ///
    /// # Errors
    /// As [`SolidModel::new`](super::SolidModel::new), except that rigid-body modes are
    /// accepted.
    pub fn floating(
        mesh: SolidMesh,
        materials: &[(u32, Material)],
        supports: Supports,
    ) -> Result<Self, FemError> {
        Self::build(mesh, (), materials, supports, true, FillOrdering::default())
    }
}

impl<const D: usize> ElasticModel<D>
where
    Dim<D>: ModelSpace<D>,
{
    /// Whether the model was built to float (the `floating` constructors).
    #[inline]
    pub fn may_float(&self) -> bool {
        self.may_float
    }

    /// The dofs pinned to factorise `K⁺` (empty without modes).
    #[inline]
    pub fn pinned_dofs(&self) -> &[usize] {
        &self.pinned
    }

    /// Finds the modes of the current dof numbering. A model that may not float and has
    /// modes is refused with [`FemError::NotPositiveDefinite`] at the first dof that would be
    /// pinned (a dof the mode moves).
    pub(super) fn find_modes(&mut self) -> Result<(), FemError> {
        let mesh = &self.mesh;
        let cells = (0..mesh.element_count()).map(|e| mesh.element(e));
        let modes = mesh_modes(mesh.nodes(), cells, self.setting, &self.dofs)?;
        let pinned = modes.pinned_dofs();
        if !self.may_float
            && let Some(&row) = pinned.first()
            && let Some((node, component)) = self.dofs.free_dof_owner(row)
        {
            return Err(FemError::NotPositiveDefinite {
                node,
                component,
                row,
            });
        }
        self.mode_basis = modes.orthonormal_basis();
        self.modes = modes;
        self.pinned = pinned;
        Ok(())
    }

    /// `b ← P b` with `P = I − Q Qᵀ`; before the solve (`pin`), the pinned entries are then
    /// zeroed (the right-hand side of the pinned factorisation).
    pub(super) fn project(&self, b: &mut [f64], pin: bool) {
        project_out(&self.mode_basis, b);
        if pin {
            for &p in &self.pinned {
                b[p] = 0.0;
            }
        }
    }

    /// [`Self::project`] on a column of a faer matrix (contiguous or not).
    pub(super) fn project_column(&self, mut col: ColMut<'_, f64>, pin: bool) {
        if let Some(b) = col.as_mut().try_as_col_major_mut() {
            self.project(b.as_slice_mut(), pin);
            return;
        }
        let n = col.nrows();
        for q in self.mode_basis.chunks_exact(n) {
            let d: f64 = (0..n).map(|i| q[i] * col[i]).sum();
            for i in 0..n {
                col[i] -= d * q[i];
            }
        }
        if pin {
            for &p in &self.pinned {
                col[p] = 0.0;
            }
        }
    }

    /// `pinned_values`: `K` with the rows and columns of the pinned dofs zeroed but for their
    /// diagonal, so that the factorisation inverts `K_SS` and leaves the pinned dofs at zero.
    pub(super) fn pin_values(&mut self) {
        let n = self.dofs.free_count();
        let mut is_pinned = vec![false; n];
        for &p in &self.pinned {
            is_pinned[p] = true;
        }
        self.pinned_values.clear();
        self.pinned_values.extend_from_slice(&self.values);
        let symbolic = self.pattern.symbolic();
        let (col_ptr, row_idx) = (symbolic.col_ptr(), symbolic.row_idx());
        for j in 0..n {
            let range = col_ptr[j]..col_ptr[j + 1];
            for (&i, v) in row_idx[range.clone()]
                .iter()
                .zip(&mut self.pinned_values[range])
            {
                if i != j && (is_pinned[i] || is_pinned[j]) {
                    *v = 0.0;
                }
            }
        }
    }

    /// `Rᵀ f` at `load_factor` (`f` the right-hand side of the free response).
    pub(super) fn mode_load_into(&self, load_factor: f64, out: &mut [f64]) -> Result<(), FemError> {
        assert_eq!(out.len(), self.modes.len(), "one entry per rigid-body mode");
        if self.modes.is_empty() {
            return Ok(());
        }
        let mut f = vec![0.0; self.dofs.free_count()];
        self.rhs_into(load_factor, &mut f);
        self.check_finite("right-hand side", &f)?;
        self.modes.project_into(&f, out);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{RectangleSpec, rectangle};
    use crate::mesh::ElementKind;
    use crate::model::{LinearElasticModel, SolidModel};
    use crate::{Component, Structure};

    fn block(kind: ElementKind, idealization: Idealization) -> LinearElasticModel {
        let spec = RectangleSpec {
            kind,
            ..RectangleSpec::new([0.5, 2.5], [0.0, 1.0], 6, 3)
        };
        let mesh = rectangle(&spec).unwrap();
        let m = Material::new(1e3, 0.3, 0.0).unwrap();
        LinearElasticModel::floating(mesh, idealization, &[(0, m)], Supports::new()).unwrap()
    }

    /// `K x` for the full lower-triangular `K` of the model.
    fn k_times<const D: usize>(model: &ElasticModel<D>, x: &[f64]) -> Vec<f64>
    where
        Dim<D>: ModelSpace<D>,
    {
        let k = model.stiffness();
        let mut y = vec![0.0; x.len()];
        for j in 0..k.ncols() {
            for (i, v) in k.row_idx_of_col(j).zip(k.val_of_col(j)) {
                y[i] += v * x[j];
                if i != j {
                    y[j] += v * x[i];
                }
            }
        }
        y
    }

    #[test]
    fn rigid_modes_are_in_the_kernel_works() {
        for kind in [ElementKind::Tri3, ElementKind::Tri6] {
            for (ideal, count) in [
                (Idealization::PlaneStrain, 3),
                (Idealization::PlaneStress { thickness: 0.1 }, 3),
                (Idealization::Axisymmetric, 1),
            ] {
                let model = block(kind, ideal);
                let modes = model.rigid_body_modes().unwrap();
                assert_eq!(modes.len(), count, "{kind:?} {ideal:?}");
                let k_max = model.values.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
                for j in 0..modes.len() {
                    let kr = k_times(&model, modes.column(j));
                    let worst = kr.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
                    // round-off of a sum of O(10) entries of size ‖K‖ per row
                    assert!(
                        worst <= 1e-12 * k_max,
                        "{kind:?} {ideal:?} mode {j}: {worst:e}"
                    );
                }
            }
        }
    }

    #[test]
    fn generalized_inverse_works() {
        for kind in [ElementKind::Tri3, ElementKind::Tri6] {
            for ideal in [Idealization::PlaneStrain, Idealization::Axisymmetric] {
                let model = block(kind, ideal);
                let modes = model.rigid_body_modes().unwrap().clone();
                let n = model.dof_count();
                // a random-looking b made balanced: b − R (RᵀR)⁻¹ Rᵀ b
                let mut b: Vec<f64> = (0..n)
                    .map(|i| ((i * 37 % 101) as f64 - 50.0) / 7.0)
                    .collect();
                let k = modes.len();
                let gram = nalgebra::DMatrix::from_fn(k, k, |a, c| {
                    modes
                        .column(a)
                        .iter()
                        .zip(modes.column(c))
                        .map(|(x, y)| x * y)
                        .sum()
                });
                let mut rtb = vec![0.0; k];
                modes.project_into(&b, &mut rtb);
                let coef = gram.lu().solve(&nalgebra::DVector::from_vec(rtb)).unwrap();
                for a in 0..k {
                    for (bi, ri) in b.iter_mut().zip(modes.column(a)) {
                        *bi -= coef[a] * ri;
                    }
                }
                let mut x = b.clone();
                model.solve_in_place(&mut x).unwrap();
                let kx = k_times(&model, &x);
                let scale = b.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
                let err = kx
                    .iter()
                    .zip(&b)
                    .fold(0.0_f64, |m, (a, c)| m.max((a - c).abs()));
                // a sparse Cholesky solve: round-off times a modest condition number
                assert!(err <= 1e-9 * scale, "{kind:?} {ideal:?}: {err:e}");
                // the projected inverse answers orthogonally to the modes
                let mut rtx = vec![0.0; k];
                modes.project_into(&x, &mut rtx);
                let x_max = x.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
                assert!(
                    rtx.iter().all(|v| v.abs() <= 1e-12 * x_max * n as f64),
                    "{rtx:?}"
                );
            }
        }
    }

    #[test]
    fn floating_rejects_a_loose_node() {
        let rect = rectangle(&RectangleSpec::new([0.0, 1.0], [0.0, 1.0], 2, 2)).unwrap();
        let mut nodes = rect.nodes().to_vec();
        nodes.push([5.0, 5.0]);
        let connectivity = rect.connectivity().to_vec();
        let mesh = Mesh::new(nodes, ElementKind::Tri3, connectivity, vec![]).unwrap();
        let m = Material::new(1.0, 0.3, 0.0).unwrap();
        let s = Supports::new();
        let err = LinearElasticModel::floating(mesh, Idealization::PlaneStrain, &[(0, m)], s)
            .unwrap_err();
        assert!(
            matches!(err, FemError::NotPositiveDefinite { node: 9, .. }),
            "{err:?}"
        );
    }

    #[test]
    fn two_bodies_float_separately_works() {
        // two unit squares side by side, not connected: 3 modes per body
        let nodes = vec![
            [0.0, 0.0],
            [1.0, 0.0],
            [1.0, 1.0],
            [0.0, 1.0],
            [2.0, 0.0],
            [3.0, 0.0],
            [3.0, 1.0],
            [2.0, 1.0],
        ];
        let conn = vec![0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7];
        let mesh = Mesh::new(nodes, ElementKind::Tri3, conn, vec![]).unwrap();
        let m = Material::new(1.0, 0.3, 0.0).unwrap();
        let mut s = Supports::new();
        s.fix(&[4, 5], Component::Y); // the second body keeps only its x translation
        let model =
            LinearElasticModel::floating(mesh, Idealization::PlaneStrain, &[(0, m)], s).unwrap();
        let modes = model.rigid_body_modes().unwrap();
        let bodies: Vec<usize> = modes.modes().iter().map(|m| m.body).collect();
        assert_eq!(bodies, vec![0, 0, 0, 1]);
        let mut load = vec![0.0; 4];
        model.rigid_body_load_into(1.0, &mut load).unwrap();
        assert_eq!(load, vec![0.0; 4]);
    }

    /// A free 3D block floats with the six rigid-body modes (three translations, three
    /// rotations): `K R = 0` to round-off, and `K⁺` solves a balanced load.
    #[test]
    fn issue_35_a_solid_floats_with_six_modes_works() {
        use crate::solid::generate::{box_mesh, lines};
        for kind in [ElementKind::Tet4, ElementKind::Hex8] {
            let mesh = box_mesh(
                &lines(0.0, 2.0, 3),
                &lines(0.0, 1.0, 2),
                &lines(0.0, 1.0, 2),
                kind,
            )
            .unwrap();
            let m = Material::new(1e3, 0.3, 0.0).unwrap();
            let mut model = SolidModel::floating(mesh, &[(0, m)], Supports::new()).unwrap();
            let modes = model.rigid_body_modes().unwrap().clone();
            assert_eq!(modes.len(), 6, "{kind:?}");
            let k_max = model.values.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            for j in 0..6 {
                let worst = k_times(&model, modes.column(j))
                    .iter()
                    .fold(0.0_f64, |m, v| m.max(v.abs()));
                // round-off of a sum of O(80) entries of size ‖K‖ per row
                assert!(worst <= 1e-11 * k_max, "{kind:?} mode {j}: {worst:e}");
            }
            // equal and opposite forces along the edge y = z = 0: balanced, so K K⁺ f = f
            let at = |x: [f64; 3]| model.mesh().nodes().iter().position(|p| *p == x).unwrap();
            let ends = [at([0.0, 0.0, 0.0]), at([2.0, 0.0, 0.0])];
            model.add_nodal_force(ends[0], [-1.0, 0.0, 0.0]).unwrap();
            model.add_nodal_force(ends[1], [1.0, 0.0, 0.0]).unwrap();
            let mut load = vec![0.0; 6];
            model.rigid_body_load_into(1.0, &mut load).unwrap();
            // R^T f: translations see 0 exactly, rotations a sum of two opposite terms
            assert!(load.iter().all(|v| v.abs() < 1e-12), "{load:?}");
            let mut u = vec![0.0; model.dof_count()];
            model.free_response_into(1.0, &mut u).unwrap();
            let mut f = vec![0.0; model.dof_count()];
            model.rhs_into(1.0, &mut f);
            let ku = k_times(&model, &u);
            let err = ku
                .iter()
                .zip(&f)
                .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
            // a sparse Cholesky solve: round-off times a modest condition number
            assert!(err <= 1e-9, "{kind:?}: {err:e}");
            // the same block held at one end is not floating
            let held = model.mesh().node_set("x0").unwrap().to_vec();
            let mut s = Supports::new();
            for c in Component::all::<3>() {
                s.fix(&held, c);
            }
            let fixed = SolidModel::floating(model.mesh().clone(), &[(0, m)], s).unwrap();
            assert!(fixed.floating().is_none());
        }
    }
}
