//! The spectral options shared by `contrast`, `map`, `albedo`, `check` and `emission`: one
//! wavelength (`--wavelength-um`) or a band (`--band FILE.csv`), as the task layer's
//! [`SpectralRequest`].

use crate::error::CliError;
use polbrdf::MaterialSpec;
use polbrdf_tasks::spectrum::{NamedMaterial, SpectralRequest};
use std::path::PathBuf;

/// At what wavelength(s) a command evaluates its materials.
#[derive(clap::Args, Debug, Clone, Default)]
pub struct SpectralArgs {
    /// Wavelength (µm) at which to evaluate materials with a spectral index (`index = …`);
    /// constant-index materials do not depend on it.
    #[arg(long, value_name = "UM", conflicts_with = "band", value_parser = crate::values::positive())]
    pub wavelength_um: Option<f64>,
    /// A band: a CSV file with columns wavelength_um,response (relative spectral response,
    /// linear between rows, zero outside). Results integrate Stokes vectors over it
    /// (docs/model.md §15): the response-weighted mean per unit irradiance.
    #[arg(long, value_name = "FILE.csv")]
    pub band: Option<PathBuf>,
    /// Largest quadrature step over the band, µm (default: 1/16 of its width; the nodes of
    /// tabulated indices are panel edges as well).
    #[arg(long, value_name = "UM", requires = "band", value_parser = crate::values::positive())]
    pub band_step_um: Option<f64>,
}

impl SpectralArgs {
    /// The request (validated by the task).
    pub fn request(&self) -> SpectralRequest {
        SpectralRequest {
            wavelength_um: self.wavelength_um,
            band: self.band.clone(),
            band_step_um: self.band_step_um,
        }
    }
}

/// A material file or preset given to an option, as a spec, with a display name (its `name`
/// key, else the preset name or file stem). Content errors name the option.
pub fn load_spec(arg: &str, option: &str) -> Result<(MaterialSpec, String), CliError> {
    let m = NamedMaterial::load(arg, option.trim_start_matches("--"))?;
    Ok((m.spec, m.name))
}
