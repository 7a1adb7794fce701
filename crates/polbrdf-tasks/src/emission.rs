//! Polarized thermal emission by Kirchhoff's law (docs/model.md §16): the emissivity Stokes
//! vector at a set of view zenith angles, at one wavelength or averaged over a band — with the
//! response, or with the response × Planck's law at a temperature (the emissivity of a surface
//! at that temperature seen in the band).

use crate::error::{TaskError, TaskResult};
use crate::spectrum::{describe, material_at, NamedMaterial, SpectralRequest};
use polbrdf::analysis::emission::{emissivities, Emissivity};
use polbrdf::analysis::thermal::planck;
use polbrdf::{Material, Spectrum, Stokes};

/// An emission request.
#[derive(Debug, Clone, PartialEq)]
pub struct EmissionRequest {
    /// A material file or a preset name.
    pub material: String,
    /// View zenith angles, degrees, in [0, 90); empty: 0, 1, …, 89.
    pub theta_deg: Vec<f64>,
    /// Over a band, also weight by Planck's law at this temperature (K, finite, > 0).
    pub temperature_k: Option<f64>,
    /// The wavelength or band.
    pub spectral: SpectralRequest,
}

/// One view angle of an [`EmissionTable`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EmissionRow {
    /// The view zenith angle, degrees, as requested.
    pub theta_deg: f64,
    /// The (band-averaged) emissivity by route A (`eps`) and route B (`eps_b`).
    pub emissivity: Emissivity,
    /// Every polarization's emissivity in [0, 1] at every spectral node and in the mean.
    pub valid: bool,
}

/// The result of [`emission`].
#[derive(Debug, Clone)]
pub struct EmissionTable {
    /// The material.
    pub material: NamedMaterial,
    /// The spectrum.
    pub spectrum: Option<Spectrum>,
    /// One row per view angle.
    pub rows: Vec<EmissionRow>,
}

impl EmissionTable {
    /// The columns of the table (a contract: other tools script against these names).
    pub const COLUMNS: [&'static str; 10] = [
        "theta_deg",
        "eps0",
        "eps1",
        "eps2",
        "eps3",
        "eps_s",
        "eps_p",
        "dolp",
        "reciprocity_residual",
        "valid",
    ];

    /// The view angles (degrees) where an emissivity leaves [0, 1].
    pub fn invalid_angles(&self) -> Vec<f64> {
        self.rows
            .iter()
            .filter(|r| !r.valid)
            .map(|r| r.theta_deg)
            .collect()
    }

    /// The material and spectrum in words.
    pub fn title(&self) -> String {
        format!("{}{}", self.material.name, describe(self.spectrum.as_ref()))
    }
}

/// The view angles with their default, checked.
fn angles(theta_deg: &[f64]) -> TaskResult<Vec<f64>> {
    let angles: Vec<f64> = if theta_deg.is_empty() {
        (0..90).map(f64::from).collect()
    } else {
        theta_deg.to_vec()
    };
    crate::limits::count_at_most("theta_deg", angles.len(), crate::limits::ANGLES)?;
    if let Some(bad) = angles.iter().find(|t| !(**t >= 0.0 && **t < 90.0)) {
        return Err(TaskError::invalid(
            "theta_deg",
            format!("{bad}: the view zenith angle must lie in [0, 90)"),
        ));
    }
    Ok(angles)
}

/// The weights of the band mean: the response's, times `B_λ(T)` at `temperature_k`,
/// normalized.
///
/// # Errors
/// [`TaskError::Invalid`] naming `temperature_k` when Planck's law gives no radiance over the
/// band.
pub fn band_weights(nodes: &[(f64, Material)], temperature_k: Option<f64>) -> TaskResult<Vec<f64>> {
    let Some(t) = temperature_k else {
        return Ok(nodes.iter().map(|(w, _)| *w).collect());
    };
    let w: Vec<f64> = nodes
        .iter()
        .map(|(w, m)| w * planck(m.wavelength_um().unwrap_or(1.0), t))
        .collect();
    let total: f64 = w.iter().sum();
    if total.is_nan() || total <= 0.0 {
        return Err(TaskError::invalid(
            "temperature_k",
            format!("{t}: Planck's law gives no radiance over the band"),
        ));
    }
    Ok(w.iter().map(|x| x / total).collect())
}

/// The emissivity Stokes vector at each view angle (route A, with route B for the
/// reciprocity residual), weighted over the spectrum's nodes; values outside [0, 1] are
/// reported (`valid = false`), never clipped. The request is checked before the material is
/// read (options before data).
///
/// # Errors
/// [`TaskError::Invalid`] naming `theta_deg`, `temperature_k` or `material` (the `paper`
/// form has no emissivity: its integrals diverge); as [`SpectralRequest::spectrum`].
pub fn emission(request: &EmissionRequest) -> TaskResult<EmissionTable> {
    let (angles, spectrum) = validated(request)?;
    let material = NamedMaterial::load(&request.material, "material")?;
    compute(material, &angles, request.temperature_k, spectrum)
}

/// [`emission`] of a material already built (the Python `Material`), named `material` in
/// messages; `request.material` is only its display source.
///
/// # Errors
/// As [`emission`].
pub fn emission_of(
    material: NamedMaterial,
    request: &EmissionRequest,
) -> TaskResult<EmissionTable> {
    let (angles, spectrum) = validated(request)?;
    compute(material, &angles, request.temperature_k, spectrum)
}

/// The request's angles (with their default) and spectrum, every number checked.
fn validated(request: &EmissionRequest) -> TaskResult<(Vec<f64>, Option<Spectrum>)> {
    let angles = angles(&request.theta_deg)?;
    if let Some(t) = request.temperature_k {
        if request.spectral.band.is_none() {
            return Err(TaskError::usage(
                "temperature_k",
                "weights a band's wavelengths: give a band",
            ));
        }
        if !(t.is_finite() && t > 0.0) {
            return Err(TaskError::invalid(
                "temperature_k",
                format!("{t}: a temperature must be finite and > 0 K"),
            ));
        }
    }
    Ok((angles, request.spectral.spectrum()?))
}

/// The table of `material` at `angles` (degrees, checked) over `spectrum`.
fn compute(
    material: NamedMaterial,
    angles: &[f64],
    temperature_k: Option<f64>,
    spectrum: Option<Spectrum>,
) -> TaskResult<EmissionTable> {
    let nodes = material_at(&material, spectrum.as_ref())?;
    let weights = band_weights(&nodes, temperature_k)?;
    let thetas: Vec<f64> = angles.iter().map(|t| t.to_radians()).collect();
    let zero = Stokes([0.0; 4]);
    let mut rows: Vec<EmissionRow> = thetas
        .iter()
        .zip(angles)
        .map(|(&t, &d)| EmissionRow {
            theta_deg: d,
            emissivity: Emissivity {
                theta_r: t,
                eps: zero,
                eps_b: zero,
            },
            valid: true,
        })
        .collect();
    for ((_, m), w) in nodes.iter().zip(&weights) {
        let at = emissivities(m, &thetas)
            .map_err(|e| TaskError::invalid("material", format!("{}: {e}", material.source)))?;
        for (row, e) in rows.iter_mut().zip(&at) {
            row.emissivity.eps = row.emissivity.eps.combine(1.0, &e.eps, *w);
            row.emissivity.eps_b = row.emissivity.eps_b.combine(1.0, &e.eps_b, *w);
            row.valid &= e.is_valid();
        }
    }
    for row in &mut rows {
        row.valid &= row.emissivity.is_valid();
    }
    Ok(EmissionTable {
        material,
        spectrum,
        rows,
    })
}
