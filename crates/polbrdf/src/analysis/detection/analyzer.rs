//! The sensor's polarization channels (detection.md §2): linear analyzers at angles `α_k`,
//! principal transmittances `q ≥ r ≥ 0`, a camera roll `ρ`, the analysis matrix `W` and the
//! pseudo-inverse `W₃⁺` of its first three columns.

use crate::error::{Error, Result};
use crate::optics::stokes::Stokes;

/// The most analyzer channels of a sensor.
pub const MAX_CHANNELS: usize = 64;

/// `K ≥ 3` linear analyzers (detection.md §2), with the pseudo-inverse of `W₃` computed once.
#[derive(Debug, Clone, PartialEq)]
pub struct Analyzer {
    /// Analyzer angles `α_k` (rad), from s toward p in the camera's frame.
    angles: Vec<f64>,
    /// Principal transmittances.
    q: f64,
    r: f64,
    /// Camera roll `ρ` (rad).
    roll: f64,
    /// The rows `a_k` of `W`.
    rows: Vec<[f64; 4]>,
    /// The columns of `W₃⁺` (3×K): column `k` multiplies channel `k`.
    pinv: Vec<[f64; 3]>,
}

impl Analyzer {
    /// Analyzers at `angles` (rad) with principal transmittances `q ≥ r ≥ 0` (`q > r`: some
    /// polarization sensitivity) and camera roll `roll` (rad) (detection.md §2).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `q`, `r` (finite, `1 ≥ q > r ≥ 0`) or `roll`
    /// (finite); [`Error::InvalidParameterAt`] naming `analyzer_angles` for a non-finite angle;
    /// [`Error::InconsistentParameters`] for fewer than 3 or more than [`MAX_CHANNELS`]
    /// channels, or angles that do not determine S0, S1, S2 (`W₃` of rank < 3, e.g. all angles
    /// equal modulo 180°).
    pub fn new(angles: Vec<f64>, q: f64, r: f64, roll: f64) -> Result<Self> {
        let bad = |name, value, reason| Error::InvalidParameter {
            name,
            value,
            reason,
        };
        if !(q.is_finite() && q > 0.0 && q <= 1.0) {
            return Err(bad("q", q, "must lie in (0, 1]"));
        }
        if !(r.is_finite() && r >= 0.0 && r < q) {
            return Err(bad(
                "r",
                r,
                "must be finite, >= 0 and below q (an analyzer that polarizes)",
            ));
        }
        if !roll.is_finite() {
            return Err(bad("roll", roll, "must be finite"));
        }
        if angles.len() < 3 || angles.len() > MAX_CHANNELS {
            return Err(Error::InconsistentParameters(format!(
                "a polarimeter needs between 3 and {MAX_CHANNELS} analyzer angles, got {}",
                angles.len()
            )));
        }
        if let Some((i, &a)) = angles.iter().enumerate().find(|(_, a)| !a.is_finite()) {
            return Err(Error::InvalidParameterAt {
                name: "analyzer_angles",
                value: a,
                index: i,
                reason: "must be finite",
            });
        }
        let rows: Vec<[f64; 4]> = angles
            .iter()
            .map(|&a| analysis_vector(a - roll, q, r))
            .collect();
        let pinv = pseudo_inverse(&rows).ok_or_else(|| {
            Error::InconsistentParameters(
                "the analyzer angles do not determine S0, S1 and S2 (W₃ has rank < 3): give at \
                 least three angles distinct modulo 180°"
                    .into(),
            )
        })?;
        Ok(Self {
            angles,
            q,
            r,
            roll,
            rows,
            pinv,
        })
    }

    /// As [`Analyzer::new`] with the extinction ratio `ER = q/r` (∞: an ideal analyzer).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `extinction_ratio` unless `ER > 1` (∞ allowed); as
    /// [`Analyzer::new`].
    pub fn with_extinction_ratio(angles: Vec<f64>, q: f64, er: f64, roll: f64) -> Result<Self> {
        if er.is_nan() || er <= 1.0 {
            return Err(Error::InvalidParameter {
                name: "extinction_ratio",
                value: er,
                reason: "must be > 1 (inf: an ideal analyzer)",
            });
        }
        Self::new(angles, q, q / er, roll)
    }

    /// The ideal division-of-focal-plane camera: `α = 0°, 45°, 90°, 135°`, `q = 1`, `r = 0`,
    /// no roll.
    pub fn ideal_dofp() -> Self {
        let angles = [0.0f64, 45.0, 90.0, 135.0].map(f64::to_radians).to_vec();
        Self::new(angles, 1.0, 0.0, 0.0).expect("valid analyzers")
    }

    /// The analyzer angles `α_k` (rad).
    pub fn angles(&self) -> &[f64] {
        &self.angles
    }
    /// `q`.
    pub fn q(&self) -> f64 {
        self.q
    }
    /// `r`.
    pub fn r(&self) -> f64 {
        self.r
    }
    /// The camera roll `ρ` (rad).
    pub fn roll(&self) -> f64 {
        self.roll
    }
    /// `ER = q/r` (∞ for `r = 0`).
    pub fn extinction_ratio(&self) -> f64 {
        self.q / self.r
    }
    /// The number of channels `K`.
    pub fn channels(&self) -> usize {
        self.rows.len()
    }
    /// The analysis matrix `W` (K×4), its rows `a_k` (detection.md §2).
    pub fn matrix(&self) -> &[[f64; 4]] {
        &self.rows
    }
    /// The columns of `W₃⁺` (3×K, detection.md §4): `Ŝ = Σ_k I_k·c_k`.
    pub fn pseudo_inverse(&self) -> &[[f64; 3]] {
        &self.pinv
    }
    /// The channel values `I_k = a_k·S` (detection.md §2), into `out` (cleared first).
    pub fn measure_into(&self, s: &Stokes, out: &mut Vec<f64>) {
        out.clear();
        out.extend(
            self.rows
                .iter()
                .map(|a| a[0] * s.0[0] + a[1] * s.0[1] + a[2] * s.0[2] + a[3] * s.0[3]),
        );
    }
    /// The channel values `I_k = a_k·S`.
    pub fn measure(&self, s: &Stokes) -> Vec<f64> {
        let mut out = Vec::with_capacity(self.rows.len());
        self.measure_into(s, &mut out);
        out
    }
}

/// `a = ½·(q + r, (q − r)·cos 2α', (q − r)·sin 2α', 0)` at `α' = α − ρ` (detection.md §2).
pub fn analysis_vector(alpha_prime: f64, q: f64, r: f64) -> [f64; 4] {
    let (s, c) = (2.0 * alpha_prime).sin_cos();
    [0.5 * (q + r), 0.5 * (q - r) * c, 0.5 * (q - r) * s, 0.0]
}

/// The Moore–Penrose pseudo-inverse of `W₃` (the first three columns of `rows`), as its K
/// columns: `(W₃ᵀW₃)⁻¹W₃ᵀ` (detection.md §4); `None` when `W₃` has rank < 3 (relative to
/// its scale).
pub fn pseudo_inverse(rows: &[[f64; 4]]) -> Option<Vec<[f64; 3]>> {
    let mut g = [[0.0f64; 3]; 3];
    for a in rows {
        for i in 0..3 {
            for j in 0..3 {
                g[i][j] += a[i] * a[j];
            }
        }
    }
    let inv = invert3(&g)?;
    Some(
        rows.iter()
            .map(|a| {
                let mut c = [0.0; 3];
                for (i, ci) in c.iter_mut().enumerate() {
                    *ci = (0..3).map(|j| inv[i][j] * a[j]).sum();
                }
                c
            })
            .collect(),
    )
}

/// The inverse of a symmetric 3×3 matrix by cofactors; `None` when it is singular relative to
/// its scale (`|det| ≤ 1e-12·‖g‖³`).
pub fn invert3(g: &[[f64; 3]; 3]) -> Option<[[f64; 3]; 3]> {
    let c = |i: usize, j: usize| {
        let (i1, i2) = ((i + 1) % 3, (i + 2) % 3);
        let (j1, j2) = ((j + 1) % 3, (j + 2) % 3);
        g[i1][j1] * g[i2][j2] - g[i1][j2] * g[i2][j1]
    };
    let det = g[0][0] * c(0, 0) + g[0][1] * c(0, 1) + g[0][2] * c(0, 2);
    let scale = g.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    if !(det.is_finite() && det.abs() > 1e-12 * scale.powi(3)) {
        return None;
    }
    let mut inv = [[0.0; 3]; 3];
    for (i, row) in inv.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            // inverse = adjugate / det, adjugate = cofactor transposed
            *x = c(j, i) / det;
        }
    }
    Some(inv)
}
