//! The Maxwell–Beard shadowing/obscuration function SO (eq. 3, spec §4).

use crate::error::{positive, Result};
use crate::geometry::AngleVariables;

/// Whether SO includes the azimuth factor `1/(1 + ΦN·θi/Ω)` of eq. 3 as printed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum AzimuthTerm {
    /// No azimuth factor (default): the simplified model (eq. 6) takes ΦN = 0.
    #[default]
    None,
    /// Eq. 3 as printed, with ΦN folded into [0, π/2] (spec §1).
    Eq3,
}

impl AzimuthTerm {
    /// The name used in material files (`"none"`, `"eq3"`).
    pub fn as_str(&self) -> &'static str {
        match self {
            AzimuthTerm::None => "none",
            AzimuthTerm::Eq3 => "eq3",
        }
    }
}

impl std::str::FromStr for AzimuthTerm {
    type Err = String;
    fn from_str(s: &str) -> std::result::Result<Self, String> {
        match s {
            "none" => Ok(AzimuthTerm::None),
            "eq3" => Ok(AzimuthTerm::Eq3),
            other => Err(format!("expected \"none\" or \"eq3\", got {other:?}")),
        }
    }
}

/// Maxwell–Beard shadowing/obscuration (eq. 3):
/// `SO = [1 + (θN/Ω)·exp(−2β/τ)] / [1 + θN/Ω]`, optionally times `1/(1 + ΦN·θi/Ω)`;
/// all angles in radians (the paper's τ = 15, Ω = 40 are degrees, spec §4).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shadowing {
    tau: f64,
    omega: f64,
    azimuth: AzimuthTerm,
}

impl Shadowing {
    /// τ and Ω in radians.
    ///
    /// # Errors
    /// [`crate::Error::InvalidParameter`] naming `tau` or `omega` unless finite and > 0.
    pub fn new(tau: f64, omega: f64, azimuth: AzimuthTerm) -> Result<Self> {
        Ok(Self {
            tau: positive("tau", tau)?,
            omega: positive("omega", omega)?,
            azimuth,
        })
    }

    /// Maxwell and Beard's values used by the paper: τ = 15°, Ω = 40°, no azimuth factor.
    pub fn paper() -> Self {
        Self {
            tau: 15f64.to_radians(),
            omega: 40f64.to_radians(),
            azimuth: AzimuthTerm::None,
        }
    }

    /// τ (rad).
    pub fn tau(&self) -> f64 {
        self.tau
    }
    /// Ω (rad).
    pub fn omega(&self) -> f64 {
        self.omega
    }
    /// The azimuth factor setting.
    pub fn azimuth_term(&self) -> AzimuthTerm {
        self.azimuth
    }

    /// SO at the given angle variables (eq. 3). Equals 1 at specular (θN = 0) and at
    /// backscatter (β = 0).
    pub fn eval(&self, v: &AngleVariables) -> f64 {
        let x = v.theta_n / self.omega;
        let so = (1.0 + x * (-2.0 * v.beta / self.tau).exp()) / (1.0 + x);
        match self.azimuth {
            AzimuthTerm::None => so,
            AzimuthTerm::Eq3 => so / (1.0 + v.phi_n * v.theta_i / self.omega),
        }
    }
}
