//! The batch API's measurements: the random geometries, full-Mueller and BRDF+DoLP throughput
//! per thread count, the per-element and spectral index against the constant one, and the
//! latency of a single evaluation.

use super::timing::{median, median_seconds};
use crate::error::CliError;
use polbrdf::batch;
use polbrdf::engine::{Engine, IndexColumns};
use polbrdf::geometry::direction;
use polbrdf::DirectionBatch;
use polbrdf::Geometry;
use polbrdf::GeometryBatch;
use std::hint::black_box;
use std::time::Instant;

/// The benchmark's random valid geometries, as angles and as direction vectors.
pub(super) struct Geometries {
    ti: Vec<f64>,
    pi: Vec<f64>,
    tr: Vec<f64>,
    pr: Vec<f64>,
    w_i: Vec<[f64; 3]>,
    w_r: Vec<[f64; 3]>,
}

impl Geometries {
    /// `n` geometries: θ uniform in [0°, 89.9°], φ uniform in [0°, 360°), from the seeded
    /// stream (seed 2024: the same stream in `polbrdf bench` and
    /// python/examples/bench_batch.rs).
    pub(super) fn random(n: usize) -> Self {
        let mut rng = polbrdf::sample::SplitMix64::new(2024);
        let ti = rng.uniform(0.0, 89.9f64.to_radians(), n);
        let pi = rng.uniform(0.0, 360f64.to_radians(), n);
        let tr = rng.uniform(0.0, 89.9f64.to_radians(), n);
        let pr = rng.uniform(0.0, 360f64.to_radians(), n);
        let w_i = ti.iter().zip(&pi).map(|(t, p)| direction(*t, *p)).collect();
        let w_r = tr.iter().zip(&pr).map(|(t, p)| direction(*t, *p)).collect();
        Geometries {
            ti,
            pi,
            tr,
            pr,
            w_i,
            w_r,
        }
    }

    /// The geometries as angles.
    pub(super) fn angles(&self) -> Result<GeometryBatch<'_>, CliError> {
        GeometryBatch::new(&self.ti, &self.pi, &self.tr, &self.pr).map_err(CliError::Model)
    }

    /// The same geometries as direction vectors.
    pub(super) fn directions(&self) -> Result<DirectionBatch<'_>, CliError> {
        DirectionBatch::new(&self.w_i, &self.w_r).map_err(CliError::Model)
    }
}

/// One thread count's results.
pub(super) struct Run {
    pub(super) threads: usize,
    pub(super) mueller_s: f64,
    /// Full Mueller in single precision (`Engine::mueller_f32_into`).
    pub(super) mueller_f32_s: f64,
    /// Full Mueller from the same geometries as direction vectors (`DirectionBatch`), f64 and
    /// f32.
    pub(super) directions_s: f64,
    pub(super) directions_f32_s: f64,
    pub(super) brdf_dolp_s: f64,
    pub(super) mueller_sum: f64,
    pub(super) brdf_sum: f64,
    pub(super) dolp_sum: f64,
}

/// The batch API's throughput on `threads` threads: seconds per batch of each route (medians
/// of `repeats`) and the checksums of the results.
pub(super) fn run_with(
    threads: usize,
    repeats: usize,
    material: &polbrdf::Material,
    batch: &GeometryBatch<'_>,
    directions: &DirectionBatch<'_>,
) -> Result<Run, CliError> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| CliError::Invalid(format!("--threads = {threads}: {e}")))?;
    let n = batch.len();
    let time = |f: &mut (dyn FnMut() + Send)| pool.install(|| median_seconds(repeats, f));
    let engine = Engine::new(material);
    let mut out = vec![[0.0; 16]; n];
    let mut out32 = vec![[0.0f32; 16]; n];
    let (mut brdf, mut dolp) = (vec![0.0; n], vec![0.0; n]);
    let mueller_s = time(&mut || {
        batch::mueller_into(material, batch, &mut out).expect("lengths match");
        black_box(&mut out);
    });
    // The checksum is the angle route's, before the direction route reuses `out`.
    let mueller_sum = out.iter().flatten().sum();
    let mueller_f32_s = time(&mut || {
        engine
            .mueller_f32_into(batch, &mut out32)
            .expect("lengths match, paint within f32");
        black_box(&mut out32);
    });
    let directions_s = time(&mut || {
        engine
            .mueller_into(directions, &mut out)
            .expect("lengths match");
        black_box(&mut out);
    });
    let directions_f32_s = time(&mut || {
        engine
            .mueller_f32_into(directions, &mut out32)
            .expect("lengths match, paint within f32");
        black_box(&mut out32);
    });
    let brdf_dolp_s = time(&mut || {
        batch::brdf_dolp_into(material, batch, &mut brdf, &mut dolp).expect("lengths match");
        black_box((&mut brdf, &mut dolp));
    });
    Ok(Run {
        threads,
        mueller_s,
        mueller_f32_s,
        directions_s,
        directions_f32_s,
        brdf_dolp_s,
        mueller_sum,
        brdf_sum: brdf.iter().sum(),
        dolp_sum: dolp.iter().sum(),
    })
}

/// The engine with a complex index per element, against the material's own index (all
/// threads): the same N in every element (the overhead of the per-element path alone, identical
/// results), and a spectral sweep — the `paint` geometry with the tabulated index of water
/// (`library:H2O/Hale`) at 100 wavelengths log-spaced over 0.4–14 µm, one wavelength per
/// element, looked up inside the engine (`Engine::with_wavelengths`) and timed with it; the
/// wavelengths in 100 contiguous runs (wavelength-major) and cycling element by element
/// (wavelength-minor); against the same material with its index at one wavelength as a
/// constant. Seconds per batch (medians).
pub(super) struct IndexRun {
    pub(super) constant_s: f64,
    /// The spectral material at one wavelength (3.2 µm), as a constant index.
    pub(super) water_s: f64,
    pub(super) same_index_s: f64,
    pub(super) runs_s: f64,
    pub(super) cycling_s: f64,
    /// Medians of the per-repeat ratios to `water_s` (paired: robust to load drifting between
    /// repeats).
    pub(super) runs_ratio: f64,
    pub(super) cycling_ratio: f64,
    pub(super) same_index_identical: bool,
    pub(super) spectral_matches: bool,
}

/// The measurements of [`IndexRun`] on the current thread pool, `repeats` interleaved rounds.
pub(super) fn run_index(
    repeats: usize,
    material: &polbrdf::Material,
    batch: &GeometryBatch<'_>,
) -> Result<IndexRun, CliError> {
    let n = batch.len();
    let (mut b0, mut d0) = (vec![0.0; n], vec![0.0; n]);
    let (mut b1, mut d1) = (vec![0.0; n], vec![0.0; n]);
    let (mut b2, mut d2) = (vec![0.0; n], vec![0.0; n]);
    let (mut b3, mut d3) = (vec![0.0; n], vec![0.0; n]);
    let index = material.index();
    let same_n = vec![index.n(); n];
    let same_k = vec![index.k(); n];
    let same = IndexColumns::new(&same_n, &same_k).expect("valid index");
    let constant = Engine::new(material);
    let per_element = Engine::new(material).with_index(same);
    // The spectral material: paint's surface with water's index.
    let mut spec = material.spec().clone();
    spec.spectral = Some(polbrdf::model::SpectralSource {
        source: "library:H2O/Hale".into(),
        index: std::sync::Arc::new(polbrdf_io::library::load("H2O/Hale")?),
    });
    let lambdas: Vec<f64> = (0..100)
        .map(|j| 0.4 * (35f64.ln() * j as f64 / 99.0).exp())
        .collect();
    let runs: Vec<f64> = (0..n).map(|i| lambdas[i * 100 / n]).collect();
    let cycling: Vec<f64> = (0..n).map(|i| lambdas[i % 100]).collect();
    let spectral = spec.build_at(lambdas[0]).map_err(CliError::Model)?;
    let water = spec.build_at(lambdas[60]).map_err(CliError::Model)?;
    let water_constant = Engine::new(&water);
    let (mut b4, mut d4) = (vec![0.0; n], vec![0.0; n]);
    let sweep = |wl: &[f64], b: &mut [f64], d: &mut [f64]| {
        Engine::new(&spectral)
            .with_wavelengths(wl)
            .expect("inside the data")
            .brdf_dolp_into(batch, b, d)
            .expect("lengths match");
    };
    let mut constant_s = Vec::new();
    let mut water_s = Vec::new();
    let mut same_index_s = Vec::new();
    let mut runs_s = Vec::new();
    let mut cycling_s = Vec::new();
    // Interleaved, so that a change of machine load affects all alike.
    for _ in 0..repeats {
        for (engine, b, d, times) in [
            (&constant, &mut b0, &mut d0, &mut constant_s),
            (&per_element, &mut b1, &mut d1, &mut same_index_s),
            (&water_constant, &mut b4, &mut d4, &mut water_s),
        ] {
            let t = Instant::now();
            engine.brdf_dolp_into(batch, b, d).expect("lengths match");
            black_box((b, d));
            times.push(t.elapsed().as_secs_f64());
        }
        let t = Instant::now();
        sweep(&runs, &mut b2, &mut d2);
        black_box((&b2, &d2));
        runs_s.push(t.elapsed().as_secs_f64());
        let t = Instant::now();
        sweep(&cycling, &mut b3, &mut d3);
        black_box((&b3, &d3));
        cycling_s.push(t.elapsed().as_secs_f64());
    }
    // A spot check of the sweep against the material built at one wavelength.
    let i = n / 2;
    let at = spec.build_at(runs[i]).map_err(CliError::Model)?;
    let want = at.evaluate(&batch.get(i)).pbrdf.m00();
    Ok(IndexRun {
        constant_s: median(constant_s),
        water_s: median(water_s.clone()),
        same_index_s: median(same_index_s),
        runs_ratio: median(runs_s.iter().zip(&water_s).map(|(a, b)| a / b).collect()),
        cycling_ratio: median(cycling_s.iter().zip(&water_s).map(|(a, b)| a / b).collect()),
        runs_s: median(runs_s),
        cycling_s: median(cycling_s),
        same_index_identical: b0 == b1 && d0 == d1,
        spectral_matches: (b2[i] - want).abs() <= 1e-12 * want.abs().max(1e-300),
    })
}

/// Median latency (ns) of one call of `f` on the first geometries of the batch.
pub(super) fn latency_ns<T>(batch: &GeometryBatch<'_>, f: impl Fn(&Geometry) -> T) -> f64 {
    let geoms: Vec<Geometry> = (0..batch.len().min(1024)).map(|i| batch.get(i)).collect();
    const CALLS: usize = 20_000;
    let mut samples = Vec::with_capacity(31);
    for _ in 0..31 {
        let t = Instant::now();
        for k in 0..CALLS {
            black_box(f(black_box(&geoms[k % geoms.len()])));
        }
        samples.push(t.elapsed().as_secs_f64() * 1e9 / CALLS as f64);
    }
    median(samples)
}
