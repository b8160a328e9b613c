//! What the one model needs per dimension beyond the mesh: the outward normals of the
//! boundary at the nodes, known in the plane (the contact coupling's facing check) and not
//! computed in space.

use crate::mesh::Mesh;
use crate::space::{Dim, Space};

/// The dimensions a model is built in (sealed through [`Space`]).
pub trait ModelSpace<const D: usize>: Space
where
    Dim<D>: Space,
{
    /// The unit outward normal of the boundary at every node of `mesh`, where it is known.
    fn outward_normals(mesh: &Mesh<D>) -> Vec<Option<[f64; D]>>;
}

impl ModelSpace<2> for Dim<2> {
    fn outward_normals(mesh: &Mesh<2>) -> Vec<Option<[f64; 2]>> {
        mesh.outward_normals()
    }
}

impl ModelSpace<3> for Dim<3> {
    /// Not computed for 3D meshes (the contact coupling then skips its facing check).
    fn outward_normals(mesh: &Mesh<3>) -> Vec<Option<[f64; 3]>> {
        vec![None; mesh.node_count()]
    }
}
