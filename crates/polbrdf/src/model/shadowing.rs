//! The Maxwell–Beard shadowing/obscuration function SO (eq. 3, docs/model.md §5).

use crate::error::{positive, Result};
use crate::geometry::AngleVariables;
use crate::numeric::math::{Math, Real, Std};

/// Whether SO includes the azimuth factor `1/(1 + ΦN·θi/Ω)` of eq. 3 as printed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum AzimuthTerm {
    /// No azimuth factor (default): the simplified model (eq. 6) takes ΦN = 0.
    #[default]
    None,
    /// Eq. 3 as printed, with ΦN folded into [0, π/2] (docs/model.md §1).
    Eq3,
}

impl AzimuthTerm {
    /// Every azimuth term (the one list that material files, the CLI and the Python module's
    /// `Literal` types spell).
    pub const ALL: [AzimuthTerm; 2] = [AzimuthTerm::None, AzimuthTerm::Eq3];

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
        crate::names::parse(&Self::ALL, |a| a.as_str(), s)
    }
}

/// Maxwell–Beard shadowing/obscuration (eq. 3):
/// `SO = [1 + (θN/Ω)·exp(−2β/τ)] / [1 + θN/Ω]`, optionally times `1/(1 + ΦN·θi/Ω)`;
/// all angles in radians (the paper's τ = 15, Ω = 40 are degrees, docs/model.md §5).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shadowing {
    tau: f64,
    omega: f64,
    azimuth: AzimuthTerm,
    /// `1/Ω` and `2/τ`, computed once.
    inv_omega: f64,
    two_over_tau: f64,
}

impl Shadowing {
    /// τ and Ω in radians.
    ///
    /// # Errors
    /// [`crate::Error::InvalidParameter`] naming `tau` or `omega` unless finite and > 0.
    pub fn new(tau: f64, omega: f64, azimuth: AzimuthTerm) -> Result<Self> {
        let (tau, omega) = (positive("tau", tau)?, positive("omega", omega)?);
        Ok(Self {
            tau,
            omega,
            azimuth,
            inv_omega: 1.0 / omega,
            two_over_tau: 2.0 / tau,
        })
    }

    /// Maxwell and Beard's values used by the paper: τ = 15°, Ω = 40°, no azimuth factor.
    pub fn paper() -> Self {
        Self::new(15f64.to_radians(), 40f64.to_radians(), AzimuthTerm::None)
            .expect("positive constants")
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

    /// The same τ and Ω with another azimuth setting.
    #[inline(always)]
    pub fn with_azimuth(self, azimuth: AzimuthTerm) -> Self {
        Self { azimuth, ..self }
    }

    /// SO at the given angle variables (eq. 3). Equals 1 at specular (θN = 0) and at
    /// backscatter (β = 0).
    pub fn eval(&self, v: &AngleVariables) -> f64 {
        let (num, den) = self.ratio::<Std>(v.theta_n, v.beta, v.phi_n, v.theta_i);
        num / den
    }

    /// SO (eq. 3) as `(numerator, denominator)`, the one formula both paths use (the batch
    /// engine folds the division into the surface term's):
    /// `num = 1 + x·exp(−2β/τ)`, `den = (1 + x)·A_φ`, `x = θN/Ω`, `A_φ = 1 + ΦN·θi/Ω` (`eq3`)
    /// or 1.
    #[inline(always)]
    pub fn ratio<M: Math>(
        &self,
        theta_n: M::F,
        beta: M::F,
        phi_n: M::F,
        theta_i: M::F,
    ) -> (M::F, M::F) {
        let (one, inv_omega) = (M::F::ONE, M::F::of(self.inv_omega));
        let x = theta_n * inv_omega;
        let e = M::exp_neg(-(beta * M::F::of(self.two_over_tau)));
        let a_phi = match self.azimuth {
            AzimuthTerm::None => one,
            AzimuthTerm::Eq3 => M::mla(phi_n * theta_i, inv_omega, one),
        };
        (M::mla(x, e, one), (one + x) * a_phi)
    }
}
