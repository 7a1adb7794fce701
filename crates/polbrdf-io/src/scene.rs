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
//! A sky model takes only its own keys (`radiance` with `model = "thermal"` is an error naming
//! the model it belongs to) and requires them (`dop_max` has a default); `cie-clear` requires
//! a `[sun]` too, for its position. A sky table's Stokes vectors are in the arriving beam's
//! basis, on a full grid of zenith angles (0° to 90°) × azimuths (in [0°, 360°)), its rows
//! in any order ([`crate::csv_io::read_sky_table_csv`]). Angles are in degrees here and in
//! radians in [`Sun`]. Temperatures must be finite and > 0 K. The files a scene names (band,
//! sky profile or table, materials) are found relative to the scene file's folder; their
//! errors name that file and its line, inside an error naming the scene file and the line of
//! the key that names it. A material that is no existing file is a preset name. Dotted keys
//! (`sky.model = "uniform"`) are not accepted: write the table out.
//!
//! The reader is table-driven: `KEYS` lists every key with its kind, each table has one
//! function, and the sky models are the rows of `SKY_MODELS` with one match on them. A new
//! table is rows of `KEYS` and a function; a new sky model is a row of `SKY_MODELS`, its keys
//! in `KEYS` and an arm of the match in `sky`.

use crate::csv_io::read_text;
use crate::csv_io::{parse_band_csv, parse_sky_profile_csv, parse_sky_table_csv};
use crate::csv_io::{read_band_csv, read_sky_profile_csv, read_sky_table_csv, show};
use crate::error::{Error, Result};
use crate::material::load_material;
use crate::toml_doc::{key, split, Format, Key, Kind, TomlDoc};
use polbrdf::analysis::detection::path::KOSCHMIEDER;
use polbrdf::analysis::detection::{Horizon, PathSpec};
use polbrdf::analysis::scene::Sun;
use polbrdf::analysis::sun_position::{Site, SunTime};
use polbrdf::analysis::thermal::temperature;
use polbrdf::analysis::{Atmosphere, SkyModel, ThermalScene};
use polbrdf::{MaterialSpec, Spectrum, Stokes};
use std::collections::BTreeMap;
use std::f64::consts::FRAC_PI_2;
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

/// Every key and table of a scene file, tables before their keys.
const KEYS: &[Key] = &[
    key("wavelength_um", Kind::Number, "one wavelength, µm"),
    key(
        "band",
        Kind::Table,
        "a band: [band] with response = \"FILE.csv\"",
    ),
    key(
        "band.response",
        Kind::Text,
        "the path of a band CSV file with columns wavelength_um,response",
    ),
    key("band.step_um", Kind::Number, "the quadrature step, µm"),
    key("surface", Kind::Table, "the surface of `polbrdf radiance`"),
    key(
        "surface.temperature_k",
        Kind::Number,
        "the surface temperature, K",
    ),
    key("target", Kind::Table, "the target of `polbrdf contrast`"),
    key(
        "target.material",
        Kind::Text,
        "a material file or a preset name",
    ),
    key("target.temperature_k", Kind::Number, "a temperature, K"),
    key(
        "background",
        Kind::Table,
        "the background of `polbrdf contrast`",
    ),
    key(
        "background.material",
        Kind::Text,
        "a material file or a preset name",
    ),
    key("background.temperature_k", Kind::Number, "a temperature, K"),
    key(
        "sun",
        Kind::Table,
        "the sun: [sun] with irradiance, and zenith_deg or date_time with latitude_deg and \
         longitude_deg",
    ),
    key(
        "sun.zenith_deg",
        Kind::Number,
        "the sun's zenith angle, degrees, in [0, 90)",
    ),
    key(
        "sun.azimuth_deg",
        Kind::Number,
        "the sun's azimuth, degrees",
    ),
    key(
        "sun.date_time",
        Kind::DateTime,
        "the date and time with its UTC offset, e.g. 2026-06-21T12:00:00Z",
    ),
    key(
        "sun.latitude_deg",
        Kind::Number,
        "the latitude, degrees, in [-90, 90] (north positive)",
    ),
    key(
        "sun.longitude_deg",
        Kind::Number,
        "the longitude, degrees, in [-180, 180] (east positive)",
    ),
    key(
        "sun.elevation_m",
        Kind::Number,
        "the height above sea level, m",
    ),
    key(
        "sun.pressure_hpa",
        Kind::Number,
        "the air pressure for refraction, hPa (0: no refraction)",
    ),
    key(
        "sun.temperature_c",
        Kind::Number,
        "the air temperature for refraction, °C",
    ),
    key(
        "sun.delta_t_s",
        Kind::Number,
        "ΔT = TT − UT1, s (default: estimated from the date)",
    ),
    key(
        "sun.phi0_azimuth_deg",
        Kind::Number,
        "the compass azimuth (from north toward east) of the surface's φ = 0 axis, degrees",
    ),
    key(
        "sun.irradiance",
        Kind::Number,
        "the sun's spectral irradiance on a plane normal to its beam, W·m⁻²·µm⁻¹",
    ),
    key(
        "sun.stokes",
        Kind::Numbers,
        "the sun's Stokes vector [s0, s1, s2, s3]",
    ),
    key("sky", Kind::Table, "the sky"),
    key("sky.model", Kind::Text, "a sky model"),
    key(
        "sky.radiance",
        Kind::Number,
        "the uniform sky's spectral radiance, W·m⁻²·sr⁻¹·µm⁻¹",
    ),
    key(
        "sky.temperature_k",
        Kind::Number,
        "the sky's brightness temperature, K",
    ),
    key(
        "sky.file",
        Kind::Text,
        "the path of a CSV file: a sky profile with columns zenith_deg,radiance, or a sky table \
         with columns theta_deg,phi_deg,s0,s1,s2,s3",
    ),
    key(
        "sky.irradiance",
        Kind::Number,
        "the clear sky's horizontal spectral irradiance, W·m⁻²·µm⁻¹",
    ),
    key(
        "sky.dop_max",
        Kind::Number,
        "the clear sky's maximum degree of polarization, in [0, 1]",
    ),
    key(
        "atmosphere",
        Kind::Table,
        "the atmosphere between surface and sensor",
    ),
    key(
        "atmosphere.transmittance",
        Kind::Number,
        "the transmittance, in [0, 1]",
    ),
    key(
        "atmosphere.path_radiance",
        Kind::Number,
        "the path spectral radiance, W·m⁻²·sr⁻¹·µm⁻¹",
    ),
    key(
        "path",
        Kind::Table,
        "the path to a detecting sensor (`polbrdf detect`)",
    ),
    key(
        "path.extinction_per_m",
        Kind::Number,
        "the extinction coefficient, m⁻¹",
    ),
    key(
        "path.visibility_km",
        Kind::Number,
        "the meteorological visibility, km (Koschmieder: β = 3.912/V)",
    ),
    key(
        "path.horizon_radiance",
        Kind::Number,
        "the horizon spectral radiance, W·m⁻²·sr⁻¹·µm⁻¹",
    ),
    key(
        "path.air_temperature_k",
        Kind::Number,
        "the air temperature, K (horizon radiance B(T_air))",
    ),
    key(
        "path.table",
        Kind::Text,
        "the path of a CSV file with columns range_m,transmittance,path_radiance",
    ),
];

/// Every key and table of a scene file by its dotted name (`table.key` inside a table), tables
/// before their keys, in the order of the format's description.
pub fn key_names() -> impl Iterator<Item = &'static str> {
    KEYS.iter().map(|k| k.name)
}

/// The names of the sky models (`[sky] model = …`), the default first.
pub fn sky_model_names() -> impl Iterator<Item = &'static str> {
    SKY_MODELS.iter().map(|m| m.name)
}

/// The sky model named `name` (`[sky] model = …`), or `None` for an unknown name.
pub fn sky_kind(name: &str) -> Option<SkyKind> {
    SKY_MODELS.iter().find(|m| m.name == name).map(|m| m.kind)
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

/// Which sky a row of `SKY_MODELS` builds: the sky models by kind, for readers of other
/// spellings of a scene (the Python module's keywords) that take the names from here.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SkyKind {
    /// `none`: no sky.
    None,
    /// `uniform`.
    Uniform,
    /// `thermal`.
    Thermal,
    /// `profile`.
    Profile,
    /// `cie-clear`.
    ClearSky,
    /// `table`.
    Table,
}

impl SkyKind {
    /// Its name in scene files (`[sky] model = …`), from `SKY_MODELS`.
    pub fn name(self) -> &'static str {
        SKY_MODELS
            .iter()
            .find(|m| m.kind == self)
            .map_or("none", |m| m.name)
    }

    /// The kind of `sky`.
    pub fn of(sky: &SkyModel) -> Self {
        match sky {
            SkyModel::None => SkyKind::None,
            SkyModel::Uniform { .. } => SkyKind::Uniform,
            SkyModel::Thermal { .. } => SkyKind::Thermal,
            SkyModel::Profile(_) => SkyKind::Profile,
            SkyModel::ClearSky { .. } => SkyKind::ClearSky,
            SkyModel::Table(_) => SkyKind::Table,
        }
    }
}

/// A sky model of `[sky] model = …` and the keys it takes besides `model`.
#[derive(Debug)]
struct SkyModelKeys {
    /// The value of `model`.
    name: &'static str,
    kind: SkyKind,
    /// Its keys (dotted names of `KEYS`); which of them are required is up to the model.
    keys: &'static [&'static str],
}

/// The sky models, the default first.
const SKY_MODELS: &[SkyModelKeys] = &[
    SkyModelKeys {
        name: "none",
        kind: SkyKind::None,
        keys: &[],
    },
    SkyModelKeys {
        name: "uniform",
        kind: SkyKind::Uniform,
        keys: &["sky.radiance"],
    },
    SkyModelKeys {
        name: "thermal",
        kind: SkyKind::Thermal,
        keys: &["sky.temperature_k"],
    },
    SkyModelKeys {
        name: "profile",
        kind: SkyKind::Profile,
        keys: &["sky.file"],
    },
    SkyModelKeys {
        name: "cie-clear",
        kind: SkyKind::ClearSky,
        keys: &["sky.irradiance", "sky.dop_max"],
    },
    SkyModelKeys {
        name: "table",
        kind: SkyKind::Table,
        keys: &["sky.file"],
    },
];

/// The scene format of [`TomlDoc`].
const FORMAT: Format<'static> = Format {
    noun: "scene file",
    example: "`wavelength_um = 10`",
    keys: KEYS,
};

/// An [`polbrdf::Error::InvalidParameter`] of `name` (a key), at its line.
fn invalid(doc: &TomlDoc<'_>, name: &'static str, value: f64, reason: &'static str) -> Error {
    doc.core_error(polbrdf::Error::InvalidParameter {
        name,
        value,
        reason,
    })
}

/// The number `key` that sky model `model` requires.
fn required_for_model(doc: &TomlDoc<'_>, model: &str, key: &str) -> Result<f64> {
    doc.number(key)
        .ok_or_else(|| missing_for_model(doc, model, key))
}

fn missing_for_model(doc: &TomlDoc<'_>, model: &str, key: &str) -> Error {
    doc.error(
        "sky.model",
        format!(
            "sky model \"{model}\" requires the key `{}` ({})",
            split(key).1,
            doc.what(key)
        ),
    )
}

/// `wavelength_um` or `[band]`: exactly one of them.
fn spectrum(doc: &TomlDoc<'_>) -> Result<Spectrum> {
    match (doc.number("wavelength_um"), doc.has("band")) {
        (Some(_), true) => Err(doc.error(
            "wavelength_um",
            format!(
                "give either `wavelength_um` (one wavelength) or a [band] table (line {}), not \
                 both",
                doc.line("band")
            ),
        )),
        (None, false) => Err(Error::File {
            path: doc.path().to_path_buf(),
            message: "no spectrum: give `wavelength_um` (one wavelength, µm) or a [band] table \
                      with response = \"FILE.csv\" (a band CSV file)"
                .into(),
        }),
        (Some(l), false) => {
            if !(l.is_finite() && l > 0.0) {
                return Err(doc.error(
                    "wavelength_um",
                    format!("{}: a wavelength must be finite and > 0 (µm)", show(l)),
                ));
            }
            Ok(Spectrum::Wavelength(l))
        }
        (None, true) => {
            let step = doc.number("band.step_um");
            if let Some(s) = step {
                if !(s.is_finite() && s > 0.0) {
                    return Err(doc.error(
                        "band.step_um",
                        format!("{}: a quadrature step must be finite and > 0 (µm)", show(s)),
                    ));
                }
            }
            let band = doc
                .read_file_or_text("band.response", read_band_csv, parse_band_csv)?
                .ok_or_else(|| {
                    doc.error(
                    "band",
                    "missing required key `response` (the path of a band CSV file with columns \
                     wavelength_um,response)",
                )
                })?;
            if let Some(s) = step {
                band.check_step(s).map_err(|e| {
                    // The core names the option `band_step_um`; here the key is `step_um`.
                    let (lo, hi) = band.range();
                    let why = match e {
                        polbrdf::Error::InvalidParameter { reason, .. } => reason.to_string(),
                        other => other.to_string(),
                    };
                    doc.error(
                        "band.step_um",
                        format!("{s:?}: {why} (the band spans {lo}–{hi} µm)"),
                    )
                })?;
            }
            Ok(Spectrum::Band(band, step))
        }
    }
}

/// `[surface]`: the surface temperature (checked with the scene).
fn surface(doc: &TomlDoc<'_>) -> Option<f64> {
    doc.number("surface.temperature_k")
}

/// The keys of `[target]` or `[background]`.
struct ObjectKeys {
    material: &'static str,
    temperature_k: &'static str,
}

const TARGET: ObjectKeys = ObjectKeys {
    material: "target.material",
    temperature_k: "target.temperature_k",
};

const BACKGROUND: ObjectKeys = ObjectKeys {
    material: "background.material",
    temperature_k: "background.temperature_k",
};

/// `[target]` or `[background]`.
fn object(doc: &TomlDoc<'_>, keys: &ObjectKeys) -> Result<SceneObject> {
    let temperature_k = doc
        .number(keys.temperature_k)
        .map(|t| temperature(keys.temperature_k, t).map_err(|e| doc.core_error(e)))
        .transpose()?;
    let material = doc
        .text(keys.material)
        .map(|arg| material(doc, keys.material, arg))
        .transpose()?;
    Ok(SceneObject {
        material,
        temperature_k,
    })
}

/// The material `arg` of `key`: a material file relative to the scene file's folder when it
/// contains a `/` or ends in `.toml`, else a preset name (as [`load_material`]); with its
/// display name.
fn material(doc: &TomlDoc<'_>, key: &str, arg: &str) -> Result<(MaterialSpec, String)> {
    if arg.is_empty() {
        return Err(doc.error(
            key,
            "expected a material file or a preset name, got an empty string",
        ));
    }
    // A file when the argument contains a `/` or ends in `.toml`, else a preset (as
    // [`load_material`]: a file named like a preset never shadows it).
    let spec = if crate::material::names_a_file(arg) {
        let file = doc.resolve(arg);
        doc.record(file.clone());
        let read = |file: &Path| match file.to_str() {
            Some(f) if crate::material::names_a_file(f) => load_material(f),
            Some(f) => load_material(&format!("./{f}")),
            None => Err(Error::File {
                path: file.to_path_buf(),
                message: "the path is not valid UTF-8".into(),
            }),
        };
        let parse = |bytes: &[u8], file: &Path| {
            crate::material::parse_material(&String::from_utf8_lossy(bytes), file)
        };
        doc.load(&file, read, parse)
    } else {
        load_material(arg)
    }
    .map_err(|e| doc.error(key, e.to_string()))?;
    if let Some(index) = crate::material::index_file(&spec) {
        doc.record(index);
    }
    let name = spec.name.clone().unwrap_or_else(|| {
        Path::new(arg)
            .file_stem()
            .map_or_else(|| arg.to_string(), |s| s.to_string_lossy().into_owned())
    });
    Ok((spec, name))
}

/// `[sun]`: `zenith_deg` and `irradiance` required, `azimuth_deg` 0 and `stokes` unpolarized by
/// default; the angles in radians (the azimuth first taken modulo 360°, exactly), the Stokes
/// vector normalized to `s0 = 1`. `None` without a `[sun]`. The values are checked here, in the units of the file (the core checks them again,
/// in radians).
fn sun(doc: &TomlDoc<'_>) -> Result<Option<Sun>> {
    if !doc.has("sun") {
        return Ok(None);
    }
    if let Some(time) = sun_time(doc)? {
        return sun_from_time(doc, &time).map(Some);
    }
    let zenith_deg = doc.required_number("sun.zenith_deg").map_err(|e| match e {
        Error::Field {
            path,
            line,
            field,
            message,
        } => Error::Field {
            path,
            line,
            field,
            message: format!(
                "{message}; or place the sun by `date_time`, `latitude_deg` and `longitude_deg`"
            ),
        },
        e => e,
    })?;
    let irradiance = doc.required_number("sun.irradiance")?;
    let azimuth_deg = doc
        .number("sun.azimuth_deg")
        .unwrap_or(Sun::DEFAULT_AZIMUTH.to_degrees());
    // −0 is 0; a zenith angle just below 90° can round to π/2 in radians.
    let zenith = zenith_deg.to_radians() + 0.0;
    if !(zenith_deg.is_finite() && (0.0..90.0).contains(&zenith_deg) && zenith < FRAC_PI_2) {
        return Err(invalid(
            doc,
            "sun.zenith_deg",
            zenith_deg,
            "the sun must be above the horizon: in [0, 90) degrees",
        ));
    }
    if !(azimuth_deg.is_finite() && azimuth_deg.abs() <= polbrdf::MAX_AZIMUTH_DEG) {
        return Err(invalid(
            doc,
            "sun.azimuth_deg",
            azimuth_deg,
            "must be finite and at most 1e8 degrees in magnitude (as every azimuth)",
        ));
    }
    // Taken modulo 360° (exact in floating point: a file's 1e8 is the sun at 280°, bit for
    // bit); an azimuth within a turn is kept as written.
    let azimuth_deg = azimuth_deg % 360.0;
    let stokes = sun_light(doc, irradiance)?;
    Ok(Some(Sun {
        zenith,
        azimuth: azimuth_deg.to_radians(),
        irradiance,
        stokes,
    }))
}

/// The keys of `[sun]` that give the sun by date, time and place (`date_time` first).
const SUN_TIME_KEYS: [&str; 8] = [
    "sun.date_time",
    "sun.latitude_deg",
    "sun.longitude_deg",
    "sun.elevation_m",
    "sun.pressure_hpa",
    "sun.temperature_c",
    "sun.delta_t_s",
    "sun.phi0_azimuth_deg",
];

/// `[sun]`'s date, time and place, when `date_time` is given (`None` otherwise): every key
/// of the two ways of giving the sun's position is checked to belong to the one used.
fn sun_time(doc: &TomlDoc<'_>) -> Result<Option<SunTime>> {
    let by_angles = ["sun.zenith_deg", "sun.azimuth_deg"];
    let Some(date_time) = doc.value("sun.date_time") else {
        if let Some(key) = SUN_TIME_KEYS.iter().find(|k| doc.has(k)) {
            return Err(doc.error(
                key,
                format!(
                    "`{}` places the sun by date, time and place: give `date_time` too (or \
                     remove it and give zenith_deg)",
                    split(key).1
                ),
            ));
        }
        return Ok(None);
    };
    if let Some(key) = by_angles.iter().find(|k| doc.has(k)) {
        return Err(doc.error(
            key,
            format!(
                "give either `{}` (the sun's angles) or `date_time` (line {}; the angles from \
                 date, time and place), not both",
                split(key).1,
                doc.line("sun.date_time")
            ),
        ));
    }
    let time = match date_time {
        Value::Datetime(d) => crate::date_time::from_toml(d),
        Value::String(t) => crate::date_time::parse_date_time(t),
        _ => unreachable!("checked against Kind::DateTime"),
    }
    .map_err(|m| doc.error("sun.date_time", m))?;
    let latitude_deg = doc.required_number("sun.latitude_deg")?;
    let longitude_deg = doc.required_number("sun.longitude_deg")?;
    let d = Site::at(latitude_deg, longitude_deg);
    let site = Site {
        elevation_m: doc.number("sun.elevation_m").unwrap_or(d.elevation_m),
        pressure_hpa: doc.number("sun.pressure_hpa").unwrap_or(d.pressure_hpa),
        temperature_c: doc.number("sun.temperature_c").unwrap_or(d.temperature_c),
        ..d
    };
    site.validate().map_err(|e| doc.core_error(e))?;
    let phi0 = doc
        .number("sun.phi0_azimuth_deg")
        .unwrap_or(SunTime::DEFAULT_PHI0_AZIMUTH_DEG);
    if !(phi0.is_finite() && phi0.abs() <= polbrdf::MAX_AZIMUTH_DEG) {
        return Err(invalid(
            doc,
            "sun.phi0_azimuth_deg",
            phi0,
            "must be finite and at most 1e8 degrees in magnitude (as every azimuth)",
        ));
    }
    Ok(Some(SunTime {
        time,
        site,
        delta_t_s: doc.number("sun.delta_t_s"),
        phi0_azimuth_deg: phi0.rem_euclid(360.0) % 360.0,
    }))
}

/// The sun of `[sun]` by date, time and place: above the horizon, or an error naming
/// `date_time` (a scene file is one instant; a sweep over the day takes the sun away at night
/// itself, docs/sun-position.md).
fn sun_from_time(doc: &TomlDoc<'_>, time: &SunTime) -> Result<Sun> {
    let irradiance = doc.required_number("sun.irradiance")?;
    let (position, direction) = time.surface_direction().map_err(|e| doc.core_error(e))?;
    let Some((zenith, azimuth)) = direction else {
        return Err(doc.error(
            "sun.date_time",
            format!(
                "the sun is not above the horizon at {} at latitude {}°, longitude {}° \
                 (elevation {:.3}°, azimuth {:.3}° from north): check the date, the UTC offset \
                 and the place, or remove [sun] for a scene without the sun",
                crate::date_time::format_date_time(&time.time),
                show(time.site.latitude_deg),
                show(time.site.longitude_deg),
                position.elevation_deg(),
                position.azimuth_deg
            ),
        ));
    };
    let stokes = sun_light(doc, irradiance)?;
    Ok(Sun {
        zenith,
        azimuth,
        irradiance,
        stokes,
    })
}

/// The sun's light, whichever way it is placed: `sun.irradiance` (read by the caller, checked
/// here: finite and ≥ 0) and its Stokes vector (`sun.stokes`, unpolarized when absent).
fn sun_light(doc: &TomlDoc<'_>, irradiance: f64) -> Result<Stokes> {
    if !(irradiance.is_finite() && irradiance >= 0.0) {
        return Err(invalid(
            doc,
            "sun.irradiance",
            irradiance,
            "must be finite and >= 0",
        ));
    }
    let stokes = match doc.numbers("sun.stokes") {
        None => Stokes::unpolarized(),
        Some(s) => sun_stokes(doc, &s)?,
    };
    Ok(stokes)
}

/// `sun.stokes`: four finite numbers, `s0 > 0`, a degree of polarization at most 1 (to 1e-9,
/// as `--stokes`), normalized to `s0 = 1` (and a DoP within the tolerance above 1 to 1).
fn sun_stokes(doc: &TomlDoc<'_>, s: &[f64]) -> Result<Stokes> {
    let key = "sun.stokes";
    let shown = || {
        let v: Vec<String> = s.iter().map(|x| show(*x)).collect();
        format!("[{}]", v.join(", "))
    };
    let [s0, s1, s2, s3] = *s else {
        return Err(doc.error(
            key,
            format!(
                "expected 4 numbers [s0, s1, s2, s3], got {} ({})",
                s.len(),
                shown()
            ),
        ));
    };
    if s.iter().any(|v| !v.is_finite()) {
        return Err(doc.error(
            key,
            format!("{}: every Stokes parameter must be finite", shown()),
        ));
    }
    if s0 <= 0.0 {
        return Err(doc.error(key, format!("{}: s0 (the intensity) must be > 0", shown())));
    }
    let p = [s1 / s0, s2 / s0, s3 / s0];
    let dop = p[0].hypot(p[1]).hypot(p[2]);
    if dop.is_nan() || dop > 1.0 + 1e-9 {
        return Err(doc.error(
            key,
            format!(
                "{}: the degree of polarization sqrt(s1² + s2² + s3²)/s0 = {} exceeds 1",
                shown(),
                show(dop)
            ),
        ));
    }
    let f = if dop > 1.0 { 1.0 / dop } else { 1.0 };
    Ok(Stokes([1.0, p[0] * f, p[1] * f, p[2] * f]))
}

/// `[sky]`: the model of `SKY_MODELS` (default `none`) with its keys only.
fn sky(doc: &TomlDoc<'_>) -> Result<SkyModel> {
    let name = doc.text("sky.model").unwrap_or(SKY_MODELS[0].name);
    let Some(model) = SKY_MODELS.iter().find(|m| m.name == name) else {
        return Err(doc.error(
            "sky.model",
            format!(
                "unknown sky model {name:?} (known: {})",
                SKY_MODELS
                    .iter()
                    .map(|m| format!("\"{}\"", m.name))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        ));
    };
    // A key of another model, the first in the file.
    let mut given: Vec<(usize, &str)> = KEYS
        .iter()
        .filter(|k| split(k.name).0 == Some("sky") && k.name != "sky.model")
        .filter(|k| doc.has(k.name))
        .map(|k| (doc.line(k.name), k.name))
        .collect();
    given.sort();
    if let Some((_, key)) = given.iter().find(|(_, k)| !model.keys.contains(k)) {
        let owners: Vec<String> = SKY_MODELS
            .iter()
            .filter(|m| m.keys.contains(key))
            .map(|m| format!("\"{}\"", m.name))
            .collect();
        let default = if doc.has("sky.model") {
            ""
        } else {
            "the default, "
        };
        let its = if model.keys.is_empty() {
            format!("{default}which takes no keys")
        } else {
            format!(
                "{default}whose keys are {}",
                model
                    .keys
                    .iter()
                    .map(|k| split(k).1)
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        };
        return Err(doc.error(
            key,
            format!(
                "`{}` is not a key of sky model \"{name}\" ({its}); it belongs to model = {}",
                split(key).1,
                owners.join(" or ")
            ),
        ));
    }
    Ok(match model.kind {
        SkyKind::None => SkyModel::None,
        SkyKind::Uniform => SkyModel::Uniform {
            radiance: required_for_model(doc, name, "sky.radiance")?,
        },
        SkyKind::Thermal => SkyModel::Thermal {
            temperature_k: required_for_model(doc, name, "sky.temperature_k")?,
        },
        SkyKind::Profile => SkyModel::Profile(
            doc.read_file_or_text("sky.file", read_sky_profile_csv, parse_sky_profile_csv)?
                .ok_or_else(|| missing_for_model(doc, name, "sky.file"))?,
        ),
        SkyKind::ClearSky => {
            let irradiance = required_for_model(doc, name, "sky.irradiance")?;
            if !doc.has("sun") {
                return Err(doc.error(
                    "sky.model",
                    format!(
                        "sky model \"{name}\" requires a [sun] table (zenith_deg, azimuth_deg, \
                         irradiance): the clear sky's radiance and polarization are set by the \
                         sun's position"
                    ),
                ));
            }
            SkyModel::ClearSky {
                irradiance,
                dop_max: doc
                    .number("sky.dop_max")
                    .unwrap_or(polbrdf::analysis::sky::ClearSky::DEFAULT_DOP_MAX),
            }
        }
        SkyKind::Table => SkyModel::Table(
            doc.read_file_or_text("sky.file", read_sky_table_csv, parse_sky_table_csv)?
                .ok_or_else(|| missing_for_model(doc, name, "sky.file"))?,
        ),
    })
}

/// `[atmosphere]`, with the defaults of [`Atmosphere`].
fn atmosphere(doc: &TomlDoc<'_>) -> Atmosphere {
    let d = Atmosphere::default();
    Atmosphere {
        transmittance: doc
            .number("atmosphere.transmittance")
            .unwrap_or(d.transmittance),
        path_radiance: doc
            .number("atmosphere.path_radiance")
            .unwrap_or(d.path_radiance),
    }
}

/// `[path]` (docs/detection.md): `table`, or one of `extinction_per_m` and `visibility_km`
/// with one of `horizon_radiance` and `air_temperature_k`.
fn air_path(doc: &TomlDoc<'_>) -> Result<Option<PathSpec>> {
    if !doc.has("path") {
        return Ok(None);
    }
    let exclusive = |a: &str, b: &str| -> Result<()> {
        if doc.has(a) && doc.has(b) {
            return Err(doc.error(
                b,
                format!("give either `{}` or `{}`, not both", split(a).1, split(b).1),
            ));
        }
        Ok(())
    };
    if doc.has("path.table") {
        for k in [
            "path.extinction_per_m",
            "path.visibility_km",
            "path.horizon_radiance",
            "path.air_temperature_k",
        ] {
            exclusive("path.table", k)?;
        }
        let table = doc.read_file_or_text(
            "path.table",
            crate::detection_csv::read_path_csv,
            crate::detection_csv::parse_path_csv,
        )?;
        return Ok(table.map(PathSpec::Table));
    }
    exclusive("path.extinction_per_m", "path.visibility_km")?;
    exclusive("path.horizon_radiance", "path.air_temperature_k")?;
    let extinction_per_m = match (
        doc.number("path.extinction_per_m"),
        doc.number("path.visibility_km"),
    ) {
        (Some(b), _) if b.is_finite() && b >= 0.0 => b,
        (Some(b), _) => {
            return Err(doc.error(
                "path.extinction_per_m",
                format!("{}: must be finite and >= 0 (m⁻¹)", show(b)),
            ))
        }
        (None, Some(v)) if v.is_finite() && v > 0.0 => KOSCHMIEDER / (v * 1e3),
        (None, Some(v)) => {
            return Err(doc.error(
                "path.visibility_km",
                format!("{}: must be finite and > 0 (km)", show(v)),
            ))
        }
        (None, None) => {
            return Err(doc.error(
                "path",
                "missing the extinction: give `extinction_per_m`, `visibility_km` or `table`",
            ))
        }
    };
    let horizon = match (doc.number("path.horizon_radiance"), doc.number("path.air_temperature_k")) {
        (Some(l), _) if l.is_finite() && (0.0..=polbrdf::error::MAX_RADIOMETRIC).contains(&l) => Horizon::Radiance(l),
        (Some(l), _) => return Err(doc.error("path.horizon_radiance", format!("{}: must be finite and >= 0 (W·m⁻²·sr⁻¹·µm⁻¹)", show(l)))),
        (None, Some(t)) => Horizon::AirTemperature(
            temperature("path.air_temperature_k", t).map_err(|e| doc.core_error(e))?,
        ),
        (None, None) => return Err(doc.error("path", "missing the horizon radiance: give `horizon_radiance` (visible) or `air_temperature_k` (thermal infrared)")),
    };
    Ok(Some(PathSpec::Homogeneous {
        extinction_per_m,
        horizon,
    }))
}

/// Parses a scene file's text; `path` names it in error messages, and its folder is where
/// relative file names (band, sky profile or table, materials) are found.
///
/// # Errors
/// [`Error::Syntax`] for malformed TOML (including duplicate keys and tables, and dotted
/// keys); [`Error::Field`] naming the line and the key (`table.key`) for an unknown key or
/// table, a wrong type, an invalid value, a key of another sky model, a missing required key
/// (also a `[sun]` the `cie-clear` sky needs, at `sky.model`) or a file that cannot be read or
/// parsed (the message then holds that file's own error);
/// [`Error::File`] when neither `wavelength_um` nor `[band]` is given.
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
    let spectrum = spectrum(&doc)?;
    let sun = sun(&doc)?;
    let sun_time = if sun.is_some() { sun_time(&doc)? } else { None };
    let thermal = ThermalScene {
        surface_temperature_k: surface(&doc),
        sky: sky(&doc)?,
        atmosphere: atmosphere(&doc),
        sun,
    };
    thermal.validate().map_err(|e| doc.core_error(e))?;
    let target = object(&doc, &TARGET)?;
    let background = object(&doc, &BACKGROUND)?;
    let air_path = air_path(&doc)?;
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
/// [`Error::Read`] if it cannot be read; [`Error::Syntax`] if it is not UTF-8 text; as
/// [`parse_scene`].
pub fn read_scene(path: &Path) -> Result<Scene> {
    let text = read_text(path)?;
    parse_scene(&text, path)
}
