//! The bridge between [`ElasticModel`](super::ElasticModel) and the mesh of each dimension
//! ([`Mesh`] in the plane, [`SolidMesh`] in space): the few accessors the model reads, so
//! that the model is written once over `D`. When the two meshes become one generic type, this
//! file reduces to that type.

use crate::element::Element;
use crate::error::FemError;
use crate::mesh::Mesh;
use crate::solid::SolidMesh;
use crate::space::{Dim, Space};
use std::fmt::Debug;

/// What a model reads from its mesh in dimension `D` (see the module docs).
pub trait ModelMesh<const D: usize>: Clone + Debug + Send + Sync + 'static
where
    Dim<D>: Space,
{
    /// Node coordinates.
    fn nodes(&self) -> &[[f64; D]];
    /// Number of nodes.
    fn node_count(&self) -> usize {
        self.nodes().len()
    }
    /// Number of elements.
    fn element_count(&self) -> usize;
    /// The nodes of element `e`.
    fn element(&self, e: usize) -> &[usize];
    /// The region of every element.
    fn regions(&self) -> &[u32];
    /// The built-in element of the mesh's kind.
    fn built_in(&self) -> &'static dyn Element<D>;
    /// The nodes of a named node set.
    ///
    /// # Errors
    /// [`FemError::UnknownSet`] if there is no such set.
    fn node_set(&self, name: &str) -> Result<&[usize], FemError>;
    /// The unit outward normal of the boundary at every node, where the mesh knows it.
    fn outward_normals(&self) -> Vec<Option<[f64; D]>>;
}

/// The dimensions a model is built in, each with its mesh type (sealed through [`Space`]).
pub trait ModelSpace<const D: usize>: Space
where
    Dim<D>: Space,
{
    /// The mesh of this dimension.
    type Mesh: ModelMesh<D>;
}

impl ModelSpace<2> for Dim<2> {
    type Mesh = Mesh;
}

impl ModelSpace<3> for Dim<3> {
    type Mesh = SolidMesh;
}

impl ModelMesh<2> for Mesh {
    fn nodes(&self) -> &[[f64; 2]] {
        Mesh::nodes(self)
    }
    fn element_count(&self) -> usize {
        Mesh::element_count(self)
    }
    fn element(&self, e: usize) -> &[usize] {
        Mesh::element(self, e)
    }
    fn regions(&self) -> &[u32] {
        Mesh::regions(self)
    }
    fn built_in(&self) -> &'static dyn Element<2> {
        self.kind().element()
    }
    fn node_set(&self, name: &str) -> Result<&[usize], FemError> {
        Mesh::node_set(self, name)
    }
    fn outward_normals(&self) -> Vec<Option<[f64; 2]>> {
        Mesh::outward_normals(self)
    }
}

impl ModelMesh<3> for SolidMesh {
    fn nodes(&self) -> &[[f64; 3]] {
        SolidMesh::nodes(self)
    }
    fn element_count(&self) -> usize {
        SolidMesh::element_count(self)
    }
    fn element(&self, e: usize) -> &[usize] {
        SolidMesh::element(self, e)
    }
    fn regions(&self) -> &[u32] {
        SolidMesh::regions(self)
    }
    fn built_in(&self) -> &'static dyn Element<3> {
        self.kind().element()
    }
    fn node_set(&self, name: &str) -> Result<&[usize], FemError> {
        SolidMesh::node_set(self, name)
    }
    /// Not computed for 3D meshes (the contact coupling then skips its facing check).
    fn outward_normals(&self) -> Vec<Option<[f64; 3]>> {
        vec![None; self.node_count()]
    }
}
