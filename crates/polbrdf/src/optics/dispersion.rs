//! Spectral refractive indices `N(λ) = n(λ) + i·k(λ)` (docs/model.md §15): tables interpolated
//! linearly in λ, n and k separately, and the dispersion formulas 1–9 of the refractiveindex.info
//! database (its document "Dispersion formulas"), with λ in µm. A wavelength outside the data is
//! an error naming the material and the range — never an extrapolation.
//!
//! Reading the database's YAML files is `polbrdf-io`'s job; this module only evaluates.

use crate::error::{Error, Result};
use crate::optics::fresnel::RefractiveIndex;

/// One quantity (n or k) as a function of the vacuum wavelength λ (µm).
#[derive(Debug, Clone, PartialEq)]
pub enum Dispersion {
    /// Values at strictly increasing wavelengths, interpolated linearly between them (exact at
    /// the nodes); defined on `[λ_first, λ_last]`.
    Table {
        /// Wavelengths (µm), strictly increasing.
        wavelengths: Vec<f64>,
        /// The quantity at each wavelength.
        values: Vec<f64>,
    },
    /// Formula `kind` (1–9) of the refractiveindex.info database with coefficients
    /// `C1, C2, …` (`coefficients[0]` is C1), valid on `range` (µm).
    Formula {
        /// 1 Sellmeier, 2 Sellmeier-2, 3 polynomial, 4 RefractiveIndex.INFO, 5 Cauchy,
        /// 6 gases, 7 Herzberger, 8 retro, 9 exotic.
        kind: u8,
        /// C1, C2, … (missing ones are 0).
        coefficients: Vec<f64>,
        /// `(λ_min, λ_max)` in µm.
        range: (f64, f64),
    },
}

impl Dispersion {
    /// The wavelength range (µm) on which it is defined.
    pub fn range(&self) -> (f64, f64) {
        match self {
            Dispersion::Table { wavelengths, .. } => (
                wavelengths.first().copied().unwrap_or(f64::NAN),
                wavelengths.last().copied().unwrap_or(f64::NAN),
            ),
            Dispersion::Formula { range, .. } => *range,
        }
    }

    /// The value at `lambda_um`, `None` outside the range.
    pub fn eval(&self, lambda_um: f64) -> Option<f64> {
        let (lo, hi) = self.range();
        if !(lambda_um >= lo && lambda_um <= hi) {
            return None;
        }
        Some(match self {
            Dispersion::Table {
                wavelengths,
                values,
            } => interpolate(wavelengths, values, lambda_um),
            Dispersion::Formula {
                kind, coefficients, ..
            } => formula(*kind, coefficients, lambda_um),
        })
    }
}

/// Linear interpolation of `(x, y)` at `x0` (`x` strictly increasing, `x0` within it); exact at
/// the nodes.
fn interpolate(x: &[f64], y: &[f64], x0: f64) -> f64 {
    let i = x.partition_point(|&v| v <= x0);
    if i == 0 {
        return y[0];
    }
    if i == x.len() {
        return y[x.len() - 1];
    }
    let (x1, x2, y1, y2) = (x[i - 1], x[i], y[i - 1], y[i]);
    if x0 == x1 {
        return y1;
    }
    y1 + (y2 - y1) * ((x0 - x1) / (x2 - x1))
}

/// The refractiveindex.info dispersion formulas, λ in µm, `c[0]` = C1 (missing coefficients are
/// 0). For 1–4, 8 and 9 the formula gives n², and n is its square root (NaN where n² < 0).
///
/// 1. Sellmeier: `n² − 1 = C1 + Σ C_i λ²/(λ² − C_{i+1}²)`, i = 2, 4, …
/// 2. Sellmeier-2: `n² − 1 = C1 + Σ C_i λ²/(λ² − C_{i+1})`
/// 3. Polynomial: `n² = C1 + Σ C_i λ^C_{i+1}`
/// 4. RefractiveIndex.INFO: `n² = C1 + C2 λ^C3/(λ² − C4^C5) + C6 λ^C7/(λ² − C8^C9)
///    + Σ_{i ≥ 10} C_i λ^C_{i+1}`
/// 5. Cauchy: `n = C1 + Σ C_i λ^C_{i+1}`
/// 6. Gases: `n − 1 = C1 + Σ C_i/(C_{i+1} − λ⁻²)`
/// 7. Herzberger: `n = C1 + C2/(λ² − 0.028) + C3/(λ² − 0.028)² + C4 λ² + C5 λ⁴ + C6 λ⁶`
/// 8. Retro: `(n² − 1)/(n² + 2) = C1 + C2 λ²/(λ² − C3) + C4 λ²`
/// 9. Exotic: `n² = C1 + C2/(λ² − C3) + C4 (λ − C5)/((λ − C5)² + C6)`
pub fn formula(kind: u8, c: &[f64], lambda_um: f64) -> f64 {
    let l = lambda_um;
    let l2 = l * l;
    let at = |i: usize| c.get(i).copied().unwrap_or(0.0);
    // Pairs (C_i, C_{i+1}) from 1-based index `first` on.
    let pairs = |first: usize| (first..c.len()).step_by(2).map(move |i| (at(i - 1), at(i)));
    match kind {
        1 => (1.0 + at(0) + pairs(2).map(|(a, b)| a * l2 / (l2 - b * b)).sum::<f64>()).sqrt(),
        2 => (1.0 + at(0) + pairs(2).map(|(a, b)| a * l2 / (l2 - b)).sum::<f64>()).sqrt(),
        3 => (at(0) + pairs(2).map(|(a, b)| a * l.powf(b)).sum::<f64>()).sqrt(),
        4 => {
            let mut n2 = at(0);
            for i in [1, 5] {
                if i < c.len() {
                    n2 += at(i) * l.powf(at(i + 1)) / (l2 - at(i + 2).powf(at(i + 3)));
                }
            }
            n2 += (10..=c.len())
                .step_by(2)
                .map(|i| at(i - 1) * l.powf(at(i)))
                .sum::<f64>();
            n2.sqrt()
        }
        5 => at(0) + pairs(2).map(|(a, b)| a * l.powf(b)).sum::<f64>(),
        6 => 1.0 + at(0) + pairs(2).map(|(a, b)| a / (b - 1.0 / l2)).sum::<f64>(),
        7 => {
            let d = l2 - 0.028;
            at(0)
                + at(1) / d
                + at(2) / (d * d)
                + at(3) * l2
                + at(4) * l2 * l2
                + at(5) * l2 * l2 * l2
        }
        8 => {
            let t = at(0) + at(1) * l2 / (l2 - at(2)) + at(3) * l2;
            ((2.0 * t + 1.0) / (1.0 - t)).sqrt()
        }
        9 => {
            let d = l - at(4);
            (at(0) + at(1) / (l2 - at(2)) + at(3) * d / (d * d + at(5))).sqrt()
        }
        _ => f64::NAN,
    }
}

/// A spectral complex index: n(λ) and, when the data give it, k(λ) (else k = 0: the medium is
/// taken as transparent). With the references and comments of its source.
#[derive(Debug, Clone, PartialEq)]
pub struct SpectralIndex {
    /// A name for messages and listings, e.g. `Au/Rakic-LD` or a file name.
    pub name: String,
    /// The real part.
    pub n: Dispersion,
    /// The extinction coefficient; `None` when the source gives none (k = 0).
    pub k: Option<Dispersion>,
    /// The source's references (as given).
    pub references: String,
    /// The source's comments (as given).
    pub comments: String,
}

impl SpectralIndex {
    /// The wavelength range (µm) where both n and (if given) k are defined.
    pub fn range(&self) -> (f64, f64) {
        let (lo, hi) = self.n.range();
        match &self.k {
            Some(k) => {
                let (a, b) = k.range();
                (lo.max(a), hi.min(b))
            }
            None => (lo, hi),
        }
    }

    /// `N(λ)` at `lambda_um`.
    ///
    /// # Errors
    /// [`Error::WavelengthOutOfRange`] naming the material and its range when λ lies outside
    /// the data (or is not finite); [`Error::InvalidParameter`] when the data give an invalid
    /// index there (e.g. a formula with n² < 0).
    pub fn at(&self, lambda_um: f64) -> Result<RefractiveIndex> {
        let (lo, hi) = self.range();
        let out = || Error::WavelengthOutOfRange {
            material: self.name.clone(),
            wavelength_um: lambda_um,
            range: (lo, hi),
            position: None,
        };
        if !(lambda_um >= lo && lambda_um <= hi) {
            return Err(out());
        }
        let n = self.n.eval(lambda_um).ok_or_else(out)?;
        let k = match &self.k {
            Some(k) => k.eval(lambda_um).ok_or_else(out)?,
            None => 0.0,
        };
        RefractiveIndex::new(n, k)
    }
}
