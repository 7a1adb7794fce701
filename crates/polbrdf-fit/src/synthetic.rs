//! Synthetic measurements from known parameters, for round-trip tests, benchmarks and
//! simulation studies (how well would a planned measurement set determine the parameters?).

use crate::fit::{Measurement, Observable};
use polbrdf::{Geometry, Material};

/// A small deterministic normal random generator (64-bit LCG + Box–Muller), so that synthetic
/// data sets are reproducible across platforms without a dependency.
#[derive(Debug, Clone)]
pub struct Normal {
    state: u64,
    spare: Option<f64>,
}

impl Normal {
    /// A generator with the given seed.
    pub fn new(seed: u64) -> Self {
        Self {
            state: seed.wrapping_mul(0x9E3779B97F4A7C15) ^ 0xD1B54A32D192ED03,
            spare: None,
        }
    }

    /// Uniform in [0, 1).
    pub fn uniform(&mut self) -> f64 {
        self.state = self
            .state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.state >> 11) as f64) / ((1u64 << 53) as f64)
    }

    /// Standard normal.
    pub fn sample(&mut self) -> f64 {
        if let Some(z) = self.spare.take() {
            return z;
        }
        let u1 = 1.0 - self.uniform();
        let u2 = self.uniform();
        let r = (-2.0 * u1.ln()).sqrt();
        let (s, c) = (2.0 * std::f64::consts::PI * u2).sin_cos();
        self.spare = Some(r * s);
        r * c
    }
}

/// Measurements of `observables` at every geometry, from `material`, with Gaussian noise of
/// standard deviation `relative_noise·|value| + absolute_noise`; each measurement carries that
/// σ when `report_sigma` is true.
pub fn measurements(
    material: &Material,
    geometries: &[Geometry],
    observables: &[Observable],
    relative_noise: f64,
    absolute_noise: f64,
    report_sigma: bool,
    rng: &mut Normal,
) -> Vec<Measurement> {
    let mut out = Vec::with_capacity(geometries.len() * observables.len());
    for g in geometries {
        let e = material.evaluate(g);
        for &obs in observables {
            let v = obs.of(&e);
            let sigma = relative_noise * v.abs() + absolute_noise;
            out.push(Measurement {
                geometry: *g,
                observable: obs,
                value: v + sigma * rng.sample(),
                sigma: report_sigma.then_some(sigma),
            });
        }
    }
    out
}

/// `count` random geometries above the horizon with zenith angles in `[0, max_theta_deg]`
/// (uniform in angle) and uniform azimuths.
pub fn random_geometries(count: usize, max_theta_deg: f64, rng: &mut Normal) -> Vec<Geometry> {
    (0..count)
        .map(|_| {
            let t = max_theta_deg.to_radians();
            let two_pi = 2.0 * std::f64::consts::PI;
            Geometry::new(
                t * rng.uniform(),
                two_pi * rng.uniform(),
                t * rng.uniform(),
                two_pi * rng.uniform(),
            )
            .expect("angles in range")
        })
        .collect()
}
