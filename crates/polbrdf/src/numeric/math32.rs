//! Single-precision counterparts of the polynomial functions of [`super::math`], for the f32
//! batch kernel.
//!
//! The same style as the f64 versions: scalar code without branches (every `if` chooses between
//! two already-computed values and compiles to a blend), no table lookups and no libm calls, all
//! `#[inline(always)]`, so that a loop over `[f32; 32]` blocks calling them vectorizes to 8-lane
//! AVX2 code. Each function is generic over `FMA`: a fused multiply-add (one rounding) where the
//! CPU has the instruction, a separate multiply and add otherwise (see [`mla32`]).
//!
//! Accuracy is stated in f32 ulps of the true value (the spacing of f32 numbers at the
//! f64-computed reference) and checked by the unit tests below against `f64::sin`, `f64::cos`,
//! `f64::exp` and `f64::atan2`.

#![allow(clippy::excessive_precision)]

use super::math::Math;
use std::f64::consts::FRAC_2_PI;

/// The single-precision backend of the batch engine's f32 kernel (docs/model.md §12,
/// "Precision"): the functions of this module, with a fused multiply-add when `FMA` (for CPUs
/// with the instruction) or a separate multiply and add.
#[derive(Debug, Clone, Copy)]
pub struct Single<const FMA: bool>;

/// The single-precision backend of the build target's baseline instruction set (fused on
/// aarch64, separate on x86-64), as [`super::math::FastPortable`].
pub type SinglePortable = Single<{ cfg!(target_arch = "aarch64") }>;

impl<const FMA: bool> Math for Single<FMA> {
    type F = f32;
    const SINCOS_MAX: f64 = SINCOS32_ARG_MAX;
    #[inline(always)]
    fn mla(a: f32, b: f32, c: f32) -> f32 {
        mla32::<FMA>(a, b, c)
    }
    #[inline(always)]
    fn sincos(x: f64) -> (f32, f32) {
        sincos32::<FMA>(x)
    }
    #[inline(always)]
    fn reduce(x: f64) -> [f32; 3] {
        reduce32::<FMA>(x)
    }
    #[inline(always)]
    fn reduce_small(x: f64) -> [f32; 3] {
        let rf = x as f32;
        [rf, (x - rf as f64) as f32, 0.0]
    }
    #[inline(always)]
    fn sincos_reduced(r: [f32; 3]) -> (f32, f32) {
        sincos32_reduced::<FMA>(r)
    }
    #[inline(always)]
    fn exp_neg(x: f32) -> f32 {
        exp_neg32::<FMA>(x)
    }
    #[inline(always)]
    fn atan2_pos(y: f32, x: f32) -> f32 {
        atan2_pos32::<FMA>(y, x)
    }
    #[inline(always)]
    fn atan2(y: f32, x: f32) -> f32 {
        atan2_32::<FMA>(y, x)
    }
}

/// Largest `|x|` (rad) for which [`sincos32`] is used (as the f64 backends' bound).
const SINCOS32_ARG_MAX: f64 = 65_536.0;

/// `a·b + c` in f64 (the reduction): one rounding with `FMA`, two without.
#[inline(always)]
fn mla64<const FMA: bool>(a: f64, b: f64, c: f64) -> f64 {
    if FMA {
        a.mul_add(b, c)
    } else {
        a * b + c
    }
}

/// `a·b + c` in f32: one rounding with `FMA`, two without.
#[inline(always)]
pub(crate) fn mla32<const FMA: bool>(a: f32, b: f32, c: f32) -> f32 {
    if FMA {
        a.mul_add(b, c)
    } else {
        a * b + c
    }
}

// -------------------------------------------------------------------------------------------
// sin / cos

/// `1.5·2⁵²`: for `|x| < 2⁵¹`, `(x + MAGIC) − MAGIC` is `x` rounded to an integer, and the low
/// bits of `(x + MAGIC).to_bits()` hold that integer (two's complement).
const MAGIC: f64 = 6_755_399_441_055_744.0;

// π/2 in two 33-bit pieces and a tail (fdlibm's `__rem_pio2`, as in `math.rs`): `k·PIO2_1`,
// `k·PIO2_2` are exact for `|k| < 2²⁰`; `PIO2_2T` = π/2 − PIO2_1 − PIO2_2 rounded.
const PIO2_1: f64 = 1.57079632673412561417e+00;
const PIO2_2: f64 = 6.07710050630396597660e-11;
const PIO2_2T: f64 = 2.02226624879595063154e-21;

// Cephes `sinf.c`: minimax polynomials of sin and cos on [−π/4, π/4] (`sincof`, `coscof`).
const SF1: f32 = -1.666_665_461_1e-1;
const SF2: f32 = 8.332_160_873_6e-3;
const SF3: f32 = -1.951_529_589_1e-4;
const CF1: f32 = 4.166_664_568_298_827e-2;
const CF2: f32 = -1.388_731_625_493_765e-3;
const CF3: f32 = 2.443_315_711_809_948e-5;

/// `(sin x, cos x)` in f32 for an f64 argument, `|x| ≤ 65536` (rad): [`reduce32`], then
/// [`sincos32_reduced`].
///
/// The reduction is done in f64 (as [`super::math`]'s `sincos`): `k = round(x·2/π)` by the
/// `MAGIC` trick, `r = x − k·π/2` with π/2 in three parts (fdlibm's `__rem_pio2` constants;
/// the first two products are exact for `|k| < 2²⁰`), so `r` is accurate to a few f64 ulps and
/// a result near a zero (e.g. `cos` of 89.99°) keeps its *relative* accuracy. `r` is then split
/// into `r_f32 + r_lo` (`|r| ≤ π/4`), the Cephes `sinf.c` polynomials (degree 7 for sin, 8 for
/// cos, on [−π/4, π/4]) are evaluated in f32 at `r_f32`, and `r_lo` is added to first order
/// (`sin r ≈ s + r_lo`, `cos r ≈ c − r_f32·r_lo`). The quadrant (`k mod 4`) swaps and flips
/// signs from the low bits of `k`.
///
/// Accuracy (measured, see the tests): within 2 ulp of the true value for each of sin and cos
/// wherever `|true value| ≥ 1e-30` (worst about 1 ulp), and within 2⁻²⁴ absolutely everywhere.
/// `sincos32(0.0) == (0.0, 1.0)`.
#[inline(always)]
pub(crate) fn sincos32<const FMA: bool>(x: f64) -> (f32, f32) {
    sincos32_reduced::<FMA>(reduce32::<FMA>(x))
}

/// The f64 part of [`sincos32`]: `[r_f32, r_lo, k]` with `x = k·π/2 + r_f32 + r_lo` (`k` an
/// integer, exact in f32 for `|x| ≤ 65536`). With `FMA` each step is one fused operation (the
/// products `k·PIO2_1` and `k·PIO2_2` are exact, so only the tail's rounding differs).
#[inline(always)]
pub(crate) fn reduce32<const FMA: bool>(x: f64) -> [f32; 3] {
    let t = mla64::<FMA>(x, FRAC_2_PI, MAGIC);
    let k = t - MAGIC;
    let r = mla64::<FMA>(-k, PIO2_1, x); // exact
    let r = mla64::<FMA>(-k, PIO2_2, r);
    let r = mla64::<FMA>(-k, PIO2_2T, r);
    let rf = r as f32;
    [rf, (r - rf as f64) as f32, k as f32]
}

/// The f32 part of [`sincos32`], from [`reduce32`]'s `[r_f32, r_lo, k]`.
#[inline(always)]
pub(crate) fn sincos32_reduced<const FMA: bool>([rf, rlo, k]: [f32; 3]) -> (f32, f32) {
    // `k + MAGIC32` holds k in its low bits (offset binary with an offset divisible by 4).
    let q = (k + MAGIC32).to_bits();
    let z = rf * rf;
    // sin r = r + r·z·(SF1 + z·(SF2 + z·SF3))
    let ps = mla32::<FMA>(mla32::<FMA>(SF3, z, SF2), z, SF1);
    let s = rf + mla32::<FMA>(rf * z, ps, rlo);
    // cos r = w + (((1 − w) − z/2) + z²·(CF1 + z·(CF2 + z·CF3))), w = 1 − z/2 (the parenthesis
    // recovers the rounding of w, as fdlibm's `__kernel_cos`)
    let pc = mla32::<FMA>(mla32::<FMA>(CF3, z, CF2), z, CF1);
    let hz = 0.5 * z;
    let w = 1.0 - hz;
    let c = w + (mla32::<FMA>(z * z, pc, (1.0 - w) - hz) - rf * rlo);
    // Quadrant k mod 4: swap on odd k, sign of sin from bit 1 of k, of cos from bit 1 of k + 1.
    let swap = q & 1 != 0;
    let s1 = if swap { c } else { s };
    let c1 = if swap { s } else { c };
    let sin = f32::from_bits(s1.to_bits() ^ ((q & 2) << 30));
    let cos = f32::from_bits(c1.to_bits() ^ ((q.wrapping_add(1) & 2) << 30));
    (sin, cos)
}

// -------------------------------------------------------------------------------------------
// exp

/// `1.5·2²³`: for `|x| < 2²²`, `(x + MAGIC32) − MAGIC32` is `x` rounded to an integer, and the
/// low bits of `(x + MAGIC32).to_bits()` hold that integer (offset binary, `0x4B40_0000 + n`).
const MAGIC32: f32 = 12_582_912.0;
const LOG2_E32: f32 = std::f32::consts::LOG2_E;
// Cephes `expf.c`: ln 2 = LN2_HI32 + LN2_LO32, LN2_HI32 = 355/512 (9 bits: k·LN2_HI32 exact).
const LN2_HI32: f32 = 0.693_359_375;
const LN2_LO32: f32 = -2.121_944_40e-4;
// Cephes `expf.c`: exp r ≈ 1 + r + r²·P(r) on |r| ≤ ln2/2, P of degree 5.
const EP: [f32; 6] = [
    5.000_000_120_1e-1,
    1.666_666_545_9e-1,
    4.166_579_589_4e-2,
    8.333_451_907_3e-3,
    1.398_199_950_7e-3,
    1.987_569_150_0e-4,
];

/// `2^k` in f32 for an integer-valued `k` in [−126, 127], built from bits.
#[inline(always)]
fn pow2i32(k: f32) -> f32 {
    // The low 9 bits of (k + MAGIC32 + 127).to_bits() hold k + 127 (∈ [1, 254]).
    f32::from_bits((k + (MAGIC32 + 127.0)).to_bits() << 23)
}

/// `exp x` in f32 for `x ≤ 0`, also `exp(−∞) = 0` (NaN is not handled).
///
/// `x` is clamped at −150 (below the underflow limit, −103.97 for the smallest subnormal
/// rounding up). Reduction `x = k·ln2 + r`, `|r| ≤ ln2/2`, with ln 2 in two parts (Cephes
/// `expf.c`: `x − k·LN2_HI32` is exact), the Cephes `expf.c` minimax polynomial
/// `1 + r + r²·P(r)` (P of degree 5), then scaling by `2^k` as two factors `2^k1·2^k2`
/// (`k1 = round(k/2)`, each built from bits), so that a subnormal result is rounded once.
///
/// Accuracy (measured, see the tests): within 2 ulp (worst about 1 ulp) for results
/// `≥ f32::MIN_POSITIVE`; a subnormal or zero result within one subnormal unit (2⁻¹⁴⁹);
/// exactly 1 at 0, exactly 0 below about −104.
#[inline(always)]
pub(crate) fn exp_neg32<const FMA: bool>(x: f32) -> f32 {
    let x = if x > -150.0 { x } else { -150.0 };
    let k = mla32::<FMA>(x, LOG2_E32, MAGIC32) - MAGIC32;
    let r = mla32::<FMA>(k, -LN2_HI32, x); // exact
    let r = mla32::<FMA>(k, -LN2_LO32, r);
    let r2 = r * r;
    // P(r) = (EP0 + r·EP1) + r²·((EP2 + r·EP3) + r²·(EP4 + r·EP5)) (Estrin)
    let p01 = mla32::<FMA>(EP[1], r, EP[0]);
    let p23 = mla32::<FMA>(EP[3], r, EP[2]);
    let p45 = mla32::<FMA>(EP[5], r, EP[4]);
    let p = mla32::<FMA>(mla32::<FMA>(p45, r2, p23), r2, p01);
    let e = 1.0 + mla32::<FMA>(p, r2, r);
    let k1 = (k * 0.5 + MAGIC32) - MAGIC32;
    let k2 = k - k1;
    e * pow2i32(k1) * pow2i32(k2)
}

// -------------------------------------------------------------------------------------------
// atan2

// atan(½) and atan(1) = π/4 as f32 plus the f32-rounded remainder (computed from the f64
// values 0.46364760900080611621 and π/4).
const ATAN_HI_HALF32: f32 = 4.636_476_039_886_474_6e-1;
const ATAN_LO_HALF32: f32 = 5.012_158_6e-9;
const ATAN_HI_ONE32: f32 = 7.853_981_852_531_433_1e-1;
const ATAN_LO_ONE32: f32 = -2.185_569_5e-8;
// π/2 and π as f32 plus the remainder.
const PIO2_HI32: f32 = std::f32::consts::FRAC_PI_2;
const PIO2_LO32: f32 = -4.371_139e-8;
const PI_HI32: f32 = std::f32::consts::PI;
const PI_LO32: f32 = -8.742_278e-8;
/// tan(3π/8) = 1/tan(π/8): tan(π/8) is the end of the interval of the Cephes polynomial.
const TAN_3PI_8: f32 = 2.414_213_56;
// Cephes `atanf.c`: atan t ≈ t + t·z·Q(z), z = t², Q of degree 3, on |t| ≤ tan(π/8).
const AQ: [f32; 4] = [
    -3.333_294_915_39e-1,
    1.997_771_064_78e-1,
    -1.387_768_560_32e-1,
    8.053_744_495_38e-2,
];

/// `atan2(y, x)` in f32 for `y ≥ 0`, `x ≥ 0` (0 when both are 0, π/2 for (1, 0)).
///
/// With `t = min/max ∈ [0, 1]`, the reduction `t' = (t − c)/(1 + c·t)` with `c = 0` for
/// `t < tan(π/8)`, `c = ½` for `t < 11/16` and `c = 1` above (fdlibm's scheme, with Cephes'
/// first breakpoint) maps onto `|t'| ≤ tan(π/8)`; it is computed from the two arguments directly
/// (`(num − c·den)/(den + c·num)`: one division, and the numerator is exact by Sterbenz' lemma
/// in each interval). Then `atan(c) + atan(t')` with the Cephes `atanf.c` minimax polynomial
/// (degree 9 in `t'`) and `atan(c)` in two parts, and `π/2 − …` when `y > x`.
///
/// Accuracy (measured, see the tests): within 2 ulp (worst about 1 ulp).
#[inline(always)]
pub(crate) fn atan2_pos32<const FMA: bool>(y: f32, x: f32) -> f32 {
    let swap = y > x;
    let num = if swap { x } else { y };
    let den = if swap { y } else { x };
    let den = if den > 0.0 { den } else { 1.0 };
    let small = num * TAN_3PI_8 < den; // t < tan(π/8), without underflow for a subnormal den
    let mid = 16.0 * num < 11.0 * den;
    let c = if small {
        0.0
    } else if mid {
        0.5
    } else {
        1.0
    };
    let hi = if small {
        0.0
    } else if mid {
        ATAN_HI_HALF32
    } else {
        ATAN_HI_ONE32
    };
    let lo = if small {
        0.0
    } else if mid {
        ATAN_LO_HALF32
    } else {
        ATAN_LO_ONE32
    };
    let t = (num - c * den) / mla32::<FMA>(c, num, den);
    let z = t * t;
    let z2 = z * z;
    let q = mla32::<FMA>(
        mla32::<FMA>(AQ[3], z, AQ[2]),
        z2,
        mla32::<FMA>(AQ[1], z, AQ[0]),
    );
    let a = hi + mla32::<FMA>(t * z, q, lo + t);
    if swap {
        (PIO2_HI32 - a) + PIO2_LO32
    } else {
        a
    }
}

/// `atan2(y, x)` in f32 for any signs, with the standard library's results at signed zeros
/// (`atan2(±0, −0) = ±π`, `atan2(±0, +0) = ±0`, the sign of the result is that of `y`).
///
/// [`atan2_pos32`] of `(|y|, |x|)`, then `π − a` when `x` has its sign bit set, and the sign of
/// `y`. Accuracy (measured, see the tests): within 2 ulp.
#[inline(always)]
pub(crate) fn atan2_32<const FMA: bool>(y: f32, x: f32) -> f32 {
    let a = atan2_pos32::<FMA>(y.abs(), x.abs());
    let a = if x.is_sign_negative() {
        (PI_HI32 - a) + PI_LO32
    } else {
        a
    };
    a.copysign(y)
}

#[cfg(test)]
mod tests {
    //! Accuracy of the f32 functions against the f64 standard library.

    use super::*;
    use std::f64::consts::FRAC_PI_2;

    /// Fewer points in a debug build (CI), the dense grids in release.
    const DEBUG: bool = cfg!(debug_assertions);

    fn scaled(n: usize) -> usize {
        if DEBUG {
            n / 8
        } else {
            n
        }
    }

    /// The spacing of f32 numbers at `want` (2⁻¹⁴⁹ in the subnormal range).
    fn ulp32(want: f64) -> f64 {
        let w = (want as f32).abs();
        let e = (w.to_bits() >> 23) as i32;
        if e <= 1 {
            2f64.powi(-149)
        } else {
            2f64.powi(e - 127 - 23)
        }
    }

    /// `|got − want|` in f32 ulps of `want`.
    fn ulps(got: f32, want: f64) -> f64 {
        if got as f64 == want {
            return 0.0;
        }
        (got as f64 - want).abs() / ulp32(want)
    }

    fn grid(lo: f64, hi: f64, n: usize) -> impl Iterator<Item = f64> {
        (0..=n).map(move |i| lo + (hi - lo) * i as f64 / n as f64)
    }

    fn sc<const FMA: bool>(x: f64, worst: &mut (f64, f64)) {
        let (s, c) = sincos32::<FMA>(x);
        let (ws, wc) = x.sin_cos();
        let abs = (s as f64 - ws).abs().max((c as f64 - wc).abs());
        worst.1 = worst.1.max(abs);
        assert!(
            abs <= 2f64.powi(-24),
            "sincos({x}) = ({s}, {c}) vs ({ws}, {wc})"
        );
        for (g, w) in [(s, ws), (c, wc)] {
            if w.abs() >= 1e-30 {
                let u = ulps(g, w);
                worst.0 = worst.0.max(u);
                assert!(u <= 2.0, "sincos({x}): {g} vs {w}: {u} ulp (fused = {FMA})");
            }
        }
    }

    fn sincos_all<const FMA: bool>() -> (f64, f64) {
        let mut worst = (0.0, 0.0);
        let w = &mut worst;
        for x in grid(-65536.0, 65536.0, scaled(2_000_000)).chain(grid(-7.0, 7.0, scaled(500_000)))
        {
            sc::<FMA>(x, w);
        }
        // Near the multiples of π/2: relative accuracy at the zeros.
        for k in -2000..=2000 {
            let x = k as f64 * FRAC_PI_2;
            let mut y = x;
            let mut z = x;
            sc::<FMA>(x, w);
            for _ in 0..4 {
                y = y.next_up();
                z = z.next_down();
                sc::<FMA>(y, w);
                sc::<FMA>(z, w);
            }
        }
        // Near ±89.99° and across [89.9°, 90.1°].
        for d in [89.99f64, -89.99, 90.01, -90.01, 89.999_999, 270.0 - 0.01] {
            let x = d.to_radians();
            let (mut y, mut z) = (x, x);
            sc::<FMA>(x, w);
            for _ in 0..100 {
                y = y.next_up();
                z = z.next_down();
                sc::<FMA>(y, w);
                sc::<FMA>(z, w);
            }
        }
        for d in grid(89.9, 90.1, scaled(100_000)) {
            sc::<FMA>(d.to_radians(), w);
            sc::<FMA>(-d.to_radians(), w);
        }
        // Tiny arguments.
        for x in [1e-30, -1e-30, -3e-9, 3e-9, 1e-10, 1e-20, 1e-37, 0.0, -0.0] {
            sc::<FMA>(x, w);
        }
        assert_eq!(sincos32::<FMA>(0.0), (0.0, 1.0));
        assert_eq!(sincos32::<FMA>(1e-30), (1e-30, 1.0));
        assert_eq!(sincos32::<FMA>(-3e-9), (-3e-9, 1.0));
        worst
    }

    #[test]
    fn math32_sincos_within_two_ulp() {
        let f = sincos_all::<true>();
        let u = sincos_all::<false>();
        eprintln!(
            "sincos32: worst {:.3} ulp, {:.3e} abs (fused); {:.3} ulp, {:.3e} abs (unfused)",
            f.0, f.1, u.0, u.1
        );
    }

    fn exp_all<const FMA: bool>() -> f64 {
        let mut worst: f64 = 0.0;
        let check = |x: f32, worst: &mut f64| {
            let e = exp_neg32::<FMA>(x);
            let want = (x as f64).exp();
            if want >= f32::MIN_POSITIVE as f64 {
                let u = ulps(e, want);
                *worst = worst.max(u);
                assert!(
                    u <= 2.0,
                    "exp({x}) = {e} vs {want}: {u} ulp (fused = {FMA})"
                );
            } else {
                let d = (e as f64 - want).abs();
                assert!(
                    d <= 2f64.powi(-149),
                    "exp({x}) = {e:e} vs {want:e} (fused = {FMA})"
                );
            }
        };
        for x in grid(-104.0, 0.0, scaled(4_000_000)).chain(grid(-1.0, 0.0, scaled(1_000_000))) {
            check(x as f32, &mut worst);
        }
        // Every f32 in [−1, 0) in release; a stride in debug.
        let step = if DEBUG { 97 } else { 1 };
        let (b0, b1) = ((-0.0f32).to_bits(), (-1.0f32).to_bits());
        for b in (b0..=b1).step_by(step) {
            if f32::from_bits(b) < -1e-12 {
                check(f32::from_bits(b), &mut worst);
            }
        }
        assert_eq!(exp_neg32::<FMA>(0.0), 1.0);
        assert_eq!(exp_neg32::<FMA>(-0.0), 1.0);
        assert_eq!(exp_neg32::<FMA>(-200.0), 0.0);
        assert_eq!(exp_neg32::<FMA>(f32::NEG_INFINITY), 0.0);
        assert_eq!(exp_neg32::<FMA>(-1e-30), 1.0);
        worst
    }

    #[test]
    fn math32_exp_within_two_ulp() {
        let (f, u) = (exp_all::<true>(), exp_all::<false>());
        eprintln!("exp_neg32: worst {f:.3} ulp (fused), {u:.3} ulp (unfused)");
    }

    fn atan_all<const FMA: bool>() -> (f64, f64) {
        let mut worst: (f64, f64) = (0.0, 0.0);
        let n = if DEBUG { 600 } else { 3000 };
        let extra = [0.0f32, 1e-30, 1e-38, 1e-8, 1e-45];
        for y in grid(0.0, 3.0, n).map(|v| v as f32).chain(extra) {
            for x in grid(0.0, 3.0, n).map(|v| v as f32).chain(extra) {
                let a = atan2_pos32::<FMA>(y, x);
                let want = (y as f64).atan2(x as f64);
                let u = ulps(a, want);
                worst.0 = worst.0.max(u);
                assert!(
                    u <= 2.0,
                    "atan2({y}, {x}) = {a} vs {want}: {u} ulp (fused = {FMA})"
                );
            }
        }
        let n = if DEBUG { 300 } else { 1500 };
        for y in grid(-3.0, 3.0, n)
            .map(|v| v as f32)
            .chain([0.0, -0.0, 1e-30, -1e-30])
        {
            for x in grid(-3.0, 3.0, n)
                .map(|v| v as f32)
                .chain([0.0, -0.0, 1e-30, -1e-30])
            {
                let a = atan2_32::<FMA>(y, x);
                let want = (y as f64).atan2(x as f64);
                let u = ulps(a, want);
                worst.1 = worst.1.max(u);
                assert!(
                    u <= 2.0 && a.is_sign_negative() == want.is_sign_negative(),
                    "atan2({y}, {x}) = {a} vs {want}: {u} ulp (fused = {FMA})"
                );
            }
        }
        for (y, x) in [
            (0.0f32, 0.0f32),
            (-0.0, 0.0),
            (0.0, -0.0),
            (-0.0, -0.0),
            (0.0, 1.0),
        ] {
            let (a, want) = (atan2_32::<FMA>(y, x), y.atan2(x));
            assert_eq!(
                a.to_bits(),
                want.to_bits(),
                "atan2({y}, {x}) = {a} vs {want}"
            );
        }
        assert_eq!(atan2_32::<FMA>(-0.0, -1.0), -std::f32::consts::PI);
        assert_eq!(atan2_pos32::<FMA>(0.0, 0.0), 0.0);
        assert_eq!(atan2_pos32::<FMA>(0.0, 1.0), 0.0);
        assert_eq!(atan2_pos32::<FMA>(1.0, 0.0), std::f32::consts::FRAC_PI_2);
        assert_eq!(atan2_pos32::<FMA>(1.0, 1.0), std::f32::consts::FRAC_PI_4);
        worst
    }

    #[test]
    fn math32_atan2_within_two_ulp() {
        let (f, u) = (atan_all::<true>(), atan_all::<false>());
        eprintln!(
            "atan2_pos32 / atan2_32: worst {:.3} / {:.3} ulp (fused), {:.3} / {:.3} ulp (unfused)",
            f.0, f.1, u.0, u.1
        );
    }

    #[test]
    fn math32_constants() {
        let h = 0.463_647_609_000_806_116_2_f64;
        assert_eq!(ATAN_HI_HALF32, h as f32);
        assert_eq!(ATAN_LO_HALF32, (h - ATAN_HI_HALF32 as f64) as f32);
        let q = std::f64::consts::FRAC_PI_4;
        assert_eq!(ATAN_HI_ONE32, q as f32);
        assert_eq!(ATAN_LO_ONE32, (q - ATAN_HI_ONE32 as f64) as f32);
        assert_eq!(PIO2_LO32, (FRAC_PI_2 - PIO2_HI32 as f64) as f32);
        assert_eq!(PI_LO32, (std::f64::consts::PI - PI_HI32 as f64) as f32);
        assert!((LN2_HI32 as f64 + LN2_LO32 as f64 - std::f64::consts::LN_2).abs() < 1e-11);
    }
}
