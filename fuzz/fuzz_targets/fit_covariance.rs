//! A `fit.json` parsed and propagated (issue 37, the detection range's uncertainty): any text
//! that parses as a fit's covariance has finite values and a finite covariance with a
//! non-negative diagonal, and its propagation through a detection range (the parameters
//! scaling a target's radiance) gives a finite, non-negative σ or no interval — no panic.
#![no_main]
use libfuzzer_sys::fuzz_target;
use polbrdf::analysis::detection::uncertainty::propagate;
use polbrdf::analysis::detection::{Criteria, Detector, MaxRange, Path as AirPath};
use polbrdf::Stokes;
use polbrdf_tasks::fit_covariance::FitCovariance;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(fit) = FitCovariance::parse(text, Path::new("fuzz.json")) else {
        return;
    };
    let n = fit.params.len();
    assert_eq!(fit.values.len(), n);
    assert_eq!(fit.covariance.len(), n * n);
    assert!(fit.covariance.iter().all(|c| c.is_finite()));
    assert!((0..n).all(|i| fit.covariance[i * n + i] >= 0.0));
    if n > 8 {
        return; // More parameters than a material has: the propagation's cost is not the point.
    }
    let sensor = polbrdf::analysis::detection::Sensor {
        analyzer: polbrdf::analysis::detection::Analyzer::ideal_dofp(),
        noise: polbrdf::analysis::detection::NoiseModel::Nel { nel: 0.05 },
        frames: 1,
        ifov_rad: 1e-4,
    };
    let criteria = Criteria {
        range_limit_m: 1e4,
        ..Criteria::default()
    };
    let path = AirPath::from_visibility(5_000.0, 1.0).unwrap();
    let det = Detector::new(sensor, path, 1.0, criteria).unwrap();
    let background = Stokes::new(1.0, 0.0, 0.05, 0.0);
    // The target's radiance scaled by 1 + Σ tanh(p_i − value_i): finite for any parameters.
    let f = |p: &[f64]| -> polbrdf::Result<Option<f64>> {
        let s: f64 = p.iter().zip(&fit.values).map(|(a, b)| (a - b).tanh()).sum();
        let t = Stokes::new(3.0 * (1.0 + 0.1 * s), 0.5, 0.2, 0.0);
        Ok(match det.max_range(&t, &background, 0.4)? {
            MaxRange::At { range_m, .. } => Some(range_m),
            _ => None,
        })
    };
    if let Ok(Some(p)) = propagate(f, &fit.values, &fit.covariance) {
        assert!(p.sigma.is_finite() && p.sigma >= 0.0, "{p:?}");
    }
});
