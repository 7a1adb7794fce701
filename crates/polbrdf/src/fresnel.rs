//! Fresnel reflection amplitudes for a complex index `N = n + ik` (spec §2; the a_ss, a_pp of
//! eq. 10–11 and R_F of eq. 1).

use crate::error::{at_most, non_negative, positive, Result, MAX_INDEX};
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

    /// Fresnel amplitudes at local incidence angle β (rad) (spec §2, eq. 10–11).
    pub fn amplitudes(&self, beta: f64) -> Fresnel {
        Fresnel::new(self.complex(), beta)
    }

    /// The Brewster angle `atan(n)` of a dielectric (meaningful for `k = 0`).
    pub fn brewster_angle(&self) -> f64 {
        self.n.atan()
    }
}

/// Fresnel reflection amplitudes `rs`, `rp` at one local incidence angle (spec §2):
/// `c = cosβ`, `q = sqrt(N² − sin²β)` (principal branch, `Im q ≥ 0`),
/// `rs = (c − q)/(c + q)`, `rp = (N²c − q)/(N²c + q)`; hence `rp(0) = −rs(0)`.
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
        let c = c.max(0.0);
        let n2 = index * index;
        let mut q = (n2 - s * s).sqrt();
        if q.im < 0.0 {
            // Decaying transmitted wave for exp(−iωt): Im q ≥ 0 (guards a −0.0 imaginary part).
            q = -q;
        }
        let ratio = |num: Complex64, den: Complex64| {
            if den.norm_sqr() > 0.0 {
                num / den
            } else {
                // c = 0 and q = 0 (N = 1 at exact grazing): the grazing limit is −1.
                Complex64::new(-1.0, 0.0)
            }
        };
        Self {
            rs: ratio(c - q, c + q),
            rp: ratio(n2 * c - q, n2 * c + q),
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
