//! # polbrdf-wasm — the web explorer's WebAssembly module
//!
//! A thin adapter, like the command line and the Python module: it takes the page's values
//! (material files as text, angles in degrees), calls the task layer (`polbrdf-tasks`:
//! [`explore`](polbrdf_tasks::explore) for the hemisphere maps and in-plane curves,
//! [`contrast_of`](polbrdf_tasks::contrast::contrast_of) for target against background) and
//! hands back plain arrays, JSON and CSV. No physics here, none in JavaScript. The page
//! (`web/`) and how to build it: docs/explorer.md.
//!
//! Errors reach JavaScript as thrown `Error`s whose message is the task layer's, e.g.
//! `material: material.toml:2: field `sigma_deg`: invalid parameter …` — the command line's
//! message for the same file.

mod contrast;
mod map;

pub use contrast::{contrast, scene_contrast, ContrastView};
pub use map::{hemisphere, in_plane, InPlaneView, MapView};

use polbrdf_plot::Colormap;
use polbrdf_tasks::spectrum::NamedMaterial;
use polbrdf_tasks::TaskError;
use wasm_bindgen::prelude::*;

/// A task error as a JavaScript `Error` with the task layer's message.
pub(crate) fn js_error(e: TaskError) -> JsError {
    JsError::new(&e.to_string())
}

/// The package version (the workspace's).
#[wasm_bindgen]
pub fn version() -> String {
    env!("CARGO_PKG_VERSION").to_string()
}

/// The preset material names (`polbrdf materials`).
#[wasm_bindgen]
pub fn presets() -> Vec<String> {
    polbrdf::presets::names()
        .iter()
        .map(|s| s.to_string())
        .collect()
}

/// A preset as the text of a material file (`polbrdf materials --show NAME`).
///
/// # Errors
/// An unknown preset name.
#[wasm_bindgen]
pub fn preset_toml(name: &str) -> Result<String, JsError> {
    let spec = polbrdf::preset(name).map_err(|e| JsError::new(&e.to_string()))?;
    Ok(polbrdf_io::material_to_toml(&spec))
}

/// The refractive-index library as JSON: `[{"id", "material", "description"}]` (a material
/// file names one as `index = "library:<id>"`).
#[wasm_bindgen]
pub fn library_json() -> String {
    let entries: Vec<serde_json::Value> = polbrdf_io::library::entries()
        .iter()
        .map(|e| {
            serde_json::json!({"id": e.id, "material": e.material, "description": e.description})
        })
        .collect();
    serde_json::Value::Array(entries).to_string()
}

/// The keys a material file may hold, in the order the page writes them.
#[wasm_bindgen]
pub fn material_keys() -> Vec<String> {
    polbrdf::model::KEYS.iter().map(|s| s.to_string()).collect()
}

/// Parses a material file's text (`file_name` names it in messages) as `field`.
pub(crate) fn material(text: &str, file_name: &str, field: &str) -> Result<NamedMaterial, JsError> {
    NamedMaterial::parse(text, file_name, field).map_err(js_error)
}

/// The material of a file's text, validated, as a material file again (every key that has a
/// value, in key order: the page's "download material TOML").
///
/// # Errors
/// The file reader's message (file name, line, key).
#[wasm_bindgen]
pub fn material_toml(text: &str, file_name: &str) -> Result<String, JsError> {
    Ok(polbrdf_io::material_to_toml(
        &material(text, file_name, "material")?.spec,
    ))
}

/// The entries of a material file's text, validated, as a JSON object `{key: value}` (for the
/// page's controls).
///
/// # Errors
/// As [`material_toml`].
#[wasm_bindgen]
pub fn material_entries(text: &str, file_name: &str) -> Result<String, JsError> {
    let spec = material(text, file_name, "material")?.spec;
    let map: serde_json::Map<String, serde_json::Value> = spec
        .entries()
        .into_iter()
        .map(|(k, v)| {
            let v = match v {
                polbrdf::model::KeyValue::Number(x) => serde_json::json!(x),
                polbrdf::model::KeyValue::Text(t) => serde_json::json!(t),
                polbrdf::model::KeyValue::Bool(b) => serde_json::json!(b),
            };
            (k.to_string(), v)
        })
        .collect();
    Ok(serde_json::Value::Object(map).to_string())
}

/// The colour map `name` (`viridis`, `diverging`, `cyclic`: polbrdf-plot's, as in the
/// command line's figures) sampled at `n ≥ 2` points from 0 to 1, as RGB bytes (`3·n`); then
/// the colour of undefined values (three more bytes).
///
/// # Errors
/// An unknown name or `n < 2`.
#[wasm_bindgen]
pub fn colormap(name: &str, n: usize) -> Result<Vec<u8>, JsError> {
    let map = match name {
        "viridis" => Colormap::Viridis,
        "diverging" => Colormap::Diverging,
        "cyclic" => Colormap::Cyclic,
        other => {
            return Err(JsError::new(&format!(
                "unknown colour map `{other}` (viridis, diverging, cyclic)"
            )))
        }
    };
    if n < 2 {
        return Err(JsError::new("a colour map needs at least 2 samples"));
    }
    let mut out = Vec::with_capacity(3 * n + 3);
    for k in 0..n {
        let c = map.rgb(k as f64 / (n - 1) as f64);
        out.extend([c.0, c.1, c.2]);
    }
    let u = polbrdf_plot::colormap::UNDEFINED;
    out.extend([u.0, u.1, u.2]);
    Ok(out)
}

/// The source of a page request: sun zenith and azimuth (degrees), incident Stokes vector.
pub(crate) fn light(
    sun_zenith_deg: f64,
    sun_azimuth_deg: f64,
    stokes: &[f64],
) -> Result<polbrdf_tasks::hemisphere::LightRequest, JsError> {
    let stokes: [f64; 4] = stokes
        .try_into()
        .map_err(|_| JsError::new("stokes: give four components S0, S1, S2, S3"))?;
    Ok(polbrdf_tasks::hemisphere::LightRequest {
        sun_zenith_deg: Some(sun_zenith_deg),
        sun_azimuth_deg,
        stokes: Some(stokes),
    })
}

/// The name of the page's band file (in messages, and in the scene file it writes).
pub(crate) const BAND_FILE: &str = "band.csv";

/// The spectrum of a page request: a wavelength (µm), or the text of a band file
/// ([`BAND_FILE`]) with its quadrature step (µm; `None`: the default), or none.
pub(crate) fn spectral(
    wavelength_um: Option<f64>,
    band_csv: Option<String>,
    band_step_um: Option<f64>,
) -> polbrdf_tasks::spectrum::SpectralText {
    polbrdf_tasks::spectrum::SpectralText {
        wavelength_um,
        band: band_csv.map(|text| (BAND_FILE.to_string(), text)),
        band_step_um,
    }
}

#[cfg(test)]
mod tests {
    //! The adapter's own logic on the native target (its success paths: a `JsError` needs a
    //! JavaScript host). The page's numbers against the CLI's: web/tests (scripts/test-web).
    use super::*;

    #[test]
    fn colour_maps_are_polbrdf_plots_tables() {
        for (name, map) in [
            ("viridis", Colormap::Viridis),
            ("diverging", Colormap::Diverging),
            ("cyclic", Colormap::Cyclic),
        ] {
            let t = colormap(name, 256).unwrap();
            assert_eq!(t.len(), 3 * 257);
            for k in [0, 1, 100, 254, 255] {
                let c = map.rgb(k as f64 / 255.0);
                assert_eq!(t[3 * k..3 * k + 3], [c.0, c.1, c.2], "{name} {k}");
            }
            assert_eq!(t[3 * 256..], [190, 190, 190], "undefined: grey");
        }
        // The cyclic map closes: its two ends are one colour.
        let c = colormap("cyclic", 10).unwrap();
        assert_eq!(c[..3], c[27..30]);
    }

    #[test]
    fn presets_and_entries_round_trip_through_the_file_format() {
        for name in presets() {
            let text = preset_toml(&name).unwrap();
            assert_eq!(material_toml(&text, "p.toml").unwrap(), text, "{name}");
            let entries: serde_json::Value =
                serde_json::from_str(&material_entries(&text, "p.toml").unwrap()).unwrap();
            assert_eq!(entries["name"], serde_json::json!(name));
        }
        let lib: serde_json::Value = serde_json::from_str(&library_json()).unwrap();
        assert!(lib
            .as_array()
            .unwrap()
            .iter()
            .any(|e| e["id"] == "Au/Johnson"));
    }

    #[test]
    fn the_map_view_holds_the_1_by_2_degree_grid_with_its_csv() {
        let text = preset_toml("paint").unwrap();
        let map = hemisphere(
            &text,
            "t.toml",
            30.0,
            0.0,
            &[1.0, 0.0, 0.0, 0.0],
            None,
            None,
            None,
            1.0,
            2.0,
        )
        .unwrap();
        assert_eq!((map.n_theta(), map.n_phi()), (90, 180));
        assert_eq!(map.thetas_deg()[89], 89.0);
        assert_eq!(map.phis_deg()[90], 180.0);
        let i = 40 * 180 + 90; // θr = 40°, φr = 180°
        let node = map.node(i);
        assert_eq!(node[..2], [40.0, 180.0]);
        assert_eq!(node[2], map.brdf()[i]);
        assert_eq!(node[9 + 5], map.mueller(5)[i]);
        assert!(map.node(16_200).is_empty());
        let csv = String::from_utf8(map.csv()).unwrap();
        assert_eq!(csv.lines().count(), 1 + 16_200);
        assert!(csv.starts_with("theta_r_deg,phi_r_deg,brdf,s0,s1,s2,s3,dolp,aolp_deg,m00,"));
    }
}
