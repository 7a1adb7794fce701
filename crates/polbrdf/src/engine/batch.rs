//! The parallel driver of the engine: every grid of the crate and of the tools around it goes
//! through here ([`try_for_chunks`]). A batch is split into chunks of at most [`CHUNK`]
//! elements, each evaluated by a [`Kernel`] on a rayon worker; a batch of at most
//! [`SERIAL_MAX`] elements runs on the calling thread.

use crate::engine::kernel::{IndexColumns, Kernel, Prepared, BLOCK};
use crate::engine::planes::Planes;
use crate::error::Result;
use crate::geometry::batch::{check_len, Batch};
use crate::geometry::{AngleVariables, Geometry, GeometryBatch};
use crate::model::Material;
use crate::optics::mueller::Mueller;
use rayon::prelude::*;

/// Most elements per parallel task: large enough to amortize scheduling.
pub const CHUNK: usize = 4096;

/// Elements per parallel task for a batch of `n`: at most [`CHUNK`], and small enough that
/// every thread gets about four tasks (a batch of a few thousand — a fit's geometries — is
/// spread over all cores), in whole blocks. Results do not depend on it.
fn chunk_len(n: usize) -> usize {
    let threads = rayon::current_num_threads().max(1);
    let per = n.div_ceil(4 * threads).div_ceil(BLOCK) * BLOCK;
    per.clamp(8 * BLOCK, CHUNK)
}

/// Batches of at most this many elements run on the calling thread: below it, handing chunks to
/// rayon's workers costs more than it saves (measured on 2 threads: at 1024 elements the
/// parallel path ran at 30–51 M/s against the serial kernel's 50; at 4096 it won, 55–58 against
/// 50–53).
pub const SERIAL_MAX: usize = 2048;

/// Outputs (and inputs) that split into disjoint parts by element, for the parallel driver
/// [`try_for_chunks`]: slices, [`Planes`], and pairs of them (split together).
pub trait Split: Sized + Send {
    /// The number of elements.
    fn len(&self) -> usize;
    /// Whether there are none.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// Elements `.. mid` and `mid ..`.
    fn split_at(self, mid: usize) -> (Self, Self);
}

impl<T: Send> Split for &mut [T] {
    fn len(&self) -> usize {
        <[T]>::len(self)
    }
    fn split_at(self, mid: usize) -> (Self, Self) {
        self.split_at_mut(mid)
    }
}

impl<T: Sync> Split for &[T] {
    fn len(&self) -> usize {
        <[T]>::len(self)
    }
    fn split_at(self, mid: usize) -> (Self, Self) {
        <[T]>::split_at(self, mid)
    }
}

impl<T: Send> Split for Planes<'_, T> {
    fn len(&self) -> usize {
        Planes::len(self)
    }
    fn split_at(self, mid: usize) -> (Self, Self) {
        Planes::split_at(self, mid)
    }
}

/// Parts of equal length (the first part's length counts), split together.
impl<A: Split, B: Split> Split for (A, B) {
    fn len(&self) -> usize {
        self.0.len()
    }
    fn split_at(self, mid: usize) -> (Self, Self) {
        let (a0, a1) = self.0.split_at(mid);
        let (b0, b1) = self.1.split_at(mid);
        ((a0, b0), (a1, b1))
    }
}

/// The one parallel driver of the engine (and of the Python module): `f(start, part)` for
/// consecutive parts of `out` of at most [`CHUNK`] elements each (about four per thread), on
/// rayon's workers — or, for at most [`SERIAL_MAX`] elements, once for the whole on the
/// calling thread; never for an empty `out`. Returns whether some call returned `Ok(true)`
/// (an overflow of f32), or an error of one of them. Results do not depend on the split.
///
/// # Errors
/// An error returned by `f`.
pub fn try_for_chunks<O: Split, E: Send>(
    out: O,
    f: impl Fn(usize, O) -> std::result::Result<bool, E> + Sync,
) -> std::result::Result<bool, E> {
    let n = out.len();
    if out.is_empty() {
        return Ok(false);
    }
    if n <= SERIAL_MAX {
        return f(0, out);
    }
    let len = chunk_len(n);
    let mut parts = Vec::with_capacity(n.div_ceil(len));
    let (mut start, mut rest) = (0, out);
    while rest.len() > len {
        let (part, tail) = rest.split_at(len);
        parts.push((start, part));
        (start, rest) = (start + len, tail);
    }
    parts.push((start, rest));
    parts
        .into_par_iter()
        .map(|(start, part)| f(start, part))
        .try_reduce(|| false, |a, b| Ok(a | b))
}

/// [`try_for_chunks`] of an infallible `f`.
fn for_chunks<O: Split>(out: O, f: impl Fn(usize, O) -> bool + Sync) -> bool {
    match try_for_chunks(out, |start, part| {
        Ok::<_, std::convert::Infallible>(f(start, part))
    }) {
        Ok(b) => b,
        Err(never) => match never {},
    }
}

/// Full-Mueller f64 outputs of at least this many elements (8 MB) bypass the caches
/// ([`Engine::streaming`], [`Kernel::streaming`]).
pub const STREAM_MIN: usize = 1 << 16;

/// The floating-point format of the results (docs/model.md §12, "Precision"). [`Precision::F32`]
/// computes the model in f32 where the float32 contract allows (every entry within
/// `1e-5·F00 + 1e-6·P` of f64, `P` the F00 at the specular direction of the same θi) — half
/// the memory and the memory traffic of a full-Mueller batch, and faster. f64 stays the
/// default and the reference (fits use it).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Precision {
    /// Double precision (the default).
    #[default]
    F64,
    /// Single precision: f64 results rounded to f32 when stored.
    F32,
}

impl Precision {
    /// Every precision (the one list the Python module's `Literal` types spell).
    pub const ALL: [Precision; 2] = [Precision::F64, Precision::F32];

    /// `"float64"` or `"float32"` (NumPy's names).
    pub fn name(self) -> &'static str {
        match self {
            Precision::F64 => "float64",
            Precision::F32 => "float32",
        }
    }
}

impl std::str::FromStr for Precision {
    type Err = crate::Error;

    /// `float64`/`f64` or `float32`/`f32`.
    fn from_str(s: &str) -> Result<Self> {
        // Rust's names `f64`, `f32` are accepted besides NumPy's.
        let alias = match s {
            "f64" => Some(Precision::F64),
            "f32" => Some(Precision::F32),
            _ => None,
        };
        alias
            .or_else(|| crate::names::find(&Self::ALL, Precision::name, s))
            .ok_or_else(|| {
                crate::Error::InconsistentParameters(format!(
                    "unknown precision {s:?}: expected {}",
                    crate::names::quoted(&Self::ALL, Precision::name)
                ))
            })
    }
}

/// The refusal of a single-precision result beyond f32's range ([`Engine::mueller_f32_into`]).
pub fn f32_overflow() -> crate::Error {
    crate::Error::InconsistentParameters(format!(
        "a pBRDF entry exceeds the float32 range (|F| > {:e} sr⁻¹): use float64",
        f32::MAX
    ))
}

/// The engine for one material: evaluates batches in parallel, optionally with a complex index
/// per element ([`Engine::with_index`]).
///
/// ```
/// use polbrdf::engine::{Engine, IndexColumns};
/// use polbrdf::{GeometryBatch, MaterialSpec};
/// let m = MaterialSpec::new(1.5, 10.0).build()?;
/// let t = [0.5, 0.5, 0.5];
/// let (pi, pr) = ([0.0; 3], [std::f64::consts::PI; 3]);
/// let batch = GeometryBatch::new(&t, &pi, &t, &pr)?;
/// // The same geometry with three indices (say, three wavelengths), in one call:
/// let (n, k) = ([1.4, 1.5, 1.6], [0.0; 3]);
/// let mut brdf = [0.0; 3];
/// let mut dolp = [0.0; 3];
/// Engine::new(&m)
///     .with_index(IndexColumns::new(&n, &k)?)
///     .brdf_dolp_into(&batch, &mut brdf, &mut dolp)?;
/// assert!(brdf[0] < brdf[1] && brdf[1] < brdf[2]);
/// # Ok::<(), polbrdf::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct Engine<'a> {
    kernel: Kernel<'a>,
    /// The length of a per-element index or of the wavelengths, and its name for messages.
    index_len: Option<(usize, &'static str)>,
    /// Non-temporal stores for f64 outputs of at least [`STREAM_MIN`] elements.
    stream: bool,
}

impl<'a> Engine<'a> {
    /// The engine of `material` (its own index for every element).
    pub fn new(material: &'a Material) -> Self {
        Self {
            kernel: Kernel::new(material),
            index_len: None,
            stream: true,
        }
    }

    /// With `on` (the default), full-Mueller f64 row-major outputs of at least [`STREAM_MIN`]
    /// elements (8 MB) are written with non-temporal stores straight from the transpose
    /// ([`Kernel::streaming`]), which skip the read for ownership of the output's cache lines
    /// and leave the caches alone. On the machine measured (a Zen 4 class AVX-512 host, 2
    /// threads, 2·10⁶ geometries, medians of 11 alternating repeats) that ran 1.02–1.35×
    /// faster than plain stores (docs/model.md §12). Turn it off when the output is read back
    /// at once and fits the last-level cache. float32 row-major outputs do the same where
    /// non-temporal stores pay on this CPU ([`crate::engine::simd::f32_streams_pay`]: they
    /// made float32 slower on AMD's Zen 3 and Zen 4, faster on an Intel Xeon); planar outputs
    /// always use plain stores. The bits are the same either way.
    pub fn streaming(mut self, on: bool) -> Self {
        self.stream = on;
        self
    }

    /// Whether [`Engine::mueller_into`] writes an output of `n` elements with non-temporal
    /// stores ([`Engine::streaming`] and [`STREAM_MIN`]) — for drivers of their own around the
    /// serial kernel (the Python module).
    pub fn streams(&self, n: usize) -> bool {
        self.stream && n >= STREAM_MIN
    }

    /// Element `j` of every batch evaluated with index `index.get(j)` (the batch must be as
    /// long as `index`).
    pub fn with_index(self, index: IndexColumns<'a>) -> Self {
        Self {
            index_len: Some((index.len(), "n")),
            kernel: self.kernel.with_index(index),
            ..self
        }
    }

    /// Element `j` of every batch evaluated with the material's spectral index at
    /// `wavelengths_um[j]` (µm; the batch must be as long), looked up block by block inside the
    /// parallel kernel — how one call covers wavelengths × geometries (docs/model.md §15). A
    /// constant index does not depend on the wavelengths.
    ///
    /// # Errors
    /// [`crate::Error::WavelengthOutOfRange`] with the position of the first wavelength outside
    /// the data.
    pub fn with_wavelengths(self, wavelengths_um: &'a [f64]) -> Result<Self> {
        Ok(Self {
            index_len: Some((wavelengths_um.len(), "wavelength_um")),
            kernel: self.kernel.with_wavelengths(wavelengths_um)?,
            ..self
        })
    }

    /// The serial kernel.
    pub fn kernel(&self) -> &Kernel<'a> {
        &self.kernel
    }

    fn check(&self, n: usize) -> Result<()> {
        match self.index_len {
            Some((len, name)) => check_len(name, len, n),
            None => Ok(()),
        }
    }

    /// The full pBRDF `F` (row-major 4×4, sr⁻¹) at every geometry, written into `out`.
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] when `out` (or the per-element index) is not as long as
    /// the batch.
    pub fn mueller_into(&self, batch: &impl Batch, out: &mut [[f64; 16]]) -> Result<()> {
        check_len("out", out.len(), batch.len())?;
        self.check(batch.len())?;
        // Outputs far beyond the caches (≥ 8 MB) bypass them (`streaming`).
        let kernel = self.kernel.clone().streaming(self.streams(out.len()));
        for_chunks(out, |start, part| {
            kernel.mueller_into(batch, start, part);
            false
        });
        Ok(())
    }

    /// As [`Engine::mueller_into`] into 16 planes (planar, structure-of-arrays: [`Planes`],
    /// entry `e = 4·i + j` of element `k` at position `k` of plane `e` — the layout of
    /// Mitsuba's Mueller matrices and of a table stored entry by entry): the same bits, without
    /// the transpose into rows (docs/model.md §12, "Layouts"). [`Engine::streaming`] does not
    /// apply.
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] when the planes (or the per-element index) are not as
    /// long as the batch.
    pub fn mueller_planes_into(&self, batch: &impl Batch, out: &mut Planes<'_, f64>) -> Result<()> {
        check_len("out", out.len(), batch.len())?;
        self.check(batch.len())?;
        let kernel = &self.kernel;
        for_chunks(out.reborrow(), |start, mut part| {
            kernel.mueller_planes_into(batch, start, &mut part);
            false
        });
        Ok(())
    }

    /// As [`Engine::mueller_f32_into`] into planes (as [`Engine::mueller_planes_into`]).
    ///
    /// # Errors
    /// As [`Engine::mueller_f32_into`].
    pub fn mueller_planes_f32_into(
        &self,
        batch: &impl Batch,
        out: &mut Planes<'_, f32>,
    ) -> Result<()> {
        check_len("out", out.len(), batch.len())?;
        self.check(batch.len())?;
        let kernel = &self.kernel;
        let overflow = for_chunks(out.reborrow(), |start, mut part| {
            kernel.mueller_planes_f32_into(batch, start, &mut part)
        });
        if overflow {
            return Err(f32_overflow());
        }
        Ok(())
    }

    /// As [`Engine::mueller_into`] in single precision ([`Precision::F32`]): the model computed
    /// in f32, within the float32 contract (`1e-5·F00 + 1e-6·P` of f64,
    /// [`Kernel::mueller_f32_into`], docs/model.md §12).
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] as [`Engine::mueller_into`];
    /// [`crate::Error::InconsistentParameters`] when an entry is beyond f32's range
    /// (`|F| > 3.4·10³⁸` sr⁻¹, only for extremely narrow distributions; `out` then holds ±∞
    /// there).
    pub fn mueller_f32_into(&self, batch: &impl Batch, out: &mut [[f32; 16]]) -> Result<()> {
        check_len("out", out.len(), batch.len())?;
        self.check(batch.len())?;
        // Non-temporal stores for large outputs where they pay on this CPU
        // (`simd::f32_streams_pay`).
        let kernel = &self.kernel.clone().streaming(self.streams(out.len()));
        let overflow = for_chunks(out, |start, part| {
            kernel.mueller_f32_into(batch, start, part)
        });
        if overflow {
            return Err(f32_overflow());
        }
        Ok(())
    }

    /// The full pBRDF at every geometry as a new vector.
    ///
    /// # Errors
    /// As [`Engine::mueller_into`].
    pub fn mueller(&self, batch: &impl Batch) -> Result<Vec<[f64; 16]>> {
        let mut out = vec![[0.0; 16]; batch.len()];
        self.mueller_into(batch, &mut out)?;
        Ok(out)
    }

    /// The scalar BRDF `f` (sr⁻¹) and the DoLP for unpolarized input at every geometry (only
    /// the first column of F, without rotations).
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] when an output slice is not as long as the batch.
    pub fn brdf_dolp_into(
        &self,
        batch: &impl Batch,
        brdf: &mut [f64],
        dolp: &mut [f64],
    ) -> Result<()> {
        check_len("brdf", brdf.len(), batch.len())?;
        check_len("dolp", dolp.len(), batch.len())?;
        self.check(batch.len())?;
        let kernel = &self.kernel;
        for_chunks((brdf, dolp), |start, (fb, fd)| {
            kernel.brdf_dolp_into(batch, start, fb, fd);
            false
        });
        Ok(())
    }

    /// The scalar BRDF `f` (sr⁻¹), the DoLP and the AoLP (rad, in (−π/2, π/2], measured from
    /// the reflected beam's s axis toward its p axis; 0 without linear polarization) for
    /// unpolarized input at every geometry — `Stokes::dolp` and `Stokes::aolp` of
    /// `F·(1, 0, 0, 0)`.
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] when an output slice is not as long as the batch.
    pub fn brdf_dolp_aolp_into(
        &self,
        batch: &impl Batch,
        brdf: &mut [f64],
        dolp: &mut [f64],
        aolp: &mut [f64],
    ) -> Result<()> {
        check_len("brdf", brdf.len(), batch.len())?;
        check_len("dolp", dolp.len(), batch.len())?;
        check_len("aolp", aolp.len(), batch.len())?;
        self.check(batch.len())?;
        let kernel = &self.kernel;
        for_chunks(((brdf, dolp), aolp), |start, ((fb, fd), fa)| {
            kernel.brdf_dolp_aolp_into(batch, start, fb, fd, fa);
            false
        });
        Ok(())
    }

    /// The geometry stages of every element of `batch`, computed once (in parallel), for
    /// [`Engine::mueller_prepared_into`] and [`Engine::brdf_dolp_prepared_into`] of any engine
    /// at the same SIMD level — the same geometries for many materials or wavelengths, as a
    /// fit or a spectral sweep needs them. Results are exactly those of the unprepared methods.
    pub fn prepare(&self, batch: &GeometryBatch<'_>) -> Prepared {
        let n = batch.len();
        if n <= SERIAL_MAX {
            return self.kernel.prepare(batch);
        }
        let len = chunk_len(n);
        let parts: Vec<Prepared> = (0..n.div_ceil(len))
            .into_par_iter()
            .map(|c| {
                let start = c * len;
                self.kernel.prepare_range(batch, start, len.min(n - start))
            })
            .collect();
        let mut all = Prepared::empty(self.kernel.level());
        for p in parts {
            all.append(p);
        }
        all
    }

    /// As [`Engine::mueller_into`], for a prepared batch.
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] when `out` (or the per-element index) is not as long as
    /// the batch.
    ///
    /// # Panics
    /// When `prepared` was made at another SIMD level than this engine's.
    pub fn mueller_prepared_into(&self, prepared: &Prepared, out: &mut [[f64; 16]]) -> Result<()> {
        check_len("out", out.len(), prepared.len())?;
        self.check(prepared.len())?;
        let kernel = self.kernel.clone().streaming(self.streams(out.len()));
        for_chunks(out, |start, part| {
            kernel.mueller_prepared_into(prepared, start, part);
            false
        });
        Ok(())
    }

    /// As [`Engine::brdf_dolp_into`], for a prepared batch.
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] when an output (or the per-element index) is not as long
    /// as the batch.
    ///
    /// # Panics
    /// When `prepared` was made at another SIMD level than this engine's.
    pub fn brdf_dolp_prepared_into(
        &self,
        prepared: &Prepared,
        brdf: &mut [f64],
        dolp: &mut [f64],
    ) -> Result<()> {
        check_len("brdf", brdf.len(), prepared.len())?;
        check_len("dolp", dolp.len(), prepared.len())?;
        self.check(prepared.len())?;
        let kernel = &self.kernel;
        for_chunks((brdf, dolp), |start, (fb, fd)| {
            kernel.brdf_dolp_prepared_into(prepared, start, fb, fd);
            false
        });
        Ok(())
    }

    /// The pBRDF at every geometry of a slice of (already validated) geometries.
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] when a per-element index is not as long as the slice.
    pub fn pbrdf_of(&self, geometries: &[Geometry]) -> Result<Vec<Mueller>> {
        self.check(geometries.len())?;
        let mut out = vec![Mueller::zero(); geometries.len()];
        let kernel = &self.kernel;
        if self.index_len.is_some() {
            // Positions matter for the index: one serial pass (the index is per element).
            kernel.mueller_of(geometries, &mut out);
        } else {
            for_chunks((out.as_mut_slice(), geometries), |_, (o, g)| {
                kernel.mueller_of(g, o);
                false
            });
        }
        Ok(out)
    }

    /// The pBRDF (row-major) at explicit angle variables (the angle-variable entry point,
    /// [`Material::evaluate_angles`]).
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] when a per-element index is not as long as `vars`.
    pub fn mueller_of_angles(&self, vars: &[AngleVariables]) -> Result<Vec<[f64; 16]>> {
        self.check(vars.len())?;
        let mut out = vec![[0.0; 16]; vars.len()];
        let kernel = &self.kernel;
        if self.index_len.is_some() {
            kernel.mueller_of_angles(vars, &mut out);
        } else {
            for_chunks((out.as_mut_slice(), vars), |_, (o, v)| {
                kernel.mueller_of_angles(v, o);
                false
            });
        }
        Ok(out)
    }
}

/// The full pBRDF `F` (row-major 4×4, sr⁻¹) at every geometry, written into `out`
/// ([`Engine::mueller_into`] with the material's own index).
///
/// # Errors
/// [`crate::Error::LengthMismatch`] when `out` is not as long as the batch.
pub fn mueller_into(material: &Material, batch: &impl Batch, out: &mut [[f64; 16]]) -> Result<()> {
    Engine::new(material).mueller_into(batch, out)
}

/// The scalar BRDF `f` (sr⁻¹) and DoLP for unpolarized input at every geometry
/// ([`Engine::brdf_dolp_into`]).
///
/// # Errors
/// [`crate::Error::LengthMismatch`] when an output slice is not as long as the batch.
pub fn brdf_dolp_into(
    material: &Material,
    batch: &impl Batch,
    brdf: &mut [f64],
    dolp: &mut [f64],
) -> Result<()> {
    Engine::new(material).brdf_dolp_into(batch, brdf, dolp)
}

/// The scalar BRDF, DoLP and AoLP for unpolarized input at every geometry
/// ([`Engine::brdf_dolp_aolp_into`]).
///
/// # Errors
/// [`crate::Error::LengthMismatch`] when an output slice is not as long as the batch.
pub fn brdf_dolp_aolp_into(
    material: &Material,
    batch: &impl Batch,
    brdf: &mut [f64],
    dolp: &mut [f64],
    aolp: &mut [f64],
) -> Result<()> {
    Engine::new(material).brdf_dolp_aolp_into(batch, brdf, dolp, aolp)
}

/// The pBRDF at every geometry of a slice of already validated geometries, in parallel
/// ([`Engine::pbrdf_of`]).
pub fn pbrdf_of(material: &Material, geometries: &[Geometry]) -> Vec<Mueller> {
    Engine::new(material)
        .pbrdf_of(geometries)
        .expect("no per-element index")
}

/// The pBRDF at every geometry as a new vector ([`Engine::mueller`]).
///
/// # Errors
/// As [`mueller_into`].
pub fn mueller(material: &Material, batch: &impl Batch) -> Result<Vec<[f64; 16]>> {
    Engine::new(material).mueller(batch)
}
