//! Jones matrices in the psps basis (docs/model.md §2, §4; eq. 11).
//!
//! A Jones matrix maps the complex amplitudes `(E_s, E_p)` of the incident beam (its psps frame,
//! time dependence `exp(−iωt)`) to those of the outgoing beam (its own psps frame).

use crate::optics::fresnel::Fresnel;
use num_complex::Complex64;
use std::ops::Mul;

/// A 2×2 Jones matrix acting on `(E_s, E_p)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jones(pub [[Complex64; 2]; 2]);

impl Jones {
    /// The identity.
    pub fn identity() -> Self {
        Self::diagonal(Complex64::new(1.0, 0.0), Complex64::new(1.0, 0.0))
    }

    /// `diag(a, b)`.
    pub fn diagonal(a: Complex64, b: Complex64) -> Self {
        let z = Complex64::new(0.0, 0.0);
        Self([[a, z], [z, b]])
    }

    /// Frame rotation `Rot(x) = [[cos x, −sin x], [sin x, cos x]]` (docs/model.md §4): the
    /// components in a frame whose s axis is turned by `x` from s toward p, expressed in the
    /// original frame (a positive `x` turns the field vector's direction from s toward p).
    pub fn rotation(x: f64) -> Self {
        let (s, c) = x.sin_cos();
        let r = |v: f64| Complex64::new(v, 0.0);
        Self([[r(c), r(-s)], [r(s), r(c)]])
    }

    /// The microfacet reflection of eq. 11: `T = Rot(η_r) · diag(rs, rp) · Rot(−η_i)`, mapping the
    /// incident beam's (s, p) components to the reflected beam's (docs/model.md §4), with the
    /// signed Priest–Meier angles η of [`crate::AngleVariables`].
    pub fn microfacet(fresnel: &Fresnel, eta_i: f64, eta_r: f64) -> Self {
        Self::rotation(eta_r) * Self::diagonal(fresnel.rs, fresnel.rp) * Self::rotation(-eta_i)
    }
}

impl Mul for Jones {
    type Output = Jones;
    fn mul(self, rhs: Jones) -> Jones {
        let (a, b) = (self.0, rhs.0);
        let mut out = [[Complex64::new(0.0, 0.0); 2]; 2];
        for (i, row) in out.iter_mut().enumerate() {
            for (j, v) in row.iter_mut().enumerate() {
                *v = a[i][0] * b[0][j] + a[i][1] * b[1][j];
            }
        }
        Jones(out)
    }
}
