//! Errors: the core's and `polbrdf-io`'s errors as Python exceptions.

use pyo3::exceptions::{
    PyFileNotFoundError, PyIsADirectoryError, PyOSError, PyPermissionError, PyValueError,
};
use pyo3::prelude::*;

/// A core error as a `ValueError` carrying the core's message. For a bad angle of a batch (and a
/// wavelength of a batch outside a spectral index's data) the exception also gets the
/// attributes `index` (flat position) and `argument` (`theta_i`, …, `wavelength_um`), which the
/// Python layer turns into a position in the broadcast shape.
pub(crate) fn core_err(py: Python<'_>, e: &polbrdf::Error) -> PyErr {
    let err = PyValueError::new_err(e.to_string());
    let located = match e {
        polbrdf::Error::InvalidAngle { name, index, .. } => Some((python_name(name), *index)),
        polbrdf::Error::InvalidDirection { name, index, .. } => Some((*name, *index)),
        polbrdf::Error::WavelengthOutOfRange {
            position: Some(i), ..
        } => Some(("wavelength_um", Some(*i))),
        _ => None,
    };
    if let Some((argument, index)) = located {
        let value = err.value(py);
        // Setting attributes on a fresh ValueError cannot fail; ignore it if it ever does.
        let _ = value.setattr("argument", argument);
        if let Some(i) = index {
            let _ = value.setattr("index", i);
        }
    }
    err
}

/// As [`core_err`] for an error about one element of the flat arrays handed over by the Python
/// layer: a [`polbrdf::Error::InvalidParameterAt`] also gets `argument` and `index` (its
/// position in those arrays). Not for positions in other tables (a band, a sky profile).
pub(crate) fn element_err(py: Python<'_>, e: &polbrdf::Error) -> PyErr {
    let err = core_err(py, e);
    if let polbrdf::Error::InvalidParameterAt { name, index, .. } = e {
        let value = err.value(py);
        let _ = value.setattr("argument", *name);
        let _ = value.setattr("index", *index);
    }
    err
}

/// A `polbrdf-io` error: reading failures become the matching `OSError` subclass, everything
/// else (syntax, unknown key, bad value) a `ValueError`. The message names file and line.
pub(crate) fn io_err(e: &polbrdf_io::Error) -> PyErr {
    let msg = e.to_string();
    match e {
        polbrdf_io::Error::Read { source, .. } | polbrdf_io::Error::Write { source, .. } => {
            os_err(source.kind(), msg)
        }
        _ => PyValueError::new_err(msg),
    }
}

pub(crate) fn os_err(kind: std::io::ErrorKind, msg: String) -> PyErr {
    use std::io::ErrorKind;
    match kind {
        ErrorKind::NotFound => PyFileNotFoundError::new_err(msg),
        ErrorKind::PermissionDenied => PyPermissionError::new_err(msg),
        ErrorKind::IsADirectory => PyIsADirectoryError::new_err(msg),
        _ => PyOSError::new_err(msg),
    }
}

/// The Python argument that a core angle name stands for (`theta_i_deg` → `theta_i`).
pub(crate) fn python_name(core: &'static str) -> &'static str {
    ["theta_i", "phi_i", "theta_r", "phi_r"]
        .into_iter()
        .find(|n| core.strip_suffix("_deg") == Some(n) || core == *n)
        .unwrap_or(core)
}

/// Raises each unit warning of polbrdf-io (`units`: a valid value in a probably wrong unit) as a
/// Python `UserWarning`, attributed to the caller's line. An error only if a warnings filter
/// turned the warning into an exception.
pub(crate) fn warn_units(py: Python<'_>, warnings: &[polbrdf_io::UnitWarning]) -> PyResult<()> {
    let category = py.get_type::<pyo3::exceptions::PyUserWarning>();
    for w in warnings {
        // The messages are ours and hold no NUL; one would only shorten the text.
        let text = std::ffi::CString::new(w.message.replace('\0', " ")).unwrap_or_default();
        PyErr::warn(py, category.as_any(), &text, 1)?;
    }
    Ok(())
}
