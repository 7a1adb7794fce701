//! Benchmark of the general fit: 5 free parameters, 10 000 measurements (5 000 geometries ×
//! BRDF and DoLP). Run with `cargo bench -p polbrdf-fit`; divan reports medians.

use polbrdf::MaterialSpec;
use polbrdf_fit::synthetic::{measurements, random_geometries, Normal};
use polbrdf_fit::{fit, FitOptions, Observable, Param};

fn main() {
    divan::main();
}

fn problem() -> (MaterialSpec, Vec<polbrdf_fit::Measurement>) {
    let mut truth = MaterialSpec::new(1.55, 12.0);
    truth.rho_d = 0.02;
    truth.rho_v = 0.01;
    truth.k = 0.02;
    let material = truth.build().unwrap();
    let mut rng = Normal::new(7);
    let geoms = random_geometries(5_000, 80.0, &mut rng);
    let data = measurements(
        &material,
        &geoms,
        &[Observable::Brdf, Observable::Dolp],
        0.02,
        1e-4,
        true,
        &mut rng,
    );
    let mut start = truth.clone();
    start.n = 1.4;
    start.sigma_deg = Some(20.0);
    start.rho_d = 0.05;
    start.rho_v = 0.0;
    start.k = 0.05;
    (start, data)
}

#[divan::bench(sample_count = 10)]
fn five_parameters_10k_points(bencher: divan::Bencher) {
    let (start, data) = problem();
    let free = [
        Param::N,
        Param::K,
        Param::SigmaDeg,
        Param::RhoD,
        Param::RhoV,
    ];
    bencher.bench(|| {
        let r = fit(&start, &free, &data, &FitOptions::default()).unwrap();
        assert!(r.converged);
        r.chi2
    });
}
