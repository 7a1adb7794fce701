//! A separate fit at each wavelength of spectral data (e.g. an effective index `n(λ)`, `k(λ)`),
//! the wavelengths in parallel.

use super::{fit, FitOptions, FitResult, Measurement};
use crate::error::FitError;
use crate::params::Param;
use polbrdf::MaterialSpec;
use rayon::prelude::*;

/// One wavelength's fit of [`fit_per_wavelength`].
#[derive(Debug, Clone, PartialEq)]
pub struct WavelengthFit {
    /// The wavelength (µm).
    pub wavelength_um: f64,
    /// The measurements at it.
    pub measurements: usize,
    /// The fit there, or why it was refused.
    pub result: Result<FitResult, FitError>,
}

/// Fits the `free` parameters separately at each wavelength of the data (every measurement
/// needs one): e.g. an effective index `n(λ)`, `k(λ)` for a material no database has. With a
/// spectral `base`, its index at each wavelength is the start of n and k there. The wavelengths
/// are fitted in parallel and returned in increasing order; a refusal at one wavelength is
/// reported there and does not stop the others.
///
/// # Errors
/// [`FitError::BadParameterList`] when a measurement has no wavelength.
pub fn fit_per_wavelength(
    base: &MaterialSpec,
    free: &[Param],
    data: &[Measurement],
    opts: &FitOptions,
) -> Result<Vec<WavelengthFit>, FitError> {
    let mut wavelengths: Vec<f64> = Vec::new();
    for d in data {
        let Some(l) = d.wavelength_um else {
            return Err(FitError::BadParameterList(
                "a fit per wavelength needs the wavelength of every measurement (a \
                 `wavelength_um` column)"
                    .into(),
            ));
        };
        if !wavelengths.contains(&l) {
            wavelengths.push(l);
        }
    }
    wavelengths.sort_by(f64::total_cmp);
    Ok(wavelengths
        .par_iter()
        .map(|&l| {
            let subset: Vec<Measurement> = data
                .iter()
                .filter(|d| d.wavelength_um == Some(l))
                .copied()
                .collect();
            let result = (|| {
                let mut at = base.clone();
                if at.spectral.is_some() {
                    let index = at.index_at(l)?;
                    (at.n, at.k) = (index.n(), index.k());
                    at.spectral = None;
                }
                fit(&at, free, &subset, opts)
            })();
            WavelengthFit {
                wavelength_um: l,
                measurements: subset.len(),
                result,
            }
        })
        .collect())
}
