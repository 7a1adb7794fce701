//! Planck's law (docs/model.md §17): the spectral radiance of a blackbody, its inverse (the
//! brightness temperature) and its band integral.
//!
//! `B_λ(λ, T) = c1L / (λ⁵ · expm1(c2/(λT)))` with λ in µm and T in K, `c1L = 2hc² =
//! 1.191042972·10⁸ W·µm⁴·m⁻²·sr⁻¹` and `c2 = hc/k = 14387.76877 µm·K` (CODATA 2018); the result
//! in W·m⁻²·sr⁻¹·µm⁻¹.

use crate::error::{positive, Error, Result};

/// First radiation constant for spectral radiance, `2hc²`, in W·µm⁴·m⁻²·sr⁻¹ (CODATA 2018).
pub const C1L: f64 = 1.191_042_972e8;

/// Second radiation constant `hc/k` in µm·K (CODATA 2018).
pub const C2: f64 = 14_387.768_77;

/// Spectral radiance of a blackbody at `temperature_k` (K) and wavelength `lambda_um` (µm), in
/// W·m⁻²·sr⁻¹·µm⁻¹. 0 where `c2/(λT)` is so large that the exponential overflows (a cold body
/// at short wavelength); no validation — see [`planck_checked`].
pub fn planck(lambda_um: f64, temperature_k: f64) -> f64 {
    let x = C2 / (lambda_um * temperature_k);
    if x > 700.0 {
        return 0.0;
    }
    C1L / (lambda_um.powi(5) * x.exp_m1())
}

/// [`planck`] after checking its arguments.
///
/// # Errors
/// [`Error::InvalidParameter`] naming `wavelength_um` or `temperature_k` when not finite and
/// > 0.
pub fn planck_checked(lambda_um: f64, temperature_k: f64) -> Result<f64> {
    positive("wavelength_um", lambda_um)?;
    positive("temperature_k", temperature_k)?;
    Ok(planck(lambda_um, temperature_k))
}

/// The brightness temperature (K) of spectral radiance `radiance` (W·m⁻²·sr⁻¹·µm⁻¹) at
/// `lambda_um`: the T with `B_λ(λ, T) = radiance` (`T = c2/(λ·ln(1 + c1L/(λ⁵L)))`); 0 for
/// `radiance ≤ 0`.
pub fn brightness_temperature(lambda_um: f64, radiance: f64) -> f64 {
    if radiance.is_nan() || radiance <= 0.0 {
        return 0.0;
    }
    C2 / (lambda_um * (C1L / (lambda_um.powi(5) * radiance)).ln_1p())
}

/// Checks a temperature (K): finite and > 0, named `name` in the error.
///
/// # Errors
/// [`Error::InvalidParameter`].
pub fn temperature(name: &'static str, t: f64) -> Result<f64> {
    if !(t.is_finite() && t > 0.0) {
        return Err(Error::InvalidParameter {
            name,
            value: t,
            reason: "a temperature must be finite and > 0 K",
        });
    }
    Ok(t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn brightness_temperature_inverts_planck() {
        for (l, t) in [(0.5, 5772.0), (4.0, 300.0), (10.0, 250.0), (12.0, 1000.0)] {
            let b = planck(l, t);
            assert!((brightness_temperature(l, b) / t - 1.0).abs() < 1e-13);
        }
        assert_eq!(planck(0.3, 3.0), 0.0, "exp overflow: no radiance");
        assert!(planck_checked(10.0, 0.0).is_err());
        assert!(planck_checked(-1.0, 300.0).is_err());
    }
}
