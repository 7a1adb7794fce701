//! `polbrdf bench`: throughput of the batch API on random valid geometries of the `paint`
//! preset — full Mueller and BRDF+DoLP evaluations per second on one thread and on all threads
//! (medians of several repeats), the latency of a single evaluation (through the kernel's
//! single-geometry entry point, and through the reference path `Material::evaluate`), the
//! per-element index and a spectral sweep against the constant index, polarized thermal emission
//! at the default accuracy (one view direction, and a table of 90 view angles), a checksum of the
//! results and the CPU it ran on.

use crate::error::CliError;
use polbrdf::analysis::emission::{emissivities, emissivity, Emissivity};
use polbrdf::analysis::facets::FacetRule;
use polbrdf::batch;
use polbrdf::engine::{elementary_into, Elementary, Engine, IndexColumns, Kernel};
use polbrdf::geometry::direction;
use polbrdf::DirectionBatch;
use polbrdf::Geometry;
use polbrdf::GeometryBatch;
use rayon::prelude::*;
use serde_json::json;
use std::hint::black_box;
use std::time::Instant;

/// `polbrdf bench`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Number of random geometries (θ uniform in [0°, 89.9°], φ uniform in [0°, 360°)).
    #[arg(long, value_name = "N", default_value_t = 1_000_000,
          value_parser = crate::values::count(1, crate::limits::BENCH_COUNT))]
    pub count: usize,
    /// Threads of the parallel runs (default: every logical CPU).
    #[arg(long, value_name = "T", value_parser = crate::values::count(1, crate::limits::THREADS))]
    pub threads: Option<usize>,
    /// Timed repeats of each measurement; the medians are reported (at least 5).
    #[arg(long, value_name = "R", default_value_t = 7,
          value_parser = crate::values::count(5, crate::limits::BENCH_REPEATS))]
    pub repeats: usize,
    /// Print the results as one JSON object instead of a table.
    #[arg(long)]
    pub json: bool,
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// Median wall time (s) of `f` over `repeats` runs, after one untimed warm-up run.
fn median_seconds(repeats: usize, mut f: impl FnMut()) -> f64 {
    f();
    median(
        (0..repeats)
            .map(|_| {
                let t = Instant::now();
                f();
                t.elapsed().as_secs_f64()
            })
            .collect(),
    )
}

/// The memory write bandwidth (bytes/s) on `threads` threads: the time to fill `n` rows of 16
/// f64 (the size of a full-Mueller output of `n` elements) in parallel chunks, median of
/// `repeats`, with plain stores and with non-temporal ones (`(plain, non_temporal)`; the
/// latter `None` off x86-64 or when the buffer is not 16-byte aligned) — the roofline of a
/// full-Mueller batch is the better of the two over 128 bytes per element (64 in f32): the
/// kernel writes large outputs with non-temporal stores where they pay (docs/model.md §12).
fn write_bandwidth(
    threads: usize,
    repeats: usize,
    n: usize,
) -> Result<(f64, Option<f64>), CliError> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| CliError::Invalid(format!("--threads = {threads}: {e}")))?;
    let mut buf = vec![[0.0f64; 16]; n];
    let bytes = size_of_val(buf.as_slice()) as f64;
    let mut x = 0.0;
    let plain = pool.install(|| {
        median_seconds(repeats, || {
            x += 1.0;
            buf.par_chunks_mut(4096).for_each(|c| c.fill([x; 16]));
            black_box(&mut buf);
        })
    });
    #[cfg(target_arch = "x86_64")]
    if (buf.as_ptr() as usize).is_multiple_of(16) {
        let nt = pool.install(|| {
            median_seconds(repeats, || {
                x += 1.0;
                buf.par_chunks_mut(4096).for_each(|c| fill_streaming(c, x));
                black_box(&mut buf);
            })
        });
        return Ok((bytes / plain, Some(bytes / nt)));
    }
    Ok((bytes / plain, None))
}

/// `rows` filled with `x` by non-temporal 16-byte stores (SSE2, part of x86-64), then a
/// store fence.
#[cfg(target_arch = "x86_64")]
fn fill_streaming(rows: &mut [[f64; 16]], x: f64) {
    use std::arch::x86_64::{_mm_set1_pd, _mm_sfence, _mm_stream_pd};
    assert!((rows.as_ptr() as usize).is_multiple_of(16));
    // SAFETY: SSE2 is part of x86-64; every store is inside `rows` (16 bytes at an even index
    // of a 16-aligned row of 16 f64, each row 128 bytes, so every store is 16-byte aligned).
    unsafe {
        let v = _mm_set1_pd(x);
        for r in rows.iter_mut() {
            let p = r.as_mut_ptr();
            for k in (0..16).step_by(2) {
                _mm_stream_pd(p.add(k), v);
            }
        }
        _mm_sfence();
    }
}

/// The arithmetic roof of one thread: fused multiply-adds per second in 128-bit, 256-bit and
/// (where the CPU has AVX-512F) 512-bit registers (4, 8 and 16 f32 lanes; 2, 4, 8 f64 lanes),
/// 12 independent chains each so that throughput binds, not latency; medians of `repeats`.
/// `None` without AVX2 and FMA. A 256-bit rate near half the 128-bit one means 256-bit
/// operations run as two 128-bit halves (AMD Zen 1): AVX2 then has no more arithmetic
/// throughput than SSE; likewise a 512-bit rate near half the 256-bit one (AMD Zen 4) means
/// AVX-512 adds no FMA throughput, only its other instructions.
fn fma_rates(repeats: usize) -> Option<FmaRates> {
    #[cfg(target_arch = "x86_64")]
    if is_x86_feature_detected!("avx2") && is_x86_feature_detected!("fma") {
        const ITERS: usize = 4_000_000;
        let mut sink = 0.0f32;
        let s128 = median_seconds(repeats, || {
            // SAFETY: the CPU has AVX2 and FMA (tested above).
            sink += unsafe { fma_chains::<false>(black_box(ITERS)) }
        });
        let s256 = median_seconds(repeats, || {
            // SAFETY: as above.
            sink += unsafe { fma_chains::<true>(black_box(ITERS)) }
        });
        let s512 = is_x86_feature_detected!("avx512f").then(|| {
            median_seconds(repeats, || {
                // SAFETY: the CPU has AVX-512F (tested just above).
                sink += unsafe { fma_chains_512(black_box(ITERS)) }
            })
        });
        black_box(sink);
        let fmas = (FMA_CHAINS * ITERS) as f64;
        return Some(FmaRates {
            r128: fmas / s128,
            r256: fmas / s256,
            r512: s512.map(|s| fmas / s),
        });
    }
    let _ = repeats;
    None
}

/// CPU seconds this thread has run (`CLOCK_THREAD_CPUTIME_ID`), or `None` where that clock is
/// not available.
fn thread_cpu_s() -> Option<f64> {
    #[cfg(unix)]
    {
        let mut ts = libc::timespec {
            tv_sec: 0,
            tv_nsec: 0,
        };
        // SAFETY: `ts` is a valid `timespec` for the call to write.
        if unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut ts) } == 0 {
            return Some(ts.tv_sec as f64 + ts.tv_nsec as f64 * 1e-9);
        }
    }
    None
}

/// Non-temporal against plain stores of float32 row-major output on one thread (the serial
/// kernel, `n` elements of `batch`): the median over `repeats` alternating pairs of each
/// pair's time ratio plain/non-temporal (> 1: non-temporal faster), by the thread's CPU time
/// where the clock is available (else wall time) — what `polbrdf::engine::simd::f32_streams_pay` decides
/// by CPU vendor, measured here (docs/model.md §12, "Stores").
fn f32_store_ratio(material: &polbrdf::Material, batch: &GeometryBatch<'_>, repeats: usize) -> f64 {
    let k = Kernel::new(material);
    let mut out = vec![[0.0f32; 16]; batch.len()];
    let mut timed = |stream: bool| {
        let (c, w) = (thread_cpu_s(), Instant::now());
        k.clone()
            .streaming_f32(stream)
            .mueller_f32_into(batch, 0, &mut out);
        black_box(&mut out);
        match (c, thread_cpu_s()) {
            (Some(a), Some(b)) if b > a => b - a,
            _ => w.elapsed().as_secs_f64(),
        }
    };
    timed(false);
    timed(true);
    median((0..repeats).map(|_| timed(false) / timed(true)).collect())
}

/// Fused multiply-adds per second of one thread by register width ([`fma_rates`]).
#[derive(Debug, Clone, Copy)]
struct FmaRates {
    r128: f64,
    r256: f64,
    r512: Option<f64>,
}

impl FmaRates {
    /// f32 lanes per second at the widest width's rate or a narrower one's, whichever is
    /// more (the peak f32 FLOP/s is twice this, f64's this).
    fn lanes(&self) -> f64 {
        (4.0 * self.r128)
            .max(8.0 * self.r256)
            .max(16.0 * self.r512.unwrap_or(0.0))
    }

    /// The widest register width (bits) whose rate reaches that peak within 25 %.
    fn widest(&self) -> u32 {
        let peak = self.lanes();
        if self.r512.is_some_and(|r| 16.0 * r >= 0.75 * peak) {
            512
        } else if 8.0 * self.r256 >= 0.75 * peak {
            256
        } else {
            128
        }
    }
}

/// [`fma_chains`] in 512-bit registers (16 f32 lanes).
///
/// # Safety
/// The CPU must support AVX-512F.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
unsafe fn fma_chains_512(iters: usize) -> f32 {
    use std::arch::x86_64::*;
    let (m, c) = (_mm512_set1_ps(0.9999), _mm512_set1_ps(1e-4));
    let mut x = [_mm512_setzero_ps(); FMA_CHAINS];
    for (k, v) in x.iter_mut().enumerate() {
        *v = _mm512_set1_ps(1.0 + 0.01 * k as f32);
    }
    for _ in 0..iters {
        for v in x.iter_mut() {
            *v = _mm512_fmadd_ps(*v, m, c);
        }
    }
    let mut sum = _mm512_setzero_ps();
    for v in x {
        sum = _mm512_add_ps(sum, v);
    }
    _mm512_reduce_add_ps(sum)
}

const FMA_CHAINS: usize = 12;

/// `iters` rounds of one fused multiply-add on each of [`FMA_CHAINS`] independent registers,
/// 256-bit wide with `WIDE`, else 128-bit; returns a lane of their sum (to keep them live).
///
/// # Safety
/// The CPU must support AVX2 and FMA.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
unsafe fn fma_chains<const WIDE: bool>(iters: usize) -> f32 {
    use std::arch::x86_64::*;
    // One body for both widths: the intrinsics of one register width.
    macro_rules! chains {
        ($set1:ident, $zero:ident, $fma:ident, $add:ident, $first:ident) => {{
            let (m, c) = ($set1(0.9999), $set1(1e-4));
            let mut x = [$zero(); FMA_CHAINS];
            for (k, v) in x.iter_mut().enumerate() {
                *v = $set1(1.0 + 0.01 * k as f32);
            }
            for _ in 0..iters {
                for v in x.iter_mut() {
                    *v = $fma(*v, m, c);
                }
            }
            let mut sum = $zero();
            for v in x {
                sum = $add(sum, v);
            }
            $first(sum)
        }};
    }
    if WIDE {
        chains!(
            _mm256_set1_ps,
            _mm256_setzero_ps,
            _mm256_fmadd_ps,
            _mm256_add_ps,
            _mm256_cvtss_f32
        )
    } else {
        chains!(
            _mm_set1_ps,
            _mm_setzero_ps,
            _mm_fmadd_ps,
            _mm_add_ps,
            _mm_cvtss_f32
        )
    }
}

/// Nanoseconds per element of each of the kernel's elementary operations on one thread
/// (4096-element arrays, in L1, at the kernel's SIMD level), medians of `repeats`; and the
/// floor they set: what one full-Mueller element of `paint` needs of them
/// ([`FLOOR_COUNTS`]).
fn elementary_ns(repeats: usize, level: polbrdf::engine::SimdLevel) -> Vec<(Elementary, f64)> {
    const N: usize = 4096;
    const REPS: usize = 200;
    let x: Vec<f64> = (0..N)
        .map(|j| 1.5 * ((j * 37) % N) as f64 / N as f64)
        .collect();
    let y: Vec<f64> = (0..N)
        .map(|j| 1.3 * ((j * 71) % N) as f64 / N as f64)
        .collect();
    let mut out = vec![0.0; N];
    Elementary::ALL
        .iter()
        .map(|&op| {
            let s = median_seconds(repeats, || {
                for _ in 0..REPS {
                    elementary_into(level, op, &x, &y, &mut out).expect("the kernel's level");
                    black_box(&mut out);
                }
            });
            (op, s / (N * REPS) as f64 * 1e9)
        })
        .collect()
}

/// How many of each elementary operation one full-Mueller element of `paint` (real index,
/// shadowing without the azimuth factor) takes in the kernel: the sines and cosines of θi, θr,
/// Δ/2, (θi − θr)/2; the arctangents of θN and β; the exponentials of D and SO; the square roots
/// of |s_xy|, |s|, sin β and q; the divisions of the surface term, the Fresnel reflectances and
/// the rotations (the arctangents' own are in theirs).
const FLOOR_COUNTS: [(Elementary, f64); 5] = [
    (Elementary::SinCos, 4.0),
    (Elementary::Atan2, 2.0),
    (Elementary::Exp, 2.0),
    (Elementary::Sqrt, 4.0),
    (Elementary::Div, 3.0),
];

/// The CPU model from /proc/cpuinfo ("model name", with the family and model numbers, which
/// tell a virtual machine's generic name apart), or the architecture elsewhere.
fn cpu_model() -> String {
    std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            let field = |key: &str| {
                s.lines()
                    .find(|l| l.split(':').next().is_some_and(|k| k.trim() == key))
                    .and_then(|l| l.split_once(':'))
                    .map(|(_, v)| v.trim().to_string())
            };
            let name = field("model name")?;
            Some(match (field("cpu family"), field("model")) {
                (Some(f), Some(m)) => format!("{name}, family {f} model {m}"),
                _ => name,
            })
        })
        .unwrap_or_else(|| std::env::consts::ARCH.to_string())
}

/// One thread count's results.
struct Run {
    threads: usize,
    mueller_s: f64,
    /// Full Mueller in single precision (`Engine::mueller_f32_into`).
    mueller_f32_s: f64,
    /// Full Mueller from the same geometries as direction vectors (`DirectionBatch`), f64 and
    /// f32.
    directions_s: f64,
    directions_f32_s: f64,
    brdf_dolp_s: f64,
    mueller_sum: f64,
    brdf_sum: f64,
    dolp_sum: f64,
}

fn run_with(
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
struct IndexRun {
    constant_s: f64,
    /// The spectral material at one wavelength (3.2 µm), as a constant index.
    water_s: f64,
    same_index_s: f64,
    runs_s: f64,
    cycling_s: f64,
    /// Medians of the per-repeat ratios to `water_s` (paired: robust to load drifting between
    /// repeats).
    runs_ratio: f64,
    cycling_ratio: f64,
    same_index_identical: bool,
    spectral_matches: bool,
}

fn run_index(
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

/// The materials of the emission section: two presets and a rough paint.
const EMISSION_MATERIALS: [&str; 3] = ["paint", "aluminium", "paint-sigma30"];
/// View zeniths (degrees) of the single-direction timings.
const EMISSION_THETAS_DEG: [f64; 3] = [0.0, 45.0, 80.0];
/// Calls per timed repeat of a single direction (the time per call is their mean).
const EMISSION_CALLS: usize = 3;

/// A preset, or `paint-sigma30`: the `paint` preset with σ = 30°.
fn emission_material(name: &str) -> Result<polbrdf::Material, CliError> {
    let spec = match name {
        "paint-sigma30" => polbrdf::MaterialSpec {
            name: Some(name.into()),
            sigma_deg: Some(30.0),
            ..polbrdf::preset("paint").map_err(CliError::Model)?
        },
        preset => polbrdf::preset(preset).map_err(CliError::Model)?,
    };
    spec.build().map_err(CliError::Model)
}

/// One `emissivity` call (default rule, both routes) toward one view direction: seconds per
/// call (medians over the repeats of the mean of [`EMISSION_CALLS`] calls), on one thread and on
/// the parallel pool.
struct EmissionDirection {
    material: &'static str,
    sigma_deg: f64,
    theta_deg: f64,
    /// Quadrature nodes of the rule per route (the call evaluates F at twice as many).
    nodes: usize,
    one_thread_s: f64,
    parallel_s: f64,
    eps: Emissivity,
}

/// Polarized thermal emission at the default accuracy: single directions, and the 90-angle
/// table θ = 0°…89° of `paint` through the batch function `emissivities` (directions in
/// parallel, each direction's nodes in parallel chunks).
struct EmissionRun {
    directions: Vec<EmissionDirection>,
    table_one_thread_s: f64,
    table_parallel_s: f64,
    /// Σ ε0 over the table.
    table_eps0_sum: f64,
    /// The table is bit-identical on one thread and on the parallel pool, and a single call
    /// gives the table's entry at the same angle.
    consistent: bool,
}

fn run_emission(repeats: usize, threads: usize) -> Result<EmissionRun, CliError> {
    let build = |t: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(t)
            .build()
            .map_err(|e| CliError::Invalid(format!("--threads = {t}: {e}")))
    };
    let one = build(1)?;
    let parallel = build(threads)?;
    let mut directions = Vec::new();
    for name in EMISSION_MATERIALS {
        let m = emission_material(name)?;
        let rule = FacetRule::for_material(&m).full();
        for theta_deg in EMISSION_THETAS_DEG {
            let t = theta_deg.to_radians();
            let eps = emissivity(&m, t).map_err(CliError::Model)?;
            let time = |pool: &rayon::ThreadPool| {
                pool.install(|| {
                    median_seconds(repeats, || {
                        for _ in 0..EMISSION_CALLS {
                            black_box(
                                emissivity(black_box(&m), black_box(t)).expect("valid angle"),
                            );
                        }
                    })
                }) / EMISSION_CALLS as f64
            };
            let one_thread_s = time(&one);
            let parallel_s = if threads == 1 {
                one_thread_s
            } else {
                time(&parallel)
            };
            directions.push(EmissionDirection {
                material: name,
                sigma_deg: m.distribution().sigma().to_degrees(),
                theta_deg,
                nodes: rule.nodes(t).len(),
                one_thread_s,
                parallel_s,
                eps,
            });
        }
    }
    let m = emission_material(EMISSION_MATERIALS[0])?;
    let thetas: Vec<f64> = (0..90).map(|d| f64::from(d).to_radians()).collect();
    // The two pools interleaved, so that a change of machine load affects both alike; no
    // separate warm-up (the single directions above ran the same code).
    let pools: &[&rayon::ThreadPool] = if threads == 1 {
        &[&one]
    } else {
        &[&one, &parallel]
    };
    let mut tables = vec![Vec::new(); pools.len()];
    let mut times = vec![Vec::new(); pools.len()];
    for _ in 0..repeats {
        for (k, pool) in pools.iter().enumerate() {
            let t = Instant::now();
            tables[k] = pool
                .install(|| emissivities(black_box(&m), black_box(&thetas)))
                .map_err(CliError::Model)?;
            black_box(&tables[k]);
            times[k].push(t.elapsed().as_secs_f64());
        }
    }
    let times: Vec<f64> = times.into_iter().map(median).collect();
    let (table_one_thread_s, table_parallel_s) = (times[0], times[times.len() - 1]);
    let on_one = &tables[0];
    let on_parallel = &tables[tables.len() - 1];
    let consistent = on_one == on_parallel
        && directions
            .iter()
            .filter(|d| d.material == EMISSION_MATERIALS[0])
            .all(|d| on_one[d.theta_deg as usize] == d.eps);
    Ok(EmissionRun {
        table_one_thread_s,
        table_parallel_s,
        table_eps0_sum: on_one.iter().map(|e| e.eps.0[0]).sum(),
        consistent,
        directions,
    })
}

/// Median latency (ns) of one call of `f` on the first geometries of the batch.
fn latency_ns<T>(batch: &GeometryBatch<'_>, f: impl Fn(&Geometry) -> T) -> f64 {
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

/// Runs `polbrdf bench`.
pub fn run(args: &Args) -> Result<(), CliError> {
    // --count, --repeats (at least 5, for a meaningful median) and --threads are in range
    // (their value parsers); the default thread count is the machine's.
    let all = std::thread::available_parallelism().map_or(1, |n| n.get());
    let threads = args.threads.unwrap_or(all).min(crate::limits::THREADS);
    let material = polbrdf::preset("paint")
        .and_then(|s| s.build())
        .map_err(CliError::Model)?;
    let n = args.count;
    // Seed 2024: the same stream in `polbrdf bench` and python/examples/bench_batch.rs.
    let mut rng = polbrdf::sample::SplitMix64::new(2024);
    let ti = rng.uniform(0.0, 89.9f64.to_radians(), n);
    let pi = rng.uniform(0.0, 360f64.to_radians(), n);
    let tr = rng.uniform(0.0, 89.9f64.to_radians(), n);
    let pr = rng.uniform(0.0, 360f64.to_radians(), n);
    let batch = GeometryBatch::new(&ti, &pi, &tr, &pr).map_err(CliError::Model)?;
    let w_i: Vec<_> = ti.iter().zip(&pi).map(|(t, p)| direction(*t, *p)).collect();
    let w_r: Vec<_> = tr.iter().zip(&pr).map(|(t, p)| direction(*t, *p)).collect();
    let directions = DirectionBatch::new(&w_i, &w_r).map_err(CliError::Model)?;

    let mut counts = vec![1];
    if threads != 1 {
        counts.push(threads);
    }
    let runs = counts
        .iter()
        .map(|&t| run_with(t, args.repeats, &material, &batch, &directions))
        .collect::<Result<Vec<_>, _>>()?;
    let (plain_bw, nt_bw) = write_bandwidth(threads, args.repeats, n)?;
    // The roofline: the better of plain and non-temporal stores (the kernel streams large
    // outputs where that pays).
    let bandwidth = plain_bw.max(nt_bw.unwrap_or(0.0));
    let elementary = elementary_ns(args.repeats, Kernel::new(&material).level());
    let fma = fma_rates(args.repeats);
    let store_ratio = f32_store_ratio(&material, &batch, args.repeats);
    // f32 lanes per second at the best width, and whether 256 bits run at full width.
    let fma_lanes = fma.map(|f| f.lanes());
    let full_width = fma.map(|f| 2.0 * f.r256 > 1.5 * f.r128);
    let floor_ns: f64 = FLOOR_COUNTS
        .iter()
        .map(|(op, k)| {
            k * elementary
                .iter()
                .find(|(o, _)| o == op)
                .map_or(0.0, |e| e.1)
        })
        .sum();
    let index = run_index(args.repeats, &material, &batch)?;
    let emission = run_emission(args.repeats, threads)?;
    let kernel = Kernel::new(&material);
    let latency_kernel = latency_ns(&batch, |g| kernel.pbrdf(g));
    let latency_reference = latency_ns(&batch, |g| material.evaluate(g));
    let cpu = cpu_model();
    let simd = kernel.level().name();
    // The results do not depend on the thread count: one checksum for all runs.
    let consistent = runs.iter().all(|r| {
        r.mueller_sum.to_bits() == runs[0].mueller_sum.to_bits()
            && r.brdf_sum.to_bits() == runs[0].brdf_sum.to_bits()
    });
    let per_s = |s: f64| n as f64 / s;

    if args.json {
        let results: Vec<_> = runs
            .iter()
            .map(|r| {
                json!({
                    "threads": r.threads,
                    "mueller_evals_per_s": per_s(r.mueller_s),
                    "mueller_f32_evals_per_s": per_s(r.mueller_f32_s),
                    "mueller_directions_evals_per_s": per_s(r.directions_s),
                    "mueller_directions_f32_evals_per_s": per_s(r.directions_f32_s),
                    "brdf_dolp_evals_per_s": per_s(r.brdf_dolp_s),
                    "mueller_seconds": r.mueller_s,
                    "brdf_dolp_seconds": r.brdf_dolp_s,
                })
            })
            .collect();
        let per_direction: Vec<_> = emission
            .directions
            .iter()
            .map(|d| {
                json!({
                    "material": d.material,
                    "sigma_deg": d.sigma_deg,
                    "theta_deg": d.theta_deg,
                    "nodes": d.nodes,
                    "one_thread_ms": 1e3 * d.one_thread_s,
                    "all_threads_ms": 1e3 * d.parallel_s,
                    "eps0": d.eps.eps.0[0],
                })
            })
            .collect();
        let doc = json!({
            "material": "paint",
            "count": n,
            "repeats": args.repeats,
            "statistic": "median",
            "cpu": {"model": cpu, "logical_cpus": all, "simd": simd},
            "results": results,
            "write_bandwidth": {
                "threads": threads,
                "bytes_per_s": bandwidth,
                "plain_bytes_per_s": plain_bw,
                "non_temporal_bytes_per_s": nt_bw,
                "full_mueller_roofline_evals_per_s": bandwidth / 128.0,
                "full_mueller_f32_roofline_evals_per_s": bandwidth / 64.0,
            },
            "f32_non_temporal_stores": {
                "paired_ratio_one_thread": store_ratio,
                "used": polbrdf::engine::simd::f32_streams_pay(),
            },
            "fma_throughput_one_thread": fma.map(|f| json!({
                "fma_per_s_128bit": f.r128,
                "fma_per_s_256bit": f.r256,
                "fma_per_s_512bit": f.r512,
                "widest_full_rate_bits": f.widest(),
                "peak_f32_flops": 2.0 * fma_lanes.unwrap_or(0.0),
                "peak_f64_flops": fma_lanes.unwrap_or(0.0),
                "full_width_256bit": full_width,
            })),
            "elementary_ns_per_element_one_thread": elementary
                .iter()
                .map(|(op, ns)| (op.name().to_string(), json!(ns)))
                .collect::<serde_json::Map<_, _>>(),
            "elementary_floor": {
                "counts": FLOOR_COUNTS
                    .iter()
                    .map(|(op, k)| (op.name().to_string(), json!(k)))
                    .collect::<serde_json::Map<_, _>>(),
                "ns_per_element_one_thread": floor_ns,
                "max_full_mueller_evals_per_s_one_thread": 1e9 / floor_ns,
            },
            "per_element_index": {
                "threads": threads,
                "constant_index_brdf_dolp_evals_per_s": per_s(index.constant_s),
                "same_index_per_element_evals_per_s": per_s(index.same_index_s),
                "spectral_sweep_runs_evals_per_s": per_s(index.runs_s),
                "spectral_sweep_cycling_evals_per_s": per_s(index.cycling_s),
                "same_index_overhead": index.same_index_s / index.constant_s - 1.0,
                "water_constant_index_evals_per_s": per_s(index.water_s),
                "spectral_sweep_runs_overhead": index.runs_ratio - 1.0,
                "spectral_sweep_cycling_overhead": index.cycling_ratio - 1.0,
                "spectral_sweep_matches_one_wavelength": index.spectral_matches,
                "same_index_results_identical": index.same_index_identical,
            },
            "single_eval_ns": {
                "kernel": latency_kernel,
                "reference": latency_reference,
            },
            "emission": {
                "accuracy": "default (FacetRule::for_material), both routes",
                "threads": threads,
                "per_direction": per_direction,
                "table_90": {
                    "material": EMISSION_MATERIALS[0],
                    "theta_deg": "0..89",
                    "one_thread_ms": 1e3 * emission.table_one_thread_s,
                    "all_threads_ms": 1e3 * emission.table_parallel_s,
                    "eps0_sum": emission.table_eps0_sum,
                },
                "same_for_all_thread_counts": emission.consistent,
            },
            "checksum": {
                "brdf_sum": runs[0].brdf_sum,
                "dolp_sum": runs[0].dolp_sum,
                "mueller_sum": runs[0].mueller_sum,
                "same_for_all_thread_counts": consistent,
            },
        });
        println!(
            "{}",
            serde_json::to_string_pretty(&doc).expect("serializable")
        );
    } else {
        println!(
            "polbrdf bench: {n} random valid geometries of `paint` through the batch API, \
             medians of {} repeats",
            args.repeats
        );
        println!("CPU: {cpu} ({all} logical CPUs); kernel SIMD level: {simd}");
        println!();
        println!(
            "{:<10} {:>22} {:>22} {:>22} {:>22} {:>22}",
            "threads",
            "full Mueller",
            "full Mueller, f32",
            "from vectors",
            "from vectors, f32",
            "BRDF + DoLP"
        );
        for r in &runs {
            println!(
                "{:<10} {:>15.2} M/s   {:>15.2} M/s   {:>15.2} M/s   {:>15.2} M/s   {:>15.2} M/s",
                r.threads,
                per_s(r.mueller_s) / 1e6,
                per_s(r.mueller_f32_s) / 1e6,
                per_s(r.directions_s) / 1e6,
                per_s(r.directions_f32_s) / 1e6,
                per_s(r.brdf_dolp_s) / 1e6
            );
        }
        println!(
            "memory write bandwidth ({threads} threads, {:.0} MB filled): {:.1} GB/s plain, \
             {} non-temporal — the full-Mueller roofline (the better) is {:.1} M/s in f64 \
             (128 B each), {:.1} M/s in f32",
            (n * 128) as f64 / 1e6,
            plain_bw / 1e9,
            nt_bw.map_or("n/a".to_string(), |b| format!("{:.1} GB/s", b / 1e9)),
            bandwidth / 128e6,
            bandwidth / 64e6
        );
        println!(
            "float32 output, non-temporal against plain stores (1 thread, paired CPU-time \
             ratios, median): {store_ratio:.2}x — {} on this CPU",
            if polbrdf::engine::simd::f32_streams_pay() {
                "used"
            } else {
                "not used"
            }
        );
        if let (Some(f), Some(lanes), Some(full)) = (fma, fma_lanes, full_width) {
            println!(
                "fused multiply-adds (1 thread): {:.2} G/s in 128-bit registers, {:.2} G/s in \
                 256-bit, {} in 512-bit (widest at full rate: {} bits): a peak of {:.1} GFLOP/s \
                 in f32, {:.1} in f64 per thread{}",
                f.r128 / 1e9,
                f.r256 / 1e9,
                f.r512
                    .map_or("n/a".to_string(), |r| format!("{:.2} G/s", r / 1e9)),
                f.widest(),
                2.0 * lanes / 1e9,
                lanes / 1e9,
                if full {
                    ""
                } else {
                    " — 256-bit operations at half rate (two 128-bit halves, as on AMD Zen 1): \
                     AVX2 has no more arithmetic throughput than SSE here"
                }
            );
        }
        let list: Vec<String> = elementary
            .iter()
            .map(|(op, ns)| format!("{} {ns:.2}", op.name()))
            .collect();
        let counts: Vec<String> = FLOOR_COUNTS
            .iter()
            .map(|(op, k)| format!("{k} {}", op.name()))
            .collect();
        println!(
            "elementary functions (1 thread, ns per element): {}; one full-Mueller element \
             needs {} = {floor_ns:.1} ns: at most {:.1} M/s per thread with nothing else",
            list.join(", "),
            counts.join(" + "),
            1e3 / floor_ns
        );
        println!();
        println!(
            "BRDF + DoLP with a complex index per element ({threads} threads): \
             {:.2} M/s with the material's own index; the same N in every element {:.2} M/s \
             ({:+.1} %{})",
            per_s(index.constant_s) / 1e6,
            per_s(index.same_index_s) / 1e6,
            100.0 * (index.same_index_s / index.constant_s - 1.0),
            if index.same_index_identical {
                ", identical results"
            } else {
                ", RESULTS DIFFER"
            },
        );
        println!(
            "spectral sweep ({threads} threads; water's tabulated index, 100 wavelengths 0.4–14 µm, \
             looked up in the engine): {:.2} M/s in runs ({:+.1} %), {:.2} M/s cycling ({:+.1} %) \
             against {:.2} M/s with water's index at 3.2 µm as a constant (time ratios: medians \
             of paired repeats){}",
            per_s(index.runs_s) / 1e6,
            100.0 * (index.runs_ratio - 1.0),
            per_s(index.cycling_s) / 1e6,
            100.0 * (index.cycling_ratio - 1.0),
            per_s(index.water_s) / 1e6,
            if index.spectral_matches {
                ""
            } else {
                " — DIFFERS from the material built at one wavelength"
            },
        );
        println!(
            "single evaluation: {latency_kernel:.1} ns (kernel, Kernel::pbrdf), \
             {latency_reference:.1} ns (one-geometry path, Material::evaluate)"
        );
        println!();
        println!(
            "emission (default accuracy, both routes of Kirchhoff's law): one `emissivity` call, \
             ms (medians)"
        );
        // The parallel column only when it is a different pool.
        let parallel_col = |ms: String| if threads == 1 { String::new() } else { ms };
        println!(
            "{:<15} {:>5} {:>5} {:>7} {:>10}{} {:>9}",
            "material",
            "σ",
            "θ",
            "nodes",
            "1 thread",
            parallel_col(format!(" {:>10}", format!("{threads} threads"))),
            "ε0"
        );
        for d in &emission.directions {
            println!(
                "{:<15} {:>4.0}° {:>4.0}° {:>7} {:>10.3}{} {:>9.6}",
                d.material,
                d.sigma_deg,
                d.theta_deg,
                d.nodes,
                1e3 * d.one_thread_s,
                parallel_col(format!(" {:>10.3}", 1e3 * d.parallel_s)),
                d.eps.eps.0[0]
            );
        }
        println!(
            "90-angle table of `{}` (θ = 0°…89°, `emissivities`): {:.1} ms on 1 thread{}; \
             Σ ε0 = {:.12e}{}",
            EMISSION_MATERIALS[0],
            1e3 * emission.table_one_thread_s,
            parallel_col(format!(
                ", {:.1} ms on {threads} threads",
                1e3 * emission.table_parallel_s
            )),
            emission.table_eps0_sum,
            match (threads, emission.consistent) {
                (1, true) => " (a single call gives the same ε)",
                (_, true) => " (identical for every thread count)",
                (1, false) => " (DIFFERS from a single call)",
                (_, false) => " (DIFFERS between thread counts)",
            }
        );
        println!(
            "checksum: Σ brdf = {:.12e}, Σ dolp = {:.12e}, Σ F = {:.12e}{}",
            runs[0].brdf_sum,
            runs[0].dolp_sum,
            runs[0].mueller_sum,
            if consistent {
                " (identical for every thread count)"
            } else {
                " (DIFFERS between thread counts)"
            }
        );
    }
    Ok(())
}
