//! Skies and the sky integral (docs/model.md §17): the Stokes radiance a surface reflects of a
//! sky, `∫_H F(w, w_r)·L_sky(w) cosθ dω`.
//!
//! A sky gives, for each direction `w` toward a sky point, the Stokes radiance of the beam that
//! arrives at the surface from there, in that beam's psps basis (`k = −w`,
//! `s_in = unit(z × k)`, `p_in = k × s_in`, docs/model.md §2) — the basis `F` takes as input.
//!
//! **The integral.** The surface term over facet normals around `w_r`
//! ([`crate::analysis::facets`], both halves of every ring, the nodes rotated to the view
//! azimuth), the volume term `f_v·diag(1, 0, 0, 0)` on a plain hemispherical rule: 2 × 14
//! smoothstep Gauss–Legendre points in θ and a 72-point midpoint rule in φ (spectrally accurate
//! for a smooth periodic integrand). A uniform unpolarized sky of radiance `L_d` reflects
//! exactly `L_d·(e0 − ε(w_r))` by Kirchhoff's law ([`crate::analysis::emission`]): no quadrature
//! is needed then, and the general integral must (and does) reproduce it
//! (`tests/emission.rs`).
//!
//! By aspect: the arriving beam's basis and linear polarization in it (`basis`), unpolarized
//! uniform and zenith-profile skies (`profile`), the CIE clear sky with Rayleigh polarization
//! (`clear`), tabulated Stokes skies (`table`) and the sky integral (`integral`).

use crate::optics::stokes::Stokes;

mod basis;
mod clear;
mod integral;
mod profile;
mod table;

pub use basis::{arriving_basis, linear_stokes};
pub use clear::{relative_irradiance_with, ClearSky};
pub use integral::{
    sky_reflection, sky_reflection_prepared, sky_reflection_with, sky_reflections_at_zenith,
    volume_reflection, volume_rings, Quality, MAP_POINTS,
};
pub use profile::{ProfileSky, UniformSky, ZenithProfile};
pub use table::TableSky;

pub use crate::geometry::direction;

/// A sky: the Stokes radiance arriving from each direction of the upper hemisphere.
pub trait SkyRadiance: Sync {
    /// The Stokes radiance of the beam arriving from the sky point in direction
    /// `(theta, phi)` (rad; the direction points away from the surface), in that beam's psps
    /// basis. Any unit; the sky integral returns the same unit.
    fn stokes(&self, theta: f64, phi: f64) -> Stokes;

    /// The azimuth (rad) the volume term's φ rule starts from: 0, or the sun's azimuth for a
    /// sky set by the sun, so that turning sun and view together turns the rule with them.
    fn azimuth_origin(&self) -> f64 {
        0.0
    }

    /// A direction `(θ, φ)` (rad) where the radiance is not differentiable (a cone point),
    /// made a panel corner of the surface term's rule: the sun of a clear sky.
    fn cone_point(&self) -> Option<(f64, f64)> {
        None
    }
}
