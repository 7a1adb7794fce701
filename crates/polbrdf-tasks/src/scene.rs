//! Scene setup: a scene file read by polbrdf-io's one reader (whose defaults are the core's, see
//! [`defaults`]), the
//! observer of a material in it, and the setup's warnings as values (valid but easy to get
//! wrong; the adapters show them).

use crate::error::{TaskError, TaskResult};
use crate::spectrum::NamedMaterial;
use polbrdf::analysis::contrast::Illumination;
use polbrdf::analysis::scene::{Observer, Sun};
use polbrdf::analysis::sky::{ClearSky, TableSky, ZenithProfile};
use polbrdf::analysis::{Atmosphere, SkyModel, ThermalScene};
use polbrdf::{Spectrum, Stokes};
use polbrdf_io::Scene;
use std::path::Path;

/// The scene defaults, re-exported from their one definition (the core) for the adapters.
pub mod defaults {
    pub use polbrdf::analysis::scene::Sun;
    pub use polbrdf::analysis::sky::ClearSky;
    pub use polbrdf::analysis::{Atmosphere, SkyModel};
    /// `dop_max` of the `cie-clear` sky when not given.
    pub const DOP_MAX: f64 = ClearSky::DEFAULT_DOP_MAX;
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

/// Parses a scene file's text (named `file_name` in messages) whose named files (band, sky
/// profile or table, materials) are given as `(name, text)` pairs rather than read from files:
/// for an adapter without a file system (the web explorer). The reader is the command line's
/// ([`polbrdf_io::parse_scene_with_files`]): the same checks and messages.
///
/// # Errors
/// [`TaskError::Io`] naming the file, the line and the key (a named file not given is one).
pub fn parse_scene_with_files(
    text: &str,
    file_name: &str,
    files: &[(String, String)],
) -> TaskResult<Scene> {
    let files = files
        .iter()
        .map(|(name, text)| (std::path::PathBuf::from(name), text.clone()))
        .collect();
    Ok(polbrdf_io::parse_scene_with_files(
        text,
        Path::new(file_name),
        &files,
    )?)
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
    contrast_warnings_over(scene, &scene.spectrum)
}

/// [`contrast_warnings`] for a scene observed over `spectrum` rather than its own (a detection
/// observes over the sensor's band): whether emission matters is judged over `spectrum`.
pub fn contrast_warnings_over(scene: &Scene, spectrum: &Spectrum) -> Vec<Warning> {
    let path = scene.path.display();
    let mut warnings = Vec::new();
    for (table, t) in [
        ("target", scene.target.temperature_k),
        ("background", scene.background.temperature_k),
    ] {
        if t.is_none() && longest_wavelength(spectrum) >= 3.0 {
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

/// The unit warnings of a material (`polbrdf_io::material_warnings`: an angle small enough to
/// be radians written in degrees), as setup warnings naming what the request or the scene gave.
pub fn material_warnings(material: &NamedMaterial) -> Vec<Warning> {
    polbrdf_io::material_warnings(&material.spec, &material.source)
        .into_iter()
        .map(|w| Warning {
            message: w.to_string(),
        })
        .collect()
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

/// A sky in the scene file's vocabulary (`[sky] model = …` with its keys), for adapters that
/// build a scene from options rather than from a file.
#[derive(Debug, Clone, PartialEq)]
pub enum SkyRequest {
    /// `model = "none"`.
    None,
    /// `model = "uniform"`: `radiance`, W·m⁻²·sr⁻¹·µm⁻¹.
    Uniform {
        /// Spectral radiance.
        radiance: f64,
    },
    /// `model = "thermal"`: brightness `temperature_k`.
    Thermal {
        /// K.
        temperature_k: f64,
    },
    /// `model = "profile"`: unpolarized radiance against zenith angle (0° … 90°).
    Profile {
        /// Zenith angles, degrees.
        zenith_deg: Vec<f64>,
        /// Spectral radiances.
        radiance: Vec<f64>,
    },
    /// `model = "cie-clear"`: horizontal `irradiance` and `dop_max` (default
    /// [`ClearSky::DEFAULT_DOP_MAX`]); needs a sun.
    ClearSky {
        /// W·m⁻²·µm⁻¹.
        irradiance: f64,
        /// In [0, 1]; `None`: the default.
        dop_max: Option<f64>,
    },
    /// `model = "table"`: Stokes radiances on a full grid, `stokes[i·nφ + j]` at
    /// `(theta_deg[i], phi_deg[j])`.
    Table {
        /// Zenith angles, degrees.
        theta_deg: Vec<f64>,
        /// Azimuths, degrees.
        phi_deg: Vec<f64>,
        /// Stokes vectors, zenith-major.
        stokes: Vec<[f64; 4]>,
    },
}

/// The sun of a scene in the file's vocabulary (`[sun]`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SunRequest {
    /// Zenith angle, degrees, in [0, 90).
    pub zenith_deg: f64,
    /// Azimuth, degrees; `None`: [`Sun::DEFAULT_AZIMUTH`].
    pub azimuth_deg: Option<f64>,
    /// Irradiance normal to the beam, W·m⁻²·µm⁻¹.
    pub irradiance: f64,
    /// Stokes vector (normalized to s0 = 1 as `--stokes`); `None`: unpolarized.
    pub stokes: Option<[f64; 4]>,
}

/// A scene from options: the keys of a scene file's `[surface]`, `[sky]`, `[sun]` and
/// `[atmosphere]`, each absent key taking the same default as in a file.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneRequest {
    /// `[surface] temperature_k`.
    pub surface_temperature_k: Option<f64>,
    /// `[sky]`.
    pub sky: SkyRequest,
    /// `[sun]`.
    pub sun: Option<SunRequest>,
    /// `[atmosphere] transmittance`; `None`: [`Atmosphere::default`].
    pub transmittance: Option<f64>,
    /// `[atmosphere] path_radiance`; `None`: [`Atmosphere::default`].
    pub path_radiance: Option<f64>,
}

impl SceneRequest {
    /// The validated scene.
    ///
    /// # Errors
    /// [`TaskError::Model`] naming the scene key (`sky.dop_max`, `sun.zenith_deg`, …) of a
    /// value out of range, a malformed profile or table, a clear sky without a sun.
    pub fn thermal(&self) -> TaskResult<ThermalScene> {
        let sun = match &self.sun {
            None => None,
            Some(s) => {
                let azimuth_deg = s.azimuth_deg.unwrap_or(Sun::DEFAULT_AZIMUTH.to_degrees());
                let stokes = match s.stokes {
                    None => Stokes::unpolarized(),
                    // The same normalization and checks as a collimated source's.
                    Some(v) => {
                        Illumination::from_degrees(s.zenith_deg, azimuth_deg, Stokes(v))?.stokes()
                    }
                };
                Some(Sun {
                    zenith: s.zenith_deg.to_radians() + 0.0,
                    azimuth: azimuth_deg.to_radians(),
                    irradiance: s.irradiance,
                    stokes,
                })
            }
        };
        let sky = match &self.sky {
            SkyRequest::None => SkyModel::None,
            SkyRequest::Uniform { radiance } => SkyModel::Uniform {
                radiance: *radiance,
            },
            SkyRequest::Thermal { temperature_k } => SkyModel::Thermal {
                temperature_k: *temperature_k,
            },
            SkyRequest::Profile {
                zenith_deg,
                radiance,
            } => SkyModel::Profile(ZenithProfile::new(zenith_deg.clone(), radiance.clone())?),
            SkyRequest::ClearSky {
                irradiance,
                dop_max,
            } => SkyModel::ClearSky {
                irradiance: *irradiance,
                dop_max: dop_max.unwrap_or(ClearSky::DEFAULT_DOP_MAX),
            },
            SkyRequest::Table {
                theta_deg,
                phi_deg,
                stokes,
            } => SkyModel::Table(TableSky::new(
                theta_deg.clone(),
                phi_deg.clone(),
                stokes.iter().map(|s| Stokes(*s)).collect(),
            )?),
        };
        let d = Atmosphere::default();
        let scene = ThermalScene {
            surface_temperature_k: self.surface_temperature_k,
            sky,
            atmosphere: Atmosphere {
                transmittance: self.transmittance.unwrap_or(d.transmittance),
                path_radiance: self.path_radiance.unwrap_or(d.path_radiance),
            },
            sun,
        };
        scene.validate()?;
        Ok(scene)
    }
}
