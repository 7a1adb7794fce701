//! The facet distribution `D(θN) = a·exp(−b·θN²)` (eq. 4, docs/model.md §5).

use crate::error::{at_most, non_negative, positive, Result, MAX_MAGNITUDE};
use crate::numeric::math::{Math, Real, Std};
use crate::numeric::quadrature::integrate;
use std::f64::consts::{FRAC_PI_2, PI};

/// Gaussian facet distribution of eq. 4: `D(θN) = a·exp(−b·θN²)`, θN in rad, `a` in sr⁻¹,
/// `b` in rad⁻².
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Distribution {
    a: f64,
    b: f64,
}

impl Distribution {
    /// Explicit `a` (sr⁻¹, `0 ≤ a ≤ 10¹⁰⁰`) and `b` (rad⁻², `0 < b ≤ 10¹⁰⁰`).
    ///
    /// # Errors
    /// [`crate::Error::InvalidParameter`] naming `a` or `b`.
    pub fn new(a: f64, b: f64) -> Result<Self> {
        Ok(Self {
            a: at_most("a", non_negative("a", a)?, MAX_MAGNITUDE, TOO_LARGE)?,
            b: checked_b("b", b)?,
        })
    }

    /// Given `b`, with `a` from the hemispherical normalization
    /// `∫ D(θN) cosθN dΩ = 1` (docs/model.md §5).
    ///
    /// # Errors
    /// [`crate::Error::InvalidParameter`] naming `b`.
    pub fn normalized(b: f64) -> Result<Self> {
        let b = checked_b("b", b)?;
        Ok(Self {
            a: normalization(b),
            b,
        })
    }

    /// From the roughness angle σ (rad): `b = 1/σ²` (SCATMECH's Gaussian angle distribution),
    /// `a` normalized (docs/model.md §5).
    ///
    /// # Errors
    /// [`crate::Error::InvalidParameter`] naming `sigma` unless σ is finite and > 0.
    pub fn from_sigma(sigma: f64) -> Result<Self> {
        let sigma = positive("sigma", sigma)?;
        Self::normalized(positive("b", 1.0 / (sigma * sigma))?)
    }

    /// Amplitude `a` (sr⁻¹).
    pub fn a(&self) -> f64 {
        self.a
    }

    /// Width parameter `b` (rad⁻²).
    pub fn b(&self) -> f64 {
        self.b
    }

    /// The equivalent roughness angle `σ = 1/sqrt(b)` (rad).
    pub fn sigma(&self) -> f64 {
        self.b.sqrt().recip()
    }

    /// `D(θN)` (eq. 4), sr⁻¹.
    pub fn eval(&self, theta_n: f64) -> f64 {
        self.eval_with::<Std>(theta_n)
    }

    /// `D(θN) = a·exp(−bθN²)` with the exponential of backend `M` — the one formula of eq. 4.
    #[inline(always)]
    pub fn eval_with<M: Math>(&self, theta_n: M::F) -> M::F {
        M::F::of(self.a) * M::exp_neg(self.exponent(theta_n))
    }

    /// The exponent `−b·θN²` of D.
    #[inline(always)]
    pub fn exponent<T: Real>(&self, theta_n: T) -> T {
        -(T::of(self.b) * theta_n * theta_n)
    }

    /// `∫_hemisphere D(θN) cosθN dΩ` (1 for a normalized distribution).
    pub fn projected_integral(&self) -> f64 {
        self.a * 2.0 * PI * half_integral(self.b)
    }
}

const TOO_LARGE: &str = "must be ≤ 1e100 (larger values overflow the BRDF near the horizon)";

/// `0 < b ≤ 10¹⁰⁰` (σ ≥ 10⁻⁵⁰ rad): a normalized `a ≈ b/π` stays finite in every output.
pub(crate) fn checked_b(name: &'static str, b: f64) -> Result<f64> {
    at_most(name, positive(name, b)?, MAX_MAGNITUDE, TOO_LARGE)
}

/// `∫_0^{π/2} exp(−bθ²) sinθ cosθ dθ`, by composite Gauss–Legendre on the support where the
/// Gaussian is above `e⁻⁶⁰` (so a narrow lobe is resolved as well as a wide one).
fn half_integral(b: f64) -> f64 {
    let hi = (60.0 / b).sqrt().min(FRAC_PI_2);
    integrate(|t| (-b * t * t).exp() * t.sin() * t.cos(), 0.0, hi, 16)
}

/// The `a` that normalizes `D` over the hemisphere, `a = 1 / (2π ∫_0^{π/2} e^{−bθ²} sinθ cosθ dθ)`
/// (docs/model.md §5). For large `b` (small σ), `a → b/π`; for `b → 0`, `a → 1/π`.
pub fn normalization(b: f64) -> f64 {
    1.0 / (2.0 * PI * half_integral(b))
}
