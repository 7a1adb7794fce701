//! Evaluation: the pBRDF (Mueller matrix), BRDF, DoLP and AoLP kernels over flat arrays, in
//! parallel chunks through the core's driver, and the complex index.

use crate::buffers::out_rows;
use crate::buffers::slices;
use crate::buffers::spread;
use crate::buffers::vectors;
use crate::buffers::zeros1;
use crate::buffers::zeros2;
use crate::buffers::Nan;
use crate::buffers::Store;
use crate::buffers::StoreF32;
use crate::buffers::StoreF64;
use crate::buffers::Target;
use crate::errors::core_err;
use crate::errors::python_name;
use crate::material::PyMaterial;
use numpy::{
    PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods,
};
use polbrdf::engine::batch::CHUNK;
use polbrdf::engine::batch::{try_for_chunks, Split};
use polbrdf::engine::Planes;
use polbrdf::engine::Precision;
use polbrdf::Engine;
use polbrdf::{GeometryBatch, Unvalidated};
use polbrdf::{Material, MaterialSpec};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// Runs `f` with the engine for elements `start .. start + len`: the material's own index, or
/// with `wavelengths` (µm, one per element) the material's index at each (a spectral index;
/// a constant one does not depend on it). A spectral material needs the wavelengths.
pub(crate) fn with_engine<T>(
    m: &Material,
    wavelengths: Option<&[f64]>,
    start: usize,
    len: usize,
    f: impl FnOnce(&Engine<'_>) -> Result<T, polbrdf::Error>,
) -> Result<T, polbrdf::Error> {
    let spec = m.spec();
    match wavelengths {
        None if spec.is_spectral() => Err(needs_wavelength(spec)),
        None => f(&Engine::new(m)),
        Some(wl) => {
            // A wavelength outside the data: its position in the whole array.
            let engine = Engine::new(m)
                .with_wavelengths(&wl[start..start + len])
                .map_err(|e| match e {
                    polbrdf::Error::WavelengthOutOfRange {
                        material,
                        wavelength_um,
                        range,
                        position,
                    } => polbrdf::Error::WavelengthOutOfRange {
                        material,
                        wavelength_um,
                        range,
                        position: position.map(|p| p + start),
                    },
                    other => other,
                })?;
            f(&engine)
        }
    }
}

/// The refusal to evaluate a material with a spectral index without wavelengths.
pub(crate) fn needs_wavelength(spec: &MaterialSpec) -> polbrdf::Error {
    let (lo, hi) = spec.wavelength_range().unwrap_or((f64::NAN, f64::NAN));
    polbrdf::Error::InconsistentParameters(format!(
        "the material has a spectral index ({lo}–{hi} µm): give wavelength_um="
    ))
}

/// The wavelength array as a slice of the angles' length.
pub(crate) fn wavelength_slice<'a>(
    wl: &'a Option<PyReadonlyArray1<'_, f64>>,
    n: usize,
) -> PyResult<Option<&'a [f64]>> {
    let Some(a) = wl else { return Ok(None) };
    let s = a.as_slice().map_err(|e| {
        PyValueError::new_err(format!(
            "`wavelength_um` must be a contiguous 1-D array: {e}"
        ))
    })?;
    if s.len() != n {
        return Err(PyValueError::new_err(format!(
            "`wavelength_um` has {} elements, the angles {n}",
            s.len()
        )));
    }
    Ok(Some(s))
}

/// Checks that the four angle arrays are equally long; returns the length.
pub(crate) fn common_len(input: [&[f64]; 4]) -> Result<usize, polbrdf::Error> {
    let n = input[0].len();
    for (s, name) in input[1..].iter().zip(["phi_i", "theta_r", "phi_r"]) {
        if s.len() != n {
            return Err(polbrdf::Error::LengthMismatch {
                name,
                got: s.len(),
                expected: n,
            });
        }
    }
    Ok(n)
}

/// The length of four angle arrays each of which is `n` long or a single value broadcast to
/// every element (the Python layer passes a scalar argument so, not materialized): the
/// wavelengths' length when given (always `n` long), else 0 when one is empty (as numpy
/// broadcasts), else the longest.
pub(crate) fn broadcast_len(
    input: [&[f64]; 4],
    wavelengths: Option<usize>,
) -> Result<usize, polbrdf::Error> {
    let n = match wavelengths {
        Some(n) => n,
        None if input.iter().any(|s| s.is_empty()) => 0,
        None => input.iter().map(|s| s.len()).max().unwrap_or(0),
    };
    for (s, name) in input.iter().zip(["theta_i", "phi_i", "theta_r", "phi_r"]) {
        if s.len() != n && s.len() != 1 {
            return Err(polbrdf::Error::LengthMismatch {
                name,
                got: s.len(),
                expected: n,
            });
        }
    }
    Ok(n)
}

/// Runs `f` on the geometries `start .. start + len` (`len ≤ CHUNK`) as a validated core batch
/// ([`GeometryBatch::new`]) in radians ([`chunk_angles`]).
pub(crate) fn chunk_batch<T>(
    input: [&[f64]; 4],
    start: usize,
    len: usize,
    degrees: bool,
    f: impl FnOnce(&GeometryBatch<'_>) -> Result<T, polbrdf::Error>,
) -> Result<T, polbrdf::Error> {
    chunk_angles(input, start, len, degrees, |[ti, pi, tr, pr]| {
        f(&GeometryBatch::new(ti, pi, tr, pr)?)
    })
}

/// Runs `f` on the geometries `start .. start + len` (`len ≤ CHUNK`) in radians, not validated
/// ([`Unvalidated`]: the kernel's `try_` methods validate each block as they read it, with
/// the same errors as [`GeometryBatch::new`]) ([`chunk_angles`]).
pub(crate) fn chunk_unvalidated<T>(
    input: [&[f64]; 4],
    start: usize,
    len: usize,
    degrees: bool,
    f: impl FnOnce(&Unvalidated<'_>) -> Result<T, polbrdf::Error>,
) -> Result<T, polbrdf::Error> {
    chunk_angles(input, start, len, degrees, |[ti, pi, tr, pr]| {
        f(&Unvalidated::angles(ti, pi, tr, pr)?)
    })
}

/// Runs `f` on the four columns of the geometries `start .. start + len` (`len ≤ CHUNK`) in
/// radians. With `degrees` the chunk is first converted into a buffer on the stack
/// (`f64::to_radians`, as `Geometry::from_degrees` does): the conversion happens in the same
/// pass as the evaluation, with no whole-array temporaries.
///
/// An invalid angle `f` reports (the core batch's validation) is reported with its index in
/// the whole array and, in degrees mode, with its value in degrees (as
/// `Geometry::from_degrees` reports it); the name stays the Python argument's (`theta_i`, …).
fn chunk_angles<T>(
    input: [&[f64]; 4],
    start: usize,
    len: usize,
    degrees: bool,
    f: impl FnOnce([&[f64]; 4]) -> Result<T, polbrdf::Error>,
) -> Result<T, polbrdf::Error> {
    // A single value (broadcast) stands for every element.
    let part = input.map(|s| {
        if s.len() == 1 {
            s
        } else {
            &s[start..start + len]
        }
    });
    let mut buf = [[0.0f64; CHUNK]; 4];
    let mut rad: [&[f64]; 4] = part;
    for ((b, s), r) in buf.iter_mut().zip(part).zip(rad.iter_mut()) {
        if s.len() == 1 && len != 1 {
            b[..len].fill(if degrees { s[0].to_radians() } else { s[0] });
            *r = &b[..len];
        } else if degrees {
            for (r, d) in b.iter_mut().zip(s) {
                *r = d.to_radians();
            }
            *r = &b[..len];
        }
    }
    f(rad).map_err(|e| match e {
        polbrdf::Error::InvalidAngle { index: Some(i), .. } if degrees => {
            // The element as given, in degrees, as `Geometry::from_degrees` checks it; named
            // by the Python argument.
            let [a, b, c, d] = part.map(|s| s[if s.len() == 1 { 0 } else { i }]);
            match polbrdf::Geometry::from_degrees(a, b, c, d) {
                Err(polbrdf::Error::InvalidAngle {
                    name,
                    value,
                    problem,
                    ..
                }) => polbrdf::Error::InvalidAngle {
                    name: python_name(name),
                    value,
                    degrees: true,
                    index: Some(i + start),
                    problem,
                },
                _ => e,
            }
        }
        polbrdf::Error::InvalidAngle {
            name,
            value,
            degrees,
            index,
            problem,
        } => polbrdf::Error::InvalidAngle {
            name,
            value,
            degrees,
            index: index.map(|i| i + start),
            problem,
        },
        other => other,
    })
}

/// Fills `rows` (one row-major 4×4 per geometry) through the core's parallel driver
/// (`try_for_chunks`: parts of at most [`CHUNK`], a small batch on the calling thread):
/// `chunk(start, rows)` evaluates the part at `start` through the serial kernel (true when an
/// entry overflowed f32), with the stores the batch API would use (`StoreF64`).
pub(crate) fn mueller_chunks<T: Send>(
    rows: Target<'_, T>,
    chunk: impl Fn(usize, Target<'_, T>) -> Result<bool, polbrdf::Error> + Sync,
) -> Result<(), polbrdf::Error> {
    let overflow = try_for_chunks(rows, chunk)?;
    if overflow {
        return Err(polbrdf::engine::batch::f32_overflow());
    }
    Ok(())
}

/// The pBRDF of the geometries `input` (angles) into `rows` ([`mueller_chunks`]).
pub(crate) fn mueller_rows<T: Send>(
    m: &Material,
    input: [&[f64]; 4],
    wl: Option<&[f64]>,
    degrees: bool,
    rows: Target<'_, T>,
    store: &impl Store<T>,
) -> Result<(), polbrdf::Error> {
    mueller_chunks(rows, |start, rows| {
        let len = rows.len();
        chunk_unvalidated(input, start, len, degrees, |b| {
            with_engine(m, wl, start, len, |e| rows.store(store, e.kernel(), b))
        })
    })
}

/// The pBRDF of the direction vectors `w_i`, `w_r` (equally long, or one of them a single
/// vector standing for all) into `rows` ([`mueller_chunks`]); a bad vector is named by its
/// index in the whole array.
pub(crate) fn direction_rows<T: Send>(
    m: &Material,
    [w_i, w_r]: [&[[f64; 3]]; 2],
    wl: Option<&[f64]>,
    rows: Target<'_, T>,
    store: &impl Store<T>,
) -> Result<(), polbrdf::Error> {
    mueller_chunks(rows, |start, rows| {
        let len = rows.len();
        let (mut bi, mut br) = ([[0.0f64; 3]; CHUNK], [[0.0f64; 3]; CHUNK]);
        let (si, sr) = (
            spread(w_i, start, len, &mut bi),
            spread(w_r, start, len, &mut br),
        );
        let batch = Unvalidated::directions(si, sr)?;
        with_engine(m, wl, start, len, |e| rows.store(store, e.kernel(), &batch)).map_err(|e| {
            match e {
                polbrdf::Error::InvalidDirection { name, value, index } => {
                    polbrdf::Error::InvalidDirection {
                        name,
                        value,
                        index: index.map(|i| i + start),
                    }
                }
                other => other,
            }
        })
    })
}

/// The pBRDF `F` (sr⁻¹, psps basis) at `n` geometries as an `(n, 16)` array, row-major 4×4 per
/// geometry, in `precision` (`"float64"`, or `"float32"`: computed in single precision within
/// the float32 contract, `1e-5·F00 + 1e-6·P + 2⁻¹⁵⁰` of float64, docs/model.md §12), written
/// into `out` when given (an `(n, 16)` C-contiguous array of that dtype, which is returned).
/// The Python layer reshapes it to `shape + (4, 4)`. With `planar`, a `(16, n)` array of 16 planes instead
/// (`Planes`), which the Python layer reshapes to `(4, 4) + shape`.
#[pyfunction]
#[pyo3(signature = (material, theta_i, phi_i, theta_r, phi_r, degrees, wavelength_um=None, out=None, precision="float64", planar=false))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn mueller_flat<'py>(
    py: Python<'py>,
    material: &PyMaterial,
    theta_i: PyReadonlyArray1<'py, f64>,
    phi_i: PyReadonlyArray1<'py, f64>,
    theta_r: PyReadonlyArray1<'py, f64>,
    phi_r: PyReadonlyArray1<'py, f64>,
    degrees: bool,
    wavelength_um: Option<PyReadonlyArray1<'py, f64>>,
    out: Option<Bound<'py, PyAny>>,
    precision: &str,
    planar: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let precision: Precision = precision.parse().map_err(|e| core_err(py, &e))?;
    let input = slices([&theta_i, &phi_i, &theta_r, &phi_r])?;
    let n = broadcast_len(input, wavelength_um.as_ref().map(|w| w.len()))
        .map_err(|e| core_err(py, &e))?;
    let wl = wavelength_slice(&wavelength_um, n)?;
    let m = &material.inner;
    match precision {
        Precision::F64 => mueller_array::<f64>(py, out, n, Precision::F64.name(), planar, |rows| {
            mueller_rows(m, input, wl, degrees, rows, &StoreF64::new(m, n))
        }),
        Precision::F32 => mueller_array::<f32>(py, out, n, Precision::F32.name(), planar, |rows| {
            mueller_rows(m, input, wl, degrees, rows, &StoreF32::new(m, n))
        }),
    }
}

/// The pBRDF at direction vectors (the direction entry point, docs/model.md §9.11): `w_i`,
/// `w_r` as `(n, 3)` C-contiguous float64 arrays (or `(1, 3)`, standing for every element),
/// each vector in the surface frame, of any length within 1e-15..1e15; otherwise as
/// [`mueller_flat`].
#[pyfunction]
#[pyo3(signature = (material, w_i, w_r, wavelength_um=None, out=None, precision="float64", planar=false))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn mueller_directions_flat<'py>(
    py: Python<'py>,
    material: &PyMaterial,
    w_i: PyReadonlyArray2<'py, f64>,
    w_r: PyReadonlyArray2<'py, f64>,
    wavelength_um: Option<PyReadonlyArray1<'py, f64>>,
    out: Option<Bound<'py, PyAny>>,
    precision: &str,
    planar: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let precision: Precision = precision.parse().map_err(|e| core_err(py, &e))?;
    let (wi, wr) = (vectors(&w_i, "w_i")?, vectors(&w_r, "w_r")?);
    let lens = [wi.len(), wr.len()];
    let n = match wavelength_um.as_ref() {
        Some(w) => w.len(),
        None if lens.contains(&0) => 0,
        None => lens[0].max(lens[1]),
    };
    for (len, name) in lens.into_iter().zip(["w_i", "w_r"]) {
        if len != n && len != 1 {
            let e = polbrdf::Error::LengthMismatch {
                name,
                got: len,
                expected: n,
            };
            return Err(core_err(py, &e));
        }
    }
    let wl = wavelength_slice(&wavelength_um, n)?;
    let m = &material.inner;
    match precision {
        Precision::F64 => mueller_array::<f64>(py, out, n, Precision::F64.name(), planar, |rows| {
            direction_rows(m, [wi, wr], wl, rows, &StoreF64::new(m, n))
        }),
        Precision::F32 => mueller_array::<f32>(py, out, n, Precision::F32.name(), planar, |rows| {
            direction_rows(m, [wi, wr], wl, rows, &StoreF32::new(m, n))
        }),
    }
}

/// [`mueller_flat`] in the element type `T` (numpy's `dtype`): `out` (checked by [`out_rows`])
/// or a new `(n, 16)` array — `(16, n)` when `planar` — filled by `fill` ([`mueller_rows`],
/// [`direction_rows`]) with the GIL released. When `fill` fails (an invalid element, found as
/// the kernel reads its block, after other chunks were written), every entry of the array is
/// set to NaN before the error is raised: a caller's `out` never holds a partial result.
#[allow(clippy::too_many_arguments)]
pub(crate) fn mueller_array<'py, T: numpy::Element + Send + Nan>(
    py: Python<'py>,
    out: Option<Bound<'py, PyAny>>,
    n: usize,
    dtype: &str,
    planar: bool,
    fill: impl FnOnce(Target<'_, T>) -> Result<(), polbrdf::Error> + Send,
) -> PyResult<Bound<'py, PyAny>> {
    let shape = if planar { [16, n] } else { [n, 16] };
    let arr = match &out {
        Some(o) => out_rows::<T>(o, shape, dtype)?,
        None => zeros2::<T>(py, shape[0], shape[1])?,
    };
    let mut rw = arr.try_readwrite().map_err(|e| {
        PyValueError::new_err(format!("`out` must be writeable and not in use: {e}"))
    })?;
    let flat = rw.as_slice_mut().expect("checked C-contiguous");
    let target = if planar {
        Target::Planes(Planes::new(flat, n).map_err(|e| core_err(py, &e))?)
    } else {
        Target::Rows(flat.as_chunks_mut::<16>().0)
    };
    if let Err(e) = py.detach(|| fill(target)) {
        flat.fill(T::NAN);
        return Err(core_err(py, &e));
    }
    drop(rw);
    Ok(arr.into_any())
}

/// The scalar BRDF `f` (sr⁻¹) and the DoLP for unpolarized input at `n` geometries, as two
/// float64 arrays of length `n`.
#[pyfunction]
#[pyo3(signature = (material, theta_i, phi_i, theta_r, phi_r, degrees, wavelength_um=None))]
#[allow(clippy::type_complexity, clippy::too_many_arguments)]
pub(crate) fn brdf_dolp_flat<'py>(
    py: Python<'py>,
    material: &PyMaterial,
    theta_i: PyReadonlyArray1<'py, f64>,
    phi_i: PyReadonlyArray1<'py, f64>,
    theta_r: PyReadonlyArray1<'py, f64>,
    phi_r: PyReadonlyArray1<'py, f64>,
    degrees: bool,
    wavelength_um: Option<PyReadonlyArray1<'py, f64>>,
) -> PyResult<ArrayPair<'py>> {
    let input = slices([&theta_i, &phi_i, &theta_r, &phi_r])?;
    let n = broadcast_len(input, wavelength_um.as_ref().map(|w| w.len()))
        .map_err(|e| core_err(py, &e))?;
    let wl = wavelength_slice(&wavelength_um, n)?;
    let brdf = zeros1(py, n)?;
    let dolp = zeros1(py, n)?;
    {
        let (mut bw, mut dw) = (brdf.readwrite(), dolp.readwrite());
        let b = bw.as_slice_mut().expect("a new array is contiguous");
        let d = dw.as_slice_mut().expect("a new array is contiguous");
        let m = &material.inner;
        py.detach(|| {
            try_for_chunks((b, d), |start, (b, d)| {
                chunk_batch(input, start, b.len(), degrees, |g| {
                    with_engine(m, wl, start, b.len(), |e| e.brdf_dolp_into(g, b, d))
                })
                .map(|()| false)
            })
        })
        .map_err(|e| core_err(py, &e))?;
    }
    Ok((brdf, dolp))
}

pub(crate) type Evaluated<'py> = (
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Option<Bound<'py, PyArray2<f64>>>,
);

/// BRDF (sr⁻¹), DoLP and AoLP (of `F·(1,0,0,0)`; degrees when `degrees`, else radians) at `n`
/// geometries, plus the `(n, 16)` pBRDF when `with_mueller`; one pass over the geometries.
#[pyfunction]
#[pyo3(signature = (material, theta_i, phi_i, theta_r, phi_r, degrees, with_mueller, wavelength_um=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn evaluate_flat<'py>(
    py: Python<'py>,
    material: &PyMaterial,
    theta_i: PyReadonlyArray1<'py, f64>,
    phi_i: PyReadonlyArray1<'py, f64>,
    theta_r: PyReadonlyArray1<'py, f64>,
    phi_r: PyReadonlyArray1<'py, f64>,
    degrees: bool,
    with_mueller: bool,
    wavelength_um: Option<PyReadonlyArray1<'py, f64>>,
) -> PyResult<Evaluated<'py>> {
    let input = slices([&theta_i, &phi_i, &theta_r, &phi_r])?;
    let n = broadcast_len(input, wavelength_um.as_ref().map(|w| w.len()))
        .map_err(|e| core_err(py, &e))?;
    let wl = wavelength_slice(&wavelength_um, n)?;
    let brdf = zeros1(py, n)?;
    let dolp = zeros1(py, n)?;
    let aolp = zeros1(py, n)?;
    let mueller = with_mueller.then(|| zeros2(py, n, 16)).transpose()?;
    {
        let (mut bw, mut dw, mut aw) = (brdf.readwrite(), dolp.readwrite(), aolp.readwrite());
        let mut mw = mueller.as_ref().map(|m| m.readwrite());
        let b = bw.as_slice_mut().expect("a new array is contiguous");
        let d = dw.as_slice_mut().expect("a new array is contiguous");
        let a = aw.as_slice_mut().expect("a new array is contiguous");
        let f = mw
            .as_mut()
            .map(|m| m.as_slice_mut().expect("a new array is contiguous"));
        let m = &material.inner;
        // BRDF, DoLP and AoLP (the core's `Stokes::dolp`/`Stokes::aolp` of F·(1, 0, 0, 0)) from
        // the kernel's BRDF+DoLP+AoLP path, so that they are bitwise those of `brdf`/`dolp`.
        let scalars =
            |start: usize, g: &GeometryBatch<'_>, b: &mut [f64], d: &mut [f64], a: &mut [f64]| {
                with_engine(m, wl, start, b.len(), |e| e.brdf_dolp_aolp_into(g, b, d, a))?;
                if degrees {
                    a.iter_mut().for_each(|x| *x = x.to_degrees());
                }
                Ok(())
            };
        py.detach(|| match f {
            Some(f) => {
                let (rows, _) = f.as_chunks_mut::<16>();
                try_for_chunks((((b, d), a), rows), |start, (((b, d), a), rows)| {
                    chunk_batch(input, start, b.len(), degrees, |g| {
                        with_engine(m, wl, start, b.len(), |e| e.mueller_into(g, rows))?;
                        scalars(start, g, b, d, a)
                    })
                    .map(|()| false)
                })
            }
            None => try_for_chunks(((b, d), a), |start, ((b, d), a)| {
                chunk_batch(input, start, b.len(), degrees, |g| {
                    scalars(start, g, b, d, a)
                })
                .map(|()| false)
            }),
        })
        .map_err(|e| core_err(py, &e))?;
    }
    Ok((brdf, dolp, aolp, mueller))
}

/// Two float64 arrays.
pub(crate) type ArrayPair<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>);

/// The complex index `n + ik` of a material at each wavelength (µm), as two float64 arrays:
/// the spectral index there, or the constant one.
#[pyfunction]
#[pyo3(signature = (material, wavelength_um))]
pub(crate) fn index_flat<'py>(
    py: Python<'py>,
    material: &PyMaterial,
    wavelength_um: PyReadonlyArray1<'py, f64>,
) -> PyResult<ArrayPair<'py>> {
    let wl = wavelength_um.as_slice().map_err(|e| {
        PyValueError::new_err(format!(
            "`wavelength_um` must be a contiguous 1-D array: {e}"
        ))
    })?;
    let spec = material.inner.spec();
    let (n, k) = py.detach(|| spec.index_columns(wl)).map_err(|(i, e)| {
        PyValueError::new_err(format!("wavelength_um = {} (at index {i}): {e}", wl[i]))
    })?;
    Ok((PyArray1::from_vec(py, n), PyArray1::from_vec(py, k)))
}
