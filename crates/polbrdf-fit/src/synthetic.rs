//! Synthetic measurements from known parameters, for round-trip tests, benchmarks and
//! simulation studies (how well would a planned measurement set determine the parameters?).
//! Reproducible with the project's one random generator, [`SplitMix64`].

use crate::fit::{Measurement, Observable};
use polbrdf::sample::SplitMix64;
use polbrdf::{Engine, Geometry, Material};

/// Measurements of `observables` at every geometry, from `material` (evaluated by the engine;
/// each measurement carries the wavelength the material was built at, if any), with Gaussian
/// noise of standard deviation `relative_noise·|value| + absolute_noise`; each
/// measurement carries that σ when `report_sigma` is true.
pub fn measurements(
    material: &Material,
    geometries: &[Geometry],
    observables: &[Observable],
    relative_noise: f64,
    absolute_noise: f64,
    report_sigma: bool,
    rng: &mut SplitMix64,
) -> Vec<Measurement> {
    let f = Engine::new(material)
        .pbrdf_of(geometries)
        .expect("no per-element index");
    let mut out = Vec::with_capacity(geometries.len() * observables.len());
    for (g, f) in geometries.iter().zip(&f) {
        for &obs in observables {
            let v = obs.of_pbrdf(f);
            let sigma = relative_noise * v.abs() + absolute_noise;
            out.push(Measurement {
                geometry: *g,
                observable: obs,
                value: v + sigma * rng.normal(),
                sigma: report_sigma.then_some(sigma),
                wavelength_um: material.wavelength_um(),
            });
        }
    }
    out
}

/// `count` random geometries above the horizon with zenith angles in `[0, max_theta_deg]`
/// (uniform in angle) and uniform azimuths.
pub fn random_geometries(count: usize, max_theta_deg: f64, rng: &mut SplitMix64) -> Vec<Geometry> {
    let t = max_theta_deg.to_radians();
    let two_pi = 2.0 * std::f64::consts::PI;
    (0..count)
        .map(|_| {
            Geometry::new(
                t * rng.next_f64(),
                two_pi * rng.next_f64(),
                t * rng.next_f64(),
                two_pi * rng.next_f64(),
            )
            .expect("angles in range")
        })
        .collect()
}
