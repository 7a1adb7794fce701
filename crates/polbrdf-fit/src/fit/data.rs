//! What a fit is given: the measurable quantities, one measured value, and the checks of a data
//! set before and after a fit (values that could overflow χ², degenerate data).

use crate::error::FitError;
use polbrdf::{Evaluation, Geometry, Mueller};

/// A measurable quantity.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Observable {
    /// Scalar BRDF `f = F00` (sr⁻¹).
    Brdf,
    /// DoLP for unpolarized illumination (eq. 13).
    Dolp,
    /// BRDF for s-polarized incidence, no analyzer: `F·(1, 1, 0, 0)` → `F00 + F01` (sr⁻¹).
    BrdfS,
    /// BRDF for p-polarized incidence, no analyzer: `F·(1, −1, 0, 0)` → `F00 − F01` (sr⁻¹).
    BrdfP,
    /// Mueller-matrix BRDF entry `F_ij` (sr⁻¹, psps basis).
    Mueller(usize, usize),
}

impl Observable {
    /// Every quantity, in the order of [`Observable::parse`]'s list: `brdf`, `dolp`, `brdf_s`,
    /// `brdf_p`, `m00` … `m33` (row-major).
    pub fn all() -> Vec<Observable> {
        let mut all = vec![
            Observable::Brdf,
            Observable::Dolp,
            Observable::BrdfS,
            Observable::BrdfP,
        ];
        all.extend((0..16).map(|k| Observable::Mueller(k / 4, k % 4)));
        all
    }

    /// From a column name: `brdf`, `dolp`, `brdf_s`, `brdf_p`, `m00` … `m33`.
    pub fn parse(name: &str) -> Option<Self> {
        match name {
            "brdf" => Some(Observable::Brdf),
            "dolp" => Some(Observable::Dolp),
            "brdf_s" => Some(Observable::BrdfS),
            "brdf_p" => Some(Observable::BrdfP),
            _ => Mueller::entry_of(name).map(|(i, j)| Observable::Mueller(i, j)),
        }
    }

    /// The column name.
    pub fn name(&self) -> String {
        match self {
            Observable::Brdf => "brdf".into(),
            Observable::Dolp => "dolp".into(),
            Observable::BrdfS => "brdf_s".into(),
            Observable::BrdfP => "brdf_p".into(),
            // An entry outside the matrix (no quantity of a file) is named as it is.
            Observable::Mueller(i, j) if *i < 4 && *j < 4 => Mueller::COLUMNS[4 * i + j].into(),
            Observable::Mueller(i, j) => format!("entry ({i}, {j}) outside the 4×4 matrix"),
        }
    }

    /// Whether the quantity needs more of `F` than `F00` and the DoLP.
    pub fn needs_matrix(&self) -> bool {
        !matches!(self, Observable::Brdf | Observable::Dolp)
    }

    /// The model's value of this quantity.
    pub fn of(&self, e: &Evaluation) -> f64 {
        self.of_pbrdf(&e.pbrdf)
    }

    /// This quantity of a pBRDF `F`: `F00`, the DoLP of `F·(1, 0, 0, 0)`, `F00 ± F01` or `F_ij`
    /// (psps basis: `(1, 1, 0, 0)` is s-polarized, docs/model.md §2).
    pub fn of_pbrdf(&self, f: &Mueller) -> f64 {
        match *self {
            Observable::Brdf => f.m00(),
            Observable::Dolp => f.dolp_unpolarized(),
            Observable::BrdfS => f.m00() + f[(0, 1)],
            Observable::BrdfP => f.m00() - f[(0, 1)],
            Observable::Mueller(i, j) => f[(i, j)],
        }
    }
}

/// One measured value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Measurement {
    /// Where it was measured.
    pub geometry: Geometry,
    /// What was measured.
    pub observable: Observable,
    /// The value.
    pub value: f64,
    /// Its 1-σ uncertainty, if known (> 0).
    pub sigma: Option<f64>,
    /// The vacuum wavelength (µm), when the data are spectral: a material with a spectral
    /// index is evaluated with its index there.
    pub wavelength_um: Option<f64>,
}

/// Refuses a measurement whose `|value/σ|` (σ = 1 when none is given) exceeds
/// [`crate::MAX_WEIGHTED_VALUE`], where its squared residual could overflow χ²: such a value
/// is an outlier or a unit error in the data (checked by [`fit`](super::fit) before anything
/// else).
///
/// # Errors
/// [`FitError::DataOutOfRange`] naming the first such measurement by its index in `data`.
pub fn check_measurements(data: &[Measurement]) -> Result<(), FitError> {
    for (index, d) in data.iter().enumerate() {
        let sigma = d.sigma.unwrap_or(1.0);
        let w = d.value / sigma;
        if !w.is_finite() || w.abs() > crate::MAX_WEIGHTED_VALUE {
            return Err(FitError::DataOutOfRange {
                index,
                observable: d.observable.name(),
                value: d.value,
                sigma,
            });
        }
    }
    Ok(())
}

/// Warnings about data that cannot give meaningful uncertainties: fewer distinct measurements
/// (geometry, wavelength and observable) than free parameters + 1 — e.g. one row repeated — so
/// that the fit is exactly determined and χ², the residual scaling and the covariance say
/// nothing about the parameters' uncertainty.
pub(super) fn degenerate_data_warnings(data: &[Measurement], free: usize) -> Vec<String> {
    let key = |d: &Measurement| {
        let g = d.geometry;
        (
            [g.theta_i(), g.phi_i(), g.theta_r(), g.phi_r()].map(f64::to_bits),
            d.wavelength_um.map(f64::to_bits),
            d.observable.name(),
        )
    };
    let distinct: std::collections::HashSet<_> = data.iter().map(key).collect();
    let geometries: std::collections::HashSet<_> = data.iter().map(|d| key(d).0).collect();
    let mut w = Vec::new();
    if distinct.len() <= free {
        w.push(format!(
            "the {} measurement(s) hold only {} distinct one(s) (same geometry, wavelength and \
             quantity repeated) for {free} free parameter(s): the fit is exactly determined and \
             the uncertainties are not meaningful",
            data.len(),
            distinct.len()
        ));
    } else if geometries.len() == 1 && data.len() > 1 {
        w.push(
            "every measurement is at the same geometry: the parameters are determined by that \
             one geometry only, and their correlations and uncertainties may not be meaningful"
                .to_string(),
        );
    }
    w
}
