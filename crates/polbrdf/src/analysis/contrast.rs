//! Target against background: polarization contrast over the viewing hemisphere, and the best
//! viewing directions (docs/model.md §11).
//!
//! Both materials are lit from the same direction by the same input Stokes vector
//! ([`Illumination`]) and looked at from every direction of a regular grid over the viewing
//! hemisphere ([`ViewGrid`]). At each direction the reflected Stokes vectors
//! `S_t = F_target·S_in` and `S_b = F_background·S_in` (per unit incident irradiance, psps basis
//! of the reflected beam, which is the same for both) give ([`ContrastSample`]):
//!
//! | quantity | definition |
//! |---|---|
//! | `dolp_target`, `dolp_background` | `sqrt(S1² + S2²)/S0` of `S_t`, `S_b` (eq. 13) |
//! | `delta_dolp` | `DoLP_t − DoLP_b` |
//! | `intensity_ratio` | `S0_t / S0_b` (the BRDF ratio for unpolarized input) |
//! | `aolp_difference` | `AoLP_t − AoLP_b` folded into (−90°, 90°]; 0 when either beam has no linear polarization |
//! | `polarization_contrast` | `sqrt((S1_t − S1_b)² + (S2_t − S2_b)²) / ((S0_t + S0_b)/2)` |
//!
//! The polarization contrast is the amplitude of the part of the target–background radiance
//! difference that a rotating linear analyzer modulates, relative to the mean radiance: through
//! an analyzer at angle ψ a camera sees `I(ψ) = ½(S0 + S1 cos2ψ + S2 sin2ψ)`, so the difference
//! `I_t(ψ) − I_b(ψ)` swings by `½·|ΔS_lin|` around `½ΔS0`. It equals `|ΔDoLP|` when the two
//! intensities and AoLPs are equal, grows with an AoLP difference (`2·DoLP·|sin ΔAoLP|` at equal
//! DoLP and intensity), and weighs each DoLP by its intensity: a dark target's polarization
//! counts for less. It lies in `[0, 2]`.
//!
//! [`Contrast::rank`] lists the best directions ([`Ranking`]) with viewing zenith angle up to
//! [`RankOptions::max_zenith`] (80° by default): sorted by score, each one at least
//! [`RankOptions::min_separation`] (great-circle angle between viewing directions) from every
//! better one (greedy non-maximum suppression), then optionally refined by brute force around
//! its grid node.

use crate::analysis::scene::Observer;
use crate::analysis::sky::Quality;
use crate::engine::{Engine, Kernel};
use crate::error::{AngleProblem, Error, Result};
use crate::geometry::{direction, Geometry};
use crate::model::Material;
use crate::optics::stokes::Stokes;
use rayon::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI};

/// Limit on the number of grid directions (a 0.1° × 0.1° grid has 3.2 million).
pub const MAX_GRID_DIRECTIONS: usize = 4_000_000;

/// The light falling on both surfaces: direction toward the source and input Stokes vector.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Illumination {
    theta_i: f64,
    phi_i: f64,
    stokes: Stokes,
}

impl Illumination {
    /// Light from `(theta_i, phi_i)` (radians; `0 ≤ θi < π/2`) with input Stokes vector
    /// `stokes`, which is normalized to `S0 = 1` (results are per unit incident irradiance).
    ///
    /// # Errors
    /// [`Error::InvalidAngle`] (`sun_zenith`, `sun_azimuth`) for a source at or below the
    /// horizon, a negative zenith or a non-finite angle; [`Error::InvalidParameter`] (`stokes`)
    /// for a non-finite vector, `S0 ≤ 0` or a degree of polarization above 1.
    pub fn new(theta_i: f64, phi_i: f64, stokes: Stokes) -> Result<Self> {
        Self::named(theta_i, phi_i, stokes, ("sun_zenith", "sun_azimuth"), false)
    }

    /// As [`Illumination::new`] with the angles in degrees; errors name `sun_zenith_deg` and
    /// `sun_azimuth_deg` and give the values in degrees.
    ///
    /// # Errors
    /// As [`Illumination::new`].
    pub fn from_degrees(sun_zenith_deg: f64, sun_azimuth_deg: f64, stokes: Stokes) -> Result<Self> {
        Self::named(
            sun_zenith_deg.to_radians(),
            sun_azimuth_deg.to_radians(),
            stokes,
            ("sun_zenith_deg", "sun_azimuth_deg"),
            true,
        )
    }

    fn named(
        theta_i: f64,
        phi_i: f64,
        stokes: Stokes,
        (zenith, azimuth): (&'static str, &'static str),
        degrees: bool,
    ) -> Result<Self> {
        let unit = if degrees { 180.0 / PI } else { 1.0 };
        if !theta_i.is_finite() || !(0.0..FRAC_PI_2).contains(&theta_i) {
            return Err(Error::InvalidAngle {
                name: zenith,
                value: theta_i * unit,
                degrees,
                index: None,
                problem: AngleProblem::SourceBelowHorizon,
            });
        }
        if !(phi_i.is_finite() && phi_i.abs() <= crate::MAX_AZIMUTH_DEG.to_radians()) {
            return Err(Error::InvalidAngle {
                name: azimuth,
                value: phi_i * unit,
                degrees,
                index: None,
                problem: if phi_i.is_finite() {
                    AngleProblem::AzimuthTooLarge
                } else {
                    AngleProblem::NotFinite
                },
            });
        }
        Ok(Self {
            theta_i: theta_i + 0.0,
            phi_i,
            stokes: normalized_stokes(stokes)?,
        })
    }

    /// Zenith angle of the source (rad).
    pub fn theta_i(&self) -> f64 {
        self.theta_i
    }
    /// Azimuth of the source (rad).
    pub fn phi_i(&self) -> f64 {
        self.phi_i
    }
    /// The input Stokes vector, normalized to `S0 = 1`.
    pub fn stokes(&self) -> Stokes {
        self.stokes
    }
    /// The geometry for viewing direction `(theta_r, phi_r)` (rad; θr clamped into
    /// `[0, π/2]`).
    pub fn geometry(&self, theta_r: f64, phi_r: f64) -> Geometry {
        Geometry::new_unchecked(
            self.theta_i,
            self.phi_i,
            theta_r.clamp(0.0, FRAC_PI_2),
            phi_r,
        )
    }
}

/// Checks a Stokes vector and scales it to `S0 = 1`.
fn normalized_stokes(s: Stokes) -> Result<Stokes> {
    let bad = |value: f64, reason: &'static str| {
        Err(Error::InvalidParameter {
            name: "stokes",
            value,
            reason,
        })
    };
    if let Some(v) = s.0.iter().find(|v| !v.is_finite()) {
        return bad(*v, "every Stokes component must be finite");
    }
    let s0 = s.s0();
    if s0 <= 0.0 {
        return bad(s0, "S0 (the intensity) must be > 0");
    }
    let dop = s.dop();
    if dop > 1.0 + 1e-9 {
        return bad(
            dop,
            "degree of polarization sqrt(S1² + S2² + S3²)/S0 must be ≤ 1",
        );
    }
    Ok(Stokes(s.0.map(|v| v / s0)))
}

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

/// One material seen from one direction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ViewSample {
    /// Viewing zenith angle θr (rad).
    pub theta_r: f64,
    /// Viewing azimuth φr (rad).
    pub phi_r: f64,
    /// Scalar BRDF `F00` (sr⁻¹).
    pub brdf: f64,
    /// Reflected Stokes vector `F·S_in` per unit irradiance (sr⁻¹, psps basis).
    pub stokes: Stokes,
}

/// Evaluates one material over the grid (through the engine, in parallel): the hemispherical
/// map of its BRDF and reflected Stokes vector.
pub fn hemisphere(material: &Material, light: &Illumination, grid: &ViewGrid) -> Vec<ViewSample> {
    hemisphere_mean(&[(1.0, material.clone())], light, grid)
}

/// As [`hemisphere`], for the weighted sum over spectral nodes `(weight, material)` (the
/// weights of a band mean): BRDF and Stokes vectors are summed, never DoLPs.
pub fn hemisphere_mean(
    nodes: &[(f64, Material)],
    light: &Illumination,
    grid: &ViewGrid,
) -> Vec<ViewSample> {
    let dirs: Vec<(f64, f64)> = (0..grid.len()).map(|i| grid.direction(i)).collect();
    let geoms: Vec<Geometry> = dirs.iter().map(|&(t, p)| light.geometry(t, p)).collect();
    let mut out: Vec<ViewSample> = dirs
        .iter()
        .map(|&(theta_r, phi_r)| ViewSample {
            theta_r,
            phi_r,
            brdf: 0.0,
            stokes: Stokes([0.0; 4]),
        })
        .collect();
    for (w, material) in nodes {
        let f = Engine::new(material)
            .pbrdf_of(&geoms)
            .expect("no per-element index");
        for (o, f) in out.iter_mut().zip(&f) {
            o.brdf += w * f.m00();
            o.stokes = o.stokes.combine(1.0, &f.apply(&light.stokes), *w);
        }
    }
    out
}

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
    /// `[0, 2]`; 0 when neither reflects anything (module documentation).
    pub fn polarization_contrast(&self) -> f64 {
        let (t, b) = (&self.target.0, &self.background.0);
        let mean = 0.5 * (t[0] + b[0]);
        if mean > 0.0 {
            (t[1] - b[1]).hypot(t[2] - b[2]) / mean
        } else {
            0.0
        }
    }
    /// The ranking score: `|ΔDoLP|` or the polarization contrast.
    pub fn score(&self, by: Ranking) -> f64 {
        match by {
            Ranking::DeltaDolp => self.delta_dolp().abs(),
            Ranking::PolarizationContrast => self.polarization_contrast(),
        }
    }
    /// Unit vector of the viewing direction.
    pub fn direction(&self) -> [f64; 3] {
        direction(self.theta_r, self.phi_r)
    }
}

/// What the best directions are ranked by.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Ranking {
    /// `|ΔDoLP|` (default).
    #[default]
    DeltaDolp,
    /// The polarization contrast `|ΔS_lin|/S̄0`, which also weighs intensity.
    PolarizationContrast,
}

impl Ranking {
    /// Every score, in the order the command line lists them.
    pub const ALL: [Ranking; 2] = [Ranking::DeltaDolp, Ranking::PolarizationContrast];

    /// The name used on the command line and in files.
    pub fn as_str(&self) -> &'static str {
        match self {
            Ranking::DeltaDolp => "delta-dolp",
            Ranking::PolarizationContrast => "polarization-contrast",
        }
    }
}

impl std::str::FromStr for Ranking {
    type Err = String;
    fn from_str(s: &str) -> std::result::Result<Self, String> {
        crate::names::parse(&Self::ALL, |r| r.as_str(), s)
    }
}

/// How [`Contrast::rank`] lists the best directions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RankOptions {
    /// The score (default `|ΔDoLP|`).
    pub by: Ranking,
    /// How many directions to list (default 10).
    pub count: usize,
    /// Minimum great-circle angle between two listed directions (rad; default 10°).
    pub min_separation: f64,
    /// Largest viewing zenith angle considered (rad; default 80°). Toward grazing view the
    /// target's projected area vanishes and the facet model (with its `1/cosθr`) is least
    /// reliable, while the contrast often keeps growing up to the horizon: without this limit
    /// the "best" direction would sit at whatever zenith angle the grid happens to reach.
    pub max_zenith: f64,
    /// Refine each listed direction by brute force around its grid node (default true): the
    /// cell of ±1 grid step in θ and φ is searched on a grid 8 times finer, twice (final
    /// resolution 1/64 of the grid step), and the list is sorted again. A refined direction
    /// stays within one grid step of its node, so two listed directions may end up slightly
    /// closer than `min_separation`.
    pub refine: bool,
}

impl Default for RankOptions {
    fn default() -> Self {
        Self {
            by: Ranking::DeltaDolp,
            count: 10,
            min_separation: 10f64.to_radians(),
            max_zenith: 80f64.to_radians(),
            refine: true,
        }
    }
}

/// Target and background compared at every view direction: either under one collimated
/// source, per unit irradiance, at one wavelength or over a band — the reflected Stokes vectors
/// are the weighted sums over spectral nodes `S = Σ w_j·F_j·S_in` (one node of weight 1 for a
/// single wavelength; a band's normalized quadrature weights otherwise,
/// `crate::analysis::spectral`) — or in a scene ([`Contrast::scene`]: each surface's observed
/// Stokes radiance, emission and sky included, docs/model.md §17). Every derived quantity
/// comes from (band-integrated) Stokes vectors.
#[derive(Debug, Clone)]
pub struct Contrast {
    source: Source,
}

#[derive(Debug, Clone)]
enum Source {
    /// `(weight, target, background)` per spectral node, under one collimated source.
    Collimated {
        nodes: Vec<(f64, Material, Material)>,
        light: Illumination,
    },
    /// Each surface in its scene.
    Scene {
        target: Box<Observer>,
        background: Box<Observer>,
    },
}

/// [`ContrastSample`]s at every node of a [`ViewGrid`], zenith-major.
#[derive(Debug, Clone, PartialEq)]
pub struct ContrastMap {
    /// The grid.
    pub grid: ViewGrid,
    /// One sample per node, `samples[k·n_phi + j]`.
    pub samples: Vec<ContrastSample>,
}

impl Contrast {
    /// Target, background and illumination, at one wavelength (the materials as given).
    pub fn new(target: &Material, background: &Material, light: Illumination) -> Self {
        Self {
            source: Source::Collimated {
                nodes: vec![(1.0, target.clone(), background.clone())],
                light,
            },
        }
    }

    /// Over spectral nodes `(weight, target, background)` (the weights of a mean, summing to
    /// 1: `Spectrum::mean_nodes`).
    ///
    /// # Panics
    /// When `nodes` is empty.
    pub fn spectral(nodes: Vec<(f64, Material, Material)>, light: Illumination) -> Self {
        assert!(!nodes.is_empty(), "at least one spectral node");
        Self {
            source: Source::Collimated { nodes, light },
        }
    }

    /// Target and background each observed in its scene (typically the same sky, band and
    /// atmosphere with each surface's own temperature): their observed Stokes radiances.
    pub fn scene(target: Observer, background: Observer) -> Self {
        Self {
            source: Source::Scene {
                target: Box::new(target),
                background: Box::new(background),
            },
        }
    }

    /// The collimated illumination, `None` in a scene without one.
    pub fn light(&self) -> Option<Illumination> {
        match &self.source {
            Source::Collimated { light, .. } => Some(*light),
            Source::Scene { target, .. } => target
                .scene()
                .sun
                .and_then(|sun| Illumination::new(sun.zenith, sun.azimuth, sun.stokes).ok()),
        }
    }

    /// The target and background observers of a scene contrast.
    pub fn observers(&self) -> Option<(&Observer, &Observer)> {
        match &self.source {
            Source::Scene {
                target, background, ..
            } => Some((target, background)),
            Source::Collimated { .. } => None,
        }
    }

    /// The spectral nodes `(weight, target, background)` of a collimated contrast (empty in a
    /// scene).
    pub fn nodes(&self) -> &[(f64, Material, Material)] {
        match &self.source {
            Source::Collimated { nodes, .. } => nodes,
            Source::Scene { .. } => &[],
        }
    }

    /// Both materials seen from `(theta_r, phi_r)` (rad; θr clamped into `[0, π/2]`), by the
    /// engine's single-element path.
    pub fn at(&self, theta_r: f64, phi_r: f64) -> ContrastSample {
        let Source::Collimated { nodes, light } = &self.source else {
            return self.at_all(&[(theta_r, phi_r)])[0];
        };
        let g = light.geometry(theta_r, phi_r);
        let s = light.stokes;
        let (mut t, mut b) = (Stokes([0.0; 4]), Stokes([0.0; 4]));
        for (w, target, background) in nodes {
            t = t.combine(1.0, &Kernel::new(target).pbrdf(&g).apply(&s), *w);
            b = b.combine(1.0, &Kernel::new(background).pbrdf(&g).apply(&s), *w);
        }
        ContrastSample {
            theta_r: g.theta_r(),
            phi_r,
            target: t,
            background: b,
        }
    }

    /// Both materials seen from each direction `(θr, φr)` (rad; θr clamped into `[0, π/2]`),
    /// through the engine.
    pub fn at_all(&self, dirs: &[(f64, f64)]) -> Vec<ContrastSample> {
        self.at_all_with(dirs, Quality::Full)
    }

    /// As [`Contrast::at_all`], a scene's azimuth-dependent sky integrated at `quality`.
    pub fn at_all_with(&self, dirs: &[(f64, f64)], quality: Quality) -> Vec<ContrastSample> {
        let (nodes, light) = match &self.source {
            Source::Collimated { nodes, light } => (nodes, light),
            Source::Scene { target, background } => {
                let (t, b) = rayon::join(
                    || target.observe_with(dirs, quality),
                    || background.observe_with(dirs, quality),
                );
                return t
                    .iter()
                    .zip(&b)
                    .map(|(t, b)| ContrastSample {
                        theta_r: t.theta_r,
                        phi_r: t.phi_r,
                        target: t.stokes,
                        background: b.stokes,
                    })
                    .collect();
            }
        };
        let geoms: Vec<Geometry> = dirs.iter().map(|&(t, p)| light.geometry(t, p)).collect();
        let s = light.stokes;
        let zero = Stokes([0.0; 4]);
        let (mut t, mut b) = (vec![zero; dirs.len()], vec![zero; dirs.len()]);
        for (w, target, background) in nodes {
            let ft = Engine::new(target).pbrdf_of(&geoms).expect("no index");
            let fb = Engine::new(background).pbrdf_of(&geoms).expect("no index");
            for k in 0..dirs.len() {
                t[k] = t[k].combine(1.0, &ft[k].apply(&s), *w);
                b[k] = b[k].combine(1.0, &fb[k].apply(&s), *w);
            }
        }
        (0..dirs.len())
            .map(|k| ContrastSample {
                theta_r: geoms[k].theta_r(),
                phi_r: dirs[k].1,
                target: t[k],
                background: b[k],
            })
            .collect()
    }

    /// Whether every result is the same at all view azimuths: a scene contrast without a sun
    /// and with an azimuth-independent sky (the model is isotropic). The best directions are
    /// then rings about the normal, and [`Contrast::rank`] ranks view zeniths (at the grid's
    /// first azimuth) instead of listing one ring's azimuths.
    pub fn is_azimuth_independent(&self) -> bool {
        match &self.source {
            Source::Scene { target, background } => {
                target.is_azimuth_independent() && background.is_azimuth_independent()
            }
            Source::Collimated { .. } => false,
        }
    }

    /// Both materials over the whole grid, through the engine (a scene's azimuth-dependent sky
    /// on the map rule, [`Quality::Map`]; the ranked directions are evaluated again on the
    /// full one).
    pub fn map(&self, grid: &ViewGrid) -> ContrastMap {
        let dirs: Vec<(f64, f64)> = (0..grid.len()).map(|i| grid.direction(i)).collect();
        ContrastMap {
            grid: grid.clone(),
            samples: self.at_all_with(&dirs, Quality::Map),
        }
    }

    /// The best directions of `map`, best first (module documentation): sorted by
    /// `opts.by` (ties by grid index), each at least `opts.min_separation` from every better one,
    /// at most `opts.count`, refined by brute force when `opts.refine`. Nodes whose score is not
    /// a number are skipped.
    pub fn rank(&self, map: &ContrastMap, opts: &RankOptions) -> Vec<ContrastSample> {
        let ring = self.is_azimuth_independent();
        let first_phi = map.grid.phis().first().copied().unwrap_or(0.0);
        let mut order: Vec<(usize, f64)> = map
            .samples
            .iter()
            .enumerate()
            .filter(|(_, s)| s.theta_r <= opts.max_zenith * (1.0 + 1e-12))
            .filter(|(_, s)| !ring || s.phi_r == first_phi)
            .map(|(i, s)| (i, s.score(opts.by)))
            .filter(|(_, v)| !v.is_nan())
            .collect();
        order.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
        let mut picked: Vec<ContrastSample> = Vec::new();
        for (i, _) in order {
            if picked.len() >= opts.count {
                break;
            }
            let s = map.samples[i];
            let w = s.direction();
            let far = picked
                .iter()
                .all(|p| separation(&w, &p.direction()) >= opts.min_separation);
            if far {
                picked.push(s);
            }
        }
        // The picked nodes at full accuracy (the map may have been taken on a coarser rule).
        let dirs: Vec<(f64, f64)> = picked.iter().map(|s| (s.theta_r, s.phi_r)).collect();
        let picked = self.at_all(&dirs);
        if opts.refine {
            let mut refined: Vec<ContrastSample> = picked
                .par_iter()
                .map(|s| self.refine(s, &map.grid, opts))
                .collect();
            // Refinement raises each score by a different amount: sort again (stable).
            refined.sort_by(|a, b| b.score(opts.by).total_cmp(&a.score(opts.by)));
            refined
        } else {
            picked
        }
    }

    /// Brute-force search of the cell of ±1 grid step around `s` (clamped to the grid's zenith
    /// range and `opts.max_zenith`), on a grid 8 times finer, twice. For azimuth-independent
    /// results ([`Contrast::is_azimuth_independent`]) the search is over the zenith only: a
    /// golden-section search of the same interval down to 1/64 of the grid step, every
    /// evaluated zenith a candidate (about 12 evaluations instead of 34).
    fn refine(&self, s: &ContrastSample, grid: &ViewGrid, opts: &RankOptions) -> ContrastSample {
        const SUB: i32 = 8;
        let by = opts.by;
        let t_max = grid.theta_max().min(opts.max_zenith * (1.0 + 1e-12));
        let mut best = *s;
        if self.is_azimuth_independent() {
            let dt = grid.theta_step();
            let (mut a, mut b) = ((s.theta_r - dt).max(0.0), (s.theta_r + dt).min(t_max));
            let g = 0.5 * (5f64.sqrt() - 1.0);
            let at = |t: f64| self.at_all(&[(t, s.phi_r)])[0];
            let consider = |c: ContrastSample, best: &mut ContrastSample| {
                if c.score(by) > best.score(by) {
                    *best = c;
                }
            };
            let (mut x1, mut x2) = (b - g * (b - a), a + g * (b - a));
            let (mut f1, mut f2) = (at(x1), at(x2));
            consider(f1, &mut best);
            consider(f2, &mut best);
            while b - a > dt / 64.0 {
                // Keep the better half; NaN scores count as worst.
                if f1.score(by) >= f2.score(by) || f2.score(by).is_nan() {
                    b = x2;
                    (x2, f2) = (x1, f1);
                    x1 = b - g * (b - a);
                    f1 = at(x1);
                    consider(f1, &mut best);
                } else {
                    a = x1;
                    (x1, f1) = (x2, f2);
                    x2 = a + g * (b - a);
                    f2 = at(x2);
                    consider(f2, &mut best);
                }
            }
            return best;
        }
        if matches!(self.source, Source::Scene { .. }) {
            return self.pattern_search(s, grid, opts, t_max);
        }
        let (mut dt, mut dp) = (grid.theta_step(), grid.phi_step());
        for _ in 0..2 {
            let (t0, p0) = (best.theta_r, best.phi_r);
            let mut cells = Vec::new();
            for a in -SUB..=SUB {
                let t = t0 + dt * f64::from(a) / f64::from(SUB);
                if t < 0.0 || t > t_max {
                    continue;
                }
                for b in -SUB..=SUB {
                    cells.push((t, p0 + dp * f64::from(b) / f64::from(SUB)));
                }
            }
            // The first strictly better candidate in scan order wins, as a serial search would.
            for c in self.at_all(&cells) {
                if c.score(by) > best.score(by) {
                    best = c;
                }
            }
            dt /= f64::from(SUB);
            dp /= f64::from(SUB);
        }
        best.phi_r = best.phi_r.rem_euclid(2.0 * PI);
        best
    }
}

impl Contrast {
    /// The refinement of a scene whose results depend on azimuth (a sun, a cie-clear or table
    /// sky), where every evaluation is a sky integral: a compass search on the map rule
    /// ([`Quality::Map`]) instead of the brute-force grid — the 8 neighbours at ±h in θ and
    /// φ (h = one grid step at first), moving to the best, halving h when the centre is best,
    /// until h is 1/64 of the step (about 60 evaluations instead of 578) — confined to the
    /// ±1-step cell; the result evaluated again on the full rule.
    fn pattern_search(
        &self,
        s: &ContrastSample,
        grid: &ViewGrid,
        opts: &RankOptions,
        t_max: f64,
    ) -> ContrastSample {
        let by = opts.by;
        let (t0, p0) = (s.theta_r, s.phi_r);
        let (dt0, dp0) = (grid.theta_step(), grid.phi_step());
        let inside = |t: f64, p: f64| {
            (0.0..=t_max).contains(&t)
                && (t - t0).abs() <= dt0 * (1.0 + 1e-12)
                && (p - p0).abs() <= dp0 * (1.0 + 1e-12)
        };
        let mut best = self.at_all_with(&[(t0, p0)], Quality::Map)[0];
        let mut h = 1.0;
        while h >= 1.0 / 64.0 {
            let (bt, bp) = (best.theta_r, best.phi_r);
            let cells: Vec<(f64, f64)> = [-1.0, 0.0, 1.0]
                .iter()
                .flat_map(|a| [-1.0, 0.0, 1.0].iter().map(move |b| (*a, *b)))
                .filter(|&(a, b)| a != 0.0 || b != 0.0)
                .map(|(a, b)| (bt + a * h * dt0, bp + b * h * dp0))
                .filter(|&(t, p)| inside(t, p))
                .collect();
            let mut moved = false;
            for c in self.at_all_with(&cells, Quality::Map) {
                if c.score(by) > best.score(by) {
                    best = c;
                    moved = true;
                }
            }
            if !moved {
                h /= 2.0;
            }
        }
        let mut out = self.at_all(&[(best.theta_r, best.phi_r)])[0];
        if out.score(by) < s.score(by) {
            out = *s;
        }
        out.phi_r = out.phi_r.rem_euclid(2.0 * PI);
        out
    }
}

fn w_dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Great-circle angle between two unit vectors, accurate at small angles.
pub fn separation(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    let cross = [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ];
    let c = cross[0].hypot(cross[1]).hypot(cross[2]);
    c.atan2(w_dot(a, b))
}

/// The locus of the polarization null of the target (`target = true`) or the background on a
/// map: for each azimuth of the grid, the view zenith angles where S1 of the observed Stokes
/// vector changes sign between two grid zeniths, interpolated linearly — where the emitted
/// (p-polarized, S1 < 0) and the reflected (s-polarized) polarizations cancel in a thermal
/// scene (docs/model.md §17). `(θr, φr)` in radians, azimuth-major. A null only where S2
/// vanishes identically — in scenes symmetric about the normal
/// ([`Contrast::is_azimuth_independent`]); elsewhere an S1 sign change is the AoLP turning
/// through ±45°.
pub fn polarization_null(map: &ContrastMap, target: bool) -> Vec<(f64, f64)> {
    let grid = &map.grid;
    let (nt, np) = (grid.n_theta(), grid.n_phi());
    let s1 = |k: usize, j: usize| {
        let s = &map.samples[k * np + j];
        (
            s.theta_r,
            if target {
                s.target.0[1]
            } else {
                s.background.0[1]
            },
        )
    };
    let mut out = Vec::new();
    for j in 0..np {
        let phi = map.samples[j].phi_r;
        for k in 1..nt {
            let ((t0, a), (t1, b)) = (s1(k - 1, j), s1(k, j));
            if a != 0.0 && b != 0.0 && (a < 0.0) != (b < 0.0) {
                out.push((t0 + (t1 - t0) * a / (a - b), phi));
            } else if b == 0.0 && a != 0.0 {
                out.push((t1, phi));
            }
        }
    }
    out
}
