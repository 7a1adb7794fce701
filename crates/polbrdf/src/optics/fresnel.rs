//! Fresnel reflection amplitudes for a complex index `N = n + ik` (docs/model.md §3; the a_ss,
//! a_pp of eqs. 10–11 and R_F of eq. 1).
//!
//! **Convention.** Time dependence `exp(−iωt)`, so an absorbing medium has `k > 0`, and the
//! transmitted wave decays: `q = sqrt(N² − sin²β)` on the principal branch, `Im q ≥ 0`. With
//! `c = cosβ`: `rs = (c − q)/(c + q)`, `rp = (N²c − q)/(N²c + q)`, so that `rp(0) = −rs(0)`
//! (the psps basis of [`crate::optics::stokes`]; the same signs as NIST SCATMECH and as
//! Born & Wolf with their p-axis convention for the reflected beam).
//!
//! The formulas are written once, in real arithmetic, generic over the elementary-function
//! backend ([`index_squared`], [`transmitted_q`], [`reflectances`], [`amplitudes`]);
//! [`Fresnel::new`] (complex numbers for a reader) and the batch engine both call them.

use crate::error::{at_most, non_negative, positive, Result, MAX_INDEX};
use crate::numeric::math::{Math, Real, Std};
use num_complex::Complex64;

/// Complex refractive index `N = n + ik` of the reflecting medium, with `n > 0`, `k ≥ 0`
/// (time dependence `exp(−iωt)`, so absorption has `k > 0`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RefractiveIndex {
    n: f64,
    k: f64,
}

impl RefractiveIndex {
    /// `N = n + ik`.
    ///
    /// # Errors
    /// [`crate::Error::InvalidParameter`] unless `0 < n ≤ 10⁶` and `0 ≤ k ≤ 10⁶`
    /// ([`crate::error::MAX_INDEX`]).
    pub fn new(n: f64, k: f64) -> Result<Self> {
        const WHY: &str = "must be ≤ 1e6 (larger indices overflow the Fresnel arithmetic)";
        Ok(Self {
            n: at_most("n", positive("n", n)?, MAX_INDEX, WHY)?,
            k: at_most("k", non_negative("k", k)?, MAX_INDEX, WHY)?,
        })
    }

    /// Real part n.
    pub fn n(&self) -> f64 {
        self.n
    }

    /// Extinction coefficient k.
    pub fn k(&self) -> f64 {
        self.k
    }

    /// `N` as a complex number.
    pub fn complex(&self) -> Complex64 {
        Complex64::new(self.n, self.k)
    }

    /// `N² = (n² − k²) + i·2nk` as `(re, im)` ([`index_squared`]).
    pub fn squared(&self) -> (f64, f64) {
        index_squared(self.n, self.k)
    }

    /// Fresnel amplitudes at local incidence angle β (rad) (docs/model.md §3, eqs. 10–11).
    pub fn amplitudes(&self, beta: f64) -> Fresnel {
        Fresnel::new(self.complex(), beta)
    }

    /// The Brewster angle `atan(n)` of a dielectric (meaningful for `k = 0`).
    pub fn brewster_angle(&self) -> f64 {
        self.n.atan()
    }
}

/// Fresnel reflection amplitudes `rs`, `rp` at one local incidence angle (module
/// documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fresnel {
    /// s (perpendicular, TE) amplitude reflection coefficient.
    pub rs: Complex64,
    /// p (parallel, TM) amplitude reflection coefficient.
    pub rp: Complex64,
}

impl Fresnel {
    /// Amplitudes for index `index` at local incidence angle `beta` (rad, `0 ≤ β ≤ π/2`).
    pub fn new(index: Complex64, beta: f64) -> Self {
        let (s, c) = beta.sin_cos();
        let (n2r, n2i) = index_squared(index.re, index.im);
        Self::from_cos_sin2::<Std>(n2r, n2i, c.max(0.0), s * s)
    }

    /// Amplitudes from `N²`, `cosβ` and `sin²β` with backend `M` (what the model computes from
    /// a geometry, where `cosβ = |w_i + w_r|/2` and `sin²β` come in closed form).
    #[inline(always)]
    pub(crate) fn from_cos_sin2<M: Math<F = f64>>(
        n2r: f64,
        n2i: f64,
        c: f64,
        sin2_beta: f64,
    ) -> Self {
        let (qr, qi) = transmitted_q::<M>(n2r, n2i, sin2_beta);
        let [_, _, inv_s, inv_p] = reflectances::<M>(n2r, n2i, c, qr, qi);
        let [rs_r, rs_i, rp_r, rp_i] = amplitudes::<M>(n2r, n2i, c, qr, qi, inv_s, inv_p);
        Self {
            rs: Complex64::new(rs_r, rs_i),
            rp: Complex64::new(rp_r, rp_i),
        }
    }

    /// Unpolarized reflectance `R_F = (|rs|² + |rp|²)/2` (eq. 1).
    pub fn reflectance(&self) -> f64 {
        0.5 * (self.rs.norm_sqr() + self.rp.norm_sqr())
    }

    /// s-polarized reflectance `|rs|²`.
    pub fn reflectance_s(&self) -> f64 {
        self.rs.norm_sqr()
    }

    /// p-polarized reflectance `|rp|²`.
    pub fn reflectance_p(&self) -> f64 {
        self.rp.norm_sqr()
    }
}

/// `N² = (n² − k²) + i·(nk + kn)` as `(re, im)`, formed the same way on every path.
#[inline(always)]
pub fn index_squared(n: f64, k: f64) -> (f64, f64) {
    (n * n - k * k, n * k + k * n)
}

/// `q = sqrt(N² − sin²β)` on the principal branch (`Im q ≥ 0`, since `Im N² ≥ 0`), as
/// `(Re q, Im q)`: with `z = N² − sin²β`, `t = sqrt((|z| + |Re z|)/2)`, `q = t + i·Im z/(2t)`
/// when `Re z ≥ 0`, else `Im z/(2t) + i·t`. For a real `N²` this is `sqrt(z)` or `i·sqrt(−z)`.
#[inline(always)]
pub fn transmitted_q<M: Math>(n2r: M::F, n2i: M::F, sin2_beta: M::F) -> (M::F, M::F) {
    if n2i == M::F::ZERO {
        transmitted_q_real(n2r, sin2_beta)
    } else {
        transmitted_q_complex::<M>(n2r, n2i, sin2_beta)
    }
}

/// [`transmitted_q`] for a real `N²` (`k = 0`): `sqrt(z)` or `i·sqrt(−z)`, one square root and
/// no division — the values the complex formula gives for `Im z = 0` (tested).
#[inline(always)]
pub fn transmitted_q_real<T: Real>(n2r: T, sin2_beta: T) -> (T, T) {
    let zr = n2r - sin2_beta;
    let t = zr.abs().sqrt();
    if zr >= T::ZERO {
        (t, T::ZERO)
    } else {
        (T::ZERO, t)
    }
}

/// [`transmitted_q`] for any `N²` with `Im N² ≥ 0`.
#[inline(always)]
pub fn transmitted_q_complex<M: Math>(n2r: M::F, n2i: M::F, sin2_beta: M::F) -> (M::F, M::F) {
    let zr = n2r - sin2_beta;
    let nonneg = zr >= M::F::ZERO;
    let zabs = M::mla(zr, zr, n2i * n2i).sqrt();
    let t = (M::F::of(0.5) * (zabs + zr.abs())).sqrt();
    let other = n2i / (M::F::of(2.0) * if t > M::F::ZERO { t } else { M::F::ONE });
    if nonneg {
        (t, other)
    } else {
        (other, t)
    }
}

/// `[|rs|², |rp|², 1/|c + q|², 1/|N²c + q|²]` from `N²`, `c = cosβ` and `q`, with one division.
/// At `c + q = 0` (only `N = 1` at exactly grazing facet incidence) the grazing limit
/// `rs = rp = −1` is taken: `[1, 1, 0, 0]` (docs/model.md §9.5).
#[inline(always)]
pub fn reflectances<M: Math>(n2r: M::F, n2i: M::F, c: M::F, qr: M::F, qi: M::F) -> [M::F; 4] {
    let (zero, one) = (M::F::ZERO, M::F::ONE);
    let qi2 = qi * qi;
    let ns = M::mla(c - qr, c - qr, qi2);
    let ds = M::mla(c + qr, c + qr, qi2);
    let (nr, ni) = (n2r * c, n2i * c);
    let np = M::mla(nr - qr, nr - qr, (ni - qi) * (ni - qi));
    let dp = M::mla(nr + qr, nr + qr, (ni + qi) * (ni + qi));
    let prod = ds * dp;
    let degenerate = prod == zero;
    let inv = one / if degenerate { one } else { prod };
    let (inv_s, inv_p) = (dp * inv, ds * inv);
    if degenerate {
        [one, one, zero, zero]
    } else {
        [ns * inv_s, np * inv_p, inv_s, inv_p]
    }
}

/// `[Re rs, Im rs, Re rp, Im rp]`: `rs = (c − q)/(c + q)`, `rp = (N²c − q)/(N²c + q)` as
/// `num·conj(den)/|den|²`, with the reciprocals of [`reflectances`]; `rs = rp = −1` where those
/// are 0 (the grazing limit).
#[inline(always)]
pub fn amplitudes<M: Math>(
    n2r: M::F,
    n2i: M::F,
    c: M::F,
    qr: M::F,
    qi: M::F,
    inv_s: M::F,
    inv_p: M::F,
) -> [M::F; 4] {
    let (ar, ai) = (c - qr, -qi);
    let (br, bi) = (c + qr, qi);
    let (nr, ni) = (n2r * c, n2i * c);
    let (er, ei) = (nr - qr, ni - qi);
    let (fr, fi) = (nr + qr, ni + qi);
    let v = [
        M::mla(ar, br, ai * bi) * inv_s,
        M::mla(ai, br, -(ar * bi)) * inv_s,
        M::mla(er, fr, ei * fi) * inv_p,
        M::mla(ei, fr, -(er * fi)) * inv_p,
    ];
    let (zero, one) = (M::F::ZERO, M::F::ONE);
    if inv_s == zero {
        [-one, zero, -one, zero]
    } else {
        v
    }
}
