//! The elementary functions every formula of the model is written with, in two backends.
//!
//! Each formula of the model (`docs/model.md` §§1–6) is written once, generic over [`Math`]:
//!
//! - [`Std`] — the standard library's `sin_cos`, `exp`, `atan2` and a separate multiply and add.
//!   The one-geometry path (`Material::evaluate`) uses it: every number it prints is the formula
//!   evaluated with the platform's correctly rounded (or nearly so) libm.
//! - [`FastFused`] / [`FastUnfused`] — branch-free polynomial versions (sine/cosine with
//!   Cody–Waite reduction and the fdlibm kernels, `exp` by its Taylor series after reduction by
//!   ln 2, `atan2` with fdlibm's reduction and polynomial), each within 2 ulp on the ranges the
//!   model uses (unit tests below), with a fused or a separate multiply-add. They are scalar
//!   code without branches, so the compiler vectorizes a loop that calls them across a block of
//!   elements: the batch engine (`crate::engine`) uses them, with the FMA instruction where the
//!   CPU has it.
//!
//! Square roots and divisions are hardware instructions in both.

#![allow(clippy::excessive_precision)]

use std::f64::consts::{FRAC_2_PI, FRAC_PI_2, LOG2_E};

/// The floating-point type the model's formulas compute in: f64 everywhere, f32 in the batch
/// engine's single-precision kernel (docs/model.md §12, "Precision"). Literals and f64
/// parameters enter a formula through [`Real::of`].
pub trait Real:
    Copy
    + PartialEq
    + PartialOrd
    + std::fmt::Debug
    + Default
    + Send
    + Sync
    + 'static
    + std::ops::Add<Output = Self>
    + std::ops::Sub<Output = Self>
    + std::ops::Mul<Output = Self>
    + std::ops::Div<Output = Self>
    + std::ops::Neg<Output = Self>
{
    /// 0.
    const ZERO: Self;
    /// 1.
    const ONE: Self;
    /// The machine epsilon (2⁻⁵² or 2⁻²³).
    const EPSILON: Self;
    /// The smallest positive normal number.
    const MIN_POSITIVE: Self;
    /// The smallest `c² + s²` of a Priest–Meier pair taken as regular
    /// ([`crate::geometry::angles::eta_pairs`]): the product of two such (in
    /// [`crate::geometry::angles::rotations`]) stays a normal number — 10⁻¹⁵⁰ in f64, 10⁻¹⁸
    /// in f32.
    const PAIR_MIN: Self;
    /// `x` rounded to this type (exact for f64).
    fn of(x: f64) -> Self;
    /// Widened to f64 (exact).
    fn to_f64(self) -> f64;
    /// The square root (the hardware instruction).
    fn sqrt(self) -> Self;
    /// `|x|`.
    fn abs(self) -> Self;
    /// The smaller of the two (the other one where one is NaN).
    fn min(self, other: Self) -> Self;
    /// The larger of the two (the other one where one is NaN).
    fn max(self, other: Self) -> Self;
    /// `|self|` with the sign of `sign`.
    fn copysign(self, sign: Self) -> Self;
    /// Whether the sign bit is set (−0 included).
    fn is_sign_negative(self) -> bool;
}

macro_rules! real {
    ($t:ty, $pair_min:expr) => {
        impl Real for $t {
            const ZERO: Self = 0.0;
            const ONE: Self = 1.0;
            const EPSILON: Self = <$t>::EPSILON;
            const MIN_POSITIVE: Self = <$t>::MIN_POSITIVE;
            const PAIR_MIN: Self = $pair_min;
            #[inline(always)]
            fn of(x: f64) -> Self {
                x as $t
            }
            #[inline(always)]
            fn to_f64(self) -> f64 {
                self as f64
            }
            #[inline(always)]
            fn sqrt(self) -> Self {
                <$t>::sqrt(self)
            }
            #[inline(always)]
            fn abs(self) -> Self {
                <$t>::abs(self)
            }
            #[inline(always)]
            fn min(self, other: Self) -> Self {
                <$t>::min(self, other)
            }
            #[inline(always)]
            fn max(self, other: Self) -> Self {
                <$t>::max(self, other)
            }
            #[inline(always)]
            fn copysign(self, sign: Self) -> Self {
                <$t>::copysign(self, sign)
            }
            #[inline(always)]
            fn is_sign_negative(self) -> bool {
                <$t>::is_sign_negative(self)
            }
        }
    };
}
real!(f64, 1e-150);
real!(f32, 1e-18);

/// The elementary operations of the model's formulas, in the floating-point type `F`.
pub trait Math {
    /// The type the formulas compute in.
    type F: Real;
    /// Largest `|x|` for which [`Math::sincos`] keeps full accuracy (∞ for [`Std`]).
    const SINCOS_MAX: f64;
    /// `a·b + c`: fused (one rounding) where the backend has the instruction, else two roundings.
    fn mla(a: Self::F, b: Self::F, c: Self::F) -> Self::F;
    /// `(sin x, cos x)` of an angle given in f64 (a single-precision backend reduces it by π/2
    /// in f64 first, so that `cos θ` keeps its relative accuracy as θ → π/2).
    fn sincos(x: f64) -> (Self::F, Self::F);
    /// The first step of [`Math::sincos`], `sincos(x) == sincos_reduced(reduce(x))` bit for
    /// bit: the reduction by π/2, `[r, r_lo, k]` with `x = k·π/2 + r + r_lo` (`r_lo` 0 in f64;
    /// [`Std`] does not reduce: `[x, 0, 0]`). It is what needs f64 in a single-precision
    /// backend, so the batch kernel runs the two steps in separate loops, each at its own vector
    /// width (one f64 operation in a loop of f32 ones halves the width of the whole loop).
    fn reduce(x: f64) -> [Self::F; 3];
    /// [`Math::reduce`] of an `|x| ≤ π/4`, where there is nothing to reduce (`k = 0`): the
    /// same result for less work.
    fn reduce_small(x: f64) -> [Self::F; 3];
    /// The second step of [`Math::sincos`], from [`Math::reduce`]'s result.
    fn sincos_reduced(r: [Self::F; 3]) -> (Self::F, Self::F);
    /// `exp x` for `x ≤ 0` (0 below the underflow limit).
    fn exp_neg(x: Self::F) -> Self::F;
    /// `atan2(y, x)` for `y ≥ 0`, `x ≥ 0` (0 when both are 0).
    fn atan2_pos(y: Self::F, x: Self::F) -> Self::F;
    /// `atan2(y, x)` for any signs, with the standard library's results at signed zeros.
    fn atan2(y: Self::F, x: Self::F) -> Self::F;
}

/// The standard library (libm): the backend of the one-geometry path.
#[derive(Debug, Clone, Copy)]
pub struct Std;

impl Math for Std {
    type F = f64;
    const SINCOS_MAX: f64 = f64::INFINITY;
    #[inline(always)]
    fn mla(a: f64, b: f64, c: f64) -> f64 {
        a * b + c
    }
    #[inline(always)]
    fn sincos(x: f64) -> (f64, f64) {
        x.sin_cos()
    }
    #[inline(always)]
    fn reduce(x: f64) -> [f64; 3] {
        [x, 0.0, 0.0]
    }
    #[inline(always)]
    fn reduce_small(x: f64) -> [f64; 3] {
        [x, 0.0, 0.0]
    }
    #[inline(always)]
    fn sincos_reduced(r: [f64; 3]) -> (f64, f64) {
        r[0].sin_cos()
    }
    #[inline(always)]
    fn exp_neg(x: f64) -> f64 {
        x.exp()
    }
    #[inline(always)]
    fn atan2_pos(y: f64, x: f64) -> f64 {
        y.atan2(x)
    }
    #[inline(always)]
    fn atan2(y: f64, x: f64) -> f64 {
        y.atan2(x)
    }
}

/// Polynomial functions with fused multiply-add (for CPUs with the FMA instruction).
#[derive(Debug, Clone, Copy)]
pub struct FastFused;

/// Polynomial functions with separate multiply and add (for CPUs without FMA, where
/// `f64::mul_add` would be a slow library call).
#[derive(Debug, Clone, Copy)]
pub struct FastUnfused;

/// The polynomial backend of the build target's baseline instruction set: fused on aarch64
/// (FMA is part of its baseline), separate on x86-64 (FMA needs run-time detection).
#[cfg(target_arch = "aarch64")]
pub type FastPortable = FastFused;
/// The polynomial backend of the build target's baseline instruction set: fused on aarch64
/// (FMA is part of its baseline), separate on x86-64 (FMA needs run-time detection).
#[cfg(not(target_arch = "aarch64"))]
pub type FastPortable = FastUnfused;

trait Mla {
    fn mla(a: f64, b: f64, c: f64) -> f64;
}

impl Mla for FastFused {
    #[inline(always)]
    fn mla(a: f64, b: f64, c: f64) -> f64 {
        a.mul_add(b, c)
    }
}

impl Mla for FastUnfused {
    #[inline(always)]
    fn mla(a: f64, b: f64, c: f64) -> f64 {
        a * b + c
    }
}

macro_rules! fast_math {
    ($t:ty) => {
        impl Math for $t {
            type F = f64;
            const SINCOS_MAX: f64 = SINCOS_ARG_MAX;
            #[inline(always)]
            fn mla(a: f64, b: f64, c: f64) -> f64 {
                <$t as Mla>::mla(a, b, c)
            }
            #[inline(always)]
            fn sincos(x: f64) -> (f64, f64) {
                sincos::<$t>(x)
            }
            #[inline(always)]
            fn reduce(x: f64) -> [f64; 3] {
                reduce::<$t>(x)
            }
            #[inline(always)]
            fn reduce_small(x: f64) -> [f64; 3] {
                [x, 0.0, 0.0]
            }
            #[inline(always)]
            fn sincos_reduced(r: [f64; 3]) -> (f64, f64) {
                sincos_reduced::<$t>(r)
            }
            #[inline(always)]
            fn exp_neg(x: f64) -> f64 {
                exp_neg::<$t>(x)
            }
            #[inline(always)]
            fn atan2_pos(y: f64, x: f64) -> f64 {
                atan2_q1::<$t>(y, x)
            }
            #[inline(always)]
            fn atan2(y: f64, x: f64) -> f64 {
                atan2::<$t>(y, x)
            }
        }
    };
}
fast_math!(FastFused);
fast_math!(FastUnfused);

// -------------------------------------------------------------------------------------------
// Branch-free transcendental functions (scalar code written to be vectorized across a block)

/// `1.5·2⁵²`: for `|x| < 2⁵¹`, `(x + MAGIC) − MAGIC` is `x` rounded to an integer, and the low
/// bits of `(x + MAGIC).to_bits()` hold that integer (two's complement).
const MAGIC: f64 = 6_755_399_441_055_744.0;

// π/2 in two 33-bit pieces and a tail (fdlibm's `__rem_pio2`): `k·PIO2_1`, `k·PIO2_2` are exact
// for `|k| < 2²⁰`; `PIO2_2T` = π/2 − PIO2_1 − PIO2_2 rounded.
const PIO2_1: f64 = 1.57079632673412561417e+00;
const PIO2_2: f64 = 6.07710050630396597660e-11;
const PIO2_2T: f64 = 2.02226624879595063154e-21;

// fdlibm's `__kernel_sin` / `__kernel_cos` minimax coefficients on [−π/4, π/4].
const S1: f64 = -1.66666666666666324348e-01;
const S2: f64 = 8.33333333332248946124e-03;
const S3: f64 = -1.98412698298579493134e-04;
const S4: f64 = 2.75573137070700676789e-06;
const S5: f64 = -2.50507602534068634195e-08;
const S6: f64 = 1.58969099521155010221e-10;
const C1: f64 = 4.16666666666666019037e-02;
const C2: f64 = -1.38888888888741095749e-03;
const C3: f64 = 2.48015872894767294178e-05;
const C4: f64 = -2.75573143513906633035e-07;
const C5: f64 = 2.08757232129817482790e-09;
const C6: f64 = -1.13596475577881948265e-11;

/// Largest `|x|` (rad) for which the polynomial backends' [`Math::sincos`] is used (its
/// reduction is exact well beyond, up to `|x| < 2²⁰·π/2`; the margin is deliberate).
const SINCOS_ARG_MAX: f64 = 65_536.0;

/// `sin(x)` and `cos(x)` for `|x| ≤ 2¹⁷` (Cody–Waite reduction by π/2, fdlibm kernels): within
/// about 1 ulp.
#[inline(always)]
fn sincos<M: Mla>(x: f64) -> (f64, f64) {
    sincos_reduced::<M>(reduce::<M>(x))
}

/// The reduction of [`sincos`]: `[r, 0, k]` with `x = k·π/2 + r`, `|r| ≤ π/4` (`k` an integer).
#[inline(always)]
fn reduce<M: Mla>(x: f64) -> [f64; 3] {
    let t = M::mla(x, FRAC_2_PI, MAGIC);
    let k = t - MAGIC;
    let r = x - k * PIO2_1; // exact
    let r = r - k * PIO2_2;
    [r - k * PIO2_2T, 0.0, k]
}

/// The polynomials and the quadrant of [`sincos`], from [`reduce`]'s `[r, _, k]`.
#[inline(always)]
fn sincos_reduced<M: Mla>([r, _, k]: [f64; 3]) -> (f64, f64) {
    // `k + MAGIC` holds k in its low bits (as in `reduce`, where it is the same sum).
    let q = (k + MAGIC).to_bits();
    let z = r * r;
    let z2 = z * z;
    // sin r = r + r³(S1 + z·P(z)), P(z) = S2 + … + S6 z⁴ by Estrin's scheme
    let ps = M::mla(M::mla(S6, z2, M::mla(S5, z, S4)), z2, M::mla(S3, z, S2));
    let s = M::mla(z * r, M::mla(z, ps, S1), r);
    // cos r = w + (((1 − w) − z/2) + z²·Q(z)), w = 1 − z/2, Q(z) = C1 + … + C6 z⁵ (Estrin)
    let pc = M::mla(
        M::mla(M::mla(C6, z, C5), z2, M::mla(C4, z, C3)),
        z2,
        M::mla(C2, z, C1),
    );
    let hz = 0.5 * z;
    let w = 1.0 - hz;
    let c = w + (((1.0 - w) - hz) + z2 * pc);
    // Quadrant k mod 4: swap on odd k, sign of sin from bit 1 of k, of cos from bit 1 of k + 1.
    let swap = q & 1 != 0;
    let (s1, c1) = if swap { (c, s) } else { (s, c) };
    let sin = f64::from_bits(s1.to_bits() ^ ((q & 2) << 62));
    let cos = f64::from_bits(c1.to_bits() ^ ((q.wrapping_add(1) & 2) << 62));
    (sin, cos)
}

const LN2_HI: f64 = 6.93147180369123816490e-01; // 32 trailing zero bits: k·LN2_HI exact
const LN2_LO: f64 = 1.90821492927058770002e-10;

/// `1/n!` for n = 0 … 13: the Taylor series of `exp` on `|r| ≤ ln2/2` (truncation below 0.05
/// ulp).
const INV_FACT: [f64; 14] = [
    1.0,
    1.0,
    0.5,
    1.66666666666666666667e-01,
    4.16666666666666666667e-02,
    8.33333333333333333333e-03,
    1.38888888888888888889e-03,
    1.98412698412698412698e-04,
    2.48015873015873015873e-05,
    2.75573192239858906526e-06,
    2.75573192239858906526e-07,
    2.50521083854417187751e-08,
    2.08767569878680989792e-09,
    1.60590438368216145994e-10,
];

/// `2^k` for an integer-valued `k` in [−1022, 1023].
#[inline(always)]
fn pow2i(k: f64) -> f64 {
    // The low 12 bits of (k + MAGIC + 1023) hold k + 1023.
    f64::from_bits((k + (MAGIC + 1023.0)).to_bits() << 52)
}

/// `exp(x)` for `x ≤ 0` (results down to the subnormal range, 0 below −745.2): within about
/// 1 ulp.
#[inline(always)]
fn exp_neg<M: Mla>(x: f64) -> f64 {
    let x = if x > -1400.0 { x } else { -1400.0 };
    let k = M::mla(x, LOG2_E, MAGIC) - MAGIC;
    let r = x - k * LN2_HI; // exact
    let r = r - k * LN2_LO;
    // Taylor polynomial of degree 13: 1 + r(1 + r(1/2 + r·q(r))), q of degree 10 by Estrin's
    // scheme (short dependency chains); the last three steps by Horner keep the rounding of
    // the leading terms at about half an ulp.
    let c = &INV_FACT;
    let r2 = r * r;
    let r4 = r2 * r2;
    let r8 = r4 * r4;
    let q03 = M::mla(M::mla(c[6], r, c[5]), r2, M::mla(c[4], r, c[3]));
    let q47 = M::mla(M::mla(c[10], r, c[9]), r2, M::mla(c[8], r, c[7]));
    let q810 = M::mla(c[13], r2, M::mla(c[12], r, c[11]));
    let q = M::mla(q810, r8, M::mla(q47, r4, q03));
    let p = M::mla(M::mla(M::mla(q, r, c[2]), r, c[1]), r, c[0]);
    // 2^k in two factors, so that a subnormal result is rounded once, correctly.
    let k1 = (k * 0.5 + MAGIC) - MAGIC;
    let k2 = k - k1;
    p * pow2i(k1) * pow2i(k2)
}

// fdlibm `s_atan.c`.
const ATAN_HI_HALF: f64 = 4.63647609000806093515e-01;
const ATAN_LO_HALF: f64 = 2.26987774529616870924e-17;
const ATAN_HI_ONE: f64 = std::f64::consts::FRAC_PI_4;
const ATAN_LO_ONE: f64 = 3.06161699786838301793e-17;
const PIO2_LO: f64 = 6.12323399573676603587e-17;
const AT: [f64; 11] = [
    3.33333333333329318027e-01,
    -1.99999999998764832476e-01,
    1.42857142725034663711e-01,
    -1.11111104054623557880e-01,
    9.09088713343650656196e-02,
    -7.69187620504482999495e-02,
    6.66107313738753120669e-02,
    -5.83357013379057348645e-02,
    4.97687799461593236017e-02,
    -3.65315727442169155270e-02,
    1.62858201153657823623e-02,
];

/// `atan2(y, x)` for `y ≥ 0`, `x ≥ 0` (0 when both are 0): within about 1 ulp.
///
/// With `t = min/max ∈ [0, 1]`, fdlibm's reduction `t' = (t − c)/(1 + c·t)` with
/// `c ∈ {0, ½, 1}` onto `|t'| ≤ 7/16` is computed from `y` and `x` directly (one division), then
/// `atan(c) + atan(t')`, and `π/2 − …` when `y > x`.
#[inline(always)]
fn atan2_q1<M: Mla>(y: f64, x: f64) -> f64 {
    let swap = y > x;
    let (num, den) = if swap { (x, y) } else { (y, x) };
    let den = if den > 0.0 { den } else { 1.0 };
    let small = 16.0 * num < 7.0 * den;
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
        ATAN_HI_HALF
    } else {
        ATAN_HI_ONE
    };
    let lo = if small {
        0.0
    } else if mid {
        ATAN_LO_HALF
    } else {
        ATAN_LO_ONE
    };
    // num − c·den is exact (Sterbenz) in each interval.
    let t = (num - c * den) / M::mla(c, num, den);
    let z = t * t;
    let w = z * z;
    // fdlibm's odd/even split, each part as low + w³·high (shorter dependency chains).
    let w3 = w * w * w;
    let s1 = z * M::mla(
        M::mla(M::mla(AT[10], w, AT[8]), w, AT[6]),
        w3,
        M::mla(M::mla(AT[4], w, AT[2]), w, AT[0]),
    );
    let s2 = w * M::mla(
        M::mla(AT[9], w, AT[7]),
        w3,
        M::mla(M::mla(AT[5], w, AT[3]), w, AT[1]),
    );
    let a = hi - ((t * (s1 + s2) - lo) - t);
    if swap {
        (FRAC_PI_2 - a) + PIO2_LO
    } else {
        a
    }
}

/// `atan2(y, x)` for any signs, with the standard library's results at signed zeros: within
/// about 1 ulp.
#[inline(always)]
fn atan2<M: Mla>(y: f64, x: f64) -> f64 {
    let a = atan2_q1::<M>(y.abs(), x.abs());
    let a = if x.is_sign_negative() {
        (std::f64::consts::PI - a) + 2.0 * PIO2_LO
    } else {
        a
    };
    a.copysign(y)
}

#[cfg(test)]
mod tests {
    //! Accuracy of the polynomial functions against the standard library.

    use super::*;

    fn ulps(got: f64, want: f64) -> f64 {
        if got == want {
            return 0.0;
        }
        let scale = want.abs().max(f64::MIN_POSITIVE);
        (got - want).abs() / (scale * f64::EPSILON)
    }

    fn grid(lo: f64, hi: f64, n: usize) -> impl Iterator<Item = f64> {
        (0..=n).map(move |i| lo + (hi - lo) * i as f64 / n as f64)
    }

    #[test]
    fn sincos_within_two_ulp() {
        for m in [false, true] {
            let mut worst: f64 = 0.0;
            for x in grid(-2.0e4, 2.0e4, 400_000).chain(grid(-7.0, 7.0, 100_000)) {
                let (s, c) = if m {
                    sincos::<FastFused>(x)
                } else {
                    sincos::<FastUnfused>(x)
                };
                // Absolute error relative to 1 (the values are used as such), plus relative
                // error away from the zeros.
                let (ws, wc) = x.sin_cos();
                worst = worst.max((s - ws).abs().max((c - wc).abs()) / f64::EPSILON);
                if ws.abs() > 1e-3 {
                    worst = worst.max(ulps(s, ws));
                }
                if wc.abs() > 1e-3 {
                    worst = worst.max(ulps(c, wc));
                }
            }
            assert!(worst < 2.0, "fused = {m}: {worst} ulp");
        }
        // Near the zeros: relative accuracy.
        for k in 1..2000 {
            let x = k as f64 * FRAC_PI_2;
            for x in [x, x.next_up(), x.next_down(), 1e-300, 1e-20, -3e-9] {
                let (s, c) = sincos::<FastFused>(x);
                assert!(ulps(s, x.sin()) < 2.0, "sin({x}) = {s} vs {}", x.sin());
                assert!(ulps(c, x.cos()) < 2.0, "cos({x}) = {c} vs {}", x.cos());
            }
        }
        assert_eq!(sincos::<FastFused>(0.0), (0.0, 1.0));
    }

    /// `sincos` in the batch kernel's two steps is `sincos` bit for bit, for every backend, and
    /// `reduce_small` is `reduce` where it applies (`|x| ≤ π/4`).
    #[test]
    fn reduce_then_sincos_reduced_is_sincos() {
        fn check<M: Math>() {
            let bits = |(s, c): (M::F, M::F)| (s.to_f64().to_bits(), c.to_f64().to_bits());
            let small = std::f64::consts::FRAC_PI_4;
            for x in grid(-M::SINCOS_MAX.min(1e4), M::SINCOS_MAX.min(1e4), 200_001)
                .chain(grid(-small, small, 20_001))
                .chain([
                    0.0,
                    -0.0,
                    small,
                    -small,
                    1e-30,
                    FRAC_PI_2,
                    FRAC_PI_2.next_down(),
                ])
            {
                assert_eq!(
                    bits(M::sincos_reduced(M::reduce(x))),
                    bits(M::sincos(x)),
                    "{x}"
                );
                if x.abs() <= small {
                    assert_eq!(
                        bits(M::sincos_reduced(M::reduce_small(x))),
                        bits(M::sincos(x)),
                        "small {x}"
                    );
                }
            }
        }
        check::<Std>();
        check::<FastFused>();
        check::<FastUnfused>();
        check::<crate::numeric::math32::Single<true>>();
        check::<crate::numeric::math32::Single<false>>();
    }

    #[test]
    fn exp_within_two_ulp() {
        for x in grid(-745.0, 0.0, 1_000_000).chain(grid(-1.0, 0.0, 100_000)) {
            for e in [exp_neg::<FastFused>(x), exp_neg::<FastUnfused>(x)] {
                let want = x.exp();
                if want >= f64::MIN_POSITIVE {
                    assert!(ulps(e, want) < 2.0, "exp({x}) = {e} vs {want}");
                } else {
                    // Subnormal: within one unit of the last place (4.9e-324).
                    assert!((e - want).abs() <= 5e-324, "exp({x}) = {e} vs {want}");
                }
            }
        }
        assert_eq!(exp_neg::<FastFused>(0.0), 1.0);
        assert_eq!(exp_neg::<FastFused>(-800.0), 0.0);
        assert_eq!(exp_neg::<FastFused>(f64::NEG_INFINITY), 0.0);
    }

    #[test]
    fn atan2_within_two_ulp() {
        for y in grid(0.0, 3.0, 700) {
            for x in grid(0.0, 3.0, 700).chain([1e-300, 1e-30]) {
                for a in [atan2_q1::<FastFused>(y, x), atan2_q1::<FastUnfused>(y, x)] {
                    let want = y.atan2(x);
                    assert!(ulps(a, want) < 2.0, "atan2({y}, {x}) = {a} vs {want}");
                }
            }
        }
        for y in grid(-3.0, 3.0, 300).chain([0.0, -0.0]) {
            for x in grid(-3.0, 3.0, 300).chain([0.0, -0.0]) {
                let (a, want) = (atan2::<FastFused>(y, x), y.atan2(x));
                assert!(
                    ulps(a, want) < 2.0 && a.to_bits() >> 63 == want.to_bits() >> 63,
                    "atan2({y}, {x}) = {a} vs {want}"
                );
            }
        }
        assert_eq!(atan2_q1::<FastFused>(0.0, 0.0), 0.0);
        assert_eq!(atan2_q1::<FastFused>(0.0, 1.0), 0.0);
        assert_eq!(atan2_q1::<FastFused>(1.0, 0.0), FRAC_PI_2);
    }
}
