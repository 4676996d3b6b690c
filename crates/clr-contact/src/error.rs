//! The error type of clr-contact.

/// Everything that can go wrong when building or evaluating a contact or friction law.
///
/// Messages name the offending value and say what to change.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ContactError {
    /// A parameter is out of its admissible range (for example c_e outside (0, 1], a
    /// non-positive modulus or radius, v0 ≥ v1).
    #[error("{law}: parameter `{name}` = {value} is invalid: {requirement}")]
    InvalidParameter {
        /// Law or object being built, e.g. `"Hertz internal cylinder"`.
        law: &'static str,
        /// Parameter name with its unit, e.g. `"clearance (m)"`.
        name: &'static str,
        /// The value that was given.
        value: f64,
        /// What the value must satisfy, e.g. `"must be in (0, 1]"`.
        requirement: String,
    },
    /// An input lies outside the range where an empirical or implicit law is defined
    /// (Pereira's clearance range, Johnson's load limit).
    #[error("{law}: {quantity} = {value} is outside the validity range {range}; {advice}")]
    OutOfValidity {
        /// Law being evaluated.
        law: &'static str,
        /// Quantity with its unit.
        quantity: &'static str,
        /// The value that was given.
        value: f64,
        /// The admissible range, written out.
        range: String,
        /// What to do instead.
        advice: &'static str,
    },
    /// An iterative solve (implicit law, exact damping factor) did not converge.
    #[error("{law}: {what} did not converge after {iterations} iterations")]
    NoConvergence {
        /// Law being evaluated.
        law: &'static str,
        /// The solve that failed.
        what: &'static str,
        /// Iterations spent.
        iterations: usize,
    },
    /// A name (law preset, damping factor) is not known.
    #[error("unknown {kind} `{name}`; valid names: {valid}")]
    UnknownName {
        /// What kind of name, e.g. `"normal-law preset"`.
        kind: &'static str,
        /// The name that was given.
        name: String,
        /// Comma-separated list of valid names.
        valid: String,
    },
}

impl ContactError {
    /// Shorthand for [`ContactError::InvalidParameter`].
    pub fn invalid(
        law: &'static str,
        name: &'static str,
        value: f64,
        requirement: impl Into<String>,
    ) -> Self {
        Self::InvalidParameter {
            law,
            name,
            value,
            requirement: requirement.into(),
        }
    }
}

/// Require a strictly positive finite value.
pub(crate) fn positive(law: &'static str, name: &'static str, v: f64) -> Result<f64, ContactError> {
    if v > 0.0 && v.is_finite() {
        Ok(v)
    } else {
        Err(ContactError::invalid(
            law,
            name,
            v,
            "must be > 0 and finite",
        ))
    }
}
