//! The crate's error type.

/// Everything drawing a figure can fail with. None of these is the user's fault: a figure
/// declaration that cannot be drawn is a bug in the caller, and the font is embedded.
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum Error {
    /// The embedded font could not be loaded (a build problem, not a user error).
    #[error("the embedded font DejaVuSans.ttf could not be loaded")]
    Font,
    /// The plotting backend refused to draw.
    #[error("drawing failed: {0}")]
    Draw(String),
    /// The PNG encoder failed.
    #[error("PNG encoding failed: {0}")]
    Encode(String),
    /// The figure declaration is inconsistent (e.g. a grid whose values do not match its axes).
    #[error("invalid figure: {0}")]
    Invalid(String),
}

/// Shorthand for results of this crate.
pub type Result<T> = std::result::Result<T, Error>;
