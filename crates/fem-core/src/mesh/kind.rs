//! The element kinds of a mesh, of both dimensions: one [`ElementKind`] (triangles and
//! quadrilaterals in the plane, tetrahedra and hexahedra in space), each with its
//! [`dimension`](ElementKind::dimension), counts, facets and built-in element.

use crate::element::{
    Element, Hex8, Hex20, Quad4, Quad8, Quad9, Tet4, Tet10, Topology, Tri3, Tri6,
};
use crate::error::FemError;
use crate::space::{Dim, Space};
use std::any::Any;

/// The element family of a mesh, in the plane or in space ([`ElementKind::dimension`]).
///
/// Node order (Gmsh's and VTK's):
/// - triangles have corners `0, 1, 2` counter-clockwise, then for P2 the mid-edge nodes `3`
///   (edge 0–1), `4` (edge 1–2), `5` (edge 2–0); quadrilaterals have corners `0..4`
///   counter-clockwise, then for Quad8/Quad9 the mid-side nodes `4` (0–1), `5` (1–2),
///   `6` (2–3), `7` (3–0), and for Quad9 the centre `8`;
/// - tetrahedra have corners `0, 1, 2, 3` with `(x₁ − x₀, x₂ − x₀, x₃ − x₀)` a right-handed
///   triad (positive volume), then for P2 the mid-edge nodes `4` (edge 0–1), `5` (1–2),
///   `6` (2–0), `7` (0–3), `8` (1–3), `9` (2–3): VTK's order (Gmsh numbers the last two the
///   other way round; [`crate::gmsh`] swaps them on reading); hexahedra have corners `0..4`
///   counter-clockwise seen from above, then `4..8` above them, then for Hex20 the mid-edge
///   nodes in VTK's order ([`crate::element::hex20`]; Gmsh's order is mapped on reading).
///
/// A mesh of dimension `D` takes the kinds of that dimension only; [`Mesh::new`](crate::Mesh::new)
/// and the generators refuse the others with [`FemError::KindDimension`].
///
/// # Examples
/// ```
/// use fem_core::ElementKind;
/// assert_eq!(ElementKind::Quad8.dimension(), 2);
/// assert_eq!(ElementKind::Tet10.node_count(), 10);
/// assert_eq!(ElementKind::Hex8.topology().gmsh_type, 5);
/// assert_eq!(ElementKind::Tet4.element::<3>()?.node_count(), 4);
/// assert!(ElementKind::Tet4.element::<2>().is_err());
/// # Ok::<(), fem_core::FemError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum ElementKind {
    /// Linear 3-node triangle.
    Tri3,
    /// Quadratic 6-node isoparametric triangle.
    Tri6,
    /// Bilinear 4-node quadrilateral.
    Quad4,
    /// Quadratic 8-node serendipity quadrilateral.
    Quad8,
    /// Biquadratic 9-node Lagrange quadrilateral.
    Quad9,
    /// Linear 4-node tetrahedron.
    Tet4,
    /// Quadratic 10-node isoparametric tetrahedron.
    Tet10,
    /// Trilinear 8-node hexahedron.
    Hex8,
    /// Quadratic 20-node serendipity hexahedron.
    Hex20,
}

/// The former name of the 3D kinds, kept so that `SolidKind::Tet4` still compiles: write
/// [`ElementKind`].
pub type SolidKind = ElementKind;

/// The built-in elements, in the order of the kinds ([`ElementKind::ALL`]): the plane ones,
/// then the solid ones.
static PLANE: [&dyn Element<2>; 5] = [&Tri3, &Tri6, &Quad4, &Quad8, &Quad9];
static SOLID: [&dyn Element<3>; 4] = [&Tet4, &Tet10, &Hex8, &Hex20];

impl ElementKind {
    /// Every kind, the plane ones first, for tests and messages.
    pub const ALL: [ElementKind; 9] = [
        ElementKind::Tri3,
        ElementKind::Tri6,
        ElementKind::Quad4,
        ElementKind::Quad8,
        ElementKind::Quad9,
        ElementKind::Tet4,
        ElementKind::Tet10,
        ElementKind::Hex8,
        ElementKind::Hex20,
    ];

    /// The dimension of the kind's elements: 2 (triangles, quadrilaterals) or 3 (tetrahedra,
    /// hexahedra).
    #[inline]
    pub fn dimension(self) -> usize {
        match self {
            ElementKind::Tri3
            | ElementKind::Tri6
            | ElementKind::Quad4
            | ElementKind::Quad8
            | ElementKind::Quad9 => 2,
            ElementKind::Tet4 | ElementKind::Tet10 | ElementKind::Hex8 | ElementKind::Hex20 => 3,
        }
    }

    /// `Ok(self)` if the kind's dimension is `D`.
    pub(crate) fn of_dimension<const D: usize>(self) -> Result<Self, FemError> {
        if self.dimension() == D {
            Ok(self)
        } else {
            Err(self.not_of_dimension(D))
        }
    }

    /// The error of a kind given where one of `dimension` is needed.
    fn not_of_dimension(self, dimension: usize) -> FemError {
        FemError::KindDimension {
            kind: format!("{self:?}"),
            kind_dimension: self.dimension(),
            dimension,
        }
    }

    /// The built-in element of this kind, in dimension `D` (`kind.element::<2>()`).
    ///
    /// # Errors
    /// [`FemError::KindDimension`] if the kind is not of dimension `D`.
    pub fn element<const D: usize>(self) -> Result<&'static dyn Element<D>, FemError>
    where
        Dim<D>: Space,
    {
        let any: &'static dyn Any = match PLANE.get(self as usize) {
            Some(plane) => plane,
            None => &SOLID[self as usize - PLANE.len()],
        };
        any.downcast_ref::<&'static dyn Element<D>>()
            .copied()
            .ok_or_else(|| self.not_of_dimension(D))
    }

    /// The topology of the kind's element: corners, facets, VTK cell type, Gmsh type.
    #[inline]
    pub fn topology(self) -> Topology {
        match PLANE.get(self as usize) {
            Some(plane) => plane.topology(),
            None => SOLID[self as usize - PLANE.len()].topology(),
        }
    }

    /// Nodes per element: 3, 6, 4, 8 or 9 in the plane, 4, 10, 8 or 20 in space.
    #[inline]
    pub fn node_count(self) -> usize {
        match self {
            ElementKind::Tri3 => 3,
            ElementKind::Tri6 => 6,
            ElementKind::Quad4 => 4,
            ElementKind::Quad8 => 8,
            ElementKind::Quad9 => 9,
            ElementKind::Tet4 => 4,
            ElementKind::Tet10 => 10,
            ElementKind::Hex8 => 8,
            ElementKind::Hex20 => 20,
        }
    }

    /// Corners per element (they come first in the element's node order): 3 or 4 in the
    /// plane, 4 or 8 in space.
    #[inline]
    pub fn corner_count(self) -> usize {
        self.topology().corners
    }

    /// Whether the element is quadratic (its edges carry a mid-edge node).
    #[inline]
    pub fn is_quadratic(self) -> bool {
        matches!(
            self,
            ElementKind::Tri6
                | ElementKind::Quad8
                | ElementKind::Quad9
                | ElementKind::Tet10
                | ElementKind::Hex20
        )
    }

    /// Facets per element: the sides of a 2D element (3 or 4), the faces of a 3D one (4 or 6).
    #[inline]
    pub fn facet_count(self) -> usize {
        self.topology().sides.len()
    }

    /// Corners per facet (they come first in [`ElementKind::facet_nodes`]): 2 in the plane,
    /// 3 (tetrahedra) or 4 (hexahedra) in space.
    #[inline]
    pub fn facet_corner_count(self) -> usize {
        match self {
            ElementKind::Tet4 | ElementKind::Tet10 => 3,
            ElementKind::Hex8 | ElementKind::Hex20 => 4,
            _ => 2,
        }
    }

    /// The local nodes of facet `facet ∈ 0..facet_count()`.
    ///
    /// A 2D side runs from its first corner to its second (the body on its left), with the
    /// mid-side node last for quadratic kinds (`[a, b]` or `[a, b, m]`). A 3D face lists its
    /// corners counter-clockwise seen from outside, then for quadratic kinds the mid-edge
    /// nodes of the face's edges (c0–c1, c1–c2, …): the node order of a 3/6-node triangle or a
    /// 4/8-node quadrilateral. Tetrahedra:
    ///
    /// ```text
    /// face 0: 0 2 1 (opposite corner 3)    face 2: 1 2 3 (opposite corner 0)
    /// face 1: 0 1 3 (opposite corner 2)    face 3: 0 3 2 (opposite corner 1)
    /// ```
    ///
    /// hexahedra: faces `ζ = −1, η = −1, ξ = 1, η = 1, ξ = −1, ζ = 1`
    /// ([`crate::element::hex8::FACES`]).
    ///
    /// # Panics
    /// If `facet >= self.facet_count()`.
    #[inline]
    #[track_caller]
    pub fn facet_nodes(self, facet: usize) -> &'static [usize] {
        self.topology().sides[facet]
    }
}
