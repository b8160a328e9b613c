//! Reading meshes from Gmsh `.msh` files, format 4.1 (ASCII or binary), once for both
//! dimensions: [`read_mesh`] and [`parse_mesh`] make a [`Mesh<D>`](Mesh) of the file's
//! elements of dimension `D` ([`read_msh`] and [`read_msh_3d`] name them for `D = 2` and 3).
//!
//! The file is parsed by the [`mshio`] crate behind checks of its own (`file`); the mesh is
//! built once for both dimensions (`build`); what differs per dimension is a table (`plane`,
//! `solid`): the element types, the node order and orientation, and how the physical groups
//! of lower dimension become sets.
//!
//! - **Nodes.** Only the nodes used by the elements of the mesh's dimension are kept, numbered
//!   `0..n` in increasing Gmsh tag order (an unused node would be a free, unloaded degree of
//!   freedom). A 2D mesh ignores `z`: it is projected onto the plane `z = 0`.
//! - **Elements** of one kind per file, with the region of their entity: its first physical
//!   tag, or 0 if it has none (the names of physical surfaces in 2D, volumes in 3D, are not
//!   kept).
//!   - *2D*: 3-node (Gmsh type 2) or 6-node (type 9) triangles; 4-node (type 3), 8-node
//!     (type 16) and 9-node (type 10) quadrangles, in the same node order as VTK's 9, 23 and
//!     28. Clockwise elements are mirrored (triangles: corners 1 ↔ 2 and the mid-side nodes
//!     with them), so either orientation of the surface is accepted.
//!   - *3D*: 4-node (type 4) or 10-node (type 11) tetrahedra; 8-node (type 5) or 20-node
//!     (type 17) hexahedra. Gmsh numbers the last two mid-edge nodes of the 10-node
//!     tetrahedron the other way round from [`ElementKind`](crate::mesh::ElementKind) (Gmsh's node 8 is on edge 2–3, node
//!     9 on edge 1–3: checked on files written by Gmsh 4.8.4), so they are swapped. Gmsh
//!     numbers the mid-edge nodes of the 20-node hexahedron by edge 0–1, 0–3, 0–4, 1–2, 1–5,
//!     2–3, 2–6, 3–7, 4–5, 4–7, 5–6, 6–7, VTK (cell 25, our order) by 0–1, 1–2, 2–3, 3–0, 4–5,
//!     5–6, 6–7, 7–4, 0–4, 1–5, 2–6, 3–7: the reader maps them
//!     ([`crate::element::hex20::GMSH_TO_LOCAL`]). Left-handed elements are mirrored
//!     (tetrahedra: corners 2 ↔ 3 and the mid-edge nodes with them; hexahedra: bottom ↔ top).
//! - **Physical curves in 2D** (dimension 1) become an edge set and a node set of the same
//!   name. Each line element (type 1 or 8) is matched to an element side by its two end
//!   nodes; where two elements share that side (an interior curve), the one to the left of the
//!   line's direction is taken. The node set holds all the nodes of those sides, mid-side
//!   nodes included, **ordered along the curve** ([`Mesh::add_curve_node_set`], rules in
//!   [`crate::mesh::curve`]); a curve that branches or is in pieces keeps its nodes sorted,
//!   and [`Mesh::curve_order`] says why (a contact target refuses it).
//! - **Physical surfaces in 3D** (dimension 2) become a face set and a node set of the same
//!   name. Each triangle (type 2 or 9) or quadrangle (type 3 or 16) is matched to an element
//!   face by its corners; where two elements share that face (an interior surface), the one
//!   the surface element's normal (right-hand rule on its corners) points out of is taken. A
//!   6-node triangle on a P2 mesh must have the face's mid-edge nodes. The node set holds all
//!   the nodes of those faces. Physical curves in 3D become node sets holding their nodes.
//! - **Physical points** (dimension 0, type 15) become node sets.
//! - **Names** come from `$PhysicalNames`; an unnamed group is called `surface_<tag>`,
//!   `curve_<tag>` or `point_<tag>`. Groups of different dimensions with one name share one
//!   node set (in 2D, sorted by index, as it is no longer one curve).
//!
//! Lower elements outside physical groups are ignored. Any other element type (prisms,
//! pyramids, higher orders, …) is [`FemError::Unsupported`].

mod build;
mod file;
mod plane;
mod solid;

use crate::error::FemError;
use crate::mesh::{Mesh, SolidMesh};
use crate::space::{Dim, Space};
use build::{Reader, build};
use std::path::Path;

/// Reads a Gmsh `.msh` 4.1 file holding a mesh of dimension `D` (see the
/// [module docs](self)).
///
/// # Errors
/// - [`FemError::Io`] if the file cannot be read or is not valid MSH 4.1 (with the line of
///   the first error where it is known);
/// - [`FemError::Unsupported`] for another format version, an element type the dimension
///   does not read, mixed element kinds, no element of the dimension, a lower element of a
///   physical group that is not a side or face of an element, a node of a physical group that
///   no element uses, or a negative physical tag;
/// - the errors of [`Mesh::new`] (e.g. a degenerate element), told with the file's tags.
///
/// # Examples
/// ```no_run
/// let mesh = fem_core::gmsh::read_mesh::<3>(std::path::Path::new("block.msh"))?;
/// println!("{} elements", mesh.element_count());
/// # Ok::<(), fem_core::FemError>(())
/// ```
pub fn read_mesh<const D: usize>(path: &Path) -> Result<Mesh<D>, FemError>
where
    Dim<D>: Space,
{
    let origin = path.display().to_string();
    let bytes =
        std::fs::read(path).map_err(|e| FemError::io(origin.clone(), "cannot read the file", e))?;
    parse(&bytes, &origin)
}

/// Parses the bytes of a Gmsh `.msh` 4.1 file holding a mesh of dimension `D` (see
/// [`read_mesh`]). Errors about the data name the file as `<msh>`.
///
/// # Errors
/// As [`read_mesh`].
///
/// # Examples
/// ```
/// let msh = "$MeshFormat\n4.1 0 8\n$EndMeshFormat
/// $Nodes\n1 4 1 4\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n$EndNodes
/// $Elements\n1 1 1 1\n3 1 4 1\n1 1 3 2 4\n$EndElements\n";
/// let mesh = fem_core::gmsh::parse_mesh::<3>(msh.as_bytes())?;
/// assert_eq!(mesh.element_count(), 1);
/// // the left-handed tetrahedron (1, 3, 2, 4) is read as (1, 3, 4, 2)
/// assert_eq!(mesh.element(0), &[0, 2, 3, 1]);
/// # Ok::<(), fem_core::FemError>(())
/// ```
pub fn parse_mesh<const D: usize>(bytes: &[u8]) -> Result<Mesh<D>, FemError>
where
    Dim<D>: Space,
{
    parse(bytes, "<msh>")
}

/// Reads a Gmsh `.msh` 4.1 file holding a 2D mesh: [`read_mesh`] with `D = 2`.
///
/// # Errors
/// As [`read_mesh`].
///
/// # Examples
/// ```no_run
/// let mesh = fem_core::gmsh::read_msh(std::path::Path::new("block.msh")).unwrap();
/// println!("{} triangles", mesh.element_count());
/// ```
pub fn read_msh(path: &Path) -> Result<Mesh, FemError> {
    read_mesh(path)
}

/// Parses the bytes of a Gmsh `.msh` 4.1 file holding a 2D mesh: [`parse_mesh`] with `D = 2`.
///
/// # Errors
/// As [`read_mesh`].
///
/// # Examples
/// ```
/// let msh = "$MeshFormat\n4.1 0 8\n$EndMeshFormat
/// $Nodes\n1 3 1 3\n2 1 0 3\n1\n2\n3\n0 0 0\n1 0 0\n0 1 0\n$EndNodes
/// $Elements\n1 1 1 1\n2 1 2 1\n1 1 2 3\n$EndElements\n";
/// let mesh = fem_core::gmsh::parse_msh(msh.as_bytes()).unwrap();
/// assert_eq!(mesh.element_count(), 1);
/// assert_eq!(mesh.regions(), &[0]);
/// ```
pub fn parse_msh(bytes: &[u8]) -> Result<Mesh, FemError> {
    parse_mesh(bytes)
}

/// Reads a Gmsh `.msh` 4.1 file holding a 3D mesh: [`read_mesh`] with `D = 3`.
///
/// # Errors
/// As [`read_mesh`].
///
/// # Examples
/// ```no_run
/// let mesh = fem_core::gmsh::read_msh_3d(std::path::Path::new("block.msh"))?;
/// println!("{} tetrahedra", mesh.element_count());
/// # Ok::<(), fem_core::FemError>(())
/// ```
pub fn read_msh_3d(path: &Path) -> Result<SolidMesh, FemError> {
    read_mesh(path)
}

/// Parses the bytes of a Gmsh `.msh` 4.1 file holding a 3D mesh: [`parse_mesh`] with `D = 3`.
///
/// # Errors
/// As [`read_mesh`].
///
/// # Examples
/// ```
/// let msh = "$MeshFormat\n4.1 0 8\n$EndMeshFormat
/// $Nodes\n1 4 1 4\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n$EndNodes
/// $Elements\n1 1 1 1\n3 1 4 1\n1 1 2 3 4\n$EndElements\n";
/// let mesh = fem_core::gmsh::parse_msh_3d(msh.as_bytes())?;
/// assert_eq!(mesh.kind(), fem_core::mesh::ElementKind::Tet4);
/// # Ok::<(), fem_core::FemError>(())
/// ```
pub fn parse_msh_3d(bytes: &[u8]) -> Result<SolidMesh, FemError> {
    parse_mesh(bytes)
}

fn parse<const D: usize>(bytes: &[u8], origin: &str) -> Result<Mesh<D>, FemError>
where
    Dim<D>: Space,
{
    let (file, names) = file::parse_file(bytes, origin)?;
    build(file, &names, origin, reader::<D>())
}

/// The table of dimension `D`.
fn reader<const D: usize>() -> &'static Reader<D>
where
    Dim<D>: Space,
{
    let table: &'static dyn std::any::Any = match D {
        2 => &plane::PLANE,
        _ => &solid::SOLID,
    };
    // `Space` is sealed: `D` is 2 or 3, and the table of `D` is a `Reader<D>`.
    table
        .downcast_ref()
        .expect("a Gmsh table for each dimension of `Space`")
}
