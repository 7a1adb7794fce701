//! `polbrdf._polbrdf`: the compiled half of the Python package `polbrdf`.
//!
//! The Python half (`python/polbrdf/_common.py`) broadcasts the user's angles with NumPy and
//! hands this module four contiguous 1-D float64 arrays of equal length. Everything here works
//! on those flat arrays with the GIL released: in parallel chunks (rayon), each chunk converted
//! from degrees on the stack when needed, validated as a core `polbrdf::GeometryBatch` and evaluated by
//! the core's batch API ([`polbrdf::batch::mueller_into`], [`polbrdf::batch::brdf_dolp_into`]), writing straight
//! into the NumPy output arrays.
//!
//! Thermal emission takes the same road: Planck's law on flat wavelength/temperature arrays
//! (`planck_flat`, `brightness_temperature_flat`), the emissivity Stokes vector per view
//! zenith and wavelength, batched by distinct wavelength and zenith into the core's
//! `analysis::emission::emissivities` (`emissivity_flat`), and the observed Stokes radiance of
//! a thermal scene through `analysis::scene::observed_radiance` (`radiance_flat`).
//!
//! Errors are Python exceptions: the core's `InvalidAngle` / `InvalidParameter` /
//! `InconsistentParameters` / `UnknownPreset` become `ValueError` with the core's message, file
//! errors of `polbrdf-io` become `ValueError` (content) or an `OSError` subclass (reading).
//!
//! One module per concern: `errors` (exceptions), `material` (the `Material` class),
//! `buffers` (flat arrays in, output arrays out), `evaluation` (the pBRDF kernels),
//! `thermal` (Planck, emissivity), `scene` (the observed radiance, scene files), `fit`
//! (fitting), `tasks` (the task layer's jobs: contrast, maps, albedo), `jobs` (check, band
//! emissivity, lookup-table rows, `.pbsdf` tables, measurement files), `bridges` (other
//! tools' conventions: cameras, SCATMECH, Mitsuba), `vocabulary`
//! (the closed sets of names and the defaults, from their Rust
//! sources), `cli` (the `polbrdf` command); this file only registers what they define.

mod bridges;
mod buffers;
mod cli;
mod daytime;
mod detect;
mod errors;
mod evaluation;
mod fit;
mod jobs;
mod material;
mod scene;
mod tasks;
mod thermal;
mod vocabulary;

use pyo3::prelude::*;

/// The compiled part of the `polbrdf` package (import `polbrdf`, not this module).
#[pymodule]
fn _polbrdf(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<material::PyMaterial>()?;
    m.add_function(wrap_pyfunction!(material::_material_from_state, m)?)?;
    m.add_function(wrap_pyfunction!(fit::_fit_result_from_state, m)?)?;
    m.add_function(wrap_pyfunction!(evaluation::mueller_flat, m)?)?;
    m.add_function(wrap_pyfunction!(evaluation::mueller_directions_flat, m)?)?;
    m.add_function(wrap_pyfunction!(evaluation::brdf_dolp_flat, m)?)?;
    m.add_function(wrap_pyfunction!(evaluation::evaluate_flat, m)?)?;
    m.add_function(wrap_pyfunction!(evaluation::index_flat, m)?)?;
    m.add_function(wrap_pyfunction!(fit::derivative_step, m)?)?;
    m.add_function(wrap_pyfunction!(thermal::planck_flat, m)?)?;
    m.add_function(wrap_pyfunction!(thermal::brightness_temperature_flat, m)?)?;
    m.add_function(wrap_pyfunction!(thermal::emissivity_flat, m)?)?;
    m.add_function(wrap_pyfunction!(scene::radiance_flat, m)?)?;
    m.add_function(wrap_pyfunction!(scene::radiance_scene, m)?)?;
    m.add_function(wrap_pyfunction!(scene::read_scene_keys, m)?)?;
    m.add_function(wrap_pyfunction!(vocabulary::vocabulary, m)?)?;
    m.add_function(wrap_pyfunction!(tasks::contrast_task, m)?)?;
    m.add_function(wrap_pyfunction!(tasks::hemisphere_task, m)?)?;
    m.add_function(wrap_pyfunction!(tasks::albedo_task, m)?)?;
    m.add_function(wrap_pyfunction!(jobs::check_task, m)?)?;
    m.add_function(wrap_pyfunction!(jobs::emission_task, m)?)?;
    m.add_function(wrap_pyfunction!(jobs::lut_rows, m)?)?;
    m.add_function(wrap_pyfunction!(jobs::export_pbsdf_task, m)?)?;
    m.add_function(wrap_pyfunction!(jobs::read_pbsdf_task, m)?)?;
    m.add_function(wrap_pyfunction!(jobs::fit_pbsdf_task, m)?)?;
    m.add_function(wrap_pyfunction!(jobs::read_measurements_task, m)?)?;
    m.add_function(wrap_pyfunction!(fit::fit_measurements_task, m)?)?;
    m.add_function(wrap_pyfunction!(tasks::sun_task, m)?)?;
    m.add_function(wrap_pyfunction!(detect::detect_task, m)?)?;
    m.add_function(wrap_pyfunction!(daytime::daytime_task, m)?)?;
    m.add_function(wrap_pyfunction!(bridges::bridge_flat, m)?)?;
    m.add(
        "DEFAULT_DOP_MAX",
        polbrdf::analysis::sky::ClearSky::DEFAULT_DOP_MAX,
    )?;
    // The lookup tables' conventions, owned by the task layer (`polbrdf lut` writes the same).
    m.add("LUT_CONVENTIONS", polbrdf_tasks::lut::CONVENTIONS)?;
    m.add_class::<fit::PyFitResult>()?;
    m.add_function(wrap_pyfunction!(fit::fit_flat, m)?)?;
    m.add_function(wrap_pyfunction!(cli::cli_main, m)?)?;
    Ok(())
}
