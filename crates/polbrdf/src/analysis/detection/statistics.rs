//! Telling target from background (detection.md §5): `d'`, `d'_N = d'·√N_pix`, the pixels on
//! target, `P_d = Φ(d'_N − Φ⁻¹(1 − P_fa))`, and the detection range `R_max`.

use super::estimate::{Estimate, Moments};
use super::{Detection, Detector, Feature, FeatureScores, MaxRange};
use crate::error::Result;
use crate::optics::stokes::Stokes;
use std::f64::consts::{FRAC_1_SQRT_2, PI};

/// Ranges of the coarse grid of the range search per decade.
pub const SEARCH_STEPS_PER_DECADE: usize = 20;
/// Decades below `R_limit` the range search looks at.
pub const SEARCH_DECADES: usize = 6;

/// The standard normal distribution function `Φ(x) = ½·erfc(−x/√2)` (libm's erfc).
pub fn phi(x: f64) -> f64 {
    0.5 * libm::erfc(-x * FRAC_1_SQRT_2)
}

/// The standard normal quantile `Φ⁻¹(p)` for `p ∈ (0, 1)` (±∞ at 0 and 1, NaN outside):
/// Acklam's rational approximation (relative error < 1.2e-9) refined by one Halley step on
/// [`phi`], symmetric about `p = ½` so that both tails keep their precision.
pub fn phi_inv(p: f64) -> f64 {
    if !(0.0..=1.0).contains(&p) {
        return f64::NAN;
    }
    if p == 0.0 {
        return f64::NEG_INFINITY;
    }
    if p == 1.0 {
        return f64::INFINITY;
    }
    if p > 0.5 {
        return -phi_inv(1.0 - p);
    }
    const A: [f64; 6] = [
        -3.969_683_028_665_376e1,
        2.209_460_984_245_205e2,
        -2.759_285_104_469_687e2,
        1.383_577_518_672_69e2,
        -3.066_479_806_614_716e1,
        2.506_628_277_459_239,
    ];
    const B: [f64; 5] = [
        -5.447_609_879_822_406e1,
        1.615_858_368_580_409e2,
        -1.556_989_798_598_866e2,
        6.680_131_188_771_972e1,
        -1.328_068_155_288_572e1,
    ];
    const C: [f64; 6] = [
        -7.784_894_002_430_293e-3,
        -3.223_964_580_411_365e-1,
        -2.400_758_277_161_838,
        -2.549_732_539_343_734,
        4.374_664_141_464_968,
        2.938_163_982_698_783,
    ];
    const D: [f64; 4] = [
        7.784_695_709_041_462e-3,
        3.224_671_290_700_398e-1,
        2.445_134_137_142_996,
        3.754_408_661_907_416,
    ];
    let x = if p < 0.02425 {
        let q = (-2.0 * p.ln()).sqrt();
        (((((C[0] * q + C[1]) * q + C[2]) * q + C[3]) * q + C[4]) * q + C[5])
            / ((((D[0] * q + D[1]) * q + D[2]) * q + D[3]) * q + 1.0)
    } else {
        let q = p - 0.5;
        let r = q * q;
        (((((A[0] * r + A[1]) * r + A[2]) * r + A[3]) * r + A[4]) * r + A[5]) * q
            / (((((B[0] * r + B[1]) * r + B[2]) * r + B[3]) * r + B[4]) * r + 1.0)
    };
    // One Halley step on Φ(x) − p.
    let e = phi(x) - p;
    let u = e * (2.0 * PI).sqrt() * (0.5 * x * x).exp();
    x - u / (1.0 + 0.5 * x * u)
}

/// `d' = |μ_t − μ_b| / √((σ_t² + σ_b²)/2)` (detection.md §5); 0 for equal means, ∞ for
/// different means without noise.
pub fn d_prime(target: Moments, background: Moments) -> f64 {
    let diff = (target.mean - background.mean).abs();
    let pooled = 0.5 * (target.variance + background.variance);
    if diff == 0.0 {
        0.0
    } else if pooled > 0.0 {
        diff / pooled.sqrt()
    } else {
        f64::INFINITY
    }
}

/// The `d'` of a two-component feature: `√(Δμᵀ·Σ̄⁻¹·Δμ)` with the pooled covariance
/// `Σ̄ = (Σ_t + Σ_b)/2` — the Fisher linear discriminant, which for one component is
/// [`d_prime`] (detection.md §5, the combined feature; docs/detection.md). `None` when `Σ̄` is
/// singular.
pub fn d_prime_2d(
    (mt, ct): ([f64; 2], [[f64; 2]; 2]),
    (mb, cb): ([f64; 2], [[f64; 2]; 2]),
) -> Option<f64> {
    let s = [
        [0.5 * (ct[0][0] + cb[0][0]), 0.5 * (ct[0][1] + cb[0][1])],
        [0.5 * (ct[1][0] + cb[1][0]), 0.5 * (ct[1][1] + cb[1][1])],
    ];
    let det = s[0][0] * s[1][1] - s[0][1] * s[1][0];
    if !det.is_finite() || det <= 1e-14 * s[0][0] * s[1][1] {
        return None;
    }
    let d = [mt[0] - mb[0], mt[1] - mb[1]];
    let q = (d[0] * d[0] * s[1][1] - 2.0 * d[0] * d[1] * s[0][1] + d[1] * d[1] * s[0][0]) / det;
    Some(q.max(0.0).sqrt())
}

/// Pixels on target `N_pix = A·cosθ_r / (R·IFOV)²`, at least 0, a real number
/// (detection.md §5); `ifov_rad` the IFOV of one Stokes pixel.
pub fn pixels_on_target(area_m2: f64, theta_r: f64, range_m: f64, ifov_rad: f64) -> f64 {
    let n = area_m2 * theta_r.cos() / (range_m * ifov_rad).powi(2);
    if n.is_nan() {
        0.0
    } else {
        n.max(0.0)
    }
}

/// `P_d = Φ(d'_N − Φ⁻¹(1 − P_fa))` (detection.md §5).
pub fn probability_of_detection(d_prime_n: f64, pfa: f64) -> f64 {
    // Φ⁻¹(1 − P_fa) = −Φ⁻¹(P_fa), exact in the tail.
    phi(d_prime_n + phi_inv(pfa))
}

/// The `d'_N` that reaches `P_d = pd` at `P_fa = pfa`: `Φ⁻¹(P_d) + Φ⁻¹(1 − P_fa)`.
pub fn required_d_prime(pd: f64, pfa: f64) -> f64 {
    phi_inv(pd) - phi_inv(pfa)
}

/// The per-pixel `d'` of every feature between the two estimates (detection.md §5): S0, DoLP
/// (0 where DoLP is undefined, `S0 ≤ 0`), and the combined `(S0, DoLP)` (the best of the two
/// where its pooled covariance is singular).
pub fn feature_scores(target: &Estimate, background: &Estimate) -> FeatureScores {
    let s0 = d_prime(target.s0(), background.s0());
    let dolp = match (target.dolp(), background.dolp()) {
        (Some(t), Some(b)) => d_prime(t, b),
        _ => 0.0,
    };
    let combined = match (target.s0_dolp(), background.s0_dolp()) {
        (Some(t), Some(b)) => d_prime_2d(t, b).unwrap_or(s0.max(dolp)),
        _ => s0,
    };
    FeatureScores { s0, dolp, combined }
}

impl Detector {
    /// Target and background estimates at range `range_m` seen from zenith `theta_r`
    /// (detection.md §1–5).
    ///
    /// # Errors
    /// As [`super::Path::at`] (a range beyond a table, not finite, negative).
    pub fn detect(
        &self,
        target: &Stokes,
        background: &Stokes,
        theta_r: f64,
        range_m: f64,
    ) -> Result<Detection> {
        let et = Estimate::of(&self.sensor, &self.path.apply(target, range_m)?);
        let eb = Estimate::of(&self.sensor, &self.path.apply(background, range_m)?);
        let scores = feature_scores(&et, &eb);
        let pixels = pixels_on_target(self.area_m2, theta_r, range_m, self.sensor.ifov_rad);
        let (feature, d) = self.best(&scores);
        let d_prime_n = d * pixels.sqrt();
        Ok(Detection {
            range_m,
            pixels,
            scores,
            feature,
            d_prime_n,
            pd: probability_of_detection(d_prime_n, self.criteria.pfa),
            saturated: et.saturated || eb.saturated,
            target: et,
            background: eb,
        })
    }

    /// The best of the criteria's features: the largest `d'`, ties to the earlier of
    /// [`Feature::ALL`].
    fn best(&self, scores: &FeatureScores) -> (Feature, f64) {
        let mut best = (
            self.criteria.features[0],
            scores.get(self.criteria.features[0]),
        );
        for &f in &self.criteria.features[1..] {
            let d = scores.get(f);
            if d > best.1 || (d == best.1 && (f as usize) < (best.0 as usize)) {
                best = (f, d);
            }
        }
        best
    }

    /// The detection range (detection.md §5): the largest `R ∈ (0, R_limit]` with
    /// `P_d ≥ P_d,req`. A coarse geometric grid from `R_limit` down over [`SEARCH_DECADES`]
    /// decades ([`SEARCH_STEPS_PER_DECADE`] per decade) finds the largest grid range that
    /// detects; bisection between it and the next grid range above refines it to 1e-10
    /// relative. [`MaxRange::Beyond`] when `R_limit` itself detects, [`MaxRange::NotDetectable`]
    /// when no grid range does (docs/detection.md).
    ///
    /// # Errors
    /// As [`Detector::detect`].
    pub fn max_range(
        &self,
        target: &Stokes,
        background: &Stokes,
        theta_r: f64,
    ) -> Result<MaxRange> {
        let need = self.criteria.required_d_prime();
        let limit = self.criteria.range_limit_m;
        let ok = |r: f64| -> Result<Option<Feature>> {
            let d = self.detect(target, background, theta_r, r)?;
            Ok((d.d_prime_n >= need).then_some(d.feature))
        };
        if ok(limit)?.is_some() {
            return Ok(MaxRange::Beyond);
        }
        let steps = SEARCH_STEPS_PER_DECADE * SEARCH_DECADES;
        let grid = |k: usize| limit * 10f64.powf(-(k as f64) / SEARCH_STEPS_PER_DECADE as f64);
        for k in 1..=steps {
            let r = grid(k);
            if let Some(mut feature) = ok(r)? {
                let (mut lo, mut hi) = (r, grid(k - 1));
                while hi - lo > 1e-10 * hi {
                    let mid = 0.5 * (lo + hi);
                    match ok(mid)? {
                        Some(f) => {
                            lo = mid;
                            feature = f;
                        }
                        None => hi = mid,
                    }
                }
                return Ok(MaxRange::At {
                    range_m: lo,
                    feature,
                });
            }
        }
        Ok(MaxRange::NotDetectable)
    }
}
