//! Lookup-table configurations for `polbrdf lut`: materials × wavelengths × in-plane geometries
//! (docs/scaling.md). Flat TOML; unknown keys are errors naming file, line and key:
//!
//! ```toml
//! materials = ["paint", "gold.toml"]  # required: presets or material files (relative to
//!                                     # this file); named by their `name` key, else the
//!                                     # file stem or the preset name — distinct names
//! wavelength_um = [0.55, 0.6328]      # required: µm, > 0, strictly increasing
//! theta_i_deg = { start = 0, stop = 80, count = 17 }  # an array, or an evenly spaced range
//! theta_r_deg = [0, 10, 20, 30]       # required: degrees in [0, 180], strictly increasing
//! dphi_deg = [0, 90, 180]             # required: phi_r − phi_i, degrees, strictly increasing
//! quantities = ["mueller", "brdf", "dolp"]  # default; any of mueller, brdf, dolp, aolp
//! ```
//!
//! A range `{ start, stop, count }` is `start + j·(stop − start)/(count − 1)` for
//! `j = 0 … count − 2` and exactly `stop` last, as `numpy.linspace` computes it; `count = 1`
//! needs `start = stop`.

use crate::csv_io::read_text;
use crate::error::{Error, Result};
use crate::material::load_material;
use crate::toml_doc::{key, Format, Key, Kind, TomlDoc};
use polbrdf::MaterialSpec;
use std::path::{Path, PathBuf};
use toml::Value;

/// Most values along one axis of a table: every coordinate is written into the table's
/// `attrs.json` (about 25 bytes a value), so 10⁵ keeps it under ~13 MB (10⁷ cost 1 GB).
pub const MAX_AXIS: usize = 100_000;
/// Most materials of a table.
pub const MAX_MATERIALS: usize = 1000;
/// Most rows (materials × wavelengths × geometries) of a table.
pub const MAX_ROWS: u64 = 100_000_000_000;

/// A quantity of a table, in the order of the table's columns.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Quantity {
    /// The pBRDF F, 16 columns `m00 … m33` (sr⁻¹, psps basis).
    Mueller,
    /// The scalar BRDF F00 (sr⁻¹).
    Brdf,
    /// The DoLP for unpolarized illumination.
    Dolp,
    /// The AoLP for unpolarized illumination, degrees.
    Aolp,
}

impl Quantity {
    /// Every quantity, by its name in the file.
    pub const ALL: [(&'static str, Quantity); 4] = [
        ("mueller", Quantity::Mueller),
        ("brdf", Quantity::Brdf),
        ("dolp", Quantity::Dolp),
        ("aolp", Quantity::Aolp),
    ];

    /// Its name in the file (and the Python variable's).
    pub fn name(self) -> &'static str {
        Self::ALL
            .iter()
            .find(|(_, q)| *q == self)
            .map_or("?", |(n, _)| n)
    }
}

/// A lookup-table configuration, read and validated.
#[derive(Debug, Clone, PartialEq)]
pub struct LutConfig {
    /// The configuration file.
    pub path: PathBuf,
    /// The materials with their distinct names, in file order.
    pub materials: Vec<(String, MaterialSpec)>,
    /// Vacuum wavelengths, µm (finite, > 0, strictly increasing).
    pub wavelength_um: Vec<f64>,
    /// Zenith angles toward the source, degrees in [0, 180], strictly increasing.
    pub theta_i_deg: Vec<f64>,
    /// Zenith angles toward the detector, degrees in [0, 180], strictly increasing.
    pub theta_r_deg: Vec<f64>,
    /// Azimuth differences φr − φi, degrees (finite), strictly increasing.
    pub dphi_deg: Vec<f64>,
    /// The quantities, sorted and distinct.
    pub quantities: Vec<Quantity>,
}

impl LutConfig {
    /// Rows of the table: materials × wavelengths × θi × θr × Δφ (≤ [`MAX_ROWS`]).
    pub fn rows(&self) -> u64 {
        [
            self.materials.len(),
            self.wavelength_um.len(),
            self.theta_i_deg.len(),
            self.theta_r_deg.len(),
            self.dphi_deg.len(),
        ]
        .iter()
        .map(|&n| n as u64)
        .product()
    }
}

/// The keys of the file and what each holds (for messages); their values are checked here.
const KEYS: &[Key] = &[
    key(
        "materials",
        Kind::Any,
        "an array of material files or preset names (strings)",
    ),
    key(
        "wavelength_um",
        Kind::Any,
        "wavelengths in µm: an array of numbers or { start, stop, count }",
    ),
    key(
        "theta_i_deg",
        Kind::Any,
        "zenith angles in degrees: an array of numbers or { start, stop, count }",
    ),
    key(
        "theta_r_deg",
        Kind::Any,
        "zenith angles in degrees: an array of numbers or { start, stop, count }",
    ),
    key(
        "dphi_deg",
        Kind::Any,
        "azimuth differences in degrees: an array of numbers or { start, stop, count }",
    ),
    key("quantities", Kind::Any, "an array of quantity names"),
];

/// The configuration's keys, read by [`TomlDoc`].
struct Doc<'a>(TomlDoc<'a>);

impl Doc<'_> {
    fn err(&self, key: &str, message: impl Into<String>) -> Error {
        self.0.error(key, message)
    }

    fn required(&self, key: &str) -> Result<&Value> {
        self.0.value(key).ok_or_else(|| self.0.missing(key))
    }

    fn number(&self, key: &str, v: &Value, what: &str) -> Result<f64> {
        match v {
            Value::Float(x) => Ok(*x),
            Value::Integer(i) => Ok(*i as f64),
            other => Err(self.err(
                key,
                format!("{what} must be a number, got {}", other.type_str()),
            )),
        }
    }

    /// An axis: an array of numbers or `{ start, stop, count }`; finite, strictly increasing,
    /// every value accepted by `valid` (which says what is expected).
    fn axis(&self, key: &str, valid: (fn(f64) -> bool, &str)) -> Result<Vec<f64>> {
        let values = match self.required(key)? {
            Value::Array(a) => {
                if a.len() > MAX_AXIS {
                    return Err(self.err(
                        key,
                        format!("{} values: at most {MAX_AXIS} per axis", a.len()),
                    ));
                }
                a.iter()
                    .enumerate()
                    .map(|(j, v)| self.number(key, v, &format!("element {j}")))
                    .collect::<Result<Vec<f64>>>()?
            }
            Value::Table(t) => self.range(key, t)?,
            other => {
                return Err(self.err(
                    key,
                    format!(
                        "expected an array of numbers or {{ start, stop, count }}, got {}",
                        other.type_str()
                    ),
                ))
            }
        };
        if values.is_empty() {
            return Err(self.err(key, "an empty array: a table axis needs a value"));
        }
        for (j, &x) in values.iter().enumerate() {
            if !x.is_finite() || !(valid.0)(x) {
                return Err(self.err(key, format!("element {j} = {x}: expected {}", valid.1)));
            }
        }
        if let Some(j) = values.windows(2).position(|w| w[1] <= w[0]) {
            return Err(self.err(
                key,
                format!(
                    "not strictly increasing: element {j} = {}, element {} = {}",
                    values[j],
                    j + 1,
                    values[j + 1]
                ),
            ));
        }
        Ok(values)
    }

    fn range(&self, key: &str, t: &toml::Table) -> Result<Vec<f64>> {
        if let Some(k) = t
            .keys()
            .find(|k| !["start", "stop", "count"].contains(&k.as_str()))
        {
            return Err(self.err(
                key,
                format!("unknown key `{k}` in the range (known: start, stop, count)"),
            ));
        }
        let get = |k: &str| {
            t.get(k).ok_or_else(|| {
                self.err(
                    key,
                    format!("the range needs `{k}` (start, stop and count)"),
                )
            })
        };
        let start = self.number(key, get("start")?, "`start`")?;
        let stop = self.number(key, get("stop")?, "`stop`")?;
        let count = match get("count")? {
            Value::Integer(c) if *c >= 1 && (*c as u64) <= MAX_AXIS as u64 => *c as usize,
            Value::Integer(c) => {
                return Err(self.err(key, format!("`count` = {c}: expected 1 to {MAX_AXIS}")))
            }
            other => {
                return Err(self.err(
                    key,
                    format!("`count` must be an integer, got {}", other.type_str()),
                ))
            }
        };
        if !start.is_finite() || !stop.is_finite() {
            return Err(self.err(key, "`start` and `stop` must be finite"));
        }
        if count == 1 {
            return if start == stop {
                Ok(vec![start])
            } else {
                Err(self.err(key, "`count` = 1 needs `start` = `stop`"))
            };
        }
        // numpy.linspace: j·step + start, the last exactly `stop`.
        let step = (stop - start) / (count - 1) as f64;
        let mut v: Vec<f64> = (0..count).map(|j| j as f64 * step + start).collect();
        v[count - 1] = stop;
        Ok(v)
    }

    fn strings(&self, key: &str) -> Result<Vec<String>> {
        match self.required(key)? {
            Value::Array(a) => a
                .iter()
                .enumerate()
                .map(|(j, v)| match v {
                    Value::String(s) => Ok(s.clone()),
                    other => Err(self.err(
                        key,
                        format!("element {j} must be a string, got {}", other.type_str()),
                    )),
                })
                .collect(),
            other => Err(self.err(
                key,
                format!("expected an array of strings, got {}", other.type_str()),
            )),
        }
    }

    /// A material file (relative to the configuration's folder) or a preset name.
    fn material(&self, arg: &str) -> Result<(String, MaterialSpec)> {
        if arg.is_empty() {
            return Err(self.err(
                "materials",
                "an empty string: expected a material file or a preset name",
            ));
        }
        let file = self.0.resolve(arg);
        let spec = match file.to_str() {
            Some(f) if file.is_file() => load_material(f),
            _ => load_material(arg),
        }
        .map_err(|e| self.err("materials", format!("`{arg}`: {e}")))?;
        let name = spec.name.clone().unwrap_or_else(|| {
            Path::new(arg)
                .file_stem()
                .map_or_else(|| arg.to_string(), |s| s.to_string_lossy().into_owned())
        });
        Ok((name, spec))
    }
}

/// Parses a configuration (`text`, read from `path`; material files are found relative to its
/// folder).
///
/// # Errors
/// [`Error::Syntax`] for malformed TOML; [`Error::Field`] naming the line and the key for an
/// unknown key, a wrong type, an invalid, repeated or unsorted value, a material that cannot be
/// loaded (its own error inside) or two materials of the same name; [`Error::File`] for a
/// missing key or a table beyond [`MAX_ROWS`] rows.
pub fn parse_lut_config(text: &str, path: &Path) -> Result<LutConfig> {
    let doc = Doc(TomlDoc::parse(
        text,
        path,
        Format {
            noun: "lookup-table configuration",
            example: "`dphi_deg = [0, 90]`",
            keys: KEYS,
        },
    )?);
    let materials = materials(&doc)?;
    let zenith = (
        (|x: f64| (0.0..=180.0).contains(&x)) as fn(f64) -> bool,
        "a zenith angle in [0, 180] degrees",
    );
    let cfg = LutConfig {
        path: path.to_path_buf(),
        wavelength_um: doc.axis("wavelength_um", (|x| x > 0.0, "a wavelength > 0 µm"))?,
        theta_i_deg: doc.axis("theta_i_deg", zenith)?,
        theta_r_deg: doc.axis("theta_r_deg", zenith)?,
        dphi_deg: doc.axis(
            "dphi_deg",
            (
                |x| x.abs() <= polbrdf::MAX_AZIMUTH_DEG,
                "an azimuth difference within ±1e8° (polbrdf::MAX_AZIMUTH_DEG: beyond it the \
                 angle has no digit left)",
            ),
        )?,
        quantities: quantities(&doc)?,
        materials,
    };
    check_rows(&cfg)?;
    check_wavelengths(&doc, &cfg)?;
    Ok(cfg)
}

/// `materials`: 1 to [`MAX_MATERIALS`] presets or files, loaded, with distinct names.
fn materials(doc: &Doc<'_>) -> Result<Vec<(String, MaterialSpec)>> {
    let names = doc.strings("materials")?;
    if names.is_empty() || names.len() > MAX_MATERIALS {
        return Err(doc.err(
            "materials",
            format!("{} materials: expected 1 to {MAX_MATERIALS}", names.len()),
        ));
    }
    let mut materials: Vec<(String, MaterialSpec)> = Vec::with_capacity(names.len());
    for arg in &names {
        let (name, spec) = doc.material(arg)?;
        if materials.iter().any(|(n, _)| *n == name) {
            return Err(doc.err(
                "materials",
                format!("two materials are named `{name}` (set distinct `name` keys in the files)"),
            ));
        }
        materials.push((name, spec));
    }
    Ok(materials)
}

/// `quantities`, each once, in the order of the table's columns; mueller, brdf and dolp when
/// absent.
fn quantities(doc: &Doc<'_>) -> Result<Vec<Quantity>> {
    if !doc.0.has("quantities") {
        return Ok(vec![Quantity::Mueller, Quantity::Brdf, Quantity::Dolp]);
    }
    let mut q = Vec::new();
    for s in doc.strings("quantities")? {
        match Quantity::ALL.iter().find(|(n, _)| *n == s) {
            Some((_, x)) if !q.contains(x) => q.push(*x),
            Some(_) => return Err(doc.err("quantities", format!("`{s}` appears twice"))),
            None => {
                return Err(doc.err(
                    "quantities",
                    format!(
                        "unknown quantity `{s}` (known: {})",
                        Quantity::ALL.map(|(n, _)| n).join(", ")
                    ),
                ))
            }
        }
    }
    if q.is_empty() {
        return Err(doc.err("quantities", "an empty array: name a quantity"));
    }
    q.sort();
    Ok(q)
}

/// The table's rows (materials × wavelengths × theta_i × theta_r × dphi) within [`MAX_ROWS`].
fn check_rows(cfg: &LutConfig) -> Result<()> {
    let rows = [
        cfg.materials.len(),
        cfg.wavelength_um.len(),
        cfg.theta_i_deg.len(),
        cfg.theta_r_deg.len(),
        cfg.dphi_deg.len(),
    ]
    .iter()
    .try_fold(1u64, |acc, &n| acc.checked_mul(n as u64));
    if rows.is_none_or(|r| r > MAX_ROWS) {
        return Err(Error::File {
            path: cfg.path.clone(),
            message: format!(
                "the table would have more than {MAX_ROWS} rows (materials × wavelengths × \
                 theta_i × theta_r × dphi): split it"
            ),
        });
    }
    Ok(())
}

/// Every wavelength inside every spectral index's data: refused here, before any output.
fn check_wavelengths(doc: &Doc<'_>, cfg: &LutConfig) -> Result<()> {
    for (name, spec) in &cfg.materials {
        if let Some(j) = cfg
            .wavelength_um
            .iter()
            .position(|&l| spec.index_columns(&[l]).is_err())
        {
            let (lo, hi) = spec.wavelength_range().unwrap_or((f64::NAN, f64::NAN));
            return Err(doc.err(
                "wavelength_um",
                format!(
                    "element {j} = {} µm is outside the data of material `{name}`'s index \
                     ({lo}–{hi} µm)",
                    cfg.wavelength_um[j]
                ),
            ));
        }
    }
    Ok(())
}

/// Reads a configuration file and parses it ([`parse_lut_config`]).
///
/// # Errors
/// [`Error::Read`] if it cannot be read; [`Error::Syntax`] if it is not UTF-8; as
/// [`parse_lut_config`].
pub fn read_lut_config(path: &Path) -> Result<LutConfig> {
    let text = read_text(path)?;
    parse_lut_config(&text, path)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<LutConfig> {
        parse_lut_config(text, Path::new("lut.toml"))
    }

    const BASE: &str = "materials = [\"paint\"]\nwavelength_um = [0.6]\ntheta_i_deg = [0, 30]\n\
                        theta_r_deg = [0, 30]\n";

    #[test]
    fn a_range_is_numpy_linspace() {
        let c = parse(&format!(
            "{BASE}dphi_deg = {{ start = 0, stop = 180, count = 7 }}\n"
        ))
        .unwrap();
        assert_eq!(c.dphi_deg, [0.0, 30.0, 60.0, 90.0, 120.0, 150.0, 180.0]);
        let c = parse(&format!(
            "{BASE}dphi_deg = {{ start = 0.1, stop = 0.7, count = 4 }}\n"
        ))
        .unwrap();
        let step = (0.7 - 0.1) / 3.0;
        assert_eq!(c.dphi_deg, [0.1, step + 0.1, 2.0 * step + 0.1, 0.7]);
        assert_eq!(c.rows(), 4 * 4);
        assert_eq!(
            c.quantities,
            [Quantity::Mueller, Quantity::Brdf, Quantity::Dolp]
        );
        assert_eq!(c.materials[0].0, "paint");
    }

    #[test]
    fn errors_name_line_and_key() {
        let cases = [
            ("dphi_deg = [0, 0]\n", 5, "dphi_deg", "strictly increasing"),
            ("dphi_deg = [0]\nfoo = 1\n", 6, "foo", "unknown key"),
            (
                "dphi_deg = [0]\nquantities = [\"dop\"]\n",
                6,
                "quantities",
                "unknown quantity",
            ),
            (
                "dphi_deg = { start = 0, stop = 1, count = 0 }\n",
                5,
                "dphi_deg",
                "`count` = 0",
            ),
            ("dphi_deg = \"x\"\n", 5, "dphi_deg", "got string"),
        ];
        for (tail, line, field, msg) in cases {
            match parse(&format!("{BASE}{tail}")) {
                Err(Error::Field {
                    line: l,
                    field: f,
                    message,
                    ..
                }) => {
                    assert_eq!((l, f.as_str()), (line, field), "{tail}: {message}");
                    assert!(message.contains(msg), "{tail}: {message}");
                }
                other => panic!("{tail}: {other:?}"),
            }
        }
        let e = parse("materials = [\"paint\"]\n").unwrap_err().to_string();
        assert!(e.contains("missing required key `wavelength_um`"), "{e}");
        let e = parse(
            "materials = [\"paint\"]\nwavelength_um = { start = 0.5, stop = 1, count = 100000 }\n\
             theta_i_deg = { start = 0, stop = 80, count = 100000 }\ntheta_r_deg = [0, 30]\n\
             dphi_deg = { start = 0, stop = 1, count = 100000 }\n",
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("more than"), "{e}");
    }

    /// The fuzz target's property on every truncation of a valid configuration and on every
    /// one-byte substitution by a few significant characters (cargo-fuzz explores further).
    #[test]
    fn truncations_and_substitutions_never_panic() {
        let text = "materials = [\"paint\"]\nwavelength_um = [0.6]\n\
                    theta_i_deg = { start = 0, stop = 80, count = 5 }\n\
                    theta_r_deg = [0, 30, 60]\ndphi_deg = [0, 180]\nquantities = [\"dolp\"]\n";
        let check = |t: &str| match parse(t) {
            Ok(c) => {
                assert!(c.rows() >= 1);
                assert!(c.theta_r_deg.windows(2).all(|w| w[0] < w[1]));
            }
            Err(e) => assert!(e.to_string().starts_with("lut.toml"), "{e}"),
        };
        for end in 0..=text.len() {
            check(&text[..end]);
        }
        for i in 0..text.len() {
            for c in ["-", "9", "]", "{", "\"", "e", "."] {
                check(&format!("{}{c}{}", &text[..i], &text[i + 1..]));
            }
        }
    }
}
