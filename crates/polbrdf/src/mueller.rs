//! Mueller matrices and Stokes vectors in the psps basis (spec §2–3, §5; eqs. 7–9, 12–13).

use crate::jones::Jones;
use num_complex::Complex64;
use std::ops::{Add, Mul};

/// A Stokes vector `(S0, S1, S2, S3)`, psps basis: `S0 = |Es|²+|Ep|²`, `S1 = |Es|²−|Ep|²`,
/// `S2 = 2Re(Es Ep*)`, `S3 = −2Im(Es Ep*)`; `(1, 1, 0, 0)` is s-polarized (spec §2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stokes(pub [f64; 4]);

impl Stokes {
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

    /// Fully circularly polarized light of unit intensity, `(1, 0, 0, ±1)`.
    pub fn circular(sign: f64) -> Self {
        Self([1.0, 0.0, 0.0, sign.signum()])
    }

    /// The Stokes vector of a Jones vector `(E_s, E_p)` (spec §2).
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
    pub fn intensity(&self) -> f64 {
        self.0[0]
    }

    /// Degree of linear polarization `sqrt(S1² + S2²)/S0` (eq. 13); 0 when `S0 ≤ 0`.
    pub fn dolp(&self) -> f64 {
        ratio(self.0[1].hypot(self.0[2]), self.0[0])
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
        0.5 * self.0[2].atan2(self.0[1])
    }
}

fn ratio(num: f64, den: f64) -> f64 {
    if den > 0.0 {
        num / den
    } else {
        0.0
    }
}

/// A real 4×4 Mueller matrix (or pBRDF, in sr⁻¹), row-major, psps basis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mueller(pub [[f64; 4]; 4]);

impl Mueller {
    /// The zero matrix (what the model returns for directions at or below the horizon).
    pub fn zero() -> Self {
        Self([[0.0; 4]; 4])
    }

    /// The identity.
    pub fn identity() -> Self {
        Self::diagonal([1.0; 4])
    }

    /// `diag(d)`.
    pub fn diagonal(d: [f64; 4]) -> Self {
        let mut m = [[0.0; 4]; 4];
        for (i, v) in d.into_iter().enumerate() {
            m[i][i] = v;
        }
        Self(m)
    }

    /// The ideal depolarizer `diag(1, 0, 0, 0)`: the polarization form of the unpolarized volume
    /// term (eq. 9 as corrected, spec §5).
    pub fn depolarizer() -> Self {
        Self::diagonal([1.0, 0.0, 0.0, 0.0])
    }

    /// Mueller matrix of the frame rotation `Jones::rotation(x)`:
    /// `[[1,0,0,0],[0,cos2x,−sin2x,0],[0,sin2x,cos2x,0],[0,0,0,1]]`.
    pub fn rotator(x: f64) -> Self {
        let (s, c) = (2.0 * x).sin_cos();
        Self([
            [1.0, 0.0, 0.0, 0.0],
            [0.0, c, -s, 0.0],
            [0.0, s, c, 0.0],
            [0.0, 0.0, 0.0, 1.0],
        ])
    }

    /// Bohren & Huffman's Mueller matrix of a Jones matrix, `M = A (T ⊗ T*) A⁻¹` with
    /// `A = [[1,0,0,1],[1,0,0,−1],[0,1,1,0],[0,i,−i,0]]` (spec §3), written out entry by entry.
    /// With `T = [[a, b], [c, d]]`:
    /// `M00 = ½(|a|²+|b|²+|c|²+|d|²)`, `M02 = Re(ab* + cd*)`, `M30 = −Im(ac* + bd*)`, …
    pub fn from_jones(t: &Jones) -> Self {
        let [[a, b], [c, d]] = t.0;
        let (aa, bb, cc, dd) = (a.norm_sqr(), b.norm_sqr(), c.norm_sqr(), d.norm_sqr());
        let ab = a * b.conj();
        let cd = c * d.conj();
        let ac = a * c.conj();
        let bd = b * d.conj();
        let ad = a * d.conj();
        let bc = b * c.conj();
        Self([
            [
                0.5 * (aa + bb + cc + dd),
                0.5 * (aa - bb + cc - dd),
                (ab + cd).re,
                (ab + cd).im,
            ],
            [
                0.5 * (aa + bb - cc - dd),
                0.5 * (aa - bb - cc + dd),
                (ab - cd).re,
                (ab - cd).im,
            ],
            [(ac + bd).re, (ac - bd).re, (ad + bc).re, (ad - bc).im],
            [-(ac + bd).im, -(ac - bd).im, -(ad + bc).im, (ad - bc).re],
        ])
    }

    /// Element `(row, col)`.
    pub fn get(&self, row: usize, col: usize) -> f64 {
        self.0[row][col]
    }

    /// Every entry multiplied by `s`.
    pub fn scaled(&self, s: f64) -> Self {
        let mut m = self.0;
        m.iter_mut().flatten().for_each(|v| *v *= s);
        Self(m)
    }

    /// The 16 entries, row-major.
    pub fn to_row_major(&self) -> [f64; 16] {
        let mut out = [0.0; 16];
        for (i, row) in self.0.iter().enumerate() {
            out[4 * i..4 * i + 4].copy_from_slice(row);
        }
        out
    }

    /// `F · S_in` (eq. 12).
    pub fn apply(&self, s: &Stokes) -> Stokes {
        let mut out = [0.0; 4];
        for (o, row) in out.iter_mut().zip(&self.0) {
            *o = row.iter().zip(&s.0).map(|(m, v)| m * v).sum();
        }
        Stokes(out)
    }

    /// DoLP of the output for unpolarized input, `sqrt(F10² + F20²)/F00` (eq. 13); 0 when
    /// `F00 = 0`.
    pub fn dolp_unpolarized(&self) -> f64 {
        self.apply(&Stokes::unpolarized()).dolp()
    }

    /// The 4×4 Hermitian coherency (Cloude) matrix `C`, obtained by reshuffling
    /// `W = A⁻¹ M A` so that a Jones-derived matrix gives `C = vec(T) vec(T)†`. `M` is
    /// physically realizable (a sum of non-depolarizing systems) iff `C` is positive
    /// semidefinite.
    pub fn coherency(&self) -> [[Complex64; 4]; 4] {
        let o = Complex64::new(0.0, 0.0);
        let r = |v: f64| Complex64::new(v, 0.0);
        let i = Complex64::new(0.0, 1.0);
        let a = [
            [r(1.0), o, o, r(1.0)],
            [r(1.0), o, o, r(-1.0)],
            [o, r(1.0), r(1.0), o],
            [o, i, -i, o],
        ];
        let ainv = [
            [r(0.5), r(0.5), o, o],
            [o, o, r(0.5), -0.5 * i],
            [o, o, r(0.5), 0.5 * i],
            [r(0.5), r(-0.5), o, o],
        ];
        let mut ma = [[o; 4]; 4];
        for (row, out) in self.0.iter().zip(ma.iter_mut()) {
            for (j, v) in out.iter_mut().enumerate() {
                *v = (0..4).map(|k| a[k][j] * row[k]).sum();
            }
        }
        let mut w = [[o; 4]; 4];
        for (ai, out) in ainv.iter().zip(w.iter_mut()) {
            for (j, v) in out.iter_mut().enumerate() {
                *v = (0..4).map(|k| ai[k] * ma[k][j]).sum();
            }
        }
        let mut c = [[o; 4]; 4];
        for (p, row) in c.iter_mut().enumerate() {
            for (q, v) in row.iter_mut().enumerate() {
                let (ii, jj) = (p / 2, p % 2);
                let (kk, ll) = (q / 2, q % 2);
                *v = w[2 * ii + kk][2 * jj + ll];
            }
        }
        c
    }

    /// Eigenvalues of the coherency matrix, ascending. All `≥ 0` (to rounding) for a physically
    /// realizable matrix; their sum is `2·M00`.
    pub fn coherency_eigenvalues(&self) -> [f64; 4] {
        // The Jacobi iteration's convergence test squares the entries: work on F/max|F_ij| so
        // that a tiny pBRDF (e.g. D ~ 1e-236 far outside a narrow lobe) or a huge one is not
        // declared converged before the first rotation, then scale back.
        let max = self.0.iter().flatten().fold(0.0_f64, |m, v| m.max(v.abs()));
        let finite = self.0.iter().flatten().all(|v| v.is_finite());
        let scale = if finite && max > 0.0 { max } else { 1.0 };
        let c = Self(self.0.map(|row| row.map(|v| v / scale))).coherency();
        // Real symmetric 8×8 embedding [[Re C, −Im C], [Im C, Re C]]: each eigenvalue twice.
        let mut m = [[0.0; 8]; 8];
        for p in 0..4 {
            for q in 0..4 {
                m[p][q] = c[p][q].re;
                m[p + 4][q + 4] = c[p][q].re;
                m[p][q + 4] = -c[p][q].im;
                m[p + 4][q] = c[p][q].im;
            }
        }
        let (mut ev, _) = crate::linalg::symmetric_eigen(m);
        ev.sort_by(f64::total_cmp);
        [ev[0], ev[2], ev[4], ev[6]].map(|v| v * scale)
    }

    /// True when the coherency matrix is positive semidefinite to within `tol·M00`.
    pub fn is_physically_realizable(&self, tol: f64) -> bool {
        let scale = self.0[0][0].abs().max(f64::MIN_POSITIVE);
        self.coherency_eigenvalues()[0] >= -tol * scale
    }
}

impl Mul for Mueller {
    type Output = Mueller;
    fn mul(self, rhs: Mueller) -> Mueller {
        let mut out = [[0.0; 4]; 4];
        for (i, row) in out.iter_mut().enumerate() {
            for (j, v) in row.iter_mut().enumerate() {
                *v = (0..4).map(|k| self.0[i][k] * rhs.0[k][j]).sum();
            }
        }
        Mueller(out)
    }
}

impl Add for Mueller {
    type Output = Mueller;
    fn add(self, rhs: Mueller) -> Mueller {
        let mut out = self.0;
        for (o, r) in out.iter_mut().flatten().zip(rhs.0.iter().flatten()) {
            *o += r;
        }
        Mueller(out)
    }
}

impl Mul<Stokes> for Mueller {
    type Output = Stokes;
    fn mul(self, rhs: Stokes) -> Stokes {
        self.apply(&rhs)
    }
}
