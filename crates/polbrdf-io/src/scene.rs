//! Scene files: what a surface sees, for `polbrdf radiance` and `polbrdf contrast --scene` —
//! the spectrum (one wavelength or a band), the surface's temperature, a target and a
//! background, the sun, the sky and the atmosphere ([`polbrdf::analysis::scene`]).
//!
//! Flat-ish TOML; every key is optional unless stated, and every unknown key or table is an
//! error naming file, line and key:
//!
//! ```toml
//! wavelength_um = 10.0    # one wavelength (µm) ... (exactly one of the two is required)
//! [band]                  # ... or a band
//! response = "lwir.csv"   # a band CSV (wavelength_um,response), required in [band]
//! step_um = 0.05          # the quadrature step (µm, finite, > 0; default 1/16 of the band)
//!
//! [surface]               # the surface of `polbrdf radiance`
//! temperature_k = 300     # absent: no thermal emission
//!
//! [target]                # for `polbrdf contrast --scene`
//! material = "paint.toml" # a material file or a preset name
//! temperature_k = 300
//! [background]            # the same keys as [target]
//!
//! [sun]                   # absent: no sun
//! zenith_deg = 40         # in [0, 90): the sun above the horizon; required unless date_time
//! azimuth_deg = 0         # default 0 (the surface frame's φ of the sun)
//! # ... or, instead of zenith_deg and azimuth_deg, the sun placed by NREL SPA
//! # (polbrdf::analysis::sun_position, docs/sun-position.md):
//! date_time = "2026-06-21T12:00:00Z"  # RFC 3339 with its UTC offset (string or TOML date-time)
//! latitude_deg = 48.21    # required with date_time, in [-90, 90], north positive
//! longitude_deg = 16.37   # required with date_time, in [-180, 180], east positive
//! elevation_m = 0         # default 0
//! pressure_hpa = 1013.25  # default 1013.25; 0: no refraction
//! temperature_c = 15      # default 15
//! delta_t_s = 69          # TT − UT1; default estimated from the date
//! phi0_azimuth_deg = 0    # compass azimuth of the surface's φ = 0 axis; default 0 (north)
//! irradiance = 1000       # required: W·m⁻²·µm⁻¹ on a plane normal to the beam (finite, ≥ 0)
//! stokes = [1, 0, 0, 0]   # default unpolarized; any s0 > 0, DoP ≤ 1, normalized to s0 = 1
//!
//! [sky]
//! model = "none"          # "none" (default) | "uniform" | "thermal" | "profile" |
//!                         # "cie-clear" | "table"
//! radiance = 1.5          # uniform: spectral radiance, W·m⁻²·sr⁻¹·µm⁻¹ (finite, ≥ 0)
//! temperature_k = 250     # thermal: brightness temperature (K, finite, > 0)
//! file = "sky.csv"        # profile: a CSV with columns zenith_deg,radiance;
//!                         # table: a CSV with columns theta_deg,phi_deg,s0,s1,s2,s3
//! irradiance = 50         # cie-clear: the sky's horizontal irradiance, W·m⁻²·µm⁻¹ (≥ 0)
//! dop_max = 0.75          # cie-clear: the maximum degree of polarization, in [0, 1]
//!
//! [atmosphere]
//! transmittance = 0.9     # in [0, 1], default 1
//! path_radiance = 0.2     # W·m⁻²·sr⁻¹·µm⁻¹, ≥ 0, default 0
//!
//! [path]                  # the path to a detecting sensor (`polbrdf detect`, docs/detection.md)
//! visibility_km = 23      # or extinction_per_m = 1.7e-4 (one of the two), ...
//! horizon_radiance = 60   # ... with horizon_radiance (W·m⁻²·sr⁻¹·µm⁻¹) or air_temperature_k;
//! table = "path.csv"      # or instead a CSV with columns range_m,transmittance,path_radiance
//! ```
//!
//! A `[sun]` by `date_time` must be above the horizon at that instant (an error naming
//! `sun.date_time` otherwise); the keys of the two ways (angles, date and place) exclude each
//! other.
//!
//! A sky model takes only its own keys (`radiance` with `model = "thermal"` is an error naming the
//! model it belongs to) and requires them (`dop_max` has a default); `cie-clear` requires a `[sun]`
//! too, for its position. A sky table's Stokes vectors are in the arriving beam's basis, on a full
//! grid of zenith angles (0° to 90°) × azimuths (in [0°, 360°)), its rows in any order
//! ([`crate::csv_io::read_sky_table_csv`]). Angles are in degrees here and in radians in
//! [`Sun`](polbrdf::analysis::scene::Sun). Temperatures must be finite and > 0 K. The files a scene
//! names (band, sky profile or table, materials) are found relative to the scene file's folder;
//! their errors name that file and its line, inside an error naming the scene file and the line of
//! the key that names it. A material that is no existing file is a preset name. Dotted keys
//! (`sky.model = "uniform"`) are not accepted: write the table out.
//!
//! The reader is table-driven: `KEYS` (`scene/keys.rs`) lists every key with its kind, each
//! table has one function in the file of its aspect (`spectrum.rs`, `surfaces.rs`, `sun.rs`,
//! `sky.rs`, `atmosphere.rs` under `scene/`), and the sky models are the rows of `SKY_MODELS`
//! (`scene/sky.rs`) with one match on them. A new table is rows of `KEYS` and a function; a new
//! sky model is a row of `SKY_MODELS`, its keys in `KEYS` and an arm of the match in `sky`.

mod atmosphere;
mod keys;
mod sky;
mod spectrum;
mod sun;
mod surfaces;

pub use keys::key_names;
pub use sky::{sky_kind, sky_model_names, SkyKind};

use crate::csv_io::read_text;
use crate::error::Result;
use crate::toml_doc::TomlDoc;
use keys::{FORMAT, KEYS};
use polbrdf::analysis::detection::PathSpec;
use polbrdf::analysis::sun_position::SunTime;
use polbrdf::analysis::ThermalScene;
use polbrdf::{MaterialSpec, Spectrum};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use toml::Value;

/// A target or a background of a scene (`[target]`, `[background]`).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SceneObject {
    /// Its material with a display name (the material's `name` key, else the file stem or the
    /// preset name); `None` when the table names none.
    pub material: Option<(MaterialSpec, String)>,
    /// Its temperature (K, finite and > 0); `None` when not given.
    pub temperature_k: Option<f64>,
}

/// A scene file, read and validated.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// The scene file.
    pub path: PathBuf,
    /// One wavelength (`wavelength_um`) or a band with its quadrature step (`[band]`).
    pub spectrum: Spectrum,
    /// The surface temperature (`[surface]`), the sun (`[sun]`), the sky (`[sky]`) and the
    /// atmosphere (`[atmosphere]`); [`ThermalScene::validate`] holds.
    pub thermal: ThermalScene,
    /// `[target]`.
    pub target: SceneObject,
    /// `[background]`.
    pub background: SceneObject,
    /// `[sun]`'s date, time and place when it gives `date_time` (`thermal.sun` then holds the
    /// sun they place); `None` when the sun is given by its angles, or not at all.
    pub sun_time: Option<SunTime>,
    /// `[path]`: the path to a detecting sensor (`polbrdf detect`); `None` when not given.
    pub air_path: Option<PathSpec>,
    /// Every file the scene names, as resolved (band, sky table, sky profile, material files
    /// and the index files these name): inputs an output must not replace.
    pub files: Vec<PathBuf>,
}

/// The value of a key of a scene file, as given.
#[derive(Debug, Clone, PartialEq)]
pub enum SceneValue {
    /// A number (an integer read as a float).
    Number(f64),
    /// An array of numbers.
    Numbers(Vec<f64>),
    /// A string; a file name as the reader finds it (relative to the scene file's folder).
    Text(String),
}

/// Parses a scene file's text; `path` names it in error messages, and its folder is where
/// relative file names (band, sky profile or table, materials) are found.
///
/// # Errors
/// [`Error::Syntax`](crate::Error::Syntax) for malformed TOML (including duplicate keys and tables,
/// and dotted keys); [`Error::Field`](crate::Error::Field) naming the line and the key
/// (`table.key`) for an unknown key or table, a wrong type, an invalid value, a key of another sky
/// model, a missing required key (also a `[sun]` the `cie-clear` sky needs, at `sky.model`) or a
/// file that cannot be read or parsed (the message then holds that file's own error);
/// [`Error::File`](crate::Error::File) when neither `wavelength_um` nor `[band]` is given.
pub fn parse_scene(text: &str, path: &Path) -> Result<Scene> {
    scene_of(TomlDoc::parse(text, path, FORMAT)?)
}

/// Parses a scene file's text as [`parse_scene`] does, with the files it names (band, sky
/// profile or table, materials, path table) taken from `files` — their texts by the path the
/// reader resolves them to (relative to `path`'s folder) — instead of the file system: for an
/// adapter without one (the web explorer). A named file missing from `files` is an error naming
/// it; a material's refractive-index file is still read from the file system.
///
/// # Errors
/// As [`parse_scene`].
pub fn parse_scene_with_files(
    text: &str,
    path: &Path,
    files: &BTreeMap<PathBuf, String>,
) -> Result<Scene> {
    scene_of(TomlDoc::parse(text, path, FORMAT)?.with_files(files))
}

/// The scene of a parsed scene document.
fn scene_of(doc: TomlDoc<'_>) -> Result<Scene> {
    let path = doc.path();
    let spectrum = spectrum::spectrum(&doc)?;
    let sun = sun::sun(&doc)?;
    let sun_time = if sun.is_some() {
        sun::sun_time(&doc)?
    } else {
        None
    };
    let thermal = ThermalScene {
        surface_temperature_k: surfaces::surface(&doc),
        sky: sky::sky(&doc)?,
        atmosphere: atmosphere::atmosphere(&doc),
        sun,
    };
    thermal.validate().map_err(|e| doc.core_error(e))?;
    let target = surfaces::object(&doc, &surfaces::TARGET)?;
    let background = surfaces::object(&doc, &surfaces::BACKGROUND)?;
    let air_path = atmosphere::air_path(&doc)?;
    Ok(Scene {
        path: path.to_path_buf(),
        spectrum,
        thermal,
        target,
        background,
        sun_time,
        air_path,
        files: doc.files(),
    })
}

/// Reads a scene file as [`read_scene`] does (every check, the same errors) and returns the
/// keys it gives besides the scene: `(dotted name, value)` in the order of [`key_names`], tables
/// left out. File names (`band.response`, `sky.file`, a `material` that names a file) are
/// given as the reader finds them: relative to the scene file's folder, joined to it.
///
/// # Errors
/// As [`read_scene`].
pub fn read_scene_keys(path: &Path) -> Result<(Scene, Vec<(&'static str, SceneValue)>)> {
    let text = read_text(path)?;
    let scene = parse_scene(&text, path)?;
    let doc = TomlDoc::parse(&text, path, FORMAT)?;
    let files = ["band.response", "sky.file", "path.table"];
    let materials = ["target.material", "background.material"];
    let keys = KEYS
        .iter()
        .filter_map(|k| {
            let value = match doc.value(k.name)? {
                Value::String(s) if files.contains(&k.name) => {
                    SceneValue::Text(doc.resolve(s).to_string_lossy().into_owned())
                }
                Value::String(s)
                    if materials.contains(&k.name) && crate::material::names_a_file(s) =>
                {
                    SceneValue::Text(doc.resolve(s).to_string_lossy().into_owned())
                }
                Value::String(s) => SceneValue::Text(s.clone()),
                Value::Datetime(d) => SceneValue::Text(d.to_string()),
                Value::Array(_) => SceneValue::Numbers(doc.numbers(k.name)?),
                Value::Table(_) => return None,
                _ => SceneValue::Number(doc.number(k.name)?),
            };
            Some((k.name, value))
        })
        .collect();
    Ok((scene, keys))
}

/// Reads a scene file (`-`: standard input, relative file names then taken relative to the
/// working directory) and parses it ([`parse_scene`]).
///
/// # Errors
/// [`Error::Read`](crate::Error::Read) if it cannot be read;
/// [`Error::Syntax`](crate::Error::Syntax) if it is not UTF-8 text; as [`parse_scene`].
pub fn read_scene(path: &Path) -> Result<Scene> {
    let text = read_text(path)?;
    parse_scene(&text, path)
}
