//! Thermal emission: Planck's law, the brightness temperature and the emissivity over flat
//! arrays.

use crate::buffers::can_allocate;
use crate::buffers::flat;
use crate::buffers::flat_pair;
use crate::buffers::stokes_array;
use crate::buffers::zeros1;
use crate::errors::element_err;
use crate::evaluation::needs_wavelength;
use crate::evaluation::wavelength_slice;
use crate::material::PyMaterial;
use numpy::{PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1};
use polbrdf::analysis::emission::{emissivities, Emissivity};
use polbrdf::analysis::thermal;
use polbrdf::engine::batch::CHUNK;
use polbrdf::{AngleProblem, Material};
use pyo3::prelude::*;
use rayon::prelude::*;
use std::collections::HashMap;
use std::f64::consts::FRAC_PI_2;

/// Checks that `value` (element `index` of the argument `name`) is finite and > 0, with the
/// core's wording.
pub(crate) fn positive_at(
    name: &'static str,
    value: f64,
    index: usize,
) -> Result<f64, polbrdf::Error> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(polbrdf::Error::InvalidParameterAt {
            name,
            value,
            index,
            reason: "must be finite and > 0",
        })
    }
}

/// A core [`polbrdf::Error::InvalidParameter`] about element `index` of a flat argument.
pub(crate) fn at_index(e: polbrdf::Error, index: usize) -> polbrdf::Error {
    e.at_position(Some(index))
}

/// A view zenith angle (element `index` of the argument `name`, in degrees when `degrees`) in
/// radians, checked to lie in `[0, π/2)` as the emissivity needs (`-0` becomes `+0`).
pub(crate) fn view_zenith(
    name: &'static str,
    value: f64,
    degrees: bool,
    index: usize,
) -> Result<f64, polbrdf::Error> {
    let rad = if degrees { value.to_radians() } else { value };
    if rad.is_finite() && (0.0..FRAC_PI_2).contains(&rad) {
        Ok(rad + 0.0)
    } else {
        Err(polbrdf::Error::InvalidAngle {
            name,
            value,
            degrees,
            index: Some(index),
            problem: if value.is_finite() {
                AngleProblem::ViewBelowHorizon
            } else {
                AngleProblem::NotFinite
            },
        })
    }
}

/// A view azimuth angle in radians, checked to be finite.
pub(crate) fn view_azimuth(value: f64, degrees: bool, index: usize) -> Result<f64, polbrdf::Error> {
    let rad = if degrees { value.to_radians() } else { value };
    if rad.is_finite() {
        Ok(rad)
    } else {
        Err(polbrdf::Error::InvalidAngle {
            name: "phi_r",
            value,
            degrees,
            index: Some(index),
            problem: AngleProblem::NotFinite,
        })
    }
}

/// Planck's law `B_λ(λ, T)` (W·m⁻²·sr⁻¹·µm⁻¹) at `n` pairs of a wavelength (µm) and a
/// temperature (K), through the core's `planck_checked`.
#[pyfunction]
pub(crate) fn planck_flat<'py>(
    py: Python<'py>,
    wavelength_um: PyReadonlyArray1<'py, f64>,
    temperature_k: PyReadonlyArray1<'py, f64>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let (l, t) = flat_pair(
        &wavelength_um,
        &temperature_k,
        ["wavelength_um", "temperature_k"],
    )?;
    let out = zeros1(py, l.len())?;
    {
        let mut w = out.readwrite();
        let o = w.as_slice_mut().expect("a new array is contiguous");
        let valid = py.detach(|| {
            o.par_chunks_mut(CHUNK).enumerate().all(|(c, o)| {
                let start = c * CHUNK;
                o.iter_mut().enumerate().all(|(j, o)| {
                    match thermal::planck_checked(l[start + j], t[start + j]) {
                        Ok(b) => {
                            *o = b;
                            true
                        }
                        Err(_) => false,
                    }
                })
            })
        });
        if !valid {
            // The first bad element, found again in order (the parallel pass may stop at any).
            for (i, (&l, &t)) in l.iter().zip(t).enumerate() {
                if let Err(e) = thermal::planck_checked(l, t) {
                    return Err(element_err(py, &at_index(e, i)));
                }
            }
        }
    }
    Ok(out)
}

/// The brightness temperature (K) of `n` spectral radiances (W·m⁻²·sr⁻¹·µm⁻¹) at wavelengths
/// (µm), through the core's `brightness_temperature`.
#[pyfunction]
pub(crate) fn brightness_temperature_flat<'py>(
    py: Python<'py>,
    wavelength_um: PyReadonlyArray1<'py, f64>,
    radiance: PyReadonlyArray1<'py, f64>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let (l, r) = flat_pair(&wavelength_um, &radiance, ["wavelength_um", "radiance"])?;
    for (i, (&l, &r)) in l.iter().zip(r).enumerate() {
        positive_at("wavelength_um", l, i)
            .and_then(|_| positive_at("radiance", r, i))
            .map_err(|e| element_err(py, &e))?;
    }
    let out = zeros1(py, l.len())?;
    {
        let mut w = out.readwrite();
        let o = w.as_slice_mut().expect("a new array is contiguous");
        py.detach(|| {
            o.par_chunks_mut(CHUNK).enumerate().for_each(|(c, o)| {
                let start = c * CHUNK;
                for (j, o) in o.iter_mut().enumerate() {
                    *o = thermal::brightness_temperature(l[start + j], r[start + j]);
                }
            })
        });
    }
    Ok(out)
}

/// The emissivity of `m` toward every view zenith of `theta_r`, each at its wavelength:
/// validated in order, then one core `emissivities` call per distinct wavelength (one in all
/// for a constant index) with the distinct zenith angles of that wavelength.
pub(crate) fn emissivity_batch(
    m: &Material,
    theta_r: &[f64],
    degrees: bool,
    wavelengths: Option<&[f64]>,
) -> Result<Vec<Emissivity>, polbrdf::Error> {
    let n = theta_r.len();
    let rad = theta_r
        .iter()
        .enumerate()
        .map(|(i, &t)| view_zenith("theta_r", t, degrees, i))
        .collect::<Result<Vec<f64>, _>>()?;
    let spec = m.spec();
    // The material of each element: one per distinct wavelength of a spectral index.
    let mut materials: Vec<Material> = Vec::new();
    let mut group = vec![0usize; n];
    match wavelengths {
        None if spec.is_spectral() => return Err(needs_wavelength(spec)),
        Some(wl) if spec.is_spectral() => {
            let mut seen: HashMap<u64, usize> = HashMap::new();
            for (i, &l) in wl.iter().enumerate() {
                positive_at("wavelength_um", l, i)?;
                group[i] = match seen.get(&l.to_bits()) {
                    Some(&g) => g,
                    None => {
                        materials.push(m.at_wavelength(l).map_err(|e| at_index(e, i))?);
                        seen.insert(l.to_bits(), materials.len() - 1);
                        materials.len() - 1
                    }
                };
            }
        }
        Some(wl) => {
            // A constant index does not depend on λ: one evaluation for every wavelength.
            for (i, &l) in wl.iter().enumerate() {
                positive_at("wavelength_um", l, i)?;
            }
            materials.push(m.clone());
        }
        None => materials.push(m.clone()),
    }
    // The distinct zenith angles of each material, in first-seen order.
    let mut seen: Vec<HashMap<u64, usize>> = vec![HashMap::new(); materials.len()];
    let mut zeniths: Vec<Vec<f64>> = vec![Vec::new(); materials.len()];
    let slot: Vec<usize> = rad
        .iter()
        .zip(&group)
        .map(|(&t, &g)| {
            *seen[g].entry(t.to_bits()).or_insert_with(|| {
                zeniths[g].push(t);
                zeniths[g].len() - 1
            })
        })
        .collect();
    let results: Vec<Vec<Emissivity>> = materials
        .par_iter()
        .zip(zeniths.par_iter())
        .map(|(m, z)| emissivities(m, z))
        .collect::<Result<_, _>>()?;
    Ok(group
        .iter()
        .zip(&slot)
        .map(|(&g, &j)| results[g][j])
        .collect())
}

/// The arrays of [`emissivity_flat`].
pub(crate) type Emitted<'py> = (
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<bool>>,
);

/// The emissivity (Kirchhoff's law, the core's `analysis::emission::emissivities`) toward `n`
/// view zenith angles `theta_r` (degrees when `degrees`, else radians; in `[0°, 90°)`), each at
/// its wavelength (µm; required for a spectral index): `(eps (n, 4), eps_b (n, 4), eps_s,
/// eps_p, dolp, reciprocity_residual, valid)`.
#[pyfunction]
#[pyo3(signature = (material, theta_r, degrees, wavelength_um=None))]
pub(crate) fn emissivity_flat<'py>(
    py: Python<'py>,
    material: &PyMaterial,
    theta_r: PyReadonlyArray1<'py, f64>,
    degrees: bool,
    wavelength_um: Option<PyReadonlyArray1<'py, f64>>,
) -> PyResult<Emitted<'py>> {
    let t = flat(&theta_r, "theta_r")?;
    let n = t.len();
    let wl = wavelength_slice(&wavelength_um, n)?;
    // The results and their 14 output columns: MemoryError now rather than an abort later.
    can_allocate::<Emissivity>(n)?;
    can_allocate::<f64>(n.saturating_mul(14))?;
    let m = &material.inner;
    let e = py
        .detach(|| emissivity_batch(m, t, degrees, wl))
        .map_err(|e| element_err(py, &e))?;
    let valid = e.iter().map(Emissivity::is_valid).collect();
    emissivity_arrays(py, &e, valid)
}

/// The arrays of emissivities `e` (one per row) and their validity flags `valid`: `(eps (n, 4),
/// eps_b (n, 4), eps_s, eps_p, dolp, reciprocity_residual, valid)` — [`emissivity_flat`]'s and
/// `polbrdf_tasks::emission`'s (`jobs::emission_task`) one layout.
pub(crate) fn emissivity_arrays<'py>(
    py: Python<'py>,
    e: &[Emissivity],
    valid: Vec<bool>,
) -> PyResult<Emitted<'py>> {
    let n = e.len();
    let column = |f: fn(&Emissivity) -> f64| PyArray1::from_vec(py, e.iter().map(f).collect());
    Ok((
        stokes_array(py, e.iter().map(|e| e.eps), n)?,
        stokes_array(py, e.iter().map(|e| e.eps_b), n)?,
        column(Emissivity::eps_s),
        column(Emissivity::eps_p),
        column(Emissivity::dolp),
        column(Emissivity::reciprocity_residual),
        PyArray1::from_vec(py, valid),
    ))
}
