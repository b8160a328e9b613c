//! The element kinds of a mesh: [`ElementKind`] in the plane, [`SolidKind`] in 3D, and what
//! the dimension-generic [`Mesh`](super::Mesh) needs of them ([`CellKind`], [`Kinds`]).

use crate::element::{Element, Hex8, Hex20, Quad4, Quad8, Quad9, Tet4, Tet10, Tri3, Tri6};
use crate::space::{CellKind, Dim, Kinds, sealed::Sealed};
use std::any::Any;

/// The element family of a mesh.
///
/// Node order (Gmsh's and VTK's): triangles have corners `0, 1, 2` counter-clockwise, then for
/// P2 the mid-edge nodes `3` (edge 0–1), `4` (edge 1–2), `5` (edge 2–0); quadrilaterals have
/// corners `0..4` counter-clockwise, then for Quad8/Quad9 the mid-side nodes `4` (0–1),
/// `5` (1–2), `6` (2–3), `7` (3–0), and for Quad9 the centre `8`. The element of each kind is
/// [`ElementKind::element`].
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
}

impl ElementKind {
    /// Every kind, for tests and messages.
    pub const ALL: [ElementKind; 5] = [
        ElementKind::Tri3,
        ElementKind::Tri6,
        ElementKind::Quad4,
        ElementKind::Quad8,
        ElementKind::Quad9,
    ];

    /// The built-in element of this kind.
    #[inline]
    pub fn element(self) -> &'static dyn Element<2> {
        PLANE[self as usize]
    }

    /// Nodes per element: 3, 6, 4, 8 or 9.
    #[inline]
    pub fn node_count(self) -> usize {
        match self {
            ElementKind::Tri3 => 3,
            ElementKind::Tri6 => 6,
            ElementKind::Quad4 => 4,
            ElementKind::Quad8 => 8,
            ElementKind::Quad9 => 9,
        }
    }

    /// Corners per element: 3 or 4.
    #[inline]
    pub fn corner_count(self) -> usize {
        self.side_count()
    }

    /// Sides per element: 3 (triangles) or 4 (quadrilaterals).
    #[inline]
    pub fn side_count(self) -> usize {
        match self {
            ElementKind::Tri3 | ElementKind::Tri6 => 3,
            _ => 4,
        }
    }

    /// Whether the sides carry a mid-side node (3-node sides).
    #[inline]
    pub fn is_quadratic(self) -> bool {
        matches!(
            self,
            ElementKind::Tri6 | ElementKind::Quad8 | ElementKind::Quad9
        )
    }

    /// The local nodes of side `side ∈ 0..side_count()`, from its first corner to its second
    /// (the body on its left), with the mid-side node last for quadratic kinds (`[a, b]` or
    /// `[a, b, m]`).
    ///
    /// # Panics
    /// If `side >= self.side_count()`.
    #[inline]
    #[track_caller]
    pub fn side_nodes(self, side: usize) -> &'static [usize] {
        self.element().topology().sides[side]
    }
}

/// The element family of a 3D mesh.
///
/// Node order: tetrahedra have corners `0, 1, 2, 3` with `(x₁ − x₀, x₂ − x₀, x₃ − x₀)` a
/// right-handed triad (positive volume), then for P2 the mid-edge nodes `4` (edge 0–1), `5`
/// (1–2), `6` (2–0), `7` (0–3), `8` (1–3), `9` (2–3): VTK's order. Gmsh numbers the last two the
/// other way round; [`crate::gmsh`] swaps them on reading. Hexahedra have corners
/// `0..4` counter-clockwise seen from above, then `4..8` above them, then for Hex20 the
/// mid-edge nodes in VTK's order ([`crate::element::hex20`]; Gmsh's order is mapped on reading).
/// The element of each kind is [`SolidKind::element`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum SolidKind {
    /// Linear 4-node tetrahedron.
    Tet4,
    /// Quadratic 10-node isoparametric tetrahedron.
    Tet10,
    /// Trilinear 8-node hexahedron.
    Hex8,
    /// Quadratic 20-node serendipity hexahedron.
    Hex20,
}

impl SolidKind {
    /// Every kind, for tests and messages.
    pub const ALL: [SolidKind; 4] = [
        SolidKind::Tet4,
        SolidKind::Tet10,
        SolidKind::Hex8,
        SolidKind::Hex20,
    ];

    /// The built-in element of this kind.
    #[inline]
    pub fn element(self) -> &'static dyn Element<3> {
        SOLID[self as usize]
    }

    /// Nodes per element: 4, 10, 8 or 20.
    #[inline]
    pub fn node_count(self) -> usize {
        match self {
            SolidKind::Tet4 => 4,
            SolidKind::Tet10 => 10,
            SolidKind::Hex8 => 8,
            SolidKind::Hex20 => 20,
        }
    }

    /// Corners per element: 4 or 8.
    #[inline]
    pub fn corner_count(self) -> usize {
        match self {
            SolidKind::Tet4 | SolidKind::Tet10 => 4,
            _ => 8,
        }
    }

    /// Faces per element: 4 (triangles) or 6 (quadrilaterals).
    #[inline]
    pub fn face_count(self) -> usize {
        match self {
            SolidKind::Tet4 | SolidKind::Tet10 => 4,
            _ => 6,
        }
    }

    /// Corners per face: 3 or 4.
    #[inline]
    pub fn face_corner_count(self) -> usize {
        match self {
            SolidKind::Tet4 | SolidKind::Tet10 => 3,
            _ => 4,
        }
    }

    /// The local nodes of face `face ∈ 0..face_count()`, corners counter-clockwise seen from
    /// outside, then for quadratic kinds the mid-edge nodes of the face's edges (c0–c1, c1–c2,
    /// …): the node order of a 3/6-node triangle or a 4/8-node quadrilateral. Tetrahedra:
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
    /// If `face >= self.face_count()`.
    #[inline]
    #[track_caller]
    pub fn face_nodes(self, face: usize) -> &'static [usize] {
        self.element().topology().sides[face]
    }
}

/// The built-in elements, in the order of the kinds ([`ElementKind::ALL`], [`SolidKind::ALL`]).
static PLANE: [&dyn Element<2>; 5] = [&Tri3, &Tri6, &Quad4, &Quad8, &Quad9];
static SOLID: [&dyn Element<3>; 4] = [&Tet4, &Tet10, &Hex8, &Hex20];

impl Sealed for ElementKind {}
impl Sealed for SolidKind {}

impl Kinds for Dim<2> {
    type Kind = ElementKind;
}

impl Kinds for Dim<3> {
    type Kind = SolidKind;
}

impl CellKind for ElementKind {
    const FACET: &'static str = "edge";
    #[inline]
    fn node_count(self) -> usize {
        ElementKind::node_count(self)
    }
    #[inline]
    fn corner_count(self) -> usize {
        ElementKind::corner_count(self)
    }
    #[inline]
    fn facet_count(self) -> usize {
        self.side_count()
    }
    #[inline]
    fn facet_corner_count(self) -> usize {
        2
    }
    #[inline]
    fn facet_nodes(self, facet: usize) -> &'static [usize] {
        self.side_nodes(facet)
    }
    #[inline]
    fn element_any(self) -> &'static dyn Any {
        &PLANE[self as usize]
    }
}

impl CellKind for SolidKind {
    const FACET: &'static str = "face";
    #[inline]
    fn node_count(self) -> usize {
        SolidKind::node_count(self)
    }
    #[inline]
    fn corner_count(self) -> usize {
        SolidKind::corner_count(self)
    }
    #[inline]
    fn facet_count(self) -> usize {
        self.face_count()
    }
    #[inline]
    fn facet_corner_count(self) -> usize {
        self.face_corner_count()
    }
    #[inline]
    fn facet_nodes(self, facet: usize) -> &'static [usize] {
        self.face_nodes(facet)
    }
    #[inline]
    fn element_any(self) -> &'static dyn Any {
        &SOLID[self as usize]
    }
}
