//! The fittable parameters, how they map onto a [`MaterialSpec`], and the transformations that
//! keep them in their physical domain during the fit.

use crate::error::FitError;
use polbrdf::MaterialSpec;

/// A parameter of the material that a fit may free.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Param {
    /// Real refractive index n (> 0).
    N,
    /// Extinction coefficient k (≥ 0).
    K,
    /// Amplitude a of D (sr⁻¹, ≥ 0, eq. 4). Freeing it turns the normalization off.
    A,
    /// Width b of D (rad⁻², > 0, eq. 4).
    B,
    /// Roughness σ in degrees (> 0; b = 1/σ²).
    SigmaDeg,
    /// ρ_D (sr⁻¹, ≥ 0, eq. 1).
    RhoD,
    /// ρ_V (sr⁻¹, ≥ 0, eq. 1).
    RhoV,
    /// τ of eq. 3 in degrees (> 0).
    TauDeg,
    /// Ω of eq. 3 in degrees (> 0).
    OmegaDeg,
}

impl Param {
    /// Every parameter, in the order of the material file.
    pub const ALL: [Param; 9] = [
        Param::N,
        Param::K,
        Param::SigmaDeg,
        Param::B,
        Param::A,
        Param::TauDeg,
        Param::OmegaDeg,
        Param::RhoD,
        Param::RhoV,
    ];

    /// The material-file key.
    pub fn name(self) -> &'static str {
        match self {
            Param::N => "n",
            Param::K => "k",
            Param::A => "a",
            Param::B => "b",
            Param::SigmaDeg => "sigma_deg",
            Param::RhoD => "rho_d",
            Param::RhoV => "rho_v",
            Param::TauDeg => "tau_deg",
            Param::OmegaDeg => "omega_deg",
        }
    }

    /// Parses a material-file key.
    ///
    /// # Errors
    /// [`FitError::UnknownParameter`].
    pub fn parse(s: &str) -> Result<Param, FitError> {
        Param::ALL
            .into_iter()
            .find(|p| p.name() == s.trim())
            .ok_or_else(|| FitError::UnknownParameter(s.trim().to_string()))
    }

    /// Parses a comma-separated list such as `n,sigma_deg,rho_d`, rejecting repeats, an empty
    /// list, and `b` together with `sigma_deg`.
    ///
    /// # Errors
    /// [`FitError::UnknownParameter`], [`FitError::BadParameterList`].
    pub fn parse_list(s: &str) -> Result<Vec<Param>, FitError> {
        let mut out: Vec<Param> = Vec::new();
        for item in s.split(',').filter(|x| !x.trim().is_empty()) {
            let p = Param::parse(item)?;
            if out.contains(&p) {
                return Err(FitError::BadParameterList(format!(
                    "parameter `{}` is listed twice",
                    p.name()
                )));
            }
            out.push(p);
        }
        if out.is_empty() {
            return Err(FitError::BadParameterList(
                "no free parameter given (e.g. --free n,sigma_deg,rho_d)".into(),
            ));
        }
        if out.contains(&Param::B) && out.contains(&Param::SigmaDeg) {
            return Err(FitError::BadParameterList(
                "`b` and `sigma_deg` are the same roughness (b = 1/σ²): free one of them".into(),
            ));
        }
        Ok(out)
    }

    /// True for parameters that must be strictly positive (fitted as `ln x`); the others are
    /// non-negative (fitted as `x = u²`).
    pub fn strictly_positive(self) -> bool {
        matches!(
            self,
            Param::N | Param::B | Param::SigmaDeg | Param::TauDeg | Param::OmegaDeg
        )
    }

    /// The parameter's current value in `spec` (for `a` and the roughness, the value the built
    /// material actually uses).
    ///
    /// # Errors
    /// [`FitError::Model`] if the spec is invalid.
    pub fn value(self, spec: &MaterialSpec) -> Result<f64, FitError> {
        Ok(match self {
            Param::N => spec.n,
            Param::K => spec.k,
            Param::A => spec.build()?.distribution().a(),
            Param::B => spec.build()?.distribution().b(),
            Param::SigmaDeg => spec.build()?.distribution().sigma().to_degrees(),
            Param::RhoD => spec.rho_d,
            Param::RhoV => spec.rho_v,
            Param::TauDeg => spec.tau_deg,
            Param::OmegaDeg => spec.omega_deg,
        })
    }

    /// Sets the parameter in `spec`. Setting `b` or `sigma_deg` switches the spec to that
    /// roughness key; setting `a` makes `a` explicit.
    pub fn set(self, spec: &mut MaterialSpec, v: f64) {
        match self {
            Param::N => spec.n = v,
            Param::K => spec.k = v,
            Param::A => spec.a = Some(v),
            Param::B => {
                spec.b = Some(v);
                spec.sigma_deg = None;
            }
            Param::SigmaDeg => {
                spec.sigma_deg = Some(v);
                spec.b = None;
            }
            Param::RhoD => spec.rho_d = v,
            Param::RhoV => spec.rho_v = v,
            Param::TauDeg => spec.tau_deg = v,
            Param::OmegaDeg => spec.omega_deg = v,
        }
    }

    /// Internal (unconstrained) coordinate of value `x`: `ln x` or `sqrt(x)`.
    pub fn to_internal(self, x: f64) -> f64 {
        if self.strictly_positive() {
            x.ln()
        } else {
            x.max(0.0).sqrt()
        }
    }

    /// Value of internal coordinate `u`: `exp u` or `u²` — always inside the domain.
    pub fn from_internal(self, u: f64) -> f64 {
        if self.strictly_positive() {
            u.exp()
        } else {
            u * u
        }
    }

    /// A start value to use instead of exactly 0 for a non-negative parameter (the square
    /// transform has zero slope at 0, so a fit started there could never move).
    pub fn nonzero_start(self) -> f64 {
        match self {
            Param::K => 1e-2,
            Param::A => 1.0,
            _ => 1e-3,
        }
    }
}
