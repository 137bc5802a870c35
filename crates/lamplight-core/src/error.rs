//! The core library's error type.

/// Why a core object could not be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A parameter is out of its valid range.
    #[error("invalid {name}: {reason}")]
    InvalidParameter {
        /// The parameter's name, as a scene file spells it.
        name: String,
        /// What was expected.
        reason: String,
    },
    /// Geometry with no area or volume (a triangle with collinear vertices, a zero axis).
    #[error("degenerate geometry: {0}")]
    DegenerateGeometry(String),
    /// The render could not start (thread pool, sizes).
    #[error("cannot render: {0}")]
    Render(String),
}

impl Error {
    /// An [`Error::InvalidParameter`].
    pub fn invalid(name: impl Into<String>, reason: impl Into<String>) -> Error {
        Error::InvalidParameter { name: name.into(), reason: reason.into() }
    }
}
