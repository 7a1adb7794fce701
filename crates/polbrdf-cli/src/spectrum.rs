//! The spectral options shared by `contrast`, `map`, `albedo` and `check`: one wavelength
//! (`--wavelength-um`) or a band (`--band FILE.csv`), and the materials at their spectral nodes.

use crate::error::CliError;
use polbrdf::{Material, MaterialSpec, Spectrum};
use std::path::{Path, PathBuf};

/// At what wavelength(s) a command evaluates its materials.
#[derive(clap::Args, Debug, Clone, Default)]
pub struct SpectralArgs {
    /// Wavelength (µm) at which to evaluate materials with a spectral index (`index = …`);
    /// constant-index materials do not depend on it.
    #[arg(long, value_name = "UM", conflicts_with = "band")]
    pub wavelength_um: Option<f64>,
    /// A band: a CSV file with columns wavelength_um,response (relative spectral response,
    /// linear between rows, zero outside). Results integrate Stokes vectors over it
    /// (docs/model.md §15): the response-weighted mean per unit irradiance.
    #[arg(long, value_name = "FILE.csv")]
    pub band: Option<PathBuf>,
    /// Largest quadrature step over the band, µm (default: 1/16 of its width; the nodes of
    /// tabulated indices are panel edges as well).
    #[arg(long, value_name = "UM", requires = "band")]
    pub band_step_um: Option<f64>,
}

impl SpectralArgs {
    /// The validated spectrum; `None` when neither option is given.
    pub fn spectrum(&self) -> Result<Option<Spectrum>, CliError> {
        if let Some(l) = self.wavelength_um {
            if !(l.is_finite() && l > 0.0) {
                return Err(CliError::Invalid(format!(
                    "--wavelength-um = {l}: must be finite and > 0 (µm)"
                )));
            }
            return Ok(Some(Spectrum::Wavelength(l)));
        }
        let Some(path) = &self.band else {
            return Ok(None);
        };
        if let Some(s) = self.band_step_um {
            if !(s.is_finite() && s > 0.0) {
                return Err(CliError::Invalid(format!(
                    "--band-step-um = {s}: must be finite and > 0 (µm)"
                )));
            }
        }
        let band = polbrdf_io::read_band_csv(path)?;
        if let Some(s) = self.band_step_um {
            band.check_step(s)
                .map_err(|e| CliError::Invalid(format!("--band-step-um: {e}")))?;
        }
        Ok(Some(Spectrum::Band(band, self.band_step_um)))
    }
}

/// The spectrum in words, for terminal output.
pub fn describe(spectrum: &Option<Spectrum>) -> String {
    match spectrum {
        None => String::new(),
        Some(Spectrum::Wavelength(l)) => format!(" at λ = {l} µm"),
        Some(Spectrum::Band(b, _)) => {
            let (lo, hi) = b.range();
            format!(" over the band {} ({lo}–{hi} µm)", b.name())
        }
    }
}

/// The spectrum as JSON (for `best.json`).
pub fn to_json(spectrum: &Option<Spectrum>, nodes: usize) -> serde_json::Value {
    match spectrum {
        None => serde_json::Value::Null,
        Some(Spectrum::Wavelength(l)) => serde_json::json!({"wavelength_um": l}),
        Some(Spectrum::Band(b, step)) => {
            let (lo, hi) = b.range();
            serde_json::json!({"band": b.name(), "range_um": [lo, hi],
                "step_um": step.unwrap_or_else(|| b.default_step()), "nodes": nodes,
                "integrated": "Stokes vectors, response-weighted mean"})
        }
    }
}

/// A material file or preset given to an option, as a spec, with a display name (its `name`
/// key, else the preset name or file stem). Content errors name the option.
pub fn load_spec(arg: &str, option: &str) -> Result<(MaterialSpec, String), CliError> {
    let spec = polbrdf_io::load_material(arg).map_err(|e| {
        if e.is_data_error() {
            CliError::Invalid(format!("{option}: {e}"))
        } else {
            CliError::Io(e)
        }
    })?;
    let name = spec.name.clone().unwrap_or_else(|| {
        Path::new(arg)
            .file_stem()
            .map_or_else(|| arg.to_string(), |s| s.to_string_lossy().into_owned())
    });
    Ok((spec, name))
}

/// The materials at each spectral node: `(weight, [one material per spec])`, the weights of the
/// spectrum's mean (one node of weight 1 for a wavelength, or with no spectrum for
/// constant-index materials). `specs` pairs each spec with its option and argument, for
/// messages.
pub fn materials_at(
    specs: &[(&MaterialSpec, &str, &str)],
    spectrum: &Option<Spectrum>,
) -> Result<Vec<(f64, Vec<Material>)>, CliError> {
    let what = |option: &str, arg: &str, e: polbrdf::Error| {
        CliError::Invalid(format!("{option} {arg}: {e}"))
    };
    let Some(spectrum) = spectrum else {
        let ms = specs
            .iter()
            .map(|(s, option, arg)| {
                if s.is_spectral() {
                    let (lo, hi) = s.wavelength_range().unwrap_or((f64::NAN, f64::NAN));
                    Err(CliError::Invalid(format!(
                        "{option} {arg}: the material has a spectral index ({lo}–{hi} µm): \
                         give --wavelength-um or --band"
                    )))
                } else {
                    s.build().map_err(|e| what(option, arg, e))
                }
            })
            .collect::<Result<Vec<_>, _>>()?;
        return Ok(vec![(1.0, ms)]);
    };
    let plain: Vec<&MaterialSpec> = specs.iter().map(|s| s.0).collect();
    let nodes = spectrum.mean_nodes(&plain);
    let per_spec = specs
        .iter()
        .map(|(s, option, arg)| Spectrum::materials(s, &nodes).map_err(|e| what(option, arg, e)))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(nodes
        .iter()
        .enumerate()
        .map(|(j, (_, w))| (*w, per_spec.iter().map(|ms| ms[j].clone()).collect()))
        .collect())
}
