//! One material over the viewing hemisphere (full Mueller) and in the plane of incidence:
//! the task layer's `explore` job for the page.

use crate::{js_error, light, material, spectral};
use polbrdf_tasks::explore::{self, InPlane, MuellerMap};
use polbrdf_tasks::hemisphere::deg;
use wasm_bindgen::prelude::*;

/// A hemisphere map ([`hemisphere`]): per grid node `i = k·n_phi + j` (zenith `k`, azimuth
/// `j`) the full `F`, the BRDF, the reflected Stokes vector, its DoLP and AoLP.
#[wasm_bindgen]
pub struct MapView {
    map: MuellerMap,
}

#[wasm_bindgen]
impl MapView {
    /// Number of zenith angles.
    pub fn n_theta(&self) -> usize {
        self.map.grid.n_theta()
    }
    /// Number of azimuths.
    pub fn n_phi(&self) -> usize {
        self.map.grid.n_phi()
    }
    /// The zenith angles, degrees (as the map CSV prints them).
    pub fn thetas_deg(&self) -> Vec<f64> {
        self.map.grid.thetas().into_iter().map(deg).collect()
    }
    /// The azimuths, degrees (as the map CSV prints them).
    pub fn phis_deg(&self) -> Vec<f64> {
        self.map.grid.phis().into_iter().map(deg).collect()
    }
    /// Entry `e` (0…15, row-major: `m_rc` at `4r + c`) of `F` at every node (sr⁻¹).
    pub fn mueller(&self, e: usize) -> Vec<f64> {
        self.map
            .mueller
            .iter()
            .map(|f| f.get(e).copied().unwrap_or(f64::NAN))
            .collect()
    }
    /// The BRDF `F00` at every node (sr⁻¹).
    pub fn brdf(&self) -> Vec<f64> {
        self.mueller(0)
    }
    /// The DoLP of the reflected beam at every node.
    pub fn dolp(&self) -> Vec<f64> {
        self.map.stokes.iter().map(|s| s.dolp()).collect()
    }
    /// The AoLP of the reflected beam at every node, degrees in (−90, 90].
    pub fn aolp_deg(&self) -> Vec<f64> {
        self.map
            .stokes
            .iter()
            .map(|s| s.aolp().to_degrees())
            .collect()
    }
    /// The names of [`MapView::node`]'s values (the map CSV's columns).
    pub fn columns(&self) -> Vec<String> {
        MuellerMap::columns()
    }
    /// Node `i`'s row of the map CSV: θr, φr, BRDF, S0…S3, DoLP, AoLP, `m00 … m33`; empty
    /// beyond the grid.
    pub fn node(&self, i: usize) -> Vec<f64> {
        self.map.row(i).unwrap_or_default()
    }
    /// The map as CSV (the project's CSV writer: shortest round-trip numbers).
    pub fn csv(&self) -> Vec<u8> {
        polbrdf_io::CsvTable::document(MuellerMap::columns(), self.map.rows())
    }
}

/// The full-Mueller hemisphere map of the material file `text` (named `file_name` in
/// messages) under a sun at `(sun_zenith_deg, sun_azimuth_deg)` with incident Stokes vector
/// `stokes` (four components), at `wavelength_um` or over the band whose file's text is
/// `band_csv` (`band.csv` in messages; columns wavelength_um,response) with the quadrature step
/// `band_step_um` (needed for a spectral index), on the grid of steps `(dtheta_deg, dphi_deg)`.
///
/// # Errors
/// The task layer's message: the material file's (line, key), the source's, the grid's.
#[wasm_bindgen]
#[allow(clippy::too_many_arguments)] // The page's controls, one argument each.
pub fn hemisphere(
    text: &str,
    file_name: &str,
    sun_zenith_deg: f64,
    sun_azimuth_deg: f64,
    stokes: &[f64],
    wavelength_um: Option<f64>,
    band_csv: Option<String>,
    band_step_um: Option<f64>,
    dtheta_deg: f64,
    dphi_deg: f64,
) -> Result<MapView, JsError> {
    let m = material(text, file_name, "material")?;
    let l = light(sun_zenith_deg, sun_azimuth_deg, stokes)?;
    let s = spectral(wavelength_um, band_csv, band_step_um);
    let map = explore::mueller_map(&m, &l, (dtheta_deg, dphi_deg), &s).map_err(js_error)?;
    Ok(MapView { map })
}

/// The in-plane curves ([`in_plane`]).
#[wasm_bindgen]
pub struct InPlaneView {
    curves: InPlane,
}

#[wasm_bindgen]
impl InPlaneView {
    /// Signed view zenith angles in the plane of incidence, degrees (positive: specular side).
    pub fn theta_r_deg(&self) -> Vec<f64> {
        self.curves.theta_r_deg.clone()
    }
    /// The BRDF at each of them (sr⁻¹).
    pub fn brdf(&self) -> Vec<f64> {
        self.curves.brdf.clone()
    }
    /// The reflected beam's DoLP at each of them.
    pub fn dolp(&self) -> Vec<f64> {
        self.curves.dolp.clone()
    }
    /// Angles of incidence of the specular curve, degrees.
    pub fn theta_i_deg(&self) -> Vec<f64> {
        self.curves.theta_i_deg.clone()
    }
    /// The specular DoLP at each angle of incidence.
    pub fn specular_dolp(&self) -> Vec<f64> {
        self.curves.specular_dolp.clone()
    }
}

/// The in-plane curves of the material file `text` under the sun and Stokes vector given (as
/// [`hemisphere`]): BRDF and DoLP in the plane of incidence, and the specular DoLP against
/// the angle of incidence.
///
/// # Errors
/// As [`hemisphere`].
#[wasm_bindgen]
#[allow(clippy::too_many_arguments)] // The page's controls, one argument each.
pub fn in_plane(
    text: &str,
    file_name: &str,
    sun_zenith_deg: f64,
    sun_azimuth_deg: f64,
    stokes: &[f64],
    wavelength_um: Option<f64>,
    band_csv: Option<String>,
    band_step_um: Option<f64>,
) -> Result<InPlaneView, JsError> {
    let m = material(text, file_name, "material")?;
    let l = light(sun_zenith_deg, sun_azimuth_deg, stokes)?;
    let s = spectral(wavelength_um, band_csv, band_step_um);
    let curves = explore::in_plane(&m, &l, &s).map_err(js_error)?;
    Ok(InPlaneView { curves })
}
