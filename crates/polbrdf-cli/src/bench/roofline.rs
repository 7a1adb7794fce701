//! The machine's bounds on the kernel's throughput: the memory write bandwidth (plain and
//! non-temporal stores), float32 non-temporal against plain stores, and the floor the
//! elementary functions set on one full-Mueller element.

use super::timing::{median, median_seconds, thread_cpu_s};
use crate::error::CliError;
use polbrdf::engine::{elementary_into, Elementary, Kernel};
use polbrdf::GeometryBatch;
use rayon::prelude::*;
use std::hint::black_box;
use std::time::Instant;

/// The memory write bandwidth (bytes/s) on `threads` threads: the time to fill `n` rows of 16
/// f64 (the size of a full-Mueller output of `n` elements) in parallel chunks, median of
/// `repeats`, with plain stores and with non-temporal ones (`(plain, non_temporal)`; the
/// latter `None` off x86-64 or when the buffer is not 16-byte aligned) — the roofline of a
/// full-Mueller batch is the better of the two over 128 bytes per element (64 in f32): the
/// kernel writes large outputs with non-temporal stores where they pay (docs/model.md §12).
pub(super) fn write_bandwidth(
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

/// Non-temporal against plain stores of float32 row-major output on one thread (the serial
/// kernel, `n` elements of `batch`): the median over `repeats` alternating pairs of each
/// pair's time ratio plain/non-temporal (> 1: non-temporal faster), by the thread's CPU time
/// where the clock is available (else wall time) — what `polbrdf::engine::simd::f32_streams_pay` decides
/// by CPU vendor, measured here (docs/model.md §12, "Stores").
pub(super) fn f32_store_ratio(
    material: &polbrdf::Material,
    batch: &GeometryBatch<'_>,
    repeats: usize,
) -> f64 {
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

/// Nanoseconds per element of each of the kernel's elementary operations on one thread
/// (4096-element arrays, in L1, at the kernel's SIMD level), medians of `repeats`; and the
/// floor they set: what one full-Mueller element of `paint` needs of them
/// ([`FLOOR_COUNTS`]).
pub(super) fn elementary_ns(
    repeats: usize,
    level: polbrdf::engine::SimdLevel,
) -> Vec<(Elementary, f64)> {
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
pub(super) const FLOOR_COUNTS: [(Elementary, f64); 5] = [
    (Elementary::SinCos, 4.0),
    (Elementary::Atan2, 2.0),
    (Elementary::Exp, 2.0),
    (Elementary::Sqrt, 4.0),
    (Elementary::Div, 3.0),
];

/// The floor of [`FLOOR_COUNTS`] at the timed rates `elementary` (ns per element of each
/// operation): the nanoseconds one full-Mueller element needs on one thread for its elementary
/// functions alone.
pub(super) fn floor_ns(elementary: &[(Elementary, f64)]) -> f64 {
    FLOOR_COUNTS
        .iter()
        .map(|(op, k)| {
            k * elementary
                .iter()
                .find(|(o, _)| o == op)
                .map_or(0.0, |e| e.1)
        })
        .sum()
}
