//! Zero-bistatic inversion (eq. 5, docs/model.md §7).
//!
//! In backscatter (β = 0, SO = 1, θi = θr = θN = θ) both forms give
//! `f(θ) = R_F(0)·D(θ)/(4cos²θ) + ρ_D + ρ_V/cosθ`, hence
//! `D(θ) = 4cos²θ·(f − ρ_D − ρ_V/cosθ)/R_F(0)` and `ln D = ln a − b·θ²`: a straight line in θ².

use crate::error::FitError;
use polbrdf::RefractiveIndex;

/// One backscatter measurement.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ZbsPoint {
    /// θ = θi = θr (rad).
    pub theta: f64,
    /// Measured BRDF (sr⁻¹).
    pub f: f64,
    /// 1-σ uncertainty of `f`, if known.
    pub sigma: Option<f64>,
}

/// Result of the inversion.
#[derive(Debug, Clone, PartialEq)]
pub struct ZbsFit {
    /// `a` (sr⁻¹).
    pub a: f64,
    /// `b` (rad⁻²).
    pub b: f64,
    /// Standard error of `a` (delta method from `ln a`).
    pub stderr_a: f64,
    /// Standard error of `b`.
    pub stderr_b: f64,
    /// Correlation of the estimates of `a` and `b`.
    pub correlation_ab: f64,
    /// The D(θN) samples used: `(θN (rad), D (sr⁻¹))`.
    pub samples: Vec<(f64, f64)>,
    /// Indices of points not used because `f` does not exceed the volume term (D ≤ 0 has no
    /// logarithm) or, with uncertainties, exceeds it by less than 3σ (the logarithm of a
    /// signal within noise is biased): reported, never silently dropped.
    pub excluded: Vec<usize>,
    /// True when the regression used the given uncertainties; false when it used equal weights
    /// and estimated the scatter from the residuals.
    pub weighted: bool,
}

/// Inverts backscatter measurements for `(a, b)` given the index and the volume constants.
///
/// # Errors
/// [`FitError::ZeroBistatic`] with fewer than 3 usable points or fewer than 2 distinct angles.
pub fn invert(
    points: &[ZbsPoint],
    index: RefractiveIndex,
    rho_d: f64,
    rho_v: f64,
) -> Result<ZbsFit, FitError> {
    let rf0 = index.amplitudes(0.0).reflectance();
    let weighted = !points.is_empty() && points.iter().all(|p| p.sigma.is_some());
    let mut samples = Vec::new();
    let mut excluded = Vec::new();
    // (x = θ², y = ln D, w = 1/σ_y²)
    let mut rows = Vec::new();
    for (i, p) in points.iter().enumerate() {
        let c = p.theta.cos();
        let surface = p.f - rho_d - rho_v / c;
        // The logarithm needs a positive surface signal, and is biased where the signal is
        // within noise: such points are excluded (and reported).
        let snr_too_low = matches!((weighted, p.sigma), (true, Some(s)) if surface < 3.0 * s);
        if surface.is_nan() || surface <= 0.0 || c <= 0.0 || snr_too_low {
            excluded.push(i);
            continue;
        }
        let d = 4.0 * c * c * surface / rf0;
        samples.push((p.theta, d));
        // σ(ln D) = σ_f / (f − ρ_D − ρ_V/cosθ).
        let w = match (weighted, p.sigma) {
            (true, Some(s)) => (surface / s).powi(2),
            _ => 1.0,
        };
        rows.push((p.theta * p.theta, d.ln(), w));
    }
    if rows.len() < 3 {
        return Err(FitError::ZeroBistatic(format!(
            "{} usable backscatter point(s) (of {}); need at least 3 where the BRDF exceeds the volume term",
            rows.len(),
            points.len()
        )));
    }
    let (sw, swx, swy, swxx, swxy) =
        rows.iter()
            .fold((0.0, 0.0, 0.0, 0.0, 0.0), |s, &(x, y, w)| {
                (
                    s.0 + w,
                    s.1 + w * x,
                    s.2 + w * y,
                    s.3 + w * x * x,
                    s.4 + w * x * y,
                )
            });
    let det = sw * swxx - swx * swx;
    if det.is_nan() || det <= 1e-12 * sw * swxx {
        return Err(FitError::ZeroBistatic(
            "the backscatter points need at least 2 distinct angles".into(),
        ));
    }
    let c1 = (sw * swxy - swx * swy) / det;
    let c0 = (swy - c1 * swx) / sw;
    // Covariance of (c0, c1): (XᵀWX)⁻¹, scaled by the residual variance when unweighted.
    let dof = rows.len() as f64 - 2.0;
    let scale = if weighted {
        1.0
    } else {
        rows.iter()
            .map(|&(x, y, _)| (y - c0 - c1 * x).powi(2))
            .sum::<f64>()
            / dof
    };
    let var_c0 = scale * swxx / det;
    let var_c1 = scale * sw / det;
    let cov01 = -scale * swx / det;
    let a = c0.exp();
    Ok(ZbsFit {
        a,
        b: -c1,
        stderr_a: a * var_c0.sqrt(),
        stderr_b: var_c1.sqrt(),
        // corr(a, b) = corr(ln a, −c1) = −corr(c0, c1).
        correlation_ab: if var_c0 > 0.0 && var_c1 > 0.0 {
            -cov01 / (var_c0 * var_c1).sqrt()
        } else {
            0.0
        },
        samples,
        excluded,
        weighted,
    })
}
