//! Material files: flat TOML with the keys of [`polbrdf::MaterialSpec`] (see the README's CLI
//! contract), or a preset name.

use crate::csv_io::read_text;
use crate::error::{Error, Result};
use crate::toml_doc::{self, Format, Key, Kind, TomlDoc};
use polbrdf::model::KeyValue;
use polbrdf::MaterialSpec;
use std::path::Path;
use toml::Value;

/// The keys a material file may hold, in the order [`material_to_toml`] writes them (the core's
/// list, [`polbrdf::model::KEYS`]).
pub use polbrdf::model::KEYS;

/// Parses a material file's text; `path` names it in error messages, and its folder is where a
/// relative `index = "file.yml"` is found (`library:<id>` names a library entry instead).
///
/// # Errors
/// [`Error::Syntax`] for malformed TOML (including duplicate keys), [`Error::Field`] for an
/// unknown key, a wrong type or an invalid value (with the key's line), [`Error::File`] for a
/// missing required key.
pub fn parse_material(text: &str, path: &Path) -> Result<MaterialSpec> {
    let keys: Vec<Key> = KEYS
        .iter()
        .map(|k| toml_doc::key(k, Kind::Any, ""))
        .collect();
    let doc = TomlDoc::parse(
        text,
        path,
        Format {
            noun: "material file",
            example: "`n = 1.5`",
            keys: &keys,
        },
    )?;
    let mut spec = MaterialSpec::new(f64::NAN, f64::NAN);
    spec.sigma_deg = None;
    spec.k = 0.0;
    for (known, _, v) in doc.keys() {
        let value = key_value(&doc, known, v)?;
        if known == "index" {
            spec.spectral = Some(spectral_source(&doc, path, value)?);
            continue;
        }
        spec.set(known, value).map_err(|m| doc.error(known, m))?;
    }
    check_index_or_n(&doc)?;
    validate(&doc, &spec)?;
    Ok(spec)
}

/// The value of key `known` as the core takes it (an integer as a number); a table, array or
/// date is an error saying what the key expects.
fn key_value(doc: &TomlDoc<'_>, known: &str, v: &Value) -> Result<KeyValue> {
    Ok(match v {
        Value::Float(x) => KeyValue::Number(*x),
        Value::Integer(i) => KeyValue::Number(*i as f64),
        Value::String(t) => KeyValue::Text(t.clone()),
        Value::Boolean(b) => KeyValue::Bool(*b),
        other => {
            let want = polbrdf::model::spec::expected(known).unwrap_or("a value");
            return Err(doc.error(known, format!("expected {want}, got {}", other.type_str())));
        }
    })
}

/// `index`: a library id or a refractiveindex.info YAML file relative to the material file's
/// folder (`path`'s), loaded; a file is recorded by its absolute path.
fn spectral_source(
    doc: &TomlDoc<'_>,
    path: &Path,
    value: KeyValue,
) -> Result<polbrdf::model::SpectralSource> {
    let known = "index";
    let KeyValue::Text(source) = value else {
        return Err(doc.error(
            known,
            format!(
                "expected {}",
                polbrdf::model::spec::expected(known).unwrap_or("a string")
            ),
        ));
    };
    // A library id or a refractiveindex.info YAML file, relative to this file's folder.
    let folder = path.parent().filter(|p| !p.as_os_str().is_empty());
    let index =
        crate::library::resolve(&source, folder).map_err(|e| doc.error(known, e.to_string()))?;
    // A file is recorded by its absolute path, so that a material written elsewhere
    // (`material_to_toml`, a fit's output) still finds it.
    let source = match source.strip_prefix(crate::library::PREFIX) {
        Some(_) => source,
        None => {
            let p = Path::new(&source);
            let p = match folder {
                Some(dir) if p.is_relative() => dir.join(p),
                _ => p.to_path_buf(),
            };
            std::fs::canonicalize(&p)
                .map(|p| p.to_string_lossy().into_owned())
                .unwrap_or(source)
        }
    };
    Ok(polbrdf::model::SpectralSource {
        source,
        index: std::sync::Arc::new(index),
    })
}

/// The index is given once: `index` (a spectral index) or the constant `n` (with `k`), not
/// both, and one of them.
fn check_index_or_n(doc: &TomlDoc<'_>) -> Result<()> {
    if doc.has("index") {
        let line = doc.line("index");
        if let Some(both) = ["n", "k"].into_iter().find(|k| doc.has(k)) {
            return Err(doc.error(
                both,
                format!(
                    "give either `index` (line {line}: a spectral index) or the constant `n`, `k`, \
                     not both"
                ),
            ));
        }
    } else if !doc.has("n") {
        return Err(doc.file_error(
            "missing required key `n` (real refractive index), or `index` (a spectral index: \
             \"library:<id>\" or a refractiveindex.info YAML file)",
        ));
    }
    Ok(())
}

/// The core's validation of `spec`, its errors mapped back to the file's keys and lines. A
/// spectral material is validated at the first wavelength of its data.
fn validate(doc: &TomlDoc<'_>, spec: &MaterialSpec) -> Result<()> {
    let built = match spec.wavelength_range() {
        Some((lo, _)) => spec.build_at(lo),
        None => spec.build(),
    };
    built.map_err(|e| {
        let key = match &e {
            polbrdf::Error::InvalidParameter { name, .. }
                if spec.is_spectral() && (*name == "n" || *name == "k") =>
            {
                Some("index")
            }
            polbrdf::Error::InvalidParameter { name, .. } => Some(*name),
            polbrdf::Error::InconsistentParameters(_) => {
                Some(if spec.b.is_some() { "b" } else { "sigma_deg" })
            }
            _ => None,
        };
        match key.filter(|k| doc.has(k)) {
            Some(k) => doc.error(k, e.to_string()),
            None => doc.file_error(e.to_string()),
        }
    })?;
    Ok(())
}

/// Loads `arg` as a material: the path of a TOML file when it contains a `/` or ends in
/// `.toml` ([`names_a_file`]), else a preset name (`polbrdf::presets`) — whatever files exist
/// in the working directory.
///
/// # Errors
/// As [`parse_material`]; [`Error::Read`] if the file cannot be read; [`Error::File`] if `arg`
/// is not a preset (saying so when a file of that name exists).
pub fn load_material(arg: &str) -> Result<MaterialSpec> {
    let path = Path::new(arg);
    if !names_a_file(arg) {
        return polbrdf::preset(arg).map_err(|_| Error::File {
            path: path.to_path_buf(),
            message: format!(
                "not a preset material (presets: {}){}",
                polbrdf::presets::names().join(", "),
                if path.exists() {
                    format!(
                        "; a file of that name exists: write ./{} to read it (a material \
                         argument is a file when it contains a `/` or ends in `.toml`)",
                        crate::csv_io::short_name(arg)
                    )
                } else {
                    String::new()
                }
            ),
        });
    }
    read_material(path)
}

/// Reads the material file `path` (`-`: standard input) and parses it ([`parse_material`]):
/// the one material-file reader of the CLI and the Python module.
///
/// # Errors
/// [`Error::Read`] if it cannot be read; [`Error::Syntax`] if it is not UTF-8 text; as
/// [`parse_material`].
pub fn read_material(path: &Path) -> Result<MaterialSpec> {
    let text = read_text(path)?;
    parse_material(&text, path)
}

/// Whether a material argument names a file rather than a preset: it contains a path separator
/// or ends in `.toml` (so a file or folder in the working directory named like a preset never
/// shadows it).
pub fn names_a_file(arg: &str) -> bool {
    arg.contains('/') || arg.contains(std::path::MAIN_SEPARATOR) || arg.ends_with(".toml")
}

/// A material file for `spec` that [`parse_material`] reads back to the same spec: every key
/// that has a value, in [`KEYS`] order; the name TOML-escaped by the toml crate, numbers in the
/// shortest round-trip form.
pub fn material_to_toml(spec: &MaterialSpec) -> String {
    let mut text = String::new();
    for (key, value) in spec.entries() {
        let v = match value {
            KeyValue::Number(x) => format!("{x:?}"),
            KeyValue::Text(t) => Value::String(t).to_string(),
            KeyValue::Bool(b) => b.to_string(),
        };
        text += &format!("{key} = {v}\n");
    }
    text
}

/// The refractive-index file a material names (`index = "FILE.yml"`, recorded by its absolute
/// path), or `None` for a constant index or a library id: an input an output must not replace.
pub fn index_file(spec: &MaterialSpec) -> Option<std::path::PathBuf> {
    let source = &spec.spectral.as_ref()?.source;
    (!source.starts_with(crate::library::PREFIX)).then(|| std::path::PathBuf::from(source))
}
