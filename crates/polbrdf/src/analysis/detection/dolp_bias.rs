//! The Rician bias of the estimated DoLP (detection.md §4, docs/detection-frame.md).
//!
//! When `Ŝ1` and `Ŝ2` carry independent Gaussian noise of equal standard deviation `σ` around
//! `(S1, S2)`, the length `|Ŝ12| = √(Ŝ1² + Ŝ2²)` is Rice-distributed with parameter
//! `ν = √(S1² + S2²)`, and its mean is
//! `E|Ŝ12| = σ·√(π/2)·L_{1/2}(−ν²/(2σ²))`, where `L_{1/2}(x) = e^{x/2}·[(1 − x)·I0(−x/2) −
//! x·I1(−x/2)]` (Laguerre polynomial of order ½; `I0`, `I1` modified Bessel functions). With `S0`
//! known much better than `S1`, `S2` (its relative error second order), the estimated DoLP
//! `P̂ = |Ŝ12|/Ŝ0` has mean `E|Ŝ12|/S0`: above the true `P = ν/S0` always, by
//! `√(π/2)·σ/S0` at `P = 0` (the Rayleigh mean) and by `σ²/(2·P·S0²)` once `P·S0 ≫ σ`. Its
//! variance follows from the exact second moment `E|Ŝ12|² = ν² + 2σ²`:
//! `var P̂ = (ν² + 2σ² − (E|Ŝ12|)²)/S0²` — `(2 − π/2)·σ²/S0²` at `P = 0`, and the first-order
//! `σ²/S0²` of §4 once `P·S0 ≫ σ`.

/// `e^{−u}·I0(u)` and `e^{−u}·I1(u)` for `u ≥ 0` (power series below 20, the asymptotic
/// expansion above, both to better than 1e-13 relative).
fn scaled_bessel_i0_i1(u: f64) -> (f64, f64) {
    if u < 20.0 {
        // I0 = Σ t^k/(k!)², I1 = (u/2)·Σ t^k/(k!(k+1)!), t = u²/4; the terms peak near k = u/2.
        let t = u * u / 4.0;
        let (mut a, mut b) = (1.0, u / 2.0);
        let (mut i0, mut i1) = (a, b);
        for k in 1..200 {
            let k = f64::from(k);
            a *= t / (k * k);
            b *= t / (k * (k + 1.0));
            i0 += a;
            i1 += b;
            if a < 1e-17 * i0 && b < 1e-17 * i1 {
                break;
            }
        }
        let s = (-u).exp();
        (i0 * s, i1 * s)
    } else {
        // e^{−u} I_n(u) ≈ (2πu)^{−½}·Σ_k (−1)^k·Π_{j≤k}(4n² − (2j − 1)²)/(k!·(8u)^k).
        let series = |n: f64| {
            let mu = 4.0 * n * n;
            let (mut term, mut sum) = (1.0, 1.0);
            for k in 1..30 {
                let j = f64::from(k);
                let next = -term * (mu - (2.0 * j - 1.0).powi(2)) / (j * 8.0 * u);
                if next.abs() >= term.abs() {
                    break;
                }
                term = next;
                sum += term;
            }
            sum / (2.0 * std::f64::consts::PI * u).sqrt()
        };
        (series(0.0), series(1.0))
    }
}

/// The mean of a Rice-distributed length: `E|Z|` for a 2-D Gaussian `Z` of mean length `nu ≥ 0`
/// and per-component standard deviation `sigma > 0`.
pub fn rice_mean(nu: f64, sigma: f64) -> f64 {
    // u = ν²/(4σ²) = −x/2; L_{1/2}(x) = (1 + 2u)·e^{−u}I0(u) + 2u·e^{−u}I1(u).
    let u = (nu / sigma).powi(2) / 4.0;
    let (i0, i1) = scaled_bessel_i0_i1(u);
    sigma * (std::f64::consts::PI / 2.0).sqrt() * ((1.0 + 2.0 * u) * i0 + 2.0 * u * i1)
}

/// The mean of the estimated DoLP for a true `dolp` at intensity `s0 > 0`, when `Ŝ1` and `Ŝ2`
/// each carry Gaussian noise of standard deviation `sigma_lin > 0` (module documentation; for
/// unequal variances use their mean). Always above `dolp`.
pub fn expected_dolp(dolp: f64, s0: f64, sigma_lin: f64) -> f64 {
    rice_mean(dolp * s0, sigma_lin) / s0
}

/// The variance of the estimated DoLP under the same assumptions as [`expected_dolp`]:
/// `(ν² + 2σ² − (E|Ŝ12|)²)/S0²`, `ν = dolp·s0`.
pub fn dolp_variance(dolp: f64, s0: f64, sigma_lin: f64) -> f64 {
    let nu = dolp * s0;
    let m = rice_mean(nu, sigma_lin);
    ((nu * nu + 2.0 * sigma_lin * sigma_lin - m * m) / (s0 * s0)).max(0.0)
}
