//! The detection range's uncertainty by linear propagation (`detection::uncertainty`),
//! validated against the spread of `R_max` over parameters drawn from the covariance.

use polbrdf::analysis::detection::noise::photons_per_joule;
use polbrdf::analysis::detection::uncertainty::propagate;
use polbrdf::analysis::detection::{
    Analyzer, Criteria, Detector, MaxRange, NoiseModel, Path, PhotonCounting, Sensor,
};
use polbrdf::sample::SplitMix64;
use polbrdf::{Error, Stokes};

fn detector() -> Detector {
    let camera = PhotonCounting {
        integration_time_s: 0.005,
        pixel_pitch_m: 3.45e-6,
        f_number: 2.8,
        optics_transmittance: 0.9,
        photons_per_joule: photons_per_joule(0.55),
        dark_current_e_per_s: 3.0,
        read_noise_e: 2.3,
        gain_e_per_count: 2.5,
        full_well_e: 1e6,
    };
    let sensor = Sensor {
        analyzer: Analyzer::ideal_dofp(),
        noise: NoiseModel::PhotonCounting(camera),
        frames: 1,
        ifov_rad: 2.0 * 3.45e-6 / 0.05,
    };
    // Hazy air (visibility 8 km): the range depends on the parameters non-linearly.
    let path = Path::from_visibility(8000.0, 30.0).unwrap();
    let criteria = Criteria {
        range_limit_m: 1e6,
        ..Criteria::default()
    };
    Detector::new(sensor, path, 4.0, criteria).unwrap()
}

/// Parameters: the target's radiance relative to the background's, and its DoLP.
fn r_max(d: &Detector, p: &[f64]) -> polbrdf::Result<Option<f64>> {
    let lb = 40.0;
    let background = Stokes::new(lb, 0.0, 0.0, 0.0);
    let target = Stokes::new(lb * p[0], lb * p[0] * p[1], 0.0, 0.0);
    Ok(match d.max_range(&target, &background, 0.5)? {
        MaxRange::At { range_m, .. } => Some(range_m),
        _ => None,
    })
}

#[test]
fn linear_propagation_matches_the_spread_of_the_range_over_sampled_parameters() {
    let d = detector();
    let p0 = [0.9, 0.12];
    // Standard deviations 0.03 and 0.02, correlation 0.5.
    let cov = [9e-4, 0.5 * 0.03 * 0.02, 0.5 * 0.03 * 0.02, 4e-4];
    let prop = propagate(|p| r_max(&d, p), &p0, &cov).unwrap().unwrap();
    assert!(
        prop.value > 100.0 && prop.sigma > 0.02 * prop.value,
        "{prop:?}"
    );

    // Draws from N(p0, Σ) by its Cholesky factor.
    let l00 = cov[0].sqrt();
    let l10 = cov[2] / l00;
    let l11 = (cov[3] - l10 * l10).sqrt();
    let mut rng = SplitMix64::new(11);
    let n = 600;
    let ranges: Vec<f64> = (0..n)
        .map(|_| {
            let (z0, z1) = (rng.normal(), rng.normal());
            let p = [p0[0] + l00 * z0, p0[1] + l10 * z0 + l11 * z1];
            r_max(&d, &p).unwrap().unwrap()
        })
        .collect();
    let mean = ranges.iter().sum::<f64>() / n as f64;
    let sd = (ranges.iter().map(|r| (r - mean).powi(2)).sum::<f64>() / (n - 1) as f64).sqrt();
    // The sample standard deviation's standard error is ≈ sd/√(2n) ≈ 2.9 %; 4 of them, plus
    // 3 % for what the linearization leaves out, bound the agreement.
    let rel = (sd - prop.sigma).abs() / prop.sigma;
    assert!(
        rel < 4.0 / (2.0 * n as f64).sqrt() + 0.03,
        "sd {sd} vs σ_R {}",
        prop.sigma
    );
    // The mean range: R(p0) within 4 standard errors of the mean (plus the curvature's bias,
    // second order in σ).
    assert!((mean - prop.value).abs() < 4.0 * sd / (n as f64).sqrt() + 0.01 * prop.value);
    // The interval.
    let (lo, hi) = prop.interval(1.96);
    assert!(lo < prop.value && hi > prop.value && (hi - lo - 3.92 * prop.sigma).abs() < 1e-9);
}

#[test]
fn zero_variance_parameters_and_undefined_ranges() {
    let d = detector();
    // A parameter known exactly contributes nothing.
    let prop = propagate(|p| r_max(&d, p), &[0.9, 0.12], &[1e-4, 0.0, 0.0, 0.0])
        .unwrap()
        .unwrap();
    assert_eq!(prop.jacobian[1], 0.0);
    assert!((prop.sigma - prop.jacobian[0].abs() * 0.01).abs() < 1e-12 * prop.value);
    // A target identical to its background is not detectable: no range, no interval.
    assert!(
        propagate(|p| r_max(&d, p), &[1.0, 0.0], &[1e-4, 0.0, 0.0, 1e-6])
            .unwrap()
            .is_none()
    );
    // A covariance of the wrong size, or with a negative variance, is refused.
    for bad in [vec![1e-4; 3], vec![-1e-4, 0.0, 0.0, 1e-6]] {
        assert!(matches!(
            propagate(|p| r_max(&d, p), &[0.9, 0.12], &bad),
            Err(Error::InconsistentParameters(_))
        ));
    }
}
