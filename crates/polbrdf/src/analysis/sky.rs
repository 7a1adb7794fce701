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
    /// `[0°, 90°]` or not above the previous one, or a radiance that is not finite, ≥ 0 and at
    /// most [`crate::error::MAX_RADIOMETRIC`] (1e150, as every radiance of a scene: beyond it
    /// the sky integral overflows to ∞ and NaN); [`Error::InconsistentParameters`] for fewer
    /// than two rows or a table that does not
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
            if !(l.is_finite() && (0.0..=crate::error::MAX_RADIOMETRIC).contains(&l)) {
                return Err(at("radiance", l, "must be finite, >= 0 and at most 1e150"));
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

pub use crate::geometry::direction;

/// The psps basis `(s_in, p_in)` of the beam arriving at the surface from the sky point in
/// direction `(theta, phi)`: `k = −w`, `s_in = unit(z × k) = (sinφ, −cosφ, 0)` (its θ → 0⁺
/// limit at the given azimuth at the zenith), `p_in = k × s_in` (docs/model.md §2). The one
/// place the arriving frame is written.
pub fn arriving_basis(theta: f64, phi: f64) -> ([f64; 3], [f64; 3]) {
    let (sp, cp) = phi.sin_cos();
    basis_of(&direction(theta, phi), sp, cp)
}

/// [`arriving_basis`] of the direction `w` at azimuth φ given by `(sinφ, cosφ)`.
fn basis_of(w: &[f64; 3], sp: f64, cp: f64) -> ([f64; 3], [f64; 3]) {
    let s = [sp, -cp, 0.0];
    // p = k × s with k = −w.
    let p = cross(&s, w);
    (s, p)
}

fn cross(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The Stokes vector `L·(1, P·cos2ψ, P·sin2ψ, 0)` of linearly polarized light of radiance `L`
/// and degree `P` whose electric vector is along `e`, arriving from `(theta, phi)`, in the
/// arriving beam's basis: `ψ = atan2(e·p_in, e·s_in)` ([`arriving_basis`]).
pub fn linear_stokes(radiance: f64, dolp: f64, e: &[f64; 3], theta: f64, phi: f64) -> Stokes {
    let (sp, cp) = phi.sin_cos();
    linear_stokes_of(radiance, dolp, e, &direction(theta, phi), sp, cp)
}

/// [`linear_stokes`] arriving from the direction `w` at azimuth φ given by `(sinφ, cosφ)`.
fn linear_stokes_of(
    radiance: f64,
    dolp: f64,
    e: &[f64; 3],
    w: &[f64; 3],
    sp: f64,
    cp: f64,
) -> Stokes {
    let (s, p) = basis_of(w, sp, cp);
    let (x, y) = (dot(e, &s), dot(e, &p));
    let r2 = x * x + y * y;
    if r2.is_nan() || r2 <= 0.0 || dolp == 0.0 {
        return Stokes([radiance, 0.0, 0.0, 0.0]);
    }
    // cos 2ψ = (x² − y²)/r², sin 2ψ = 2xy/r².
    Stokes([
        radiance,
        radiance * dolp * (x * x - y * y) / r2,
        radiance * dolp * 2.0 * x * y / r2,
        0.0,
    ])
}

/// The CIE standard clear sky (ISO 15469 / CIE S 011, type 12) with Rayleigh single-scattering
/// polarization (docs/model.md §18).
///
/// Radiance `L(Z, γ) = scale·f(γ)·φ(Z)` with `φ(Z) = 1 + a·exp(b/cos Z)` (φ = 1 at the
/// horizon) and `f(γ) = 1 + c·(exp(dγ) − exp(dπ/2)) + e·cos²γ`, `a = −1, b = −0.32, c = 10,
/// d = −3, e = 0.45`; Z the zenith angle of the sky point, γ its angle from the sun. `scale`
/// makes the horizontal irradiance `∫_H L cosθ dω` the given one. DoLP
/// `δ_max·sin²γ/(1 + cos²γ)`, electric vector along `w × w_s` (perpendicular to the plane of
/// sun, sky point and observer), in the arriving beam's basis ([`linear_stokes`]).
#[derive(Debug, Clone, PartialEq)]
pub struct ClearSky {
    sun_zenith: f64,
    sun_azimuth: f64,
    sun: [f64; 3],
    scale: f64,
    dop_max: f64,
}

impl ClearSky {
    /// The default maximum degree of polarization δ_max of the clear sky (90° from the sun),
    /// written only here: the scene files' `dop_max` and the Python module's take it.
    pub const DEFAULT_DOP_MAX: f64 = 0.75;

    /// The parameters `(a, b, c, d, e)` of CIE sky type 12 (clear, low turbidity).
    pub const CIE12: (f64, f64, f64, f64, f64) = (-1.0, -0.32, 10.0, -3.0, 0.45);

    /// A clear sky for the sun at `(sun_zenith, sun_azimuth)` (rad; the sun may be anywhere on
    /// the upper hemisphere, its zenith angle in `[0, π/2]`), scaled to the horizontal
    /// irradiance `irradiance` (≥ 0, any unit: the sky's radiance is in that unit per sr), with
    /// the maximum degree of polarization `dop_max` in `[0, 1]`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `sun.zenith_deg`, `sun.azimuth_deg`,
    /// `sky.irradiance` or `sky.dop_max`.
    pub fn new(sun_zenith: f64, sun_azimuth: f64, irradiance: f64, dop_max: f64) -> Result<Self> {
        if !(sun_zenith.is_finite() && (0.0..=FRAC_PI_2).contains(&sun_zenith)) {
            return Err(Error::InvalidParameter {
                name: "sun.zenith_deg",
                value: sun_zenith.to_degrees(),
                reason: "the sun of a clear sky must be above the horizon: in [0, 90] degrees",
            });
        }
        if !sun_azimuth.is_finite() {
            return Err(Error::InvalidParameter {
                name: "sun.azimuth_deg",
                value: sun_azimuth,
                reason: "must be finite",
            });
        }
        crate::error::radiometric("sky.irradiance", irradiance)?;
        if !(dop_max.is_finite() && (0.0..=1.0).contains(&dop_max)) {
            return Err(Error::InvalidParameter {
                name: "sky.dop_max",
                value: dop_max,
                reason: "must lie in [0, 1]",
            });
        }
        let mut sky = Self {
            sun_zenith,
            sun_azimuth,
            sun: direction(sun_zenith, sun_azimuth),
            scale: 1.0,
            dop_max,
        };
        let relative = sky.relative_irradiance();
        sky.scale = irradiance / relative;
        Ok(sky)
    }

    /// `f(γ)·φ(Z)` toward `(theta, phi)`.
    pub fn relative_radiance(&self, theta: f64, phi: f64) -> f64 {
        self.relative_at(&direction(theta, phi)).0
    }

    /// `(f(γ)·φ(Z), cosγ)` toward the unit vector `w`: the one place the CIE formula is written.
    fn relative_at(&self, w: &[f64; 3]) -> (f64, f64) {
        let (a, b, c, d, e) = Self::CIE12;
        let cg = dot(w, &self.sun).clamp(-1.0, 1.0);
        let f = 1.0 + c * ((d * cg.acos()).exp() - (d * FRAC_PI_2).exp()) + e * cg * cg;
        let ct = w[2];
        let grad = if ct > 0.0 {
            1.0 + a * (b / ct).exp()
        } else {
            1.0
        };
        (f * grad, cg)
    }

    /// `∫_H f(γ)·φ(Z) cosθ dω` on a product rule with the sun at a panel corner
    /// ([`relative_irradiance_with`] with 4 panels of 16 points per segment): converged to
    /// 1e-11 relative (`tests/daylight.rs`).
    pub fn relative_irradiance(&self) -> f64 {
        relative_irradiance_with(self, 4, 16)
    }

    /// The radiance factor: `L = scale·f(γ)·φ(Z)`.
    pub fn scale(&self) -> f64 {
        self.scale
    }

    /// The sun's zenith angle and azimuth (rad).
    pub fn sun(&self) -> (f64, f64) {
        (self.sun_zenith, self.sun_azimuth)
    }

    /// `δ_max`.
    pub fn dop_max(&self) -> f64 {
        self.dop_max
    }

    /// The Rayleigh DoLP `δ_max·sin²γ/(1 + cos²γ)` at angle `gamma` from the sun.
    pub fn dolp_at(&self, gamma: f64) -> f64 {
        self.dolp_of_cos(gamma.cos())
    }

    /// [`ClearSky::dolp_at`] of `cosγ`.
    fn dolp_of_cos(&self, c: f64) -> f64 {
        self.dop_max * (1.0 - c * c) / (1.0 + c * c)
    }
}

/// `∫_H f(γ)·φ(Z) cosθ dω` of `sky`: θ in two segments split at the sun's zenith angle, φ in
/// two split at the sun's azimuth and the opposite one, each segment on `panels` smoothstep
/// Gauss–Legendre panels of `points` points — the sun, the integrand's one cone point, at a
/// panel corner where the smoothstep map clusters the nodes.
pub fn relative_irradiance_with(sky: &ClearSky, panels: usize, points: usize) -> f64 {
    let (zs, azs) = (sky.sun_zenith, sky.sun_azimuth);
    let thetas: Vec<(f64, f64)> = [(0.0, zs), (zs, FRAC_PI_2)]
        .iter()
        .filter(|(a, b)| b > a)
        .flat_map(|&(a, b)| smoothstep_n(a, b, panels, points))
        .collect();
    let phis: Vec<(f64, f64)> = [(azs, azs + PI), (azs + PI, azs + 2.0 * PI)]
        .iter()
        .flat_map(|&(a, b)| smoothstep_n(a, b, panels, points))
        .collect();
    thetas
        .iter()
        .map(|&(t, wt)| {
            let (st, ct) = t.sin_cos();
            let ring: f64 = phis
                .iter()
                .map(|&(p, wp)| wp * sky.relative_radiance(t, p))
                .sum();
            wt * ct * st * ring
        })
        .sum()
}

impl SkyRadiance for ClearSky {
    fn azimuth_origin(&self) -> f64 {
        self.sun_azimuth
    }

    fn cone_point(&self) -> Option<(f64, f64)> {
        Some((self.sun_zenith, self.sun_azimuth))
    }

    /// [`ClearSky::relative_radiance`] times `scale`, with [`ClearSky::dolp_at`] along
    /// `w × w_s` ([`linear_stokes`]); the direction's trigonometric functions taken once (this
    /// runs at every node of every sky integral).
    fn stokes(&self, theta: f64, phi: f64) -> Stokes {
        let (st, ct) = theta.sin_cos();
        let (sp, cp) = phi.sin_cos();
        let w = [st * cp, st * sp, ct];
        let (rel, cg) = self.relative_at(&w);
        linear_stokes_of(
            self.scale * rel,
            self.dolp_of_cos(cg),
            &cross(&w, &self.sun),
            &w,
            sp,
            cp,
        )
    }
}

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
    reflection(material, theta_r, phi_r, sky, rule, None)
}

/// The volume term's rule with the sky's S0 summed over each ring: `(θ, weight·Σ_φ S0)` per
/// zenith node, so that the volume term toward any view is `Σ f_v(θ, θr)·w`. The φ nodes are
/// fixed (not turned with the view): the ring sums depend on the sky alone and are computed
/// once per sky ([`sky_reflection_prepared`]).
pub fn volume_rings(sky: &dyn SkyRadiance) -> Vec<(f64, f64)> {
    let origin = sky.azimuth_origin();
    let ring_of = |t: f64, phis: &[(f64, f64)]| -> f64 {
        phis.iter().map(|&(p, w)| w * sky.stokes(t, p).0[0]).sum()
    };
    let weigh = |(t, wt): (f64, f64), ring: f64| {
        let (st, ct) = t.sin_cos();
        (t, wt * ct * st * ring)
    };
    match sky.cone_point() {
        // A cone point (the sun): θ split at its zenith, φ at its azimuth and the opposite
        // one, 2 smoothstep panels of 14 points per segment, so that it is a panel corner.
        Some((zs, azs)) => {
            let phis: Vec<(f64, f64)> = [(azs, azs + PI), (azs + PI, azs + 2.0 * PI)]
                .iter()
                .flat_map(|&(a, b)| smoothstep_n(a, b, 2, 14))
                .collect();
            [(0.0, zs), (zs, FRAC_PI_2)]
                .iter()
                .filter(|(a, b)| b > a)
                .flat_map(|&(a, b)| smoothstep_n(a, b, 2, 14))
                .map(|tw| weigh(tw, ring_of(tw.0, &phis)))
                .collect()
        }
        None => {
            let dphi = 2.0 * PI / VOLUME_PHI as f64;
            let phis: Vec<(f64, f64)> = (0..VOLUME_PHI)
                .map(|j| (origin + (j as f64 + 0.5) * dphi, dphi))
                .collect();
            smoothstep_n(0.0, FRAC_PI_2, VOLUME_THETA.0, VOLUME_THETA.1)
                .map(|tw| weigh(tw, ring_of(tw.0, &phis)))
                .collect()
        }
    }
}

/// As [`sky_reflection`] with the volume rings of `sky` computed beforehand
/// ([`volume_rings`]): what many views of one sky share.
///
/// # Errors
/// As [`sky_reflection`].
pub fn sky_reflection_prepared(
    material: &Material,
    theta_r: f64,
    phi_r: f64,
    sky: &dyn SkyRadiance,
    rings: &[(f64, f64)],
    quality: Quality,
) -> Result<Stokes> {
    let mut rule = FacetRule::for_material(material);
    if quality == Quality::Map {
        rule.theta_points = MAP_POINTS;
        rule.phi_points = MAP_POINTS;
    }
    reflection(material, theta_r, phi_r, sky, rule, Some(rings))
}

/// How accurately a sky integral is taken.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Quality {
    /// The default rule: 1.3e-5 of S0 at worst on every component, for lobes from σ = 0.5°
    /// to 60° under the clear sky, converging fast under refinement (`tests/daylight.rs`).
    #[default]
    Full,
    /// 10 instead of 14 Gauss–Legendre points per panel and no panel corner at the sun,
    /// about half the nodes, shared by every azimuth of a view zenith
    /// ([`sky_reflections_at_zenith`]): 5.3e-4 of the reflected S0 at worst (σ = 0.5°…60°,
    /// `tests/daylight.rs`) — for hemispherical maps, whose values are not read to five
    /// digits; the best directions of a contrast are evaluated again with [`Quality::Full`].
    Map,
}

/// Gauss–Legendre points per panel of [`Quality::Map`].
pub const MAP_POINTS: usize = 10;

fn reflection(
    material: &Material,
    theta_r: f64,
    phi_r: f64,
    sky: &dyn SkyRadiance,
    rule: FacetRule,
    rings: Option<&[(f64, f64)]>,
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
    // Surface term: incidence directions at the facet nodes around w_r, rotated to φr; a
    // cone point of the sky, in the frame where the view is at azimuth 0, is a panel corner.
    let rule = match sky.cone_point() {
        Some((t, p)) => rule.with_cone(direction(t, p - phi_r)),
        None => rule,
    };
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
        let owned;
        let rings = match rings {
            Some(r) => r,
            None => {
                owned = volume_rings(sky);
                &owned
            }
        };
        total.0[0] += volume_reflection(material, theta_r, rings);
    }
    Ok(total)
}

/// The volume term's part of the sky integral toward view zenith `theta_r`,
/// `∫_H f_v(θ, θr)·S0(w) cosθ dω` on the rings of [`volume_rings`] (it is unpolarized).
pub fn volume_reflection(material: &Material, theta_r: f64, rings: &[(f64, f64)]) -> f64 {
    let (rho_d, rho_v) = (material.rho_d(), material.rho_v());
    let cr = theta_r.cos();
    rings
        .iter()
        .map(|&(t, w)| (rho_d + 2.0 * rho_v / (t.cos() + cr)) * w)
        .sum()
}

/// The sky integrals of one material toward many view azimuths at one view zenith, the way a
/// hemispherical map needs them: the facet nodes of the view zenith (without a cone point,
/// relative to the view azimuth) and the Mueller matrices there are computed once — the model
/// is isotropic, so only the sky turns with the view — and each azimuth costs one sky
/// evaluation and one matrix–vector product per node. The rule is that of `quality`.
///
/// # Panics
/// For `theta_r` outside `[0, π/2)` (the caller clamps), or the `paper` form.
pub fn sky_reflections_at_zenith(
    material: &Material,
    theta_r: f64,
    phis: &[f64],
    sky: &dyn SkyRadiance,
    rings: &[(f64, f64)],
    quality: Quality,
) -> Vec<Stokes> {
    assert!(
        !surface_integral_diverges(material),
        "the paper form has no sky integral"
    );
    let mut rule = FacetRule::for_material(material);
    if quality == Quality::Map {
        rule.theta_points = MAP_POINTS;
        rule.phi_points = MAP_POINTS;
    }
    let nodes = rule.full().nodes(theta_r);
    let m = nodes.len();
    let fixed_t = vec![theta_r; m];
    let zeros = vec![0.0; m];
    let node_t: Vec<f64> = nodes.iter().map(|n| n.theta).collect();
    let node_p: Vec<f64> = nodes.iter().map(|n| n.phi).collect();
    let batch = GeometryBatch::new(&node_t, &node_p, &fixed_t, &zeros)
        .expect("directions above the horizon by construction");
    let surface = material.surface_only();
    let kernel = Kernel::new(&surface);
    let mut f = vec![[0.0; 16]; m];
    kernel.mueller_into(&batch, 0, &mut f);
    let volume = if material.rho_d() > 0.0 || material.rho_v() > 0.0 {
        volume_reflection(material, theta_r, rings)
    } else {
        0.0
    };
    phis.iter()
        .map(|&phi_r| {
            let mut s = [0.0; 4];
            for ((fm, n), (&t, &p)) in f.iter().zip(&nodes).zip(node_t.iter().zip(&node_p)) {
                let l = sky.stokes(t, p + phi_r).0;
                for (i, si) in s.iter_mut().enumerate() {
                    let row = &fm[4 * i..4 * i + 4];
                    *si +=
                        n.weight * (row[0] * l[0] + row[1] * l[1] + row[2] * l[2] + row[3] * l[3]);
                }
            }
            s[0] += volume;
            Stokes(s)
        })
        .collect()
}
