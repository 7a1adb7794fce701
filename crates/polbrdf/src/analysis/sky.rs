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

use crate::analysis::albedo::surface_integral_diverges;
use crate::analysis::facets::{smoothstep_n, FacetRule};
use crate::engine::Kernel;
use crate::error::{Error, Result};
use crate::geometry::GeometryBatch;
use crate::model::Material;
use crate::optics::mueller::Mueller;
use crate::optics::stokes::Stokes;
use std::f64::consts::{FRAC_PI_2, PI};

/// A sky: the Stokes radiance arriving from each direction of the upper hemisphere.
pub trait SkyRadiance: Sync {
    /// The Stokes radiance of the beam arriving from the sky point in direction
    /// `(theta, phi)` (rad; the direction points away from the surface), in that beam's psps
    /// basis. Any unit; the sky integral returns the same unit.
    fn stokes(&self, theta: f64, phi: f64) -> Stokes;
}

/// An unpolarized sky whose radiance depends on the zenith angle only, tabulated at zenith
/// angles (degrees, strictly increasing, from 0 to 90) and linear between them.
#[derive(Debug, Clone, PartialEq)]
pub struct ZenithProfile {
    zenith_deg: Vec<f64>,
    radiance: Vec<f64>,
}

impl ZenithProfile {
    /// A profile `radiance[j]` at `zenith_deg[j]`.
    ///
    /// # Errors
    /// [`Error::InvalidParameterAt`] for a zenith angle that is not finite, outside
    /// `[0°, 90°]` or not above the previous one, or a radiance that is not finite and ≥ 0;
    /// [`Error::InconsistentParameters`] for fewer than two rows or a table that does not
    /// start at 0° and end at 90°.
    pub fn new(zenith_deg: Vec<f64>, radiance: Vec<f64>) -> Result<Self> {
        crate::geometry::batch::check_len("radiance", radiance.len(), zenith_deg.len())?;
        if zenith_deg.len() < 2 {
            return Err(Error::InconsistentParameters(
                "a sky profile needs at least two zenith angles".into(),
            ));
        }
        for (i, (&z, &l)) in zenith_deg.iter().zip(&radiance).enumerate() {
            let at = |name, value, reason| Error::InvalidParameterAt {
                name,
                value,
                index: i,
                reason,
            };
            if !(z.is_finite() && (0.0..=90.0).contains(&z)) {
                return Err(at("zenith_deg", z, "must lie in [0°, 90°]"));
            }
            if i > 0 && z <= zenith_deg[i - 1] {
                return Err(at("zenith_deg", z, "zenith angles must increase strictly"));
            }
            if !(l.is_finite() && l >= 0.0) {
                return Err(at("radiance", l, "must be finite and >= 0"));
            }
        }
        if zenith_deg[0] != 0.0 || zenith_deg[zenith_deg.len() - 1] != 90.0 {
            return Err(Error::InconsistentParameters(
                "a sky profile must cover the whole sky: from zenith 0° to 90°".into(),
            ));
        }
        Ok(Self {
            zenith_deg,
            radiance,
        })
    }

    /// The radiance at zenith angle `theta` (rad), linear in the table.
    pub fn at(&self, theta: f64) -> f64 {
        let z = theta.to_degrees().clamp(0.0, 90.0);
        let x = &self.zenith_deg;
        let i = x.partition_point(|&v| v <= z).clamp(1, x.len() - 1);
        let t = (z - x[i - 1]) / (x[i] - x[i - 1]);
        self.radiance[i - 1] + (self.radiance[i] - self.radiance[i - 1]) * t
    }

    /// The table's zenith angles (degrees) and radiances.
    pub fn table(&self) -> (&[f64], &[f64]) {
        (&self.zenith_deg, &self.radiance)
    }
}

/// An unpolarized sky of one radiance everywhere.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UniformSky(pub f64);

impl SkyRadiance for UniformSky {
    fn stokes(&self, _theta: f64, _phi: f64) -> Stokes {
        Stokes([self.0, 0.0, 0.0, 0.0])
    }
}

/// A [`ZenithProfile`] scaled by `scale` (e.g. the profile as relative values times a
/// radiance), unpolarized.
#[derive(Debug, Clone, PartialEq)]
pub struct ProfileSky {
    /// The profile.
    pub profile: ZenithProfile,
    /// A factor applied to it.
    pub scale: f64,
}

impl SkyRadiance for ProfileSky {
    fn stokes(&self, theta: f64, _phi: f64) -> Stokes {
        Stokes([self.scale * self.profile.at(theta), 0.0, 0.0, 0.0])
    }
}

/// Points of the volume term's hemispherical rule: θ panels, points per panel, φ points.
const VOLUME_THETA: (usize, usize) = (2, 14);
const VOLUME_PHI: usize = 72;

/// The Stokes radiance `material` reflects toward `(theta_r, phi_r)` (rad) of `sky`:
/// `∫_H F(w, w_r)·L_sky(w) cosθ dω` (module documentation).
///
/// # Errors
/// [`Error::InvalidAngle`] (`theta_r`) outside `[0, π/2)` or a non-finite `phi_r`;
/// [`Error::InconsistentParameters`] for the `paper` form, whose integral diverges.
pub fn sky_reflection(
    material: &Material,
    theta_r: f64,
    phi_r: f64,
    sky: &dyn SkyRadiance,
) -> Result<Stokes> {
    sky_reflection_with(
        material,
        theta_r,
        phi_r,
        sky,
        FacetRule::for_material(material),
    )
}

/// As [`sky_reflection`] with a given facet rule for the surface term.
///
/// # Errors
/// As [`sky_reflection`].
pub fn sky_reflection_with(
    material: &Material,
    theta_r: f64,
    phi_r: f64,
    sky: &dyn SkyRadiance,
    rule: FacetRule,
) -> Result<Stokes> {
    use rayon::prelude::*;
    if !(theta_r.is_finite() && (0.0..FRAC_PI_2).contains(&theta_r) && phi_r.is_finite()) {
        return Err(Error::InvalidAngle {
            name: if phi_r.is_finite() {
                "theta_r"
            } else {
                "phi_r"
            },
            value: if phi_r.is_finite() { theta_r } else { phi_r },
            degrees: false,
            index: None,
            problem: if phi_r.is_finite() {
                crate::error::AngleProblem::ViewBelowHorizon
            } else {
                crate::error::AngleProblem::NotFinite
            },
        });
    }
    if surface_integral_diverges(material) {
        return Err(Error::InconsistentParameters(
            "the `paper` form reflects an infinite sky radiance: its f·cosθ grows like 1/cosθ \
             toward the horizon (use form = \"standard\")"
                .into(),
        ));
    }
    // Surface term: incidence directions at the facet nodes around w_r, rotated to φr.
    let nodes = rule.full().nodes(theta_r);
    let m = nodes.len();
    let fixed_t = vec![theta_r; m];
    let fixed_p = vec![phi_r; m];
    let node_t: Vec<f64> = nodes.iter().map(|n| n.theta).collect();
    let node_p: Vec<f64> = nodes.iter().map(|n| n.phi + phi_r).collect();
    let batch = GeometryBatch::new(&node_t, &node_p, &fixed_t, &fixed_p)
        .expect("directions above the horizon by construction");
    let surface = material.surface_only();
    let kernel = Kernel::new(&surface);
    const CHUNK: usize = 512;
    let partial: Vec<Stokes> = nodes
        .par_chunks(CHUNK)
        .enumerate()
        .map(|(c, chunk)| {
            let mut buf = [[0.0; 16]; CHUNK];
            let out = &mut buf[..chunk.len()];
            kernel.mueller_into(&batch, c * CHUNK, out);
            let mut s = Stokes([0.0; 4]);
            for (j, (f, n)) in out.iter().zip(chunk).enumerate() {
                let i = c * CHUNK + j;
                let l = sky.stokes(node_t[i], node_p[i]);
                s = s.combine(1.0, &Mueller::from_row_major(f).apply(&l), n.weight);
            }
            s
        })
        .collect();
    let mut total = partial
        .iter()
        .fold(Stokes([0.0; 4]), |a, s| a.combine(1.0, s, 1.0));
    // Volume term: f_v(θ, θr)·S0(w), S0 only.
    let (rho_d, rho_v) = (material.rho_d(), material.rho_v());
    if rho_d > 0.0 || rho_v > 0.0 {
        let cr = theta_r.cos();
        let dphi = 2.0 * PI / VOLUME_PHI as f64;
        let mut v = 0.0;
        for (t, wt) in smoothstep_n(0.0, FRAC_PI_2, VOLUME_THETA.0, VOLUME_THETA.1) {
            let (st, ct) = t.sin_cos();
            let fv = rho_d + 2.0 * rho_v / (ct + cr);
            let ring: f64 = (0..VOLUME_PHI)
                .map(|j| sky.stokes(t, phi_r + (j as f64 + 0.5) * dphi).0[0])
                .sum();
            v += wt * fv * ct * st * ring * dphi;
        }
        total.0[0] += v;
    }
    Ok(total)
}
