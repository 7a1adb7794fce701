//! Run-time choice of the instruction set: the block kernel is compiled for AVX-512, AVX2+FMA
//! and the build target's baseline, and the best one the CPU supports is used.

use std::sync::OnceLock;

/// The instruction set a [`crate::engine::Kernel`] runs with.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SimdLevel {
    /// Baseline code of the build target (SSE2 on x86-64), no FMA on x86-64.
    Portable,
    /// x86-64 with AVX2 and FMA (4 lanes of f64).
    Avx2,
    /// x86-64 with AVX-512 F/DQ/VL (8 lanes of f64).
    Avx512,
}

impl SimdLevel {
    /// A short name: `"portable"`, `"avx2+fma"`, `"avx512"`.
    pub fn name(self) -> &'static str {
        match self {
            SimdLevel::Portable => "portable",
            SimdLevel::Avx2 => "avx2+fma",
            SimdLevel::Avx512 => "avx512",
        }
    }

    /// Whether this CPU can run code of this level.
    pub fn is_supported(self) -> bool {
        match self {
            SimdLevel::Portable => true,
            #[cfg(target_arch = "x86_64")]
            SimdLevel::Avx2 => {
                std::arch::is_x86_feature_detected!("avx2")
                    && std::arch::is_x86_feature_detected!("fma")
            }
            #[cfg(target_arch = "x86_64")]
            SimdLevel::Avx512 => {
                SimdLevel::Avx2.is_supported()
                    && std::arch::is_x86_feature_detected!("avx512f")
                    && std::arch::is_x86_feature_detected!("avx512dq")
                    && std::arch::is_x86_feature_detected!("avx512vl")
            }
            #[cfg(not(target_arch = "x86_64"))]
            _ => false,
        }
    }

    /// Every level this CPU supports, best last.
    pub fn supported() -> Vec<SimdLevel> {
        [SimdLevel::Portable, SimdLevel::Avx2, SimdLevel::Avx512]
            .into_iter()
            .filter(|l| l.is_supported())
            .collect()
    }
}

/// The best level this CPU supports (detected once, then cached): what `Kernel::new` uses.
pub fn simd_level() -> SimdLevel {
    static LEVEL: OnceLock<SimdLevel> = OnceLock::new();
    *LEVEL.get_or_init(|| {
        *SimdLevel::supported()
            .last()
            .unwrap_or(&SimdLevel::Portable)
    })
}

/// Whether large float32 row-major outputs are written with non-temporal stores on this CPU
/// (`Kernel::streaming`): a rule by CPU vendor, from measurements (docs/model.md §12,
/// "Stores"). They paid on an Intel Xeon with AVX-512 (1.23× at 2·10⁶ elements, one thread,
/// issue 34) and lost on AMD: Zen 3 (0.78–0.83×) and Zen 4 (see docs/model.md §12). So: Intel
/// with AVX-512 streams, every other CPU (AMD, Intel without AVX-512, unknown) keeps plain
/// stores, as before. float64 outputs stream on every CPU with AVX (measured to pay on both
/// vendors).
pub fn f32_streams_pay() -> bool {
    static PAYS: OnceLock<bool> = OnceLock::new();
    *PAYS.get_or_init(|| simd_level() == SimdLevel::Avx512 && vendor() == *b"GenuineIntel")
}

/// The CPU's vendor string (CPUID leaf 0), or zeros off x86-64.
fn vendor() -> [u8; 12] {
    #[cfg(target_arch = "x86_64")]
    {
        // SAFETY: CPUID leaf 0 exists on every x86-64 CPU (`unsafe` until Rust 1.94).
        #[allow(unused_unsafe)]
        let r = unsafe { std::arch::x86_64::__cpuid(0) };
        let mut v = [0u8; 12];
        v[..4].copy_from_slice(&r.ebx.to_le_bytes());
        v[4..8].copy_from_slice(&r.edx.to_le_bytes());
        v[8..].copy_from_slice(&r.ecx.to_le_bytes());
        v
    }
    #[cfg(not(target_arch = "x86_64"))]
    [0u8; 12]
}
