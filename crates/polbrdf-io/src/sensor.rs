//! Sensor files (docs/detection.md): flat TOML, units in the key names, read by the one TOML
//! reader ([`crate::toml_doc`]) as material files are: every unknown key, wrong type or invalid
//! value an error naming the file, the line and the key. Two noise models:
//!
//! ```toml
//! name = "a DoFP camera"               # optional display name
//! noise_model = "photon-counting"      # required: "photon-counting" | "nel"
//! layout = "dofp"                      # "dofp" (2×2 super-pixel, default) | "per-pixel"
//! analyzer_angles_deg = [0, 45, 90, 135]   # default; ≥ 3 angles
//! q = 0.8                              # principal transmittance (default 1)
//! extinction_ratio = 300               # or r = …; one of the two is required (inf: ideal)
//! roll_deg = 0                         # camera roll (default 0)
//! pixel_pitch_um = 3.45                # required
//! focal_length_mm = 25                 # required
//! frames = 1                           # frames averaged (default 1)
//! band_response = "band.csv"           # a band CSV (wavelength_um,response) ...
//! band_lo_um = 0.4                     # ... or a flat band from band_lo_um to band_hi_um
//! band_hi_um = 0.7
//! # photon-counting only:
//! f_number = 2.8                       # required
//! optics_transmittance = 0.9           # default 1
//! quantum_efficiency = 0.6             # or quantum_efficiency_file = "qe.csv" (wavelength_um,qe)
//! integration_time_ms = 10             # required
//! full_well_e = 10500                  # required
//! dark_current_e_per_s = 3             # default 0
//! read_noise_e = 2.3                   # required
//! adc_bits = 12                        # required; the ADC spans the full well
//! # nel only: nel_w_per_m2_sr = 0.02, or netd_mk = 50 with netd_reference_k = 300 (default)
//! ```
//!
//! Files named (`band_response`, `quantum_efficiency_file`) are found relative to the sensor
//! file's folder.

use crate::csv_io::{read_band_csv, read_text};
use crate::detection_csv::read_qe_csv;
use crate::error::{Error, Result};
use crate::toml_doc::{key, Format, Key, Kind, TomlDoc};
use polbrdf::analysis::detection::{
    Analyzer, Layout, NoiseSpec, QuantumEfficiency, Sensor, SensorSpec,
};
use polbrdf::{names, Band, Spectrum};
use std::path::{Path, PathBuf};

/// The noise models of `noise_model = …` (which noise model a key belongs to).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Model {
    /// `photon-counting`: a photon-counting camera.
    Photon,
    /// `nel`: a noise-equivalent radiance (or NETD).
    Nel,
}

impl Model {
    /// Every noise model.
    pub const ALL: [Model; 2] = [Model::Photon, Model::Nel];

    /// Its name in sensor files (and in `detect`'s `best.json`).
    pub fn name(self) -> &'static str {
        match self {
            Model::Photon => "photon-counting",
            Model::Nel => "nel",
        }
    }
}

/// Every key, its kind and what it is (for messages).
const KEYS: &[Key] = &[
    key("name", Kind::Text, "a display name"),
    key("noise_model", Kind::Text, "the noise model"),
    key("layout", Kind::Text, "the analyzer channels' layout"),
    key(
        "analyzer_angles_deg",
        Kind::Numbers,
        "the analyzer angles, degrees",
    ),
    key(
        "q",
        Kind::Number,
        "the principal transmittance q, in (0, 1]",
    ),
    key(
        "r",
        Kind::Number,
        "the minor principal transmittance r, in [0, q)",
    ),
    key(
        "extinction_ratio",
        Kind::Number,
        "the extinction ratio q/r, > 1",
    ),
    key("roll_deg", Kind::Number, "the camera roll, degrees"),
    key("pixel_pitch_um", Kind::Number, "the pixel pitch, µm"),
    key("focal_length_mm", Kind::Number, "the focal length, mm"),
    key("frames", Kind::Number, "frames averaged, an integer ≥ 1"),
    key(
        "band_response",
        Kind::Text,
        "a band CSV file (wavelength_um,response)",
    ),
    key(
        "band_lo_um",
        Kind::Number,
        "the lower edge of a flat band, µm",
    ),
    key(
        "band_hi_um",
        Kind::Number,
        "the upper edge of a flat band, µm",
    ),
    key("f_number", Kind::Number, "the f-number"),
    key(
        "optics_transmittance",
        Kind::Number,
        "the optics transmittance, in (0, 1]",
    ),
    key(
        "quantum_efficiency",
        Kind::Number,
        "a constant quantum efficiency, in (0, 1]",
    ),
    key(
        "quantum_efficiency_file",
        Kind::Text,
        "a QE CSV file (wavelength_um,qe)",
    ),
    key(
        "integration_time_ms",
        Kind::Number,
        "the integration time, ms",
    ),
    key("full_well_e", Kind::Number, "the full well, electrons"),
    key(
        "dark_current_e_per_s",
        Kind::Number,
        "the dark current, electrons/s",
    ),
    key(
        "read_noise_e",
        Kind::Number,
        "the read noise, electrons rms",
    ),
    key(
        "adc_bits",
        Kind::Number,
        "the ADC's bits, an integer in 1..=32",
    ),
    key(
        "nel_w_per_m2_sr",
        Kind::Number,
        "the NEL per channel, W·m⁻²·sr⁻¹",
    ),
    key("netd_mk", Kind::Number, "the NETD, mK"),
    key(
        "netd_reference_k",
        Kind::Number,
        "the NETD's reference temperature, K",
    ),
];

/// The keys of one noise model only.
const MODEL_KEYS: &[(&str, Model)] = &[
    ("f_number", Model::Photon),
    ("optics_transmittance", Model::Photon),
    ("quantum_efficiency", Model::Photon),
    ("quantum_efficiency_file", Model::Photon),
    ("integration_time_ms", Model::Photon),
    ("full_well_e", Model::Photon),
    ("dark_current_e_per_s", Model::Photon),
    ("read_noise_e", Model::Photon),
    ("adc_bits", Model::Photon),
    ("nel_w_per_m2_sr", Model::Nel),
    ("netd_mk", Model::Nel),
    ("netd_reference_k", Model::Nel),
];

/// The core's parameter names and the keys that give them.
const CORE_NAMES: &[(&str, &str)] = &[
    ("q", "q"),
    ("r", "r"),
    ("extinction_ratio", "extinction_ratio"),
    ("roll", "roll_deg"),
    ("analyzer_angles", "analyzer_angles_deg"),
    ("integration_time_s", "integration_time_ms"),
    ("pixel_pitch_m", "pixel_pitch_um"),
    ("focal_length_m", "focal_length_mm"),
    ("ifov_rad", "focal_length_mm"),
    ("f_number", "f_number"),
    ("optics_transmittance", "optics_transmittance"),
    ("dark_current_e_per_s", "dark_current_e_per_s"),
    ("read_noise_e", "read_noise_e"),
    ("gain_e_per_count", "full_well_e"),
    ("full_well_e", "full_well_e"),
    ("frames", "frames"),
    ("adc_bits", "adc_bits"),
    ("nel", "nel_w_per_m2_sr"),
    ("netd_k", "netd_mk"),
    ("reference_temperature_k", "netd_reference_k"),
];

/// A sensor file, read and validated.
#[derive(Debug, Clone, PartialEq)]
pub struct SensorFile {
    /// The file.
    pub path: PathBuf,
    /// The sensor as the file gives it.
    pub spec: SensorSpec,
    /// The sensor it makes and the spectrum a scene is observed over for it.
    pub sensor: Sensor,
    /// That spectrum.
    pub spectrum: Spectrum,
    /// The files it names (band, QE): inputs an output must not replace.
    pub files: Vec<PathBuf>,
}

/// The sensor format of [`TomlDoc`].
const FORMAT: Format<'static> = Format {
    noun: "sensor file",
    example: "`f_number = 2.8`",
    keys: KEYS,
};

/// The number `key`, required (an error of the file when absent).
fn required(doc: &TomlDoc<'_>, key: &str) -> Result<f64> {
    doc.required_number(key)
}

/// An integer key in `range` (default `default`).
fn integer(
    doc: &TomlDoc<'_>,
    key: &str,
    default: u32,
    range: std::ops::RangeInclusive<u32>,
) -> Result<u32> {
    let Some(v) = doc.number(key) else {
        return Ok(default);
    };
    if v.fract() != 0.0 || v < f64::from(*range.start()) || v > f64::from(*range.end()) {
        return Err(doc.error(
            key,
            format!(
                "{v}: must be an integer in {}..={}",
                range.start(),
                range.end()
            ),
        ));
    }
    Ok(v as u32)
}

/// Exactly one of `a` and `b`.
fn one_of(doc: &TomlDoc<'_>, a: &str, b: &str) -> Result<()> {
    match (doc.has(a), doc.has(b)) {
        (true, true) => Err(doc.error(b, format!("give either `{a}` or `{b}`, not both"))),
        (false, false) => Err(doc.file_error(format!("missing required key: give `{a}` or `{b}`"))),
        _ => Ok(()),
    }
}

/// Parses a sensor file's text (module documentation); `path` names it in messages and its
/// folder is where the files it names are found.
///
/// # Errors
/// [`Error::Syntax`] for malformed TOML (tables and dotted keys included); [`Error::Field`]
/// naming the line and the key for an unknown key, a key of the other noise model, a wrong
/// type, an invalid value, two keys that exclude each other, or a file it names that cannot be
/// read; [`Error::File`] for a missing required key.
pub fn parse_sensor(text: &str, path: &Path) -> Result<SensorFile> {
    let doc = TomlDoc::parse(text, path, FORMAT)?;
    let spec = spec(&doc)?;
    let (sensor, spectrum) = spec.sensor().map_err(|e| core_error(&doc, e))?;
    Ok(SensorFile {
        path: path.to_path_buf(),
        spec,
        sensor,
        spectrum,
        files: doc.files(),
    })
}

/// A core error at the line of the key that gives the parameter it names.
fn core_error(doc: &TomlDoc<'_>, e: polbrdf::Error) -> Error {
    let name = match &e {
        polbrdf::Error::InvalidParameter { name, .. }
        | polbrdf::Error::InvalidParameterAt { name, .. } => Some(*name),
        polbrdf::Error::InconsistentParameters(m) if m.contains("analyzer") => {
            Some("analyzer_angles")
        }
        polbrdf::Error::InconsistentParameters(m) if m.contains("quantum efficiency") => {
            Some("quantum_efficiency_file")
        }
        _ => None,
    };
    let key = name.and_then(|n| {
        CORE_NAMES
            .iter()
            .find(|c| c.0 == n)
            .map_or(Some(n), |c| Some(c.1))
    });
    match key.filter(|k| doc.has(k)) {
        Some(k) => doc.error(k, e.to_string()),
        None => doc.file_error(e.to_string()),
    }
}

/// The spec of the keys found.
fn spec(doc: &TomlDoc<'_>) -> Result<SensorSpec> {
    let models = || names::quoted(&Model::ALL, Model::name);
    let model = match doc.text("noise_model") {
        Some(name) => names::find(&Model::ALL, Model::name, name).ok_or_else(|| {
            doc.error(
                "noise_model",
                format!("unknown noise model {name:?} (known: {})", models()),
            )
        })?,
        None => {
            return Err(doc.file_error(format!("missing required key `noise_model` ({})", models())))
        }
    };
    if let Some(k) = MODEL_KEYS.iter().find(|k| k.1 != model && doc.has(k.0)) {
        return Err(doc.error(
            k.0,
            format!(
                "belongs to noise_model = \"{}\", not to noise_model = \"{}\"",
                k.1.name(),
                model.name()
            ),
        ));
    }
    let layout = match doc.text("layout") {
        None => Layout::ALL[0],
        Some(name) => Layout::parse(name).ok_or_else(|| {
            doc.error(
                "layout",
                format!(
                    "unknown layout {name:?} (known: {})",
                    names::quoted(&Layout::ALL, Layout::as_str)
                ),
            )
        })?,
    };
    let analyzer = analyzer(doc)?;
    let band = band(doc)?;
    let noise = match model {
        Model::Photon => photon(doc)?,
        _ => nel(doc)?,
    };
    let name = doc.text("name").map_or_else(
        || {
            doc.path()
                .file_stem()
                .map_or_else(|| "sensor".into(), |s| s.to_string_lossy().into_owned())
        },
        str::to_string,
    );
    Ok(SensorSpec {
        name,
        analyzer,
        layout,
        pixel_pitch_m: required(doc, "pixel_pitch_um")? * 1e-6,
        focal_length_m: required(doc, "focal_length_mm")? * 1e-3,
        frames: integer(
            doc,
            "frames",
            1,
            1..=polbrdf::analysis::detection::noise::MAX_FRAMES,
        )?,
        band,
        noise,
    })
}

fn analyzer(doc: &TomlDoc<'_>) -> Result<Analyzer> {
    let angles: Vec<f64> = match doc.numbers("analyzer_angles_deg") {
        Some(a) => a.into_iter().map(f64::to_radians).collect(),
        None => [0.0f64, 45.0, 90.0, 135.0].map(f64::to_radians).to_vec(),
    };
    let q = doc.number("q").unwrap_or(1.0);
    let roll = doc.number("roll_deg").unwrap_or(0.0).to_radians();
    one_of(doc, "r", "extinction_ratio")?;
    let built = match doc.number("r") {
        Some(r) => Analyzer::new(angles, q, r, roll),
        None => {
            Analyzer::with_extinction_ratio(angles, q, required(doc, "extinction_ratio")?, roll)
        }
    };
    built.map_err(|e| core_error(doc, e))
}

fn band(doc: &TomlDoc<'_>) -> Result<Band> {
    if doc.has("band_response") {
        for k in ["band_lo_um", "band_hi_um"] {
            if doc.has(k) {
                return Err(doc.error(
                    k,
                    "give either `band_response` or `band_lo_um` and `band_hi_um`, not both",
                ));
            }
        }
        return Ok(doc
            .read_file("band_response", read_band_csv)?
            .expect("present"));
    }
    let (lo, hi) = match (doc.number("band_lo_um"), doc.number("band_hi_um")) {
        (Some(lo), Some(hi)) => (lo, hi),
        _ => {
            return Err(doc.file_error(
                "missing the band: give `band_response` (a band CSV file) or `band_lo_um` and \
                 `band_hi_um` (a flat band, µm)",
            ))
        }
    };
    if !(lo.is_finite() && lo > 0.0) {
        return Err(doc.error("band_lo_um", format!("{lo}: must be finite and > 0 (µm)")));
    }
    if !(hi.is_finite() && hi > lo) {
        return Err(doc.error(
            "band_hi_um",
            format!("{hi}: must be finite and above band_lo_um"),
        ));
    }
    Band::new("flat band", vec![lo, hi], vec![1.0, 1.0]).map_err(|e| core_error(doc, e))
}

fn photon(doc: &TomlDoc<'_>) -> Result<NoiseSpec> {
    one_of(doc, "quantum_efficiency", "quantum_efficiency_file")?;
    let quantum_efficiency = match doc.number("quantum_efficiency") {
        Some(q) if q > 0.0 && q <= 1.0 => QuantumEfficiency::Constant(q),
        Some(q) => return Err(doc.error("quantum_efficiency", format!("{q}: must lie in (0, 1]"))),
        None => doc
            .read_file("quantum_efficiency_file", read_qe_csv)?
            .expect("one of the two"),
    };
    Ok(NoiseSpec::PhotonCounting {
        integration_time_s: required(doc, "integration_time_ms")? * 1e-3,
        f_number: required(doc, "f_number")?,
        optics_transmittance: doc.number("optics_transmittance").unwrap_or(1.0),
        quantum_efficiency,
        dark_current_e_per_s: doc.number("dark_current_e_per_s").unwrap_or(0.0),
        read_noise_e: required(doc, "read_noise_e")?,
        adc_bits: {
            required(doc, "adc_bits")?;
            integer(doc, "adc_bits", 1, 1..=32)?
        },
        full_well_e: required(doc, "full_well_e")?,
    })
}

fn nel(doc: &TomlDoc<'_>) -> Result<NoiseSpec> {
    one_of(doc, "nel_w_per_m2_sr", "netd_mk")?;
    if let Some(nel) = doc.number("nel_w_per_m2_sr") {
        if doc.has("netd_reference_k") {
            return Err(doc.error("netd_reference_k", "only with `netd_mk`"));
        }
        return Ok(NoiseSpec::Nel(nel));
    }
    Ok(NoiseSpec::Netd {
        netd_k: required(doc, "netd_mk")? * 1e-3,
        reference_temperature_k: doc.number("netd_reference_k").unwrap_or(300.0),
    })
}

/// Reads a sensor file ([`parse_sensor`]).
///
/// # Errors
/// [`Error::Read`] if it cannot be read; as [`parse_sensor`].
pub fn read_sensor(path: &Path) -> Result<SensorFile> {
    let text = read_text(path)?;
    parse_sensor(&text, path)
}
