//! [`Mass`]: the capability of a structure that has inertia, for a dynamic time scheme.
//!
//! ```text
//! M = Σ_e ∫ ρ Nᵀ N w dΩ         (consistent; w = 1, the thickness, or r per radian)
//! m_i = Σ_e m_e,i (HRZ)        (lumped: the diagonal of M_e scaled to the element's mass)
//! ```
//! Both on the free dofs, numbered as the stiffness (Hinton, Rock & Zienkiewicz 1976 for HRZ).

#[cfg(doc)]
use crate::structure::Structure;
use faer::sparse::SparseColMatRef;

/// The mass of a [`Structure`], reached through [`Structure::mass`]: what a dynamic time
/// scheme needs (Moreau–Jean: products `M v` and the iteration matrix `M + hθC + h²θ²K`).
///
/// Everything lives on the structure's **free dofs**, in the numbering of the stiffness
/// ([`Structure::node_dofs`]); a prescribed dof has no entry, and the nodes of a tie share
/// theirs (their masses add). In axisymmetry the weight is `r` **per radian**, as for the
/// stiffness and the loads, so `M` and `K` stay on one basis (the mass of the whole ring is
/// `2π` times). The mass changes only when the dof numbering does, which also changes
/// [`Structure::stiffness_version`].
///
/// A user's FE code implements [`mul_into`](Self::mul_into) and [`lumped`](Self::lumped)
/// (an explicit code with a diagonal mass only may answer `mul_into` with its diagonal: say
/// so in its docs), and [`matrix`](Self::matrix) when it has `M` assembled.
///
/// # Examples
/// A P1 square of density 2: a rigid translation carries the whole mass, `tᵀ M t = ρ A`.
/// ```
/// use fem_core::generate::{RectangleSpec, rectangle};
/// use fem_core::{Idealization, LinearElasticModel, Material, Structure, Supports};
/// let mesh = rectangle(&RectangleSpec::new([0.0, 1.0], [0.0, 1.0], 2, 2))?;
/// let steel = Material::new(200.0, 0.3, 0.0)?.with_density(2.0)?;
/// let model = LinearElasticModel::floating(mesh, Idealization::PlaneStrain,
///     &[(0, steel)], Supports::new())?;
/// let mass = model.mass().expect("every region has a density");
/// let n = model.dof_count();
/// let t: Vec<f64> = (0..n).map(|i| if i % 2 == 0 { 1.0 } else { 0.0 }).collect(); // x
/// let mut mt = vec![0.0; n];
/// mass.mul_into(&t, &mut mt);
/// let total: f64 = t.iter().zip(&mt).map(|(a, b)| a * b).sum();
/// assert!((total - 2.0).abs() < 1e-14);
/// assert!((mass.lumped().iter().sum::<f64>() - 2.0 * 2.0).abs() < 1e-14); // x and y
/// # Ok::<(), fem_core::FemError>(())
/// ```
pub trait Mass {
    /// `y = M x` with the consistent mass, on the free dofs.
    ///
    /// # Panics
    /// If `x.len()` or `y.len()` is not the structure's `dof_count()`.
    fn mul_into(&self, x: &[f64], y: &mut [f64]);

    /// The lumped (diagonal) mass, one entry per free dof, each positive. fem-core's models
    /// lump by HRZ diagonal scaling, not by row sums: the row sums of quadratic elements
    /// vanish (Tri6) or turn negative (Tet10, Quad8, Hex20) at the corners, while HRZ stays
    /// positive and keeps each element's mass exact.
    fn lumped(&self) -> &[f64];

    /// The consistent mass as its lower triangle in CSC form (row indices sorted in each
    /// column, every diagonal entry stored), if the structure has it assembled; `None` (the
    /// default) otherwise. fem-core's models store it on the pattern of the stiffness
    /// ([`Structure::stiffness_matrix`]), so `M + c K` is a sum of value arrays.
    fn matrix(&self) -> Option<SparseColMatRef<'_, usize, f64>> {
        None
    }
}
