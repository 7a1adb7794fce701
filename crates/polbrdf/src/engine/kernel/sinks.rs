//! Where a job's results go: row-major 4×4 results or planes, in f64 or f32, and the
//! transposes from a block's rows (with non-temporal stores where asked).

use crate::engine::block::Lanes;
use crate::engine::planes::Planes;
use crate::optics::mueller::Mueller;

/// Where one 4×4 result goes.
pub(super) trait MuellerOut: Sized {
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
                transpose_f32::<N, false>(&narrow, whole);
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
pub(super) fn stream_to<T>(dst: &[T], stream: bool) -> bool {
    stream && (dst.as_ptr() as usize).is_multiple_of(16)
}

/// Where a job's results go: the caller's row-major array ([`Rows`]) or its planes
/// ([`Planes`]), written a block ([`PutRows`]) or one element at a time at positions relative
/// to the job's start.
pub(super) trait Sink {
    /// The number of elements.
    fn len(&self) -> usize;

    /// Element `i` (row-major). Returns whether a finite value became infinite (only a
    /// narrower format can overflow).
    fn put_one(&mut self, i: usize, v: &[f64; 16]) -> bool;

    /// Every entry of every element set to NaN (a job stopped at invalid input: the output
    /// holds no partial result).
    fn poison(&mut self);
}

/// A [`Sink`] that takes a block's rows of lanes of `L`: f64 from the f64 kernel, f32 from the
/// f32 kernel.
pub(super) trait PutRows<L>: Sink {
    /// Elements `start .. start + len` from a block's 16 rows of lanes (entry-major), through
    /// `staged` where needed; `stream`: whole blocks of row-major outputs with non-temporal
    /// stores where the format and the destination allow ([`MuellerOut::write_rows`]). Returns
    /// as [`Sink::put_one`].
    fn put_rows<const N: usize>(
        &mut self,
        start: usize,
        len: usize,
        rows: &[[L; N]; 16],
        staged: &mut [[L; 16]; N],
        stream: bool,
    ) -> bool;
}

/// A [`Sink`] of single precision: it takes the f32 kernel's rows and the f64 kernel's (the
/// elements the f32 kernel hands on, and materials it does not take).
pub(super) trait SinkF32: PutRows<f64> + PutRows<f32> {}

impl<W: PutRows<f64> + PutRows<f32>> SinkF32 for W {}

/// A row-major output: one 4×4 result per element.
pub(super) struct Rows<'o, O>(pub(super) &'o mut [O]);

impl<O: MuellerOut> PutRows<f64> for Rows<'_, O> {
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
}

impl<O: MuellerOut> Sink for Rows<'_, O> {
    #[inline(always)]
    fn len(&self) -> usize {
        self.0.len()
    }
    #[inline(always)]
    fn put_one(&mut self, i: usize, v: &[f64; 16]) -> bool {
        O::write_block(&mut self.0[i..i + 1], std::slice::from_ref(v))
    }
    fn poison(&mut self) {
        for o in self.0.iter_mut() {
            o.set(&[f64::NAN; 16]);
        }
    }
}

impl PutRows<f32> for Rows<'_, [f32; 16]> {
    /// A whole block is transposed straight into the output (with `stream`, by non-temporal
    /// stores where it is 16-byte aligned), a partial one through `staged`. (f32 lanes do not
    /// overflow f32.)
    #[inline(always)]
    fn put_rows<const N: usize>(
        &mut self,
        start: usize,
        len: usize,
        rows: &[[f32; N]; 16],
        staged: &mut [[f32; 16]; N],
        stream: bool,
    ) -> bool {
        let dst = &mut self.0[start..start + len];
        match <&mut [[f32; 16]; N]>::try_from(&mut *dst) {
            Ok(whole) if stream_to(whole, stream) => transpose_f32::<N, true>(rows, whole),
            Ok(whole) => transpose_f32::<N, false>(rows, whole),
            Err(_) => {
                transpose_f32::<N, false>(rows, staged);
                dst.copy_from_slice(&staged[..len]);
            }
        }
        false
    }
}

/// An element type of planar output from lanes of `L`: f64 from f64, f32 from f32 as it is,
/// or f32 from f64 with each entry rounded to the nearest (`as f32`, as [`MuellerOut`] for
/// `[f32; 16]`).
pub(super) trait Narrow<L>: Copy {
    /// `x` in this type, and whether a finite `x` became infinite.
    fn narrow(x: L) -> (Self, bool);
}

impl Narrow<f64> for f64 {
    #[inline(always)]
    fn narrow(x: f64) -> (f64, bool) {
        (x, false)
    }
}

impl Narrow<f64> for f32 {
    #[inline(always)]
    fn narrow(x: f64) -> (f32, bool) {
        let y = x as f32;
        (y, y.is_infinite() & x.is_finite())
    }
}

impl Narrow<f32> for f32 {
    #[inline(always)]
    fn narrow(x: f32) -> (f32, bool) {
        (x, false)
    }
}

/// Planes take a block's rows as they are, from either kernel: 16 contiguous runs, no
/// transpose (and no non-temporal stores: `stream` is ignored).
impl<L: Copy, T: Narrow<f64> + Narrow<L>> PutRows<L> for Planes<'_, T> {
    #[inline(always)]
    fn put_rows<const N: usize>(
        &mut self,
        start: usize,
        len: usize,
        rows: &[[L; N]; 16],
        _staged: &mut [[L; 16]; N],
        _stream: bool,
    ) -> bool {
        let mut overflow = false;
        for (plane, row) in self.planes.iter_mut().zip(rows) {
            let dst = &mut plane[start..start + len];
            // A whole block as a fixed-size loop (vector moves; no `memcpy` call per plane).
            if let Ok(whole) = <&mut [T; N]>::try_from(&mut *dst) {
                for (o, &x) in whole.iter_mut().zip(row) {
                    let (y, over) = <T as Narrow<L>>::narrow(x);
                    *o = y;
                    overflow |= over;
                }
            } else {
                for (o, &x) in dst.iter_mut().zip(row) {
                    let (y, over) = <T as Narrow<L>>::narrow(x);
                    *o = y;
                    overflow |= over;
                }
            }
        }
        overflow
    }
}

impl<T: Narrow<f64>> Sink for Planes<'_, T> {
    #[inline(always)]
    fn len(&self) -> usize {
        Planes::len(self)
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
    fn poison(&mut self) {
        let (nan, _) = T::narrow(f64::NAN);
        for plane in self.planes.iter_mut() {
            plane.fill(nan);
        }
    }
}

/// 16 rows of lanes (entry-major) into row-major 4×4 results (element-major): with AVX
/// register shuffles in 4×4 tiles where the CPU has them.
#[inline(always)]
pub(super) fn transpose<const N: usize>(
    rows: &[Lanes<N>; 16],
    out: &mut [[f64; 16]; N],
    stream: bool,
) {
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
    #[cfg(not(target_arch = "x86_64"))]
    let _ = stream; // Streaming stores are x86's.
    transpose_tail(rows, out, 0);
}

/// Elements `from ..` of [`transpose`] (or [`transpose_f32`]), one entry at a time.
#[inline(always)]
pub(super) fn transpose_tail<T: Copy, const N: usize>(
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

/// [`transpose`] of single-precision rows: with SSE shuffles (part of x86-64) in 4×4 tiles;
/// with `STREAM` by non-temporal stores (16 bytes at a time; `out` must then be 16-byte
/// aligned), which pay on some CPUs and not on others ([`crate::engine::simd::f32_streams_pay`]).
#[inline(always)]
pub(super) fn transpose_f32<const N: usize, const STREAM: bool>(
    rows: &[[f32; N]; 16],
    out: &mut [[f32; 16]; N],
) {
    #[cfg(not(target_arch = "x86_64"))]
    let from = 0;
    #[cfg(target_arch = "x86_64")]
    let from = {
        use std::arch::x86_64::{
            __m128, _mm_loadu_ps, _mm_movehl_ps, _mm_movelh_ps, _mm_storeu_ps, _mm_stream_ps,
            _mm_unpackhi_ps, _mm_unpacklo_ps,
        };
        debug_assert!(!STREAM || (out.as_ptr() as usize).is_multiple_of(16));
        // SAFETY (of calls): `p` is valid for 16 bytes; with STREAM, 16-byte aligned (every
        // row of `out` is 64 bytes).
        #[inline(always)]
        unsafe fn put<const STREAM: bool>(p: *mut f32, v: __m128) {
            // SAFETY: as the caller promises.
            unsafe {
                if STREAM {
                    _mm_stream_ps(p, v);
                } else {
                    _mm_storeu_ps(p, v);
                }
            }
        }
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
                    put::<STREAM>(out[j0][e0..].as_mut_ptr(), _mm_movelh_ps(t0, t2));
                    put::<STREAM>(out[j0 + 1][e0..].as_mut_ptr(), _mm_movehl_ps(t2, t0));
                    put::<STREAM>(out[j0 + 2][e0..].as_mut_ptr(), _mm_movelh_ps(t1, t3));
                    put::<STREAM>(out[j0 + 3][e0..].as_mut_ptr(), _mm_movehl_ps(t3, t1));
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
pub(super) fn store_fence() {
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
