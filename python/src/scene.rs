//! The observed radiance of a scene (`radiance_flat`): its spectrum, sky and sun.

use crate::buffers::flat_pair;
use crate::buffers::stokes_array;
use crate::errors::{core_err, io_err};
use crate::material::PyMaterial;
use crate::thermal::view_azimuth;
use crate::thermal::view_zenith;
use numpy::{PyArray1, PyArray2, PyReadonlyArray1, PyReadonlyArray2};
use polbrdf::analysis::scene::{check_views, Atmosphere, Observer, SkyModel, Sun, ThermalScene};
use polbrdf::analysis::sky::{ClearSky, TableSky, ZenithProfile};
use polbrdf::{Band, Spectrum};
use polbrdf_io::scene::SkyKind;
use polbrdf_io::{SceneObject, SceneValue};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// Most quadrature pieces a band may be split into (`band_step_um` against the band's width):
/// every spectral node costs an emissivity quadrature, and a vanishing step would not end.
pub(crate) const MAX_BAND_PIECES: f64 = 1e5;

/// The spectrum of [`radiance_flat`]: one wavelength or a band, exactly one.
pub(crate) fn radiance_spectrum(
    wavelength_um: Option<f64>,
    band: Option<(Vec<f64>, Vec<f64>)>,
    band_step_um: Option<f64>,
) -> PyResult<Spectrum> {
    match (wavelength_um, band) {
        (Some(_), Some(_)) => Err(PyValueError::new_err(
            "give either `wavelength_um` (one wavelength, µm) or `band` = (wavelengths_um, \
             response), not both",
        )),
        (None, None) => Err(PyValueError::new_err(
            "give `wavelength_um` (one wavelength, µm) or `band` = (wavelengths_um, response): \
             the radiance is spectral",
        )),
        (Some(_), None) if band_step_um.is_some() => Err(PyValueError::new_err(
            "`band_step_um` is the quadrature step of a band: give `band`, not `wavelength_um`",
        )),
        (Some(l), None) => Ok(Spectrum::Wavelength(l)),
        (None, Some((w, r))) => {
            let band = Band::new("band", w, r).map_err(|e| {
                let msg = e.to_string();
                PyValueError::new_err(if msg.starts_with("band `band`") {
                    msg
                } else {
                    format!("`band`: {msg}")
                })
            })?;
            if let Some(s) = band_step_um {
                let (lo, hi) = band.range();
                if !(s.is_finite() && s > 0.0) {
                    return Err(PyValueError::new_err(
                        polbrdf::Error::InvalidParameter {
                            name: "band_step_um",
                            value: s,
                            reason: "must be finite and > 0 (µm)",
                        }
                        .to_string(),
                    ));
                }
                if (hi - lo) / s > MAX_BAND_PIECES {
                    return Err(PyValueError::new_err(format!(
                        "invalid parameter `band_step_um` = {s:e}: it would split the band \
                         ({lo}–{hi} µm) into more than {MAX_BAND_PIECES} pieces"
                    )));
                }
            }
            Ok(Spectrum::Band(band, band_step_um))
        }
    }
}

/// The sky arguments of [`radiance_flat`], as handed over by the Python layer.
pub(crate) struct SkyArgs<'py> {
    radiance: Option<f64>,
    temperature_k: Option<f64>,
    profile: Table<'py>,
    irradiance: Option<f64>,
    dop_max: Option<f64>,
    table: SkyTable<'py>,
}

/// A sky table as handed over by the Python layer: zenith angles and azimuths (degrees, 1-D)
/// and the Stokes radiances of the nodes, θ-major, shape `(len(theta_deg)·len(phi_deg), 4)`.
pub(crate) type SkyTable<'py> = Option<(
    PyReadonlyArray1<'py, f64>,
    PyReadonlyArray1<'py, f64>,
    PyReadonlyArray2<'py, f64>,
)>;

/// The sky of [`radiance_flat`] from its model name and the arguments that model takes
/// (`has_sun`: whether a sun was given, which the `cie-clear` sky needs).
pub(crate) fn radiance_sky(sky: &str, args: SkyArgs<'_>, has_sun: bool) -> PyResult<SkyModel> {
    let given = [
        ("sky_radiance", args.radiance.is_some()),
        ("sky_temperature_k", args.temperature_k.is_some()),
        ("sky_profile", args.profile.is_some()),
        ("sky_irradiance", args.irradiance.is_some()),
        ("dop_max", args.dop_max.is_some()),
        ("sky_table", args.table.is_some()),
    ];
    // The model by its name in the scene files' list (the one list of sky models).
    let Some(kind) = polbrdf_io::scene::sky_kind(sky) else {
        let known: Vec<String> = polbrdf_io::scene::sky_model_names()
            .map(|m| format!("\"{m}\""))
            .collect();
        return Err(PyValueError::new_err(format!(
            "invalid `sky`: unknown sky model `{sky}` (expected {})",
            known.join(", ")
        )));
    };
    // The arguments the model needs, those it may take, and how to say so.
    let (needs, optional, what): (&[&str], &[&str], &str) = match kind {
        SkyKind::None => (&[], &[], "no sky argument"),
        SkyKind::Uniform => (&["sky_radiance"], &[], "`sky_radiance` (W·m⁻²·sr⁻¹·µm⁻¹)"),
        SkyKind::Thermal => (&["sky_temperature_k"], &[], "`sky_temperature_k` (K)"),
        SkyKind::Profile => (
            &["sky_profile"],
            &[],
            "`sky_profile` = (zenith_deg, radiance)",
        ),
        SkyKind::ClearSky => (
            &["sky_irradiance"],
            &["dop_max"],
            "`sky_irradiance` (W·m⁻²·µm⁻¹), optionally `dop_max`, and a `sun`",
        ),
        SkyKind::Table => (
            &["sky_table"],
            &[],
            "`sky_table` = (theta_deg, phi_deg, stokes)",
        ),
    };
    for (name, is_given) in given {
        if is_given && !needs.contains(&name) && !optional.contains(&name) {
            return Err(PyValueError::new_err(format!(
                "`{name}` does not apply to sky = \"{sky}\", which takes {what}"
            )));
        }
        if !is_given && needs.contains(&name) {
            return Err(PyValueError::new_err(format!(
                "sky = \"{sky}\" needs {what}"
            )));
        }
    }
    if kind == SkyKind::ClearSky && !has_sun {
        return Err(PyValueError::new_err(format!(
            "sky = \"{sky}\" needs a `sun` = (zenith, azimuth, irradiance): the clear sky's \
             radiance and polarization are set by the sun's position",
        )));
    }
    Ok(match kind {
        SkyKind::None => SkyModel::None,
        SkyKind::Uniform => SkyModel::Uniform {
            radiance: args.radiance.expect("checked above"),
        },
        SkyKind::Thermal => SkyModel::Thermal {
            temperature_k: args.temperature_k.expect("checked above"),
        },
        SkyKind::Profile => {
            let (zenith_deg, radiance) = table(args.profile).expect("checked above");
            SkyModel::Profile(
                ZenithProfile::new(zenith_deg, radiance)
                    .map_err(|e| PyValueError::new_err(format!("`sky_profile`: {e}")))?,
            )
        }
        SkyKind::ClearSky => SkyModel::ClearSky {
            irradiance: args.irradiance.expect("checked above"),
            dop_max: args.dop_max.unwrap_or(ClearSky::DEFAULT_DOP_MAX),
        },
        SkyKind::Table => SkyModel::Table(sky_table(args.table.expect("checked above"))?),
    })
}

/// The [`TableSky`] of the `sky_table` argument; its errors prefixed with `sky_table`, the
/// flat node of a bad Stokes parameter also given as its `(theta, phi)` position.
pub(crate) fn sky_table(
    (theta, phi, stokes): (
        PyReadonlyArray1<'_, f64>,
        PyReadonlyArray1<'_, f64>,
        PyReadonlyArray2<'_, f64>,
    ),
) -> PyResult<TableSky> {
    let theta = theta.as_array().to_vec();
    let phi = phi.as_array().to_vec();
    let stokes = stokes.as_array();
    if stokes.ncols() != 4 {
        return Err(PyValueError::new_err(format!(
            "`sky_table`: the Stokes radiances must have 4 columns (s0, s1, s2, s3), got {}",
            stokes.ncols()
        )));
    }
    let nodes: Vec<polbrdf::Stokes> = stokes
        .rows()
        .into_iter()
        .map(|r| polbrdf::Stokes([r[0], r[1], r[2], r[3]]))
        .collect();
    let n_phi = phi.len();
    TableSky::new(theta, phi, nodes).map_err(|e| {
        let node = match &e {
            polbrdf::Error::InvalidParameterAt { name, index, .. }
                if name.starts_with('s') && n_phi > 0 =>
            {
                format!(
                    " (node {index} is stokes[{}, {}])",
                    index / n_phi,
                    index % n_phi
                )
            }
            _ => String::new(),
        };
        PyValueError::new_err(format!("`sky_table`: {e}{node}"))
    })
}

/// The sun of [`radiance_flat`]: `(zenith, azimuth, irradiance, stokes)` with the angles in
/// degrees when `degrees` (else radians) and the Stokes vector normalized to `s0 = 1` here
/// (a degree of polarization up to 1e-9 above 1 scaled to 1, as in a scene file); the rest is
/// checked by the core ([`ThermalScene::validate`]).
pub(crate) fn radiance_sun(
    sun: Option<(f64, f64, f64, [f64; 4])>,
    degrees: bool,
) -> PyResult<Option<Sun>> {
    let Some((zenith, azimuth, irradiance, s)) = sun else {
        return Ok(None);
    };
    let show = |s: &[f64; 4]| format!("({}, {}, {}, {})", s[0], s[1], s[2], s[3]);
    if !(s.iter().all(|v| v.is_finite()) && s[0] > 0.0) {
        return Err(PyValueError::new_err(format!(
            "invalid parameter `sun[3] (stokes)` = {}: must be finite with s0 > 0 (it is \
             normalized to s0 = 1)",
            show(&s)
        )));
    }
    let mut n = s.map(|v| v / s[0]);
    let dop = (n[1] * n[1] + n[2] * n[2] + n[3] * n[3]).sqrt();
    // As a scene file's `[sun] stokes`: up to 1e-9 above 1 is rounding, scaled back to 1.
    if dop.is_nan() || dop > 1.0 + 1e-9 {
        return Err(PyValueError::new_err(format!(
            "invalid parameter `sun[3] (stokes)` = {}: its degree of polarization \
             sqrt(s1² + s2² + s3²)/s0 = {dop} exceeds 1",
            show(&s)
        )));
    }
    if dop > 1.0 {
        for v in &mut n[1..] {
            *v /= dop;
        }
    }
    let rad = |a: f64| if degrees { a.to_radians() } else { a };
    Ok(Some(Sun {
        zenith: rad(zenith) + 0.0,
        azimuth: rad(azimuth),
        irradiance,
        stokes: polbrdf::Stokes(n),
    }))
}

/// The Python argument of a key of the core's [`ThermalScene::validate`].
pub(crate) fn scene_argument(core: &'static str) -> &'static str {
    match core {
        "surface.temperature_k" => "temperature_k",
        "sky.radiance" => "sky_radiance",
        "sky.temperature_k" => "sky_temperature_k",
        "sky.irradiance" => "sky_irradiance",
        "sky.dop_max" => "dop_max",
        "sun.zenith_deg" => "sun[0] (zenith)",
        "sun.azimuth_deg" => "sun[1] (azimuth)",
        "sun.irradiance" => "sun[2] (irradiance)",
        "sun.stokes" => "sun[3] (stokes)",
        "atmosphere.transmittance" => "transmittance",
        "atmosphere.path_radiance" => "path_radiance",
        other => other,
    }
}

/// The arrays of [`radiance_flat`].
pub(crate) type Observed<'py> = (
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
);

/// An optional pair of 1-D arrays (a band, a sky profile) as two vectors.
pub(crate) type Table<'py> = Option<(PyReadonlyArray1<'py, f64>, PyReadonlyArray1<'py, f64>)>;

pub(crate) fn table(t: Table<'_>) -> Option<(Vec<f64>, Vec<f64>)> {
    t.map(|(a, b)| (a.as_array().to_vec(), b.as_array().to_vec()))
}

/// The observed Stokes radiance (the core's `analysis::scene::observed_radiance`) at `n` views
/// `(theta_r, phi_r)` (degrees when `degrees`, else radians; `theta_r` in `[0°, 90°)`):
/// `(stokes (n, 4), emitted (n, 4), reflected (n, 4), dolp, aolp)`, AoLP in the unit of the
/// angles. W·m⁻²·sr⁻¹·µm⁻¹ at one wavelength, W·m⁻²·sr⁻¹ over a band. `sun` is
/// `(zenith, azimuth, irradiance, stokes)` (angles in the unit of the views, the Stokes vector
/// normalized here); `sky_table` the zenith angles and azimuths (degrees) and the
/// `(n_theta·n_phi, 4)` Stokes radiances, θ-major.
#[pyfunction]
#[pyo3(signature = (
    material, theta_r, phi_r, degrees, wavelength_um=None, band=None, band_step_um=None,
    temperature_k=None, sky=None, sky_radiance=None, sky_temperature_k=None, sky_profile=None,
    transmittance=None, path_radiance=None, sun=None, sky_irradiance=None, dop_max=None,
    sky_table=None
))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn radiance_flat<'py>(
    py: Python<'py>,
    material: &PyMaterial,
    theta_r: PyReadonlyArray1<'py, f64>,
    phi_r: PyReadonlyArray1<'py, f64>,
    degrees: bool,
    wavelength_um: Option<f64>,
    band: Table<'py>,
    band_step_um: Option<f64>,
    temperature_k: Option<f64>,
    sky: Option<&str>,
    sky_radiance: Option<f64>,
    sky_temperature_k: Option<f64>,
    sky_profile: Table<'py>,
    transmittance: Option<f64>,
    path_radiance: Option<f64>,
    sun: Option<(f64, f64, f64, [f64; 4])>,
    sky_irradiance: Option<f64>,
    dop_max: Option<f64>,
    sky_table: SkyTable<'py>,
) -> PyResult<Observed<'py>> {
    let (t, p) = flat_pair(&theta_r, &phi_r, ["theta_r", "phi_r"])?;
    let spectrum = radiance_spectrum(wavelength_um, table(band), band_step_um)?;
    let sun = radiance_sun(sun, degrees)?;
    // `None`: the scene files' default model (the first of their list).
    let sky = sky.unwrap_or_else(|| {
        polbrdf_io::scene::sky_model_names()
            .next()
            .expect("the scene format has sky models")
    });
    let sky_args = SkyArgs {
        radiance: sky_radiance,
        temperature_k: sky_temperature_k,
        profile: sky_profile,
        irradiance: sky_irradiance,
        dop_max,
        table: sky_table,
    };
    let scene = ThermalScene {
        surface_temperature_k: temperature_k,
        sky: radiance_sky(sky, sky_args, sun.is_some())?,
        // `None`: the core's defaults (written once, in `Atmosphere::default`).
        atmosphere: Atmosphere {
            transmittance: transmittance.unwrap_or(Atmosphere::default().transmittance),
            path_radiance: path_radiance.unwrap_or(Atmosphere::default().path_radiance),
        },
        sun,
    };
    scene.validate().map_err(|e| match e {
        polbrdf::Error::InvalidParameter {
            name,
            value,
            reason,
        } => {
            let err = core_err(
                py,
                &polbrdf::Error::InvalidParameter {
                    name: scene_argument(name),
                    value,
                    reason,
                },
            );
            // The core reports the sun's zenith angle in degrees: say what was given.
            match (&scene.sun, name) {
                (Some(s), "sun.zenith_deg") if !degrees => PyValueError::new_err(format!(
                    "{} (given in radians: {})",
                    err.value(py),
                    s.zenith
                )),
                _ => err,
            }
        }
        other => core_err(py, &other),
    })?;
    observe(py, material, &scene, &spectrum, (t, p), degrees)
}

/// The observed radiance of `material` in `scene` over `spectrum` at the views `(t, p)`
/// (degrees when `degrees`, else radians), as the arrays of [`radiance_flat`]; the core's
/// `observed_radiance`, which `polbrdf radiance` runs too.
fn observe<'py>(
    py: Python<'py>,
    material: &PyMaterial,
    scene: &ThermalScene,
    spectrum: &Spectrum,
    (t, p): (&[f64], &[f64]),
    degrees: bool,
) -> PyResult<Observed<'py>> {
    let n = t.len();
    // The views in radians, checked in order; each distinct one evaluated once.
    let mut seen: HashMap<(u64, u64), usize> = HashMap::new();
    let mut views: Vec<(f64, f64)> = Vec::new();
    let mut slot = Vec::with_capacity(n);
    for (i, (&t, &p)) in t.iter().zip(p).enumerate() {
        let v = view_zenith("theta_r", t, degrees, i)
            .and_then(|t| Ok((t, view_azimuth(p, degrees, i)?)))
            .map_err(|e| core_err(py, &e))?;
        slot.push(
            *seen
                .entry((v.0.to_bits(), v.1.to_bits()))
                .or_insert_with(|| {
                    views.push(v);
                    views.len() - 1
                }),
        );
    }
    let spec = material.inner.spec();
    check_views(&views).map_err(|e| core_err(py, &e))?;
    // The observer's setup (spectral materials, the prepared sky) with the GIL released, as the
    // observation itself.
    let observer = py
        .detach(|| Observer::new(spec, scene, spectrum))
        .map_err(|e| core_err(py, &e))?;
    // The task layer's work bound (polbrdf radiance's), before anything is observed.
    polbrdf_tasks::radiance::check_work(&observer, views.len()).map_err(|e| match e {
        polbrdf_tasks::TaskError::Usage { message, .. } => {
            let err = PyValueError::new_err(format!("invalid `theta_r`, `phi_r`: {message}"));
            let _ = err.value(py).setattr("argument", "theta_r");
            err
        }
        e => crate::tasks::task_err(py, &e),
    })?;
    let r = py.detach(|| observer.observe(&views));
    let at = |k: &usize| &r[*k];
    let to_unit = |a: f64| if degrees { a.to_degrees() } else { a };
    Ok((
        stokes_array(py, slot.iter().map(|k| at(k).stokes), n)?,
        stokes_array(py, slot.iter().map(|k| at(k).emitted), n)?,
        stokes_array(py, slot.iter().map(|k| at(k).reflected), n)?,
        PyArray1::from_vec(py, slot.iter().map(|k| at(k).stokes.dolp()).collect()),
        PyArray1::from_vec(
            py,
            slot.iter().map(|k| to_unit(at(k).stokes.aolp())).collect(),
        ),
    ))
}

/// A value of [`read_scene_keys`]: a number, an array of numbers or a string.
#[derive(IntoPyObject)]
pub(crate) enum KeyValue {
    Number(f64),
    Numbers(Vec<f64>),
    Text(String),
}

/// Reads a scene file with `polbrdf-io`'s reader (the CLI's: every check, the same errors) and
/// returns the keys it gives, `[(dotted name, value)]`, tables left out, file names joined to
/// the scene file's folder (`polbrdf_io::read_scene_keys`).
#[pyfunction]
pub(crate) fn read_scene_keys(path: PathBuf) -> PyResult<Vec<(&'static str, KeyValue)>> {
    // A file named `-` is a file here, not standard input.
    let path = if path.as_os_str() == "-" {
        Path::new(".").join("-")
    } else {
        path
    };
    let (_, keys) = polbrdf_io::read_scene_keys(&path).map_err(|e| io_err(&e))?;
    Ok(keys
        .into_iter()
        .map(|(k, v)| {
            let v = match v {
                SceneValue::Number(x) => KeyValue::Number(x),
                SceneValue::Numbers(x) => KeyValue::Numbers(x),
                SceneValue::Text(s) => KeyValue::Text(s),
            };
            (k, v)
        })
        .collect())
}

/// The observed radiance of `material` in the scene of the scene-file text `text` (read by
/// `polbrdf-io`'s reader, as `polbrdf radiance` reads its `--scene`; `source` names it in
/// messages, relative file names are taken relative to the working directory) at the views
/// `(theta_r, phi_r)`, as the arrays of [`radiance_flat`]. A scene with a `[target]` or a
/// `[background]` (for `polbrdf contrast`) is refused: the surface here is `material`, at the
/// `[surface]` temperature.
#[pyfunction]
pub(crate) fn radiance_scene<'py>(
    py: Python<'py>,
    material: &PyMaterial,
    text: &str,
    source: &str,
    theta_r: PyReadonlyArray1<'py, f64>,
    phi_r: PyReadonlyArray1<'py, f64>,
    degrees: bool,
) -> PyResult<Observed<'py>> {
    let scene = polbrdf_io::parse_scene(text, Path::new(source)).map_err(|e| io_err(&e))?;
    for (table, object) in [("target", &scene.target), ("background", &scene.background)] {
        if *object != SceneObject::default() {
            return Err(PyValueError::new_err(format!(
                "{source}: the scene has a [{table}] table, which is for `contrast`: radiance \
                 observes `material` at the [surface] temperature (give `surface`, not \
                 `{table}`)"
            )));
        }
    }
    let (t, p) = flat_pair(&theta_r, &phi_r, ["theta_r", "phi_r"])?;
    observe(
        py,
        material,
        &scene.thermal,
        &scene.spectrum,
        (t, p),
        degrees,
    )
}
