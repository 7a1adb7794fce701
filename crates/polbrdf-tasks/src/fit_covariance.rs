//! A fitted material's parameters and their covariance, as a detection study takes them
//! (docs/detection.md, "Uncertainty of the range"): from a `fit.json` written by `polbrdf fit`
//! ([`FitCovariance::read`]) or from a [`FitResult`] ([`FitCovariance::from_fit`]), checked
//! against the material they are the covariance of ([`FitCovariance::check_material`]).
//!
//! A parameter at the lower bound of its domain has no covariance (`null` in `fit.json`, NaN in
//! a `FitResult`): it is held fixed, and listed. Any other missing, non-finite or inconsistent
//! entry (a negative variance, an asymmetric matrix, a correlation beyond ±1) is refused.

use crate::{TaskError, TaskResult};
use polbrdf::MaterialSpec;
use polbrdf_fit::{Bound, FitResult, Param};
use serde_json::Value;
use std::path::{Path, PathBuf};

/// Relative agreement required between a fit's value and the material's (the value written to
/// `fit.json` and to `--material-out` both round-trip exactly; 1e-12 leaves room for a value
/// typed with fewer digits than it was printed with, not for another material).
pub const VALUE_TOLERANCE: f64 = 1e-12;

/// Relative tolerance of the covariance's symmetry and of its correlations' `|ρ| ≤ 1`.
const MATRIX_TOLERANCE: f64 = 1e-9;

/// A fitted material's free parameters, their values and covariance.
#[derive(Debug, Clone, PartialEq)]
pub struct FitCovariance {
    /// Where it comes from: the `fit.json`, or `<FitResult>` (for messages).
    pub source: PathBuf,
    /// The parameters with a covariance, in the fit's order.
    pub params: Vec<Param>,
    /// Their fitted values.
    pub values: Vec<f64>,
    /// Their covariance, row-major `n × n`.
    pub covariance: Vec<f64>,
    /// The fit's parameters at a bound (no covariance; held fixed), with their values.
    pub held_fixed: Vec<(Param, f64)>,
}

/// A fit's parameter before the split into free and held fixed.
struct Entry {
    param: Param,
    value: f64,
    at_bound: bool,
}

fn file_error(path: &Path, message: String) -> TaskError {
    TaskError::Io(polbrdf_io::Error::File {
        path: path.to_path_buf(),
        message,
    })
}

impl FitCovariance {
    /// Reads a `fit.json` of `polbrdf fit` (one fit, not a per-wavelength one).
    ///
    /// # Errors
    /// [`TaskError::Io`]: the file cannot be read ([`polbrdf_io::Error::Read`]), is not JSON
    /// (naming its line), or lacks or has a bad `parameter_order`, `parameters.<name>.value`
    /// or `covariance` entry (naming the key).
    pub fn read(path: &Path) -> TaskResult<Self> {
        let text = std::fs::read_to_string(path).map_err(|source| polbrdf_io::Error::Read {
            path: path.to_path_buf(),
            source,
        })?;
        Self::parse(&text, path)
    }

    /// Parses the text of a `fit.json`, read from `path` (for messages).
    ///
    /// # Errors
    /// As [`FitCovariance::read`].
    pub fn parse(text: &str, path: &Path) -> TaskResult<Self> {
        let doc: Value = serde_json::from_str(text).map_err(|e| polbrdf_io::Error::Syntax {
            path: path.to_path_buf(),
            line: e.line().max(1),
            message: format!("not valid JSON: {e}"),
        })?;
        let bad = |key: &str, what: &str| {
            file_error(
                path,
                format!("`{key}`: {what} (expected the fit.json of one `polbrdf fit`)"),
            )
        };
        let order = doc
            .get("parameter_order")
            .and_then(Value::as_array)
            .ok_or_else(|| bad("parameter_order", "missing or not a list"))?;
        let mut entries = Vec::with_capacity(order.len());
        for name in order {
            let name = name
                .as_str()
                .ok_or_else(|| bad("parameter_order", "a name is not a string"))?;
            let param = Param::parse(name).map_err(|e| bad("parameter_order", &e.to_string()))?;
            let key = format!("parameters.{name}.value");
            let entry = doc.get("parameters").and_then(|p| p.get(name));
            let value = entry
                .and_then(|e| e.get("value"))
                .and_then(Value::as_f64)
                .ok_or_else(|| bad(&key, "missing or not a number"))?;
            let at_bound = entry
                .and_then(|e| e.get("bound"))
                .and_then(Value::as_str)
                .is_some_and(|b| b != "interior");
            entries.push(Entry {
                param,
                value,
                at_bound,
            });
        }
        let rows = doc
            .get("covariance")
            .and_then(Value::as_array)
            .ok_or_else(|| bad("covariance", "missing or not a list of rows"))?;
        let n = entries.len();
        let mut cov = Vec::with_capacity(n * n);
        if rows.len() != n {
            return Err(bad(
                "covariance",
                &format!("{} rows for {n} parameter(s)", rows.len()),
            ));
        }
        for (i, row) in rows.iter().enumerate() {
            let row = row
                .as_array()
                .filter(|r| r.len() == n)
                .ok_or_else(|| bad(&format!("covariance[{i}]"), &format!("not {n} values")))?;
            for (j, v) in row.iter().enumerate() {
                cov.push(match v {
                    Value::Null => f64::NAN,
                    v => v.as_f64().ok_or_else(|| {
                        bad(&format!("covariance[{i}][{j}]"), "not a number or null")
                    })?,
                });
            }
        }
        Self::new(path, entries, cov)
    }

    /// The covariance of a fit's result.
    ///
    /// # Errors
    /// As [`FitCovariance::read`], naming `<FitResult>`.
    pub fn from_fit(r: &FitResult) -> TaskResult<Self> {
        let entries = r
            .params
            .iter()
            .zip(&r.values)
            .zip(&r.bounds)
            .map(|((p, v), b)| Entry {
                param: *p,
                value: *v,
                at_bound: !matches!(b, Bound::Interior),
            })
            .collect();
        let n = r.params.len();
        if r.covariance.len() != n || r.covariance.iter().any(|row| row.len() != n) {
            return Err(file_error(
                Path::new("<FitResult>"),
                format!("`covariance`: not {n} × {n}"),
            ));
        }
        Self::new(Path::new("<FitResult>"), entries, r.covariance.concat())
    }

    /// Splits the parameters at a bound off and checks the rest's covariance.
    fn new(source: &Path, entries: Vec<Entry>, cov: Vec<f64>) -> TaskResult<Self> {
        let n = entries.len();
        let bad = |key: String, what: String| file_error(source, format!("`{key}`: {what}"));
        let free: Vec<usize> = (0..n).filter(|&i| !entries[i].at_bound).collect();
        for (i, e) in entries.iter().enumerate() {
            if !e.value.is_finite() {
                let name = e.param.name();
                return Err(bad(format!("parameters.{name}.value"), "not finite".into()));
            }
            if entries[..i].iter().any(|o| o.param == e.param) {
                return Err(bad(
                    "parameter_order".into(),
                    format!("`{}` is listed twice", e.param.name()),
                ));
            }
        }
        for &i in &free {
            for &j in &free {
                let (c, t) = (cov[i * n + j], cov[j * n + i]);
                let key = format!("covariance[{i}][{j}]");
                if !c.is_finite() {
                    return Err(bad(
                        key,
                        format!(
                            "{c}: not finite, but `{}` and `{}` are not at a bound",
                            entries[i].param.name(),
                            entries[j].param.name()
                        ),
                    ));
                }
                let scale = (cov[i * n + i] * cov[j * n + j]).abs().sqrt();
                if i == j && c < 0.0 {
                    return Err(bad(key, format!("{c}: a variance must be ≥ 0")));
                }
                if (c - t).abs() > MATRIX_TOLERANCE * scale {
                    return Err(bad(
                        key,
                        format!("{c} ≠ covariance[{j}][{i}] = {t}: not symmetric"),
                    ));
                }
                if c.abs() > (1.0 + MATRIX_TOLERANCE) * scale {
                    return Err(bad(
                        key,
                        format!("{c}: a correlation beyond ±1 (not a covariance)"),
                    ));
                }
            }
        }
        Ok(Self {
            source: source.to_path_buf(),
            params: free.iter().map(|&i| entries[i].param).collect(),
            values: free.iter().map(|&i| entries[i].value).collect(),
            covariance: free
                .iter()
                .flat_map(|&i| free.iter().map(move |&j| (i, j)))
                .map(|(i, j)| cov[i * n + j])
                .collect(),
            held_fixed: entries
                .iter()
                .filter(|e| e.at_bound)
                .map(|e| (e.param, e.value))
                .collect(),
        })
    }

    /// Checks that `spec` (the `role` material, given as `given`) is the fitted material: every
    /// parameter of the fit has the fit's value in it (to [`VALUE_TOLERANCE`] relative).
    ///
    /// # Errors
    /// [`TaskError::Io`] naming this fit's source and the parameter's key.
    pub fn check_material(&self, spec: &MaterialSpec, role: &str, given: &str) -> TaskResult<()> {
        let all = self
            .params
            .iter()
            .zip(&self.values)
            .chain(self.held_fixed.iter().map(|(p, v)| (p, v)));
        for (p, v) in all {
            let mine = p.value(spec).ok().filter(|m| m.is_finite());
            let agrees = mine.is_some_and(|m| (m - v).abs() <= VALUE_TOLERANCE * v.abs().max(1.0));
            if !agrees {
                let name = p.name();
                return Err(file_error(
                    &self.source,
                    format!(
                        "`parameters.{name}.value` = {v} of the fit, but the {role} material \
                         ({given}) has `{name}` = {}: the covariance is of another material or \
                         parameter set (give the fitted material, `polbrdf fit --material-out`, \
                         as the {role})",
                        mine.map_or("no value".to_string(), |m| m.to_string())
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The standard deviation of each parameter.
    pub fn sigmas(&self) -> Vec<f64> {
        let n = self.params.len();
        (0..n).map(|i| self.covariance[i * n + i].sqrt()).collect()
    }
}
