//! Buffers: the flat NumPy arrays handed over by the Python layer as slices, new output
//! arrays (or `MemoryError`), and where a pBRDF call writes (rows or planes).

use numpy::{
    PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods,
};
use polbrdf::engine::batch::Split;
use polbrdf::engine::batch::CHUNK;
use polbrdf::engine::Kernel;
use polbrdf::engine::Planes;
use polbrdf::Engine;
use polbrdf::Material;
use polbrdf::Result;
use polbrdf::Unvalidated;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The four angle arrays as slices (contiguous by construction in the Python layer).
pub(crate) fn slices<'a>(arrays: [&'a PyReadonlyArray1<'_, f64>; 4]) -> PyResult<[&'a [f64]; 4]> {
    let mut out: [&[f64]; 4] = [&[]; 4];
    for (o, (a, name)) in out.iter_mut().zip(
        arrays
            .into_iter()
            .zip(["theta_i", "phi_i", "theta_r", "phi_r"]),
    ) {
        *o = a.as_slice().map_err(|e| {
            PyValueError::new_err(format!("`{name}` must be a contiguous 1-D array: {e}"))
        })?;
    }
    Ok(out)
}

/// A new float64 array of `n` zeros, or `MemoryError` when it cannot be allocated (numpy's
/// `zeros`: `PyArray1::zeros` would panic on a null pointer instead, a `BaseException`).
pub(crate) fn zeros1(py: Python<'_>, n: usize) -> PyResult<Bound<'_, PyArray1<f64>>> {
    let a = py.import("numpy")?.call_method1("zeros", ((n,),))?;
    Ok(a.cast_into::<PyArray1<f64>>()?)
}

/// A new `(n, m)` array of zeros of `T`'s dtype, or `MemoryError` ([`zeros1`]).
pub(crate) fn zeros2<T: numpy::Element>(
    py: Python<'_>,
    n: usize,
    m: usize,
) -> PyResult<Bound<'_, PyArray2<T>>> {
    let kwargs = PyDict::new(py);
    kwargs.set_item("dtype", numpy::dtype::<T>(py))?;
    let a = py
        .import("numpy")?
        .call_method("zeros", ((n, m),), Some(&kwargs))?;
    Ok(a.cast_into::<PyArray2<T>>()?)
}

/// `MemoryError` unless `count` values of `T` can be allocated (tried, then freed): for results
/// the core returns as a `Vec`, whose failed allocation would abort the interpreter.
pub(crate) fn can_allocate<T>(count: usize) -> PyResult<()> {
    let fail = || {
        pyo3::exceptions::PyMemoryError::new_err(format!(
            "cannot allocate {count} results of {} bytes",
            size_of::<T>()
        ))
    };
    let bytes = count.checked_mul(size_of::<T>()).ok_or_else(fail)?;
    Vec::<u8>::new()
        .try_reserve_exact(bytes)
        .map_err(|_| fail())
}

/// Elements `start .. start + len` of `w`, or its single vector `len` times (in `buf`).
pub(crate) fn spread<'a>(
    w: &'a [[f64; 3]],
    start: usize,
    len: usize,
    buf: &'a mut [[f64; 3]; CHUNK],
) -> &'a [[f64; 3]] {
    match w {
        [one] if len > 1 => {
            buf[..len].fill(*one);
            &buf[..len]
        }
        [_] => w,
        _ => &w[start..start + len],
    }
}

/// How a Mueller-matrix array is filled, chunk by chunk, whatever the kind of batch: the
/// serial kernel's `try_mueller_into` (f64) or `try_mueller_f32_into` (f32, which reports an
/// entry beyond f32's range), validating each block as it reads it.
pub(crate) trait Store<T>: Sync {
    /// Fills `rows` for `batch`; true when an entry overflowed f32. An invalid element: the
    /// batch constructor's error, `rows` all NaN.
    fn store(&self, k: &Kernel<'_>, batch: &Unvalidated<'_>, rows: &mut [[T; 16]]) -> Result<bool>;
    /// Fills `planes` for `batch` (the planar layout); as [`Store::store`].
    fn store_planes(
        &self,
        k: &Kernel<'_>,
        batch: &Unvalidated<'_>,
        planes: &mut Planes<'_, T>,
    ) -> Result<bool>;
}

/// NaN of an output's element type (what an output holds after an error).
pub(crate) trait Nan: Copy {
    const NAN: Self;
}

impl Nan for f64 {
    const NAN: f64 = f64::NAN;
}

impl Nan for f32 {
    const NAN: f32 = f32::NAN;
}

/// Where a Python pBRDF call writes: one row-major 4×4 per geometry (an `(n, 16)` array), or
/// 16 planes (a `(16, n)` array, `layout="planar"`). (The planes' 16 slices make that variant
/// 256 bytes; a target is made once per chunk, so its size does not matter.)
#[allow(clippy::large_enum_variant)]
pub(crate) enum Target<'a, T> {
    Rows(&'a mut [[T; 16]]),
    Planes(Planes<'a, T>),
}

impl<T: Send> Split for Target<'_, T> {
    fn len(&self) -> usize {
        match self {
            Target::Rows(r) => r.len(),
            Target::Planes(p) => p.len(),
        }
    }
    fn split_at(self, mid: usize) -> (Self, Self) {
        match self {
            Target::Rows(r) => {
                let (a, b) = r.split_at_mut(mid);
                (Target::Rows(a), Target::Rows(b))
            }
            Target::Planes(p) => {
                let (a, b) = p.split_at(mid);
                (Target::Planes(a), Target::Planes(b))
            }
        }
    }
}

impl<T> Target<'_, T> {
    /// Fills the target through `store`; as [`Store::store`].
    pub(crate) fn store(
        self,
        store: &impl Store<T>,
        k: &Kernel<'_>,
        batch: &Unvalidated<'_>,
    ) -> Result<bool> {
        match self {
            Target::Rows(r) => store.store(k, batch, r),
            Target::Planes(mut p) => store.store_planes(k, batch, &mut p),
        }
    }
}

/// [`Store`] in float64; `stream`: with non-temporal stores, as the engine writes an output of
/// the whole array's length (`Engine::streams`).
pub(crate) struct StoreF64 {
    stream: bool,
}

impl StoreF64 {
    pub(crate) fn new(m: &Material, n: usize) -> Self {
        Self {
            stream: Engine::new(m).streams(n),
        }
    }
}

impl Store<f64> for StoreF64 {
    fn store(&self, k: &Kernel<'_>, b: &Unvalidated<'_>, rows: &mut [[f64; 16]]) -> Result<bool> {
        if self.stream {
            k.clone().streaming(true).try_mueller_into(b, 0, rows)?;
        } else {
            k.try_mueller_into(b, 0, rows)?;
        }
        Ok(false)
    }
    fn store_planes(
        &self,
        k: &Kernel<'_>,
        b: &Unvalidated<'_>,
        planes: &mut Planes<'_, f64>,
    ) -> Result<bool> {
        k.try_mueller_planes_into(b, 0, planes)?;
        Ok(false)
    }
}

/// [`Store`] in float32; `stream` as [`StoreF64`] (non-temporal stores only where they pay on
/// this CPU: `Kernel::streaming`).
pub(crate) struct StoreF32 {
    stream: bool,
}

impl StoreF32 {
    pub(crate) fn new(m: &Material, n: usize) -> Self {
        Self {
            stream: Engine::new(m).streams(n),
        }
    }
}

impl Store<f32> for StoreF32 {
    fn store(&self, k: &Kernel<'_>, b: &Unvalidated<'_>, rows: &mut [[f32; 16]]) -> Result<bool> {
        if self.stream {
            k.clone().streaming(true).try_mueller_f32_into(b, 0, rows)
        } else {
            k.try_mueller_f32_into(b, 0, rows)
        }
    }
    fn store_planes(
        &self,
        k: &Kernel<'_>,
        b: &Unvalidated<'_>,
        planes: &mut Planes<'_, f32>,
    ) -> Result<bool> {
        k.try_mueller_planes_f32_into(b, 0, planes)
    }
}

/// A caller's output array for `n` pBRDFs: an `(n, 16)` (or, planar, `(16, n)`) C-contiguous,
/// writeable array of the precision's dtype (the Python layer checks the user's array and
/// passes this view of it).
pub(crate) fn out_rows<'py, T: numpy::Element>(
    out: &Bound<'py, PyAny>,
    shape: [usize; 2],
    dtype: &str,
) -> PyResult<Bound<'py, PyArray2<T>>> {
    let [a0, a1] = shape;
    let a = out.cast::<PyArray2<T>>().map_err(|_| {
        PyValueError::new_err(format!(
            "`out` must be a 2-D {dtype} array of shape ({a0}, {a1})"
        ))
    })?;
    if a.shape() != shape || !a.is_c_contiguous() {
        return Err(PyValueError::new_err(format!(
            "`out` must be a C-contiguous {dtype} array of shape ({a0}, {a1}), got shape {:?}",
            a.shape()
        )));
    }
    Ok(a.clone())
}

/// The vectors of an `(n, 3)` C-contiguous float64 array.
pub(crate) fn vectors<'a>(
    a: &'a PyReadonlyArray2<'_, f64>,
    name: &str,
) -> PyResult<&'a [[f64; 3]]> {
    let flat = a
        .as_slice()
        .ok()
        .filter(|_| a.shape()[1] == 3)
        .ok_or_else(|| {
            PyValueError::new_err(format!(
                "`{name}` must be a C-contiguous (n, 3) array of vectors, got shape {:?}",
                a.shape()
            ))
        })?;
    Ok(flat.as_chunks::<3>().0)
}

/// A flat argument as a slice (contiguous by construction in the Python layer).
pub(crate) fn flat<'a>(a: &'a PyReadonlyArray1<'_, f64>, name: &str) -> PyResult<&'a [f64]> {
    a.as_slice()
        .map_err(|e| PyValueError::new_err(format!("`{name}` must be a contiguous 1-D array: {e}")))
}

/// Two flat arguments of equal length.
pub(crate) fn flat_pair<'a>(
    a: &'a PyReadonlyArray1<'_, f64>,
    b: &'a PyReadonlyArray1<'_, f64>,
    names: [&'static str; 2],
) -> PyResult<(&'a [f64], &'a [f64])> {
    let (x, y) = (flat(a, names[0])?, flat(b, names[1])?);
    if x.len() != y.len() {
        return Err(PyValueError::new_err(format!(
            "`{}` has {} elements, `{}` {}",
            names[1],
            y.len(),
            names[0],
            x.len()
        )));
    }
    Ok((x, y))
}

/// `n` Stokes vectors as an `(n, 4)` float64 array.
pub(crate) fn stokes_array<'py>(
    py: Python<'py>,
    s: impl Iterator<Item = polbrdf::Stokes>,
    n: usize,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let v: Vec<f64> = s.flat_map(|s| s.0).collect();
    PyArray1::from_vec(py, v).reshape([n, 4])
}
