//! Physical validity of a parameter set (docs/model.md §10): F realizable over a dense grid,
//! albedo ≤ 1 at every incidence angle, reciprocity where the model form has it — at every
//! spectral node of a band, with the worst node of each check.

use crate::error::{TaskError, TaskResult};
use crate::spectrum::{materials_at, spectrum_json, NamedMaterial, SpectralRequest};
use polbrdf::{physical_validity, CheckGrid, Geometry, Spectrum, ValidityReport};
use serde_json::{json, Value};

/// The grid's default zenith step, degrees (`polbrdf check --grid-deg`, Python's `grid_deg`).
pub const DEFAULT_GRID_DEG: f64 = 5.0;

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
    /// The grid's zenith step, degrees (the relative azimuth's is twice this).
    pub grid_deg: f64,
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

/// Runs every check at each spectral node. The grid step, its size and the spectrum are
/// checked before the material is read.
///
/// # Errors
/// [`TaskError::Invalid`] naming `grid_deg`, [`TaskError::Limit`] for a grid over
/// [`crate::limits::CHECK_GEOMETRIES`]; [`TaskError::Io`] for the material;
/// as [`SpectralRequest::spectrum`].
pub fn check(request: &CheckRequest) -> TaskResult<CheckOutcome> {
    let spectrum = validated(request)?;
    let spec = polbrdf_io::load_material(&request.material)?;
    let material = NamedMaterial {
        name: spec
            .name
            .clone()
            .unwrap_or_else(|| request.material.clone()),
        spec,
        source: request.material.clone(),
        field: "material".into(),
    };
    compute(material, request.grid_deg, spectrum)
}

/// [`check`] of a material already built (the Python `Material`); `request.material` is not
/// read.
///
/// # Errors
/// As [`check`].
pub fn check_of(material: NamedMaterial, request: &CheckRequest) -> TaskResult<CheckOutcome> {
    let spectrum = validated(request)?;
    compute(material, request.grid_deg, spectrum)
}

/// The grid step and size and the spectrum, checked (options before data, issue 35).
fn validated(request: &CheckRequest) -> TaskResult<Option<Spectrum>> {
    let g = request.grid_deg;
    if !(g.is_finite() && g > 0.0 && g <= 30.0) {
        return Err(TaskError::invalid(
            "grid_deg",
            format!("{g}: must lie in (0, 30]"),
        ));
    }
    // The grid's size (physical_validity's loops), bounded before it is allocated.
    let max = crate::limits::CHECK_GEOMETRIES;
    if request.geometries().is_none_or(|n| n > max) {
        return Err(TaskError::Limit {
            field: "grid_deg".into(),
            what: format!(
                " = {g:e}: more than {max} geometries of the grid (a step under about 0.9°)"
            ),
            max,
        });
    }
    request.spectral.spectrum()
}

/// Every check of `material` at each node of `spectrum`.
fn compute(
    material: NamedMaterial,
    g: f64,
    spectrum: Option<Spectrum>,
) -> TaskResult<CheckOutcome> {
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
        grid_deg: g,
        spectrum,
        reports,
    })
}

/// A geometry as `[θi, φi, θr, φr]` in degrees.
fn degrees(g: &Geometry) -> [f64; 4] {
    [g.theta_i(), g.phi_i(), g.theta_r(), g.phi_r()].map(f64::to_degrees)
}

/// One node's entry of the check's document.
fn node_json(wavelength_um: Option<f64>, r: &ValidityReport) -> Value {
    let albedo: Vec<Value> = r
        .albedo
        .iter()
        .map(|a| {
            json!({"theta_i_deg": a.theta_i.to_degrees(), "albedo": a.total(),
                   "surface": a.surface, "volume": a.volume})
        })
        .collect();
    json!({
        "wavelength_um": wavelength_um,
        "passes": r.passes(),
        "realizable": r.realizable(),
        "min_coherency": r.min_coherency.0,
        "min_coherency_at_deg": degrees(&r.min_coherency.1),
        "conserves_energy": r.conserves_energy(),
        "albedo": albedo,
        "reciprocity_expected": r.reciprocity_expected,
        "reciprocal": r.reciprocal(),
        "reciprocity_scalar": r.reciprocity.0,
        "reciprocity_matrix": r.reciprocity.1,
        "reciprocity_at_deg": degrees(&r.reciprocity.2),
    })
}

impl CheckOutcome {
    /// The check's document (`polbrdf check --output`, Python's `CheckReport.document`): the
    /// material, the grid, the spectrum, whether everything passes, and every node's checks
    /// (angles in degrees; `min_coherency` relative to F00; the albedo at θi = 0°, 5°, …, 85°).
    pub fn to_json(&self) -> Value {
        let first = &self.reports[0].1;
        json!({
            "material": self.name,
            "grid_deg": {"zenith": self.grid_deg, "azimuth": 2.0 * self.grid_deg},
            "geometries": first.geometries,
            "spectrum": spectrum_json(self.spectrum.as_ref(), self.reports.len()),
            "passes": self.passes(),
            "nodes": self.reports.iter().map(|(l, r)| node_json(*l, r)).collect::<Vec<_>>(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn request(grid_deg: f64) -> CheckRequest {
        CheckRequest {
            material: "paint".into(),
            grid_deg,
            spectral: SpectralRequest::default(),
        }
    }

    #[test]
    fn a_grid_over_its_limit_is_refused_before_the_material_is_read() {
        let mut r = request(0.5);
        r.material = "/nonexistent/material.toml".into();
        match check(&r).unwrap_err() {
            TaskError::Limit { field, max, .. } => {
                assert_eq!(
                    (field.as_str(), max),
                    ("grid_deg", crate::limits::CHECK_GEOMETRIES)
                );
            }
            e => panic!("{e}"),
        }
        // 1° is within the limit: 90 · 90 zeniths × 180 relative azimuths.
        assert_eq!(request(1.0).geometries(), Some(1_458_000));
    }

    #[test]
    fn the_document_holds_every_node_and_the_verdict() {
        let out = check(&request(10.0)).unwrap();
        let doc = out.to_json();
        assert_eq!(doc["material"], out.name.as_str());
        assert_eq!(doc["passes"], out.passes());
        // 9 zeniths of incidence and of view, 18 relative azimuths (a step of 20°).
        assert_eq!(doc["geometries"], 9 * 9 * 18);
        let node = &doc["nodes"][0];
        assert_eq!(node["albedo"].as_array().unwrap().len(), 18);
        assert_eq!(node["min_coherency"], out.reports[0].1.min_coherency.0);
    }
}
