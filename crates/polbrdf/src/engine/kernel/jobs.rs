//! The jobs: blocks through the kernel, fallback elements through the one-geometry path;
//! each compiled once per instruction set and run at the kernel's ([`dispatch`]).

use super::index::{IndexSource, SpectralCache};
use super::sinks::{store_fence, PutRows, SinkF32};
use super::sources::{load, BatchSource, Blocks, F32Blocks, Prepared};
use super::{Kernel, BLOCK};
use crate::engine::block::{self, AngleNeeds, Front, GeomScratch, Lanes, Thresholds};
use crate::engine::simd::SimdLevel;
use crate::numeric::math::{FastPortable, Math};
use crate::numeric::math32::SinglePortable;
use crate::optics::stokes::Stokes;

// -------------------------------------------------------------------------------------------
// The jobs: blocks through the kernel, fallback elements through the one-geometry path; each
// compiled once per instruction set and run at the kernel's ([`dispatch`]).

/// A piece of work generic over the elementary-function backends: `M` in f64, `S` in f32 (for
/// the single-precision kernel), both for one instruction set.
pub(super) trait Job {
    fn run<M: Math<F = f64>, S: Math<F = f32>>(&mut self);
}

/// Runs `job` with the code of `level` (the CPU supports it: a kernel is only built at a
/// supported level).
pub(super) fn dispatch<J: Job>(level: SimdLevel, job: &mut J) {
    match level {
        #[cfg(target_arch = "x86_64")]
        // SAFETY: a kernel of this level is only built when the CPU supports it.
        SimdLevel::Avx512 => unsafe { x86::avx512(job) },
        #[cfg(target_arch = "x86_64")]
        // SAFETY: as above.
        SimdLevel::Avx2 => unsafe { x86::avx2(job) },
        _ => job.run::<FastPortable, SinglePortable>(),
    }
}

pub(super) struct MuellerJob<'k, 'a, 's, 'o, G, W, const N: usize> {
    pub(super) kernel: &'k Kernel<'a>,
    pub(super) src: &'s G,
    pub(super) index: IndexSource<'k>,
    pub(super) out: &'o mut W,
    /// A finite entry beyond the output format's range.
    pub(super) overflow: bool,
    /// Stopped at a block that failed validation ([`Blocks::valid`]).
    pub(super) invalid: bool,
}

impl<G: Blocks, W: PutRows<f64>, const N: usize> Job for MuellerJob<'_, '_, '_, '_, G, W, N> {
    #[inline(always)]
    fn run<M: Math<F = f64>, S: Math<F = f32>>(&mut self) {
        let k = self.kernel;
        let needs = AngleNeeds::of(&k.params);
        // Made once per job, overwritten block by block.
        let mut scratch = GeomScratch::<N>::zeroed();
        let mut front = Front::<N>::zeroed();
        let mut rows = [[0.0; N]; 16];
        let mut staged = [[0.0; 16]; N];
        let mut cache = SpectralCache::new();
        let n = self.out.len();
        for start in (0..n).step_by(N) {
            let len = N.min(n - start);
            if !self.src.valid(start, len) {
                self.invalid = true;
                break;
            }
            let geo = self
                .src
                .geometry::<M, N, true>(start, len, needs, &mut scratch);
            let idx = self.index.lanes::<N>(start, len, &mut cache);
            block::front::<M, N>(&k.params, geo, &idx, &mut front);
            block::mueller::<M, N>(&mut front, geo, &mut rows);
            self.overflow |= self.out.put_rows(start, len, &rows, &mut staged, k.stream);
            for j in 0..len {
                if front.fallback[j] {
                    let v = self.src.reference(k, self.index, start + j);
                    self.overflow |= self.out.put_one(start + j, &v.pbrdf.to_row_major());
                }
            }
        }
        if k.stream {
            store_fence();
        }
    }
}

/// The single-precision job: blocks through the kernel in f32 (backend `S`); the elements it
/// flags are gathered, [`BLOCK`] at a time, into blocks of the f64 kernel (backend `M`), and
/// those the f64 kernel flags in turn take the one-geometry path — every element ends where
/// its accuracy holds, and most of the work stays in f32.
pub(super) struct MuellerF32Job<'k, 'a, 's, 'o, G, W, const N: usize> {
    pub(super) kernel: &'k Kernel<'a>,
    pub(super) src: &'s G,
    pub(super) index: IndexSource<'k>,
    pub(super) out: &'o mut W,
    /// A finite entry beyond f32's range.
    pub(super) overflow: bool,
    /// Stopped at a block that failed validation ([`Blocks::valid`]).
    pub(super) invalid: bool,
}

/// What the f64 blocks of [`MuellerF32Job`] work in.
pub(super) struct Wide<const N: usize> {
    scratch: GeomScratch<N>,
    front: Front<N>,
    rows: [Lanes<N>; 16],
    /// Positions of the elements waiting for an f64 block, and how many.
    pending: [usize; N],
    len: usize,
}

impl<G: F32Blocks, W: SinkF32, const N: usize> MuellerF32Job<'_, '_, '_, '_, G, W, N> {
    /// The pending elements through the f64 kernel (and, where it flags them, the one-geometry
    /// path), rounded to f32 into their places.
    #[inline(always)]
    fn flush<M: Math<F = f64>>(&mut self, w: &mut Wide<N>, cache: &mut SpectralCache) {
        let k = self.kernel;
        let pos = &w.pending[..w.len];
        self.src
            .gathered_geometry::<M, N>(pos, AngleNeeds::of(&k.params), &mut w.scratch);
        let idx = self
            .index
            .lanes_at::<N>(|j| pos[if j < pos.len() { j } else { 0 }], cache);
        block::front::<M, N>(&k.params, &w.scratch.geo, &idx, &mut w.front);
        block::mueller::<M, N>(&mut w.front, &w.scratch.geo, &mut w.rows);
        for (j, &i) in pos.iter().enumerate() {
            let v = if w.front.fallback[j] {
                self.src.reference(k, self.index, i).pbrdf.to_row_major()
            } else {
                std::array::from_fn(|e| w.rows[e][j])
            };
            self.overflow |= self.out.put_one(i, &v);
        }
        w.len = 0;
    }
}

/// D of the lanes `tail` of an f32 block recomputed from θN in f64 (backend `M`) and rounded
/// to f32: far down D's tail its relative error is `2bθN²` times θN's, which f32 cannot hold
/// to 1e-5 beyond `bθN² ≈ 20` (docs/model.md §12, "Precision"), while D itself only
/// multiplies the other terms, whose f32 accuracy does not degrade there. Only θN is
/// recomputed in f64 from the block's input ([`F32Blocks::theta_n_f64`]: from angles as the
/// f64 path computes it, from direction vectors by their half vector), 4 lanes at a time; where even f64 is ill-conditioned, or D is below f32's comfortable range, the element
/// takes the f64 path (`fallback`).
#[inline(always)]
pub(super) fn refine_d<M: Math<F = f64>, G: F32Blocks, const N: usize>(
    scratch: &GeomScratch<N, f32>,
    len: usize,
    dist: crate::model::distribution::Distribution,
    d: &mut Lanes<N, f32>,
    tail: &[bool; N],
    fallback: &mut [bool; N],
) {
    const L: usize = 4;
    const { assert!(N <= 64, "a block's lanes are one u64 mask") };
    // The lanes to refine as a bit mask, in one pass over the block; a block without any (most
    // blocks of a rough material) leaves here.
    let mut mask = 0u64;
    for j in 0..N {
        mask |= u64::from(tail[j] & !fallback[j]) << j;
    }
    if len < 64 {
        mask &= (1u64 << len) - 1;
    }
    // Groups of L lanes taken from the mask, lowest first (no branch per lane: the lanes are
    // random, and a mispredicted branch per lane cost more than the arithmetic); a group
    // short of L repeats its last lane, which writes the same result twice.
    while mask != 0 {
        let mut group = [0usize; L];
        let mut last = mask.trailing_zeros() as usize;
        for g in group.iter_mut() {
            let j = if mask != 0 {
                mask.trailing_zeros() as usize
            } else {
                last
            };
            *g = j;
            last = j;
            mask &= mask.wrapping_sub(1);
        }
        // The arithmetic in plain loops over contiguous lanes (a closure that is not inlined
        // would not inherit the kernel's target features: an `array::map` here once compiled
        // to calls of a software fma). The angles are the block's f64 input, reduced by the
        // f64 backend as on the f64 path.
        let mut input = [[0.0f64; L]; 6];
        for l in 0..L {
            let x = G::lane_input::<N>(scratch, group[l]);
            for c in 0..6 {
                input[c][l] = x[c];
            }
        }
        let mut dv = [0.0f64; L];
        let mut ok = [false; L];
        for l in 0..L {
            let tn = G::theta_n_f64::<M>(std::array::from_fn(|c| input[c][l]));
            dv[l] = dist.eval_with::<M>(tn);
            ok[l] = -dist.exponent(tn) <= <f64 as Thresholds>::D_EXPONENT_MAX
                && dv[l] >= f64::from(<f32 as Thresholds>::TINY);
        }
        for l in 0..L {
            let j = group[l];
            if ok[l] {
                d[j] = dv[l] as f32;
            } else {
                fallback[j] = true;
            }
        }
    }
}

impl<G: F32Blocks, W: SinkF32, const N: usize> Job for MuellerF32Job<'_, '_, '_, '_, G, W, N> {
    #[inline(always)]
    fn run<M: Math<F = f64>, S1: Math<F = f32>>(&mut self) {
        let k = self.kernel;
        let needs = AngleNeeds::of(&k.params);
        // Made once per job, overwritten block by block.
        let mut scratch = GeomScratch::<N, f32>::zeroed();
        let mut front = Front::<N, f32>::zeroed();
        let mut rows = [[0.0f32; N]; 16];
        let mut staged = [[0.0f32; 16]; N];
        let mut cache = SpectralCache::new();
        let mut wide = Wide::<N> {
            scratch: GeomScratch::zeroed(),
            front: Front::zeroed(),
            rows: [[0.0; N]; 16],
            pending: [0; N],
            len: 0,
        };
        let n = self.out.len();
        for start in (0..n).step_by(N) {
            let len = N.min(n - start);
            if !self.src.valid(start, len) {
                self.invalid = true;
                break;
            }
            self.src
                .geometry::<S1, N, true>(start, len, needs, &mut scratch);
            let geo = &scratch.geo;
            let idx = self.index.lanes_f32::<N>(start, len, k.ill32, &mut cache);
            block::front_q_d::<S1, N>(&k.params, geo, &idx, &mut front);
            let (d, tail, fb) = front.d_tail_mut();
            refine_d::<M, G, N>(&scratch, len, k.params.distribution, d, tail, fb);
            block::front_terms::<S1, N>(&k.params, geo, &mut front);
            block::mueller::<S1, N>(&mut front, geo, &mut rows);
            self.overflow |=
                PutRows::<f32>::put_rows(self.out, start, len, &rows, &mut staged, k.stream32);
            for j in 0..len {
                if front.fallback[j] {
                    wide.pending[wide.len] = start + j;
                    wide.len += 1;
                    if wide.len == N {
                        self.flush::<M>(&mut wide, &mut cache);
                    }
                }
            }
        }
        if wide.len > 0 && !self.invalid {
            self.flush::<M>(&mut wide, &mut cache);
        }
        if k.stream32 {
            store_fence();
        }
    }
}

/// BRDF, DoLP and (with `AOLP`) AoLP; `aolp` is empty without `AOLP`.
pub(super) struct BrdfDolpJob<'k, 'a, 's, 'o, G, const N: usize, const AOLP: bool> {
    pub(super) kernel: &'k Kernel<'a>,
    pub(super) src: &'s G,
    pub(super) index: IndexSource<'k>,
    pub(super) brdf: &'o mut [f64],
    pub(super) dolp: &'o mut [f64],
    pub(super) aolp: &'o mut [f64],
}

impl<G: Blocks, const N: usize, const AOLP: bool> Job for BrdfDolpJob<'_, '_, '_, '_, G, N, AOLP> {
    #[inline(always)]
    fn run<M: Math<F = f64>, S: Math<F = f32>>(&mut self) {
        let k = self.kernel;
        let needs = AngleNeeds::of(&k.params);
        let mut lanes: [Lanes<N>; 3] = [[0.0; N]; 3];
        let n = self.brdf.len();
        let mut cache = SpectralCache::new();
        let mut scratch = GeomScratch::<N>::zeroed();
        let mut front = Front::<N>::zeroed();
        for start in (0..n).step_by(N) {
            let len = N.min(n - start);
            let geo = self
                .src
                .geometry::<M, N, AOLP>(start, len, needs, &mut scratch);
            let idx = self.index.lanes::<N>(start, len, &mut cache);
            block::front::<M, N>(&k.params, geo, &idx, &mut front);
            block::brdf_dolp::<M, N, AOLP>(&mut front, geo, &mut lanes);
            self.brdf[start..start + len].copy_from_slice(&lanes[0][..len]);
            self.dolp[start..start + len].copy_from_slice(&lanes[1][..len]);
            if AOLP {
                self.aolp[start..start + len].copy_from_slice(&lanes[2][..len]);
            }
            for j in 0..len {
                if front.fallback[j] {
                    let e = self.src.reference(k, self.index, start + j);
                    (self.brdf[start + j], self.dolp[start + j]) = (e.brdf(), e.dolp());
                    if AOLP {
                        self.aolp[start + j] = e.reflect(&Stokes::unpolarized()).aolp();
                    }
                }
            }
        }
    }
}

/// The geometry stages of a batch, block by block, into a [`Prepared`].
pub(super) struct PrepareJob<'s, 'b> {
    pub(super) src: &'s BatchSource<'b>,
    pub(super) out: Prepared,
}

impl Job for PrepareJob<'_, '_> {
    #[inline(always)]
    fn run<M: Math<F = f64>, S: Math<F = f32>>(&mut self) {
        let n = self.src.cols[0].len();
        let mut scratch = GeomScratch::<BLOCK>::zeroed();
        for start in (0..n).step_by(BLOCK) {
            let len = BLOCK.min(n - start);
            load::<_, BLOCK>(self.src, start, len, &mut scratch.input);
            // Every angle: the prepared geometry serves every material.
            block::geometry::<M, BLOCK, true>(&mut scratch, AngleNeeds::ALL);
            let b = &scratch.input;
            scratch.geo.angles = [b.ti, b.pi, b.tr, b.pr];
            self.out.push(scratch.geo.clone(), len);
        }
    }
}

/// One of the kernel's elementary operations, for [`elementary_into`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Elementary {
    /// `sin x + cos x` (one [`Math::sincos`]).
    SinCos,
    /// `atan2(y, x)` for `x, y ≥ 0` ([`Math::atan2_pos`]).
    Atan2,
    /// `exp(−x)` for `x ≥ 0` ([`Math::exp_neg`]).
    Exp,
    /// `sqrt x` (the hardware instruction).
    Sqrt,
    /// `y / x` (the hardware instruction).
    Div,
}

impl Elementary {
    /// Every operation.
    pub const ALL: [Elementary; 5] = [
        Elementary::SinCos,
        Elementary::Atan2,
        Elementary::Exp,
        Elementary::Sqrt,
        Elementary::Div,
    ];

    /// A short name.
    pub fn name(self) -> &'static str {
        match self {
            Elementary::SinCos => "sincos",
            Elementary::Atan2 => "atan2",
            Elementary::Exp => "exp",
            Elementary::Sqrt => "sqrt",
            Elementary::Div => "div",
        }
    }
}

/// `out[j] = op(x[j], y[j])` with the kernel's elementary functions at `level`, vectorized as
/// the kernel's stages are — for benchmarks that bound the kernel's cost from below (the model
/// needs, per element, four sine/cosine pairs, two arctangents, two exponentials; `polbrdf
/// bench` times them). `None` when the CPU does not support `level`.
///
/// # Panics
/// When `x`, `y` and `out` differ in length.
pub fn elementary_into(
    level: SimdLevel,
    op: Elementary,
    x: &[f64],
    y: &[f64],
    out: &mut [f64],
) -> Option<()> {
    assert!(x.len() == out.len() && y.len() == out.len(), "lengths");
    if !level.is_supported() {
        return None;
    }
    let mut job = ElementaryJob { op, x, y, out };
    dispatch(level, &mut job);
    Some(())
}

pub(super) struct ElementaryJob<'a> {
    op: Elementary,
    x: &'a [f64],
    y: &'a [f64],
    pub(super) out: &'a mut [f64],
}

impl Job for ElementaryJob<'_> {
    #[inline(always)]
    fn run<M: Math<F = f64>, S: Math<F = f32>>(&mut self) {
        let (x, y) = (self.x, self.y);
        let out = &mut *self.out;
        match self.op {
            Elementary::SinCos => {
                for j in 0..out.len() {
                    let (s, c) = M::sincos(x[j]);
                    out[j] = s + c;
                }
            }
            Elementary::Atan2 => {
                for j in 0..out.len() {
                    out[j] = M::atan2_pos(y[j], x[j]);
                }
            }
            Elementary::Exp => {
                for j in 0..out.len() {
                    out[j] = M::exp_neg(-x[j]);
                }
            }
            Elementary::Sqrt => {
                for j in 0..out.len() {
                    out[j] = x[j].sqrt();
                }
            }
            Elementary::Div => {
                for j in 0..out.len() {
                    out[j] = y[j] / x[j];
                }
            }
        }
    }
}

#[cfg(target_arch = "x86_64")]
mod x86 {
    //! The jobs compiled for AVX2+FMA and for AVX-512.

    use super::Job;
    use crate::numeric::math::FastFused;
    use crate::numeric::math32::Single;

    /// # Safety
    /// The CPU must support AVX-512 F/DQ/VL, AVX2 and FMA.
    #[target_feature(enable = "avx512f,avx512dq,avx512vl,avx2,fma")]
    pub(super) unsafe fn avx512<J: Job>(job: &mut J) {
        job.run::<FastFused, Single<true>>()
    }

    /// # Safety
    /// The CPU must support AVX2 and FMA.
    #[target_feature(enable = "avx2,fma")]
    pub(super) unsafe fn avx2<J: Job>(job: &mut J) {
        job.run::<FastFused, Single<true>>()
    }
}
