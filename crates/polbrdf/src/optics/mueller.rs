//! Mueller matrices in the psps basis (docs/model.md §2, §4, §6; eqs. 7–9, 12).
//!
//! A Mueller matrix `M` maps the Stokes vector of the incident beam, in the incident beam's psps
//! frame, to the Stokes vector of the outgoing beam in the outgoing beam's frame:
//! `S_out = M·S_in` (eq. 12). A pBRDF `F` is such a matrix in sr⁻¹. Both frames follow
//! [`crate::optics::stokes`]; so the mirror at normal incidence is `R_F·diag(1, 1, −1, −1)` here,
//! not the identity (the reflected frame's s axis is the incident one's, its p axis reversed).

use crate::numeric::math::{Math, Real};
use crate::optics::jones::Jones;
use crate::optics::stokes::Stokes;
use num_complex::Complex64;
use std::ops::{Add, Index, IndexMut, Mul};

/// The names of the 16 entries in row-major order, `m00 … m33` (`mIJ`: row `I`, column `J`):
/// the one list of the Mueller column names of every file and table (result CSV, measurement
/// CSV, lookup tables, fit quantities, the explorer's maps, the Python module).
pub const COLUMNS: [&str; 16] = [
    "m00", "m01", "m02", "m03", "m10", "m11", "m12", "m13", "m20", "m21", "m22", "m23", "m30",
    "m31", "m32", "m33",
];

/// A real 4×4 Mueller matrix (or pBRDF, in sr⁻¹), row-major, psps basis. `m[(i, j)]` is the
/// entry of row `i` (output component `S_i`) and column `j` (input component `S_j`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mueller(pub [[f64; 4]; 4]);

impl Mueller {
    /// The names of the entries, row-major ([`COLUMNS`]).
    pub const COLUMNS: [&str; 16] = COLUMNS;

    /// The row and column of the entry named `name` (`"m12"` → `(1, 2)`), or `None` for a
    /// name not in [`COLUMNS`].
    pub fn entry_of(name: &str) -> Option<(usize, usize)> {
        COLUMNS
            .iter()
            .position(|c| *c == name)
            .map(|k| (k / 4, k % 4))
    }

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
    /// term (eq. 9 as corrected, docs/model.md §6).
    pub fn depolarizer() -> Self {
        Self::diagonal([1.0, 0.0, 0.0, 0.0])
    }

    /// Mueller matrix of the frame rotation `Jones::rotation(x)`:
    /// `[[1,0,0,0],[0,cos2x,−sin2x,0],[0,sin2x,cos2x,0],[0,0,0,1]]`. It maps Stokes components
    /// given in a frame turned by `x` (from s toward p) back into the original frame: the
    /// linear polarization turns by `+x` (its AoLP grows by `x`), S0 and S3 are unchanged.
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
    /// `A = [[1,0,0,1],[1,0,0,−1],[0,1,1,0],[0,i,−i,0]]` (docs/model.md §4; Bohren & Huffman,
    /// *Absorption and Scattering of Light by Small Particles*, 1983, §3.3), written out entry by
    /// entry. The sign of row/column 3 follows `S3 = −2Im(E_s E_p*)`.
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

    /// `F00`: the scalar BRDF of a pBRDF (the output intensity for unit unpolarized input).
    pub fn m00(&self) -> f64 {
        self.0[0][0]
    }

    /// The first column `(M00, M10, M20, M30)`: the output for unpolarized input of unit
    /// intensity.
    pub fn first_column(&self) -> Stokes {
        Stokes([self.0[0][0], self.0[1][0], self.0[2][0], self.0[3][0]])
    }

    /// The first row `(M00, M01, M02, M03)`: the output intensity for each input component.
    pub fn first_row(&self) -> [f64; 4] {
        self.0[0]
    }

    /// From 16 entries in row-major order.
    pub fn from_row_major(v: &[f64; 16]) -> Self {
        Self(std::array::from_fn(|r| {
            std::array::from_fn(|c| v[4 * r + c])
        }))
    }

    /// The transpose.
    pub fn transpose(&self) -> Self {
        Self(std::array::from_fn(|r| {
            std::array::from_fn(|c| self.0[c][r])
        }))
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
        self.first_column().dolp()
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
        let (mut ev, _) = crate::numeric::linalg::symmetric_eigen(m);
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

impl Index<(usize, usize)> for Mueller {
    type Output = f64;
    fn index(&self, (r, c): (usize, usize)) -> &f64 {
        &self.0[r][c]
    }
}

impl IndexMut<(usize, usize)> for Mueller {
    fn index_mut(&mut self, (r, c): (usize, usize)) -> &mut f64 {
        &mut self.0[r][c]
    }
}

/// The coefficients of the Mueller matrix of `diag(rs, rp)` (a diattenuating retarder aligned
/// with s and p): `M_d = [[A, B, 0, 0], [B, A, 0, 0], [0, 0, C, S], [0, 0, −S, C]]` with
/// `A = (|rs|² + |rp|²)/2`, `B = (|rs|² − |rp|²)/2`, `C + iS = rs·rp*` — [`Mueller::from_jones`]
/// of the diagonal matrix. Takes `|rs|²`, `|rp|²` and the real and imaginary parts of rs, rp.
#[inline(always)]
pub fn diagonal_coefficients<M: Math>(
    rs2: M::F,
    rp2: M::F,
    [rs_r, rs_i, rp_r, rp_i]: [M::F; 4],
) -> [M::F; 4] {
    let [a, b] = intensity_coefficients(rs2, rp2);
    [
        a,
        b,
        M::mla(rs_r, rp_r, rs_i * rp_i),
        M::mla(rs_i, rp_r, -(rs_r * rp_i)),
    ]
}

/// `[A, B] = [(|rs|² + |rp|²)/2, (|rs|² − |rp|²)/2]`: the first two coefficients of
/// [`diagonal_coefficients`], all that the intensity and the linear polarization for
/// unpolarized input need (`A = R_F`, eq. 1).
#[inline(always)]
pub fn intensity_coefficients<T: Real>(rs2: T, rp2: T) -> [T; 2] {
    let half = T::of(0.5);
    [half * (rs2 + rp2), half * (rs2 - rp2)]
}

/// The model's pBRDF, row-major (docs/model.md §6, §12):
/// `F = R(η_r)·(g·M_d)·R(−η_i) + f_v·diag(1, 0, 0, 0)`, the Mueller matrix of
/// `T = Rot(η_r)·diag(rs, rp)·Rot(−η_i)` (eq. 11) scaled by `g = f_s/M00`, plus the unpolarized
/// volume term (eq. 9 corrected).
///
/// `gm = [g·A, g·B, g·C, g·S]` ([`diagonal_coefficients`] times g); `rot` = `[cos2η_i, sin2η_i,
/// cos2η_r, sin2η_r]` ([`crate::geometry::angles::rotations`]); `R` is [`Mueller::rotator`].
/// That this equals [`Mueller::from_jones`] of T is tested.
#[inline(always)]
pub fn facet_pbrdf<M: Math>(gm: [M::F; 4], fv: M::F, rot: [M::F; 4]) -> [M::F; 16] {
    let zero = M::F::ZERO;
    let [ga, gb, gc, gs] = gm;
    let [ci2, si2, cr2, sr2] = rot;
    let p1 = ga * ci2;
    let p2 = ga * si2;
    let q1 = gc * si2;
    let q2 = gc * ci2;
    [
        ga + fv,
        gb * ci2,
        gb * si2,
        zero,
        cr2 * gb,
        M::mla(cr2, p1, sr2 * q1),
        M::mla(cr2, p2, -(sr2 * q2)),
        -(sr2 * gs),
        sr2 * gb,
        M::mla(sr2, p1, -(cr2 * q1)),
        M::mla(sr2, p2, cr2 * q2),
        cr2 * gs,
        zero,
        gs * si2,
        -(gs * ci2),
        gc,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_column_names_are_row_major_and_name_their_entries() {
        for (k, name) in COLUMNS.iter().enumerate() {
            let (i, j) = (k / 4, k % 4);
            assert_eq!(*name, format!("m{i}{j}"));
            assert_eq!(Mueller::entry_of(name), Some((i, j)));
        }
        for bad in ["m44", "m4", "m000", "M00", "m0x", ""] {
            assert_eq!(Mueller::entry_of(bad), None, "{bad}");
        }
    }
}
