//! The results of a detection study: each view's ([`ViewResult`], with its range's
//! uncertainty [`RangeUncertainty`]) and the study's ([`DetectStudy`]). Plain values that the
//! job ([`super::detect`]) fills and the tables ([`super::out`]), the warnings and the
//! uncertainty read.

use crate::fit_covariance::FitCovariance;
use crate::scene::Warning;
use crate::spectrum::NamedMaterial;
use polbrdf::analysis::contrast::ViewGrid;
use polbrdf::analysis::detection::{Detection, Detector, MaxRange};
use polbrdf::{Spectrum, Stokes};
use polbrdf_io::{Scene, SensorFile};

/// One view's results.
#[derive(Debug, Clone, PartialEq)]
pub struct ViewResult {
    /// View zenith (rad).
    pub theta_r: f64,
    /// View azimuth (rad).
    pub phi_r: f64,
    /// The target's Stokes radiance leaving the surface, over the sensor's spectral weights.
    pub target: Stokes,
    /// The background's, likewise.
    pub background: Stokes,
    /// Detection at each of the request's ranges (without ranges: at the detection range, or
    /// at the range limit when beyond it or not detectable).
    pub at_ranges: Vec<Detection>,
    /// The detection range (with `search`).
    pub max_range: Option<MaxRange>,
    /// Its uncertainty, with fits and for the views given one (docs/detection.md).
    pub range_uncertainty: Option<RangeUncertainty>,
}

/// The result of [`detect`](super::detect).
#[derive(Debug, Clone)]
pub struct DetectStudy {
    /// The scene.
    pub scene: Box<Scene>,
    /// The sensor file.
    pub sensor: Box<SensorFile>,
    /// The target.
    pub target: NamedMaterial,
    /// The background.
    pub background: NamedMaterial,
    /// The detector (sensor, path in signal units, area, criteria).
    pub detector: Detector,
    /// The spectrum observed over (the sensor's).
    pub spectrum: Spectrum,
    /// The grid, for grid views.
    pub grid: Option<ViewGrid>,
    /// Per view, zenith-major for a grid.
    pub views: Vec<ViewResult>,
    /// The request's ranges (m).
    pub ranges_m: Vec<f64>,
    /// Setup warnings.
    pub warnings: Vec<Warning>,
    /// The target's and the background's fits, when given.
    pub fits: [Option<FitCovariance>; 2],
    /// With fits: the best-ranked views given an interval (`None`: every view).
    pub uncertainty_views: Option<usize>,
}

/// A view's detection range with its uncertainty.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RangeUncertainty {
    /// `σ_R` and the interval `R ± z·σ_R` (its lower end at least 0).
    Interval {
        /// `σ_R` (m).
        sigma_m: f64,
        /// `max(R − z·σ_R, 0)` (m).
        lo_m: f64,
        /// `R + z·σ_R` (m).
        hi_m: f64,
    },
    /// No interval: a perturbed parameter set has no detection range (beyond the range limit
    /// or not detectable) or leaves its parameter's domain (docs/detection.md).
    Undefined,
}
