//! Monte Carlo of the simulated DoFP frame (detection.md §6) against the analytic channel and
//! Stokes statistics of §3–4 (the detection core's `NoiseModel::variance`, `Estimate`), at high
//! and at low SNR, and the Rician bias of the estimated DoLP at low SNR (`dolp_bias`).
//!
//! **Confidence.** Every comparison is a z-test: (sample statistic − analytic value) / its
//! standard error estimated from the same sample (for a variance, from the sample's fourth
//! moment; for a covariance, `√((σ_i²σ_j² + σ_ij²)/n)`; for a mean, `s/√n`), required below
//! [`Z`] = 4 in magnitude (two-sided probability 6.3·10⁻⁵ per comparison for a correct model).
//! The seeds are fixed, so the tests are deterministic; with the ~60 comparisons below a fresh
//! seed would fail a correct implementation with probability below 0.4 %.

use polbrdf::analysis::detection::dolp_bias::{dolp_variance, expected_dolp};
use polbrdf::analysis::detection::frame::{simulate, Frame, FrameSpec};
use polbrdf::analysis::detection::noise::photons_per_joule;
use polbrdf::analysis::detection::{Analyzer, Estimate, NoiseModel, PhotonCounting, Sensor};
use polbrdf::Stokes;

/// The z-score bound of every comparison.
const Z: f64 = 4.0;

fn camera(read_noise_e: f64, gain: f64, dark_e_per_s: f64) -> PhotonCounting {
    PhotonCounting {
        integration_time_s: 0.01,
        pixel_pitch_m: 3.45e-6,
        f_number: 2.8,
        optics_transmittance: 0.9,
        photons_per_joule: photons_per_joule(0.55),
        dark_current_e_per_s: dark_e_per_s,
        read_noise_e,
        gain_e_per_count: gain,
        full_well_e: 1e6,
    }
}

fn sensor(analyzer: Analyzer, camera: PhotonCounting, frames: u32) -> Sensor {
    Sensor {
        analyzer,
        noise: NoiseModel::PhotonCounting(camera),
        frames,
        ifov_rad: 1e-4,
    }
}

/// A Stokes radiance whose unanalyzed signal is `s0_e` electrons, with DoLP `p` at AoLP `aolp`.
fn stokes_e(s: &Sensor, s0_e: f64, p: f64, aolp_deg: f64) -> Stokes {
    let g = s.noise.gain();
    let (sn, cs) = (2.0 * aolp_deg.to_radians()).sin_cos();
    Stokes::new(s0_e / g, p * cs * s0_e / g, p * sn * s0_e / g, 0.0)
}

/// (mean, unbiased variance, standard error of the variance) of `x`.
fn moments(x: &[f64]) -> (f64, f64, f64) {
    let n = x.len() as f64;
    let mean = x.iter().sum::<f64>() / n;
    let m2 = x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n;
    let m4 = x.iter().map(|v| (v - mean).powi(4)).sum::<f64>() / n;
    let var = m2 * n / (n - 1.0);
    let se = ((m4 - m2 * m2 * (n - 3.0) / (n - 1.0)) / n).sqrt();
    (mean, var, se)
}

fn check_mean(what: &str, x: &[f64], want: f64) {
    let (mean, var, _) = moments(x);
    let z = (mean - want) / (var / x.len() as f64).sqrt();
    assert!(z.abs() < Z, "{what}: mean {mean} vs {want} (z = {z:.2})");
}

fn check_variance(what: &str, x: &[f64], want: f64) {
    let (_, var, se) = moments(x);
    let z = (var - want) / se;
    assert!(z.abs() < Z, "{what}: variance {var} vs {want} (z = {z:.2})");
}

fn check_covariance(what: &str, a: &[f64], b: &[f64], cov: &[[f64; 3]; 3], (i, j): (usize, usize)) {
    let n = a.len() as f64;
    let (ma, mb) = (a.iter().sum::<f64>() / n, b.iter().sum::<f64>() / n);
    let c = a
        .iter()
        .zip(b)
        .map(|(x, y)| (x - ma) * (y - mb))
        .sum::<f64>()
        / (n - 1.0);
    let se = ((cov[i][i] * cov[j][j] + cov[i][j] * cov[i][j]) / n).sqrt();
    let z = (c - cov[i][j]) / se;
    assert!(
        z.abs() < Z,
        "{what}: covariance [{i}][{j}] {c} vs {} (z = {z:.2})",
        cov[i][j]
    );
}

/// The values of `image` (one per super-pixel) on the target or the background.
fn region(f: &Frame, image: &[f64], target: bool) -> Vec<f64> {
    (0..f.side * f.side)
        .filter(|&i| f.on_target(i / f.side, i % f.side) == target)
        .map(|i| image[i])
        .collect()
}

/// Raw pixels of channel `k` (layout position `(r, c)`), as electrons `g·counts`.
fn channel(f: &Frame, (r, c): (usize, usize), gain: f64, target: bool) -> Vec<f64> {
    let w = 2 * f.side;
    (0..f.side * f.side)
        .filter(|&i| f.on_target(i / f.side, i % f.side) == target)
        .map(|i| gain * f.raw_counts[(2 * (i / f.side) + r) * w + 2 * (i % f.side) + c])
        .collect()
}

/// The layout position of each channel of a 0°, 45°, 90°, 135° analyzer:
/// `[[90°, 45°], [135°, 0°]]`.
const POSITION: [(usize, usize); 4] = [(1, 1), (0, 1), (0, 0), (1, 0)];

/// Simulates `s` seeing target and background; checks every channel's mean and variance and
/// the Stokes means and covariances of both regions against §3–4.
fn check_channels_and_stokes(s: &Sensor, target: &Stokes, background: &Stokes, seed: u64) -> Frame {
    let spec = FrameSpec::for_sensor(s, target, background, 16, (128, 90), seed).unwrap();
    let f = simulate(&spec).unwrap();
    assert_eq!(f.saturated_pixels(), 0);
    let NoiseModel::PhotonCounting(cam) = s.noise else {
        unreachable!()
    };
    let dark = cam.dark_current_e_per_s * cam.integration_time_s;
    let frames = f64::from(s.frames);
    for (on, stokes, e) in [
        (true, target, spec.target_e),
        (false, background, spec.background_e),
    ] {
        let est = Estimate::of(s, stokes);
        for (k, &pos) in POSITION.iter().enumerate() {
            let x = channel(&f, pos, cam.gain_e_per_count, on);
            let what = format!("target {on}, channel {k}");
            check_mean(&what, &x, e[k] + dark);
            check_variance(&what, &x, s.noise.variance(e[k]) / frames);
        }
        let images = [&f.s0, &f.s1, &f.s2].map(|image| region(&f, image, on));
        for (i, x) in images.iter().enumerate() {
            check_mean(&format!("target {on}, S{i}"), x, est.stokes[i]);
            for (j, y) in images.iter().enumerate().skip(i) {
                check_covariance(&format!("target {on}"), x, y, &est.covariance, (i, j));
            }
        }
    }
    f
}

#[test]
fn high_snr_channels_stokes_and_dolp_match_the_first_order_statistics() {
    // 20 000 e⁻ per pixel: DoLP SNR ≈ 0.3·20000/√(2·20000) ≈ 40 on the target.
    for (analyzer, seed) in [
        (Analyzer::ideal_dofp(), 1),
        (
            Analyzer::with_extinction_ratio(
                [0.0f64, 45.0, 90.0, 135.0].map(f64::to_radians).to_vec(),
                0.8,
                10.0,
                0.3,
            )
            .unwrap(),
            2,
        ),
    ] {
        let s = sensor(analyzer, camera(6.0, 2.5, 800.0), 1);
        let (t, b) = (
            stokes_e(&s, 20_000.0, 0.3, 30.0),
            stokes_e(&s, 18_000.0, 0.05, -60.0),
        );
        let f = check_channels_and_stokes(&s, &t, &b, seed);
        for (on, stokes) in [(true, &t), (false, &b)] {
            let est = Estimate::of(&s, stokes);
            let d = est.dolp().unwrap();
            let x = region(&f, &f.dolp, on);
            // The variance is §4's first order; the mean carries the Rician bias
            // σ²/(2·P·S0²) even here (5.6·10⁻⁴ on the background, 7 standard errors of the
            // mean): compare it with the Rice mean, of which the true DoLP is the limit.
            let sigma = (0.5 * (est.covariance[1][1] + est.covariance[2][2])).sqrt();
            let rice = expected_dolp(d.mean, est.stokes[0], sigma);
            assert!(rice - d.mean < 0.02 * d.mean);
            check_mean(&format!("DoLP target {on}"), &x, rice);
            check_variance(&format!("DoLP target {on}"), &x, d.variance);
        }
    }
}

#[test]
fn low_snr_channels_and_stokes_match_with_frames_averaged() {
    // 60 e⁻ per pixel, read noise and dark comparable to the signal, 4 frames averaged.
    let s = sensor(Analyzer::ideal_dofp(), camera(4.0, 1.5, 2000.0), 4);
    let (t, b) = (
        stokes_e(&s, 120.0, 0.2, 10.0),
        stokes_e(&s, 100.0, 0.0, 0.0),
    );
    check_channels_and_stokes(&s, &t, &b, 3);
}

#[test]
fn low_snr_dolp_is_rician_biased_upward_as_documented() {
    // S0 = 200 e⁻: σ(S1) ≈ σ(S2) ≈ 16 e⁻, so the target's |S12| = 10 e⁻ is below the noise.
    let s = sensor(Analyzer::ideal_dofp(), camera(3.0, 1.0, 500.0), 1);
    let (t, b) = (
        stokes_e(&s, 200.0, 0.05, 20.0),
        stokes_e(&s, 200.0, 0.0, 0.0),
    );
    let spec = FrameSpec::for_sensor(&s, &t, &b, 16, (128, 90), 4).unwrap();
    let f = simulate(&spec).unwrap();
    for (on, stokes, p) in [(true, &t, 0.05), (false, &b, 0.0)] {
        let est = Estimate::of(&s, stokes);
        let s0 = est.stokes[0];
        let sigma = (0.5 * (est.covariance[1][1] + est.covariance[2][2])).sqrt();
        let x = region(&f, &f.dolp, on);
        let (mean, var, _) = moments(&x);
        let se = (var / x.len() as f64).sqrt();
        // Far above the true DoLP: the bias is many standard errors of the mean…
        assert!(mean - p > 20.0 * se, "target {on}: mean {mean} vs true {p}");
        // …and it is the Rice mean, √(π/2)·σ/S0 at P = 0. The relative noise of Ŝ0 (≈ 6 %)
        // adds ≈ 0.3 % to E[1/Ŝ0]: allowed for beside the sampling error.
        let want = expected_dolp(p, s0, sigma);
        assert!(
            (mean - want).abs() < Z * se + 0.005 * want,
            "target {on}: mean {mean} vs Rice {want}"
        );
        let want_var = dolp_variance(p, s0, sigma);
        let (_, _, var_se) = moments(&x);
        assert!(
            (var - want_var).abs() < Z * var_se + 0.02 * want_var,
            "target {on}: variance {var} vs Rice {want_var}"
        );
    }
    // The first-order mean of §4 (the true DoLP) misses it: the bias is of the size of the
    // noise, √(π/2)·σ/S0 ≈ 0.1 on the background.
    assert!(f.background.dolp.mean > 0.09 && f.background.dolp.mean < 0.11);
}
