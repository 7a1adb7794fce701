//! The Stokes estimate and its covariance (detection.md §4): `Ŝ = W₃⁺ I`,
//! `Σ_S = W₃⁺ diag(σ_k²) W₃⁺ᵀ`, and the features S0, DoLP and the polarization contrast with
//! their first-order variances.

use super::Sensor;
use crate::optics::stokes::Stokes;

/// The estimate of `(S0, S1, S2)` of one Stokes pixel and its covariance, in the channel
/// signal's units (electrons for a photon-counting camera, radiance for a NEL model).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Estimate {
    /// The mean of `Ŝ` (= `(S0, S1, S2)` times the channel gain: `W₃⁺W₃ = 1`).
    pub stokes: [f64; 3],
    /// `Σ_S`, after averaging the sensor's frames.
    pub covariance: [[f64; 3]; 3],
    /// Whether a channel is above the full well (detection.md §3: flagged, not clipped).
    pub saturated: bool,
}

/// A feature's mean and variance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Moments {
    /// Mean.
    pub mean: f64,
    /// Variance.
    pub variance: f64,
}

impl Estimate {
    /// The estimate of a pixel seeing `stokes` at the sensor (detection.md §4): channel values
    /// `I_k = a_k·S'`, signals `g·I_k`, variances per §3 divided by the frames `M`.
    pub fn of(sensor: &Sensor, stokes: &Stokes) -> Self {
        let gain = sensor.noise.gain();
        let frames = f64::from(sensor.frames);
        let mut s = [0.0; 3];
        let mut cov = [[0.0; 3]; 3];
        let mut saturated = false;
        let rows = sensor.analyzer.matrix();
        for (a, c) in rows.iter().zip(sensor.analyzer.pseudo_inverse()) {
            let i_k =
                a[0] * stokes.0[0] + a[1] * stokes.0[1] + a[2] * stokes.0[2] + a[3] * stokes.0[3];
            let n = gain * i_k;
            let var = sensor.noise.variance(n) / frames;
            saturated |= sensor.noise.saturated(n);
            for i in 0..3 {
                s[i] += c[i] * n;
                for j in 0..3 {
                    cov[i][j] += var * c[i] * c[j];
                }
            }
        }
        Self {
            stokes: s,
            covariance: cov,
            saturated,
        }
    }

    /// `Ŝ0` and its variance `Σ_S[0][0]`.
    pub fn s0(&self) -> Moments {
        Moments {
            mean: self.stokes[0],
            variance: self.covariance[0][0],
        }
    }

    /// `∇DoLP` with respect to `(S0, S1, S2)`: `(−P/S0, S1/(S0·L), S2/(S0·L))`,
    /// `L = √(S1² + S2²)`. Where `L = 0` the gradient is undefined; `None` there and for
    /// `S0 ≤ 0`.
    pub fn dolp_gradient(&self) -> Option<[f64; 3]> {
        let [s0, s1, s2] = self.stokes;
        let l = s1.hypot(s2);
        if s0.is_nan() || s0 <= 0.0 || l == 0.0 {
            return None;
        }
        let p = l / s0;
        Some([-p / s0, s1 / (s0 * l), s2 / (s0 * l)])
    }

    /// `DoLP = √(S1² + S2²)/S0` and its first-order variance `∇DoLP·Σ_S·∇DoLPᵀ`
    /// (detection.md §4). For an unpolarized mean (`L = 0`), where the gradient is undefined,
    /// the variance is the first-order variance along a direction averaged over the S1–S2
    /// plane, `(Σ11 + Σ22)/(2·S0²)` (docs/detection.md); `None` for `S0 ≤ 0` (no signal).
    pub fn dolp(&self) -> Option<Moments> {
        let s0 = self.stokes[0];
        if s0.is_nan() || s0 <= 0.0 {
            return None;
        }
        let mean = self.stokes[1].hypot(self.stokes[2]) / s0;
        let variance = match self.dolp_gradient() {
            Some(g) => quadratic(&g, &self.covariance),
            None => (self.covariance[1][1] + self.covariance[2][2]) / (2.0 * s0 * s0),
        };
        Some(Moments { mean, variance })
    }

    /// The joint feature `(S0, DoLP)`: its mean and 2×2 covariance to first order (the
    /// combined feature of detection.md §5); `None` where DoLP is.
    pub fn s0_dolp(&self) -> Option<([f64; 2], [[f64; 2]; 2])> {
        let d = self.dolp()?;
        let cov01 = match self.dolp_gradient() {
            Some(g) => (0..3).map(|j| g[j] * self.covariance[0][j]).sum(),
            None => 0.0,
        };
        Some((
            [self.stokes[0], d.mean],
            [[self.covariance[0][0], cov01], [cov01, d.variance]],
        ))
    }
}

/// `g·Σ·gᵀ`.
fn quadratic(g: &[f64; 3], cov: &[[f64; 3]; 3]) -> f64 {
    (0..3)
        .map(|i| (0..3).map(|j| g[i] * cov[i][j] * g[j]).sum::<f64>())
        .sum()
}

/// The polarization contrast of the project's contrast command (docs/model.md §11),
/// `PC = √((S1t − S1b)² + (S2t − S2b)²)/((S0t + S0b)/2)`, of a target and a background pixel,
/// with its first-order variance (both pixels independent; detection.md §4). `None` where it is
/// undefined (`S0t + S0b ≤ 0`); at `ΔS1 = ΔS2 = 0` the variance is that along a direction
/// averaged over the ΔS1–ΔS2 plane.
pub fn polarization_contrast(target: &Estimate, background: &Estimate) -> Option<Moments> {
    let (t, b) = (target.stokes, background.stokes);
    let m = 0.5 * (t[0] + b[0]);
    if m.is_nan() || m <= 0.0 {
        return None;
    }
    let (d1, d2) = (t[1] - b[1], t[2] - b[2]);
    let d = d1.hypot(d2);
    let pc = d / m;
    let (ct, cb) = (&target.covariance, &background.covariance);
    let variance = if d > 0.0 {
        let gt = [-pc / (2.0 * m), d1 / (d * m), d2 / (d * m)];
        let gb = [-pc / (2.0 * m), -d1 / (d * m), -d2 / (d * m)];
        quadratic(&gt, ct) + quadratic(&gb, cb)
    } else {
        (ct[1][1] + ct[2][2] + cb[1][1] + cb[2][2]) / (2.0 * m * m)
    };
    Some(Moments { mean: pc, variance })
}
