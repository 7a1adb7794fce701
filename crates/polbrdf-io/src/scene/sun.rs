//! `[sun]` of a scene file: the sun placed by its angles or by date, time and place (NREL SPA),
//! with its irradiance and Stokes vector.

use crate::csv_io::show;
use crate::error::{Error, Result};
use crate::toml_doc::{split, TomlDoc};
use polbrdf::analysis::scene::Sun;
use polbrdf::analysis::sun_position::{Site, SunTime};
use polbrdf::Stokes;
use std::f64::consts::FRAC_PI_2;
use toml::Value;

/// An [`polbrdf::Error::InvalidParameter`] of `name` (a key), at its line.
fn invalid(doc: &TomlDoc<'_>, name: &'static str, value: f64, reason: &'static str) -> Error {
    doc.core_error(polbrdf::Error::InvalidParameter {
        name,
        value,
        reason,
    })
}

/// `[sun]`: `zenith_deg` and `irradiance` required, `azimuth_deg` 0 and `stokes` unpolarized by
/// default; the angles in radians (the azimuth first taken modulo 360°, exactly), the Stokes
/// vector normalized to `s0 = 1`. `None` without a `[sun]`. The values are checked here, in the
/// units of the file (the core checks them again, in radians).
pub(super) fn sun(doc: &TomlDoc<'_>) -> Result<Option<Sun>> {
    if !doc.has("sun") {
        return Ok(None);
    }
    if let Some(time) = sun_time(doc)? {
        return sun_from_time(doc, &time).map(Some);
    }
    let zenith_deg = doc.required_number("sun.zenith_deg").map_err(|e| {
        e.with_more("; or place the sun by `date_time`, `latitude_deg` and `longitude_deg`")
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
pub(super) fn sun_time(doc: &TomlDoc<'_>) -> Result<Option<SunTime>> {
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
