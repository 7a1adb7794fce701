//! `[atmosphere]` and `[path]` of a scene file: the air between the surface and a sensor.

use crate::csv_io::show;
use crate::error::Result;
use crate::toml_doc::{split, TomlDoc};
use polbrdf::analysis::detection::path::KOSCHMIEDER;
use polbrdf::analysis::detection::{Horizon, PathSpec};
use polbrdf::analysis::thermal::temperature;
use polbrdf::analysis::Atmosphere;

/// `[atmosphere]`, with the defaults of [`Atmosphere`].
pub(super) fn atmosphere(doc: &TomlDoc<'_>) -> Atmosphere {
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
pub(super) fn air_path(doc: &TomlDoc<'_>) -> Result<Option<PathSpec>> {
    if !doc.has("path") {
        return Ok(None);
    }
    if doc.has("path.table") {
        return path_table(doc);
    }
    exclusive(doc, "path.extinction_per_m", "path.visibility_km")?;
    exclusive(doc, "path.horizon_radiance", "path.air_temperature_k")?;
    let extinction_per_m = extinction(doc)?;
    let horizon = horizon(doc)?;
    Ok(Some(PathSpec::Homogeneous {
        extinction_per_m,
        horizon,
    }))
}

/// An error at `b` when both `a` and `b` are given.
fn exclusive(doc: &TomlDoc<'_>, a: &str, b: &str) -> Result<()> {
    if doc.has(a) && doc.has(b) {
        return Err(doc.error(
            b,
            format!("give either `{}` or `{}`, not both", split(a).1, split(b).1),
        ));
    }
    Ok(())
}

/// `[path]` by `table`: the CSV file it names, with none of the homogeneous path's keys.
fn path_table(doc: &TomlDoc<'_>) -> Result<Option<PathSpec>> {
    for k in [
        "path.extinction_per_m",
        "path.visibility_km",
        "path.horizon_radiance",
        "path.air_temperature_k",
    ] {
        exclusive(doc, "path.table", k)?;
    }
    let table = doc.read_file_or_text(
        "path.table",
        crate::detection_csv::read_path_csv,
        crate::detection_csv::parse_path_csv,
    )?;
    Ok(table.map(PathSpec::Table))
}

/// The extinction coefficient (m⁻¹) of a homogeneous path: `extinction_per_m`, or
/// `visibility_km` by Koschmieder's relation β = 3.912/V.
fn extinction(doc: &TomlDoc<'_>) -> Result<f64> {
    match (
        doc.number("path.extinction_per_m"),
        doc.number("path.visibility_km"),
    ) {
        (Some(b), _) if b.is_finite() && b >= 0.0 => Ok(b),
        (Some(b), _) => Err(doc.error(
            "path.extinction_per_m",
            format!("{}: must be finite and >= 0 (m⁻¹)", show(b)),
        )),
        (None, Some(v)) if v.is_finite() && v > 0.0 => Ok(KOSCHMIEDER / (v * 1e3)),
        (None, Some(v)) => Err(doc.error(
            "path.visibility_km",
            format!("{}: must be finite and > 0 (km)", show(v)),
        )),
        (None, None) => Err(doc.error(
            "path",
            "missing the extinction: give `extinction_per_m`, `visibility_km` or `table`",
        )),
    }
}

/// The horizon radiance of a homogeneous path: `horizon_radiance`, or `air_temperature_k` (the
/// horizon then radiates B(T_air)).
fn horizon(doc: &TomlDoc<'_>) -> Result<Horizon> {
    match (
        doc.number("path.horizon_radiance"),
        doc.number("path.air_temperature_k"),
    ) {
        (Some(l), _) if l.is_finite() && (0.0..=polbrdf::error::MAX_RADIOMETRIC).contains(&l) => {
            Ok(Horizon::Radiance(l))
        }
        (Some(l), _) => Err(doc.error(
            "path.horizon_radiance",
            format!("{}: must be finite and >= 0 (W·m⁻²·sr⁻¹·µm⁻¹)", show(l)),
        )),
        (None, Some(t)) => Ok(Horizon::AirTemperature(
            temperature("path.air_temperature_k", t).map_err(|e| doc.core_error(e))?,
        )),
        (None, None) => Err(doc.error(
            "path",
            "missing the horizon radiance: give `horizon_radiance` (visible) or \
             `air_temperature_k` (thermal infrared)",
        )),
    }
}
