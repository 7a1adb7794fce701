//! The core's error type.

/// Everything the core can refuse. Each variant names the offending quantity and its value.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A material/model parameter is outside its physical domain (spec §2, §4).
    #[error("invalid parameter `{name}` = {}: {reason}", show(*value))]
    InvalidParameter {
        /// The parameter's name as the user spells it (e.g. `sigma_deg`, `n`).
        name: &'static str,
        /// The value that was given.
        value: f64,
        /// What the parameter must satisfy.
        reason: &'static str,
    },
    /// A direction angle is NaN/∞ or outside its range (spec §1).
    #[error("invalid angle `{name}` = {}{}: {reason}", show(*value), index.map(|i| format!(" (at index {i})")).unwrap_or_default())]
    InvalidAngle {
        /// `theta_i`, `phi_i`, `theta_r` or `phi_r` (with `_deg` when given in degrees).
        name: &'static str,
        /// The value that was given, in the unit the name implies.
        value: f64,
        /// Position in a batch, when the angle came from one.
        index: Option<usize>,
        /// What the angle must satisfy.
        reason: &'static str,
    },
    /// Two parameters that exclude each other were both given, or a required one is missing.
    #[error("{0}")]
    InconsistentParameters(String),
    /// Batch input and output slices differ in length.
    #[error("batch length mismatch: `{name}` has {got} elements, expected {expected}")]
    LengthMismatch {
        /// The slice whose length is wrong.
        name: &'static str,
        /// Its length.
        got: usize,
        /// The length of `theta_i`.
        expected: usize,
    },
    /// A name was given that is not a known preset material.
    #[error("unknown material preset `{0}` (known: {known})", known = crate::presets::names().join(", "))]
    UnknownPreset(String),
}

/// A value as a message shows it: plainly (`200`, `-1.5`) in the ordinary range, in exponent
/// form (`1e300`, `1e-200`) beyond it, so an absurd input does not print 300 digits.
fn show(v: f64) -> String {
    if v == 0.0 || !v.is_finite() || (1e-5..1e16).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// Shorthand for results of this crate.
pub type Result<T> = std::result::Result<T, Error>;

/// Checks that `value` is finite and `> 0`.
pub(crate) fn positive(name: &'static str, value: f64) -> Result<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(Error::InvalidParameter {
            name,
            value,
            reason: "must be finite and > 0",
        })
    }
}

/// Checks that `value` is finite and `>= 0`; returns `+0.0` for `-0.0`.
pub(crate) fn non_negative(name: &'static str, value: f64) -> Result<f64> {
    if value.is_finite() && value >= 0.0 {
        Ok(value + 0.0)
    } else {
        Err(Error::InvalidParameter {
            name,
            value,
            reason: "must be finite and >= 0",
        })
    }
}

/// Largest accepted `n` and `k`. Beyond radio-frequency metals (|N| ~ 10⁴); larger values would
/// overflow the complex Fresnel arithmetic (|N²|² must stay finite).
pub const MAX_INDEX: f64 = 1e6;

/// Largest accepted `a`, `b` (and so `b/π` for a normalized `a`), `ρ_D`, `ρ_V`: with it every
/// output stays finite even where the paper form's 1/cos⁴ reaches its f64 maximum (~1e65) next to
/// the horizon.
pub const MAX_MAGNITUDE: f64 = 1e100;

/// Checks that `value` is at most `max` (after the sign checks above).
pub(crate) fn at_most(
    name: &'static str,
    value: f64,
    max: f64,
    reason: &'static str,
) -> Result<f64> {
    if value <= max {
        Ok(value)
    } else {
        Err(Error::InvalidParameter {
            name,
            value,
            reason,
        })
    }
}
