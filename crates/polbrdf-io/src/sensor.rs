//! Sensor files (docs/detection.md): flat TOML, units in the key names, read as material files
//! are ([`crate::material`]): every unknown key, wrong type or invalid value an error naming
//! the file, the line and the key. Two noise models:
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

use crate::csv_io::{line_of, read_band_csv, read_text, short_name, toml_message};
use crate::detection_csv::read_qe_csv;
use crate::error::{Error, Result};
use polbrdf::analysis::detection::{
    Analyzer, Layout, NoiseSpec, QuantumEfficiency, Sensor, SensorSpec,
};
use polbrdf::{Band, Spectrum};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use toml::{Spanned, Value};

/// Which noise model a key belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Model {
    Any,
    Photon,
    Nel,
}

/// What a key holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    Number,
    Numbers,
    Text,
}

/// Every key: name, kind, model, what it is (for messages).
const KEYS: &[(&str, Kind, Model, &str)] = &[
    ("name", Kind::Text, Model::Any, "a display name"),
    (
        "noise_model",
        Kind::Text,
        Model::Any,
        "\"photon-counting\" or \"nel\"",
    ),
    (
        "layout",
        Kind::Text,
        Model::Any,
        "\"dofp\" or \"per-pixel\"",
    ),
    (
        "analyzer_angles_deg",
        Kind::Numbers,
        Model::Any,
        "the analyzer angles, degrees",
    ),
    (
        "q",
        Kind::Number,
        Model::Any,
        "the principal transmittance q, in (0, 1]",
    ),
    (
        "r",
        Kind::Number,
        Model::Any,
        "the minor principal transmittance r, in [0, q)",
    ),
    (
        "extinction_ratio",
        Kind::Number,
        Model::Any,
        "the extinction ratio q/r, > 1",
    ),
    (
        "roll_deg",
        Kind::Number,
        Model::Any,
        "the camera roll, degrees",
    ),
    (
        "pixel_pitch_um",
        Kind::Number,
        Model::Any,
        "the pixel pitch, µm",
    ),
    (
        "focal_length_mm",
        Kind::Number,
        Model::Any,
        "the focal length, mm",
    ),
    (
        "frames",
        Kind::Number,
        Model::Any,
        "frames averaged, an integer ≥ 1",
    ),
    (
        "band_response",
        Kind::Text,
        Model::Any,
        "a band CSV file (wavelength_um,response)",
    ),
    (
        "band_lo_um",
        Kind::Number,
        Model::Any,
        "the lower edge of a flat band, µm",
    ),
    (
        "band_hi_um",
        Kind::Number,
        Model::Any,
        "the upper edge of a flat band, µm",
    ),
    ("f_number", Kind::Number, Model::Photon, "the f-number"),
    (
        "optics_transmittance",
        Kind::Number,
        Model::Photon,
        "the optics transmittance, in (0, 1]",
    ),
    (
        "quantum_efficiency",
        Kind::Number,
        Model::Photon,
        "a constant quantum efficiency, in (0, 1]",
    ),
    (
        "quantum_efficiency_file",
        Kind::Text,
        Model::Photon,
        "a QE CSV file (wavelength_um,qe)",
    ),
    (
        "integration_time_ms",
        Kind::Number,
        Model::Photon,
        "the integration time, ms",
    ),
    (
        "full_well_e",
        Kind::Number,
        Model::Photon,
        "the full well, electrons",
    ),
    (
        "dark_current_e_per_s",
        Kind::Number,
        Model::Photon,
        "the dark current, electrons/s",
    ),
    (
        "read_noise_e",
        Kind::Number,
        Model::Photon,
        "the read noise, electrons rms",
    ),
    (
        "adc_bits",
        Kind::Number,
        Model::Photon,
        "the ADC's bits, an integer in 1..=32",
    ),
    (
        "nel_w_per_m2_sr",
        Kind::Number,
        Model::Nel,
        "the NEL per channel, W·m⁻²·sr⁻¹",
    ),
    ("netd_mk", Kind::Number, Model::Nel, "the NETD, mK"),
    (
        "netd_reference_k",
        Kind::Number,
        Model::Nel,
        "the NETD's reference temperature, K",
    ),
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

/// The keys given: line and value.
struct Doc<'a> {
    path: &'a Path,
    found: BTreeMap<&'static str, (usize, Value)>,
    files: Vec<PathBuf>,
}

impl Doc<'_> {
    fn error(&self, key: &str, message: impl Into<String>) -> Error {
        Error::Field {
            path: self.path.to_path_buf(),
            line: self.found.get(key).map_or(1, |f| f.0),
            field: key.to_string(),
            message: message.into(),
        }
    }

    fn number(&self, key: &str) -> Option<f64> {
        match self.found.get(key)? {
            (_, Value::Float(x)) => Some(*x),
            (_, Value::Integer(i)) => Some(*i as f64),
            _ => None,
        }
    }

    fn text(&self, key: &str) -> Option<&str> {
        match self.found.get(key)? {
            (_, Value::String(s)) => Some(s),
            _ => None,
        }
    }

    fn required(&self, key: &str) -> Result<f64> {
        self.number(key).ok_or_else(|| {
            let what = KEYS.iter().find(|k| k.0 == key).map_or("", |k| k.3);
            Error::File {
                path: self.path.to_path_buf(),
                message: format!("missing required key `{key}` ({what})"),
            }
        })
    }

    /// An integer key in `range` (default `default`).
    fn integer(
        &self,
        key: &str,
        default: u32,
        range: std::ops::RangeInclusive<u32>,
    ) -> Result<u32> {
        let Some(v) = self.number(key) else {
            return Ok(default);
        };
        if v.fract() != 0.0 || v < f64::from(*range.start()) || v > f64::from(*range.end()) {
            return Err(self.error(
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
    fn one_of(&self, a: &str, b: &str) -> Result<()> {
        match (self.found.contains_key(a), self.found.contains_key(b)) {
            (true, true) => Err(self.error(b, format!("give either `{a}` or `{b}`, not both"))),
            (false, false) => Err(Error::File {
                path: self.path.to_path_buf(),
                message: format!("missing required key: give `{a}` or `{b}`"),
            }),
            _ => Ok(()),
        }
    }

    /// The file `key` names, relative to the sensor file's folder, read by `read`.
    fn file<T>(&mut self, key: &str, read: impl FnOnce(&Path) -> Result<T>) -> Result<Option<T>> {
        let Some(name) = self.text(key).map(str::to_string) else {
            return Ok(None);
        };
        if name.is_empty() {
            return Err(self.error(key, "expected the path of a file, got an empty string"));
        }
        let file = match self.path.parent().filter(|p| !p.as_os_str().is_empty()) {
            Some(dir) if Path::new(&name).is_relative() => dir.join(&name),
            _ => PathBuf::from(&name),
        };
        self.files.push(file.clone());
        read(&file)
            .map(Some)
            .map_err(|e| self.error(key, e.to_string()))
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
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let text = &*crate::csv_io::lone_cr_to_lf(text);
    let table: BTreeMap<Spanned<String>, Spanned<Value>> =
        toml::from_str(text).map_err(|e| Error::Syntax {
            path: path.to_path_buf(),
            line: e.span().map_or(1, |s| line_of(text, s.start)),
            message: if toml::from_str::<toml::Table>(text).is_ok() {
                "dotted keys (`a.b = …`) and tables are not allowed in a sensor file: every key \
                 is a plain name (`f_number = 2.8`)"
                    .into()
            } else {
                toml_message(&e, text)
            },
        })?;
    let mut doc = Doc {
        path,
        found: BTreeMap::new(),
        files: Vec::new(),
    };
    for (key, value) in table {
        let line = line_of(text, key.span().start);
        let name = key.get_ref().as_str();
        if matches!(value.get_ref(), Value::Table(_)) {
            return Err(Error::Field {
                path: path.to_path_buf(),
                line,
                field: short_name(name),
                message: "tables are not allowed in a sensor file: every key is a plain name \
                          (`f_number = 2.8`)"
                    .into(),
            });
        }
        let Some(k) = KEYS.iter().find(|k| k.0 == name) else {
            let known: Vec<&str> = KEYS.iter().map(|k| k.0).collect();
            return Err(Error::Field {
                path: path.to_path_buf(),
                line,
                field: short_name(name),
                message: format!("unknown key (known keys: {})", known.join(", ")),
            });
        };
        let v = value.into_inner();
        let ok = match (k.1, &v) {
            (Kind::Number, Value::Float(_) | Value::Integer(_)) => true,
            (Kind::Text, Value::String(_)) => true,
            (Kind::Numbers, Value::Array(a)) => a
                .iter()
                .all(|x| matches!(x, Value::Float(_) | Value::Integer(_))),
            _ => false,
        };
        if !ok {
            let want = match k.1 {
                Kind::Number => "a number",
                Kind::Numbers => "an array of numbers",
                Kind::Text => "a string",
            };
            return Err(Error::Field {
                path: path.to_path_buf(),
                line,
                field: k.0.to_string(),
                message: format!("expected {want} ({}), got {}", k.3, v.type_str()),
            });
        }
        doc.found.insert(k.0, (line, v));
    }
    let spec = spec(&mut doc)?;
    let (sensor, spectrum) = spec.sensor().map_err(|e| core_error(&doc, e))?;
    Ok(SensorFile {
        path: path.to_path_buf(),
        spec,
        sensor,
        spectrum,
        files: doc.files,
    })
}

/// A core error at the line of the key that gives the parameter it names.
fn core_error(doc: &Doc<'_>, e: polbrdf::Error) -> Error {
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
    match key.filter(|k| doc.found.contains_key(k)) {
        Some(k) => doc.error(k, e.to_string()),
        None => Error::File {
            path: doc.path.to_path_buf(),
            message: e.to_string(),
        },
    }
}

/// The spec of the keys found.
fn spec(doc: &mut Doc<'_>) -> Result<SensorSpec> {
    let model = match doc.text("noise_model") {
        Some("photon-counting") => Model::Photon,
        Some("nel") => Model::Nel,
        Some(other) => {
            return Err(doc.error(
                "noise_model",
                format!("unknown noise model {other:?} (known: \"photon-counting\", \"nel\")"),
            ))
        }
        None => {
            return Err(Error::File {
                path: doc.path.to_path_buf(),
                message: "missing required key `noise_model` (\"photon-counting\" or \"nel\")"
                    .into(),
            })
        }
    };
    if let Some(k) = KEYS
        .iter()
        .find(|k| k.2 != Model::Any && k.2 != model && doc.found.contains_key(k.0))
    {
        let other = if k.2 == Model::Photon {
            "photon-counting"
        } else {
            "nel"
        };
        return Err(doc.error(
            k.0,
            format!(
                "belongs to noise_model = \"{other}\", not to noise_model = \"{}\"",
                if model == Model::Photon {
                    "photon-counting"
                } else {
                    "nel"
                }
            ),
        ));
    }
    let layout = match doc.text("layout").unwrap_or("dofp") {
        "dofp" => Layout::Dofp,
        "per-pixel" => Layout::PerPixel,
        other => {
            return Err(doc.error(
                "layout",
                format!("unknown layout {other:?} (known: \"dofp\", \"per-pixel\")"),
            ))
        }
    };
    let analyzer = analyzer(doc)?;
    let band = band(doc)?;
    let noise = match model {
        Model::Photon => photon(doc)?,
        _ => nel(doc)?,
    };
    let name = doc.text("name").map_or_else(
        || {
            doc.path
                .file_stem()
                .map_or_else(|| "sensor".into(), |s| s.to_string_lossy().into_owned())
        },
        str::to_string,
    );
    Ok(SensorSpec {
        name,
        analyzer,
        layout,
        pixel_pitch_m: doc.required("pixel_pitch_um")? * 1e-6,
        focal_length_m: doc.required("focal_length_mm")? * 1e-3,
        frames: doc.integer(
            "frames",
            1,
            1..=polbrdf::analysis::detection::noise::MAX_FRAMES,
        )?,
        band,
        noise,
    })
}

fn analyzer(doc: &Doc<'_>) -> Result<Analyzer> {
    let angles: Vec<f64> = match doc.found.get("analyzer_angles_deg") {
        Some((_, Value::Array(a))) => a
            .iter()
            .map(|v| match v {
                Value::Float(x) => x.to_radians(),
                Value::Integer(i) => (*i as f64).to_radians(),
                _ => f64::NAN,
            })
            .collect(),
        _ => [0.0f64, 45.0, 90.0, 135.0].map(f64::to_radians).to_vec(),
    };
    let q = doc.number("q").unwrap_or(1.0);
    let roll = doc.number("roll_deg").unwrap_or(0.0).to_radians();
    doc.one_of("r", "extinction_ratio")?;
    let built = match doc.number("r") {
        Some(r) => Analyzer::new(angles, q, r, roll),
        None => Analyzer::with_extinction_ratio(angles, q, doc.required("extinction_ratio")?, roll),
    };
    built.map_err(|e| core_error(doc, e))
}

fn band(doc: &mut Doc<'_>) -> Result<Band> {
    if doc.found.contains_key("band_response") {
        for k in ["band_lo_um", "band_hi_um"] {
            if doc.found.contains_key(k) {
                return Err(doc.error(
                    k,
                    "give either `band_response` or `band_lo_um` and `band_hi_um`, not both",
                ));
            }
        }
        return Ok(doc.file("band_response", read_band_csv)?.expect("present"));
    }
    let (lo, hi) = match (doc.number("band_lo_um"), doc.number("band_hi_um")) {
        (Some(lo), Some(hi)) => (lo, hi),
        _ => {
            return Err(Error::File {
                path: doc.path.to_path_buf(),
                message: "missing the band: give `band_response` (a band CSV file) or \
                          `band_lo_um` and `band_hi_um` (a flat band, µm)"
                    .into(),
            })
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

fn photon(doc: &mut Doc<'_>) -> Result<NoiseSpec> {
    doc.one_of("quantum_efficiency", "quantum_efficiency_file")?;
    let quantum_efficiency = match doc.number("quantum_efficiency") {
        Some(q) if q > 0.0 && q <= 1.0 => QuantumEfficiency::Constant(q),
        Some(q) => return Err(doc.error("quantum_efficiency", format!("{q}: must lie in (0, 1]"))),
        None => doc
            .file("quantum_efficiency_file", read_qe_csv)?
            .expect("one of the two"),
    };
    Ok(NoiseSpec::PhotonCounting {
        integration_time_s: doc.required("integration_time_ms")? * 1e-3,
        f_number: doc.required("f_number")?,
        optics_transmittance: doc.number("optics_transmittance").unwrap_or(1.0),
        quantum_efficiency,
        dark_current_e_per_s: doc.number("dark_current_e_per_s").unwrap_or(0.0),
        read_noise_e: doc.required("read_noise_e")?,
        adc_bits: {
            doc.required("adc_bits")?;
            doc.integer("adc_bits", 1, 1..=32)?
        },
        full_well_e: doc.required("full_well_e")?,
    })
}

fn nel(doc: &Doc<'_>) -> Result<NoiseSpec> {
    doc.one_of("nel_w_per_m2_sr", "netd_mk")?;
    if let Some(nel) = doc.number("nel_w_per_m2_sr") {
        if doc.found.contains_key("netd_reference_k") {
            return Err(doc.error("netd_reference_k", "only with `netd_mk`"));
        }
        return Ok(NoiseSpec::Nel(nel));
    }
    Ok(NoiseSpec::Netd {
        netd_k: doc.required("netd_mk")? * 1e-3,
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
