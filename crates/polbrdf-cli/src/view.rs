//! The illumination and viewing-grid options shared by `map` and `contrast`, parsed into the
//! task layer's [`LightRequest`] and grid steps.

use crate::error::CliError;
use crate::spectrum::SpectralArgs;
use polbrdf_tasks::hemisphere::LightRequest;

/// Illumination and viewing grid, shared by `map` and `contrast`.
#[derive(clap::Args, Debug)]
pub struct ViewArgs {
    /// Zenith angle of the source (sun), degrees, in [0, 90) (required, except for `contrast
    /// --scene`).
    #[arg(long, value_name = "DEG", allow_negative_numbers = true)]
    pub sun_zenith_deg: Option<f64>,
    /// Azimuth of the source, degrees (the specular direction is at azimuth + 180°).
    #[arg(
        long,
        value_name = "DEG",
        default_value_t = 0.0,
        allow_negative_numbers = true
    )]
    pub sun_azimuth_deg: f64,
    /// Viewing grid steps in degrees: `DTHETA,DPHI`, or one value for both. Zenith angles run
    /// from 0 in steps of DTHETA below 90°; the azimuth step is rounded to divide 360°.
    #[arg(
        long,
        value_name = "DTHETA[,DPHI]",
        default_value = "1,2",
        allow_hyphen_values = true
    )]
    pub grid_deg: String,
    /// Input Stokes vector `S0,S1,S2,S3` (psps basis of the incident beam; normalized to
    /// S0 = 1). Default: unpolarized, 1,0,0,0.
    #[arg(long, value_name = "S0,S1,S2,S3", allow_hyphen_values = true)]
    pub stokes: Option<String>,
    #[command(flatten)]
    pub spectral: SpectralArgs,
}

impl ViewArgs {
    /// The source as a request (the numbers parsed; validated by the task).
    pub fn light(&self) -> Result<LightRequest, CliError> {
        Ok(LightRequest {
            sun_zenith_deg: self.sun_zenith_deg,
            sun_azimuth_deg: self.sun_azimuth_deg,
            stokes: self.stokes.as_deref().map(parse_stokes).transpose()?,
        })
    }

    /// `--grid-deg`: one or two steps in degrees.
    pub fn grid_deg(&self) -> Result<(f64, f64), CliError> {
        let text = &self.grid_deg;
        match numbers(text, "--grid-deg", "DTHETA or DTHETA,DPHI in degrees")?[..] {
            [a] => Ok((a, a)),
            [a, b] => Ok((a, b)),
            _ => Err(CliError::Invalid(format!(
                "--grid-deg {text:?}: expected DTHETA or DTHETA,DPHI in degrees"
            ))),
        }
    }
}

fn numbers(text: &str, option: &str, what: &str) -> Result<Vec<f64>, CliError> {
    text.split(',')
        .map(|t| {
            t.trim().parse::<f64>().map_err(|_| {
                CliError::Invalid(format!(
                    "{option} {text:?}: {t:?} is not a number (expected {what})"
                ))
            })
        })
        .collect()
}

/// `--stokes`: four numbers.
fn parse_stokes(text: &str) -> Result<[f64; 4], CliError> {
    match numbers(text, "--stokes", "S0,S1,S2,S3")?[..] {
        [s0, s1, s2, s3] => Ok([s0, s1, s2, s3]),
        _ => Err(CliError::Invalid(format!(
            "--stokes {text:?}: expected four numbers S0,S1,S2,S3"
        ))),
    }
}
