//! The core's error type. A leaf module: it imports nothing from the crate.

/// Everything the core can refuse. Each variant names the offending quantity and its value.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A material/model parameter is outside its physical domain (docs/model.md §8).
    #[error("invalid parameter `{name}` = {}: {reason}", show(*value))]
    InvalidParameter {
        /// The parameter's name as the user spells it (e.g. `sigma_deg`, `n`).
        name: &'static str,
        /// The value that was given.
        value: f64,
        /// What the parameter must satisfy.
        reason: &'static str,
    },
    /// One element of a batch of parameters (e.g. a per-element refractive index) is outside
    /// its domain.
    #[error("invalid parameter `{name}` = {} (at index {index}): {reason}", show(*value))]
    InvalidParameterAt {
        /// The parameter's name (`n`, `k`, `wavelength_um`, …).
        name: &'static str,
        /// The value that was given.
        value: f64,
        /// Its position in the batch.
        index: usize,
        /// What the parameter must satisfy.
        reason: &'static str,
    },
    /// A direction vector is not finite or its length is outside
    /// [`crate::geometry::angles::DIRECTION_LENGTH`] (the direction entry point,
    /// docs/model.md §9.11).
    #[error("invalid direction `{name}` = [{}, {}, {}]{}: a direction vector must be finite, with a length between 1e-15 and 1e15",
            show(value[0]), show(value[1]), show(value[2]),
            index.map(|i| format!(" (at index {i})")).unwrap_or_default())]
    InvalidDirection {
        /// `w_i` or `w_r` (or the caller's name for it).
        name: &'static str,
        /// The vector that was given.
        value: [f64; 3],
        /// Position in a batch.
        index: Option<usize>,
    },
    /// A direction angle is NaN/∞ or outside its range (docs/model.md §1).
    #[error("invalid angle `{name}` = {}{}: {}", show(*value),
            index.map(|i| format!(" (at index {i})")).unwrap_or_default(), problem.reason(*degrees))]
    InvalidAngle {
        /// The angle's name as the caller spells it: `theta_i`, `phi_r`, `sun_zenith`, …, with
        /// `_deg` when it was given in degrees.
        name: &'static str,
        /// The value that was given, in the caller's unit.
        value: f64,
        /// Whether `value` (and `name`) are in degrees.
        degrees: bool,
        /// Position in a batch, when the angle came from one.
        index: Option<usize>,
        /// What is wrong with it.
        problem: AngleProblem,
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
    /// A wavelength outside the data of a spectral index (never extrapolated).
    #[error("wavelength {} µm{} is outside the data of `{material}` ({} – {} µm)", show(*wavelength_um), element(*position), show(range.0), show(range.1))]
    WavelengthOutOfRange {
        /// The material (or data set) whose index was asked for.
        material: String,
        /// The wavelength asked for (µm).
        wavelength_um: f64,
        /// The range of the data (µm).
        range: (f64, f64),
        /// Its position in a batch, when it came from one.
        position: Option<usize>,
    },
    /// A name was given that is not a known preset material.
    #[error("unknown material preset `{name}` (known: {known})")]
    UnknownPreset {
        /// The name that was asked for.
        name: String,
        /// The known names, comma-separated.
        known: String,
    },
}

/// What is wrong with an angle ([`Error::InvalidAngle`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum AngleProblem {
    /// NaN or ±∞.
    NotFinite,
    /// A zenith angle outside [0°, 180°].
    ZenithRange,
    /// A source at or below the horizon where one above it is needed.
    SourceBelowHorizon,
    /// A view direction at or below the horizon where one above it is needed.
    ViewBelowHorizon,
    /// An azimuth beyond ±[`crate::MAX_AZIMUTH_DEG`]: too large for its digits to hold the
    /// angle (at 1e17° not one digit of the angle modulo 360° is left).
    AzimuthTooLarge,
}

impl AngleProblem {
    /// The rule the angle breaks, in the unit of the value.
    pub fn reason(self, degrees: bool) -> &'static str {
        match (self, degrees) {
            (AngleProblem::NotFinite, _) => "must be finite",
            (AngleProblem::ZenithRange, true) => "zenith angle must lie in [0°, 180°]",
            (AngleProblem::ZenithRange, false) => {
                "zenith angle must lie in [0, π] rad ([0°, 180°])"
            }
            (AngleProblem::SourceBelowHorizon, _) => {
                "the source must be above the horizon: 0 ≤ zenith angle < 90°"
            }
            (AngleProblem::ViewBelowHorizon, _) => {
                "the view direction must be above the horizon: 0 ≤ zenith angle < 90°"
            }
            (AngleProblem::AzimuthTooLarge, _) => {
                "an azimuth must lie within ±1e8° (±1.75e6 rad): beyond it too few digits of the \
                 angle remain"
            }
        }
    }
}

/// A value as a message shows it: plainly (`200`, `-1.5`) in the ordinary range, in exponent
/// form (`1e300`, `1e-200`) beyond it, so an absurd input does not print 300 digits.
/// " (element i)" for a position in a batch, else nothing.
fn element(position: Option<usize>) -> String {
    position
        .map(|i| format!(" (element {i})"))
        .unwrap_or_default()
}

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

impl Error {
    /// The same error about element `position` of a batch (`None`: about no element): an
    /// [`Error::InvalidParameter`] becomes [`Error::InvalidParameterAt`] there, an
    /// [`Error::WavelengthOutOfRange`] carries the position; any other error is unchanged.
    pub fn at_position(self, position: Option<usize>) -> Self {
        match (self, position) {
            (
                Error::InvalidParameter {
                    name,
                    value,
                    reason,
                },
                Some(index),
            ) => Error::InvalidParameterAt {
                name,
                value,
                index,
                reason,
            },
            (
                Error::WavelengthOutOfRange {
                    material,
                    wavelength_um,
                    range,
                    ..
                },
                position,
            ) => Error::WavelengthOutOfRange {
                material,
                wavelength_um,
                range,
                position,
            },
            (other, _) => other,
        }
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

/// Largest accepted radiance or irradiance of a source (sun, sky, path radiance), in any
/// unit: far beyond any physical value, and small enough that sums of products of it with a
/// BRDF, weights and Planck radiances stay finite.
pub const MAX_RADIOMETRIC: f64 = 1e150;

/// `value` if finite, ≥ 0 and at most [`MAX_RADIOMETRIC`] (a radiance or an irradiance).
pub(crate) fn radiometric(name: &'static str, value: f64) -> Result<f64> {
    if value.is_finite() && (0.0..=MAX_RADIOMETRIC).contains(&value) {
        Ok(value + 0.0)
    } else {
        Err(Error::InvalidParameter {
            name,
            value,
            reason: "must be finite, >= 0 and at most 1e150",
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
