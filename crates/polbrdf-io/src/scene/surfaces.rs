//! `[surface]`, `[target]` and `[background]` of a scene file: the surfaces it looks at, their
//! materials and temperatures.

use super::SceneObject;
use crate::error::{Error, Result};
use crate::material::load_material;
use crate::toml_doc::TomlDoc;
use polbrdf::analysis::thermal::temperature;
use polbrdf::MaterialSpec;
use std::path::Path;

/// `[surface]`: the surface temperature (checked with the scene).
pub(super) fn surface(doc: &TomlDoc<'_>) -> Option<f64> {
    doc.number("surface.temperature_k")
}

/// The keys of `[target]` or `[background]`.
pub(super) struct ObjectKeys {
    material: &'static str,
    temperature_k: &'static str,
}

pub(super) const TARGET: ObjectKeys = ObjectKeys {
    material: "target.material",
    temperature_k: "target.temperature_k",
};

pub(super) const BACKGROUND: ObjectKeys = ObjectKeys {
    material: "background.material",
    temperature_k: "background.temperature_k",
};

/// `[target]` or `[background]`.
pub(super) fn object(doc: &TomlDoc<'_>, keys: &ObjectKeys) -> Result<SceneObject> {
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
