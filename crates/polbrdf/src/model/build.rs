//! Validation: a [`MaterialSpec`] built into a [`Material`] — every key checked and the model's
//! quantities derived (docs/model.md §8). Apart from the spec so that the spec (what the user
//! writes) does not depend on the material (what the model evaluates), which holds its spec.

use crate::error::{non_negative, Error, Result};
use crate::model::distribution::Distribution;
use crate::model::material::{Material, ModelParams};
use crate::model::shadowing::Shadowing;
use crate::model::spec::MaterialSpec;
use crate::optics::fresnel::RefractiveIndex;

impl MaterialSpec {
    /// Validates every key and builds the material at wavelength `lambda_um` (µm): with the
    /// spectral index at λ, or the constant index (λ then plays no part).
    ///
    /// # Errors
    /// As [`MaterialSpec::build`], and [`Error::WavelengthOutOfRange`] outside the data.
    pub fn build_at(&self, lambda_um: f64) -> Result<Material> {
        let index = self.index_at(lambda_um)?;
        let mut constant = self.clone();
        constant.n = index.n();
        constant.k = index.k();
        let spectral = constant.spectral.take();
        let mut m = constant.build()?;
        m.set_origin(spectral, Some(lambda_um));
        Ok(m)
    }

    /// Validates every key and derives the model's quantities.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming the key and its value, or
    /// [`Error::InconsistentParameters`] when `sigma_deg` and `b` are both or neither given.
    pub fn build(&self) -> Result<Material> {
        if let Some(s) = &self.spectral {
            let (lo, hi) = s.index.range();
            return Err(Error::InconsistentParameters(format!(
                "the material{} has a spectral index (`index = \"{}\"`, {lo}–{hi} µm): give a \
                 wavelength",
                self.name
                    .as_deref()
                    .map(|n| format!(" `{n}`"))
                    .unwrap_or_default(),
                s.source
            )));
        }
        let index = RefractiveIndex::new(self.n, self.k)?;
        let b = match (self.sigma_deg, self.b) {
            (Some(s), None) => {
                let sigma = crate::error::positive("sigma_deg", s)?.to_radians();
                let b = 1.0 / (sigma * sigma);
                if !(b > 0.0 && b <= crate::error::MAX_MAGNITUDE) {
                    return Err(Error::InvalidParameter {
                        name: "sigma_deg",
                        value: s,
                        reason: "out of range: b = 1/σ² must lie in (0, 1e100]",
                    });
                }
                b
            }
            (None, Some(b)) => crate::model::distribution::checked_b("b", b)?,
            (Some(_), Some(_)) => {
                return Err(Error::InconsistentParameters(
                    "give exactly one of `sigma_deg` and `b`, not both".into(),
                ))
            }
            (None, None) => {
                return Err(Error::InconsistentParameters(
                    "missing roughness: give one of `sigma_deg` or `b`".into(),
                ))
            }
        };
        let distribution = match self.a {
            Some(a) => Distribution::new(a, b)?,
            None => Distribution::normalized(b)?,
        };
        let tau = crate::error::positive("tau_deg", self.tau_deg)?.to_radians();
        let omega = crate::error::positive("omega_deg", self.omega_deg)?.to_radians();
        let shadowing = Shadowing::new(tau, omega, self.azimuth_term)?;
        let params = ModelParams {
            distribution,
            shadowing: self.shadowing.then_some(shadowing),
            form: self.form,
            rho_d: rho("rho_d", self.rho_d)?,
            rho_v: rho("rho_v", self.rho_v)?,
        };
        Ok(Material::from_parts(self.clone(), index, params))
    }
}

/// `0 ≤ ρ ≤ 10¹⁰⁰`.
fn rho(name: &'static str, v: f64) -> Result<f64> {
    crate::error::at_most(
        name,
        non_negative(name, v)?,
        crate::error::MAX_MAGNITUDE,
        "must be ≤ 1e100 (larger values overflow the BRDF near the horizon)",
    )
}
