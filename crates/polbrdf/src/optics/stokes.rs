//! Stokes vectors in the psps basis (docs/model.md §2), and the degrees and angle of
//! polarization — defined here once for every path of the crate.
//!
//! **Basis.** Each beam has a right-handed frame (s, p, k): `k` the propagation direction,
//! `s = unit(z × k)`, `p = k × s` (NIST SCATMECH's "psps" basis, time dependence `exp(−iωt)`).
//! With the field `E = Re[(E_s·s + E_p·p)·exp(−iωt)]`:
//! `S = (|E_s|² + |E_p|², |E_s|² − |E_p|², 2Re(E_s E_p*), −2Im(E_s E_p*))`.
//!
//! - `S1 > 0`: more s than p (s-polarized is `(1, 1, 0, 0)`); `S2 > 0`: more light polarized at
//!   +45° from s toward p than at −45°.
//! - **Handedness.** `S3 > 0` is the field `E_s = 1, E_p = i`, i.e.
//!   `E(t) = cos ωt·s + sin ωt·p`: it turns from s toward p, a positive rotation about the
//!   direction of propagation k — counterclockwise as seen by a receiver looking back toward the
//!   source. That is *left*-circular in the optics convention of Born & Wolf (handedness judged
//!   by the receiver) and positive helicity (right-handed about k) in the IEEE/engineering
//!   convention.
//! - AoLP is measured from s toward p, in (−90°, 90°].

use crate::numeric::math::{Math, Real, Std};
use num_complex::Complex64;
use std::ops::{Index, IndexMut};

/// A Stokes vector `(S0, S1, S2, S3)` in a beam's psps basis (module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stokes(pub [f64; 4]);

impl Stokes {
    /// `(s0, s1, s2, s3)`.
    pub fn new(s0: f64, s1: f64, s2: f64, s3: f64) -> Self {
        Self([s0, s1, s2, s3])
    }

    /// Unpolarized light of unit intensity, `(1, 0, 0, 0)`.
    pub fn unpolarized() -> Self {
        Self([1.0, 0.0, 0.0, 0.0])
    }

    /// Fully linearly polarized light of unit intensity at angle `psi` (rad) from the s axis
    /// toward the p axis: `(1, cos2ψ, sin2ψ, 0)`.
    pub fn linear(psi: f64) -> Self {
        let (s, c) = (2.0 * psi).sin_cos();
        Self([1.0, c, s, 0.0])
    }

    /// s-polarized light, `(1, 1, 0, 0)`.
    pub fn s_polarized() -> Self {
        Self([1.0, 1.0, 0.0, 0.0])
    }

    /// p-polarized light, `(1, −1, 0, 0)`.
    pub fn p_polarized() -> Self {
        Self([1.0, -1.0, 0.0, 0.0])
    }

    /// Fully circularly polarized light of unit intensity, `(1, 0, 0, ±1)`; `+1` turns from s
    /// toward p (handedness: module documentation).
    pub fn circular(sign: f64) -> Self {
        Self([1.0, 0.0, 0.0, sign.signum()])
    }

    /// The Stokes vector of a Jones vector `(E_s, E_p)` (module documentation).
    pub fn from_field(es: Complex64, ep: Complex64) -> Self {
        let x = es * ep.conj();
        Self([
            es.norm_sqr() + ep.norm_sqr(),
            es.norm_sqr() - ep.norm_sqr(),
            2.0 * x.re,
            -2.0 * x.im,
        ])
    }

    /// Intensity S0.
    pub fn s0(&self) -> f64 {
        self.0[0]
    }
    /// S1 (s minus p).
    pub fn s1(&self) -> f64 {
        self.0[1]
    }
    /// S2 (+45° minus −45°).
    pub fn s2(&self) -> f64 {
        self.0[2]
    }
    /// S3 (circular; sign convention in the module documentation).
    pub fn s3(&self) -> f64 {
        self.0[3]
    }

    /// Intensity S0.
    pub fn intensity(&self) -> f64 {
        self.0[0]
    }

    /// Degree of linear polarization `sqrt(S1² + S2²)/S0` (eq. 13); 0 when `S0 ≤ 0`.
    pub fn dolp(&self) -> f64 {
        dolp(self.0[1].hypot(self.0[2]), self.0[0])
    }

    /// Degree of polarization `sqrt(S1² + S2² + S3²)/S0`; 0 when `S0 ≤ 0`.
    pub fn dop(&self) -> f64 {
        let [s0, s1, s2, s3] = self.0;
        // hypot: squares of a tiny (or huge) radiance would underflow (overflow).
        ratio(s1.hypot(s2).hypot(s3), s0)
    }

    /// Degree of circular polarization `S3/S0`; 0 when `S0 ≤ 0`.
    pub fn docp(&self) -> f64 {
        ratio(self.0[3], self.0[0])
    }

    /// Angle of linear polarization `½·atan2(S2, S1)` (rad, in (−π/2, π/2], measured from the
    /// s axis toward the p axis); 0 for light with no linear polarization.
    pub fn aolp(&self) -> f64 {
        aolp::<Std>(self.0[1], self.0[2])
    }

    /// `a·self + b·other`.
    pub fn combine(&self, a: f64, other: &Stokes, b: f64) -> Stokes {
        Stokes(std::array::from_fn(|i| a * self.0[i] + b * other.0[i]))
    }

    /// Every component multiplied by `s`.
    pub fn scaled(&self, s: f64) -> Stokes {
        Stokes(self.0.map(|v| v * s))
    }
}

impl Index<usize> for Stokes {
    type Output = f64;
    fn index(&self, i: usize) -> &f64 {
        &self.0[i]
    }
}

impl IndexMut<usize> for Stokes {
    fn index_mut(&mut self, i: usize) -> &mut f64 {
        &mut self.0[i]
    }
}

impl std::ops::Add for Stokes {
    type Output = Stokes;
    fn add(self, rhs: Stokes) -> Stokes {
        Stokes(std::array::from_fn(|i| self.0[i] + rhs.0[i]))
    }
}

/// `num/den`, or 0 when `den ≤ 0` (no light).
#[inline(always)]
fn ratio<T: Real>(num: T, den: T) -> T {
    if den > T::ZERO {
        num / den
    } else {
        T::ZERO
    }
}

/// The DoLP from the magnitude of the linear part, `lin = sqrt(S1² + S2²)`, and `S0` (eq. 13);
/// 0 when `S0 ≤ 0`. [`Stokes::dolp`] and the batch engine (which knows `lin` in closed form)
/// both use it.
#[inline(always)]
pub fn dolp<T: Real>(lin: T, s0: T) -> T {
    ratio(lin, s0)
}

/// The AoLP `½·atan2(S2, S1)` (rad, in (−π/2, π/2], from s toward p), with the arctangent of
/// backend `M`. [`Stokes::aolp`] and the batch engine both use it.
#[inline(always)]
pub fn aolp<M: Math>(s1: M::F, s2: M::F) -> M::F {
    M::F::of(0.5) * M::atan2(s2, s1)
}
