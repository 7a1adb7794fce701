//! The serial evaluator of the batch engine: blocks of [`BLOCK`] elements through the block
//! kernel (`crate::engine::block`), at the best instruction set of the CPU, with the
//! one-geometry path for the elements the kernel must not vectorize. `crate::engine::batch` runs
//! it in parallel.

#![allow(clippy::needless_range_loop)]

use crate::engine::block::{
    self, AngleNeeds, BlockIn, Front, Geom, GeomScratch, IndexLanes, Lanes, Thresholds,
};
use crate::engine::planes::Planes;
use crate::engine::simd::{simd_level, SimdLevel};
use crate::error::{Error, Result, MAX_INDEX};
use crate::geometry::angles::{self, Trig};
use crate::geometry::batch::{Batch, Input};
use crate::geometry::{AngleVariables, DirectionBatch, Geometry, GeometryBatch};
use crate::model::{Evaluation, Material, ModelParams};
use crate::numeric::math::{FastPortable, Math};
use crate::numeric::math32::SinglePortable;
use crate::optics::dispersion::SpectralIndex;
use crate::optics::fresnel::{index_squared, RefractiveIndex};
use crate::optics::mueller::Mueller;
use crate::optics::stokes::Stokes;

/// Runs `$body` with `$src` bound to the kernel's source of elements `$start .. $start + $len`
/// of `$batch` (a [`Batch`]): angles or direction vectors.
macro_rules! with_source {
    ($batch:expr, $start:expr, $len:expr, |$src:ident| $body:expr) => {
        match $batch.input() {
            Input::Angles(b) => {
                let $src = Computed(BatchSource::new(&b, $start, $len));
                $body
            }
            Input::Directions(d) => {
                let $src = Directions::new(&d, $start, $len);
                $body
            }
        }
    };
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

/// A complex refractive index per element, `N_j = n_j + i·k_j`, validated (each as by
/// [`RefractiveIndex::new`]): the engine evaluates element `j` with `N_j` instead of the
/// material's own index — how one call covers materials × wavelengths × geometries.
#[derive(Debug, Clone, Copy)]
pub struct IndexColumns<'a> {
    n: &'a [f64],
    k: &'a [f64],
}

impl<'a> IndexColumns<'a> {
    /// `n` and `k` of equal length.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`], or [`Error::InvalidParameterAt`] naming `n` or `k`, the value
    /// and the element.
    pub fn new(n: &'a [f64], k: &'a [f64]) -> Result<Self> {
        crate::geometry::batch::check_len("k", k.len(), n.len())?;
        for (i, (&nv, &kv)) in n.iter().zip(k).enumerate() {
            if let Err(Error::InvalidParameter {
                name,
                value,
                reason,
            }) = RefractiveIndex::new(nv, kv)
            {
                return Err(Error::InvalidParameterAt {
                    name,
                    value,
                    index: i,
                    reason,
                });
            }
        }
        Ok(Self { n, k })
    }

    /// Number of elements.
    pub fn len(&self) -> usize {
        self.n.len()
    }

    /// True when there are none.
    pub fn is_empty(&self) -> bool {
        self.n.is_empty()
    }

    /// The index of element `i`.
    pub fn get(&self, i: usize) -> RefractiveIndex {
        RefractiveIndex::new(self.n[i], self.k[i]).expect("validated at construction")
    }

    fn slice(&self, start: usize, len: usize) -> Self {
        Self {
            n: &self.n[start..start + len],
            k: &self.k[start..start + len],
        }
    }
}

/// Where the index of each element comes from.
#[derive(Debug, Clone, Copy)]
enum IndexSource<'a> {
    /// The material's own: `N²` and whether it is outside the kernel's accurate domain.
    Constant { n2r: f64, n2i: f64, ill: bool },
    /// One per element.
    PerElement(IndexColumns<'a>),
    /// A spectral index at one wavelength (µm) per element, looked up block by block through a
    /// [`SpectralCache`] (validated in range by [`Kernel::with_wavelengths`]).
    Spectral {
        index: &'a SpectralIndex,
        wavelengths: &'a [f64],
    },
}

/// The per-job cache of a spectral index: `N²` and the domain flag of the wavelengths seen, in
/// an open-addressing table keyed on the wavelength's bits (allocated on first use, so jobs
/// without a spectral index pay nothing). Up to [`SpectralCache::KEYS`] distinct wavelengths
/// per job stay cached — a repeated wavelength, in runs or cycling, costs a comparison or two
/// instead of a search of the data; beyond that the table starts over.
struct SpectralCache {
    slots: Vec<(f64, f64, f64, bool)>,
    used: usize,
}

impl SpectralCache {
    const SLOTS: usize = 256;
    const KEYS: usize = Self::SLOTS / 2;

    fn new() -> Self {
        Self {
            slots: Vec::new(),
            used: 0,
        }
    }

    /// An empty table (NaN never equals a key: every slot starts empty).
    #[cold]
    fn reset(&mut self) {
        self.slots.clear();
        self.slots.resize(Self::SLOTS, (f64::NAN, 0.0, 0.0, true));
        self.used = 0;
    }

    /// `(n2r, n2i, ill)` at `lambda_um`; NaN and ill where the data give no valid index there
    /// (the element then takes the one-geometry path, which reports NaN).
    #[inline(always)]
    fn get(&mut self, index: &SpectralIndex, lambda_um: f64) -> (f64, f64, bool) {
        if self.slots.is_empty() || self.used >= Self::KEYS {
            self.reset();
        }
        // Fibonacci hashing of the bits into 8 bits, then linear probing.
        let mut slot = (lambda_um.to_bits().wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 56) as usize;
        loop {
            let (key, a, b, ill) = self.slots[slot];
            if key == lambda_um {
                return (a, b, ill);
            }
            if key.is_nan() {
                break;
            }
            slot = (slot + 1) % Self::SLOTS;
        }
        self.insert(index, lambda_um, slot)
    }

    /// A wavelength not in the table: looked up in the data and stored in `slot`.
    #[cold]
    #[inline(never)]
    fn insert(&mut self, index: &SpectralIndex, lambda_um: f64, slot: usize) -> (f64, f64, bool) {
        let (a, b, ill) = match index.at(lambda_um) {
            Ok(n) => {
                let (a, b) = n.squared();
                (a, b, index_ill(a, b))
            }
            Err(_) => (f64::NAN, f64::NAN, true),
        };
        if !lambda_um.is_nan() {
            self.slots[slot] = (lambda_um, a, b, ill);
            self.used += 1;
        }
        (a, b, ill)
    }
}

/// Whether an index is outside the f64 kernel's accurate domain ([`index_ill_for`]).
#[inline(always)]
fn index_ill(n2r: f64, n2i: f64) -> bool {
    index_ill_for::<f64>(n2r, n2i)
}

/// Whether an index is outside the accurate domain of the kernel in `T`: the Fresnel
/// amplitudes lose relative accuracy as `N² → 1` (`rs = (1 − N²)/(c + q)²`), with condition
/// `(1 + sqrt(|N²| + 1))²/|1 − N²|` — at [`Thresholds::INDEX_COND_MAX`] or more (100 in f64,
/// 20 in f32) such elements take the one-geometry path — and magnitudes of `N²` beyond
/// `10^±100` are left to it too.
#[inline(always)]
fn index_ill_for<T: Thresholds>(n2r: f64, n2i: f64) -> bool {
    // Squares, not `hypot`: this runs per element for a per-element index (|N²| ≤ 2·10¹², so
    // nothing overflows).
    let n2_abs = (n2r * n2r + n2i * n2i).sqrt();
    let c = 1.0 + (n2_abs + 1.0).sqrt();
    let gap = ((1.0 - n2r) * (1.0 - n2r) + n2i * n2i).sqrt();
    !(c * c < T::INDEX_COND_MAX * gap && n2_abs < 1e100 && n2_abs > 1e-100)
}

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
    /// larger than the caches, slower for outputs read back at once. Partial blocks,
    /// elements taken from the one-geometry path and other outputs use plain stores. The bits
    /// are the same either way. Off by default ([`crate::Engine`] decides by the output's
    /// size).
    pub fn streaming(mut self, on: bool) -> Self {
        self.stream = on;
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
    /// same formulas computed in f32, within 1e-5·F00 of the f64 results; an element where f32
    /// would not reach that (D far down its tail, both directions near grazing, an index near
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
            if self.scalar_only || !self.single {
                return self.run_mueller::<_, _, BLOCK>(&src, index, out);
            }
            match self.level {
                SimdLevel::Avx512 | SimdLevel::Avx2 => {
                    self.f32_job::<_, _, BLOCK_F32_WIDE>(&src, index, out)
                }
                SimdLevel::Portable => self.f32_job::<_, _, BLOCK>(&src, index, out),
            }
        })
    }

    /// The f32 kernel over blocks of `N` elements.
    fn f32_job<G: F32Blocks, W: SinkF32, const N: usize>(
        &self,
        src: &G,
        index: IndexSource<'_>,
        out: &mut W,
    ) -> bool {
        let mut job = MuellerF32Job::<_, _, N> {
            kernel: self,
            src,
            index,
            out,
            overflow: false,
        };
        dispatch(self.level, &mut job);
        job.overflow
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

    fn run_mueller<G: Blocks, W: Sink, const N: usize>(
        &self,
        src: &G,
        index: IndexSource<'_>,
        out: &mut W,
    ) -> bool {
        if self.scalar_only {
            let mut overflow = false;
            for i in 0..out.len() {
                let v = src.reference(self, index, i).pbrdf.to_row_major();
                overflow |= out.put_one(i, &v);
            }
            return overflow;
        }
        let mut job = MuellerJob::<G, W, N> {
            kernel: self,
            src,
            index,
            out,
            overflow: false,
        };
        dispatch(self.level_for(N), &mut job);
        job.overflow
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

impl IndexSource<'_> {
    /// The index of element `i`; `None` where a spectral index's data give no valid one.
    fn get(&self, i: usize, material: &Material) -> Option<RefractiveIndex> {
        match self {
            IndexSource::Constant { .. } => Some(material.index()),
            IndexSource::PerElement(cols) => Some(cols.get(i)),
            IndexSource::Spectral { index, wavelengths } => index.at(wavelengths[i]).ok(),
        }
    }

    /// `N²` and the domain flag of elements `start .. start + len` (the rest of the block
    /// repeats element `start`).
    #[inline(always)]
    fn lanes<const N: usize>(
        &self,
        start: usize,
        len: usize,
        cache: &mut SpectralCache,
    ) -> IndexLanes<N> {
        self.lanes_at(|j| start + if j < len { j } else { 0 }, cache)
    }

    /// `N²` and the domain flag of the elements at positions `pos(0) .. pos(N − 1)`.
    #[inline(always)]
    fn lanes_at<const N: usize>(
        &self,
        pos: impl Fn(usize) -> usize,
        cache: &mut SpectralCache,
    ) -> IndexLanes<N> {
        match *self {
            IndexSource::Spectral { index, wavelengths } => {
                let mut b = IndexLanes {
                    n2r: [0.0; N],
                    n2i: [0.0; N],
                    index_ill: [false; N],
                };
                let mut last = f64::NAN;
                let mut value = (0.0, 0.0, true);
                for j in 0..N {
                    let l = wavelengths[pos(j)];
                    // Runs of one wavelength (wavelength-major) skip the table.
                    if l != last {
                        value = cache.get(index, l);
                        last = l;
                    }
                    (b.n2r[j], b.n2i[j], b.index_ill[j]) = value;
                }
                b
            }
            IndexSource::Constant { n2r, n2i, ill } => IndexLanes {
                n2r: [n2r; N],
                n2i: [n2i; N],
                index_ill: [ill; N],
            },
            IndexSource::PerElement(cols) => {
                let mut b = IndexLanes {
                    n2r: [0.0; N],
                    n2i: [0.0; N],
                    index_ill: [false; N],
                };
                for j in 0..N {
                    let i = pos(j);
                    (b.n2r[j], b.n2i[j]) = index_squared(cols.n[i], cols.k[i]);
                }
                for j in 0..N {
                    b.index_ill[j] = index_ill(b.n2r[j], b.n2i[j]);
                }
                b
            }
        }
    }

    /// [`IndexSource::lanes`] for the f32 kernel: `N²` rounded to f32, and the f32 kernel's
    /// (narrower) domain; `ill32` is that domain's flag of a constant index.
    #[inline(always)]
    fn lanes_f32<const N: usize>(
        &self,
        start: usize,
        len: usize,
        ill32: bool,
        cache: &mut SpectralCache,
    ) -> IndexLanes<N, f32> {
        if let IndexSource::Constant { n2r, n2i, .. } = *self {
            return IndexLanes {
                n2r: [n2r as f32; N],
                n2i: [n2i as f32; N],
                index_ill: [ill32; N],
            };
        }
        let w = self.lanes::<N>(start, len, cache);
        IndexLanes {
            n2r: w.n2r.map(|x| x as f32),
            n2i: w.n2i.map(|x| x as f32),
            index_ill: std::array::from_fn(|j| {
                w.index_ill[j] || index_ill_for::<f32>(w.n2r[j], w.n2i[j])
            }),
        }
    }
}

// Compile-time check that the bound the index columns are validated against is the one the
// domain test assumes (|N²| ≤ 2·10¹² < 10¹⁰⁰).
const _: () = assert!(MAX_INDEX <= 1e6);

// -------------------------------------------------------------------------------------------
// Inputs: angles by index; the geometry part of a block, computed or prepared.

/// Validated angles (θi, φi, θr, φr) in radians, by index.
trait Source {
    fn get(&self, i: usize) -> [f64; 4];

    /// Elements `start .. start + N` into `b`.
    #[inline(always)]
    fn load_block<const N: usize>(&self, start: usize, b: &mut BlockIn<N>) {
        for j in 0..N {
            [b.ti[j], b.pi[j], b.tr[j], b.pr[j]] = self.get(start + j);
        }
    }
}

struct BatchSource<'a> {
    cols: [&'a [f64]; 4],
}

impl<'a> BatchSource<'a> {
    fn new(batch: &GeometryBatch<'a>, start: usize, len: usize) -> Self {
        let cols = batch.columns();
        assert!(
            start.checked_add(len).is_some_and(|end| end <= batch.len()),
            "range {start}..{start}+{len} beyond a batch of {}",
            batch.len()
        );
        Self {
            cols: cols.map(|c| &c[start..start + len]),
        }
    }
}

impl Source for BatchSource<'_> {
    #[inline(always)]
    fn get(&self, i: usize) -> [f64; 4] {
        [
            self.cols[0][i],
            self.cols[1][i],
            self.cols[2][i],
            self.cols[3][i],
        ]
    }

    #[inline(always)]
    fn load_block<const N: usize>(&self, start: usize, b: &mut BlockIn<N>) {
        let r = start..start + N;
        b.ti.copy_from_slice(&self.cols[0][r.clone()]);
        b.pi.copy_from_slice(&self.cols[1][r.clone()]);
        b.tr.copy_from_slice(&self.cols[2][r.clone()]);
        b.pr.copy_from_slice(&self.cols[3][r]);
    }
}

impl Source for &[Geometry] {
    #[inline(always)]
    fn get(&self, i: usize) -> [f64; 4] {
        let g = &self[i];
        [g.theta_i(), g.phi_i(), g.theta_r(), g.phi_r()]
    }
}

/// Elements `start .. start + len` (len ≤ N) of `src` into `b`; the rest of the block repeats
/// element `start` (valid input, results discarded).
#[inline(always)]
fn load<S: Source, const N: usize>(src: &S, start: usize, len: usize, b: &mut BlockIn<N>) {
    if len == N {
        src.load_block(start, b);
    } else {
        for j in 0..N {
            [b.ti[j], b.pi[j], b.tr[j], b.pr[j]] = src.get(start + if j < len { j } else { 0 });
        }
    }
    for j in 0..N {
        // `+ 0.0` turns −0.0 into +0.0, as `Geometry` does.
        b.ti[j] += 0.0;
        b.tr[j] += 0.0;
    }
}

/// Where the geometry part of each block comes from, and the one-geometry path of an element.
trait Blocks {
    /// The geometry part of elements `start .. start + len` (len ≤ N), the optional angles
    /// where `needs` says:
    /// computed in `scratch` (and returned from there) or taken from where it was prepared.
    fn geometry<'s, M: Math, const N: usize, const PAIRS: bool>(
        &'s self,
        start: usize,
        len: usize,
        needs: AngleNeeds,
        scratch: &'s mut GeomScratch<N, M::F>,
    ) -> &'s Geom<N, M::F>
    where
        M::F: Thresholds;

    /// Element `i` by the one-geometry path.
    fn reference(&self, k: &Kernel<'_>, index: IndexSource<'_>, i: usize) -> Evaluation;
}

/// Geometries whose geometry stages the kernel computes.
struct Computed<S>(S);

impl<S: Source> Blocks for Computed<S> {
    #[inline(always)]
    fn geometry<'s, M: Math, const N: usize, const PAIRS: bool>(
        &'s self,
        start: usize,
        len: usize,
        needs: AngleNeeds,
        scratch: &'s mut GeomScratch<N, M::F>,
    ) -> &'s Geom<N, M::F>
    where
        M::F: Thresholds,
    {
        load::<S, N>(&self.0, start, len, &mut scratch.input);
        block::geometry::<M, N, PAIRS>(scratch, needs);
        &scratch.geo
    }

    fn reference(&self, k: &Kernel<'_>, index: IndexSource<'_>, i: usize) -> Evaluation {
        let [ti, pi, tr, pr] = self.0.get(i);
        one_geometry(
            k,
            index,
            i,
            Geometry::new_unchecked(ti + 0.0, pi, tr + 0.0, pr),
        )
    }
}

/// Element `i` (at geometry `g`) by the one-geometry path, with its index.
fn one_geometry(k: &Kernel<'_>, index: IndexSource<'_>, i: usize, g: Geometry) -> Evaluation {
    index
        .get(i, k.material)
        .map_or_else(Evaluation::undefined, |n| {
            k.material.evaluate_with_index(&g, n)
        })
}

/// What the single-precision job needs of a source beyond [`Blocks`]: θN in f64 for D's
/// refinement, and the f64 geometry of gathered elements.
trait F32Blocks: Blocks {
    /// The f64 input of lane `j` of the block whose f32 geometry `scratch` holds (angles, or
    /// the two vectors), for [`F32Blocks::theta_n_f64`].
    fn lane_input<const N: usize>(scratch: &GeomScratch<N, f32>, j: usize) -> [f64; 6];

    /// θN (rad) in f64 (backend `M`) of one element's [`F32Blocks::lane_input`].
    fn theta_n_f64<M: Math<F = f64>>(x: [f64; 6]) -> f64;

    /// The f64 geometry stages of the elements at positions `pos` (at most N; the rest of the
    /// block repeats the first) into `scratch`.
    fn gathered_geometry<M: Math<F = f64>, const N: usize>(
        &self,
        pos: &[usize],
        needs: AngleNeeds,
        scratch: &mut GeomScratch<N>,
    );
}

impl<S: Source> F32Blocks for Computed<S> {
    #[inline(always)]
    fn lane_input<const N: usize>(scratch: &GeomScratch<N, f32>, j: usize) -> [f64; 6] {
        let b = &scratch.input;
        [b.ti[j], b.pi[j], b.tr[j], b.pr[j], 0.0, 0.0]
    }

    #[inline(always)]
    fn theta_n_f64<M: Math<F = f64>>(x: [f64; 6]) -> f64 {
        // As the f64 path computes it: the reduction, the four sine/cosine pairs, the half
        // vector and one arctangent, from the block's f64 angles.
        let t = Trig::<f64>::new::<M>(x[0], x[1], x[2], x[3]);
        angles::theta_n::<M>(&angles::half_vector::<M>(&t))
    }

    #[inline(always)]
    fn gathered_geometry<M: Math<F = f64>, const N: usize>(
        &self,
        pos: &[usize],
        needs: AngleNeeds,
        scratch: &mut GeomScratch<N>,
    ) {
        let src = Gathered { src: &self.0, pos };
        load::<_, N>(&src, 0, pos.len(), &mut scratch.input);
        block::geometry::<M, N, true>(scratch, needs);
    }
}

/// Direction vectors (the direction entry point, [`DirectionBatch`]) of elements
/// `start .. start + len` of a batch.
struct Directions<'a> {
    w_i: &'a [[f64; 3]],
    w_r: &'a [[f64; 3]],
}

impl<'a> Directions<'a> {
    fn new(batch: &DirectionBatch<'a>, start: usize, len: usize) -> Self {
        assert!(
            start.checked_add(len).is_some_and(|end| end <= batch.len()),
            "range {start}..{start}+{len} beyond a batch of {}",
            batch.len()
        );
        let (w_i, w_r) = batch.directions();
        Self {
            w_i: &w_i[start..start + len],
            w_r: &w_r[start..start + len],
        }
    }

    /// The vectors of elements `pos(0) .. pos(N − 1)` into `dirs` (structure of arrays).
    #[inline(always)]
    fn load<const N: usize>(&self, pos: impl Fn(usize) -> usize, dirs: &mut [Lanes<N>; 6]) {
        for j in 0..N {
            let (a, b) = (self.w_i[pos(j)], self.w_r[pos(j)]);
            [dirs[0][j], dirs[1][j], dirs[2][j]] = a;
            [dirs[3][j], dirs[4][j], dirs[5][j]] = b;
        }
    }
}

impl Blocks for Directions<'_> {
    #[inline(always)]
    fn geometry<'s, M: Math, const N: usize, const PAIRS: bool>(
        &'s self,
        start: usize,
        len: usize,
        needs: AngleNeeds,
        scratch: &'s mut GeomScratch<N, M::F>,
    ) -> &'s Geom<N, M::F>
    where
        M::F: Thresholds,
    {
        self.load::<N>(|j| start + if j < len { j } else { 0 }, &mut scratch.dirs);
        block::geometry_of_directions::<M, N, PAIRS>(scratch, needs);
        &scratch.geo
    }

    fn reference(&self, k: &Kernel<'_>, index: IndexSource<'_>, i: usize) -> Evaluation {
        let (ti, pi) = angles::direction_angles(self.w_i[i]);
        let (tr, pr) = angles::direction_angles(self.w_r[i]);
        one_geometry(k, index, i, Geometry::new_unchecked(ti, pi, tr, pr))
    }
}

impl F32Blocks for Directions<'_> {
    #[inline(always)]
    fn lane_input<const N: usize>(scratch: &GeomScratch<N, f32>, j: usize) -> [f64; 6] {
        std::array::from_fn(|c| scratch.dirs[c][j])
    }

    #[inline(always)]
    fn theta_n_f64<M: Math<F = f64>>(x: [f64; 6]) -> f64 {
        // θN = atan2(|s_xy|, s_z) of the half vector s = ŵ_i + ŵ_r of the f64 vectors.
        let unit = |v: [f64; 3]| {
            let inv = 1.0 / M::mla(v[0], v[0], M::mla(v[1], v[1], v[2] * v[2])).sqrt();
            [v[0] * inv, v[1] * inv, v[2] * inv]
        };
        let (a, b) = (unit([x[0], x[1], x[2]]), unit([x[3], x[4], x[5]]));
        let s = [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
        M::atan2_pos(M::mla(s[0], s[0], s[1] * s[1]).sqrt(), s[2].max(0.0))
    }

    #[inline(always)]
    fn gathered_geometry<M: Math<F = f64>, const N: usize>(
        &self,
        pos: &[usize],
        needs: AngleNeeds,
        scratch: &mut GeomScratch<N>,
    ) {
        self.load::<N>(
            |j| pos[if j < pos.len() { j } else { 0 }],
            &mut scratch.dirs,
        );
        block::geometry_of_directions::<M, N, true>(scratch, needs);
    }
}

/// Explicit angle variables (the angle-variable entry point).
struct Variables<'v>(&'v [AngleVariables]);

impl Blocks for Variables<'_> {
    #[inline(always)]
    fn geometry<'s, M: Math, const N: usize, const PAIRS: bool>(
        &'s self,
        start: usize,
        len: usize,
        _needs: AngleNeeds,
        scratch: &'s mut GeomScratch<N, M::F>,
    ) -> &'s Geom<N, M::F>
    where
        M::F: Thresholds,
    {
        let v: [AngleVariables; N] =
            std::array::from_fn(|j| self.0[start + if j < len { j } else { 0 }]);
        block::geometry_of_variables(&v, &mut scratch.geo);
        &scratch.geo
    }

    fn reference(&self, k: &Kernel<'_>, index: IndexSource<'_>, i: usize) -> Evaluation {
        index
            .get(i, k.material)
            .map_or_else(Evaluation::undefined, |n| {
                k.material.evaluate_angles_with_index(&self.0[i], n)
            })
    }
}

/// The geometry stages of a batch, computed once ([`Kernel::prepare`]): what does not depend
/// on the material, per element, in the blocks the kernel evaluates.
#[derive(Clone)]
pub struct Prepared {
    level: SimdLevel,
    len: usize,
    blocks: Vec<Geom<BLOCK>>,
}

impl std::fmt::Debug for Prepared {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Prepared")
            .field("level", &self.level)
            .field("len", &self.len)
            .finish_non_exhaustive()
    }
}

impl Prepared {
    fn with_capacity(n: usize, level: SimdLevel) -> Self {
        Self {
            level,
            len: 0,
            blocks: Vec::with_capacity(n.div_ceil(BLOCK)),
        }
    }

    /// Number of elements.
    pub fn len(&self) -> usize {
        self.len
    }

    /// True when there are none.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The SIMD level the geometry was computed with (kernels of this level use it).
    pub fn level(&self) -> SimdLevel {
        self.level
    }

    /// `other`'s elements after this one's (this one a whole number of blocks long).
    pub(crate) fn append(&mut self, other: Prepared) {
        assert_eq!(self.level, other.level, "prepared at one SIMD level");
        assert_eq!(self.len % BLOCK, 0, "appended after whole blocks");
        self.blocks.extend(other.blocks);
        self.len += other.len;
    }

    /// An empty batch prepared at `level`.
    pub(crate) fn empty(level: SimdLevel) -> Self {
        Self::with_capacity(0, level)
    }

    fn push(&mut self, g: Geom<BLOCK>, len: usize) {
        self.blocks.push(g);
        self.len += len;
    }

    fn range(&self, start: usize, len: usize, level: SimdLevel) -> PreparedRange<'_> {
        assert_eq!(
            self.level, level,
            "a batch prepared at one SIMD level evaluated at another"
        );
        assert!(
            start.is_multiple_of(BLOCK) && start + len <= self.len,
            "range {start}..{start}+{len} of a prepared batch of {} (start a multiple of {BLOCK})",
            self.len
        );
        PreparedRange {
            p: self,
            first: start / BLOCK,
        }
    }
}

/// The blocks of a prepared batch from block `first` on.
struct PreparedRange<'p> {
    p: &'p Prepared,
    first: usize,
}

impl Blocks for PreparedRange<'_> {
    #[inline(always)]
    fn geometry<'s, M: Math, const N: usize, const PAIRS: bool>(
        &'s self,
        start: usize,
        _len: usize,
        _needs: AngleNeeds,
        _scratch: &'s mut GeomScratch<N, M::F>,
    ) -> &'s Geom<N, M::F>
    where
        M::F: Thresholds,
    {
        // Only whole blocks are prepared: the jobs run prepared batches with N = BLOCK. (A
        // partial last block was padded when prepared, as `load` pads.)
        assert!(start.is_multiple_of(BLOCK), "prepared blocks of {BLOCK}");
        let g: &dyn std::any::Any = &self.p.blocks[self.first + start / BLOCK];
        g.downcast_ref::<Geom<N, M::F>>()
            .expect("prepared blocks are evaluated in blocks of BLOCK")
    }

    fn reference(&self, k: &Kernel<'_>, index: IndexSource<'_>, i: usize) -> Evaluation {
        let g = &self.p.blocks[self.first + i / BLOCK];
        let a = |c: usize| g.angles[c][i % BLOCK];
        one_geometry(k, index, i, Geometry::new_unchecked(a(0), a(1), a(2), a(3)))
    }
}

/// Where one 4×4 result goes.
trait MuellerOut: Sized {
    fn set(&mut self, v: &[f64; 16]);

    /// Writes a block given as 16 rows of lanes (entry-major; the first `dst.len()` lanes),
    /// through `staged`; `stream`: with non-temporal stores where the format and the
    /// destination allow (outputs much larger than the caches, not read back soon). Returns as
    /// [`MuellerOut::write_block`].
    #[inline(always)]
    fn write_rows<const N: usize>(
        dst: &mut [Self],
        rows: &[Lanes<N>; 16],
        staged: &mut [[f64; 16]; N],
        _stream: bool,
    ) -> bool {
        transpose(rows, staged, false);
        Self::write_block(dst, staged)
    }

    /// Copies results out. Returns whether a finite value became infinite (only a narrower
    /// format can overflow).
    #[inline(always)]
    fn write_block(dst: &mut [Self], src: &[[f64; 16]]) -> bool {
        for (o, v) in dst.iter_mut().zip(src) {
            o.set(v);
        }
        false
    }
}

impl MuellerOut for [f64; 16] {
    #[inline(always)]
    fn set(&mut self, v: &[f64; 16]) {
        *self = *v;
    }

    /// A whole block is transposed straight into `dst` (with `stream`, by non-temporal stores
    /// where `dst` is 16-byte aligned), a partial one through `staged`.
    #[inline(always)]
    fn write_rows<const N: usize>(
        dst: &mut [Self],
        rows: &[Lanes<N>; 16],
        staged: &mut [[f64; 16]; N],
        stream: bool,
    ) -> bool {
        match <&mut [Self; N]>::try_from(&mut *dst) {
            Ok(whole) => transpose(rows, whole, stream),
            Err(_) => {
                transpose(rows, staged, false);
                dst.copy_from_slice(&staged[..dst.len()]);
            }
        }
        false
    }
}

/// Single precision: each entry rounded to the nearest f32 (`as f32`), which is what a caller
/// converting f64 results would get, without the f64 array in memory.
impl MuellerOut for [f32; 16] {
    #[inline(always)]
    fn set(&mut self, v: &[f64; 16]) {
        *self = v.map(|x| x as f32);
    }

    /// A whole block: rounded to f32 entry-major (one vectorized loop, with the overflow
    /// check), then transposed straight into `dst`; a partial one through `staged`. Plain
    /// stores ([`transpose_f32`]).
    #[inline(always)]
    fn write_rows<const N: usize>(
        dst: &mut [Self],
        rows: &[Lanes<N>; 16],
        staged: &mut [[f64; 16]; N],
        _stream: bool,
    ) -> bool {
        match <&mut [Self; N]>::try_from(&mut *dst) {
            Ok(whole) => {
                // Built in place (no zeroing per block).
                let narrow: [[f32; N]; 16] =
                    std::array::from_fn(|e| std::array::from_fn(|j| rows[e][j] as f32));
                let mut overflow = false;
                for (o, r) in narrow.iter().zip(rows) {
                    for (y, x) in o.iter().zip(r) {
                        overflow |= y.is_infinite() & x.is_finite();
                    }
                }
                transpose_f32(&narrow, whole);
                overflow
            }
            Err(_) => {
                transpose(rows, staged, false);
                Self::write_block(dst, staged)
            }
        }
    }

    #[inline(always)]
    fn write_block(dst: &mut [Self], src: &[[f64; 16]]) -> bool {
        let n = dst.len().min(src.len());
        // Flat, so that the conversion is one vectorized loop.
        let (dst, src) = (dst[..n].as_flattened_mut(), src[..n].as_flattened());
        let mut overflow = false;
        for (o, x) in dst.iter_mut().zip(src) {
            *o = *x as f32;
            overflow |= o.is_infinite() & x.is_finite();
        }
        overflow
    }
}

/// Whether non-temporal stores can go to `dst`: 16-byte aligned (every row of a block then is).
#[inline(always)]
fn stream_to<T>(dst: &[T], stream: bool) -> bool {
    stream && (dst.as_ptr() as usize).is_multiple_of(16)
}

/// Where a job's results go: the caller's row-major array ([`Rows`]) or its planes
/// ([`Planes`]), written a block (or one element) at a time at positions relative to the job's
/// start.
trait Sink {
    /// The number of elements.
    fn len(&self) -> usize;

    /// Elements `start .. start + len` from a block's 16 rows of lanes (entry-major), through
    /// `staged` where needed; `stream` as [`MuellerOut::write_rows`]. Returns whether a finite
    /// value became infinite (only a narrower format can overflow).
    fn put_rows<const N: usize>(
        &mut self,
        start: usize,
        len: usize,
        rows: &[Lanes<N>; 16],
        staged: &mut [[f64; 16]; N],
        stream: bool,
    ) -> bool;

    /// Element `i` (row-major), returning as [`Sink::put_rows`].
    fn put_one(&mut self, i: usize, v: &[f64; 16]) -> bool;
}

/// A [`Sink`] of single precision, which also takes the f32 kernel's rows.
trait SinkF32: Sink {
    /// Elements `start .. start + len` from a block's 16 rows of f32 lanes.
    fn put_rows_f32<const N: usize>(
        &mut self,
        start: usize,
        len: usize,
        rows: &[[f32; N]; 16],
        staged: &mut [[f32; 16]; N],
    );
}

/// A row-major output: one 4×4 result per element.
struct Rows<'o, O>(&'o mut [O]);

impl<O: MuellerOut> Sink for Rows<'_, O> {
    #[inline(always)]
    fn len(&self) -> usize {
        self.0.len()
    }
    #[inline(always)]
    fn put_rows<const N: usize>(
        &mut self,
        start: usize,
        len: usize,
        rows: &[Lanes<N>; 16],
        staged: &mut [[f64; 16]; N],
        stream: bool,
    ) -> bool {
        O::write_rows(&mut self.0[start..start + len], rows, staged, stream)
    }
    #[inline(always)]
    fn put_one(&mut self, i: usize, v: &[f64; 16]) -> bool {
        O::write_block(&mut self.0[i..i + 1], std::slice::from_ref(v))
    }
}

impl SinkF32 for Rows<'_, [f32; 16]> {
    /// A whole block is transposed straight into the output, a partial one through `staged`.
    #[inline(always)]
    fn put_rows_f32<const N: usize>(
        &mut self,
        start: usize,
        len: usize,
        rows: &[[f32; N]; 16],
        staged: &mut [[f32; 16]; N],
    ) {
        let dst = &mut self.0[start..start + len];
        match <&mut [[f32; 16]; N]>::try_from(&mut *dst) {
            Ok(whole) => transpose_f32(rows, whole),
            Err(_) => {
                transpose_f32(rows, staged);
                dst.copy_from_slice(&staged[..len]);
            }
        }
    }
}

/// Lanes `..len` of each row into `planes[e][start..start + len]`: a whole block as fixed-size
/// copies (a few vector moves each; a `memcpy` call per plane would cost more than the copy).
#[inline(always)]
fn copy_rows<T: Copy, const N: usize>(
    planes: &mut [&mut [T]; 16],
    start: usize,
    len: usize,
    rows: &[[T; N]; 16],
) {
    for (plane, row) in planes.iter_mut().zip(rows) {
        match <&mut [T; N]>::try_from(&mut plane[start..start + len]) {
            Ok(whole) => *whole = *row,
            Err(_) => plane[start..start + len].copy_from_slice(&row[..len]),
        }
    }
}

/// An element type of planar output: f64, or f32 with each entry rounded to the nearest
/// (`as f32`, as [`MuellerOut`] for `[f32; 16]`).
trait PlaneElem: Copy {
    /// `x` in this type, and whether a finite `x` became infinite.
    fn narrow(x: f64) -> (Self, bool);
}

impl PlaneElem for f64 {
    #[inline(always)]
    fn narrow(x: f64) -> (f64, bool) {
        (x, false)
    }
}

impl PlaneElem for f32 {
    #[inline(always)]
    fn narrow(x: f64) -> (f32, bool) {
        let y = x as f32;
        (y, y.is_infinite() & x.is_finite())
    }
}

/// Planes take a block's rows as they are: 16 contiguous runs, no transpose (and no
/// non-temporal stores: `stream` is ignored).
impl<T: PlaneElem> Sink for Planes<'_, T> {
    #[inline(always)]
    fn len(&self) -> usize {
        Planes::len(self)
    }
    #[inline(always)]
    fn put_rows<const N: usize>(
        &mut self,
        start: usize,
        len: usize,
        rows: &[Lanes<N>; 16],
        _staged: &mut [[f64; 16]; N],
        _stream: bool,
    ) -> bool {
        let mut overflow = false;
        for (plane, row) in self.planes.iter_mut().zip(rows) {
            let dst = &mut plane[start..start + len];
            // A whole block as a fixed-size loop (vector moves; no `memcpy` call per plane).
            if let Ok(whole) = <&mut [T; N]>::try_from(&mut *dst) {
                for (o, &x) in whole.iter_mut().zip(row) {
                    let (y, over) = T::narrow(x);
                    *o = y;
                    overflow |= over;
                }
            } else {
                for (o, &x) in dst.iter_mut().zip(row) {
                    let (y, over) = T::narrow(x);
                    *o = y;
                    overflow |= over;
                }
            }
        }
        overflow
    }
    #[inline(always)]
    fn put_one(&mut self, i: usize, v: &[f64; 16]) -> bool {
        let mut overflow = false;
        for (plane, &x) in self.planes.iter_mut().zip(v) {
            let (y, over) = T::narrow(x);
            plane[i] = y;
            overflow |= over;
        }
        overflow
    }
}

impl SinkF32 for Planes<'_, f32> {
    #[inline(always)]
    fn put_rows_f32<const N: usize>(
        &mut self,
        start: usize,
        len: usize,
        rows: &[[f32; N]; 16],
        _staged: &mut [[f32; 16]; N],
    ) {
        copy_rows(&mut self.planes, start, len, rows);
    }
}

/// 16 rows of lanes (entry-major) into row-major 4×4 results (element-major): with AVX
/// register shuffles in 4×4 tiles where the CPU has them.
#[inline(always)]
fn transpose<const N: usize>(rows: &[Lanes<N>; 16], out: &mut [[f64; 16]; N], stream: bool) {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx") {
        // SAFETY: the CPU has AVX; with streaming, `out` is 16-byte aligned.
        unsafe {
            if stream_to(out, stream) {
                transpose_avx::<N, true>(rows, out);
            } else {
                transpose_avx::<N, false>(rows, out);
            }
        }
        return;
    }
    transpose_tail(rows, out, 0);
}

/// Elements `from ..` of [`transpose`] (or [`transpose_f32`]), one entry at a time.
#[inline(always)]
fn transpose_tail<T: Copy, const N: usize>(
    rows: &[[T; N]; 16],
    out: &mut [[T; 16]; N],
    from: usize,
) {
    for j in from..N {
        for e in 0..16 {
            out[j][e] = rows[e][j];
        }
    }
}

/// [`transpose`] of single-precision rows: with SSE shuffles (part of x86-64) in 4×4 tiles.
/// Always plain stores: non-temporal ones (16 bytes at a time) made the float32 output
/// slower (docs/model.md §12).
#[inline(always)]
fn transpose_f32<const N: usize>(rows: &[[f32; N]; 16], out: &mut [[f32; 16]; N]) {
    #[cfg(not(target_arch = "x86_64"))]
    let from = 0;
    #[cfg(target_arch = "x86_64")]
    let from = {
        use std::arch::x86_64::{
            _mm_loadu_ps, _mm_movehl_ps, _mm_movelh_ps, _mm_storeu_ps, _mm_unpackhi_ps,
            _mm_unpacklo_ps,
        };
        let whole = N - N % 4;
        for j0 in (0..whole).step_by(4) {
            for e0 in (0..16).step_by(4) {
                // SAFETY: j0 + 4 ≤ N and e0 + 4 ≤ 16: every load and store is in bounds; SSE
                // is part of x86-64.
                unsafe {
                    let a = _mm_loadu_ps(rows[e0][j0..].as_ptr());
                    let b = _mm_loadu_ps(rows[e0 + 1][j0..].as_ptr());
                    let c = _mm_loadu_ps(rows[e0 + 2][j0..].as_ptr());
                    let d = _mm_loadu_ps(rows[e0 + 3][j0..].as_ptr());
                    let (t0, t1) = (_mm_unpacklo_ps(a, b), _mm_unpackhi_ps(a, b));
                    let (t2, t3) = (_mm_unpacklo_ps(c, d), _mm_unpackhi_ps(c, d));
                    _mm_storeu_ps(out[j0][e0..].as_mut_ptr(), _mm_movelh_ps(t0, t2));
                    _mm_storeu_ps(out[j0 + 1][e0..].as_mut_ptr(), _mm_movehl_ps(t2, t0));
                    _mm_storeu_ps(out[j0 + 2][e0..].as_mut_ptr(), _mm_movelh_ps(t1, t3));
                    _mm_storeu_ps(out[j0 + 3][e0..].as_mut_ptr(), _mm_movehl_ps(t3, t1));
                }
            }
        }
        whole
    };
    transpose_tail(rows, out, from);
}

/// [`transpose`] with AVX: each 4×4 tile of (entries × elements) from 128-bit loads, each
/// pair of rows `e, e + 2` loaded into the two halves of one register (`vinsertf128` from
/// memory), then one unpack per output row. No cross-lane permute: `vperm2f128` is 8 µops on
/// AMD's Zen 1 (and 1 on Intel), a 128-bit insert from memory about as cheap as a load on both.
///
/// With `STREAM`, by non-temporal stores (256-bit where `out` is 32-byte aligned, else its
/// 128-bit halves).
///
/// # Safety
/// The CPU must support AVX; with `STREAM`, `out` must be 16-byte aligned.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
#[inline]
unsafe fn transpose_avx<const N: usize, const STREAM: bool>(
    rows: &[Lanes<N>; 16],
    out: &mut [[f64; 16]; N],
) {
    use std::arch::x86_64::{
        _mm256_castpd128_pd256, _mm256_castpd256_pd128, _mm256_extractf128_pd,
        _mm256_insertf128_pd, _mm256_storeu_pd, _mm256_stream_pd, _mm256_unpackhi_pd,
        _mm256_unpacklo_pd, _mm_loadu_pd, _mm_stream_pd,
    };
    let whole = N - N % 2;
    // Every row of `out` is 128 bytes, so one test covers the block.
    let aligned32 = (out.as_ptr() as usize).is_multiple_of(32);
    for j0 in (0..whole).step_by(2) {
        for e0 in (0..16).step_by(4) {
            // SAFETY: j0 + 2 ≤ N and e0 + 4 ≤ 16: every load and store is in bounds.
            unsafe {
                // (No closures here: they would not inherit the target feature.)
                // a = [F(e0)[j0], F(e0)[j0+1], F(e0+2)[j0], F(e0+2)[j0+1]], b the same for
                // e0+1 and e0+3: unpacklo(a, b) is element j0's entries e0..e0+4, unpackhi
                // element j0+1's.
                let a = _mm256_insertf128_pd::<1>(
                    _mm256_castpd128_pd256(_mm_loadu_pd(rows[e0][j0..].as_ptr())),
                    _mm_loadu_pd(rows[e0 + 2][j0..].as_ptr()),
                );
                let b = _mm256_insertf128_pd::<1>(
                    _mm256_castpd128_pd256(_mm_loadu_pd(rows[e0 + 1][j0..].as_ptr())),
                    _mm_loadu_pd(rows[e0 + 3][j0..].as_ptr()),
                );
                let (lo, hi) = (_mm256_unpacklo_pd(a, b), _mm256_unpackhi_pd(a, b));
                let (p, q) = (out[j0][e0..].as_mut_ptr(), out[j0 + 1][e0..].as_mut_ptr());
                if STREAM && aligned32 {
                    _mm256_stream_pd(p, lo);
                    _mm256_stream_pd(q, hi);
                } else if STREAM {
                    // 16-byte aligned: the halves.
                    _mm_stream_pd(p, _mm256_castpd256_pd128(lo));
                    _mm_stream_pd(p.add(2), _mm256_extractf128_pd::<1>(lo));
                    _mm_stream_pd(q, _mm256_castpd256_pd128(hi));
                    _mm_stream_pd(q.add(2), _mm256_extractf128_pd::<1>(hi));
                } else {
                    _mm256_storeu_pd(out[j0][e0..].as_mut_ptr(), lo);
                    _mm256_storeu_pd(out[j0 + 1][e0..].as_mut_ptr(), hi);
                }
            }
        }
    }
    transpose_tail(rows, out, whole);
}

/// Orders non-temporal stores before what follows (they are weakly ordered).
#[inline(always)]
fn store_fence() {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: SSE is part of x86-64.
    unsafe {
        std::arch::x86_64::_mm_sfence()
    };
}

impl MuellerOut for Mueller {
    #[inline(always)]
    fn set(&mut self, v: &[f64; 16]) {
        *self = Mueller::from_row_major(v);
    }
}

// -------------------------------------------------------------------------------------------
// The jobs: blocks through the kernel, fallback elements through the one-geometry path; each
// compiled once per instruction set and run at the kernel's ([`dispatch`]).

/// A piece of work generic over the elementary-function backends: `M` in f64, `S` in f32 (for
/// the single-precision kernel), both for one instruction set.
trait Job {
    fn run<M: Math<F = f64>, S: Math<F = f32>>(&mut self);
}

/// Runs `job` with the code of `level` (the CPU supports it: a kernel is only built at a
/// supported level).
fn dispatch<J: Job>(level: SimdLevel, job: &mut J) {
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

struct MuellerJob<'k, 'a, 's, 'o, G, W, const N: usize> {
    kernel: &'k Kernel<'a>,
    src: &'s G,
    index: IndexSource<'k>,
    out: &'o mut W,
    /// A finite entry beyond the output format's range.
    overflow: bool,
}

impl<G: Blocks, W: Sink, const N: usize> Job for MuellerJob<'_, '_, '_, '_, G, W, N> {
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
struct MuellerF32Job<'k, 'a, 's, 'o, G, W, const N: usize> {
    kernel: &'k Kernel<'a>,
    src: &'s G,
    index: IndexSource<'k>,
    out: &'o mut W,
    /// A finite entry beyond f32's range.
    overflow: bool,
}

/// What the f64 blocks of [`MuellerF32Job`] work in.
struct Wide<const N: usize> {
    scratch: GeomScratch<N>,
    front: Front<N>,
    rows: [Lanes<N>; 16],
    /// Positions of the elements waiting for an f64 block, and how many.
    pending: [usize; N],
    len: usize,
}

/// Positions `pos` of a source, as a source.
struct Gathered<'a, S> {
    src: &'a S,
    pos: &'a [usize],
}

impl<S: Source> Source for Gathered<'_, S> {
    #[inline(always)]
    fn get(&self, i: usize) -> [f64; 4] {
        self.src.get(self.pos[i])
    }
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
fn refine_d<M: Math<F = f64>, G: F32Blocks, const N: usize>(
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
            self.src
                .geometry::<S1, N, true>(start, len, needs, &mut scratch);
            let geo = &scratch.geo;
            let idx = self.index.lanes_f32::<N>(start, len, k.ill32, &mut cache);
            block::front_q_d::<S1, N>(&k.params, geo, &idx, &mut front);
            let (d, tail, fb) = front.d_tail_mut();
            refine_d::<M, G, N>(&scratch, len, k.params.distribution, d, tail, fb);
            block::front_terms::<S1, N>(&k.params, geo, &mut front);
            block::mueller::<S1, N>(&mut front, geo, &mut rows);
            self.out.put_rows_f32(start, len, &rows, &mut staged);
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
        if wide.len > 0 {
            self.flush::<M>(&mut wide, &mut cache);
        }
    }
}

/// BRDF, DoLP and (with `AOLP`) AoLP; `aolp` is empty without `AOLP`.
struct BrdfDolpJob<'k, 'a, 's, 'o, G, const N: usize, const AOLP: bool> {
    kernel: &'k Kernel<'a>,
    src: &'s G,
    index: IndexSource<'k>,
    brdf: &'o mut [f64],
    dolp: &'o mut [f64],
    aolp: &'o mut [f64],
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
struct PrepareJob<'s, 'b> {
    src: &'s BatchSource<'b>,
    out: Prepared,
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

struct ElementaryJob<'a> {
    op: Elementary,
    x: &'a [f64],
    y: &'a [f64],
    out: &'a mut [f64],
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::math::FastUnfused;
    use crate::numeric::sample::SplitMix64;

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
