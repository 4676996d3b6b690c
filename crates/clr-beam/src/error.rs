//! Typed errors of clr-beam. Every message says what to change.

use thiserror::Error;

/// Everything that can go wrong when building, assembling or solving a beam model.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum BeamError {
    /// A material or section parameter is zero, negative or not finite.
    #[error("{name} must be a positive finite number (got {value}); give {name} in SI units > 0")]
    NonPositive {
        /// Which parameter (e.g. "Young's modulus E").
        name: &'static str,
        /// The offending value.
        value: f64,
    },
    /// Poisson's ratio outside (−1, 0.5).
    #[error("Poisson's ratio must lie in (-1, 0.5) (got {0}); use e.g. 0.3 for steel")]
    PoissonRatio(f64),
    /// A section built from dimensions is geometrically impossible.
    #[error("invalid section dimensions: {0}")]
    SectionGeometry(String),
    /// An element (or member) would have zero or non-finite length.
    #[error(
        "element between nodes {0} and {1} has zero or non-finite length; move one of the nodes"
    )]
    ZeroLength(usize, usize),
    /// A node index does not exist.
    #[error(
        "node {node} does not exist: the model has {count} nodes (nodes 0 to {}); give one \
         of those (or add the node first)",
        count.saturating_sub(1)
    )]
    NoSuchNode {
        /// Requested node.
        node: usize,
        /// Number of nodes in the model.
        count: usize,
    },
    /// An element index does not exist.
    #[error("element {element} does not exist (the model has {count} elements)")]
    NoSuchElement {
        /// Requested element.
        element: usize,
        /// Number of elements in the model.
        count: usize,
    },
    /// A member was asked to be divided into zero elements, or the model has none.
    #[error("the model has no elements; add a member with at least one element")]
    NoElements,
    /// Every degree of freedom is constrained.
    #[error("every degree of freedom is constrained; free at least one DOF")]
    NoFreeDof,
    /// The stiffness restricted to the free DOF is singular: the structure is a mechanism.
    #[error(
        "the stiffness matrix is singular after boundary conditions (free DOF {dof} has no \
         stiffness: the structure is a mechanism); add supports (e.g. clamp or pin a node) \
         so that no rigid-body motion is left"
    )]
    SingularStiffness {
        /// Full-model DOF index (3·node + component) where the factorization broke down.
        dof: usize,
    },
    /// The stiffness is indefinite (e.g. a compressive axial force beyond the buckling load).
    #[error(
        "the stiffness matrix is indefinite (eigenvalue ω² = {lambda:.6e} < 0): a compressive \
         axial force exceeds the buckling load; reduce the compressive geometric-stiffness force"
    )]
    Indefinite {
        /// The most negative generalized eigenvalue found (rad²/s²).
        lambda: f64,
    },
    /// The mass matrix restricted to the free DOF is not positive definite.
    #[error("the mass matrix is not positive definite on the free DOF; check densities and areas")]
    SingularMass,
    /// More modes than free degrees of freedom were requested.
    #[error("asked for {requested} modes but the model has only {available} free DOF; ask for at most {available}")]
    TooManyModes {
        /// Number requested.
        requested: usize,
        /// Number of free DOF.
        available: usize,
    },
    /// More Craig–Bampton modes than interior degrees of freedom (free DOF not on an
    /// interface node) were requested.
    #[error(
        "asked for {requested} Craig–Bampton modes but the model has only {available} interior \
         DOF (free DOF not on an interface node); ask for at most {available}, or refine the \
         mesh so that it has more interior nodes"
    )]
    TooManyInteriorModes {
        /// Number requested.
        requested: usize,
        /// Number of interior DOF.
        available: usize,
    },
    /// Zero modes were requested.
    #[error("ask for at least one mode")]
    ZeroModes,
    /// Arc length outside the path.
    #[error("arc length s = {s} m lies outside the beam [0, {length}] m; clamp s to the beam")]
    OutsideBeam {
        /// Requested arc length (m).
        s: f64,
        /// Length of the path (m).
        length: f64,
    },
    /// A vector has the wrong length.
    #[error("{what} has length {got}, expected {expected}")]
    Length {
        /// What vector.
        what: &'static str,
        /// Its length.
        got: usize,
        /// The expected length.
        expected: usize,
    },
    /// Elements given to a path do not form a connected chain.
    #[error("elements {0} and {1} do not share a node; give the path's elements in order along the beam")]
    NotAChain(usize, usize),
    /// A Craig–Bampton reduction was asked with no interface node.
    #[error("Craig–Bampton needs at least one interface node with a free DOF")]
    NoInterface,
    /// The eigenvalue solver did not converge.
    #[error("the eigenvalue solver did not converge: {0}")]
    Eigen(String),
    /// A sparse assembly or factorization failed (out of memory or index overflow).
    #[error("sparse matrix operation failed: {0}; reduce the model size")]
    Sparse(String),
    /// A prescribed component index is not 0 (u), 1 (v) or 2 (θ).
    #[error("DOF component {0} does not exist; use 0 (u), 1 (v) or 2 (θ)")]
    NoSuchComponent(usize),
}

/// Check that `value` is positive and finite.
pub(crate) fn positive(name: &'static str, value: f64) -> Result<f64, BeamError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(BeamError::NonPositive { name, value })
    }
}
