//! `[sky]` of a scene file: the sky models (`SKY_MODELS`), each with its own keys, and the
//! reader of the table.

use super::keys::KEYS;
use crate::csv_io::{parse_sky_profile_csv, parse_sky_table_csv};
use crate::csv_io::{read_sky_profile_csv, read_sky_table_csv};
use crate::error::{Error, Result};
use crate::toml_doc::{split, TomlDoc};
use polbrdf::analysis::SkyModel;

/// The names of the sky models (`[sky] model = …`), the default first.
pub fn sky_model_names() -> impl Iterator<Item = &'static str> {
    SKY_MODELS.iter().map(|m| m.name)
}

/// The sky model named `name` (`[sky] model = …`), or `None` for an unknown name.
pub fn sky_kind(name: &str) -> Option<SkyKind> {
    SKY_MODELS.iter().find(|m| m.name == name).map(|m| m.kind)
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

/// `[sky]`: the model of `SKY_MODELS` (default `none`) with its keys only.
pub(super) fn sky(doc: &TomlDoc<'_>) -> Result<SkyModel> {
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
