//! The regular grid of viewing directions over the hemisphere that maps are taken on.

use crate::error::{Error, Result};
use std::f64::consts::PI;

/// Limit on the number of grid directions (a 0.1° × 0.1° grid has 3.2 million).
pub const MAX_GRID_DIRECTIONS: usize = 4_000_000;

/// A regular grid over the viewing hemisphere: zenith angles `θ_k = k·Δθ` for `k·Δθ < 90°`
/// and azimuths `φ_j = j·Δφ`, `j = 0 … n−1`, with `Δφ = 360°/n` (the requested azimuth step
/// is rounded so that it divides the full turn). Nodes are numbered zenith-major:
/// `index = k·n_phi + j`. The `n_phi` nodes at θ = 0 are the same direction (their reflected
/// beams' reference frames differ by the azimuth).
#[derive(Debug, Clone, PartialEq)]
pub struct ViewGrid {
    theta_step: f64,
    phi_step: f64,
    n_theta: usize,
    n_phi: usize,
}

impl ViewGrid {
    /// A grid with the given steps in degrees.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] (`grid_deg`) for a step that is not finite, ≤ 0, above 30°
    /// (zenith) or 90° (azimuth), or a grid of more than [`MAX_GRID_DIRECTIONS`] directions.
    pub fn from_degrees(theta_step_deg: f64, phi_step_deg: f64) -> Result<Self> {
        for (v, max) in [(theta_step_deg, 30.0), (phi_step_deg, 90.0)] {
            if !(v.is_finite() && v > 0.0 && v <= max) {
                return Err(Error::InvalidParameter {
                    name: "grid_deg",
                    value: v,
                    reason: "grid steps must be > 0 and at most 30° (zenith) and 90° (azimuth)",
                });
            }
        }
        let n_theta = (90.0 / theta_step_deg - 1e-9).ceil() as usize;
        let n_phi = (360.0 / phi_step_deg).round().max(4.0) as usize;
        if n_theta.saturating_mul(n_phi) > MAX_GRID_DIRECTIONS {
            return Err(Error::InvalidParameter {
                name: "grid_deg",
                value: theta_step_deg.min(phi_step_deg),
                reason: "grid too fine: more than 4 000 000 viewing directions",
            });
        }
        Ok(Self {
            theta_step: theta_step_deg.to_radians(),
            phi_step: 2.0 * PI / n_phi as f64,
            n_theta,
            n_phi,
        })
    }

    /// Zenith step Δθ (rad).
    pub fn theta_step(&self) -> f64 {
        self.theta_step
    }
    /// Azimuth step Δφ (rad), `2π/n_phi`.
    pub fn phi_step(&self) -> f64 {
        self.phi_step
    }
    /// Number of zenith angles.
    pub fn n_theta(&self) -> usize {
        self.n_theta
    }
    /// Number of azimuths.
    pub fn n_phi(&self) -> usize {
        self.n_phi
    }
    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.n_theta * self.n_phi
    }
    /// True when there are no nodes (never, for a grid built by [`ViewGrid::from_degrees`]).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// The zenith angles (rad), ascending from 0.
    pub fn thetas(&self) -> Vec<f64> {
        (0..self.n_theta)
            .map(|k| k as f64 * self.theta_step)
            .collect()
    }
    /// The azimuths (rad), from 0.
    pub fn phis(&self) -> Vec<f64> {
        (0..self.n_phi).map(|j| j as f64 * self.phi_step).collect()
    }
    /// The direction `(θr, φr)` (rad) of node `index`.
    pub fn direction(&self, index: usize) -> (f64, f64) {
        (
            (index / self.n_phi) as f64 * self.theta_step,
            (index % self.n_phi) as f64 * self.phi_step,
        )
    }
    /// The largest zenith angle of the grid (rad).
    pub fn theta_max(&self) -> f64 {
        (self.n_theta - 1) as f64 * self.theta_step
    }
}
