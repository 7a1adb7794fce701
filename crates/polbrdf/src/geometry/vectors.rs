//! The model's geometry straight from two direction vectors (the batch engine's direction
//! route, docs/engine-performance.md): sums, differences, dot and cross products of the unit
//! vectors — no angles, no arctangent or sine on the way, two square roots and two divisions
//! (the normalization, [`unit`]) besides those of θN and cosβ (and of β, θi, ΦN where a
//! material uses them). The same quantities as [`crate::geometry::angles`]
//! computes from the angles the vectors stand for ([`crate::geometry::angles::direction_angles`],
//! `φ = 0` along the normal), to rounding.
//!
//! With `ŵ_i`, `ŵ_r` the unit vectors (`z` floored at [`COS_BELOW_90`] above the horizon),
//! `s = ŵ_i + ŵ_r` (the half vector, unnormalized) and `d = ŵ_r − ŵ_i`:
//! - `cosθi = ẑ_i`, `cosθr = ẑ_r`, `s_z`, `|s_xy|² = s_x² + s_y²`, `|s|²`, so `θN =
//!   atan2(|s_xy|, s_z)` and `cosβ = |s|/2`;
//! - `sin²β = |d|²/4` (β is half the angle between the two vectors: no `1 − cos` cancellation
//!   near retro-reflection);
//! - the Priest–Meier pairs of [`crate::geometry::angles::eta_pairs`], each up to a positive
//!   factor (the rotations need only their direction): with `a_i` the horizontal part of
//!   `ŵ_i` (scaled by a power of two to `max(|a_x|, |a_y|) ∈ [1, 2)`, exact; `(1, 0)` along
//!   the normal, i.e. φ = 0) and `a_r` that of `ŵ_r`,
//!   `c_i = (a_i·ŵ_i,xy)·d_z − ẑ_i·(a_i·d_xy)`, `s_i = a_i × d_xy = a_i × s_xy`,
//!   `c_r = ẑ_r·(a_r·d_xy) − (a_r·ŵ_r,xy)·d_z`, `s_r = a_r × d_xy = −a_r × s_xy`: `|a|·sin2β`
//!   times `(cos η, sin η)`; the `c` are linear in `d`, so as accurate near retro-reflection as
//!   `d` is, and the `s` are taken from the shorter of `d_xy` and `s_xy` (a cross product
//!   rounds in proportion to its factors' lengths: `s_xy` near specular). Where
//!   `sin2β/2 ≤ √PAIR_MIN` (β = 0 to within 10⁻⁷⁵ in f64) the degenerate pairs of
//!   `eta_pairs`: `η_i = 0`, `(cos η_r, sin η_r) ∝ (−a_i·a_r, ẑ_r·(a_i × a_r))`;
//! - ΦN (eq. 3 only) from its two components along and across the plane of incidence,
//!   `sinθi + sinθr cosΔ = (sinθi − sinθr) + sinθr·|â_i + â_r|²/2` (`sinθi − sinθr` as it
//!   stands where `sinθi + sinθr ≤ ẑi + ẑr`, else as `(ẑr² − ẑi²)/(sinθi + sinθr)`) and `sinθr sinΔ
//!   = sinθr·(â_i × (â_i ± â_r))` (`â` the unit horizontal axes, the shorter of the two
//!   sums): `atan2(|across|, |along|)`, 0 where `|s_xy| ≤ 8ε·(sinθi + sinθr)` (docs/model.md
//!   §9.3, azimuth scale 1 for vectors). Each small part is formed where it is small (the `z`
//!   near grazing, `â_i + â_r` near specular): `a_i·s_xy` would carry `s_xy`'s absolute
//!   rounding, ε, where ΦN needs ε·cosθ near grazing.

use crate::geometry::angles::COS_BELOW_90;

/// `(x, y)` scaled by the power of two that puts `max(|x|, |y|)` in `[1, 2)` (exact), and
/// `(1, 0)` where both are 0 (the azimuth φ = 0 along the normal). Branch-free bit
/// arithmetic, so that it vectorizes. (A subnormal `max` is scaled by 2¹⁰²³ only; such a
/// vector is within 10⁻¹⁴⁰ rad of the normal, where the engine takes the one-geometry path.)
#[inline(always)]
pub(crate) fn azimuth_axis(x: f64, y: f64) -> [f64; 2] {
    let m = x.abs().max(y.abs());
    let scale = f64::from_bits(2046u64.wrapping_sub(m.to_bits() >> 52) << 52);
    if m > 0.0 {
        [x * scale, y * scale]
    } else {
        [1.0, 0.0]
    }
}

/// `z` floored above the horizon: no closer to it than an f64 angle can be
/// ([`COS_BELOW_90`]).
#[inline(always)]
fn floored([x, y, z]: [f64; 3]) -> [f64; 3] {
    [x, y, if z > 0.0 { z.max(COS_BELOW_90) } else { z }]
}

/// The unit vector of `w` (`w/|w|`, as the angle route's conversion computes it), `z`
/// floored above the horizon.
#[inline(always)]
pub(crate) fn unit(w: [f64; 3]) -> [f64; 3] {
    let inv = 1.0 / (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
    floored(w.map(|c| c * inv))
}

/// The geometry of one element from its two direction vectors, in f64 (module
/// documentation). The block kernel rounds it to its floating-point type and computes the
/// angles θN, β (and θi, ΦN where a material needs them) from it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct VectorGeometry {
    /// cosθi, cosθr (`z` of the unit vectors, floored above the horizon).
    pub cos_i: f64,
    /// cosθr.
    pub cos_r: f64,
    /// `s_z = cosθi + cosθr`.
    pub sz: f64,
    /// `|s_xy|²`.
    pub rho2: f64,
    /// `|s|²`.
    pub s2: f64,
    /// `sin²β = |d|²/4`.
    pub sin2_beta: f64,
    /// `sin²θi = x̂_i² + ŷ_i²` (for θi where SO needs it).
    pub sin2_i: f64,
    /// `sin²θr`.
    pub sin2_r: f64,
    /// The Priest–Meier pairs `[c_i, s_i, c_r, s_r]`, each up to a positive factor.
    pub pairs: [f64; 4],
    /// ΦN's components along and across the plane of incidence.
    pub along: f64,
    /// ΦN's component across the plane of incidence (its sign is not ΦN's).
    pub across: f64,
    /// `sinθi + sinθr`.
    pub sin_sum: f64,
    /// The smallest `x̂² + ŷ²` of the two unit vectors that are not exactly along the normal
    /// (1 when both are): where it is below the normal range the azimuth's axis loses digits
    /// (the engine takes the one-geometry path, as it did from angles).
    pub off_normal: f64,
}

impl VectorGeometry {
    /// From `w_i` (toward the source) and `w_r` (toward the detector), any length within
    /// [`crate::geometry::angles::DIRECTION_LENGTH`], and their unit vectors `i`, `r`
    /// ([`unit`]); `pair_min` is the floating-point type's
    /// [`crate::numeric::math::Real::PAIR_MIN`] (for the degenerate pairs at β = 0).
    #[inline(always)]
    pub(crate) fn new(w_i: [f64; 3], w_r: [f64; 3], [i, r]: [[f64; 3]; 2], pair_min: f64) -> Self {
        let s = [i[0] + r[0], i[1] + r[1], i[2] + r[2]];
        let d = [r[0] - i[0], r[1] - i[1], r[2] - i[2]];
        let rho2 = s[0] * s[0] + s[1] * s[1];
        let (sin2_i, sin2_r) = (i[0] * i[0] + i[1] * i[1], r[0] * r[0] + r[1] * r[1]);
        let off = |w: [f64; 3], r2: f64| {
            if (w[0] == 0.0) & (w[1] == 0.0) {
                1.0
            } else {
                r2
            }
        };
        let ai = azimuth_axis(i[0], i[1]);
        let ar = azimuth_axis(r[0], r[1]);
        let dot = |a: [f64; 2], b: [f64; 2]| a[0] * b[0] + a[1] * b[1];
        let cross = |a: [f64; 2], b: [f64; 2]| a[0] * b[1] - a[1] * b[0];
        let (sxy, dxy) = ([s[0], s[1]], [d[0], d[1]]);
        // `a_i × ŵ_r,xy = a_i × d_xy = a_i × s_xy` and `−a_r × ŵ_i,xy = a_r × d_xy = −a_r ×
        // s_xy`: from the shorter of `d_xy` and `s_xy`, whose rounding is the smaller (`d`
        // near retro-reflection, `s` near specular).
        let by_s = rho2 < dot(dxy, dxy);
        let v = if by_s { sxy } else { dxy };
        let s_i = cross(ai, v);
        let s_r = if by_s { -cross(ar, v) } else { cross(ar, v) };
        let c_i = dot(ai, [i[0], i[1]]) * d[2] - i[2] * dot(ai, dxy);
        let c_r = r[2] * dot(ar, dxy) - dot(ar, [r[0], r[1]]) * d[2];
        // |pair|² = |a_i|²·sin²2β against the angle route's (sin2β/2)² > PAIR_MIN.
        let regular = c_i * c_i + s_i * s_i > 4.0 * pair_min * dot(ai, ai);
        let pairs = if regular {
            [c_i, s_i, c_r, s_r]
        } else {
            [1.0, 0.0, -dot(ai, ar), r[2] * cross(ai, ar)]
        };
        // ΦN's components with the unit horizontal axes `â = (x̂, ŷ)/sinθ` (eq. 3 only; unused
        // otherwise, and then not computed): `sinθi + sinθr cosΔ`, arranged as `(sinθi −
        // sinθr) + sinθr·|â_i + â_r|²/2` with `sinθi − sinθr = (ẑr² − ẑi²)/(sinθi + sinθr)`
        // nearer grazing, and
        // `sinθr sinΔ = sinθr·(â_i × v)` with `v` the shorter of `â_i ± â_r`: each small part
        // formed where it is small (near grazing the `z`, near specular `â_i + â_r`), so ΦN is as
        // accurate as the angle route's near specular and grazing, where `s_xy`'s components
        // carry f64's absolute rounding.
        let (ri, rr) = (sin2_i.sqrt(), sin2_r.sqrt());
        let axis = |w: [f64; 3], r: f64| {
            if r > 0.0 {
                [w[0] / r, w[1] / r]
            } else {
                [1.0, 0.0]
            }
        };
        let (ui, ur) = (axis(i, ri), axis(r, rr));
        let p = [ui[0] + ur[0], ui[1] + ur[1]];
        let q = [ur[0] - ui[0], ur[1] - ui[1]];
        let sum = ri + rr;
        // sinθi − sinθr from the sines nearer the normal, from the cosines nearer grazing.
        let zsum = r[2] + i[2];
        let diff = if sum <= zsum {
            ri - rr
        } else {
            (r[2] - i[2]) * zsum / sum
        };
        let along = diff + 0.5 * rr * dot(p, p);
        let across = rr * cross(ui, if dot(p, p) < dot(q, q) { p } else { q });
        Self {
            cos_i: i[2],
            cos_r: r[2],
            sz: s[2],
            rho2,
            s2: rho2 + s[2] * s[2],
            sin2_beta: 0.25 * (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]),
            sin2_i,
            sin2_r,
            pairs,
            along,
            across,
            sin_sum: sum,
            off_normal: off(w_i, sin2_i).min(off(w_r, sin2_r)),
        }
    }

    /// Whether `|s_xy|` is at rounding level, where ΦN is 0 (docs/model.md §9.3):
    /// `|s_xy| ≤ 8ε·(sinθi + sinθr)` with f64's ε.
    #[inline(always)]
    pub(crate) fn flat(&self) -> bool {
        let level = 8.0 * f64::EPSILON * self.sin_sum;
        self.rho2.sqrt() <= level
    }
}
