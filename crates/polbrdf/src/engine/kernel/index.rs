//! Where the refractive index of each element comes from: the material's own, one per element
//! ([`IndexColumns`]), or a spectral index at one wavelength per element (with its cache).

use crate::engine::block::{IndexLanes, Thresholds};
use crate::error::{Error, Result, MAX_INDEX};
use crate::model::Material;
use crate::optics::dispersion::SpectralIndex;
use crate::optics::fresnel::{index_squared, RefractiveIndex};

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

    pub(super) fn slice(&self, start: usize, len: usize) -> Self {
        Self {
            n: &self.n[start..start + len],
            k: &self.k[start..start + len],
        }
    }
}

/// Where the index of each element comes from.
#[derive(Debug, Clone, Copy)]
pub(super) enum IndexSource<'a> {
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
pub(super) struct SpectralCache {
    slots: Vec<(f64, f64, f64, bool)>,
    used: usize,
}

impl SpectralCache {
    const SLOTS: usize = 256;
    const KEYS: usize = Self::SLOTS / 2;

    pub(super) fn new() -> Self {
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
pub(super) fn index_ill(n2r: f64, n2i: f64) -> bool {
    index_ill_for::<f64>(n2r, n2i)
}

/// Whether an index is outside the accurate domain of the kernel in `T`: the Fresnel
/// amplitudes lose relative accuracy as `N² → 1` (`rs = (1 − N²)/(c + q)²`), with condition
/// `(1 + sqrt(|N²| + 1))²/|1 − N²|` — at [`Thresholds::INDEX_COND_MAX`] or more (100 in f64,
/// 20 in f32) such elements take the one-geometry path — and magnitudes of `N²` beyond
/// `10^±100` are left to it too.
#[inline(always)]
pub(super) fn index_ill_for<T: Thresholds>(n2r: f64, n2i: f64) -> bool {
    // Squares, not `hypot`: this runs per element for a per-element index (|N²| ≤ 2·10¹², so
    // nothing overflows).
    let n2_abs = (n2r * n2r + n2i * n2i).sqrt();
    let c = 1.0 + (n2_abs + 1.0).sqrt();
    let gap = ((1.0 - n2r) * (1.0 - n2r) + n2i * n2i).sqrt();
    !(c * c < T::INDEX_COND_MAX * gap && n2_abs < 1e100 && n2_abs > 1e-100)
}

impl IndexSource<'_> {
    /// The index of element `i`; `None` where a spectral index's data give no valid one.
    pub(super) fn get(&self, i: usize, material: &Material) -> Option<RefractiveIndex> {
        match self {
            IndexSource::Constant { .. } => Some(material.index()),
            IndexSource::PerElement(cols) => Some(cols.get(i)),
            IndexSource::Spectral { index, wavelengths } => index.at(wavelengths[i]).ok(),
        }
    }

    /// `N²` and the domain flag of elements `start .. start + len` (the rest of the block
    /// repeats element `start`).
    #[inline(always)]
    pub(super) fn lanes<const N: usize>(
        &self,
        start: usize,
        len: usize,
        cache: &mut SpectralCache,
    ) -> IndexLanes<N> {
        self.lanes_at(|j| start + if j < len { j } else { 0 }, cache)
    }

    /// `N²` and the domain flag of the elements at positions `pos(0) .. pos(N − 1)`.
    #[inline(always)]
    pub(super) fn lanes_at<const N: usize>(
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
    pub(super) fn lanes_f32<const N: usize>(
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
