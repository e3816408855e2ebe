//! The planning core's error type.

use thiserror::Error;

/// Why a core computation could not produce a result.
///
/// `field` names the input the problem comes from, so the service can point the
/// client at it.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum CoreError {
    /// An input value is outside the range the model accepts.
    #[error("{field}: {reason}")]
    InvalidInput { field: String, reason: String },
    /// The data is valid but the computation cannot be carried out (e.g. a singular fit).
    #[error("{field}: {reason}")]
    Unsolvable { field: String, reason: String },
    /// The caller asked the computation to stop.
    #[error("cancelled")]
    Cancelled,
}

impl CoreError {
    pub fn invalid(field: impl Into<String>, reason: impl Into<String>) -> Self {
        CoreError::InvalidInput { field: field.into(), reason: reason.into() }
    }

    pub fn unsolvable(field: impl Into<String>, reason: impl Into<String>) -> Self {
        CoreError::Unsolvable { field: field.into(), reason: reason.into() }
    }
}

/// Checks that `value` is finite and strictly positive.
pub fn require_positive(field: &str, value: f64) -> Result<f64, CoreError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(CoreError::invalid(field, format!("must be a finite number > 0, got {value}")))
    }
}

/// Checks that `value` is finite.
pub fn require_finite(field: &str, value: f64) -> Result<f64, CoreError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(CoreError::invalid(field, format!("must be a finite number, got {value}")))
    }
}
