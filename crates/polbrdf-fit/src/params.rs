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
    /// non-negative (fitted as `x` itself, bounded below by 0).
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
        // D does not depend on the index: a spectral spec is read with a placeholder index.
        let distribution = || -> Result<polbrdf::Distribution, FitError> {
            let mut s = spec.clone();
            if s.spectral.take().is_some() {
                (s.n, s.k) = (1.5, 0.0);
            }
            Ok(s.build()?.distribution())
        };
        Ok(match self {
            Param::N => spec.n,
            Param::K => spec.k,
            Param::A => distribution()?.a(),
            Param::B => distribution()?.b(),
            Param::SigmaDeg => distribution()?.sigma().to_degrees(),
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

    /// Internal coordinate of value `x`: `ln x` (strictly positive parameters), `k²` for k (the
    /// model depends on k through `N² = n² − k² + 2ink`, and a reflectance is even in k — so its
    /// first derivative in k vanishes at k = 0, while in k² it does not), or `x` itself (ρ_D, ρ_V,
    /// a, which enter linearly); the last two with the lower bound [`Param::lower_bound`].
    pub fn to_internal(self, x: f64) -> f64 {
        if self.strictly_positive() {
            x.ln()
        } else if self == Param::K {
            x.max(0.0) * x.max(0.0)
        } else {
            x.max(0.0)
        }
    }

    /// Value of internal coordinate `u`: `exp u`, `sqrt u` (k) or `u` — inside the domain for
    /// every `u` at or above the lower bound.
    pub fn from_internal(self, u: f64) -> f64 {
        if self.strictly_positive() {
            u.exp()
        } else if self == Param::K {
            u.max(0.0).sqrt()
        } else {
            u
        }
    }

    /// The lower bound of the internal coordinate: none (−∞) for `ln x`, 0 for a non-negative
    /// parameter. The minimizer projects its steps onto `u ≥ bound`.
    pub fn lower_bound(self) -> f64 {
        if self.strictly_positive() {
            f64::NEG_INFINITY
        } else {
            0.0
        }
    }

    /// The scale of a change that changes the model appreciably, where the value itself gives
    /// none: the numerical derivatives step by `1e-6·max(|x|, step_scale)`. k acts through
    /// `N² = n² − k² + 2ink`, so its scale is that of n (1), not its own magnitude; ρ_D and ρ_V
    /// enter linearly (any step is exact).
    pub fn step_scale(self) -> f64 {
        match self {
            Param::K => 1.0,
            other => other.typical_scale(),
        }
    }

    /// The step `h = 1e-6·max(|x|, step_scale)` of the central-difference derivatives at value
    /// `x` (the fit's Jacobian, and the uncertainty propagation of the Python lookup tables).
    pub fn derivative_step(self, x: f64) -> f64 {
        1e-6 * x.abs().max(self.step_scale())
    }

    /// A typical magnitude of the parameter: the start used instead of exactly 0 for a
    /// non-negative parameter (at k = 0 the model is even in k, so the gradient vanishes there
    /// and a fit started at 0 could never leave it), the scatter of extra starts around 0, and
    /// the size of change the identifiability check tests where the value is 0.
    pub fn typical_scale(self) -> f64 {
        match self {
            Param::N => 1.0,
            Param::K => 1e-2,
            Param::A => 1.0,
            Param::B => 1.0,
            Param::SigmaDeg | Param::TauDeg | Param::OmegaDeg => 1.0,
            Param::RhoD | Param::RhoV => 1e-3,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Param;

    #[test]
    fn every_parameter_is_a_material_file_key() {
        for p in Param::ALL {
            assert!(polbrdf::model::KEYS.contains(&p.name()), "{}", p.name());
        }
    }
}
