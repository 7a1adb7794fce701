//! Target against background under the page's sun, or in the page's scene (sun, sky, thermal
//! emission): the task layer's contrast study (the map, the ranked best views and `best.json`,
//! as `polbrdf contrast` and `polbrdf contrast --scene` write them).

use crate::{js_error, light, material, spectral, BAND_FILE};
use polbrdf_tasks::contrast::{
    contrast as contrast_study, contrast_of, ContrastRequest, ContrastStudy, RankRequest,
    SourceRequest,
};
use wasm_bindgen::prelude::*;

/// A contrast study ([`contrast`]): the columns of `contrast.csv` per grid node (zenith-major,
/// as the hemisphere map) and the `best.json` document.
#[wasm_bindgen]
pub struct ContrastView {
    study: ContrastStudy,
}

#[wasm_bindgen]
impl ContrastView {
    /// The names of the columns ([`ContrastView::column`]), as in `contrast.csv`.
    pub fn columns(&self) -> Vec<String> {
        self.study.columns().iter().map(|s| s.to_string()).collect()
    }
    /// Column `name` of `contrast.csv` at every grid node (empty for an unknown name).
    pub fn column(&self, name: &str) -> Vec<f64> {
        match self.study.columns().iter().position(|c| *c == name) {
            Some(k) => self.study.rows().map(|r| r[k]).collect(),
            None => Vec::new(),
        }
    }
    /// Number of grid nodes.
    pub fn len(&self) -> usize {
        self.study.map.samples.len()
    }
    /// Whether the grid is empty (never).
    pub fn is_empty(&self) -> bool {
        self.study.map.samples.is_empty()
    }
    /// The `best.json` document (the best direction and the ranked ones), as `polbrdf
    /// contrast` writes it.
    pub fn best_json(&self) -> String {
        serde_json::to_string_pretty(&self.study.best_json()).unwrap_or_default()
    }
    /// Whether the study is in a scene (observed radiances; `contrast.csv` then has the
    /// column `radiance_difference`).
    pub fn is_scene(&self) -> bool {
        self.study.is_scene()
    }
    /// The setup's warnings (valid but probably not what was meant), as the command line
    /// prints them.
    pub fn warnings(&self) -> Vec<String> {
        self.study.warnings.iter().map(|w| w.to_string()).collect()
    }
    /// `contrast.csv` (the project's CSV writer).
    pub fn csv(&self) -> Vec<u8> {
        polbrdf_io::CsvTable::document(self.study.columns(), self.study.rows())
    }
}

/// The contrast of the material files `target` and `background` (texts, named `target.toml`
/// and `background.toml` in messages) under the sun and Stokes vector given, at
/// `wavelength_um` or over the band of the band file's text `band_csv` with the quadrature
/// step `band_step_um`, on the grid of steps `(dtheta_deg, dphi_deg)`; best views ranked by
/// `rank_by` (`delta-dolp` or `polarization-contrast`), `top` of them at least
/// `min_separation_deg` apart, zenith ≤ `max_zenith_deg`, refined when `refine`.
///
/// # Errors
/// The task layer's message (the materials', the ranking's, the source's, the grid's).
#[wasm_bindgen]
#[allow(clippy::too_many_arguments)] // The page's controls, one argument each.
pub fn contrast(
    target: &str,
    background: &str,
    sun_zenith_deg: f64,
    sun_azimuth_deg: f64,
    stokes: &[f64],
    wavelength_um: Option<f64>,
    band_csv: Option<String>,
    band_step_um: Option<f64>,
    dtheta_deg: f64,
    dphi_deg: f64,
    rank_by: &str,
    top: usize,
    min_separation_deg: f64,
    max_zenith_deg: f64,
    refine: bool,
) -> Result<ContrastView, JsError> {
    let rank = rank_request(rank_by, top, min_separation_deg, max_zenith_deg, refine)?;
    let t = material(target, "target.toml", "target")?;
    let b = material(background, "background.toml", "background")?;
    let l = light(sun_zenith_deg, sun_azimuth_deg, stokes)?;
    let study = contrast_of(
        t,
        b,
        &l,
        &spectral(wavelength_um, band_csv, band_step_um),
        (dtheta_deg, dphi_deg),
        rank,
    )
    .map_err(js_error)?;
    Ok(ContrastView { study })
}

/// The ranking of a contrast request.
fn rank_request(
    rank_by: &str,
    top: usize,
    min_separation_deg: f64,
    max_zenith_deg: f64,
    refine: bool,
) -> Result<RankRequest, JsError> {
    let by = rank_by
        .parse()
        .map_err(|e: String| JsError::new(&format!("rank_by: {e}")))?;
    Ok(RankRequest {
        by,
        top,
        min_separation_deg,
        max_zenith_deg,
        refine,
    })
}

/// The contrast in the scene file `scene` (its text, named `scene.toml` in messages) as
/// `polbrdf contrast --scene scene.toml` computes it: the files it names are the page's —
/// `target.toml` and `background.toml` (the texts `target` and `background`) and, when
/// `band_csv` is given, `band.csv`. Grid and ranking as [`contrast`].
///
/// # Errors
/// The scene reader's message (file, line, key; the command line's for the same files), the
/// ranking's, the grid's, the materials' over the scene's spectrum.
#[wasm_bindgen]
#[allow(clippy::too_many_arguments)] // The page's controls, one argument each.
pub fn scene_contrast(
    scene: &str,
    target: &str,
    background: &str,
    band_csv: Option<String>,
    dtheta_deg: f64,
    dphi_deg: f64,
    rank_by: &str,
    top: usize,
    min_separation_deg: f64,
    max_zenith_deg: f64,
    refine: bool,
) -> Result<ContrastView, JsError> {
    let rank = rank_request(rank_by, top, min_separation_deg, max_zenith_deg, refine)?;
    let mut files = vec![
        ("target.toml".to_string(), target.to_string()),
        ("background.toml".to_string(), background.to_string()),
    ];
    files.extend(band_csv.map(|b| (BAND_FILE.to_string(), b)));
    let scene = polbrdf_tasks::scene::parse_scene_with_files(scene, "scene.toml", &files)
        .map_err(js_error)?;
    let study = contrast_study(&ContrastRequest {
        target: None,
        background: None,
        source: SourceRequest::Loaded(Box::new(scene)),
        grid_deg: (dtheta_deg, dphi_deg),
        rank,
    })
    .map_err(js_error)?;
    Ok(ContrastView { study })
}
