//! Target and background seen from one direction, and the contrast quantities derived from
//! their Stokes vectors (the table in [`crate::analysis::contrast`]).

use crate::geometry::direction;
use crate::optics::stokes::Stokes;
use std::f64::consts::{FRAC_PI_2, PI};

/// Target and background seen from one direction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContrastSample {
    /// Viewing zenith angle θr (rad).
    pub theta_r: f64,
    /// Viewing azimuth φr (rad).
    pub phi_r: f64,
    /// Reflected Stokes vector of the target per unit irradiance (sr⁻¹).
    pub target: Stokes,
    /// Reflected Stokes vector of the background per unit irradiance (sr⁻¹).
    pub background: Stokes,
}

impl ContrastSample {
    /// DoLP of the light reflected by the target.
    pub fn dolp_target(&self) -> f64 {
        self.target.dolp()
    }
    /// DoLP of the light reflected by the background.
    pub fn dolp_background(&self) -> f64 {
        self.background.dolp()
    }
    /// `ΔDoLP = DoLP_target − DoLP_background`.
    pub fn delta_dolp(&self) -> f64 {
        self.dolp_target() - self.dolp_background()
    }
    /// `S0_target − S0_background`: the radiance difference an intensity camera sees (per unit
    /// irradiance under a collimated source; W·m⁻²·sr⁻¹(·µm⁻¹) in a scene).
    pub fn radiance_difference(&self) -> f64 {
        self.target.s0() - self.background.s0()
    }
    /// `S0_target / S0_background`: 1 when both are 0, +∞ when only the background is.
    pub fn intensity_ratio(&self) -> f64 {
        let (t, b) = (self.target.s0(), self.background.s0());
        if b > 0.0 {
            t / b
        } else if t > 0.0 {
            f64::INFINITY
        } else {
            1.0
        }
    }
    /// `AoLP_target − AoLP_background` (rad) folded into (−π/2, π/2]; 0 when either beam has
    /// no linear polarization (its AoLP is undefined).
    pub fn aolp_difference(&self) -> f64 {
        let lin = |s: &Stokes| s.s1().hypot(s.s2());
        if lin(&self.target) == 0.0 || lin(&self.background) == 0.0 {
            return 0.0;
        }
        let d = self.target.aolp() - self.background.aolp();
        FRAC_PI_2 - (FRAC_PI_2 - d).rem_euclid(PI)
    }
    /// The polarization contrast `|ΔS_lin| / S̄0 = sqrt(ΔS1² + ΔS2²) / ((S0_t + S0_b)/2)`, in
    /// `[0, 2]`; 0 when neither reflects anything ([`crate::analysis::contrast`]).
    pub fn polarization_contrast(&self) -> f64 {
        let (t, b) = (&self.target.0, &self.background.0);
        let mean = 0.5 * (t[0] + b[0]);
        if mean > 0.0 {
            (t[1] - b[1]).hypot(t[2] - b[2]) / mean
        } else {
            0.0
        }
    }
    /// Unit vector of the viewing direction.
    pub fn direction(&self) -> [f64; 3] {
        direction(self.theta_r, self.phi_r)
    }
}
