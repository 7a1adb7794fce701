//! Benchmark of the general fit: 5 free parameters (n, k, σ, ρ_D, ρ_V), 10 000 measurements
//! (5 000 geometries × BRDF and DoLP), 3 starts — on the batch engine, and evaluated one
//! geometry at a time as before the engine (`Evaluator::OneGeometry`), side by side in one run.
//! Run with `cargo bench -p polbrdf-fit`; divan reports medians.

use polbrdf::sample::SplitMix64;
use polbrdf::MaterialSpec;
use polbrdf_fit::synthetic::{measurements, random_geometries};
use polbrdf_fit::{fit, Evaluator, FitOptions, Observable, Param};

fn main() {
    divan::main();
}

fn problem() -> (MaterialSpec, Vec<polbrdf_fit::Measurement>) {
    let mut truth = MaterialSpec::new(1.55, 12.0);
    truth.rho_d = 0.02;
    truth.rho_v = 0.01;
    truth.k = 0.02;
    let material = truth.build().unwrap();
    let mut rng = SplitMix64::new(7);
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

const FREE: [Param; 5] = [
    Param::N,
    Param::K,
    Param::SigmaDeg,
    Param::RhoD,
    Param::RhoV,
];

fn run(bencher: divan::Bencher<'_, '_>, evaluator: Evaluator) {
    let (start, data) = problem();
    let opts = FitOptions {
        evaluator,
        ..FitOptions::default()
    };
    bencher.bench(|| {
        let r = fit(&start, &FREE, &data, &opts).unwrap();
        assert!(r.converged);
        r.chi2
    });
}

/// The fit on the batch engine (the default).
#[divan::bench(sample_count = 10)]
fn five_parameters_10k_points_engine(bencher: divan::Bencher<'_, '_>) {
    run(bencher, Evaluator::Engine);
}

/// The same fit, every residual evaluated one geometry at a time (`Material::evaluate_angles`).
#[divan::bench(sample_count = 10)]
fn five_parameters_10k_points_one_geometry(bencher: divan::Bencher<'_, '_>) {
    run(bencher, Evaluator::OneGeometry);
}
