//! Fits of measurements: the measurements of a measurement table assembled for the fitter
//! ([`measurements`]), and the `fit.json` document of a fit ([`to_json`], its contract is in
//! the README). The fitting itself is `polbrdf_fit`'s.

use crate::TaskResult;
use polbrdf_fit::{Bound, FitResult, Measurement, Observable};
use polbrdf_io::MeasurementTable;
use serde_json::{json, Map, Value};
use std::path::Path;

/// The measurements of `table`, one per measured cell, in file order; a value too large for
/// a least-squares fit is refused with its file, line and column.
///
/// # Errors
/// [`crate::TaskError::Io`] ([`polbrdf_io::Error::Field`]) naming the cell.
pub fn measurements(table: &MeasurementTable) -> TaskResult<Vec<Measurement>> {
    let mut data = Vec::new();
    // The line and column of each measurement, for messages about the data.
    let mut at = Vec::new();
    for (row, g) in table.geometries.iter().enumerate() {
        for col in &table.columns {
            let Some(value) = col.values[row] else {
                continue;
            };
            data.push(Measurement {
                geometry: *g,
                observable: Observable::parse(&col.name).expect("measurable column names parse"),
                value,
                sigma: col.sigmas.as_ref().and_then(|s| s[row]),
                wavelength_um: table.wavelengths.as_ref().map(|w| w[row]),
            });
            at.push((table.lines[row], col.name.as_str()));
        }
    }
    if let Err(polbrdf_fit::FitError::DataOutOfRange {
        index,
        value,
        sigma,
        ..
    }) = polbrdf_fit::check_measurements(&data)
    {
        let (line, field) = at[index];
        return Err(polbrdf_io::Error::Field {
            path: table.path.clone(),
            line,
            field: field.to_string(),
            message: format!(
                "{value:e} (σ = {sigma}) is too large for a least-squares fit: |value/σ| > \
                 {:e} makes χ² overflow (an outlier or a unit error?)",
                polbrdf_fit::MAX_WEIGHTED_VALUE
            ),
        }
        .into());
    }
    Ok(data)
}

fn matrix(m: &[Vec<f64>]) -> Value {
    Value::from(m.to_vec())
}

/// One parameter's entry of `fit.json`.
fn parameter(r: &FitResult, k: usize) -> Value {
    match &r.bounds[k] {
        Bound::Interior => {
            json!({"value": r.values[k], "stderr": r.stderr[k], "bound": "interior"})
        }
        Bound::AtLowerBound {
            upper_limit_95,
            correlation_at_limit,
        } => {
            let corr: Option<Map<String, Value>> = correlation_at_limit.as_ref().map(|c| {
                r.params
                    .iter()
                    .zip(c)
                    .map(|(q, v)| (q.name().to_string(), Value::from(*v)))
                    .collect()
            });
            json!({"value": r.values[k], "stderr": null, "bound": "lower",
                   "upper_limit_95": upper_limit_95, "correlation_at_limit": corr})
        }
    }
}

/// The `fit.json` document of a fit to the data of `data` (contract in the README).
pub fn to_json(r: &FitResult, data: &Path) -> Value {
    let params: Map<String, Value> = r
        .params
        .iter()
        .enumerate()
        .map(|(k, p)| (p.name().to_string(), parameter(r, k)))
        .collect();
    let zbs = r.zero_bistatic.as_ref().map(|z| {
        json!({"a": z.a, "stderr_a": z.stderr_a, "b": z.b, "stderr_b": z.stderr_b,
               "correlation_ab": z.correlation_ab, "points_used": z.samples.len(),
               "points_excluded": z.excluded})
    });
    json!({
        "parameters": params,
        "parameter_order": r.params.iter().map(|p| p.name()).collect::<Vec<_>>(),
        "covariance": matrix(&r.covariance),
        "correlation": matrix(&r.correlation),
        "chi2": r.chi2,
        "reduced_chi2": r.reduced_chi2,
        "dof": r.dof,
        "uncertainty_from_residuals": r.scaled_by_residuals,
        "converged": r.converged,
        "iterations": r.iterations,
        "message": r.message,
        "starts": {"tried": r.starts.0, "reached_best": r.starts.1},
        "zero_bistatic": zbs,
        "data": data.display().to_string(),
        "measurements": r.residuals.len(),
        "warnings": r.warnings,
    })
}
