//! The observed Stokes radiance of a surface in a scene (docs/model.md §17): its own thermal
//! emission, the sky it reflects, and the atmosphere between it and the sensor.
//!
//! At wavelength λ, for a surface at temperature T seen from `w_r`:
//! `S(w_r) = B_λ(λ, T)·ε(w_r) + ∫_H F(w, w_r)·L_sky(w) cosθ dω`, and at the sensor
//! `S_sensor = τ·S + L_path·e0`. With a uniform unpolarized sky of radiance `L_d` (`uniform`, or
//! `thermal` with `L_d = B_λ(λ, T_sky)`) the sky term is exactly `L_d·(e0 − ε)`, so
//! `S = L_d·e0 + (B_λ(T) − L_d)·ε`: the emitted and reflected polarizations cancel when
//! `B_λ(T) = L_d` (the polarization null), and the sign of S1 (the AoLP turns by 90°) flips
//! when the sky is the brighter. A tabulated sky profile takes the general sky integral
//! ([`crate::analysis::sky`]).
//!
//! Over a band the Stokes radiance is integrated, `∫ R(λ)·S(λ) dλ` (W·m⁻²·sr⁻¹), at the nodes of
//! [`crate::analysis::spectral::Spectrum::integral_nodes`]; at one wavelength it is the spectral
//! radiance (W·m⁻²·sr⁻¹·µm⁻¹). A sky's `radiance` and the path radiance are spectral radiances,
//! taken as constant across a band.

use crate::analysis::emission::emissivity_vectors;
use crate::analysis::sky::{
    sky_reflection_prepared, sky_reflections_at_zenith, volume_rings, ClearSky, ProfileSky,
    Quality, SkyRadiance, TableSky, ZenithProfile,
};
use crate::analysis::spectral::Spectrum;
use crate::analysis::thermal::{planck, temperature};
use crate::error::{Error, Result};
use crate::model::{Material, MaterialSpec};
use crate::optics::stokes::Stokes;
use std::collections::HashMap;
use std::f64::consts::{FRAC_PI_2, PI};
use std::sync::{Arc, Mutex};

mod null;
pub use null::null_temperature;

/// The sky of a thermal scene.
#[derive(Debug, Clone, PartialEq)]
pub enum SkyModel {
    /// No sky: nothing to reflect (`model = "none"`).
    None,
    /// A uniform unpolarized sky of spectral radiance `radiance` (W·m⁻²·sr⁻¹·µm⁻¹) at every
    /// wavelength (`model = "uniform"`).
    Uniform {
        /// Spectral radiance.
        radiance: f64,
    },
    /// A uniform unpolarized sky radiating as a blackbody at its brightness temperature
    /// (`model = "thermal"`): `L_d = B_λ(λ, T_sky)`.
    Thermal {
        /// Brightness temperature (K).
        temperature_k: f64,
    },
    /// An unpolarized sky whose spectral radiance depends on the zenith angle, tabulated
    /// (`model = "profile"`), the same at every wavelength.
    Profile(ZenithProfile),
    /// The CIE standard clear sky with Rayleigh polarization (`model = "cie-clear"`,
    /// [`ClearSky`]) for the scene's sun, scaled to a horizontal (spectral) irradiance, the same
    /// at every wavelength. Needs a [`Sun`] for its position.
    ClearSky {
        /// The sky's horizontal irradiance `∫_H L cosθ dω` (W·m⁻²·µm⁻¹).
        irradiance: f64,
        /// The maximum degree of polarization δ_max (90° from the sun), in [0, 1].
        dop_max: f64,
    },
    /// A tabulated Stokes sky (`model = "table"`, [`TableSky`]), the same at every wavelength.
    Table(TableSky),
}

impl SkyModel {
    /// The uniform radiance at `lambda_um`, `None` for a sky that is not uniform.
    fn uniform_at(&self, lambda_um: f64) -> Option<f64> {
        match self {
            SkyModel::None => Some(0.0),
            SkyModel::Uniform { radiance } => Some(*radiance),
            SkyModel::Thermal { temperature_k } => Some(planck(lambda_um, *temperature_k)),
            SkyModel::Profile(_) | SkyModel::ClearSky { .. } | SkyModel::Table(_) => None,
        }
    }

    /// Whether the sky is the same at every azimuth.
    pub fn is_azimuth_independent(&self) -> bool {
        !matches!(self, SkyModel::ClearSky { .. } | SkyModel::Table(_))
    }
}

/// Transmittance and path radiance between the surface and the sensor.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Atmosphere {
    /// Transmittance τ in `[0, 1]` (default 1).
    pub transmittance: f64,
    /// Unpolarized path spectral radiance (W·m⁻²·sr⁻¹·µm⁻¹, default 0), constant across a band.
    pub path_radiance: f64,
}

impl Default for Atmosphere {
    fn default() -> Self {
        Self {
            transmittance: 1.0,
            path_radiance: 0.0,
        }
    }
}

/// The sun: a collimated source from `(zenith, azimuth)` of irradiance `irradiance` on a
/// plane normal to its beam (W·m⁻²·µm⁻¹, the same at every wavelength) and Stokes vector
/// `stokes` (in the arriving beam's psps basis, normalized to `s0 = 1`). Its contribution to
/// the observed radiance is `E·cosθs·F(w_s, w_r)·s` (docs/model.md §18).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sun {
    /// Zenith angle (rad), in `[0, π/2)`.
    pub zenith: f64,
    /// Azimuth (rad).
    pub azimuth: f64,
    /// Irradiance normal to the beam (≥ 0).
    pub irradiance: f64,
    /// Stokes vector, `s0 = 1` (unpolarized: `(1, 0, 0, 0)`).
    pub stokes: Stokes,
}

impl Sun {
    /// The default azimuth of the sun (rad) when a scene gives only its zenith angle.
    pub const DEFAULT_AZIMUTH: f64 = 0.0;

    /// An unpolarized sun.
    pub fn unpolarized(zenith: f64, azimuth: f64, irradiance: f64) -> Self {
        Self {
            zenith,
            azimuth,
            irradiance,
            stokes: Stokes::unpolarized(),
        }
    }
}

/// A scene: the surface's temperature (no emission without one), the sun (none by default),
/// the sky and the atmosphere.
#[derive(Debug, Clone, PartialEq)]
pub struct ThermalScene {
    /// The surface temperature (K); `None`: no thermal emission.
    pub surface_temperature_k: Option<f64>,
    /// The sky.
    pub sky: SkyModel,
    /// The atmosphere.
    pub atmosphere: Atmosphere,
    /// The sun; `None`: no collimated source.
    pub sun: Option<Sun>,
}

/// Another name for [`ThermalScene`], which holds daylight scenes as well.
pub type Scene = ThermalScene;

impl ThermalScene {
    /// Checks every value.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `surface.temperature_k`, `sun.zenith_deg` (the sun
    /// must be above the horizon), `sun.azimuth_deg` (finite, |φs| ≤ [`crate::MAX_AZIMUTH_DEG`]
    /// as every azimuth), `sun.irradiance`, `sun.stokes`,
    /// `sky.radiance`, `sky.temperature_k`, `sky.irradiance`, `sky.dop_max`,
    /// `atmosphere.transmittance` or `atmosphere.path_radiance` (radiances and irradiances
    /// finite, ≥ 0 and at most 1e150); [`Error::InconsistentParameters`] for a cie-clear sky
    /// without a sun.
    pub fn validate(&self) -> Result<()> {
        if let Some(t) = self.surface_temperature_k {
            temperature("surface.temperature_k", t)?;
        }
        if let Some(sun) = &self.sun {
            if !(sun.zenith.is_finite() && (0.0..FRAC_PI_2).contains(&sun.zenith)) {
                return Err(Error::InvalidParameter {
                    name: "sun.zenith_deg",
                    value: sun.zenith.to_degrees(),
                    reason: "the sun must be above the horizon: in [0, 90) degrees",
                });
            }
            if !(sun.azimuth.is_finite()
                && sun.azimuth.abs() <= crate::MAX_AZIMUTH_DEG.to_radians())
            {
                return Err(Error::InvalidParameter {
                    name: "sun.azimuth_deg",
                    value: sun.azimuth.to_degrees(),
                    reason: "must be finite and at most 1e8 degrees in magnitude \
                             (polbrdf::MAX_AZIMUTH_DEG)",
                });
            }
            crate::error::radiometric("sun.irradiance", sun.irradiance)?;
            let st = sun.stokes.0;
            if st.iter().any(|v| !v.is_finite())
                || (st[0] - 1.0).abs() > 1e-12
                || st[1].hypot(st[2]).hypot(st[3]) > 1.0 + 1e-9
            {
                return Err(Error::InvalidParameter {
                    name: "sun.stokes",
                    value: st[0],
                    reason: "must be finite, normalized to s0 = 1 and of degree of \
                             polarization at most 1",
                });
            }
        }
        match &self.sky {
            SkyModel::Uniform { radiance } => {
                crate::error::radiometric("sky.radiance", *radiance)?;
            }
            SkyModel::Thermal { temperature_k } => {
                temperature("sky.temperature_k", *temperature_k)?;
            }
            SkyModel::ClearSky {
                irradiance,
                dop_max,
            } => {
                let Some(sun) = &self.sun else {
                    return Err(Error::InconsistentParameters(
                        "the cie-clear sky needs a sun ([sun] zenith_deg, azimuth_deg): its \
                         radiance and polarization are set by the sun's position"
                            .into(),
                    ));
                };
                ClearSky::new(sun.zenith, sun.azimuth, *irradiance, *dop_max)?;
            }
            SkyModel::None | SkyModel::Profile(_) | SkyModel::Table(_) => {}
        }
        let t = self.atmosphere.transmittance;
        if !(t.is_finite() && (0.0..=1.0).contains(&t)) {
            return Err(Error::InvalidParameter {
                name: "atmosphere.transmittance",
                value: t,
                reason: "must lie in [0, 1]",
            });
        }
        crate::error::radiometric("atmosphere.path_radiance", self.atmosphere.path_radiance)?;
        Ok(())
    }

    /// Whether what a surface observes here is the same at every view azimuth: no sun and an
    /// azimuth-independent sky (the model is isotropic).
    pub fn is_azimuth_independent(&self) -> bool {
        self.sun.is_none() && self.sky.is_azimuth_independent()
    }

    /// The same scene with the sun's azimuth taken into `[0, 2π)` when it lies outside
    /// `[−2π, 2π]` (the same direction): the views folded about the sun's vertical plane then
    /// stay within a turn of it, inside [`crate::MAX_AZIMUTH_DEG`], however large the sun's
    /// azimuth (a sun at the bound itself put a folded view beyond it: issue 35). Azimuths
    /// within a turn are kept as given, bit for bit.
    fn with_sun_azimuth_reduced(&self) -> Self {
        let mut scene = self.clone();
        if let Some(sun) = scene.sun.as_mut() {
            if sun.azimuth.abs() > 2.0 * PI {
                sun.azimuth = sun.azimuth.rem_euclid(2.0 * PI);
            }
        }
        scene
    }

    /// The same scene with another surface temperature.
    pub fn with_surface_temperature(&self, t: Option<f64>) -> Self {
        Self {
            surface_temperature_k: t,
            ..self.clone()
        }
    }
}

/// One observed Stokes radiance with its ingredients.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Radiance {
    /// View zenith θr (rad).
    pub theta_r: f64,
    /// View azimuth φr (rad).
    pub phi_r: f64,
    /// At the sensor: `τ·(emitted + reflected) + L_path·e0`.
    pub stokes: Stokes,
    /// The emitted part `B·ε` at the surface.
    pub emitted: Stokes,
    /// The reflected sky at the surface.
    pub reflected: Stokes,
}

/// A surface prepared for observation in a scene: its materials at the spectral nodes, the
/// scene validated — [`Observer::observe`] cannot fail.
///
/// The model is isotropic, so what the surface emits — and reflects of an azimuth-independent
/// sky — toward `(θr, φr)` depends on θr alone (its Stokes vector is in the basis of the view's
/// own plane): it is computed once per distinct view zenith and kept — a second `observe` at the
/// same zeniths (the refinement of a contrast's best directions, the other azimuths of a map)
/// costs no quadrature. Clones share that cache. The sun and an azimuth-dependent sky
/// (cie-clear, table) are computed per distinct view, folded by the scene's mirror symmetry
/// where it has one.
#[derive(Debug, Clone)]
pub struct Observer {
    scene: ThermalScene,
    /// `(λ, weight of the integral, material at λ)` per spectral node.
    nodes: Vec<(f64, f64, Material)>,
    /// Per view zenith (its bits): per spectral node, ε by route A and the profile sky's
    /// reflection (zero for other skies).
    cache: Arc<Mutex<HashMap<u64, Arc<[ZenithTerms]>>>>,
    /// A sky that depends on azimuth (cie-clear, table), with its volume rings.
    polarized_sky: Option<PreparedSky>,
    /// A profile sky (azimuth-independent, through the general sky integral), with its
    /// volume rings.
    profile_sky: Option<PreparedSky>,
}

impl std::fmt::Debug for dyn SkyRadiance + Send {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("SkyRadiance")
    }
}

/// An azimuth-dependent sky with its volume rings ([`volume_rings`]).
type PreparedSky = (Arc<dyn SkyRadiance + Send>, Arc<[(f64, f64)]>);

/// What a surface emits and reflects toward one view zenith at one spectral node.
#[derive(Debug, Clone, Copy)]
struct ZenithTerms {
    eps: Stokes,
    profile_reflection: Stokes,
}

/// [`Observer::work`] of one azimuth-dependent sky integral at one view and spectral node,
/// relative to one evaluation: measured 1.0 ms against 1.1 µs per view and node of a sun-only
/// scene (`polbrdf radiance`, one thread, olive paint at 0.55 µm; docs/io.md).
pub const SKY_INTEGRAL_WORK: f64 = 1000.0;

/// Views closer to the horizon than this (rad) are observed at `π/2 − HORIZON_MARGIN`.
pub const HORIZON_MARGIN: f64 = 1e-7;

impl Observer {
    /// The work of observing `views` views, in units of one evaluation at one spectral node
    /// (about 1 µs on one core of the reference host, docs/io.md "Resource model"): per view and
    /// spectral node, 1 for the sun and the azimuth-independent terms, [`SKY_INTEGRAL_WORK`]
    /// for the integral of an azimuth-dependent sky (cie-clear, table), which is taken per view.
    pub fn work(&self, views: usize) -> f64 {
        let per_node = if self.polarized_sky.is_some() {
            SKY_INTEGRAL_WORK
        } else {
            1.0
        };
        views as f64 * self.nodes.len() as f64 * per_node
    }

    /// Whether the sky depends on azimuth (cie-clear, table): its integral is taken per view.
    pub fn has_azimuth_sky(&self) -> bool {
        self.polarized_sky.is_some()
    }

    /// `spec` in `scene` at one wavelength or over a band ([`Spectrum::integral_nodes`]).
    ///
    /// # Errors
    /// As [`ThermalScene::validate`]; [`Error::WavelengthOutOfRange`] where the spectrum leaves
    /// a spectral index's data; [`Error::InconsistentParameters`] for the `paper` form (no
    /// emissivity).
    pub fn new(spec: &MaterialSpec, scene: &ThermalScene, spectrum: &Spectrum) -> Result<Self> {
        scene.validate()?;
        let scene = &scene.with_sun_azimuth_reduced();
        let nodes = spectrum.integral_nodes(&[spec]);
        let materials = Spectrum::materials(spec, &nodes)?;
        if let Some(m) = materials.first() {
            if crate::analysis::albedo::surface_integral_diverges(m) {
                return Err(Error::InconsistentParameters(
                    "the `paper` form has no emissivity and reflects an infinite sky radiance: \
                     its f·cosθ grows like 1/cosθ toward the horizon (use form = \"standard\")"
                        .into(),
                ));
            }
        }
        let polarized_sky: Option<Arc<dyn SkyRadiance + Send>> = match &scene.sky {
            SkyModel::ClearSky {
                irradiance,
                dop_max,
            } => {
                let sun = scene.sun.expect("validated: a clear sky has a sun");
                Some(Arc::new(ClearSky::new(
                    sun.zenith,
                    sun.azimuth,
                    *irradiance,
                    *dop_max,
                )?))
            }
            SkyModel::Table(t) => Some(Arc::new(t.clone())),
            _ => None,
        };
        Ok(Self {
            scene: scene.clone(),
            nodes: nodes
                .iter()
                .zip(materials)
                .map(|((l, w), m)| (*l, *w, m))
                .collect(),
            cache: Arc::default(),
            polarized_sky: polarized_sky.map(prepare),
            profile_sky: match &scene.sky {
                SkyModel::Profile(profile) => Some(prepare(Arc::new(ProfileSky {
                    profile: profile.clone(),
                    scale: 1.0,
                }))),
                _ => None,
            },
        })
    }

    /// Whether every observation is the same at all view azimuths
    /// ([`ThermalScene::is_azimuth_independent`]).
    pub fn is_azimuth_independent(&self) -> bool {
        self.scene.is_azimuth_independent()
    }

    /// The scene.
    pub fn scene(&self) -> &ThermalScene {
        &self.scene
    }

    /// The number of spectral nodes (1 at one wavelength).
    pub fn spectral_nodes(&self) -> usize {
        self.nodes.len()
    }

    /// The terms of every zenith of `zeniths` (clamped, distinct), computing the missing ones:
    /// all missing zeniths of one spectral node in one batched call.
    fn terms(&self, zeniths: &[f64]) -> Vec<Arc<[ZenithTerms]>> {
        let missing: Vec<f64> = {
            let cache = self.cache.lock().expect("no panic while holding the cache");
            zeniths
                .iter()
                .copied()
                .filter(|t| !cache.contains_key(&t.to_bits()))
                .collect()
        };
        if !missing.is_empty() {
            use rayon::prelude::*;
            // The terms depend on the material at a node only: spectral nodes with the same
            // material (every node of a constant-index material) share one computation.
            let mut distinct: Vec<&Material> = Vec::new();
            let which: Vec<usize> = self
                .nodes
                .iter()
                .map(|(_, _, m)| {
                    distinct.iter().position(|d| *d == m).unwrap_or_else(|| {
                        distinct.push(m);
                        distinct.len() - 1
                    })
                })
                .collect();
            // per distinct material, per missing zenith
            let per_material: Vec<Vec<ZenithTerms>> = distinct
                .par_iter()
                .map(|m| {
                    let eps = emissivity_vectors(m, &missing)
                        .expect("validated material and clamped angles");
                    let profile: Vec<Stokes> = match &self.profile_sky {
                        Some((sky, rings)) => missing
                            .par_iter()
                            .map(|&t| {
                                sky_reflection_prepared(
                                    m,
                                    t,
                                    0.0,
                                    sky.as_ref(),
                                    rings,
                                    Quality::Full,
                                )
                                .expect("validated material and clamped angles")
                            })
                            .collect(),
                        None => vec![Stokes([0.0; 4]); missing.len()],
                    };
                    eps.into_iter()
                        .zip(profile)
                        .map(|(eps, profile_reflection)| ZenithTerms {
                            eps,
                            profile_reflection,
                        })
                        .collect()
                })
                .collect();
            let mut cache = self.cache.lock().expect("no panic while holding the cache");
            for (j, t) in missing.iter().enumerate() {
                let row: Arc<[ZenithTerms]> = which.iter().map(|&d| per_material[d][j]).collect();
                cache.insert(t.to_bits(), row);
            }
        }
        let cache = self.cache.lock().expect("no panic while holding the cache");
        zeniths
            .iter()
            .map(|t| Arc::clone(&cache[&t.to_bits()]))
            .collect()
    }

    /// The observed Stokes radiance at every view `(θr, φr)` (rad; θr clamped into
    /// `[0, π/2 − HORIZON_MARGIN]`, φr any finite value).
    ///
    /// # Panics
    /// For a non-finite view angle.
    pub fn observe(&self, views: &[(f64, f64)]) -> Vec<Radiance> {
        self.observe_with(views, Quality::Full)
    }

    /// As [`Observer::observe`], with the sky integral of an azimuth-dependent sky taken at
    /// `quality` ([`Quality::Map`] for hemispherical maps).
    ///
    /// # Panics
    /// For a non-finite view angle.
    pub fn observe_with(&self, views: &[(f64, f64)], quality: Quality) -> Vec<Radiance> {
        let clamp = |t: f64| t.clamp(0.0, FRAC_PI_2 - HORIZON_MARGIN);
        // Distinct view zeniths, in first-seen order.
        let mut zeniths: Vec<f64> = Vec::new();
        let mut index = HashMap::new();
        let zi: Vec<usize> = views
            .iter()
            .map(|&(t, p)| {
                assert!(t.is_finite() && p.is_finite(), "view ({t}, {p}) not finite");
                *index.entry(clamp(t).to_bits()).or_insert_with(|| {
                    zeniths.push(clamp(t));
                    zeniths.len() - 1
                })
            })
            .collect();
        let terms = self.terms(&zeniths);
        // Per distinct zenith: emitted and reflected, summed over the spectral nodes.
        let zero = Stokes([0.0; 4]);
        let mut emitted = vec![zero; zeniths.len()];
        let mut reflected = vec![zero; zeniths.len()];
        let mut path = 0.0;
        for (j, (lambda, w, _)) in self.nodes.iter().enumerate() {
            let b = self
                .scene
                .surface_temperature_k
                .map_or(0.0, |t| planck(*lambda, t));
            let uniform = self.scene.sky.uniform_at(*lambda);
            for (z, row) in terms.iter().enumerate() {
                let ZenithTerms {
                    eps: e,
                    profile_reflection,
                } = row[j];
                emitted[z] = emitted[z].combine(1.0, &e, w * b);
                let r = match uniform {
                    Some(l) => Stokes([l * (1.0 - e.0[0]), -l * e.0[1], -l * e.0[2], -l * e.0[3]]),
                    None => profile_reflection,
                };
                reflected[z] = reflected[z].combine(1.0, &r, *w);
            }
            path += w * self.scene.atmosphere.path_radiance;
        }
        // What depends on the view azimuth: the sun and an azimuth-dependent sky, per view.
        let per_view = self.azimuth_terms(views, clamp, quality);
        let tau = self.scene.atmosphere.transmittance;
        views
            .iter()
            .zip(&zi)
            .enumerate()
            .map(|(k, (&(t, p), &z))| {
                let reflected = match &per_view {
                    Some(v) => reflected[z].combine(1.0, &v[k], 1.0),
                    None => reflected[z],
                };
                let mut s = emitted[z].combine(tau, &reflected, tau);
                s.0[0] += path;
                Radiance {
                    theta_r: clamp(t),
                    phi_r: p,
                    stokes: s,
                    emitted: emitted[z],
                    reflected,
                }
            })
            .collect()
    }

    /// The sun's reflection `E·cosθs·F(w_s, w_r)·s` and an azimuth-dependent sky's
    /// `∫_H F(w, w_r)·L_sky(w) cosθ dω`, summed over the spectral nodes, per view (distinct
    /// views in parallel); `None` when there is neither.
    ///
    /// When the scene is mirror-symmetric about the sun's vertical plane (a clear sky or none,
    /// a sun whose Stokes vector has `s2 = s3 = 0`), a view at `φs − Δ` is the mirror image of
    /// the one at `φs + Δ`: the same Stokes vector with `s2` and `s3` negated (the mirror
    /// turns `s_out` into `−s_out'` and keeps `p_out`). Each view is folded to `Δ ∈ [0, π]` and
    /// every distinct folded view computed once.
    fn azimuth_terms(
        &self,
        views: &[(f64, f64)],
        clamp: impl Fn(f64) -> f64 + Sync,
        quality: Quality,
    ) -> Option<Vec<Stokes>> {
        use rayon::prelude::*;
        if self.scene.sun.is_none() && self.polarized_sky.is_none() {
            return None;
        }
        let mirror = match (&self.scene.sun, &self.scene.sky) {
            (Some(sun), SkyModel::ClearSky { .. } | SkyModel::None)
            | (Some(sun), SkyModel::Uniform { .. } | SkyModel::Thermal { .. })
            | (Some(sun), SkyModel::Profile(_)) => {
                (sun.stokes.0[2] == 0.0 && sun.stokes.0[3] == 0.0).then_some(sun.azimuth)
            }
            _ => None,
        };
        // Fold, and deduplicate (to 1e-12 rad).
        let mut keys = HashMap::new();
        let mut distinct: Vec<(f64, f64)> = Vec::new();
        let map: Vec<(usize, bool)> = views
            .iter()
            .map(|&(t, p)| {
                let t = clamp(t);
                let (p, flipped) = match mirror {
                    Some(ps) => {
                        let d = (p - ps + PI).rem_euclid(2.0 * PI) - PI;
                        (ps + d.abs(), d < 0.0)
                    }
                    None => (p, false),
                };
                let key = (t.to_bits(), (p * 1e12).round() as i64);
                let i = *keys.entry(key).or_insert_with(|| {
                    distinct.push((t, p));
                    distinct.len() - 1
                });
                (i, flipped)
            })
            .collect();
        if quality == Quality::Map {
            let values = self.map_terms(&distinct);
            return Some(unfold(&map, &values));
        }
        let values: Vec<Stokes> = distinct
            .par_iter()
            .map(|&(t, p)| {
                let mut total = Stokes([0.0; 4]);
                for (_, w, m) in &self.nodes {
                    let mut r = Stokes([0.0; 4]);
                    if let Some(sun) = &self.scene.sun {
                        r = sun_term(m, sun, t, p);
                    }
                    if let Some((sky, rings)) = &self.polarized_sky {
                        let sky_r = sky_reflection_prepared(m, t, p, sky.as_ref(), rings, quality)
                            .expect("validated material and clamped angles");
                        r = r.combine(1.0, &sky_r, 1.0);
                    }
                    total = total.combine(1.0, &r, *w);
                }
                total
            })
            .collect();
        Some(unfold(&map, &values))
    }

    /// [`Observer::azimuth_terms`] for a map: the views grouped by zenith, each group's sky
    /// integrals through [`sky_reflections_at_zenith`] (the Mueller matrices at the facet
    /// nodes shared by every azimuth), groups in parallel.
    fn map_terms(&self, views: &[(f64, f64)]) -> Vec<Stokes> {
        use rayon::prelude::*;
        let mut groups: Vec<(f64, Vec<usize>)> = Vec::new();
        let mut by_zenith: HashMap<u64, usize> = HashMap::new();
        for (k, &(t, _)) in views.iter().enumerate() {
            let g = *by_zenith.entry(t.to_bits()).or_insert_with(|| {
                groups.push((t, Vec::new()));
                groups.len() - 1
            });
            groups[g].1.push(k);
        }
        let parts: Vec<Vec<(usize, Stokes)>> = groups
            .par_iter()
            .map(|(t, members)| {
                let phis: Vec<f64> = members.iter().map(|&k| views[k].1).collect();
                let mut total = vec![Stokes([0.0; 4]); members.len()];
                for (_, w, m) in &self.nodes {
                    if let Some((sky, rings)) = &self.polarized_sky {
                        let r = sky_reflections_at_zenith(
                            m,
                            *t,
                            &phis,
                            sky.as_ref(),
                            rings,
                            Quality::Map,
                        );
                        for (a, b) in total.iter_mut().zip(&r) {
                            *a = a.combine(1.0, b, *w);
                        }
                    }
                    if let Some(sun) = &self.scene.sun {
                        for (a, &p) in total.iter_mut().zip(&phis) {
                            *a = a.combine(1.0, &sun_term(m, sun, *t, p), *w);
                        }
                    }
                }
                members.iter().copied().zip(total).collect()
            })
            .collect();
        let mut out = vec![Stokes([0.0; 4]); views.len()];
        for (k, s) in parts.into_iter().flatten() {
            out[k] = s;
        }
        out
    }
}

/// A sky with its volume rings, computed once ([`volume_rings`]).
fn prepare(sky: Arc<dyn SkyRadiance + Send>) -> PreparedSky {
    let rings: Arc<[(f64, f64)]> = volume_rings(sky.as_ref()).into();
    (sky, rings)
}

/// The sun's reflection toward `(theta_r, phi_r)`: `E·cosθs·F(w_s, w_r)·s`.
fn sun_term(m: &Material, sun: &Sun, theta_r: f64, phi_r: f64) -> Stokes {
    let g = crate::geometry::Geometry::new(sun.zenith, sun.azimuth, theta_r, phi_r)
        .expect("validated sun and clamped view");
    let e = sun.irradiance * sun.zenith.cos();
    Stokes([0.0; 4]).combine(1.0, &m.pbrdf(&g).apply(&sun.stokes), e)
}

/// The values of folded views back at every view: `(index, mirrored)` per view, a mirror image
/// with S2 and S3 negated.
fn unfold(map: &[(usize, bool)], values: &[Stokes]) -> Vec<Stokes> {
    map.iter()
        .map(|&(i, flipped)| {
            let s = values[i];
            if flipped {
                Stokes([s.0[0], s.0[1], -s.0[2], -s.0[3]])
            } else {
                s
            }
        })
        .collect()
}

/// The observed Stokes radiance of `spec` in `scene` at every view `(θr, φr)` (rad) of
/// `views`, at one wavelength or integrated over a band ([`Spectrum::integral_nodes`]): an
/// [`Observer`] observing once.
///
/// # Errors
/// As [`Observer::new`]; [`Error::InvalidAngle`] for a view outside `[0, π/2)` or a
/// non-finite azimuth (with its position).
pub fn observed_radiance(
    spec: &MaterialSpec,
    scene: &ThermalScene,
    spectrum: &Spectrum,
    views: &[(f64, f64)],
) -> Result<Vec<Radiance>> {
    check_views(views)?;
    Ok(Observer::new(spec, scene, spectrum)?.observe(views))
}

/// Checks the views `(θr, φr)` (radians) of [`observed_radiance`]: θr in `[0, π/2)`, φr finite
/// and within ±[`crate::MAX_AZIMUTH_DEG`], for an adapter that builds its [`Observer`] itself
/// (to bound the work first, [`Observer::work`]).
///
/// # Errors
/// [`Error::InvalidAngle`] naming the first bad view by its index.
pub fn check_views(views: &[(f64, f64)]) -> Result<()> {
    for (i, &(t, p)) in views.iter().enumerate() {
        let (name, value, problem) = if !p.is_finite() {
            ("phi_r", p, crate::error::AngleProblem::NotFinite)
        } else if p.abs() > crate::MAX_AZIMUTH_DEG.to_radians() {
            ("phi_r", p, crate::error::AngleProblem::AzimuthTooLarge)
        } else if !(t.is_finite() && (0.0..FRAC_PI_2).contains(&t)) {
            ("theta_r", t, crate::error::AngleProblem::ViewBelowHorizon)
        } else {
            continue;
        };
        return Err(Error::InvalidAngle {
            name,
            value,
            degrees: false,
            index: Some(i),
            problem,
        });
    }
    Ok(())
}
