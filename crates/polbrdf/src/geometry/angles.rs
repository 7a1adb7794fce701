//! The angle variables of the model (θN, β, ΦN, η_i, η_r; docs/model.md §1, §4) in closed form,
//! written once for both paths: [`Geometry::angle_variables`](crate::Geometry::angle_variables)
//! and `Material::evaluate` call these functions with the standard library's elementary
//! functions, the batch engine with its polynomial ones, across a block of elements.
//!
//! Everything follows from four sine/cosine pairs ([`Trig`]) — of θi, θr, `Δ/2` with
//! `Δ = φr − φi`, and `u = (θi − θr)/2` — by algebra arranged without cancellation:
//! `sin(θi − θr) = 2 sin u cos u`, `1 − cosΔ = 2 sin²(Δ/2)`, `sinΔ = 2 sin(Δ/2) cos(Δ/2)`, and for
//! the half vector `s = w_i + w_r` (docs/model.md §9.2)
//! `|s_xy|² = 4(cos²v sin²u + sinθi sinθr cos²(Δ/2))` with `cos v = cos((θi + θr)/2) =
//! (cosθi + cosθr)/(2 cos u)`,
//! `s_z = cosθi + cosθr`, `cosβ = |s|/2`, `sin²β = sin²u + sinθi sinθr sin²(Δ/2)`.

use crate::numeric::math::{Math, Real, Std};

/// Sines and cosines of θi, θr, `Δ/2` (`Δ = φr − φi`) and `u = (θi − θr)/2`, in `T` (f64, or
/// f32 in the single-precision kernel).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Trig<T = f64> {
    /// sin θi, cos θi.
    pub si: T,
    /// cos θi.
    pub ci: T,
    /// sin θr.
    pub sr: T,
    /// cos θr.
    pub cr: T,
    /// sin(Δ/2).
    pub sh: T,
    /// cos(Δ/2).
    pub ch: T,
    /// sin u.
    pub su: T,
    /// cos u.
    pub cu: T,
}

impl<T: Real> Trig<T> {
    /// From the four angles (rad). `|Δ/2|` beyond the backend's accurate range
    /// ([`Math::SINCOS_MAX`]) is replaced by 0 — the batch engine sends such elements to the
    /// one-geometry path ([`Trig::in_range`]). The half angles are formed in f64 whatever `T`.
    #[inline(always)]
    pub fn new<M: Math<F = T>>(theta_i: f64, phi_i: f64, theta_r: f64, phi_r: f64) -> Self {
        Self::from_reduced::<M>(Self::reduce::<M>(theta_i, phi_i, theta_r, phi_r))
    }

    /// The arguments of [`Trig::new`] reduced by backend `M` ([`Math::reduce`]), in the order
    /// θi, θr, `Δ/2`, `u` (the batch kernel runs the reduction and [`Trig::from_reduced`] in
    /// separate loops).
    #[inline(always)]
    pub fn reduce<M: Math<F = T>>(
        theta_i: f64,
        phi_i: f64,
        theta_r: f64,
        phi_r: f64,
    ) -> [[T; 3]; 4] {
        let h = 0.5 * (phi_r - phi_i);
        let h = if h.abs() <= M::SINCOS_MAX { h } else { 0.0 };
        [
            M::reduce(theta_i),
            M::reduce(theta_r),
            M::reduce(h),
            // |u| < π/4 where both directions are above the horizon; elsewhere the element is
            // invalid (a zero result) and the value unused.
            M::reduce_small(0.5 * (theta_i - theta_r)),
        ]
    }

    /// The sines and cosines from [`Trig::reduce`]'s arguments.
    #[inline(always)]
    pub fn from_reduced<M: Math<F = T>>([ri, rr, rh, ru]: [[T; 3]; 4]) -> Self {
        let (si, ci) = M::sincos_reduced(ri);
        let (sr, cr) = M::sincos_reduced(rr);
        let (sh, ch) = M::sincos_reduced(rh);
        let (su, cu) = M::sincos_reduced(ru);
        Self {
            si,
            ci,
            sr,
            cr,
            sh,
            ch,
            su,
            cu,
        }
    }

    /// Whether backend `M` computes `sin(Δ/2)` of these azimuths to full accuracy.
    #[inline(always)]
    pub fn in_range<M: Math<F = T>>(phi_i: f64, phi_r: f64) -> bool {
        (0.5 * (phi_r - phi_i)).abs() <= M::SINCOS_MAX
    }
}

/// The shortest and longest direction vector the direction entry point accepts
/// ([`crate::DirectionBatch`]): vectors are normalized, and within these bounds every square
/// and product of their components stays in the normal range of f64 and of f32.
pub const DIRECTION_LENGTH: (f64, f64) = (1e-15, 1e15);

/// `cos θ` of the largest f64 angle below π/2 (2.83·10⁻¹⁶): the smallest cosine a direction
/// above the horizon has as an angle, and the floor [`Trig::from_directions`] puts under
/// `cos θ = z/|w|` for `z > 0` (docs/model.md §9.11) — without it a vector a few hundred
/// orders of magnitude above the horizon (`z = 1e-313`) overflowed `1/cos θ`.
pub const COS_BELOW_90: f64 = 2.832_769_448_823_99e-16;

impl<T: Real> Trig<T> {
    /// From two direction vectors `(x, y, z)` in the surface frame (z along the normal; any
    /// length within [`DIRECTION_LENGTH`], each normalized here): `w_i` toward the source,
    /// `w_r` toward the detector (docs/model.md §1, §9.11). A vector is the angles
    /// `θ = atan2(√(x² + y²), z)`, `φ = atan2(y, x)` — `φ = 0` when `x = y = 0` — with no
    /// elementary function on the way:
    /// - `sinθ = √(x² + y²)/|w|`, `cosθ = z/|w|`, the azimuth's unit vector `a = (x, y)/√(x² + y²)`
    ///   (`(1, 0)` at `x = y = 0`);
    /// - `Δ = φr − φi` taken in (−π, π]: `|cos(Δ/2)| = |a_r + a_i|/2 = cos(Δ/2)`,
    ///   `|sin(Δ/2)| = |a_r − a_i|/2` with the sign of `a_i × a_r` (only `sin(Δ/2)cos(Δ/2)`
    ///   and the squares enter the model, which do not depend on Δ's multiple of 2π);
    /// - `u = (θi − θr)/2`: `cos u = |p_i + p_r|/2`, where `p = (sinθ, cosθ)`, and
    ///   `sin u = sin(θi − θr)/(2 cos u)` with `sin(θi − θr) = p_i × p_r = sinθi cosθr −
    ///   cosθi sinθr`. (Not `|p_i − p_r|/2`: near the normal `cosθ ≈ 1` carries an absolute
    ///   rounding of ε/2 that would leave `sin u` — and the half vector's horizontal part —
    ///   at ε instead of ε·sinθ, above ΦN's rounding level, §9.3.)
    ///
    /// Each is a norm of a sum or difference of unit vectors, or a cross product, so a small
    /// angle is as accurate as the vectors' components make it (no `1 − cos` cancellation). Also returns the
    /// smallest `x² + y²` of the two normalized vectors that are not exactly along the normal
    /// (1 when both are): near the subnormal range (or underflowed to 0) the azimuth's unit
    /// vector loses digits, and the caller sends the element to a wider path.
    #[inline(always)]
    pub fn from_directions(w_i: [T; 3], w_r: [T; 3]) -> (Self, T) {
        let half = T::of(0.5);
        let polar = |w: [T; 3]| {
            let inv = T::ONE / (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
            let (x, y, z) = (w[0] * inv, w[1] * inv, w[2] * inv);
            // Above the horizon, no closer to it than an f64 angle can be ([`COS_BELOW_90`]).
            let z = if z > T::ZERO {
                z.max(T::of(COS_BELOW_90))
            } else {
                z
            };
            let r2 = x * x + y * y;
            let r = r2.sqrt();
            let inv_r = T::ONE / if r > T::ZERO { r } else { T::ONE };
            let a = if r > T::ZERO {
                [x * inv_r, y * inv_r]
            } else {
                [T::ONE, T::ZERO]
            };
            // Off the normal, the squared length of the horizontal part (`x² + y²` can
            // underflow to 0 while `(x, y)` is not 0); along it (exactly), 1.
            let off = if (w[0] == T::ZERO) & (w[1] == T::ZERO) {
                T::ONE
            } else {
                r2
            };
            (r, z, a, off)
        };
        let (si, ci, ai, r2i) = polar(w_i);
        let (sr, cr, ar, r2r) = polar(w_r);
        let cross = ai[0] * ar[1] - ai[1] * ar[0];
        let (dx, dy) = (ar[0] - ai[0], ar[1] - ai[1]);
        let (px, py) = (ar[0] + ai[0], ar[1] + ai[1]);
        let sh = half * (dx * dx + dy * dy).sqrt();
        let ch = half * (px * px + py * py).sqrt();
        let (pu, pv) = (si + sr, ci + cr);
        let cu = half * (pu * pu + pv * pv).sqrt();
        // sin u = sin(θi − θr)/(2 cos u), with sin(θi − θr) = p_i × p_r.
        let su = if cu > T::ZERO {
            (si * cr - ci * sr) / (cu + cu)
        } else {
            T::ZERO
        };
        let t = Self {
            si,
            ci,
            sr,
            cr,
            sh: if cross < T::ZERO { -sh } else { sh },
            ch,
            su,
            cu,
        };
        (t, r2i.min(r2r))
    }
}

/// The angles `(θ, φ)` (rad) of a direction vector, as [`Trig::from_directions`] defines them:
/// `θ = atan2(√(x² + y²), z)`, `φ = atan2(y, x)`, `φ = 0` when `x = y = 0` (the standard
/// library's functions; the one-geometry path of the direction entry point). A vector with
/// `z > 0` is above the horizon, as on the vectorized path: where its θ would round to 90°
/// (`z/|w| ≲ 6·10⁻¹⁷`) it is the largest f64 below π/2 (docs/model.md §9.11).
pub fn direction_angles(w: [f64; 3]) -> (f64, f64) {
    let r = w[0].hypot(w[1]);
    let phi = if r > 0.0 { w[1].atan2(w[0]) } else { 0.0 };
    let theta = r.atan2(w[2]);
    let below_90 = std::f64::consts::FRAC_PI_2.next_down();
    (
        if w[2] > 0.0 {
            theta.min(below_90)
        } else {
            theta
        },
        phi,
    )
}

/// The half vector `s = w_i + w_r` (unnormalized) in the frame of the plane of incidence.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HalfVector<T = f64> {
    /// `s∥ = sinθi + sinθr cosΔ = 2 cos v sin u + 2 sinθr cos²(Δ/2)` (along the plane of
    /// incidence).
    pub along: T,
    /// `s⊥ = sinθr sinΔ` (across it).
    pub across: T,
    /// `s_z = cosθi + cosθr`.
    pub sz: T,
    /// `|s_xy|`.
    pub rho: T,
    /// `|s|²`.
    pub s2: T,
}

/// The half vector of a geometry (module documentation).
#[inline(always)]
pub fn half_vector<M: Math>(t: &Trig<M::F>) -> HalfVector<M::F> {
    let two = M::F::of(2.0);
    let sz = t.ci + t.cr;
    // cos v from `cosθi + cosθr = 2 cos v cos u`: a sum of two non-negative terms over
    // `cos u ≥ cos(π/4)`, with no cancellation as both directions approach the horizon (where
    // `cos(θr + u) = cosθr cos u − sinθr sin u` loses `1/cos v` ulps). `cos u = 0` only below
    // the horizon (|θi − θr| = π): 0 there, an invalid element.
    let cosv = if t.cu > M::F::ZERO {
        sz / (two * t.cu)
    } else {
        M::F::ZERO
    };
    let dif = cosv * t.su;
    let ch2 = t.ch * t.ch;
    let rho2 = M::F::of(4.0) * M::mla(dif, dif, t.si * t.sr * ch2);
    HalfVector {
        along: two * M::mla(t.sr, ch2, dif),
        across: two * t.sr * (t.sh * t.ch),
        sz,
        rho: rho2.sqrt(),
        s2: M::mla(sz, sz, rho2),
    }
}

/// `sin²β = sin²u + sinθi sinθr sin²(Δ/2)` (β the local incidence angle on the facet).
#[inline(always)]
pub fn sin2_beta<M: Math>(t: &Trig<M::F>) -> M::F {
    M::mla(t.su, t.su, t.si * t.sr * (t.sh * t.sh))
}

/// `θN = acos(h·z) = atan2(|s_xy|, s_z)` (eqs. 1–4).
#[inline(always)]
pub fn theta_n<M: Math>(h: &HalfVector<M::F>) -> M::F {
    M::atan2_pos(h.rho, h.sz)
}

/// `cosβ = |s|/2` (eq. 11).
#[inline(always)]
pub fn cos_beta<M: Math>(h: &HalfVector<M::F>) -> M::F {
    M::F::of(0.5) * h.s2.sqrt()
}

/// `β = atan2(sinβ, cosβ)` and [`cos_beta`] (eqs. 1, 3, 11).
#[inline(always)]
pub fn beta<M: Math>(h: &HalfVector<M::F>, sin2_beta: M::F) -> (M::F, M::F) {
    let cos_beta = cos_beta::<M>(h);
    (M::atan2_pos(sin2_beta.sqrt(), cos_beta), cos_beta)
}

/// `ΦN` (eq. 3): the angle between the plane (z, h) and the plane of incidence,
/// `atan2(|s⊥|, |s∥|)` folded into [0, π/2] — and 0 when `|s_xy|` is at rounding level,
/// `|s_xy| ≤ 8ε·(sinθi + sinθr)·max(1, |φi|, |φr|)` (docs/model.md §9.3): an azimuth carries a
/// rounding error of order ulp(|φ|), which tilts a specular half vector by as much (ε of f64:
/// the azimuths are given in f64 and their half difference is formed in f64 on every path).
#[inline(always)]
pub fn phi_n<M: Math>(h: &HalfVector<M::F>, t: &Trig<M::F>, phi_scale: f64) -> M::F {
    let level = M::F::of(8.0 * f64::EPSILON) * (t.si + t.sr) * M::F::of(phi_scale);
    let d = M::atan2_pos(h.across.abs(), h.along.abs());
    if h.rho > level {
        d.min(M::F::of(std::f64::consts::FRAC_PI_2))
    } else {
        M::F::ZERO
    }
}

/// The rounding scale of the azimuths for [`phi_n`]: `max(1, |φi|, |φr|)`.
#[inline(always)]
pub fn phi_scale(phi_i: f64, phi_r: f64) -> f64 {
    phi_i.abs().max(phi_r.abs()).max(1.0)
}

/// The signed Priest–Meier angles as unnormalized pairs `[c_i, s_i, c_r, s_r]`,
/// `(cos η, sin η) ∝ (c, s)` (eq. 11, docs/model.md §4): half the closed forms
/// `sin2β·cos η_i = sin(θi − θr) + 2 cosθi sinθr sin²(Δ/2)`, `sin2β·sin η_i = sinθr sinΔ`,
/// `sin2β·cos η_r = sin(θr − θi) + 2 sinθi cosθr sin²(Δ/2)`, `sin2β·sin η_r = sinθi sinΔ`.
/// At β = 0 (retro-reflection, within 1e-75 of it, where F no longer depends on the direction
/// of approach) the facet frame is the incident one: `η_i = 0`, `(cos η_r, sin η_r) ∝
/// (−cosΔ, cosθr sinΔ)`.
#[inline(always)]
pub fn eta_pairs<M: Math>(t: &Trig<M::F>) -> [M::F; 4] {
    let sc = t.su * t.cu;
    let shc = t.sh * t.ch;
    let sh2 = t.sh * t.sh;
    let c_i = M::mla(t.ci * t.sr, sh2, sc);
    let s_i = t.sr * shc;
    let c_r = M::mla(t.si * t.cr, sh2, -sc);
    let s_r = t.si * shc;
    let regular = M::mla(c_i, c_i, s_i * s_i) > M::F::PAIR_MIN;
    let two = M::F::of(2.0);
    if regular {
        [c_i, s_i, c_r, s_r]
    } else {
        [
            M::F::ONE,
            M::F::ZERO,
            M::mla(two, sh2, -M::F::ONE),
            two * t.cr * shc,
        ]
    }
}

/// `[cos2η_i, sin2η_i, cos2η_r, sin2η_r]` from the pairs of [`eta_pairs`]:
/// `(cos2η, sin2η) = (c² − s², 2cs)/(c² + s²)` — the Mueller rotators need no angle.
#[inline(always)]
pub fn rotations<M: Math>([c_i, s_i, c_r, s_r]: [M::F; 4]) -> [M::F; 4] {
    let ni = M::mla(c_i, c_i, s_i * s_i);
    let nr = M::mla(c_r, c_r, s_r * s_r);
    let inv = M::F::ONE / (ni * nr);
    let (inv_i, inv_r) = (nr * inv, ni * inv);
    let two = M::F::of(2.0);
    [
        M::mla(c_i, c_i, -(s_i * s_i)) * inv_i,
        two * c_i * s_i * inv_i,
        M::mla(c_r, c_r, -(s_r * s_r)) * inv_r,
        two * c_r * s_r * inv_r,
    ]
}

/// What the model's scalar terms and Fresnel amplitudes need of one geometry: the angles and the
/// cosines, computed once per element.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FacetAngles<T = f64> {
    /// θi (rad; in the azimuth factor of eq. 3).
    pub theta_i: T,
    /// cos θi.
    pub cos_i: T,
    /// cos θr.
    pub cos_r: T,
    /// θN (rad).
    pub theta_n: T,
    /// β (rad).
    pub beta: T,
    /// ΦN (rad), 0 unless asked for.
    pub phi_n: T,
    /// cos β.
    pub cos_beta: T,
    /// sin²β.
    pub sin2_beta: T,
    /// `s_z = cosθi + cosθr`.
    pub sz: T,
    /// `|s|²`, so that `cos²θN = s_z²/|s|²`.
    pub s2: T,
}

impl<T: Real> FacetAngles<T> {
    /// From a geometry's sines and cosines; ΦN only when `with_phi_n` (the eq. 3 azimuth factor
    /// is the only term that uses it), β only when `with_beta` (only SO uses it; cos β and
    /// sin²β, which the Fresnel amplitudes use, always). An angle not computed is 0.
    #[inline(always)]
    pub fn from_trig<M: Math<F = T>>(
        theta_i: T,
        t: &Trig<T>,
        phi_scale: f64,
        with_phi_n: bool,
        with_beta: bool,
    ) -> Self {
        let h = half_vector::<M>(t);
        let sin2_beta = sin2_beta::<M>(t);
        let (beta, cos_beta) = if with_beta {
            beta::<M>(&h, sin2_beta)
        } else {
            (T::ZERO, cos_beta::<M>(&h))
        };
        Self {
            theta_i,
            cos_i: t.ci,
            cos_r: t.cr,
            theta_n: theta_n::<M>(&h),
            beta,
            phi_n: if with_phi_n {
                phi_n::<M>(&h, t, phi_scale)
            } else {
                T::ZERO
            },
            cos_beta,
            sin2_beta,
            sz: h.sz,
            s2: h.s2,
        }
    }

    /// From explicit angle variables (the angle-variable entry point): the cosines of the given
    /// angles, and `|s|² = s_z²/cos²θN` (∞ at θN = π/2, where cos²θN = 0), computed in f64 and
    /// rounded to `T`.
    pub fn from_variables(v: &AngleVariables) -> Self {
        let (ci, cr) = (v.theta_i.cos(), v.theta_r.cos());
        let (sb, cb) = v.beta.sin_cos();
        let sz = ci + cr;
        let cn = v.theta_n.cos();
        Self {
            theta_i: T::of(v.theta_i),
            cos_i: T::of(ci),
            cos_r: T::of(cr),
            theta_n: T::of(v.theta_n),
            beta: T::of(v.beta),
            phi_n: T::of(v.phi_n),
            cos_beta: T::of(cb.max(0.0)),
            sin2_beta: T::of(sb * sb),
            sz: T::of(sz),
            s2: T::of(sz * sz / (cn * cn)),
        }
    }
}

/// The angle variables the model is written in (radians).
///
/// This is the "angle-variable entry point" of docs/model.md §6:
/// [`crate::Material::evaluate_angles`] takes one directly, so a caller can set θN as a free
/// roughness variable at in-plane specular geometry, as the paper's Fig. 2 does.
/// [`crate::Geometry::angle_variables`] computes it from two directions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AngleVariables {
    /// Incidence zenith angle θi (eq. 1).
    pub theta_i: f64,
    /// Viewing zenith angle θr (eq. 1).
    pub theta_r: f64,
    /// Local incidence angle on the facet, β = acos(w_i·h) (eqs. 1, 3, 11).
    pub beta: f64,
    /// Facet-normal zenith angle θN = acos(h·z) (eqs. 1–4).
    pub theta_n: f64,
    /// Facet-normal azimuth relative to the plane of incidence, folded into [0, π/2] (eq. 3).
    pub phi_n: f64,
    /// Signed rotation from the incident beam's s axis to the facet's s axis (eq. 11).
    pub eta_i: f64,
    /// Signed rotation from the reflected beam's s axis to the facet's s axis (eq. 11).
    pub eta_r: f64,
}

impl AngleVariables {
    /// Angle variables of an in-plane specular configuration with the facet tilted by θN, as in
    /// the paper's Fig. 2: `θi = θr = β = theta`, `ΦN = 0`, `η_i = η_r = 0`.
    pub fn in_plane_specular(theta: f64, theta_n: f64) -> Self {
        Self {
            theta_i: theta,
            theta_r: theta,
            beta: theta,
            theta_n,
            phi_n: 0.0,
            eta_i: 0.0,
            eta_r: 0.0,
        }
    }

    /// The angle variables of a geometry above the horizon (both zenith angles below π/2), by
    /// the closed forms of this module with the standard library's functions.
    pub fn of(theta_i: f64, phi_i: f64, theta_r: f64, phi_r: f64) -> Self {
        let t = Trig::new::<Std>(theta_i, phi_i, theta_r, phi_r);
        let a = FacetAngles::from_trig::<Std>(theta_i, &t, phi_scale(phi_i, phi_r), true, true);
        let [c_i, s_i, c_r, s_r] = eta_pairs::<Std>(&t);
        Self {
            theta_i,
            theta_r,
            beta: a.beta,
            theta_n: a.theta_n,
            phi_n: a.phi_n,
            eta_i: s_i.atan2(c_i),
            eta_r: s_r.atan2(c_r),
        }
    }

    /// `[cos η_i, sin η_i, cos η_r, sin η_r]`: the pairs [`rotations`] takes.
    pub fn eta_pairs(&self) -> [f64; 4] {
        let (si, ci) = self.eta_i.sin_cos();
        let (sr, cr) = self.eta_r.sin_cos();
        [ci, si, cr, sr]
    }
}
