//! The sun's position from a date, a time and a place (docs/sun-position.md): NREL SPA through
//! the core ([`polbrdf::analysis::sun_position`]), with the date-time read by polbrdf-io's one
//! parser — for `polbrdf sun` and `polbrdf.sun_position`, which print or return
//! [`SunReport::to_json`].

use crate::error::{TaskError, TaskResult};
use polbrdf::analysis::sun_position::{CivilTime, Site, SunPosition, SunTime};
use serde_json::{json, Value};

/// Where and when.
#[derive(Debug, Clone, PartialEq)]
pub struct SunRequest {
    /// RFC 3339 with the UTC offset (`2026-06-21T12:00:00Z`, `2003-10-17T12:30:30-07:00`).
    pub date_time: String,
    /// Degrees, north positive.
    pub latitude_deg: f64,
    /// Degrees, east positive.
    pub longitude_deg: f64,
    /// Metres above sea level (default 0).
    pub elevation_m: Option<f64>,
    /// Air pressure for refraction, hPa (default 1013.25; 0: no refraction).
    pub pressure_hpa: Option<f64>,
    /// Air temperature for refraction, °C (default 15).
    pub temperature_c: Option<f64>,
    /// ΔT = TT − UT1, s (default: estimated from the date).
    pub delta_t_s: Option<f64>,
    /// Compass azimuth of the surface frame's φ = 0 axis, degrees (default 0: north).
    pub phi0_azimuth_deg: Option<f64>,
}

/// The sun at that time and place.
#[derive(Debug, Clone, PartialEq)]
pub struct SunReport {
    /// The date, time, place and frame, resolved (defaults filled in).
    pub sun_time: SunTime,
    /// Where the sun is.
    pub position: SunPosition,
}

/// A core error about a `[sun]` key as the request's field: `sun.latitude_deg` is
/// `latitude_deg`.
pub(crate) fn field_error(e: polbrdf::Error) -> TaskError {
    match e {
        polbrdf::Error::InvalidParameter {
            name,
            value,
            reason,
        } => TaskError::invalid(
            name.strip_prefix("sun.").unwrap_or(name),
            format!("{value}: {reason}"),
        ),
        other => TaskError::Model(other),
    }
}

/// The place and frame of a request, checked.
fn sun_time(request: &SunRequest, time: CivilTime) -> TaskResult<SunTime> {
    let d = Site::at(request.latitude_deg, request.longitude_deg);
    let site = Site {
        elevation_m: request.elevation_m.unwrap_or(d.elevation_m),
        pressure_hpa: request.pressure_hpa.unwrap_or(d.pressure_hpa),
        temperature_c: request.temperature_c.unwrap_or(d.temperature_c),
        ..d
    };
    site.validate().map_err(field_error)?;
    let phi0 = request
        .phi0_azimuth_deg
        .unwrap_or(SunTime::DEFAULT_PHI0_AZIMUTH_DEG);
    if !(phi0.is_finite() && phi0.abs() <= polbrdf::MAX_AZIMUTH_DEG) {
        return Err(TaskError::invalid(
            "phi0_azimuth_deg",
            format!("{phi0}: must be finite and at most 1e8 degrees in magnitude"),
        ));
    }
    Ok(SunTime {
        time,
        site,
        delta_t_s: request.delta_t_s,
        phi0_azimuth_deg: phi0.rem_euclid(360.0) % 360.0,
    })
}

/// The sun's position at the request's time and place.
///
/// # Errors
/// [`TaskError::Invalid`] naming the request field (`date_time`, `latitude_deg`, …).
pub fn sun(request: &SunRequest) -> TaskResult<SunReport> {
    let time = polbrdf_io::date_time::parse_date_time(&request.date_time)
        .map_err(|m| TaskError::invalid("date_time", m))?;
    let sun_time = sun_time(request, time)?;
    let position = sun_time.position().map_err(field_error)?;
    Ok(SunReport { sun_time, position })
}

impl SunReport {
    /// The report as JSON: the inputs resolved, then the position (`azimuth_deg` from north
    /// toward east; `phi_deg` the sun's azimuth in the surface frame).
    pub fn to_json(&self) -> Value {
        let t = &self.sun_time;
        let p = &self.position;
        json!({
            "algorithm": "NREL SPA (Reda & Andreas 2008), ±0.0003°",
            "date_time": polbrdf_io::date_time::format_date_time(&t.time),
            "julian_day": p.julian_day,
            "delta_t_s": p.delta_t_s,
            "latitude_deg": t.site.latitude_deg,
            "longitude_deg": t.site.longitude_deg,
            "elevation_m": t.site.elevation_m,
            "pressure_hpa": t.site.pressure_hpa,
            "temperature_c": t.site.temperature_c,
            "zenith_deg": p.zenith_deg,
            "elevation_deg": p.elevation_deg(),
            "azimuth_deg": p.azimuth_deg,
            "phi0_azimuth_deg": t.phi0_azimuth_deg,
            "phi_deg": p.phi_deg(t.phi0_azimuth_deg),
            "above_horizon": p.is_up(),
        })
    }
}
