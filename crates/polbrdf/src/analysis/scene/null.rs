//! The null temperature of a scene under a uniform sky (docs/theory-emission.md): where the
//! emitted and the reflected polarizations cancel.

use super::SkyModel;
use crate::analysis::spectral::Spectrum;
use crate::analysis::thermal::planck;

/// The surface temperature (K) at which, under a uniform sky (`uniform` or `thermal`), the
/// emitted and reflected polarizations cancel: the T with `∫ R·B_λ(T) dλ = ∫ R·L_d dλ` over
/// the spectrum. Exact in every direction at one wavelength and for a `thermal` sky
/// (`B_λ(T) = L_d` at every λ: T = T_sky); for a `uniform` sky over a band it is the
/// band-radiance match, exact only where the emissivity's polarization does not change across
/// the band (the polarized part is `∫ R·(B_λ(T) − L_d)·ε_lin(λ) dλ`). `None` for a
/// non-uniform sky, or no sky radiance at all.
pub fn null_temperature(sky: &SkyModel, spectrum: &Spectrum) -> Option<f64> {
    let nodes = spectrum.integral_nodes(&[]);
    let sky_band: f64 = nodes
        .iter()
        .map(|(l, w)| w * sky.uniform_at(*l).unwrap_or(f64::NAN))
        .sum();
    if sky_band.is_nan() || sky_band <= 0.0 {
        return None;
    }
    let band = |t: f64| -> f64 { nodes.iter().map(|(l, w)| w * planck(*l, t)).sum() };
    // Bisection in ln T over 1 K … 10⁶ K (the band radiance increases with T).
    let (mut lo, mut hi) = (0.0f64, 6.0 * std::f64::consts::LN_10);
    if band(hi.exp()) < sky_band {
        return None;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if band(mid.exp()) < sky_band {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some((0.5 * (lo + hi)).exp())
}
