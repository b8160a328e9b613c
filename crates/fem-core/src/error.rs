//! Errors of `fem-core`.

/// Error of `fem-core`: invalid mesh, material, boundary condition or load, or a failure of
/// the sparse factorisation.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum FemError {
    /// A real parameter is NaN, infinite or outside its admissible range.
    #[error("invalid parameter `{name}` = {value}: expected {expected}")]
    InvalidParameter {
        /// Name of the parameter (`young`, `poisson`, `thickness`, …).
        name: &'static str,
        /// The rejected value.
        value: f64,
        /// What was expected, in words.
        expected: &'static str,
    },
    /// A node coordinate is NaN or infinite.
    #[error("node {node} has a non-finite coordinate ({x}, {y})")]
    NonFiniteNode {
        /// Node index.
        node: usize,
        /// First coordinate (x or r).
        x: f64,
        /// Second coordinate (y or z).
        y: f64,
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
    #[error("axisymmetric mesh: node {node} has negative radius r = {r}")]
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
    /// A mesh entity that this crate does not support (e.g. a quadrilateral in a `.msh`).
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
    /// The stiffness is not positive definite: a rigid-body mode (missing supports) or a
    /// mechanism. `pivot` is the first non-positive pivot of the Cholesky factorisation, in the
    /// fill-reducing order.
    #[error(
        "stiffness matrix is not positive definite (pivot {pivot}): the structure probably lacks supports against a rigid-body motion"
    )]
    NotPositiveDefinite {
        /// Index of the first non-positive pivot.
        pivot: usize,
    },
    /// The sparse linear algebra failed for a reason other than definiteness (allocation,
    /// index overflow).
    #[error("sparse linear algebra failed: {detail}")]
    LinearAlgebra {
        /// faer's own description.
        detail: String,
    },
    /// Reading or writing a file failed.
    #[error("{path}: {detail}")]
    Io {
        /// The file.
        path: String,
        /// What went wrong.
        detail: String,
    },
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
    fn from(e: faer::sparse::linalg::LltError) -> Self {
        match e {
            faer::sparse::linalg::LltError::Numeric(
                faer::linalg::cholesky::llt::factor::LltError::NonPositivePivot { index },
            ) => FemError::NotPositiveDefinite { pivot: index },
            faer::sparse::linalg::LltError::Generic(g) => g.into(),
        }
    }
}

/// Checks that `value` is finite and `> 0`.
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
