//! Hemisphere maps of one material under a collimated source: the illumination and the viewing
//! grid of a request, and the BRDF and reflected Stokes vector at every grid direction
//! (averaged over a band's nodes), as a table.

use crate::error::{TaskError, TaskResult};
use crate::spectrum::{material_at, NamedMaterial, SpectralRequest};
use polbrdf::analysis::contrast::{hemisphere_mean, Illumination, ViewGrid, ViewSample};
use polbrdf::analysis::emissivity;
use polbrdf::{Material, Spectrum, Stokes};

/// A collimated source (the sun): zenith angle (required), azimuth and Stokes vector, degrees.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LightRequest {
    /// Zenith angle of the source, degrees, in [0, 90).
    pub sun_zenith_deg: Option<f64>,
    /// Azimuth of the source, degrees (default 0; the specular direction is 180° away).
    pub sun_azimuth_deg: f64,
    /// The input Stokes vector (psps basis of the incident beam; normalized to S0 = 1);
    /// `None`: unpolarized.
    pub stokes: Option<[f64; 4]>,
}

impl LightRequest {
    /// An unpolarized sun at `(zenith, azimuth)` degrees.
    pub fn sun(sun_zenith_deg: f64, sun_azimuth_deg: f64) -> Self {
        Self {
            sun_zenith_deg: Some(sun_zenith_deg),
            sun_azimuth_deg,
            stokes: None,
        }
    }

    /// The validated illumination.
    ///
    /// # Errors
    /// [`TaskError::Usage`] without a zenith angle; [`TaskError::Model`] for a source at or
    /// below the horizon or a Stokes vector that is not physical.
    pub fn illumination(&self) -> TaskResult<Illumination> {
        let stokes = self.stokes.map_or_else(Stokes::unpolarized, Stokes);
        let Some(zenith) = self.sun_zenith_deg else {
            return Err(TaskError::usage(
                "sun_zenith_deg",
                "is required (the zenith angle of the source, degrees)",
            ));
        };
        Ok(Illumination::from_degrees(
            zenith,
            self.sun_azimuth_deg,
            stokes,
        )?)
    }
}

/// The default grid steps `(Δθ, Δφ)` of the hemisphere jobs, degrees (16 200 directions).
pub const DEFAULT_GRID_DEG: (f64, f64) = (1.0, 2.0);

/// The viewing grid of steps `(Δθ, Δφ)` in degrees (the azimuth step rounded to divide 360°).
///
/// # Errors
/// [`TaskError::Model`] for a step that is not positive or a grid over the core's size limit.
pub fn view_grid((theta_step_deg, phi_step_deg): (f64, f64)) -> TaskResult<ViewGrid> {
    Ok(ViewGrid::from_degrees(theta_step_deg, phi_step_deg)?)
}

/// A grid angle (rad) in degrees, rounded to 1e-9° so that grid nodes print exactly (every
/// table and summary of the hemisphere jobs shows angles through it).
pub fn deg(x: f64) -> f64 {
    let d = (x.to_degrees() * 1e9).round() / 1e9;
    d + 0.0
}

/// A hemisphere map: one material, a source and a viewing grid.
#[derive(Debug, Clone, PartialEq)]
pub struct HemisphereRequest {
    /// A material file or a preset name.
    pub material: String,
    /// The source.
    pub light: LightRequest,
    /// Grid steps `(Δθ, Δφ)`, degrees.
    pub grid_deg: (f64, f64),
    /// The wavelength or band.
    pub spectral: SpectralRequest,
}

/// The map of [`hemisphere`].
#[derive(Debug, Clone)]
pub struct Hemisphere {
    /// The material.
    pub material: NamedMaterial,
    /// The spectrum it was evaluated at.
    pub spectrum: Option<Spectrum>,
    /// The source.
    pub light: Illumination,
    /// The viewing grid.
    pub grid: ViewGrid,
    /// One sample per grid direction, zenith-major.
    pub samples: Vec<ViewSample>,
    /// The grid zeniths (rad) where the model is flagged invalid ([`invalid_zeniths`]).
    pub invalid_zeniths: Vec<f64>,
}

impl Hemisphere {
    /// The columns of [`Hemisphere::rows`] (`map.csv`).
    pub const COLUMNS: [&'static str; 9] = [
        "theta_r_deg",
        "phi_r_deg",
        "brdf",
        "s0",
        "s1",
        "s2",
        "s3",
        "dolp",
        "aolp_deg",
    ];

    /// One row per grid direction, the values of [`Hemisphere::COLUMNS`].
    pub fn rows(&self) -> impl Iterator<Item = Vec<f64>> + '_ {
        self.samples.iter().map(|s| {
            let [s0, s1, s2, s3] = s.stokes.0;
            vec![
                deg(s.theta_r),
                deg(s.phi_r),
                s.brdf,
                s0,
                s1,
                s2,
                s3,
                s.stokes.dolp(),
                s.stokes.aolp().to_degrees(),
            ]
        })
    }

    /// The direction of the highest DoLP among those with a finite S0.
    pub fn highest_dolp(&self) -> Option<&ViewSample> {
        self.samples
            .iter()
            .filter(|s| s.stokes.0[0].is_finite())
            .max_by(|a, b| a.stokes.dolp().total_cmp(&b.stokes.dolp()))
    }
}

/// The hemisphere map of a material: BRDF and reflected Stokes vector per unit irradiance at
/// every grid direction, the weighted sum over the spectrum's nodes (never of DoLPs).
///
/// # Errors
/// As [`LightRequest::illumination`], [`view_grid`], [`SpectralRequest::spectrum`],
/// [`NamedMaterial::load`] and [`crate::spectrum::materials_at`] (validated in that order).
pub fn hemisphere(request: &HemisphereRequest) -> TaskResult<Hemisphere> {
    let light = request.light.illumination()?;
    let grid = view_grid(request.grid_deg)?;
    let spectrum = request.spectral.spectrum()?;
    let material = NamedMaterial::load(&request.material, "material")?;
    let nodes = material_at(&material, spectrum.as_ref())?;
    let samples = hemisphere_mean(&nodes, &light, &grid);
    let materials: Vec<&Material> = nodes.iter().map(|(_, m)| m).collect();
    let invalid_zeniths = invalid_zeniths(&materials, &grid);
    Ok(Hemisphere {
        material,
        spectrum,
        light,
        grid,
        samples,
        invalid_zeniths,
    })
}

/// The grid zeniths (rad) where the model is flagged invalid: the material's emissivity toward
/// that zenith — by reciprocity one minus the reflectance of light arriving from there — lies
/// outside `[0, 1]` for some polarization at some node of the spectrum (`nodes`: the material
/// at each node; `Emissivity::is_valid`, docs/model.md §10, §16): the model reflects more than
/// it receives there. Empty for the `paper` form, whose hemispherical integral diverges (no
/// finite flag). At most one emissivity per zenith and node (a hemispherical integral each).
pub fn invalid_zeniths(nodes: &[&Material], grid: &ViewGrid) -> Vec<f64> {
    grid.thetas()
        .into_iter()
        .filter(|&t| t < std::f64::consts::FRAC_PI_2)
        .filter(|&t| {
            nodes
                .iter()
                .any(|m| emissivity(m, t).is_ok_and(|e| !e.is_valid()))
        })
        .collect()
}
