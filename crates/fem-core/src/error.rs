//! Errors of `fem-core`.

use crate::component::Component;
use std::error::Error;
use std::fmt;
use std::sync::Arc;

/// Error of `fem-core`: invalid mesh, material, boundary condition or load, or a failure of
/// the sparse factorisation.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum FemError {
    /// A real parameter is NaN, infinite or outside its admissible range.
    #[error("invalid parameter `{name}` = {value:?}: expected {expected}")]
    InvalidParameter {
        /// Name of the parameter (`young`, `poisson`, `thickness`, …).
        name: &'static str,
        /// The rejected value.
        value: f64,
        /// What was expected, in words.
        expected: &'static str,
    },
    /// A node coordinate is NaN or infinite.
    #[error("node {node} has a non-finite coordinate ({x:?}, {y:?})")]
    NonFiniteNode {
        /// Node index.
        node: usize,
        /// First coordinate (x or r).
        x: f64,
        /// Second coordinate (y or z).
        y: f64,
    },
    /// Something other than an element (a node set, a support, a nodal force) refers to a
    /// node that does not exist.
    #[error("{what} refers to node {node}, but the mesh has {node_count} nodes")]
    UnknownNode {
        /// What refers to it: "a node set", "a support", "a nodal force".
        what: &'static str,
        /// The offending node index.
        node: usize,
        /// Number of nodes of the mesh.
        node_count: usize,
    },
    /// An element's stiffness is not finite: the product of its material's Young modulus and
    /// its size overflows (or a parameter is absurd, e.g. `young = 1e308`).
    #[error(
        "the stiffness of element {element} (region {region}) is not finite: its Young modulus \
         {young:e} and its size overflow"
    )]
    NonFiniteStiffness {
        /// Element index.
        element: usize,
        /// Its region.
        region: u32,
        /// The region's Young modulus.
        young: f64,
    },
    /// A solve met a non-finite value: a load factor, a load or a prescribed value, or a
    /// displacement that overflowed.
    #[error("{what} is not finite ({value:?}){}", at_node(.node))]
    NonFiniteSolve {
        /// What was not finite: "load factor", "right-hand side", "displacement".
        what: &'static str,
        /// The node and component concerned, when known.
        node: Option<(usize, crate::Component)>,
        /// The value.
        value: f64,
    },
    /// A mesh without elements (nothing to assemble, nothing to solve).
    #[error("the mesh has no element ({node_count} nodes, an empty connectivity)")]
    EmptyMesh {
        /// The number of nodes given.
        node_count: usize,
    },
    /// Two prescriptions of one degree of freedom with different values.
    #[error(
        "component {component} of node {node} is prescribed twice, as {first:?} and as \
         {second:?}: a degree of freedom takes one prescribed value"
    )]
    ConflictingPrescription {
        /// The node.
        node: usize,
        /// Its component.
        component: Component,
        /// The value it had.
        first: f64,
        /// The other value asked for.
        second: f64,
    },
    /// A generator asked for more than it may build: refused before anything is allocated.
    #[error("{what}: {} exceeds the limit of {limit}", requested.map_or("more than usize::MAX".to_string(), |n| n.to_string()))]
    TooLarge {
        /// What was counted ("nodes of the generated mesh", "cells of a graded line").
        what: &'static str,
        /// The count asked for (`None` if it overflows `usize`).
        requested: Option<usize>,
        /// The limit.
        limit: usize,
    },
    /// An element refers to a node that does not exist.
    #[error("element {element} refers to node {node}, but the mesh has {node_count} nodes")]
    NodeOutOfRange {
        /// Element index.
        element: usize,
        /// The offending node index.
        node: usize,
        /// Number of nodes of the mesh.
        node_count: usize,
    },
    /// The connectivity array does not hold a whole number of elements.
    #[error(
        "connectivity of length {len} is not a multiple of {nodes_per_element} nodes per element"
    )]
    BadConnectivity {
        /// Length of the connectivity array.
        len: usize,
        /// Nodes per element of the mesh's kind.
        nodes_per_element: usize,
    },
    /// An element has zero (or nearly zero) area.
    #[error("element {element} is degenerate: signed area {area:e}")]
    DegenerateElement {
        /// Element index.
        element: usize,
        /// Its signed area (corner nodes).
        area: f64,
    },
    /// An element is inverted (clockwise corners, or a Jacobian that changes sign inside a
    /// curved P2 element).
    #[error("element {element} is inverted: Jacobian determinant {det_j:e} at a quadrature point")]
    InvertedElement {
        /// Element index.
        element: usize,
        /// The non-positive Jacobian determinant found.
        det_j: f64,
    },
    /// An axisymmetric mesh has a node at negative radius.
    #[error("axisymmetric mesh: node {node} has negative radius r = {r:?}")]
    NegativeRadius {
        /// Node index.
        node: usize,
        /// Its radius.
        r: f64,
    },
    /// An edge-set side names an element or a local side (`0..3`) that does not exist.
    #[error(
        "side {side} of element {element} does not exist (the mesh has {element_count} elements, sides 0..3)"
    )]
    InvalidSide {
        /// Element index.
        element: usize,
        /// Local side index.
        side: u8,
        /// Number of elements of the mesh.
        element_count: usize,
    },
    /// A boundary mass ([`BoundaryMass`](crate::boundary_mass::BoundaryMass)) was asked of
    /// no side or face.
    #[error("{what}: the list is empty, so there is no boundary to integrate over")]
    EmptyBoundary {
        /// Which boundary.
        what: &'static str,
    },
    /// The consistent mass of a boundary is singular: the sides or faces through `node` carry
    /// no weight (in axisymmetry, sides along the axis `r = 0`).
    #[error(
        "the boundary mass is singular at node {node}: the sides through it carry no weight \
         (in axisymmetry, a side along the axis r = 0)"
    )]
    SingularBoundaryMass {
        /// The node (mesh numbering) whose pivot failed.
        node: usize,
    },
    /// A node coordinate of a 3D mesh is NaN or infinite.
    #[error("node {node} has a non-finite coordinate {coords:?}")]
    NonFiniteNode3 {
        /// Node index.
        node: usize,
        /// Its coordinates `(x, y, z)`.
        coords: [f64; 3],
    },
    /// A tetrahedron has zero (or nearly zero) volume.
    #[error("element {element} is degenerate: signed volume {volume:e}")]
    DegenerateSolid {
        /// Element index.
        element: usize,
        /// Its signed volume (corner nodes).
        volume: f64,
    },
    /// A displacement component that the model's dimension does not have (`Z` in 2D).
    #[error("{what}{} is along {component}, but the model is {dimension}D", .node.map_or(String::new(), |n| format!(" at node {n}")))]
    InvalidComponent {
        /// What named it ("a support", "a tie", "a load").
        what: &'static str,
        /// The node, if one is concerned.
        node: Option<usize>,
        /// The component.
        component: Component,
        /// The model's dimension.
        dimension: usize,
    },
    /// An element kind of the other dimension: a 3D kind (`Tet4`) for a 2D mesh, a 2D kind
    /// (`Tri3`) for a 3D one.
    #[error("element kind {kind} is {kind_dimension}D, but the mesh is {dimension}D")]
    KindDimension {
        /// The kind given (`"Tet4"`).
        kind: String,
        /// Its dimension.
        kind_dimension: usize,
        /// The dimension of the mesh (or of the element asked for).
        dimension: usize,
    },
    /// A named node set or edge set is not in the mesh.
    #[error("the mesh has no {kind} set named `{name}`")]
    UnknownSet {
        /// "node" or "edge".
        kind: &'static str,
        /// The requested name.
        name: String,
    },
    /// A region id has no material.
    #[error("region {region} (element {element}) has no material")]
    MissingMaterial {
        /// Region id.
        region: u32,
        /// First element of that region.
        element: usize,
    },
    /// A model's mass was asked for (some region's material has a density) but the material
    /// of `region` has none ([`Material::with_density`](crate::Material::with_density)):
    /// a region without inertia would be a silent zero mass.
    #[error(
        "region {region} (element {element}) has no density: give every region's material one \
         (`Material::with_density`) or none"
    )]
    MissingDensity {
        /// Region id.
        region: u32,
        /// First element of that region.
        element: usize,
    },
    /// A region id that no element of the mesh has.
    #[error("no element of the mesh is in region {region}")]
    UnknownRegion {
        /// Region id.
        region: u32,
    },
    /// A tie ([`Supports::tie`](crate::Supports::tie)) that cannot be built.
    #[error("tie along {component}{}: {reason}", .node.map_or(String::new(), |n| format!(" at node {n}")))]
    InvalidTie {
        /// The tied component.
        component: Component,
        /// The node that shows the problem, if one does.
        node: Option<usize>,
        /// What is wrong.
        reason: &'static str,
    },
    /// A mesh entity or operation that this crate does not support (e.g. a quadrilateral in
    /// a `.msh`, joining meshes of different element kinds).
    #[error("unsupported mesh entity: {what}")]
    Unsupported {
        /// Description of the entity.
        what: String,
    },
    /// A slice passed to a function has the wrong length.
    #[error("length mismatch for `{what}`: expected {expected}, got {got}")]
    LengthMismatch {
        /// What the slice holds.
        what: &'static str,
        /// Expected length.
        expected: usize,
        /// Actual length.
        got: usize,
    },
    /// The stiffness of a model is not positive definite: a rigid-body mode (missing
    /// supports), a mechanism, or a node that no element connects. The Cholesky factorisation
    /// stopped at the dof `component` of node `node`: that dof takes part in the zero-energy
    /// motion (for a node that no element connects, it is that node).
    #[error(
        "stiffness matrix is not positive definite at node {node}, component {component} \
         (row {row} of the reduced system): the structure probably lacks supports against a \
         rigid-body motion of that dof, or no element connects that node"
    )]
    NotPositiveDefinite {
        /// Index of the node (in the mesh's numbering) whose dof had the first non-positive
        /// pivot.
        node: usize,
        /// Which of its displacement components.
        component: Component,
        /// The same dof as a row of the reduced system (the free-dof index of the model's
        /// [`DofMap`](crate::DofMap)), not faer's permuted pivot index.
        row: usize,
    },
    /// A matrix is not positive definite: its Cholesky factorisation met a non-positive
    /// pivot. [`SpdSolver::factor`](crate::SpdSolver::factor) reports the `row` of the matrix
    /// (in the matrix's own numbering, mapped back through the fill-reducing permutation); a
    /// faer factorisation converted with `From<faer::sparse::linalg::LltError>` cannot be
    /// mapped back (faer's index is in its permuted order), so `row` is `None`. A
    /// [`LinearElasticModel`](crate::LinearElasticModel) reports
    /// [`FemError::NotPositiveDefinite`] instead, with the node and component.
    #[error("matrix is not positive definite: non-positive Cholesky pivot{}", at_row(.row))]
    NonPositivePivot {
        /// Row (and column) of the matrix whose pivot failed, when known.
        row: Option<usize>,
    },
    /// A [`Structure`](crate::Structure) relies on a default method that cannot answer for it.
    /// (No default of fem-core's traits returns it since a floating body's modes and load
    /// became one capability, [`Floating`](crate::Floating); kept for implementers' own
    /// defaults.)
    #[error("the structure must implement `Structure::{method}`: {reason}")]
    MissingMethod {
        /// The method.
        method: &'static str,
        /// Why it is needed.
        reason: &'static str,
    },
    /// The sparse linear algebra failed for a reason other than definiteness (allocation,
    /// index overflow).
    #[error("sparse linear algebra failed: {detail}")]
    LinearAlgebra {
        /// faer's own description.
        detail: String,
    },
    /// Reading or writing a file failed, or a file's content is not valid. `detail` says
    /// what failed in words; the underlying error, when there is one (the operating system's
    /// I/O error, the VTK writer's error), is the [`source`](std::error::Error::source) and
    /// is not repeated in the message.
    #[error("{path}: {detail}")]
    Io {
        /// The file.
        path: String,
        /// What went wrong: `cannot read the file`, `cannot write the file`, …, or, for
        /// invalid content, the parser's message.
        detail: String,
        /// The underlying error; `None` when the content is invalid.
        #[source]
        source: Option<IoCause>,
    },
    /// An initial (e.g. geostatic) stress lies outside the yield surface of its material at a
    /// quadrature point (`yield_function > 0`): not a plastically admissible state.
    #[error(
        "the initial stress of region {region} is outside the yield surface at quadrature \
         point {point} of element {element} (yield function {yield_function:e} > 0): lower K0 \
         or raise the strength"
    )]
    OutsideYieldSurface {
        /// The region of the element.
        region: u32,
        /// The element.
        element: usize,
        /// The quadrature point, in the element's stiffness rule.
        point: usize,
        /// The yield function there (units of stress).
        yield_function: f64,
    },
    /// A Newton load path ([`crate::plastic::newton`]) could not converge at a load factor
    /// after the allowed step cuts; the structure keeps the last converged state (committed).
    #[error(
        "Newton did not converge at load factor {load_factor} after {cuts} step cuts; the \
         last converged state (load factor {converged_load_factor}) is kept"
    )]
    NotConverged {
        /// The load factor of the failed step.
        load_factor: f64,
        /// The load factor of the last converged (committed) state.
        converged_load_factor: f64,
        /// The step cuts made.
        cuts: usize,
        /// The residual history of every step tried.
        report: Box<crate::convergence::NewtonReport>,
    },
}

/// The underlying error of a [`FemError::Io`] (an I/O error, the VTK writer's error), shared
/// so that [`FemError`] stays `Clone`. Its `Display` is the wrapped error's; two causes are
/// equal when their messages are.
#[derive(Clone, Debug)]
pub struct IoCause(Arc<dyn Error + Send + Sync + 'static>);

impl IoCause {
    /// Wraps an error.
    pub fn new(e: impl Error + Send + Sync + 'static) -> Self {
        Self(Arc::new(e))
    }

    /// The wrapped error (e.g. to downcast it with `downcast_ref::<std::io::Error>()`).
    pub fn get_ref(&self) -> &(dyn Error + Send + Sync + 'static) {
        &*self.0
    }
}

impl fmt::Display for IoCause {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.0.fmt(f)
    }
}

impl Error for IoCause {
    fn source(&self) -> Option<&(dyn Error + 'static)> {
        self.0.source()
    }
}

impl PartialEq for IoCause {
    fn eq(&self, other: &Self) -> bool {
        self.0.to_string() == other.0.to_string()
    }
}

impl FemError {
    /// A [`FemError::Io`] for `path` with the underlying error `source`.
    pub(crate) fn io(
        path: impl Into<String>,
        detail: impl Into<String>,
        source: impl Error + Send + Sync + 'static,
    ) -> Self {
        FemError::Io {
            path: path.into(),
            detail: detail.into(),
            source: Some(IoCause::new(source)),
        }
    }

    /// A [`FemError::Io`] for invalid content of `path` (no underlying error).
    pub(crate) fn invalid_file(path: impl Into<String>, detail: impl Into<String>) -> Self {
        FemError::Io {
            path: path.into(),
            detail: detail.into(),
            source: None,
        }
    }
}

impl From<faer::sparse::FaerError> for FemError {
    fn from(e: faer::sparse::FaerError) -> Self {
        FemError::LinearAlgebra {
            detail: format!("{e:?}"),
        }
    }
}

impl From<faer::sparse::CreationError> for FemError {
    fn from(e: faer::sparse::CreationError) -> Self {
        FemError::LinearAlgebra {
            detail: format!("could not build the sparse matrix: {e:?}"),
        }
    }
}

impl From<faer::sparse::linalg::LltError> for FemError {
    /// For factorisations done with faer directly (not through [`crate::SpdSolver`]): faer's
    /// pivot index is in its fill-reducing order, which its high-level `Llt` does not expose,
    /// so the row is left unknown.
    fn from(e: faer::sparse::linalg::LltError) -> Self {
        match e {
            faer::sparse::linalg::LltError::Numeric(
                faer::linalg::cholesky::llt::factor::LltError::NonPositivePivot { .. },
            ) => FemError::NonPositivePivot { row: None },
            faer::sparse::linalg::LltError::Generic(g) => g.into(),
        }
    }
}

/// ` at row {row}`, or nothing when the row is unknown.
fn at_row(row: &Option<usize>) -> String {
    row.map_or_else(String::new, |row| format!(" at row {row}"))
}

/// Checks that `value` is finite and `> 0`.
fn at_node(node: &Option<(usize, crate::Component)>) -> String {
    match node {
        Some((n, c)) => format!(" at node {n}, component {c}"),
        None => String::new(),
    }
}

pub(crate) fn positive(name: &'static str, value: f64) -> Result<f64, FemError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(FemError::InvalidParameter {
            name,
            value,
            expected: "a finite value > 0",
        })
    }
}

/// Checks that `value` is finite and `>= 0`.
pub(crate) fn non_negative(name: &'static str, value: f64) -> Result<f64, FemError> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(FemError::InvalidParameter {
            name,
            value,
            expected: "a finite value >= 0",
        })
    }
}

/// Checks that `value` is finite.
pub(crate) fn finite(name: &'static str, value: f64) -> Result<f64, FemError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(FemError::InvalidParameter {
            name,
            value,
            expected: "a finite value",
        })
    }
}
