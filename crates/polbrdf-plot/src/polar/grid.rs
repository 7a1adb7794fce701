//! The data of a polar map: values on a regular grid of viewing directions (θ rows, φ columns
//! over one full turn) and their bilinear interpolation at any direction.

use crate::error::{Error, Result};

/// Values on a regular grid of viewing directions: rows of constant zenith angle θ
/// (ascending, in `[0°, 90°]`), each with the same uniformly spaced azimuths φ covering the
/// full circle.
#[derive(Debug, Clone, PartialEq)]
pub struct PolarGrid {
    theta_deg: Vec<f64>,
    phi0_deg: f64,
    phi_step_deg: f64,
    n_phi: usize,
    values: Vec<f64>,
}

impl PolarGrid {
    /// A grid from its axes (degrees) and `values[i·phi.len() + j]` at
    /// `(theta_deg[i], phi_deg[j])`.
    ///
    /// # Errors
    /// [`Error::Invalid`] when θ is not ascending within `[0, 90]`, φ is not uniformly spaced
    /// over exactly one turn (`n·Δφ = 360°`), there are fewer than 2 zenith or 3 azimuth values,
    /// or `values` has the wrong length.
    pub fn new(theta_deg: Vec<f64>, phi_deg: Vec<f64>, values: Vec<f64>) -> Result<Self> {
        let bad = |m: &str| Err(Error::Invalid(format!("polar grid: {m}")));
        if theta_deg.len() < 2 || phi_deg.len() < 3 {
            return bad("needs at least 2 zenith angles and 3 azimuths");
        }
        let ascending = theta_deg.windows(2).all(|w| w[0] < w[1]);
        if !(ascending && theta_deg[0] >= 0.0 && theta_deg[theta_deg.len() - 1] <= 90.0) {
            return bad("zenith angles must ascend within [0°, 90°]");
        }
        let n_phi = phi_deg.len();
        let step = 360.0 / n_phi as f64;
        let uniform = phi_deg
            .iter()
            .enumerate()
            .all(|(j, p)| (p - (phi_deg[0] + j as f64 * step)).abs() <= 1e-6 * step);
        if !uniform || !phi_deg[0].is_finite() {
            return bad("azimuths must be uniformly spaced over one full turn");
        }
        if values.len() != theta_deg.len() * n_phi {
            return bad("values must have one entry per (zenith, azimuth) pair");
        }
        Ok(Self {
            theta_deg,
            phi0_deg: phi_deg[0],
            phi_step_deg: step,
            n_phi,
            values,
        })
    }

    /// The zenith angles (degrees).
    pub fn theta_deg(&self) -> &[f64] {
        &self.theta_deg
    }

    /// Number of azimuths.
    pub fn n_phi(&self) -> usize {
        self.n_phi
    }

    /// The values, zenith-major.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// The value drawn at the direction `(theta, phi)` (degrees): bilinear interpolation of
    /// the grid, θ clamped to its range, φ wrapping around; with `period`, on the circle (the
    /// result then lies in `(−period/2, period/2]`).
    pub fn value_at(&self, theta_deg: f64, phi_deg: f64, period: Option<f64>) -> f64 {
        self.interpolate(&self.values, theta_deg, phi_deg, period)
    }

    /// Bilinear interpolation of `values` (laid out like the grid's) at `(theta, phi)` degrees;
    /// θ is clamped to the grid's range, φ wraps around. With `period`, values are angles
    /// interpolated on the circle (result in `(−period/2, period/2]`).
    pub(super) fn interpolate(
        &self,
        values: &[f64],
        theta: f64,
        phi: f64,
        period: Option<f64>,
    ) -> f64 {
        let th = &self.theta_deg;
        let last = th.len() - 1;
        let (i0, i1, ft) = if theta <= th[0] {
            (0, 0, 0.0)
        } else if theta >= th[last] {
            (last, last, 0.0)
        } else {
            let i = th.partition_point(|&t| t <= theta) - 1;
            (i, i + 1, (theta - th[i]) / (th[i + 1] - th[i]))
        };
        let u = ((phi - self.phi0_deg) / self.phi_step_deg).rem_euclid(self.n_phi as f64);
        let j0 = (u.floor() as usize).min(self.n_phi - 1);
        let j1 = (j0 + 1) % self.n_phi;
        let fp = u - j0 as f64;
        let at = |i: usize, j: usize| values[i * self.n_phi + j];
        let corners = [
            (at(i0, j0), (1.0 - ft) * (1.0 - fp)),
            (at(i0, j1), (1.0 - ft) * fp),
            (at(i1, j0), ft * (1.0 - fp)),
            (at(i1, j1), ft * fp),
        ];
        match period {
            None => corners
                .iter()
                .filter(|(_, w)| *w > 0.0)
                .map(|(v, w)| v * w)
                .sum(),
            Some(p) => {
                let k = std::f64::consts::TAU / p;
                let (mut c, mut s) = (0.0, 0.0);
                for (v, w) in corners.iter().filter(|(_, w)| *w > 0.0) {
                    c += w * (k * v).cos();
                    s += w * (k * v).sin();
                }
                s.atan2(c) / k
            }
        }
    }
}
