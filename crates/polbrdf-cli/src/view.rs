//! The illumination and viewing-grid options shared by `map` and `contrast`, parsed into the
//! task layer's [`LightRequest`] and grid steps.

use crate::error::CliError;
use crate::spectrum::SpectralArgs;
use crate::values::{self, GridDeg, Quad};
use polbrdf_tasks::hemisphere::{LightRequest, DEFAULT_GRID_DEG};

/// Illumination and viewing grid, shared by `map` and `contrast`.
#[derive(clap::Args, Debug)]
pub struct ViewArgs {
    /// Zenith angle of the source (sun), degrees, in [0, 90) (required, except for `contrast
    /// --scene`).
    #[arg(long, value_name = "DEG", allow_negative_numbers = true,
          value_parser = values::zenith())]
    pub sun_zenith_deg: Option<f64>,
    /// Azimuth of the source, degrees (the specular direction is at azimuth + 180°).
    #[arg(
        long,
        value_name = "DEG",
        default_value_t = 0.0,
        allow_negative_numbers = true,
        value_parser = values::azimuth()
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
    #[arg(long, value_name = "S0,S1,S2,S3", allow_hyphen_values = true,
          value_parser = values::stokes())]
    pub stokes: Option<Quad>,
    #[command(flatten)]
    pub spectral: SpectralArgs,
}

impl ViewArgs {
    /// The source as a request (the numbers parsed; validated by the task).
    pub fn light(&self) -> Result<LightRequest, CliError> {
        Ok(LightRequest {
            sun_zenith_deg: self.sun_zenith_deg,
            sun_azimuth_deg: self.sun_azimuth_deg,
            stokes: self.stokes.map(|s| s.0),
        })
    }

    /// `--grid-deg`: the steps in degrees (validated by the task).
    pub fn grid_deg(&self) -> (f64, f64) {
        self.grid_deg.0
    }
}
