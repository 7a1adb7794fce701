//! The illumination and viewing-grid options shared by `map` and `contrast`, parsed into the
//! task layer's [`LightRequest`] and grid steps.

use crate::error::CliError;
use crate::spectrum::SpectralArgs;
use polbrdf_tasks::hemisphere::{LightRequest, DEFAULT_GRID_DEG};

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
        default_value_t = GridDeg(DEFAULT_GRID_DEG),
        allow_hyphen_values = true
    )]
    pub grid_deg: GridDeg,
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

    /// `--grid-deg`: the steps in degrees (validated by the task).
    pub fn grid_deg(&self) -> (f64, f64) {
        self.grid_deg.0
    }
}

/// `--grid-deg`: `DTHETA[,DPHI]` in degrees. Its default is the task layer's
/// ([`DEFAULT_GRID_DEG`]), shown in the help through [`std::fmt::Display`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GridDeg(pub (f64, f64));

impl std::fmt::Display for GridDeg {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{},{}", self.0 .0, self.0 .1)
    }
}

impl std::str::FromStr for GridDeg {
    type Err = String;

    /// One step for both angles or two; a malformed value is clap's usage error (exit 2).
    fn from_str(text: &str) -> Result<Self, String> {
        let what = "DTHETA or DTHETA,DPHI in degrees";
        let v = numbers(text, "--grid-deg", what).map_err(|e| e.to_string())?;
        match v[..] {
            [a] => Ok(GridDeg((a, a))),
            [a, b] => Ok(GridDeg((a, b))),
            _ => Err(format!("--grid-deg {text:?}: expected {what}")),
        }
    }
}

/// Comma-separated numbers of `option` (`what` they are, for the message).
pub(crate) fn numbers(text: &str, option: &str, what: &str) -> Result<Vec<f64>, CliError> {
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
