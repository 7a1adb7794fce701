//! The project's one random generator, for benchmarks, tests, fit starts and simulation
//! studies: deterministic, so that the same seed gives the same numbers on every platform and in
//! every tool (the `polbrdf bench` command and the Python package's Rust baseline time identical
//! inputs; synthetic measurement sets are reproducible).
//!
//! It is also a `rand_core` generator ([`rand_core::Rng`], through [`rand_core::TryRng`]), so
//! the distributions of `rand_distr` (Poisson, normal) draw from it: the simulated camera frame
//! (`analysis::detection::frame`) is reproducible from its seed like everything else.

/// SplitMix64 (Steele, Lea & Flood 2014): 64-bit state, uniform doubles in [0, 1).
#[derive(Debug, Clone)]
pub struct SplitMix64 {
    state: u64,
    /// The second value of the last Box–Muller pair, not yet returned by [`SplitMix64::normal`].
    spare: Option<f64>,
}

impl SplitMix64 {
    /// A generator with the given seed.
    pub fn new(seed: u64) -> Self {
        Self {
            state: seed,
            spare: None,
        }
    }

    /// The next 64 random bits.
    pub fn next_bits(&mut self) -> u64 {
        self.state = self.state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1), with 53 random bits.
    pub fn next_f64(&mut self) -> f64 {
        (self.next_bits() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in [lo, hi).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next_f64()
    }

    /// Uniform integer in [0, n) (`n > 0`).
    pub fn below(&mut self, n: usize) -> usize {
        ((self.next_f64() * n as f64) as usize).min(n - 1)
    }

    /// `n` values uniform in [lo, hi).
    pub fn uniform(&mut self, lo: f64, hi: f64, n: usize) -> Vec<f64> {
        (0..n).map(|_| self.range(lo, hi)).collect()
    }

    /// A standard normal deviate (Box–Muller on two uniforms; the pair's second value is kept
    /// for the next call).
    pub fn normal(&mut self) -> f64 {
        if let Some(z) = self.spare.take() {
            return z;
        }
        let u1 = 1.0 - self.next_f64(); // in (0, 1]: ln is finite
        let u2 = self.next_f64();
        let r = (-2.0 * u1.ln()).sqrt();
        let (s, c) = (2.0 * std::f64::consts::PI * u2).sin_cos();
        self.spare = Some(r * s);
        r * c
    }
}

impl rand_core::TryRng for SplitMix64 {
    type Error = core::convert::Infallible;

    /// The high 32 bits of [`SplitMix64::next_bits`] (the better-mixed half).
    fn try_next_u32(&mut self) -> Result<u32, Self::Error> {
        Ok((self.next_bits() >> 32) as u32)
    }

    fn try_next_u64(&mut self) -> Result<u64, Self::Error> {
        Ok(self.next_bits())
    }

    /// Little-endian bytes of successive [`SplitMix64::next_bits`] values.
    fn try_fill_bytes(&mut self, dst: &mut [u8]) -> Result<(), Self::Error> {
        for chunk in dst.chunks_mut(8) {
            let bytes = self.next_bits().to_le_bytes();
            chunk.copy_from_slice(&bytes[..chunk.len()]);
        }
        Ok(())
    }
}
