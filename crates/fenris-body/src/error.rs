//! Errors of fenris-body.

use fem_core::FemError;

/// What can go wrong when a fenris body is built or used.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum FenrisBodyError {
    /// A material or load parameter is out of range.
    #[error("parameter `{name}` = {value}: {reason}")]
    InvalidParameter {
        /// The parameter's name.
        name: &'static str,
        /// Its value.
        value: f64,
        /// What is wrong with it.
        reason: &'static str,
    },
    /// A node index (in a support or a node set) is not a node of the mesh.
    #[error("{what}: node {node} does not exist (the mesh has {count} nodes)")]
    UnknownNode {
        /// Where the index was given (`supports`, or the node set's name).
        what: String,
        /// The index.
        node: usize,
        /// The number of nodes.
        count: usize,
    },
    /// A support names a component a plane body does not have.
    #[error("supports: node {node} has no component {component:?} in a plane body")]
    BadComponent {
        /// The node.
        node: usize,
        /// The component.
        component: fem_core::Component,
    },
    /// The supports leave a rigid-body motion free: `K` is singular (this body returns no
    /// rigid-body modes, so it must be held by its supports).
    #[error("the supports leave the rigid-body {motion} free: add a support that prevents it")]
    RigidBodyMotion {
        /// `translation along x`, `translation along y` or `rotation`.
        motion: &'static str,
    },
    /// fenris failed (quadrature rule or assembly).
    #[error("fenris: {0}")]
    Fenris(String),
    /// The factorisation of the stiffness failed (e.g. not enough supports: `K` singular).
    #[error(transparent)]
    Fem(#[from] FemError),
}
