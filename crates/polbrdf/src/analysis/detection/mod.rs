//! Detection (docs/detection.md; the binding physics is the project's detection
//! specification): from the Stokes radiance leaving a target and its background to "will this
//! sensor see the target, by which feature, and out to what range".
//!
//! | section | module |
//! |---|---|
//! | §1 the path: `τ(R)`, `L_path(R)`, `S' = τS + L_path·e0` | [`path`] |
//! | §2 the analyzers: `a_k`, `W`, `W₃⁺` | [`analyzer`] |
//! | §3 signal and noise of a channel | [`noise`] |
//! | §4 the Stokes estimate, its covariance, the features | [`estimate`] |
//! | §5 `d'`, pixels on target, `P_d`, `R_max` | [`statistics`] |
//! | a sensor file's sensor and spectrum | [`sensor`] |
//! | §6 the simulated DoFP frame and its Stokes images | [`frame`] |
//! | §4 the Rician bias of the estimated DoLP | [`dolp_bias`] |
//! | the range's uncertainty from fitted parameters' covariance | [`uncertainty`] |
//!
//! The Stokes vectors given to a [`Detector`] are the band-integrated radiances the sensor's
//! channels weigh (for a photon-counting camera, weighted by its photon response
//! [`noise::photon_band`]); the path's radiances are in the same units.

pub mod analyzer;
pub mod dolp_bias;
pub mod estimate;
pub mod frame;
pub mod noise;
pub mod path;
pub mod sensor;
pub mod statistics;
pub mod uncertainty;

pub use analyzer::Analyzer;
pub use estimate::{Estimate, Moments};
pub use noise::{NoiseModel, PhotonCounting, QuantumEfficiency};
pub use path::{Horizon, Path, PathSpec, PathTable};
pub use sensor::{Layout, NoiseSpec, SensorSpec};

use crate::error::{positive, Error, Result};

/// A polarimetric sensor: its analyzers, its noise, the frames averaged and the IFOV of one
/// Stokes pixel (for a division-of-focal-plane camera the 2×2 super-pixel's, detection.md §5).
#[derive(Debug, Clone, PartialEq)]
pub struct Sensor {
    /// The analyzer channels (§2).
    pub analyzer: Analyzer,
    /// The noise model (§3).
    pub noise: NoiseModel,
    /// Frames averaged `M` (≥ 1; every variance divided by `M`).
    pub frames: u32,
    /// IFOV of one Stokes pixel (rad).
    pub ifov_rad: f64,
}

impl Sensor {
    /// Checks the noise model, the frames and the IFOV.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming the field (`frames` in 1..=10⁶, `ifov_rad` finite
    /// and > 0).
    pub fn validate(&self) -> Result<()> {
        self.noise.validate()?;
        if !(1..=noise::MAX_FRAMES).contains(&self.frames) {
            return Err(Error::InvalidParameter {
                name: "frames",
                value: f64::from(self.frames),
                reason: "must lie in 1..=1000000",
            });
        }
        positive("ifov_rad", self.ifov_rad)?;
        Ok(())
    }
}

/// A feature a detector thresholds (detection.md §5).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Feature {
    /// The intensity `S0`.
    S0 = 0,
    /// The degree of linear polarization.
    Dolp = 1,
    /// `(S0, DoLP)` combined by the Fisher linear discriminant (docs/detection.md).
    Combined = 2,
}

impl Feature {
    /// Every feature, in the order ties are broken.
    pub const ALL: [Feature; 3] = [Feature::S0, Feature::Dolp, Feature::Combined];

    /// Its name in files: `s0`, `dolp`, `s0+dolp`.
    pub fn as_str(self) -> &'static str {
        match self {
            Feature::S0 => "s0",
            Feature::Dolp => "dolp",
            Feature::Combined => "s0+dolp",
        }
    }

    /// The feature named `name` ([`Feature::as_str`]).
    pub fn parse(name: &str) -> Option<Self> {
        crate::names::find(&Self::ALL, Self::as_str, name)
    }
}

/// The per-pixel `d'` of every feature (detection.md §5).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FeatureScores {
    /// Of S0.
    pub s0: f64,
    /// Of DoLP.
    pub dolp: f64,
    /// Of the combined feature.
    pub combined: f64,
}

impl FeatureScores {
    /// The score of `feature`.
    pub fn get(&self, feature: Feature) -> f64 {
        match feature {
            Feature::S0 => self.s0,
            Feature::Dolp => self.dolp,
            Feature::Combined => self.combined,
        }
    }
}

/// How detection is decided (detection.md §5).
#[derive(Debug, Clone, PartialEq)]
pub struct Criteria {
    /// The false-alarm probability `P_fa` in (0, 1) (default 10⁻⁶).
    pub pfa: f64,
    /// The required `P_d` in (0, 1) (default 0.9).
    pub pd_required: f64,
    /// The largest range searched (m, > 0).
    pub range_limit_m: f64,
    /// The features the detector may use (not empty; default all).
    pub features: Vec<Feature>,
}

impl Default for Criteria {
    fn default() -> Self {
        Self {
            pfa: 1e-6,
            pd_required: 0.9,
            range_limit_m: 10_000.0,
            features: Feature::ALL.to_vec(),
        }
    }
}

impl Criteria {
    /// `Φ⁻¹(P_d,req) + Φ⁻¹(1 − P_fa)`.
    pub fn required_d_prime(&self) -> f64 {
        statistics::required_d_prime(self.pd_required, self.pfa)
    }
}

/// A sensor, a path, a target's area and the criteria: what decides detection at a view.
#[derive(Debug, Clone, PartialEq)]
pub struct Detector {
    /// The sensor.
    pub sensor: Sensor,
    /// The path.
    pub path: Path,
    /// The target's area `A` (m², a flat patch).
    pub area_m2: f64,
    /// The criteria.
    pub criteria: Criteria,
}

impl Detector {
    /// A detector, validated.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `area_m2` (finite, > 0), `pfa`, `pd` (in (0, 1)),
    /// `range_limit_m` (finite, > 0, within a path table); [`Error::InconsistentParameters`]
    /// for no feature; as [`Sensor::validate`].
    pub fn new(sensor: Sensor, path: Path, area_m2: f64, criteria: Criteria) -> Result<Self> {
        sensor.validate()?;
        positive("area_m2", area_m2)?;
        let open = |name, value: f64| {
            if value > 0.0 && value < 1.0 {
                Ok(())
            } else {
                Err(Error::InvalidParameter {
                    name,
                    value,
                    reason: "must lie in (0, 1)",
                })
            }
        };
        open("pfa", criteria.pfa)?;
        open("pd", criteria.pd_required)?;
        positive("range_limit_m", criteria.range_limit_m)?;
        if let Some(max) = path.max_range() {
            if criteria.range_limit_m > max {
                return Err(Error::InvalidParameter {
                    name: "range_limit_m",
                    value: criteria.range_limit_m,
                    reason: "beyond the last row of the path table (a table is never extrapolated)",
                });
            }
        }
        if criteria.features.is_empty() {
            return Err(Error::InconsistentParameters(
                "no feature to detect with: give at least one of s0, dolp, s0+dolp".into(),
            ));
        }
        Ok(Self {
            sensor,
            path,
            area_m2,
            criteria,
        })
    }
}

/// Detection at one view and range (detection.md §5).
#[derive(Debug, Clone, PartialEq)]
pub struct Detection {
    /// The range (m).
    pub range_m: f64,
    /// Stokes pixels on target (a real number ≥ 0).
    pub pixels: f64,
    /// Per-pixel `d'` of every feature.
    pub scores: FeatureScores,
    /// The detecting feature: the best of the criteria's.
    pub feature: Feature,
    /// `d'_N = d'·√N_pix` of that feature.
    pub d_prime_n: f64,
    /// `P_d` at the criteria's `P_fa`.
    pub pd: f64,
    /// Whether a channel of the target or the background is saturated.
    pub saturated: bool,
    /// The target's estimate at the sensor.
    pub target: Estimate,
    /// The background's estimate at the sensor.
    pub background: Estimate,
}

/// The detection range of a view (detection.md §5).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MaxRange {
    /// Detected at the range limit: "beyond R_limit".
    Beyond,
    /// Not detected at any range searched.
    NotDetectable,
    /// The largest range that detects, and the feature that detects there.
    At {
        /// Range (m).
        range_m: f64,
        /// The detecting feature.
        feature: Feature,
    },
}
