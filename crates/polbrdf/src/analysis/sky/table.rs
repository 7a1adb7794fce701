//! A tabulated Stokes sky: a zenith × azimuth grid, bilinear between its nodes, periodic in
//! azimuth.

use super::SkyRadiance;
use crate::error::{Error, Result};
use crate::optics::stokes::Stokes;

/// A tabulated sky: the Stokes radiance `(s0, s1, s2, s3)` in the arriving beam's basis on a
/// full grid of zenith angles (degrees, strictly increasing, from 0 to 90) × azimuths
/// (degrees, strictly increasing in `[0, 360)`), bilinear between the nodes, periodic in
/// azimuth (e.g. a radiative-transfer model's output).
#[derive(Debug, Clone, PartialEq)]
pub struct TableSky {
    theta_deg: Vec<f64>,
    phi_deg: Vec<f64>,
    /// `stokes[j·n_phi + k]` at `(theta_deg[j], phi_deg[k])`.
    stokes: Vec<Stokes>,
}

impl TableSky {
    /// The table, `stokes[j·phi_deg.len() + k]` at `(theta_deg[j], phi_deg[k])`.
    ///
    /// # Errors
    /// [`Error::InvalidParameterAt`] (`theta_deg`, `phi_deg`, `s0` … `s3`, with the index:
    /// of the angle, or of the flat node) for an angle that is not finite, out of range or not
    /// above the previous one, a non-finite Stokes parameter, `s0 < 0` or a degree of
    /// polarization above 1 (to 1e-9); [`Error::InconsistentParameters`] for a table that does
    /// not span 0° to 90° in zenith or holds the wrong number of nodes.
    pub fn new(theta_deg: Vec<f64>, phi_deg: Vec<f64>, stokes: Vec<Stokes>) -> Result<Self> {
        let at = |name, value, index, reason| Error::InvalidParameterAt {
            name,
            value,
            index,
            reason,
        };
        for (i, &t) in theta_deg.iter().enumerate() {
            if !(t.is_finite() && (0.0..=90.0).contains(&t)) {
                return Err(at("theta_deg", t, i, "must lie in [0°, 90°]"));
            }
            if i > 0 && t <= theta_deg[i - 1] {
                return Err(at(
                    "theta_deg",
                    t,
                    i,
                    "zenith angles must increase strictly",
                ));
            }
        }
        for (i, &p) in phi_deg.iter().enumerate() {
            if !(p.is_finite() && (0.0..360.0).contains(&p)) {
                return Err(at("phi_deg", p, i, "must lie in [0°, 360°)"));
            }
            if i > 0 && p <= phi_deg[i - 1] {
                return Err(at("phi_deg", p, i, "azimuths must increase strictly"));
            }
        }
        if theta_deg.len() < 2 || theta_deg[0] != 0.0 || theta_deg[theta_deg.len() - 1] != 90.0 {
            return Err(Error::InconsistentParameters(
                "a sky table must cover the whole sky: zenith angles from 0° to 90°".into(),
            ));
        }
        if phi_deg.is_empty() || stokes.len() != theta_deg.len() * phi_deg.len() {
            return Err(Error::InconsistentParameters(format!(
                "a sky table needs every zenith × azimuth node: {} × {} = {} nodes, got {}",
                theta_deg.len(),
                phi_deg.len(),
                theta_deg.len() * phi_deg.len(),
                stokes.len()
            )));
        }
        let max = crate::error::MAX_RADIOMETRIC;
        for (i, s) in stokes.iter().enumerate() {
            for (j, name) in ["s0", "s1", "s2", "s3"].into_iter().enumerate() {
                if !(s.0[j].is_finite() && s.0[j].abs() <= max) {
                    return Err(at(
                        name,
                        s.0[j],
                        i,
                        "must be finite and at most 1e150 in size",
                    ));
                }
            }
            if s.0[0] < 0.0 {
                return Err(at("s0", s.0[0], i, "must be >= 0"));
            }
            let pol = s.0[1].hypot(s.0[2]).hypot(s.0[3]);
            if pol > s.0[0] * (1.0 + 1e-9) {
                return Err(at(
                    "s0",
                    s.0[0],
                    i,
                    "the degree of polarization sqrt(s1² + s2² + s3²)/s0 exceeds 1",
                ));
            }
        }
        Ok(Self {
            theta_deg,
            phi_deg,
            stokes,
        })
    }

    /// The grid: zenith angles and azimuths (degrees).
    pub fn grid(&self) -> (&[f64], &[f64]) {
        (&self.theta_deg, &self.phi_deg)
    }
}

impl SkyRadiance for TableSky {
    fn stokes(&self, theta: f64, phi: f64) -> Stokes {
        let z = theta.to_degrees().clamp(0.0, 90.0);
        let x = &self.theta_deg;
        let i = x.partition_point(|&v| v <= z).clamp(1, x.len() - 1);
        let u = (z - x[i - 1]) / (x[i] - x[i - 1]);
        let p = phi.to_degrees().rem_euclid(360.0);
        let ph = &self.phi_deg;
        let n = ph.len();
        // The azimuth interval [ph[k0], ph[k1]) holding p, wrapping around 360°.
        let k = ph.partition_point(|&v| v <= p);
        let (k0, k1, lo, hi) = if k == 0 {
            (n - 1, 0, ph[n - 1] - 360.0, ph[0])
        } else if k == n {
            (n - 1, 0, ph[n - 1], ph[0] + 360.0)
        } else {
            (k - 1, k, ph[k - 1], ph[k])
        };
        let v = if n == 1 { 0.0 } else { (p - lo) / (hi - lo) };
        let node = |j: usize, k: usize| self.stokes[j * n + k];
        let mut out = [0.0; 4];
        for (c, w) in [
            (node(i - 1, k0), (1.0 - u) * (1.0 - v)),
            (node(i - 1, k1), (1.0 - u) * v),
            (node(i, k0), u * (1.0 - v)),
            (node(i, k1), u * v),
        ] {
            for (o, x) in out.iter_mut().zip(c.0) {
                *o += w * x;
            }
        }
        Stokes(out)
    }
}
