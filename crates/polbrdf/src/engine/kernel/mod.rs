//! The serial evaluator of the batch engine: blocks of [`BLOCK`] elements through the block
//! kernel (`crate::engine::block`), at the best instruction set of the CPU, with the
//! one-geometry path for the elements the kernel must not vectorize. `crate::engine::batch` runs
//! it in parallel.

#![allow(clippy::needless_range_loop)]

use crate::engine::planes::Planes;
use crate::engine::simd::{simd_level, SimdLevel};
use crate::error::{Error, Result};
use crate::geometry::batch::{Batch, Input};
use crate::geometry::{AngleVariables, Geometry, GeometryBatch};
use crate::model::{Material, ModelParams};
use crate::optics::dispersion::SpectralIndex;
use crate::optics::mueller::Mueller;
use crate::optics::stokes::Stokes;
use index::{index_ill, index_ill_for, IndexSource};
use jobs::{dispatch, BrdfDolpJob, MuellerF32Job, MuellerJob, PrepareJob};
use sinks::{PutRows, Rows, SinkF32};
use sources::{BatchSource, Blocks, Computed, Directions, F32Blocks, Variables};

mod index;
mod jobs;
mod sinks;
mod sources;

pub use index::IndexColumns;
pub use jobs::{elementary_into, Elementary};
pub use sources::Prepared;

/// Runs `$body` with `$src` bound to the kernel's source of elements `$start .. $start + $len`
/// of `$batch` (a [`Batch`]): angles or direction vectors. With `checked`, of an
/// [`crate::geometry::Unvalidated`] batch, each source wrapped in `Checked` (validated block by
/// block).
macro_rules! with_source {
    ($batch:expr, $start:expr, $len:expr, |$src:ident| $body:expr) => {
        with_source!(@ $batch.input(), $start, $len, , |$src| $body)
    };
    (checked $raw:expr, $start:expr, $len:expr, |$src:ident| $body:expr) => {
        with_source!(@ $raw.input(), $start, $len, Checked, |$src| $body)
    };
    (@ $input:expr, $start:expr, $len:expr, $($wrap:ident)?, |$src:ident| $body:expr) => {
        match $input {
            Input::Angles(b) => {
                let $src = $($wrap)?(Computed(BatchSource::new(&b, $start, $len)));
                $body
            }
            Input::Directions(d) => {
                let $src = $($wrap)?(Directions::new(&d, $start, $len));
                $body
            }
        }
    };
}

// After the macro, which it uses.
mod validating;

/// How a run of the kernel ended.
#[derive(Debug, Clone, Copy)]
struct Outcome {
    /// A finite entry beyond the output format's range.
    overflow: bool,
    /// Stopped at a block that failed validation (a `Checked` source).
    invalid: bool,
}

/// Elements per block: every stage of the kernel runs over this many elements at a time.
/// Measured on an AVX2 machine with 32 KB of L1 data cache per core (AMD EPYC, Zen 1 class):
/// 16 is 6–10 % faster than 32 on the peer benchmark's conductor in both precisions, and no
/// slower on `paint`; at 32 a block's arrays (sines and cosines, angles, front terms, the 16
/// rows and their transpose, about 23 KB in f64) crowd the L1 cache. 8 is slower (too little
/// work per stage loop).
pub const BLOCK: usize = 16;

/// Elements per block of the f32 kernel at AVX-512 and AVX2: two 16-lane (four 8-lane) f32
/// registers per array, where [`BLOCK`] fills only one (two), so its f32 arrays take the room
/// of a 16-element f64 block. Measured at AVX-512 (AMD EPYC, Zen 4 class; scratch program,
/// medians of 15 alternating pairs, identical bits): 1.07–1.17× the rate of blocks of 16 over
/// 4096 elements in cache on one thread, 1.05–1.10× through the engine at 2·10⁶. At AVX2 (AMD
/// EPYC, Zen 3, full-width 256-bit FMAs; `polbrdf bench`, 10⁶ `paint` geometries, medians of 7
/// alternating runs): 1.12× on one thread, 1.01× on two, 1.44× / 1.19× from direction
/// vectors; the peer's conductor through Python at 2·10⁶, medians of three paired ratios:
/// 1.01× (rows), 1.10× (directions); identical bits. (On a Zen 1 class AVX2 host, which
/// splits 256-bit operations in two, the gain was not consistent across materials.) The
/// baseline level keeps [`BLOCK`].
const BLOCK_F32_WIDE: usize = 32;

/// The fast evaluator of one material (see the module documentation). Cheap to build.
///
/// Its methods evaluate serially; `polbrdf::engine::batch` runs them in parallel over chunks.
#[derive(Debug, Clone)]
pub struct Kernel<'a> {
    material: &'a Material,
    params: ModelParams,
    index: IndexSource<'a>,
    level: SimdLevel,
    /// Parameters outside the kernel's accurate domain (extreme magnitudes): every element
    /// takes the one-geometry path.
    scalar_only: bool,
    /// Parameters inside the f32 kernel's domain (else single precision is computed in f64
    /// and rounded).
    single: bool,
    /// A constant index outside the f32 kernel's domain ([`index_ill_for`]).
    ill32: bool,
    /// Write full-Mueller results with non-temporal stores (for large outputs).
    stream: bool,
    /// The same for the f32 kernel's row-major outputs.
    stream32: bool,
}

impl<'a> Kernel<'a> {
    /// The kernel of `material` at the best SIMD level of this CPU ([`simd_level`]).
    pub fn new(material: &'a Material) -> Self {
        Self::build(material, simd_level())
    }

    /// The kernel at a given SIMD level, or `None` when this CPU does not support it (for
    /// tests and benchmarks comparing levels).
    pub fn with_level(material: &'a Material, level: SimdLevel) -> Option<Self> {
        level.is_supported().then(|| Self::build(material, level))
    }

    fn build(material: &'a Material, level: SimdLevel) -> Self {
        let (n2r, n2i) = material.index().squared();
        let p = *material.params();
        let d = p.distribution;
        let (inv_omega, two_over_tau) = p
            .shadowing
            .map_or((0.0, 0.0), |s| (1.0 / s.omega(), 2.0 / s.tau()));
        let in_domain = d.a() < 1e200
            && d.b() < 1e200
            && inv_omega < 1e100
            && two_over_tau < 1e100
            && p.rho_v < 1e200
            && p.rho_d < 1e200;
        Self {
            material,
            params: p,
            index: IndexSource::Constant {
                n2r,
                n2i,
                ill: index_ill(n2r, n2i),
            },
            level,
            scalar_only: !in_domain || (d.a() > 0.0 && d.a() < 1e-200),
            single: [d.a(), d.b(), inv_omega, two_over_tau, p.rho_v, p.rho_d]
                .iter()
                .all(|x| *x < 1e20)
                && (d.a() == 0.0 || d.a() > 1e-20),
            ill32: index_ill_for::<f32>(n2r, n2i),
            stream: false,
            stream32: false,
        }
    }

    /// Evaluate element `j` with index `index.get(j)` instead of the material's (positions are
    /// those of the batch or slice passed to each method).
    pub fn with_index(mut self, index: IndexColumns<'a>) -> Self {
        self.index = IndexSource::PerElement(index);
        self
    }

    /// Evaluate element `j` with the material's spectral index at `wavelengths_um[j]` (µm);
    /// a material with a constant index is unchanged (the wavelengths play no part).
    ///
    /// # Errors
    /// [`Error::WavelengthOutOfRange`] with the position of the first wavelength outside the
    /// index's data (or not finite).
    pub fn with_wavelengths(mut self, wavelengths_um: &'a [f64]) -> Result<Self> {
        if let Some(s) = &self.material.spec().spectral {
            let index: &'a SpectralIndex = &s.index;
            let (lo, hi) = index.range();
            if let Some(i) = wavelengths_um.iter().position(|l| !(*l >= lo && *l <= hi)) {
                return Err(Error::WavelengthOutOfRange {
                    material: index.name.clone(),
                    wavelength_um: wavelengths_um[i],
                    range: (lo, hi),
                    position: Some(i),
                });
            }
            self.index = IndexSource::Spectral {
                index,
                wavelengths: wavelengths_um,
            };
        }
        Ok(self)
    }

    /// With `on`, [`Kernel::mueller_into`] (f64, row-major) writes whole blocks with
    /// non-temporal stores, straight from the transpose, where the CPU has AVX and the output
    /// is 16-byte aligned (256-bit stores where it is 32-byte aligned): no read for ownership
    /// of the output's cache lines, and the caches are left alone — faster for outputs much
    /// larger than the caches, slower for outputs read back at once. So does
    /// [`Kernel::mueller_f32_into`] (128-bit stores) where they pay on this CPU
    /// ([`crate::engine::simd::f32_streams_pay`]; [`Kernel::streaming_f32`] sets it alone).
    /// Partial blocks, elements taken from the one-geometry path and other outputs use plain
    /// stores. The bits are the same either way. Off by default ([`crate::Engine`] decides by
    /// the output's size).
    pub fn streaming(mut self, on: bool) -> Self {
        self.stream = on;
        self.stream32 = on && crate::engine::simd::f32_streams_pay();
        self
    }

    /// Non-temporal stores for [`Kernel::mueller_f32_into`]'s whole blocks (16-byte aligned
    /// outputs) on or off, whatever the CPU — for measuring them (`polbrdf bench`), and for
    /// tests.
    pub fn streaming_f32(mut self, on: bool) -> Self {
        self.stream32 = on;
        self
    }

    /// The SIMD level this kernel runs with.
    pub fn level(&self) -> SimdLevel {
        self.level
    }

    /// The material.
    pub fn material(&self) -> &'a Material {
        self.material
    }

    /// The pBRDF `F` (row-major, sr⁻¹) of elements `start .. start + out.len()` of `batch`.
    ///
    /// # Panics
    /// When the range exceeds the batch (or a per-element index).
    pub fn mueller_into(&self, batch: &impl Batch, start: usize, out: &mut [[f64; 16]]) {
        let index = self.index_at(start, out.len());
        with_source!(batch, start, out.len(), |src| {
            self.run_mueller::<_, _, BLOCK>(&src, index, &mut Rows(out));
        })
    }

    /// As [`Kernel::mueller_into`] into planes ([`Planes`]: entry `e = 4·i + j` of element
    /// `k` at position `k` of plane `e`) — the same bits, without the transpose into rows.
    ///
    /// # Panics
    /// When the range exceeds the batch (or a per-element index).
    pub fn mueller_planes_into(&self, batch: &impl Batch, start: usize, out: &mut Planes<'_, f64>) {
        let index = self.index_at(start, out.len());
        with_source!(batch, start, out.len(), |src| {
            self.run_mueller::<_, _, BLOCK>(&src, index, out);
        })
    }

    /// As [`Kernel::mueller_into`] in single precision (docs/model.md §12, "Precision"): the
    /// same formulas computed in f32, within the float32 contract — `1e-5·F00 + 1e-6·P` of the
    /// f64 results, `P` the F00 at the specular direction of the same θi; an element where f32
    /// would not reach that (D far down its tail with a direction near grazing, an index near
    /// 1, a non-finite intermediate) is computed in f64 and rounded, as is every element of a
    /// material whose parameters are beyond f32's comfortable range. Returns whether some
    /// finite entry was beyond f32's range (stored as ±∞).
    ///
    /// # Panics
    /// When the range exceeds the batch (or a per-element index).
    pub fn mueller_f32_into(
        &self,
        batch: &impl Batch,
        start: usize,
        out: &mut [[f32; 16]],
    ) -> bool {
        self.run_f32(batch, start, &mut Rows(out))
    }

    /// As [`Kernel::mueller_f32_into`] into planes (as [`Kernel::mueller_planes_into`]): the
    /// same bits, without the transpose into rows.
    ///
    /// # Panics
    /// When the range exceeds the batch (or a per-element index).
    pub fn mueller_planes_f32_into(
        &self,
        batch: &impl Batch,
        start: usize,
        out: &mut Planes<'_, f32>,
    ) -> bool {
        self.run_f32(batch, start, out)
    }

    fn run_f32<W: SinkF32>(&self, batch: &impl Batch, start: usize, out: &mut W) -> bool {
        let index = self.index_at(start, out.len());
        with_source!(batch, start, out.len(), |src| {
            self.f32_source(&src, index, out).overflow
        })
    }

    /// The f32 kernel of `src` (or the f64 one, rounded, where the material asks).
    fn f32_source<G: F32Blocks, W: SinkF32>(
        &self,
        src: &G,
        index: IndexSource<'_>,
        out: &mut W,
    ) -> Outcome {
        if self.scalar_only || !self.single {
            return self.run_mueller::<_, _, BLOCK>(src, index, out);
        }
        match self.level {
            SimdLevel::Avx512 | SimdLevel::Avx2 => {
                self.f32_job::<_, _, BLOCK_F32_WIDE>(src, index, out)
            }
            SimdLevel::Portable => self.f32_job::<_, _, BLOCK>(src, index, out),
        }
    }

    /// The f32 kernel over blocks of `N` elements.
    fn f32_job<G: F32Blocks, W: SinkF32, const N: usize>(
        &self,
        src: &G,
        index: IndexSource<'_>,
        out: &mut W,
    ) -> Outcome {
        let mut job = MuellerF32Job::<_, _, N> {
            kernel: self,
            src,
            index,
            out,
            overflow: false,
            invalid: false,
        };
        dispatch(self.level, &mut job);
        Outcome {
            overflow: job.overflow,
            invalid: job.invalid,
        }
    }

    /// As [`Kernel::mueller_f32_into`], computed in f64 and each entry rounded to the nearest
    /// f32 (the reference the f32 kernel is tested against, and what single precision gave
    /// before it).
    ///
    /// # Panics
    /// When the range exceeds the batch (or a per-element index).
    pub fn mueller_f64_rounded_into(
        &self,
        batch: &impl Batch,
        start: usize,
        out: &mut [[f32; 16]],
    ) -> bool {
        let index = self.index_at(start, out.len());
        with_source!(batch, start, out.len(), |src| {
            self.run_mueller::<_, _, BLOCK>(&src, index, &mut Rows(out))
                .overflow
        })
    }

    /// The scalar BRDF (sr⁻¹) and the DoLP for unpolarized input of elements
    /// `start .. start + brdf.len()` of `batch`.
    ///
    /// # Panics
    /// When `brdf` and `dolp` differ in length or the range exceeds the batch.
    pub fn brdf_dolp_into(
        &self,
        batch: &impl Batch,
        start: usize,
        brdf: &mut [f64],
        dolp: &mut [f64],
    ) {
        assert_eq!(brdf.len(), dolp.len(), "brdf and dolp lengths");
        let index = self.index_at(start, brdf.len());
        with_source!(batch, start, brdf.len(), |src| {
            self.run_brdf_dolp::<_, BLOCK, false>(&src, index, brdf, dolp, &mut []);
        })
    }

    /// As [`Kernel::brdf_dolp_into`], plus the AoLP (rad, in (−π/2, π/2], from the reflected
    /// beam's s axis toward its p axis; 0 without linear polarization) for unpolarized input:
    /// `Stokes::aolp` of `F·(1, 0, 0, 0)`.
    ///
    /// # Panics
    /// When the three outputs differ in length or the range exceeds the batch.
    pub fn brdf_dolp_aolp_into(
        &self,
        batch: &impl Batch,
        start: usize,
        brdf: &mut [f64],
        dolp: &mut [f64],
        aolp: &mut [f64],
    ) {
        assert_eq!(brdf.len(), dolp.len(), "brdf and dolp lengths");
        assert_eq!(brdf.len(), aolp.len(), "brdf and aolp lengths");
        let index = self.index_at(start, brdf.len());
        with_source!(batch, start, brdf.len(), |src| {
            self.run_brdf_dolp::<_, BLOCK, true>(&src, index, brdf, dolp, aolp);
        })
    }

    /// The pBRDF at each geometry of a slice (already validated by construction).
    ///
    /// # Panics
    /// When `out` is not as long as `geometries`.
    pub fn mueller_of(&self, geometries: &[Geometry], out: &mut [Mueller]) {
        assert_eq!(geometries.len(), out.len(), "output length");
        let index = self.index_at(0, out.len());
        self.run_mueller::<_, _, BLOCK>(&Computed(geometries), index, &mut Rows(out));
    }

    /// The pBRDF at explicit angle variables (the angle-variable entry point,
    /// [`Material::evaluate_angles`]), row-major.
    ///
    /// # Panics
    /// When `out` is not as long as `vars`.
    pub fn mueller_of_angles(&self, vars: &[AngleVariables], out: &mut [[f64; 16]]) {
        assert_eq!(vars.len(), out.len(), "output length");
        let index = self.index_at(0, out.len());
        self.run_mueller::<_, _, BLOCK>(&Variables(vars), index, &mut Rows(out));
    }

    /// The geometry stages of every element of `batch` (the part of the kernel that does not
    /// depend on the material), computed once, for [`Kernel::mueller_prepared_into`] and
    /// [`Kernel::brdf_dolp_prepared_into`] — of this kernel or of any other at the same SIMD
    /// level, whatever its material or index. The results are exactly those of the unprepared
    /// methods.
    pub fn prepare(&self, batch: &GeometryBatch<'_>) -> Prepared {
        self.prepare_range(batch, 0, batch.len())
    }

    /// [`Kernel::prepare`] of elements `start .. start + len`.
    pub(crate) fn prepare_range(
        &self,
        batch: &GeometryBatch<'_>,
        start: usize,
        len: usize,
    ) -> Prepared {
        let src = BatchSource::new(batch, start, len);
        let mut job = PrepareJob {
            src: &src,
            out: Prepared::with_capacity(len, self.level),
        };
        dispatch(self.level, &mut job);
        job.out
    }

    /// As [`Kernel::mueller_into`], for elements `start .. start + out.len()` of a prepared
    /// batch.
    ///
    /// # Panics
    /// When `start` is not a multiple of [`BLOCK`], the range exceeds the batch, or `prepared`
    /// was made at another SIMD level.
    pub fn mueller_prepared_into(&self, prepared: &Prepared, start: usize, out: &mut [[f64; 16]]) {
        let src = prepared.range(start, out.len(), self.level);
        self.run_mueller::<_, _, BLOCK>(&src, self.index_at(start, out.len()), &mut Rows(out));
    }

    /// As [`Kernel::brdf_dolp_into`], for elements `start .. start + brdf.len()` of a prepared
    /// batch.
    ///
    /// # Panics
    /// As [`Kernel::mueller_prepared_into`], or when `brdf` and `dolp` differ in length.
    pub fn brdf_dolp_prepared_into(
        &self,
        prepared: &Prepared,
        start: usize,
        brdf: &mut [f64],
        dolp: &mut [f64],
    ) {
        assert_eq!(brdf.len(), dolp.len(), "brdf and dolp lengths");
        let src = prepared.range(start, brdf.len(), self.level);
        let index = self.index_at(start, brdf.len());
        self.run_brdf_dolp::<_, BLOCK, false>(&src, index, brdf, dolp, &mut []);
    }

    /// The pBRDF `F` at one geometry: the kernel's code for a single element, for the lowest
    /// latency (the batch methods are faster per element).
    pub fn pbrdf(&self, g: &Geometry) -> Mueller {
        let mut out = [Mueller::zero()];
        let index = self.index_at(0, 1);
        self.run_mueller::<_, _, 1>(
            &Computed(std::slice::from_ref(g)),
            index,
            &mut Rows(&mut out),
        );
        out[0]
    }

    /// The scalar BRDF (sr⁻¹) and the DoLP for unpolarized input at one geometry (single-element
    /// code, as [`Kernel::pbrdf`]).
    pub fn brdf_dolp(&self, g: &Geometry) -> (f64, f64) {
        let (mut b, mut d) = ([0.0], [0.0]);
        let index = self.index_at(0, 1);
        let src = Computed(std::slice::from_ref(g));
        self.run_brdf_dolp::<_, 1, false>(&src, index, &mut b, &mut d, &mut []);
        (b[0], d[0])
    }

    /// The index source for elements `start .. start + len`.
    fn index_at(&self, start: usize, len: usize) -> IndexSource<'a> {
        match self.index {
            IndexSource::PerElement(cols) => {
                assert!(
                    start + len <= cols.len(),
                    "range {start}..{start}+{len} beyond a per-element index of {}",
                    cols.len()
                );
                IndexSource::PerElement(cols.slice(start, len))
            }
            IndexSource::Spectral { index, wavelengths } => {
                assert!(
                    start + len <= wavelengths.len(),
                    "range {start}..{start}+{len} beyond {} wavelengths",
                    wavelengths.len()
                );
                IndexSource::Spectral {
                    index,
                    wavelengths: &wavelengths[start..start + len],
                }
            }
            c => c,
        }
    }

    fn run_mueller<G: Blocks, W: PutRows<f64>, const N: usize>(
        &self,
        src: &G,
        index: IndexSource<'_>,
        out: &mut W,
    ) -> Outcome {
        if self.scalar_only {
            let mut overflow = false;
            for i in 0..out.len() {
                if !src.valid(i, 1) {
                    return Outcome {
                        overflow,
                        invalid: true,
                    };
                }
                let v = src.reference(self, index, i).pbrdf.to_row_major();
                overflow |= out.put_one(i, &v);
            }
            return Outcome {
                overflow,
                invalid: false,
            };
        }
        let mut job = MuellerJob::<G, W, N> {
            kernel: self,
            src,
            index,
            out,
            overflow: false,
            invalid: false,
        };
        dispatch(self.level_for(N), &mut job);
        Outcome {
            overflow: job.overflow,
            invalid: job.invalid,
        }
    }

    fn run_brdf_dolp<G: Blocks, const N: usize, const AOLP: bool>(
        &self,
        src: &G,
        index: IndexSource<'_>,
        brdf: &mut [f64],
        dolp: &mut [f64],
        aolp: &mut [f64],
    ) {
        if self.scalar_only {
            for i in 0..brdf.len() {
                let e = src.reference(self, index, i);
                (brdf[i], dolp[i]) = (e.brdf(), e.dolp());
                if AOLP {
                    aolp[i] = e.reflect(&Stokes::unpolarized()).aolp();
                }
            }
            return;
        }
        let mut job = BrdfDolpJob::<G, N, AOLP> {
            kernel: self,
            src,
            index,
            brdf,
            dolp,
            aolp,
        };
        dispatch(self.level_for(N), &mut job);
    }

    /// The level to run blocks of `n` elements with: a single element is scalar code, where the
    /// AVX2+FMA build is the fastest.
    fn level_for(&self, n: usize) -> SimdLevel {
        if n == 1 && self.level == SimdLevel::Avx512 {
            SimdLevel::Avx2
        } else {
            self.level
        }
    }
}

#[cfg(test)]
mod direction_route;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::block::{self, AngleNeeds, BlockIn, Front, GeomScratch};
    use crate::numeric::math::FastUnfused;
    use crate::numeric::sample::SplitMix64;
    use index::SpectralCache;

    #[test]
    fn presets_never_take_the_one_geometry_path() {
        // "For ordinary materials and geometries no element takes that path."
        let mut rng = SplitMix64::new(1);
        for preset in crate::model::presets::all() {
            let m = preset.spec.build().unwrap();
            let k = Kernel::new(&m);
            for _ in 0..1000 {
                let mut b = BlockIn::<BLOCK>::zeroed();
                for j in 0..BLOCK {
                    b.ti[j] = rng.range(0.0, 89.9f64.to_radians());
                    b.pi[j] = rng.range(0.0, 2.0 * std::f64::consts::PI);
                    b.tr[j] = rng.range(0.0, 89.9f64.to_radians());
                    b.pr[j] = rng.range(0.0, 2.0 * std::f64::consts::PI);
                }
                let idx = k.index.lanes::<BLOCK>(0, BLOCK, &mut SpectralCache::new());
                let mut s = GeomScratch::<BLOCK>::zeroed();
                s.input = b;
                block::geometry::<FastUnfused, BLOCK, true>(&mut s, AngleNeeds::of(&k.params));
                let mut rows = [[0.0; BLOCK]; 16];
                let mut f = Front::<BLOCK>::zeroed();
                block::front::<FastUnfused, BLOCK>(&k.params, &s.geo, &idx, &mut f);
                block::mueller::<FastUnfused, BLOCK>(&mut f, &s.geo, &mut rows);
                assert!(!f.fallback.iter().any(|f| *f), "{}", preset.name);
                let mut lanes = [[0.0; BLOCK]; 3];
                let mut f = Front::<BLOCK>::zeroed();
                block::front::<FastUnfused, BLOCK>(&k.params, &s.geo, &idx, &mut f);
                block::brdf_dolp::<FastUnfused, BLOCK, true>(&mut f, &s.geo, &mut lanes);
                assert!(!f.fallback.iter().any(|f| *f), "{}", preset.name);
            }
        }
    }
}
