//! Scene setup: a scene file read by polbrdf-io's one reader (whose defaults are the core's, see
//! [`defaults`]), the
//! observer of a material in it, and the setup's warnings as values (valid but easy to get
//! wrong; the adapters show them).

use crate::error::{TaskError, TaskResult};
use crate::spectrum::NamedMaterial;
use polbrdf::analysis::scene::Observer;
use polbrdf::Spectrum;
use polbrdf_io::Scene;
use std::path::Path;

/// The scene defaults, re-exported from their one definition (the core) for the adapters.
pub mod defaults {
    pub use polbrdf::analysis::scene::Sun;
    pub use polbrdf::analysis::{Atmosphere, SkyModel};
    /// `dop_max` of the `cie-clear` sky when not given.
    pub const DOP_MAX: f64 = SkyModel::DEFAULT_DOP_MAX;
}

/// A setup that is valid but probably not what was meant.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Warning {
    /// The sentence, naming the file and the table it is about.
    pub message: String,
}

impl std::fmt::Display for Warning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

/// Reads and validates a scene file (files it names are found relative to it).
///
/// # Errors
/// [`TaskError::Io`] naming the file, the line and the key.
pub fn read_scene(path: &Path) -> TaskResult<Scene> {
    Ok(polbrdf_io::read_scene(path)?)
}

/// The longest wavelength a spectrum reaches, µm.
fn longest_wavelength(spectrum: &Spectrum) -> f64 {
    match spectrum {
        Spectrum::Wavelength(l) => *l,
        Spectrum::Band(b, _) => b.range().1,
    }
}

/// The warnings of a scene used for a contrast (`[target]` against `[background]`): a surface
/// without a temperature where emission matters (from 3 µm on: at 300 K, B_λ at 3 µm is already
/// 1e-3 of its peak; in the visible it is below 1e-20), and a `[surface]` table, which
/// contrast does not use.
pub fn contrast_warnings(scene: &Scene) -> Vec<Warning> {
    let path = scene.path.display();
    let mut warnings = Vec::new();
    for (table, t) in [
        ("target", scene.target.temperature_k),
        ("background", scene.background.temperature_k),
    ] {
        if t.is_none() && longest_wavelength(&scene.spectrum) >= 3.0 {
            warnings.push(Warning {
                message: format!(
                    "{path}: [{table}] has no temperature_k, so the {table} emits nothing (it \
                     only reflects the sky)"
                ),
            });
        }
    }
    if scene.thermal.surface_temperature_k.is_some() {
        warnings.push(Warning {
            message: format!(
                "{path}: [surface] is for `polbrdf radiance`; contrast uses the temperatures of \
                 [target] and [background]"
            ),
        });
    }
    warnings
}

/// A scene given to the radiance of one surface must describe that surface (`[surface]`):
/// a `[target]` or `[background]` table (for a contrast) would otherwise be dropped silently.
///
/// # Errors
/// [`TaskError::Io`] (a data error) naming the scene file and the table.
pub fn check_single_surface(scene: &Scene) -> TaskResult<()> {
    for (table, object) in [("target", &scene.target), ("background", &scene.background)] {
        if object.material.is_some() || object.temperature_k.is_some() {
            return Err(TaskError::Io(polbrdf_io::Error::File {
                path: scene.path.clone(),
                message: format!(
                    "[{table}]: this scene compares a target and a background (`polbrdf contrast \
                     --scene`); the radiance of one surface takes its material from the request \
                     and its temperature from [surface] (temperature_k): move the temperature \
                     there and remove [target] and [background]"
                ),
            }));
        }
    }
    Ok(())
}

/// The observer of `material` in `scene` at the surface temperature `temperature_k` (replacing
/// the scene's `[surface]`). `what` names the material in messages (a request field and its
/// value, or the scene table it came from).
///
/// # Errors
/// [`TaskError::Invalid`] naming `field`: the material does not cover the spectrum (over a
/// band, the message names the band), or the model refuses it.
pub fn observer(
    material: &NamedMaterial,
    scene: &Scene,
    temperature_k: Option<f64>,
    (field, what): (&str, &str),
) -> TaskResult<Observer> {
    let thermal = scene.thermal.with_surface_temperature(temperature_k);
    Observer::new(&material.spec, &thermal, &scene.spectrum)
        .map_err(|e| observer_error(field, what, &e, &scene.spectrum))
}

/// An error of [`Observer::new`]. Over a band, a wavelength outside the material's data is one
/// of the quadrature's nodes: the message names the band.
fn observer_error(field: &str, what: &str, e: &polbrdf::Error, spectrum: &Spectrum) -> TaskError {
    if let (
        Spectrum::Band(band, _),
        polbrdf::Error::WavelengthOutOfRange {
            material, range, ..
        },
    ) = (spectrum, e)
    {
        let (lo, hi) = band.range();
        return TaskError::invalid(
            field,
            format!(
                "{what}: the band {} ({lo}–{hi} µm) reaches outside the data of `{material}` \
                 ({} – {} µm)",
                band.name(),
                range.0,
                range.1
            ),
        );
    }
    TaskError::invalid(field, format!("{what}: {e}"))
}

/// The units of a scene's Stokes radiances.
pub fn radiance_units(spectrum: &Spectrum) -> &'static str {
    match spectrum {
        Spectrum::Wavelength(_) => "W·m⁻²·sr⁻¹·µm⁻¹ (spectral radiance)",
        Spectrum::Band(..) => "W·m⁻²·sr⁻¹ (band-integrated radiance)",
    }
}
