//! Energy conservation of a parameter set: the directional–hemispherical reflectance (albedo)
//! at a set of incidence angles, averaged over a band's nodes, with a verdict on values above 1.

use crate::error::{TaskError, TaskResult};
use crate::spectrum::{describe, material_at, NamedMaterial, SpectralRequest};
use polbrdf::{directional_hemispherical, Albedo, Spectrum};

/// An albedo request.
#[derive(Debug, Clone, PartialEq)]
pub struct AlbedoRequest {
    /// A material file or a preset name.
    pub material: String,
    /// Incidence angles, degrees, in [0, 90); empty: 0, 5, …, 85.
    pub theta_i_deg: Vec<f64>,
    /// The wavelength or band.
    pub spectral: SpectralRequest,
}

/// What the albedos say about energy conservation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Verdict {
    /// The albedo is infinite at `count` angles (the `paper` form's surface integral diverges).
    Diverges {
        /// How many angles.
        count: usize,
    },
    /// The albedo exceeds 1 at `count` angles, most at `theta_i_deg`.
    Exceeds {
        /// How many angles.
        count: usize,
        /// The largest albedo.
        largest: f64,
        /// Where, degrees.
        theta_i_deg: f64,
    },
    /// At or below 1 everywhere.
    Conserves {
        /// The largest albedo.
        largest: f64,
    },
}

/// The result of [`albedo`].
#[derive(Debug, Clone)]
pub struct AlbedoTable {
    /// The material.
    pub material: NamedMaterial,
    /// The spectrum.
    pub spectrum: Option<Spectrum>,
    /// `(θi in degrees as requested, albedo)`, one per angle.
    pub rows: Vec<(f64, Albedo)>,
}

impl AlbedoTable {
    /// The columns of the table.
    pub const COLUMNS: [&'static str; 5] =
        ["theta_i_deg", "albedo", "surface", "volume", "exceeds_one"];

    /// The material and spectrum in words.
    pub fn title(&self) -> String {
        format!("{}{}", self.material.name, describe(self.spectrum.as_ref()))
    }

    /// The verdict over all angles.
    pub fn verdict(&self) -> Verdict {
        let over: Vec<(f64, f64)> = self
            .rows
            .iter()
            .filter(|(_, a)| a.total() > 1.0)
            .map(|(t, a)| (*t, a.total()))
            .collect();
        let infinite = over.iter().filter(|(_, v)| v.is_infinite()).count();
        if infinite > 0 {
            Verdict::Diverges { count: infinite }
        } else if let Some(&(t, v)) = over.iter().max_by(|a, b| a.1.total_cmp(&b.1)) {
            Verdict::Exceeds {
                count: over.len(),
                largest: v,
                theta_i_deg: t,
            }
        } else {
            Verdict::Conserves {
                largest: self.rows.iter().map(|(_, a)| a.total()).fold(0.0, f64::max),
            }
        }
    }
}

/// The albedo at each incidence angle: over a band, the response-weighted mean of the albedos
/// at the band's nodes (each through the engine, in parallel).
///
/// # Errors
/// [`TaskError::Invalid`] naming `theta_i_deg` ([`TaskError::Limit`] over
/// [`crate::limits::ANGLES`] angles); as [`SpectralRequest::spectrum`] and
/// [`NamedMaterial::load`].
pub fn albedo(request: &AlbedoRequest) -> TaskResult<AlbedoTable> {
    let angles: Vec<f64> = if request.theta_i_deg.is_empty() {
        (0..18).map(|k| 5.0 * f64::from(k)).collect()
    } else {
        request.theta_i_deg.clone()
    };
    crate::limits::count_at_most("theta_i_deg", angles.len(), crate::limits::ANGLES)?;
    if let Some(bad) = angles.iter().find(|t| !(**t >= 0.0 && **t < 90.0)) {
        return Err(TaskError::invalid(
            "theta_i_deg",
            format!("{bad}: the incidence angle must lie in [0, 90)"),
        ));
    }
    let spectrum = request.spectral.spectrum()?;
    let material = NamedMaterial::load(&request.material, "material")?;
    let nodes = material_at(&material, spectrum.as_ref())?;
    let rows = angles
        .iter()
        .map(|t| {
            let mut a = Albedo {
                theta_i: t.to_radians(),
                surface: 0.0,
                volume: 0.0,
            };
            for (w, m) in &nodes {
                let x = directional_hemispherical(m, t.to_radians());
                a.surface += w * x.surface;
                a.volume += w * x.volume;
            }
            (*t, a)
        })
        .collect();
    Ok(AlbedoTable {
        material,
        spectrum,
        rows,
    })
}
