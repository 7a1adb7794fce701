//! Bridges to other tools' conventions (`polbrdf::geometry::bridges`, docs/bridges.md) over flat
//! arrays: the Python layer (`polbrdf.bridges`) broadcasts and stacks the arguments into rows,
//! this calls the core once per row.

use numpy::{PyArray2, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods};
use polbrdf::geometry::bridges as b;
use polbrdf::{Geometry, Mueller, Stokes};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// One conversion: the widths of its value and angle rows and of its result row.
struct Op {
    values: usize,
    angles: usize,
    out: usize,
}

fn op(name: &str) -> PyResult<Op> {
    let (values, angles, out) = match name {
        "to_scatmech" => (0, 4, 3),
        "from_scatmech" => (0, 3, 4),
        "camera_roll" => (3, 2, 1),
        "stokes_to_camera" | "stokes_from_camera" | "stokes_to_polanalyser" => (4, 1, 4),
        "aolp_to_polanalyser" => (0, 2, 1),
        "mueller_to_mitsuba" | "mueller_from_mitsuba" => (16, 4, 16),
        "stokes_to_mitsuba" => (4, 4, 4),
        "mitsuba_stokes_basis" => (3, 0, 3),
        _ => return Err(PyValueError::new_err(format!("unknown bridge `{name}`"))),
    };
    Ok(Op {
        values,
        angles,
        out,
    })
}

fn rows<'a>(a: &'a PyReadonlyArray2<'_, f64>, width: usize, what: &str) -> PyResult<&'a [f64]> {
    a.as_slice()
        .ok()
        .filter(|_| a.shape()[1] == width)
        .ok_or_else(|| {
            PyValueError::new_err(format!(
                "{what} must be a C-contiguous (n, {width}) array, got shape {:?}",
                a.shape()
            ))
        })
}

fn geometry(a: &[f64], degrees: bool) -> polbrdf::Result<Geometry> {
    if degrees {
        Geometry::from_degrees(a[0], a[1], a[2], a[3])
    } else {
        Geometry::new(a[0], a[1], a[2], a[3])
    }
}

fn matrix(v: &[f64]) -> Mueller {
    Mueller(std::array::from_fn(|i| {
        std::array::from_fn(|j| v[4 * i + j])
    }))
}

fn stokes(v: &[f64]) -> Stokes {
    Stokes::new(v[0], v[1], v[2], v[3])
}

/// Row `v` (values) and `a` (angles, radians unless stated) of `name` into `out`.
fn convert(
    name: &str,
    v: &[f64],
    a: &[f64],
    degrees: bool,
    y: b::ImageY,
    out: &mut [f64],
) -> polbrdf::Result<()> {
    let rad = |x: f64| if degrees { x.to_radians() } else { x };
    let unit = |x: f64| if degrees { x.to_degrees() } else { x };
    match name {
        // The angles stay in the unit given (no round trip through radians): validated as a
        // geometry, θ passed through, φs by the core's rule in that unit.
        "to_scatmech" => {
            geometry(a, degrees)?;
            let half_turn = unit(std::f64::consts::PI);
            out.copy_from_slice(&[a[0], a[2], b::scatmech_phi_s(a[1], a[3], half_turn)]);
        }
        "from_scatmech" => {
            b::from_scatmech(rad(a[0]), rad(a[1]), rad(a[2]))?;
            out.copy_from_slice(&[a[0], unit(std::f64::consts::PI), a[1], a[2]]);
        }
        "camera_roll" => {
            let g = geometry(&[0.0, 0.0, a[0], a[1]], degrees)?;
            out[0] = unit(b::camera_roll(&g, [v[0], v[1], v[2]])?);
        }
        "stokes_to_camera" => out.copy_from_slice(&b::stokes_to_camera(&stokes(v), rad(a[0])).0),
        "stokes_from_camera" => {
            out.copy_from_slice(&b::stokes_from_camera(&stokes(v), rad(a[0])).0);
        }
        "stokes_to_polanalyser" => {
            out.copy_from_slice(&b::stokes_to_polanalyser(&stokes(v), rad(a[0]), y).0);
        }
        "aolp_to_polanalyser" => out[0] = b::aolp_to_polanalyser(rad(a[0]), rad(a[1]), y),
        "mueller_to_mitsuba" | "mueller_from_mitsuba" => {
            let g = geometry(a, degrees)?;
            let m = if name == "mueller_to_mitsuba" {
                b::mueller_to_mitsuba(&matrix(v), &g)
            } else {
                b::mueller_from_mitsuba(&matrix(v), &g)
            };
            out.copy_from_slice(m.0.as_flattened());
        }
        "stokes_to_mitsuba" => {
            let g = geometry(a, degrees)?;
            out.copy_from_slice(&b::stokes_to_mitsuba(&stokes(v), &g).0);
        }
        _ => out.copy_from_slice(&b::mitsuba_stokes_basis([v[0], v[1], v[2]])),
    }
    Ok(())
}

/// The bridge `name` applied row by row: `values` `(n, w_v)` and `angles` `(n, w_a)` (in degrees
/// when `degrees`) to an `(n, w_out)` array. A bad row raises `ValueError` naming its position.
#[pyfunction]
#[pyo3(signature = (name, values, angles, degrees, y_down))]
pub(crate) fn bridge_flat<'py>(
    py: Python<'py>,
    name: &str,
    values: PyReadonlyArray2<'py, f64>,
    angles: PyReadonlyArray2<'py, f64>,
    degrees: bool,
    y_down: bool,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let o = op(name)?;
    let n = values.shape()[0];
    if angles.shape()[0] != n {
        return Err(PyValueError::new_err(format!(
            "{n} value rows but {} angle rows",
            angles.shape()[0]
        )));
    }
    let (v, a) = (
        rows(&values, o.values, "values")?,
        rows(&angles, o.angles, "angles")?,
    );
    let y = if y_down {
        b::ImageY::Down
    } else {
        b::ImageY::Up
    };
    let out = crate::buffers::zeros2::<f64>(py, n, o.out)?;
    {
        let mut w = out.readwrite();
        let dst = w.as_slice_mut()?;
        for i in 0..n {
            let vi = &v[i * o.values..(i + 1) * o.values];
            let ai = &a[i * o.angles..(i + 1) * o.angles];
            convert(
                name,
                vi,
                ai,
                degrees,
                y,
                &mut dst[i * o.out..(i + 1) * o.out],
            )
            .map_err(|e| PyValueError::new_err(format!("element {i}: {e}")))?;
        }
    }
    Ok(out)
}
