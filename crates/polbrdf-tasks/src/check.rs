//! Physical validity of a parameter set (docs/model.md §10): F realizable over a dense grid,
//! albedo ≤ 1 at every incidence angle, reciprocity where the model form has it — at every
//! spectral node of a band, with the worst node of each check.

use crate::error::{TaskError, TaskResult};
use crate::spectrum::{materials_at, SpectralRequest};
use polbrdf::{physical_validity, CheckGrid, Spectrum, ValidityReport};

/// A check request.
#[derive(Debug, Clone, PartialEq)]
pub struct CheckRequest {
    /// A material file or a preset name.
    pub material: String,
    /// Zenith step of the grid, degrees, in (0, 30] (the relative azimuth uses twice this).
    pub grid_deg: f64,
    /// The wavelength or band.
    pub spectral: SpectralRequest,
}

impl CheckRequest {
    /// The number of geometries of the grid (θi × θr × Δφ), `None` on overflow: to bound it
    /// before anything is allocated.
    pub fn geometries(&self) -> Option<usize> {
        let zeniths = (90.0 / self.grid_deg).ceil() as usize;
        let azimuths = (180.0 / self.grid_deg).ceil() as usize;
        zeniths.checked_mul(zeniths)?.checked_mul(azimuths)
    }
}

/// The result of [`check`]: one report per spectral node.
#[derive(Debug, Clone)]
pub struct CheckOutcome {
    /// The material's name (its `name` key, else what the request gave).
    pub name: String,
    /// The spectrum.
    pub spectrum: Option<Spectrum>,
    /// `(wavelength of the node, report)`.
    pub reports: Vec<(Option<f64>, ValidityReport)>,
}

impl CheckOutcome {
    /// The node with the largest `key`.
    fn worst(&self, key: impl Fn(&ValidityReport) -> f64) -> &(Option<f64>, ValidityReport) {
        self.reports
            .iter()
            .max_by(|a, b| key(&a.1).total_cmp(&key(&b.1)))
            .expect("at least one node")
    }

    /// The node least realizable (smallest coherency eigenvalue).
    pub fn worst_realizability(&self) -> &(Option<f64>, ValidityReport) {
        self.worst(|r| -r.min_coherency.0)
    }

    /// The node with the largest albedo.
    pub fn worst_energy(&self) -> &(Option<f64>, ValidityReport) {
        self.worst(|r| r.max_albedo().total())
    }

    /// The node with the largest reciprocity deviation.
    pub fn worst_reciprocity(&self) -> &(Option<f64>, ValidityReport) {
        self.worst(|r| r.reciprocity.0.max(r.reciprocity.1))
    }

    /// Whether every check passes at every node.
    pub fn passes(&self) -> bool {
        self.reports.iter().all(|(_, r)| r.passes())
    }
}

/// Runs every check at each spectral node.
///
/// # Errors
/// [`TaskError::Invalid`] naming `grid_deg`; [`TaskError::Io`] for the material;
/// as [`SpectralRequest::spectrum`].
pub fn check(request: &CheckRequest) -> TaskResult<CheckOutcome> {
    let g = request.grid_deg;
    if !(g.is_finite() && g > 0.0 && g <= 30.0) {
        return Err(TaskError::invalid(
            "grid_deg",
            format!("{g}: must lie in (0, 30]"),
        ));
    }
    // The spectral options before the material file (issue 35: options before data).
    let spectrum = request.spectral.spectrum()?;
    let spec = polbrdf_io::load_material(&request.material)?;
    let material = crate::spectrum::NamedMaterial {
        name: spec
            .name
            .clone()
            .unwrap_or_else(|| request.material.clone()),
        spec,
        source: request.material.clone(),
        field: "material".into(),
    };
    let nodes = materials_at(&[&material], spectrum.as_ref())?;
    let grid = CheckGrid {
        zenith_step: g.to_radians(),
        azimuth_step: (2.0 * g).to_radians(),
    };
    let reports = nodes
        .iter()
        .map(|(_, ms)| (ms[0].wavelength_um(), physical_validity(&ms[0], &grid)))
        .collect();
    Ok(CheckOutcome {
        name: material.name,
        spectrum,
        reports,
    })
}
