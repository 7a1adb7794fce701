//! The fast batch kernel: the same model as [`Material::evaluate`], for blocks of geometries in
//! structure-of-arrays form, vectorized. `polbrdf::batch` runs it in parallel.
//!
//! [`Material::evaluate`] stays the reference: it is what `docs/model.md` traces equation by
//! equation. This module evaluates exactly those equations, rearranged for speed:
//!
//! - Per material, the constants are computed once ([`Kernel::new`]): `N²`, `a`, `b`, `1/Ω`,
//!   `2/τ`, the form, `ρ_D`, `ρ_V` and the shadowing/azimuth switches.
//! - Per block of [`BLOCK`] geometries, each stage runs over the whole block into small stack
//!   arrays (no heap allocation, no branches in the loops), so the compiler vectorizes every
//!   stage across the block; the stages are short, so the processor overlaps their iterations.
//! - Only four sine/cosine pairs are evaluated per geometry — of θi, θr, `u = (θi − θr)/2` and
//!   `Δ/2` with `Δ = φr − φi` — and everything else follows algebraically, as in
//!   [`crate::Geometry::angle_variables`]: `sin(θi − θr) = 2 sin u cos u`,
//!   `1 − cosΔ = 2 sin²(Δ/2)`, `sinΔ = 2 sin(Δ/2) cos(Δ/2)`; for the half vector
//!   `s = w_i + w_r`, `|s_xy|² = 4(cos²v sin²u + sinθi sinθr cos²(Δ/2))` with
//!   `cos v = cos((θi+θr)/2) = cos(θr + u)`, `s_z = cosθi + cosθr`, `θN = atan2(|s_xy|, s_z)`,
//!   `cosβ = |s|/2`, `sin²β = sin²u + sinθi sinθr sin²(Δ/2)` (all without cancellation) and
//!   `β = atan2(sinβ, cosβ)`.
//! - The Priest–Meier rotations enter only as `cos2η`, `sin2η`, taken from the same
//!   unnormalized closed-form pairs (c, s) as [`crate::Geometry::angle_variables`]:
//!   `(cos2η, sin2η) = (c² − s², 2cs)/(c² + s²)` — no `atan2` for η.
//! - The Mueller matrix of `T = Rot(η_r)·diag(rs, rp)·Rot(−η_i)` is written as
//!   `R(η_r)·M_d·R(−η_i)` with the Mueller rotators `R` and
//!   `M_d = [[A,B,0,0],[B,A,0,0],[0,0,C,S],[0,0,−S,C]]`, `A = (|rs|²+|rp|²)/2`,
//!   `B = (|rs|²−|rp|²)/2`, `C + iS = rs·rp*`; and `F = f_s·M/M00 + f_v·diag(1,0,0,0)` becomes
//!   `g·M + f_v·diag(1,0,0,0)` with `g = D·SO/(4 cosθi cosθr)` (standard form) or
//!   `g = D·SO·cos²θN/(4 cos²θi cos²θr)` (paper form, `cos²θN = s_z²/|s|²`), since
//!   `M00 = A = R_F`.
//! - The BRDF+DoLP path needs only `F00`, `F10`, `F20`; since `F10 = g·B·cos2η_r` and
//!   `F20 = g·B·sin2η_r`, `DoLP = |g·B|/F00` and no rotation is needed; the AoLP,
//!   `½·atan2(F20, F10)`, needs only η_r.
//! - The transcendental functions are branch-free polynomial versions below (sine/cosine with
//!   Cody–Waite reduction and the fdlibm kernels, `exp` by its Taylor series after reduction by
//!   `ln 2`, `atan2` with fdlibm's reduction and polynomial), each within 2 ulp on the ranges
//!   used (unit tests below); square roots and divisions are hardware instructions.
//! - The block code is one generic body compiled several times — AVX-512, AVX2+FMA and a
//!   portable version — and the best one the CPU supports is chosen at run time
//!   ([`simd_level`]), so a portable binary (and the Python wheel) uses AVX2/AVX-512 where
//!   present. No build flag is needed.
//!
//! **Accuracy.** Every entry agrees with [`Material::evaluate`] to within `1e-12·F00` (and the
//! BRDF and DoLP to `1e-12` relative/absolute); `tests/kernel.rs` checks it on the reference test
//! vectors and on random inputs across materials. Where the model itself is ill-conditioned —
//! so that the reference's own rounding decides the last digits (the Fresnel branch point
//! `N² = sin²β` of an index below 1, the far tail `bθN² > 600` of the facet distribution, a
//! result near the underflow limit, ΦN of the `eq3` azimuth factor close to specular, cos θN of
//! the paper form with both directions grazing) — and for azimuth differences beyond ±2¹⁷ rad or
//! an index within a few percent of 1, the kernel falls back, element by element, to
//! [`Material::evaluate`] itself, which gives exactly the reference's results there. For
//! ordinary materials and geometries no element takes that path.

#![allow(clippy::excessive_precision, clippy::needless_range_loop)]

use crate::batch::GeometryBatch;
use crate::geometry::Geometry;
use crate::model::{Form, Material};
use crate::mueller::{Mueller, Stokes};
use crate::shadowing::AzimuthTerm;
use std::f64::consts::{FRAC_2_PI, FRAC_PI_2, LOG2_E};
use std::sync::OnceLock;

/// Geometries per block: every stage of the kernel runs over this many elements at a time.
pub const BLOCK: usize = 32;

// -------------------------------------------------------------------------------------------
// Runtime CPU-feature dispatch

/// The instruction set a [`Kernel`] runs with.
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

/// The best level this CPU supports (detected once, then cached): what [`Kernel::new`] uses.
pub fn simd_level() -> SimdLevel {
    static LEVEL: OnceLock<SimdLevel> = OnceLock::new();
    *LEVEL.get_or_init(|| {
        *SimdLevel::supported()
            .last()
            .unwrap_or(&SimdLevel::Portable)
    })
}

// -------------------------------------------------------------------------------------------
// Multiply-add: fused where the instruction exists (same rounding as the FMA instruction),
// separate multiply and add where it does not (`f64::mul_add` would be a slow library call).

trait Mla {
    fn mla(a: f64, b: f64, c: f64) -> f64;
}

struct Fused;
struct Unfused;

impl Mla for Fused {
    #[inline(always)]
    fn mla(a: f64, b: f64, c: f64) -> f64 {
        a.mul_add(b, c)
    }
}

impl Mla for Unfused {
    #[inline(always)]
    fn mla(a: f64, b: f64, c: f64) -> f64 {
        a * b + c
    }
}

#[cfg(target_arch = "aarch64")]
type PortableMla = Fused;
#[cfg(not(target_arch = "aarch64"))]
type PortableMla = Unfused;

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

/// Largest `|Δ/2|` (rad) the kernel's argument reduction handles to full accuracy; beyond it an
/// element takes the reference path.
const HALF_DELTA_MAX: f64 = 65_536.0;

/// `sin(x)` and `cos(x)` for `|x| ≤ 2¹⁷` (Cody–Waite reduction by π/2, fdlibm kernels): within
/// about 1 ulp.
#[inline(always)]
fn sincos<M: Mla>(x: f64) -> (f64, f64) {
    let t = M::mla(x, FRAC_2_PI, MAGIC);
    let k = t - MAGIC;
    let q = t.to_bits();
    let r = x - k * PIO2_1; // exact
    let r = r - k * PIO2_2;
    let r = r - k * PIO2_2T;
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

// -------------------------------------------------------------------------------------------
// Per-material constants

/// Beyond `b·θN²` of this (`D` below `e⁻⁶⁰⁰` of its peak), `D = a·exp(−bθN²)` is so
/// sensitive to the last bit of θN (relative condition `2bθN²`) that the rounding of θN in the
/// reference itself shows at 1e-12: such elements take the reference path.
const D_EXPONENT_MAX: f64 = 600.0;
/// Below `cos²θN` of this (θN within 0.6° of 90°, both directions grazing), the reference's
/// `cos θN` of the paper form, taken from the rounded angle θN, has a relative error above
/// 1e-13: reference path.
const PAPER_COS2_MIN: f64 = 1e-4;
/// Below `|N² − sin²β|` of this, `q = sqrt(N² − sin²β)` is near its branch point (an index
/// below 1 near its critical angle) and amplifies rounding: reference path.
const BRANCH_POINT_MIN: f64 = 1e-4;
/// Results below this (but not zero) are near the subnormal range, where relative accuracy
/// ends: reference path.
const TINY: f64 = 1e-280;

#[derive(Debug, Clone, Copy)]
struct Params {
    n2r: f64,
    n2i: f64,
    a: f64,
    b: f64,
    shadow: bool,
    inv_omega: f64,
    two_over_tau: f64,
    eq3: bool,
    /// `|s_xy|/(sinθi + sinθr)` below which ΦN of the eq3 factor is ill-conditioned.
    phi_tol: f64,
    paper: bool,
    rho_d: f64,
    rho_v: f64,
}

/// The fast evaluator of one material (see the module documentation). Cheap to build.
///
/// Its methods evaluate serially; `polbrdf::batch` runs them in parallel over chunks.
#[derive(Debug, Clone)]
pub struct Kernel<'m> {
    material: &'m Material,
    p: Params,
    level: SimdLevel,
    /// The material is outside the kernel's accurate domain (an index within a few percent of
    /// 1, or extreme magnitudes): every element takes the reference path.
    scalar_only: bool,
    /// Write full-Mueller results with non-temporal stores (for large outputs).
    stream: bool,
}

impl<'m> Kernel<'m> {
    /// The kernel of `material` at the best SIMD level of this CPU ([`simd_level`]).
    pub fn new(material: &'m Material) -> Self {
        Self::build(material, simd_level())
    }

    /// The kernel at a given SIMD level, or `None` when this CPU does not support it (for
    /// tests and benchmarks comparing levels).
    pub fn with_level(material: &'m Material, level: SimdLevel) -> Option<Self> {
        level.is_supported().then(|| Self::build(material, level))
    }

    fn build(material: &'m Material, level: SimdLevel) -> Self {
        let (n, k) = (material.index().n(), material.index().k());
        // N² exactly as the reference forms it (complex multiplication).
        let (n2r, n2i) = (n * n - k * k, n * k + k * n);
        let d = material.distribution();
        let (shadow, inv_omega, two_over_tau, eq3) = match material.shadowing() {
            Some(s) => (
                true,
                1.0 / s.omega(),
                2.0 / s.tau(),
                s.azimuth_term() == AzimuthTerm::Eq3,
            ),
            None => (false, 0.0, 0.0, false),
        };
        let p = Params {
            n2r,
            n2i,
            a: d.a(),
            b: d.b(),
            shadow,
            inv_omega,
            two_over_tau,
            eq3,
            phi_tol: 2e-2 * inv_omega.max(1.0),
            paper: material.form() == Form::Paper,
            rho_d: material.rho_d(),
            rho_v: material.rho_v(),
        };
        // The Fresnel amplitudes lose relative accuracy as N² → 1 (rs = (1 − N²)/(c + q)²):
        // condition (1 + sqrt(|N²| + 1))² / |1 − N²|.
        let n2_abs = n2r.hypot(n2i);
        let kappa = (1.0 + (n2_abs + 1.0).sqrt()).powi(2) / (1.0 - n2r).hypot(n2i);
        let in_domain = kappa < 100.0
            && n2_abs < 1e100
            && n2_abs > 1e-100
            && p.a < 1e200
            && p.b < 1e200
            && p.inv_omega < 1e100
            && p.two_over_tau < 1e100
            && p.rho_v < 1e200
            && p.rho_d < 1e200;
        let scalar_only = !in_domain || (p.a > 0.0 && p.a < 1e-200);
        Self {
            material,
            p,
            level,
            scalar_only,
            stream: false,
        }
    }

    /// With `on`, [`Kernel::mueller_into`] writes its results with non-temporal stores where the
    /// CPU has them (x86-64): faster for outputs much larger than the caches, slower for
    /// outputs read back at once.
    pub fn streaming(mut self, on: bool) -> Self {
        self.stream = on;
        self
    }

    /// The SIMD level this kernel runs with.
    pub fn level(&self) -> SimdLevel {
        self.level
    }

    /// The pBRDF `F` (row-major, sr⁻¹) of elements `start .. start + out.len()` of `batch`.
    ///
    /// # Panics
    /// When the range exceeds the batch.
    pub fn mueller_into(&self, batch: &GeometryBatch<'_>, start: usize, out: &mut [[f64; 16]]) {
        let src = BatchSource::new(batch, start, out.len());
        self.run_mueller::<_, _, BLOCK>(&src, out);
    }

    /// The scalar BRDF (sr⁻¹) and the DoLP for unpolarized input of elements
    /// `start .. start + brdf.len()` of `batch`.
    ///
    /// # Panics
    /// When `brdf` and `dolp` differ in length or the range exceeds the batch.
    pub fn brdf_dolp_into(
        &self,
        batch: &GeometryBatch<'_>,
        start: usize,
        brdf: &mut [f64],
        dolp: &mut [f64],
    ) {
        assert_eq!(brdf.len(), dolp.len(), "brdf and dolp lengths");
        let src = BatchSource::new(batch, start, brdf.len());
        self.run_brdf_dolp::<_, BLOCK, false>(&src, brdf, dolp, &mut []);
    }

    /// As [`Kernel::brdf_dolp_into`], plus the AoLP (rad, in (−π/2, π/2], from the reflected
    /// beam's s axis toward its p axis; 0 without linear polarization) for unpolarized input:
    /// `Stokes::aolp` of `F·(1, 0, 0, 0)`.
    ///
    /// # Panics
    /// When the three outputs differ in length or the range exceeds the batch.
    pub fn brdf_dolp_aolp_into(
        &self,
        batch: &GeometryBatch<'_>,
        start: usize,
        brdf: &mut [f64],
        dolp: &mut [f64],
        aolp: &mut [f64],
    ) {
        assert_eq!(brdf.len(), dolp.len(), "brdf and dolp lengths");
        assert_eq!(brdf.len(), aolp.len(), "brdf and aolp lengths");
        let src = BatchSource::new(batch, start, brdf.len());
        self.run_brdf_dolp::<_, BLOCK, true>(&src, brdf, dolp, aolp);
    }

    /// The pBRDF at each geometry of a slice (already validated by construction).
    ///
    /// # Panics
    /// When `out` is not as long as `geometries`.
    pub fn mueller_of(&self, geometries: &[Geometry], out: &mut [Mueller]) {
        assert_eq!(geometries.len(), out.len(), "output length");
        self.run_mueller::<_, _, BLOCK>(&geometries, out);
    }

    /// The pBRDF `F` at one geometry: the kernel's code for a single element, for the lowest
    /// latency (the batch methods are faster per element).
    pub fn pbrdf(&self, g: &Geometry) -> Mueller {
        let mut out = [Mueller::zero()];
        self.run_mueller::<_, _, 1>(&std::slice::from_ref(g), &mut out);
        out[0]
    }

    /// The scalar BRDF (sr⁻¹) and the DoLP for unpolarized input at one geometry (single-element
    /// code, as [`Kernel::pbrdf`]).
    pub fn brdf_dolp(&self, g: &Geometry) -> (f64, f64) {
        let (mut b, mut d) = ([0.0], [0.0]);
        self.run_brdf_dolp::<_, 1, false>(&std::slice::from_ref(g), &mut b, &mut d, &mut []);
        (b[0], d[0])
    }

    fn run_mueller<S: Source, O: MuellerOut, const N: usize>(&self, src: &S, out: &mut [O]) {
        if self.scalar_only {
            for (i, o) in out.iter_mut().enumerate() {
                o.set(&self.reference(src.get(i)).pbrdf.to_row_major());
            }
            return;
        }
        match self.level_for(N) {
            #[cfg(target_arch = "x86_64")]
            // SAFETY: a kernel of this level is only built when the CPU supports it.
            SimdLevel::Avx512 => unsafe { x86::mueller_avx512::<S, O, N>(self, src, out) },
            #[cfg(target_arch = "x86_64")]
            // SAFETY: as above.
            SimdLevel::Avx2 => unsafe { x86::mueller_avx2::<S, O, N>(self, src, out) },
            _ => mueller_chunk::<PortableMla, S, O, N>(self, src, out),
        }
    }

    fn run_brdf_dolp<S: Source, const N: usize, const AOLP: bool>(
        &self,
        src: &S,
        brdf: &mut [f64],
        dolp: &mut [f64],
        aolp: &mut [f64],
    ) {
        if self.scalar_only {
            for i in 0..brdf.len() {
                let e = self.reference(src.get(i));
                (brdf[i], dolp[i]) = (e.brdf(), e.dolp());
                if AOLP {
                    aolp[i] = e.reflect(&Stokes::unpolarized()).aolp();
                }
            }
            return;
        }
        match self.level_for(N) {
            #[cfg(target_arch = "x86_64")]
            // SAFETY: a kernel of this level is only built when the CPU supports it.
            SimdLevel::Avx512 => unsafe {
                x86::brdf_dolp_avx512::<S, N, AOLP>(self, src, brdf, dolp, aolp)
            },
            #[cfg(target_arch = "x86_64")]
            // SAFETY: as above.
            SimdLevel::Avx2 => unsafe {
                x86::brdf_dolp_avx2::<S, N, AOLP>(self, src, brdf, dolp, aolp)
            },
            _ => brdf_dolp_chunk::<PortableMla, S, N, AOLP>(self, src, brdf, dolp, aolp),
        }
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

    /// The reference path for one element.
    fn reference(&self, [ti, pi, tr, pr]: [f64; 4]) -> crate::model::Evaluation {
        self.material
            .evaluate(&Geometry::new_unchecked(ti, pi, tr, pr))
    }
}

// -------------------------------------------------------------------------------------------
// Inputs and outputs

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

/// Where one 4×4 result goes.
trait MuellerOut: Sized {
    fn set(&mut self, v: &[f64; 16]);

    /// Copies a block of results out; `stream`: with non-temporal stores where possible (for
    /// outputs much larger than the caches, which are then not read back soon).
    #[inline(always)]
    fn write_block(dst: &mut [Self], src: &[[f64; 16]], _stream: bool) {
        for (o, v) in dst.iter_mut().zip(src) {
            o.set(v);
        }
    }
}

impl MuellerOut for [f64; 16] {
    #[inline(always)]
    fn set(&mut self, v: &[f64; 16]) {
        *self = *v;
    }

    #[inline(always)]
    fn write_block(dst: &mut [Self], src: &[[f64; 16]], stream: bool) {
        #[cfg(target_arch = "x86_64")]
        if stream && dst.as_ptr() as usize % 16 == 0 {
            use std::arch::x86_64::{_mm_loadu_pd, _mm_stream_pd};
            let n = dst.len().min(src.len());
            let (d, s) = (dst.as_mut_ptr().cast::<f64>(), src.as_ptr().cast::<f64>());
            for i in (0..16 * n).step_by(2) {
                // SAFETY: `d` and `s` are valid for 16·n f64 each, `d` is 16-byte aligned (so is
                // every even offset from it), and SSE2 is part of x86-64.
                unsafe { _mm_stream_pd(d.add(i), _mm_loadu_pd(s.add(i))) };
            }
            return;
        }
        let n = dst.len().min(src.len());
        dst[..n].copy_from_slice(&src[..n]);
    }
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
        for (r, row) in self.0.iter_mut().enumerate() {
            row.copy_from_slice(&v[4 * r..4 * r + 4]);
        }
    }
}

// -------------------------------------------------------------------------------------------
// The block kernel

type Lanes<const N: usize> = [f64; N];

/// One block of inputs.
struct BlockIn<const N: usize> {
    ti: Lanes<N>,
    pi: Lanes<N>,
    tr: Lanes<N>,
    pr: Lanes<N>,
}

impl<const N: usize> BlockIn<N> {
    /// Elements `start .. start + len` (len ≤ N) of `src`; the rest of the block repeats
    /// element `start` (valid input, results discarded).
    #[inline(always)]
    fn load<S: Source>(src: &S, start: usize, len: usize) -> Self {
        let mut b = BlockIn {
            ti: [0.0; N],
            pi: [0.0; N],
            tr: [0.0; N],
            pr: [0.0; N],
        };
        if len == N {
            src.load_block(start, &mut b);
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
        b
    }
}

/// The shared front of both paths, per element of a block: the validity and fallback masks,
/// the scalar factor `g` (`F = g·M + f_v·diag(1, 0, 0, 0)`), the volume term, what the Fresnel
/// amplitudes need (`cosβ` and `q = sqrt(N² − sin²β)`) and the sines and cosines the rotation
/// angles need.
struct Front<const N: usize> {
    /// Both directions above the horizon.
    valid: [bool; N],
    /// The element must take the reference path.
    fallback: [bool; N],
    g: Lanes<N>,
    fv: Lanes<N>,
    cosb: Lanes<N>,
    qr: Lanes<N>,
    qi: Lanes<N>,
    /// Sines and cosines of θi, θr, Δ/2 and u = (θi − θr)/2 (indices `TI`, `TR`, `H`, `U`).
    sin: [Lanes<N>; 4],
    cos: [Lanes<N>; 4],
}

const TI: usize = 0;
const TR: usize = 1;
const H: usize = 2;
const U: usize = 3;

/// Every stage is a loop over the block with a short body, so that the out-of-order core
/// overlaps several iterations (the polynomial chains are long in latency, short in work).
#[inline(always)]
fn front<M: Mla, const N: usize>(p: &Params, b: &BlockIn<N>) -> Front<N> {
    let z = [0.0; N];
    let mut f = Front {
        valid: [false; N],
        fallback: [false; N],
        g: z,
        fv: z,
        cosb: z,
        qr: z,
        qi: z,
        sin: [z; 4],
        cos: [z; 4],
    };
    // Stage 1: the four sine/cosine pairs, of θi, θr, Δ/2 and u = (θi − θr)/2 — one loop over
    // all of them (so that even a single element fills a vector).
    let mut angle = [z; 4];
    for j in 0..N {
        let h = 0.5 * (b.pr[j] - b.pi[j]);
        let in_range = h.abs() <= HALF_DELTA_MAX;
        f.fallback[j] = !in_range;
        f.valid[j] = b.ti[j] < FRAC_PI_2 && b.tr[j] < FRAC_PI_2;
        angle[TI][j] = b.ti[j];
        angle[TR][j] = b.tr[j];
        angle[H][j] = if in_range { h } else { 0.0 };
        angle[U][j] = 0.5 * (b.ti[j] - b.tr[j]);
    }
    for ((x, s), c) in angle
        .as_flattened()
        .iter()
        .zip(f.sin.as_flattened_mut())
        .zip(f.cos.as_flattened_mut())
    {
        (*s, *c) = sincos::<M>(*x);
    }
    // Stage 2: the half vector s = w_i + w_r in the frame of the plane of incidence,
    // |s| = 2cosβ, sin²β.
    let (mut along, mut across, mut sz, mut rho, mut s2, mut sinb2) = (z, z, z, z, z, z);
    for j in 0..N {
        let (si, sr, cr) = (f.sin[TI][j], f.sin[TR][j], f.cos[TR][j]);
        let (sh, ch, su, cu) = (f.sin[H][j], f.cos[H][j], f.sin[U][j], f.cos[U][j]);
        // |s_xy|² = (sinθi − sinθr)² + 4 sinθi sinθr cos²(Δ/2), sinθi − sinθr = 2 cos v sin u
        // with cos v = cos((θi+θr)/2) = cos(θr + u) (spec §1; see `Geometry::angle_variables`);
        // for ΦN, s∥ = sinθi + sinθr cosΔ = 2 cos v sin u + 2 sinθr cos²(Δ/2), s⊥ = sinθr sinΔ.
        let cosv = M::mla(cr, cu, -(sr * su));
        let dif = cosv * su;
        let ch2 = ch * ch;
        along[j] = 2.0 * M::mla(sr, ch2, dif);
        across[j] = 2.0 * sr * (sh * ch);
        sz[j] = f.cos[TI][j] + cr;
        let rho2 = 4.0 * M::mla(dif, dif, si * sr * ch2);
        rho[j] = rho2.sqrt();
        s2[j] = M::mla(sz[j], sz[j], rho2);
        f.cosb[j] = 0.5 * s2[j].sqrt();
        sinb2[j] = M::mla(su, su, si * sr * (sh * sh));
    }
    // Stage 3: the angles θN and β (one loop over both), and ΦN.
    let mut num = [rho, z];
    let mut den = [sz, f.cosb];
    for j in 0..N {
        num[1][j] = sinb2[j].sqrt();
    }
    let mut angle = [z; 2];
    for ((a, y), x) in angle
        .as_flattened_mut()
        .iter_mut()
        .zip(num.as_flattened())
        .zip(den.as_flattened_mut())
    {
        *a = atan2_q1::<M>(*y, *x);
    }
    let [theta_n, beta] = angle;
    let mut phi_n = z;
    if p.eq3 {
        for j in 0..N {
            phi_n[j] = atan2_q1::<M>(across[j].abs(), along[j].abs());
            // ΦN is ill-conditioned close to specular (and set to 0 below the rounding level).
            let phi_scale = b.pi[j].abs().max(b.pr[j].abs()).max(1.0);
            let tol = p.phi_tol.max(64.0 * f64::EPSILON * phi_scale);
            f.fallback[j] |= rho[j] < (f.sin[TI][j] + f.sin[TR][j]) * tol;
        }
    }
    // Stage 4: q = sqrt(N² − sin²β) on the principal branch (Im q ≥ 0 since Im N² ≥ 0).
    // Near the branch point N² = sin²β, q amplifies rounding: reference path.
    if p.n2i == 0.0 {
        // Real N² (k = 0): q = sqrt(|z|) or i·sqrt(|z|) — the same values as the general
        // formula below gives for Im z = 0, with one square root and no division.
        for j in 0..N {
            let zr = p.n2r - sinb2[j];
            let t = zr.abs().sqrt();
            let nonneg = zr >= 0.0;
            f.qr[j] = if nonneg { t } else { 0.0 };
            f.qi[j] = if nonneg { 0.0 } else { t };
            f.fallback[j] |= zr.abs() < BRANCH_POINT_MIN;
        }
    } else {
        for j in 0..N {
            let zr = p.n2r - sinb2[j];
            let zi = p.n2i;
            let zabs = M::mla(zr, zr, zi * zi).sqrt();
            let t = (0.5 * (zabs + zr.abs())).sqrt();
            let other = zi / (2.0 * if t > 0.0 { t } else { 1.0 });
            let nonneg = zr >= 0.0;
            f.qr[j] = if nonneg { t } else { other };
            f.qi[j] = if nonneg { other } else { t };
            f.fallback[j] |= zabs < BRANCH_POINT_MIN;
        }
    }
    // Stage 5: the exponentials of D (eq. 4) and SO (eq. 3), one loop over both.
    let mut y = [z; 2];
    for j in 0..N {
        y[0][j] = -(p.b * theta_n[j] * theta_n[j]);
        y[1][j] = -(beta[j] * p.two_over_tau);
    }
    let mut ex = [z; 2];
    for (e, y) in ex.as_flattened_mut().iter_mut().zip(y.as_flattened()) {
        *e = exp_neg::<M>(*y);
    }
    let (mut d, e) = (z, ex[1]);
    for j in 0..N {
        d[j] = p.a * ex[0][j];
        // D so far down its tail that θN's last bit shows, or near the underflow limit.
        let y = y[0][j];
        f.fallback[j] |= p.a > 0.0 && y > -750.0 && (d[j] < TINY || -y > D_EXPONENT_MAX);
    }
    // Stage 6: SO, g and f_v, with one division:
    // g = D·(1 + x·e)/((1 + x)·A_φ·4cosθi cosθr) (standard) or
    //     D·(1 + x·e)·s_z²/((1 + x)·A_φ·4cos²θi cos²θr·|s|²) (paper, cos²θN = s_z²/|s|²),
    // f_v = ρ_D + 2ρ_V/s_z; x = θN/Ω, A_φ = 1 + ΦN·θi/Ω (eq3) or 1.
    for j in 0..N {
        let x = theta_n[j] * p.inv_omega;
        let (so_num, so_den) = if p.shadow {
            let a_phi = if p.eq3 {
                M::mla(phi_n[j] * b.ti[j], p.inv_omega, 1.0)
            } else {
                1.0
            };
            (M::mla(x, e[j], 1.0), (1.0 + x) * a_phi)
        } else {
            (1.0, 1.0)
        };
        let (ci, cr) = (f.cos[TI][j], f.cos[TR][j]);
        let four_cc = 4.0 * ci * cr;
        let (num, den) = if p.paper {
            (
                d[j] * so_num * (sz[j] * sz[j]),
                so_den * (four_cc * ci * cr) * s2[j],
            )
        } else {
            (d[j] * so_num, so_den * four_cc)
        };
        let r = 1.0 / (den * sz[j]);
        f.g[j] = num * sz[j] * r;
        f.fv[j] = M::mla(2.0 * p.rho_v, den * r, p.rho_d);
        // Paper form with both directions grazing: the reference's cos θN (of the rounded
        // angle θN ≈ 90°) has lost relative accuracy.
        let paper_ill = p.paper && sz[j] * sz[j] < PAPER_COS2_MIN * s2[j];
        f.fallback[j] = f.valid[j] && (f.fallback[j] || paper_ill);
    }
    f
}

/// The brdf (F00), the DoLP and, with `AOLP`, the AoLP (rad) of a block.
#[inline(always)]
fn block_brdf_dolp<M: Mla, const N: usize, const AOLP: bool>(
    p: &Params,
    b: &BlockIn<N>,
    out: &mut [Lanes<N>; 3],
) -> [bool; N] {
    let mut f = front::<M, N>(p, b);
    let mut gb = [0.0; N];
    for j in 0..N {
        let [rs2, rp2, _, _] = reflectances::<M>(p, f.cosb[j], f.qr[j], f.qi[j]);
        let (ga, gbj, _) = surface(f.g[j], rs2, rp2);
        let f00 = ga + f.fv[j];
        // F10 = g·B·cos2η_r and F20 = g·B·sin2η_r: DoLP = |g·B|/F00 needs no rotation.
        gb[j] = gbj;
        let d = if f00 > 0.0 { gb[j].abs() / f00 } else { 0.0 };
        f.fallback[j] |= f00 > 0.0 && f00 < TINY;
        out[0][j] = if f.valid[j] { f00 } else { 0.0 };
        out[1][j] = if f.valid[j] { d } else { 0.0 };
    }
    if AOLP {
        // AoLP = ½·atan2(F20, F10) (`Stokes::aolp` of F·(1, 0, 0, 0)); 0 without polarization.
        for j in 0..N {
            let [_, _, cr2, sr2] = rotations::<M, N>(&f, j);
            let a = 0.5 * atan2::<M>(sr2 * gb[j], cr2 * gb[j]);
            out[2][j] = if f.valid[j] && gb[j] != 0.0 { a } else { 0.0 };
        }
    }
    f.fallback
}

/// `[|rs|², |rp|², 1/|c + q|², 1/|N²c + q|²]` (`rs = (c − q)/(c + q)`,
/// `rp = (N²c − q)/(N²c + q)`) with one division — the same arithmetic in every path, so that
/// F00 is bitwise the same whichever path computes it.
#[inline(always)]
fn reflectances<M: Mla>(p: &Params, c: f64, qr: f64, qi: f64) -> [f64; 4] {
    let qi2 = qi * qi;
    let ns = M::mla(c - qr, c - qr, qi2);
    let ds = M::mla(c + qr, c + qr, qi2);
    let (nr, ni) = (p.n2r * c, p.n2i * c);
    let np = M::mla(nr - qr, nr - qr, (ni - qi) * (ni - qi));
    let dp = M::mla(nr + qr, nr + qr, (ni + qi) * (ni + qi));
    let inv = 1.0 / (ds * dp);
    let (inv_s, inv_p) = (dp * inv, ds * inv);
    [ns * inv_s, np * inv_p, inv_s, inv_p]
}

/// `(g·A, g·B, g)` with `A = (|rs|²+|rp|²)/2`, `B = (|rs|²−|rp|²)/2`; `g` set to 0 when the
/// surface term `g·A` is below the smallest normal f64 (flushed to zero, as the reference does).
#[inline(always)]
fn surface(g: f64, rs2: f64, rp2: f64) -> (f64, f64, f64) {
    let a = 0.5 * (rs2 + rp2);
    let g = if g * a >= f64::MIN_POSITIVE { g } else { 0.0 };
    (g * a, g * (0.5 * (rs2 - rp2)), g)
}

/// `(cos2η_i, sin2η_i, cos2η_r, sin2η_r)` of element `j`, as `(c² − s², 2cs)/(c² + s²)` from
/// the closed-form pairs of spec §3 (halved): cos/sin η_i ∝ (c_i, s_i), cos/sin η_r ∝ (c_r, s_r).
#[inline(always)]
fn rotations<M: Mla, const N: usize>(f: &Front<N>, j: usize) -> [f64; 4] {
    let (si, ci) = (f.sin[TI][j], f.cos[TI][j]);
    let (sr, cr) = (f.sin[TR][j], f.cos[TR][j]);
    let (sh, ch, su, cu) = (f.sin[H][j], f.cos[H][j], f.sin[U][j], f.cos[U][j]);
    let sc = su * cu;
    let shc = sh * ch;
    let sh2 = sh * sh;
    let c_i = M::mla(ci * sr, sh2, sc);
    let s_i = sr * shc;
    let c_r = M::mla(si * cr, sh2, -sc);
    let s_r = si * shc;
    let norm_i = M::mla(c_i, c_i, s_i * s_i);
    // β = 0 (or within 1e-75 of it, where F no longer depends on the direction of approach):
    // η_i = 0, and η_r from (cos, sin) ∝ (−cosΔ, cosθr·sinΔ) (spec §3).
    let regular = norm_i > 1e-150;
    let (c_i, s_i) = if regular { (c_i, s_i) } else { (1.0, 0.0) };
    let (c_r, s_r) = if regular {
        (c_r, s_r)
    } else {
        (M::mla(2.0, sh2, -1.0), 2.0 * cr * shc)
    };
    let ni = M::mla(c_i, c_i, s_i * s_i);
    let nr = M::mla(c_r, c_r, s_r * s_r);
    let inv = 1.0 / (ni * nr);
    let (inv_i, inv_r) = (nr * inv, ni * inv);
    [
        M::mla(c_i, c_i, -(s_i * s_i)) * inv_i,
        2.0 * c_i * s_i * inv_i,
        M::mla(c_r, c_r, -(s_r * s_r)) * inv_r,
        2.0 * c_r * s_r * inv_r,
    ]
}

/// The full pBRDF of a block, as 16 rows of lanes (row-major entry index first).
#[inline(always)]
fn block_mueller<M: Mla, const N: usize>(
    p: &Params,
    b: &BlockIn<N>,
    out: &mut [Lanes<N>; 16],
) -> [bool; N] {
    let mut f = front::<M, N>(p, b);
    let z = [0.0; N];
    // Fresnel amplitudes rs = (c − q)/(c + q), rp = (N²c − q)/(N²c + q) (one division), and
    // g·A, g·B, g·C, g·S with A = (|rs|²+|rp|²)/2, B = (|rs|²−|rp|²)/2, C + iS = rs·rp*.
    let (mut ga, mut gb, mut gc, mut gs) = (z, z, z, z);
    for j in 0..N {
        let (c, qr, qi) = (f.cosb[j], f.qr[j], f.qi[j]);
        let [rs2, rp2, inv_s, inv_p] = reflectances::<M>(p, c, qr, qi);
        let (ar, ai) = (c - qr, -qi);
        let (br, bi) = (c + qr, qi);
        let (nr, ni) = (p.n2r * c, p.n2i * c);
        let (er, ei) = (nr - qr, ni - qi);
        let (fr, fi) = (nr + qr, ni + qi);
        let rs_r = M::mla(ar, br, ai * bi) * inv_s;
        let rs_i = M::mla(ai, br, -(ar * bi)) * inv_s;
        let rp_r = M::mla(er, fr, ei * fi) * inv_p;
        let rp_i = M::mla(ei, fr, -(er * fi)) * inv_p;
        let g;
        (ga[j], gb[j], g) = surface(f.g[j], rs2, rp2);
        gc[j] = g * M::mla(rs_r, rp_r, rs_i * rp_i);
        gs[j] = g * M::mla(rs_i, rp_r, -(rs_r * rp_i));
    }
    // The rotations.
    let (mut ci2, mut si2, mut cr2, mut sr2) = (z, z, z, z);
    for j in 0..N {
        [ci2[j], si2[j], cr2[j], sr2[j]] = rotations::<M, N>(&f, j);
    }
    // F = g·R(η_r)·M_d·R(−η_i) + f_v·diag(1, 0, 0, 0).
    for j in 0..N {
        let (ci2, si2, cr2, sr2) = (ci2[j], si2[j], cr2[j], sr2[j]);
        let (ga, gb, gc, gs) = (ga[j], gb[j], gc[j], gs[j]);
        let f00 = ga + f.fv[j];
        f.fallback[j] |= f00 > 0.0 && f00 < TINY;
        let p1 = ga * ci2;
        let p2 = ga * si2;
        let q1 = gc * si2;
        let q2 = gc * ci2;
        let v = [
            f00,
            gb * ci2,
            gb * si2,
            0.0,
            cr2 * gb,
            M::mla(cr2, p1, sr2 * q1),
            M::mla(cr2, p2, -(sr2 * q2)),
            -(sr2 * gs),
            sr2 * gb,
            M::mla(sr2, p1, -(cr2 * q1)),
            M::mla(sr2, p2, cr2 * q2),
            cr2 * gs,
            0.0,
            gs * si2,
            -(gs * ci2),
            gc,
        ];
        let valid = f.valid[j];
        for (o, x) in out.iter_mut().zip(v) {
            o[j] = if valid { x } else { 0.0 };
        }
    }
    f.fallback
}

#[inline(always)]
fn mueller_chunk<M: Mla, S: Source, O: MuellerOut, const N: usize>(
    k: &Kernel<'_>,
    src: &S,
    out: &mut [O],
) {
    let mut rows = [[0.0; N]; 16];
    let mut staged = [[0.0; 16]; N];
    for (blk, dst) in out.chunks_mut(N).enumerate() {
        let start = blk * N;
        let input = BlockIn::load(src, start, dst.len());
        let fallback = block_mueller::<M, N>(&k.p, &input, &mut rows);
        // Transpose into a row-major staging block (in L1), then copy out contiguously.
        for e in 0..16 {
            for j in 0..N {
                staged[j][e] = rows[e][j];
            }
        }
        for j in 0..dst.len() {
            if fallback[j] {
                staged[j] = k.reference(src.get(start + j)).pbrdf.to_row_major();
            }
        }
        O::write_block(dst, &staged, k.stream);
    }
    if k.stream {
        store_fence();
    }
}

/// BRDF, DoLP and (with `AOLP`) AoLP; `aolp` is empty without `AOLP`.
#[inline(always)]
fn brdf_dolp_chunk<M: Mla, S: Source, const N: usize, const AOLP: bool>(
    k: &Kernel<'_>,
    src: &S,
    brdf: &mut [f64],
    dolp: &mut [f64],
    aolp: &mut [f64],
) {
    let mut lanes = [[0.0; N]; 3];
    let n = brdf.len();
    for start in (0..n).step_by(N) {
        let len = N.min(n - start);
        let input = BlockIn::load(src, start, len);
        let fallback = block_brdf_dolp::<M, N, AOLP>(&k.p, &input, &mut lanes);
        brdf[start..start + len].copy_from_slice(&lanes[0][..len]);
        dolp[start..start + len].copy_from_slice(&lanes[1][..len]);
        if AOLP {
            aolp[start..start + len].copy_from_slice(&lanes[2][..len]);
        }
        for j in 0..len {
            if fallback[j] {
                let e = k.reference(src.get(start + j));
                (brdf[start + j], dolp[start + j]) = (e.brdf(), e.dolp());
                if AOLP {
                    aolp[start + j] = e.reflect(&Stokes::unpolarized()).aolp();
                }
            }
        }
    }
}

#[cfg(target_arch = "x86_64")]
mod x86 {
    //! The block kernel compiled for AVX2+FMA and for AVX-512.

    use super::{brdf_dolp_chunk, mueller_chunk, Fused, Kernel, MuellerOut, Source};

    /// # Safety
    /// The CPU must support AVX-512 F/DQ/VL, AVX2 and FMA.
    #[target_feature(enable = "avx512f,avx512dq,avx512vl,avx2,fma")]
    pub(super) unsafe fn mueller_avx512<S: Source, O: MuellerOut, const N: usize>(
        k: &Kernel<'_>,
        src: &S,
        out: &mut [O],
    ) {
        mueller_chunk::<Fused, S, O, N>(k, src, out)
    }

    /// # Safety
    /// The CPU must support AVX2 and FMA.
    #[target_feature(enable = "avx2,fma")]
    pub(super) unsafe fn mueller_avx2<S: Source, O: MuellerOut, const N: usize>(
        k: &Kernel<'_>,
        src: &S,
        out: &mut [O],
    ) {
        mueller_chunk::<Fused, S, O, N>(k, src, out)
    }

    /// # Safety
    /// The CPU must support AVX-512 F/DQ/VL, AVX2 and FMA.
    #[target_feature(enable = "avx512f,avx512dq,avx512vl,avx2,fma")]
    pub(super) unsafe fn brdf_dolp_avx512<S: Source, const N: usize, const AOLP: bool>(
        k: &Kernel<'_>,
        src: &S,
        brdf: &mut [f64],
        dolp: &mut [f64],
        aolp: &mut [f64],
    ) {
        brdf_dolp_chunk::<Fused, S, N, AOLP>(k, src, brdf, dolp, aolp)
    }

    /// # Safety
    /// The CPU must support AVX2 and FMA.
    #[target_feature(enable = "avx2,fma")]
    pub(super) unsafe fn brdf_dolp_avx2<S: Source, const N: usize, const AOLP: bool>(
        k: &Kernel<'_>,
        src: &S,
        brdf: &mut [f64],
        dolp: &mut [f64],
        aolp: &mut [f64],
    ) {
        brdf_dolp_chunk::<Fused, S, N, AOLP>(k, src, brdf, dolp, aolp)
    }
}

#[cfg(test)]
mod tests {
    //! Accuracy of the polynomial transcendental functions against the standard library.

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
                    sincos::<Fused>(x)
                } else {
                    sincos::<Unfused>(x)
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
            let x = k as f64 * std::f64::consts::FRAC_PI_2;
            for x in [x, x.next_up(), x.next_down(), 1e-300, 1e-20, -3e-9] {
                let (s, c) = sincos::<Fused>(x);
                assert!(ulps(s, x.sin()) < 2.0, "sin({x}) = {s} vs {}", x.sin());
                assert!(ulps(c, x.cos()) < 2.0, "cos({x}) = {c} vs {}", x.cos());
            }
        }
        assert_eq!(sincos::<Fused>(0.0), (0.0, 1.0));
    }

    #[test]
    fn exp_within_two_ulp() {
        for x in grid(-745.0, 0.0, 1_000_000).chain(grid(-1.0, 0.0, 100_000)) {
            for e in [exp_neg::<Fused>(x), exp_neg::<Unfused>(x)] {
                let want = x.exp();
                if want >= f64::MIN_POSITIVE {
                    assert!(ulps(e, want) < 2.0, "exp({x}) = {e} vs {want}");
                } else {
                    // Subnormal: within one unit of the last place (4.9e-324).
                    assert!((e - want).abs() <= 5e-324, "exp({x}) = {e} vs {want}");
                }
            }
        }
        assert_eq!(exp_neg::<Fused>(0.0), 1.0);
        assert_eq!(exp_neg::<Fused>(-800.0), 0.0);
        assert_eq!(exp_neg::<Fused>(f64::NEG_INFINITY), 0.0);
    }

    #[test]
    fn presets_never_take_the_reference_path() {
        // "For ordinary materials and geometries no element takes that path."
        let mut state = 1u64;
        let mut next = move || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for preset in crate::presets::all() {
            let m = preset.spec.build().unwrap();
            let k = Kernel::new(&m);
            for _ in 0..1000 {
                let mut b = BlockIn::<BLOCK> {
                    ti: [0.0; BLOCK],
                    pi: [0.0; BLOCK],
                    tr: [0.0; BLOCK],
                    pr: [0.0; BLOCK],
                };
                for j in 0..BLOCK {
                    b.ti[j] = next() * 89.9f64.to_radians();
                    b.pi[j] = next() * 2.0 * std::f64::consts::PI;
                    b.tr[j] = next() * 89.9f64.to_radians();
                    b.pr[j] = next() * 2.0 * std::f64::consts::PI;
                }
                let mut rows = [[0.0; BLOCK]; 16];
                let fallback = block_mueller::<Unfused, BLOCK>(&k.p, &b, &mut rows);
                assert!(!fallback.iter().any(|f| *f), "{}", preset.name);
                let mut lanes = [[0.0; BLOCK]; 3];
                let fallback = block_brdf_dolp::<Unfused, BLOCK, true>(&k.p, &b, &mut lanes);
                assert!(!fallback.iter().any(|f| *f), "{}", preset.name);
            }
        }
    }

    #[test]
    fn atan2_within_two_ulp() {
        for y in grid(0.0, 3.0, 700) {
            for x in grid(0.0, 3.0, 700).chain([1e-300, 1e-30]) {
                for a in [atan2_q1::<Fused>(y, x), atan2_q1::<Unfused>(y, x)] {
                    let want = y.atan2(x);
                    assert!(ulps(a, want) < 2.0, "atan2({y}, {x}) = {a} vs {want}");
                }
            }
        }
        for y in grid(-3.0, 3.0, 300).chain([0.0, -0.0]) {
            for x in grid(-3.0, 3.0, 300).chain([0.0, -0.0]) {
                let (a, want) = (atan2::<Fused>(y, x), y.atan2(x));
                assert!(
                    ulps(a, want) < 2.0 && a.to_bits() >> 63 == want.to_bits() >> 63,
                    "atan2({y}, {x}) = {a} vs {want}"
                );
            }
        }
        assert_eq!(atan2_q1::<Fused>(0.0, 0.0), 0.0);
        assert_eq!(atan2_q1::<Fused>(0.0, 1.0), 0.0);
        assert_eq!(atan2_q1::<Fused>(1.0, 0.0), FRAC_PI_2);
    }
}
