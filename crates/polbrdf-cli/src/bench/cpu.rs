//! Which CPU the benchmark ran on: its model name, and its fused multiply-add throughput by
//! register width (which tells whether AVX2 and AVX-512 widen the arithmetic or only split it).

use super::timing::median_seconds;
use std::hint::black_box;

/// The CPU model from /proc/cpuinfo ("model name", with the family and model numbers, which
/// tell a virtual machine's generic name apart), or the architecture elsewhere.
pub(super) fn cpu_model() -> String {
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

/// The arithmetic roof of one thread: fused multiply-adds per second in 128-bit, 256-bit and
/// (where the CPU has AVX-512F) 512-bit registers (4, 8 and 16 f32 lanes; 2, 4, 8 f64 lanes),
/// 12 independent chains each so that throughput binds, not latency; medians of `repeats`.
/// `None` without AVX2 and FMA. A 256-bit rate near half the 128-bit one means 256-bit
/// operations run as two 128-bit halves (AMD Zen 1): AVX2 then has no more arithmetic
/// throughput than SSE; likewise a 512-bit rate near half the 256-bit one (AMD Zen 4) means
/// AVX-512 adds no FMA throughput, only its other instructions.
pub(super) fn fma_rates(repeats: usize) -> Option<FmaRates> {
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

/// Fused multiply-adds per second of one thread by register width ([`fma_rates`]).
#[derive(Debug, Clone, Copy)]
pub(super) struct FmaRates {
    pub(super) r128: f64,
    pub(super) r256: f64,
    pub(super) r512: Option<f64>,
}

impl FmaRates {
    /// f32 lanes per second at the widest width's rate or a narrower one's, whichever is
    /// more (the peak f32 FLOP/s is twice this, f64's this).
    pub(super) fn lanes(&self) -> f64 {
        (4.0 * self.r128)
            .max(8.0 * self.r256)
            .max(16.0 * self.r512.unwrap_or(0.0))
    }

    /// The widest register width (bits) whose rate reaches that peak within 25 %.
    pub(super) fn widest(&self) -> u32 {
        let peak = self.lanes();
        if self.r512.is_some_and(|r| 16.0 * r >= 0.75 * peak) {
            512
        } else if 8.0 * self.r256 >= 0.75 * peak {
            256
        } else {
            128
        }
    }

    /// Whether 256-bit operations run at full width: more than 1.5 times as many f32 lanes per
    /// second as 128-bit ones (at half rate, as on AMD Zen 1, they give the same).
    pub(super) fn full_width_256(&self) -> bool {
        2.0 * self.r256 > 1.5 * self.r128
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
