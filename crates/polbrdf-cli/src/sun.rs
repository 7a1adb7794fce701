//! `polbrdf sun`: the sun's position at a date, time and place by NREL SPA
//! (docs/sun-position.md), as the JSON document of `polbrdf_tasks::sun` — the numbers
//! `polbrdf.sun_position` returns, on standard output.

use crate::error::CliError;
use crate::output::write_output;
use crate::values::{self, Range};
use polbrdf_tasks::sun::{sun, SunRequest};

/// `polbrdf sun`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The date and time with its UTC offset (RFC 3339): 2026-06-21T12:00:00Z (UTC) or
    /// 2026-06-21T14:00:00+02:00 (local time at UTC+2).
    #[arg(long, value_name = "DATE_TIME", value_parser = values::date_time())]
    pub date_time: String,
    /// Latitude, degrees, north positive.
    #[arg(long, value_name = "DEG", allow_hyphen_values = true,
          value_parser = values::number(Range::closed(-90.0, 90.0)))]
    pub latitude_deg: f64,
    /// Longitude, degrees, east positive.
    #[arg(long, value_name = "DEG", allow_hyphen_values = true,
          value_parser = values::number(Range::closed(-180.0, 180.0)))]
    pub longitude_deg: f64,
    /// Height above sea level, m. Default 0.
    #[arg(long, value_name = "M", allow_hyphen_values = true,
          value_parser = values::number(Range::closed(-1000.0, 100_000.0)))]
    pub elevation_m: Option<f64>,
    /// Air pressure for refraction, hPa. Default 1013.25; 0: no refraction.
    #[arg(long, value_name = "HPA", allow_hyphen_values = true,
          value_parser = values::number(Range::closed(0.0, 2000.0)))]
    pub pressure_hpa: Option<f64>,
    /// Air temperature for refraction, °C. Default 15.
    #[arg(long, value_name = "C", allow_hyphen_values = true,
          value_parser = values::number(Range::closed(-100.0, 100.0)))]
    pub temperature_c: Option<f64>,
    /// ΔT = TT − UT1, s. Default: estimated from the date.
    #[arg(long, value_name = "S", allow_hyphen_values = true,
          value_parser = values::number(Range::closed(
              -polbrdf::analysis::sun_position::MAX_DELTA_T_S,
              polbrdf::analysis::sun_position::MAX_DELTA_T_S)))]
    pub delta_t_s: Option<f64>,
    /// Compass azimuth (from north toward east) of the surface frame's φ = 0 axis, degrees;
    /// gives the sun's φ in that frame. Default 0 (north).
    #[arg(long, value_name = "DEG", allow_hyphen_values = true, value_parser = values::azimuth())]
    pub phi0_azimuth_deg: Option<f64>,
}

/// Runs `polbrdf sun`.
pub fn run(args: &Args) -> Result<(), CliError> {
    let report = sun(&SunRequest {
        date_time: args.date_time.clone(),
        latitude_deg: args.latitude_deg,
        longitude_deg: args.longitude_deg,
        elevation_m: args.elevation_m,
        pressure_hpa: args.pressure_hpa,
        temperature_c: args.temperature_c,
        delta_t_s: args.delta_t_s,
        phi0_azimuth_deg: args.phi0_azimuth_deg,
    })
    // Every field of the request is an option (no file): a refusal is a usage error.
    .map_err(CliError::usage)?;
    let mut text = serde_json::to_string_pretty(&report.to_json()).expect("JSON of numbers");
    text.push('\n');
    write_output(None, text.as_bytes())
}
