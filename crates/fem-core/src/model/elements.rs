//! Users' elements in a model: a region's elements computed by the user's [`Element`]
//! implementation in place of the built-in one of the mesh's kind.

use super::{ElasticModel, ModelSpace};
use crate::element::Element;
use crate::error::FemError;
use crate::space::Dim;
use std::sync::Arc;

impl<const D: usize> ElasticModel<D>
where
    Dim<D>: ModelSpace<D>,
{
    /// Computes the elements of `region` with `element` in place of the built-in element of
    /// the mesh's kind (same node count and node order: the mesh's connectivity is the
    /// element's), then reassembles and refactors the stiffness. Call it before adding loads
    /// and an initial stress: those already added keep the values computed with the previous
    /// element.
    ///
    /// # Errors
    /// - [`FemError::MissingMaterial`] if no element of the mesh is in `region` (named with
    ///   element `usize::MAX`);
    /// - [`FemError::LengthMismatch`] if the element's node count is not the mesh kind's;
    /// - the errors of the assembly and factorisation (as the constructors).
    ///
    /// # Examples
    /// A user's 4-node quadrilateral that takes the built-in shape functions with its own
    /// 3×3 rule; on a rectangle its stiffness equals the built-in 2×2 one (both are exact for
    /// a bilinear element on a parallelogram):
    /// ```
    /// use fem_core::element::{Element, Quad4, QuadPoint, Topology};
    /// use fem_core::generate::{RectangleSpec, rectangle};
    /// use fem_core::quadrature::gauss_tensor;
    /// use fem_core::{Component, ElementKind, Idealization, LinearElasticModel, Material, Supports};
    /// use std::sync::{Arc, OnceLock};
    ///
    /// #[derive(Debug)]
    /// struct MyQuad;
    /// impl Element<2> for MyQuad {
    ///     fn node_count(&self) -> usize { 4 }
    ///     fn shape(&self, xi: [f64; 2], n: &mut [f64], dn: &mut [[f64; 2]]) {
    ///         Quad4.shape(xi, n, dn)
    ///     }
    ///     fn stiffness_rule(&self, _: &Idealization, _: &[[f64; 2]]) -> &[QuadPoint<2>] {
    ///         static RULE: OnceLock<Vec<QuadPoint<2>>> = OnceLock::new();
    ///         RULE.get_or_init(|| gauss_tensor::<2>(3))
    ///     }
    ///     fn load_rule(&self, s: &Idealization) -> &[QuadPoint<2>] { Quad4.load_rule(s) }
    ///     fn topology(&self) -> Topology { Quad4.topology() }
    /// }
    ///
    /// let spec = RectangleSpec { kind: ElementKind::Quad4, ..RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 4, 2) };
    /// let mesh = rectangle(&spec)?;
    /// let mut supports = Supports::new();
    /// let bottom = mesh.node_set("bottom")?.to_vec();
    /// supports.fix(&bottom, Component::X).fix(&bottom, Component::Y);
    /// let material = [(0, Material::new(100.0, 0.3, 0.0)?)];
    /// let built_in = LinearElasticModel::new(mesh.clone(), Idealization::PlaneStrain, &material, supports.clone())?;
    /// let mine = LinearElasticModel::new(mesh, Idealization::PlaneStrain, &material, supports)?
    ///     .with_element(0, Arc::new(MyQuad))?;
    /// let (a, b) = (built_in.stiffness().val(), mine.stiffness().val());
    /// let scale = a.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    /// assert!(a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-12 * scale));
    /// # Ok::<(), fem_core::FemError>(())
    /// ```
    ///
    /// A user's 8-node hexahedron with a 3×3×3 rule: on a box its stiffness differs from the
    /// built-in 2×2×2 one by round-off only (both are exact on a parallelepiped):
    /// ```
    /// use fem_core::element::{Element, Hex8, QuadPoint, Topology};
    /// use fem_core::quadrature::gauss_tensor;
    /// use fem_core::solid::{SolidMesh, SolidModel};
    /// use fem_core::{Component, ElementKind, Material, Supports};
    /// use std::sync::{Arc, OnceLock};
    ///
    /// #[derive(Debug)]
    /// struct MyHex;
    /// impl Element<3> for MyHex {
    ///     fn node_count(&self) -> usize { 8 }
    ///     fn shape(&self, xi: [f64; 3], n: &mut [f64], dn: &mut [[f64; 3]]) {
    ///         Hex8.shape(xi, n, dn)
    ///     }
    ///     fn stiffness_rule(&self, _: &(), _: &[[f64; 3]]) -> &[QuadPoint<3>] {
    ///         static RULE: OnceLock<Vec<QuadPoint<3>>> = OnceLock::new();
    ///         RULE.get_or_init(|| gauss_tensor::<3>(3))
    ///     }
    ///     fn load_rule(&self, s: &()) -> &[QuadPoint<3>] { Hex8.load_rule(s) }
    ///     fn topology(&self) -> Topology { Hex8.topology() }
    /// }
    ///
    /// let nodes = vec![
    ///     [0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [2.0, 1.0, 0.0], [0.0, 1.0, 0.0],
    ///     [0.0, 0.0, 1.0], [2.0, 0.0, 1.0], [2.0, 1.0, 1.0], [0.0, 1.0, 1.0],
    /// ];
    /// let mesh = SolidMesh::new(nodes, ElementKind::Hex8, (0..8).collect(), vec![])?;
    /// let mut supports = Supports::new();
    /// for c in [Component::X, Component::Y, Component::Z] {
    ///     supports.fix(&[0, 1, 2, 3], c);
    /// }
    /// let material = [(0, Material::new(100.0, 0.3, 0.0)?)];
    /// let built_in = SolidModel::new(mesh.clone(), &material, supports.clone())?;
    /// let mine = SolidModel::new(mesh, &material, supports)?.with_element(0, Arc::new(MyHex))?;
    /// let (a, b) = (built_in.stiffness().val(), mine.stiffness().val());
    /// let scale = a.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    /// assert!(a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-12 * scale));
    /// # Ok::<(), fem_core::FemError>(())
    /// ```
    pub fn with_element(
        mut self,
        region: u32,
        element: Arc<dyn Element<D>>,
    ) -> Result<Self, FemError> {
        let nodes = self.mesh.built_in_element().node_count();
        self.elements
            .insert(region, element, self.mesh.regions(), nodes)?;
        self.assemble_and_factor()?;
        Ok(self)
    }

    /// The element that computes element `e`: the user's for its region, else the built-in
    /// one of the mesh's kind.
    pub(crate) fn element_at(&self, e: usize) -> &dyn Element<D> {
        self.elements
            .get(self.mesh.regions()[e], self.mesh.built_in_element())
    }
}
