//! Material files: flat TOML with the keys of [`polbrdf::MaterialSpec`] (see the README's CLI
//! contract), or a preset name.

use crate::error::{Error, Result};
use polbrdf::{AzimuthTerm, Form, MaterialSpec};
use std::collections::BTreeMap;
use std::path::Path;
use toml::{Spanned, Value};

/// The keys a material file may hold, in the order [`material_to_toml`] writes them.
pub const KEYS: &[&str] = &[
    "name",
    "n",
    "k",
    "sigma_deg",
    "b",
    "a",
    "form",
    "shadowing",
    "tau_deg",
    "omega_deg",
    "azimuth_term",
    "rho_d",
    "rho_v",
];

/// 1-based line of byte offset `pos` in `text`.
fn line_of(text: &str, pos: usize) -> usize {
    text.as_bytes()[..pos.min(text.len())]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
        + 1
}

/// Parses a material file's text; `path` is used in error messages only.
///
/// # Errors
/// [`Error::Syntax`] for malformed TOML (including duplicate keys), [`Error::Field`] for an
/// unknown key, a wrong type or an invalid value (with the key's line), [`Error::File`] for a
/// missing required key.
pub fn parse_material(text: &str, path: &Path) -> Result<MaterialSpec> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let table: BTreeMap<Spanned<String>, Spanned<Value>> =
        toml::from_str(text).map_err(|e| Error::Syntax {
            path: path.to_path_buf(),
            line: e.span().map_or(1, |s| line_of(text, s.start)),
            message: e.message().trim().to_string(),
        })?;
    let mut lines: BTreeMap<&str, usize> = BTreeMap::new();
    let field_err = |key: &str, line: usize, message: String| Error::Field {
        path: path.to_path_buf(),
        line,
        field: key.to_string(),
        message,
    };

    let mut spec = MaterialSpec::new(f64::NAN, f64::NAN);
    spec.sigma_deg = None;
    let mut have_n = false;
    for (key, value) in &table {
        let line = line_of(text, key.span().start);
        let name = key.get_ref().as_str();
        let Some(&known) = KEYS.iter().find(|k| **k == name) else {
            return Err(field_err(
                name,
                line,
                format!("unknown key (known keys: {})", KEYS.join(", ")),
            ));
        };
        lines.insert(known, line);
        let v = value.get_ref();
        let number = || -> Result<f64> {
            match v {
                Value::Float(x) => Ok(*x),
                Value::Integer(i) => Ok(*i as f64),
                other => Err(field_err(
                    known,
                    line,
                    format!("expected a number, got {}", other.type_str()),
                )),
            }
        };
        let string = || -> Result<&str> {
            v.as_str().ok_or_else(|| {
                field_err(
                    known,
                    line,
                    format!("expected a string, got {}", v.type_str()),
                )
            })
        };
        match known {
            "name" => spec.name = Some(string()?.to_string()),
            "n" => {
                spec.n = number()?;
                have_n = true;
            }
            "k" => spec.k = number()?,
            "sigma_deg" => spec.sigma_deg = Some(number()?),
            "b" => spec.b = Some(number()?),
            "a" => spec.a = Some(number()?),
            "form" => {
                spec.form = string()?
                    .parse::<Form>()
                    .map_err(|m| field_err(known, line, m))?
            }
            "shadowing" => {
                spec.shadowing = v.as_bool().ok_or_else(|| {
                    field_err(
                        known,
                        line,
                        format!("expected true or false, got {}", v.type_str()),
                    )
                })?
            }
            "tau_deg" => spec.tau_deg = number()?,
            "omega_deg" => spec.omega_deg = number()?,
            "azimuth_term" => {
                spec.azimuth_term = string()?
                    .parse::<AzimuthTerm>()
                    .map_err(|m| field_err(known, line, m))?
            }
            "rho_d" => spec.rho_d = number()?,
            "rho_v" => spec.rho_v = number()?,
            _ => unreachable!("every key of KEYS is handled"),
        }
    }
    if !have_n {
        return Err(Error::File {
            path: path.to_path_buf(),
            message: "missing required key `n` (real refractive index)".into(),
        });
    }
    // Let the core validate values; map its parameter names back to the file's lines.
    spec.build().map_err(|e| {
        let key = match &e {
            polbrdf::Error::InvalidParameter { name, .. } => Some(*name),
            polbrdf::Error::InconsistentParameters(_) => {
                Some(if spec.b.is_some() { "b" } else { "sigma_deg" })
            }
            _ => None,
        };
        match key.and_then(|k| lines.get(k).map(|l| (k, *l))) {
            Some((k, line)) => field_err(k, line, e.to_string()),
            None => Error::File {
                path: path.to_path_buf(),
                message: e.to_string(),
            },
        }
    })?;
    Ok(spec)
}

/// Loads `arg` as a material: the path of a TOML file if such a file exists, else a preset
/// name (`polbrdf::presets`).
///
/// # Errors
/// As [`parse_material`]; [`Error::Read`] if the file cannot be read; [`Error::File`] if `arg`
/// is neither an existing file nor a preset.
pub fn load_material(arg: &str) -> Result<MaterialSpec> {
    let path = Path::new(arg);
    if path.exists() {
        let bytes = std::fs::read(path).map_err(|source| Error::Read {
            path: path.to_path_buf(),
            source,
        })?;
        let text = String::from_utf8(bytes).map_err(|e| {
            let pos = e.utf8_error().valid_up_to();
            Error::Syntax {
                path: path.to_path_buf(),
                line: line_of(&String::from_utf8_lossy(e.as_bytes()), pos),
                message: "file is not valid UTF-8 text".into(),
            }
        })?;
        return parse_material(&text, path);
    }
    polbrdf::preset(arg).map_err(|_| Error::File {
        path: path.to_path_buf(),
        message: format!(
            "no such file, and not a preset material (presets: {})",
            polbrdf::presets::names().join(", ")
        ),
    })
}

/// A material file for `spec` that [`parse_material`] reads back to the same spec.
pub fn material_to_toml(spec: &MaterialSpec) -> String {
    // Written in KEYS order; the name is TOML-escaped by the toml crate; numbers use the
    // shortest round-trip form.
    let mut lines = Vec::new();
    if let Some(name) = &spec.name {
        lines.push(format!("name = {}", Value::String(name.clone())));
    }
    lines.push(format!("n = {:?}", spec.n));
    lines.push(format!("k = {:?}", spec.k));
    if let Some(s) = spec.sigma_deg {
        lines.push(format!("sigma_deg = {s:?}"));
    }
    if let Some(b) = spec.b {
        lines.push(format!("b = {b:?}"));
    }
    if let Some(a) = spec.a {
        lines.push(format!("a = {a:?}"));
    }
    lines.push(format!("form = \"{}\"", spec.form.as_str()));
    lines.push(format!("shadowing = {}", spec.shadowing));
    lines.push(format!("tau_deg = {:?}", spec.tau_deg));
    lines.push(format!("omega_deg = {:?}", spec.omega_deg));
    lines.push(format!("azimuth_term = \"{}\"", spec.azimuth_term.as_str()));
    lines.push(format!("rho_d = {:?}", spec.rho_d));
    lines.push(format!("rho_v = {:?}", spec.rho_v));
    lines.join("\n") + "\n"
}
