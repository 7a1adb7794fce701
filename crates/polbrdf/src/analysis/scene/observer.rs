//! A surface prepared for observation in a scene ([`Observer`]): its materials at the spectral
//! nodes, the terms that depend on the view zenith alone (emission, a uniform or profile sky's
//! reflection) cached per zenith, and the observed Stokes radiance at the sensor.

use super::{SkyModel, ThermalScene};
use crate::analysis::emission::emissivity_vectors;
use crate::analysis::sky::{
    sky_reflection_prepared, volume_rings, ClearSky, ProfileSky, Quality, SkyRadiance,
};
use crate::analysis::spectral::Spectrum;
use crate::analysis::thermal::planck;
use crate::error::{Error, Result};
use crate::model::{Material, MaterialSpec};
use crate::optics::stokes::Stokes;
use std::collections::HashMap;
use std::f64::consts::FRAC_PI_2;
use std::sync::{Arc, Mutex};

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
    pub(super) scene: ThermalScene,
    /// `(λ, weight of the integral, material at λ)` per spectral node.
    pub(super) nodes: Vec<(f64, f64, Material)>,
    /// Per view zenith (its bits): per spectral node, ε by route A and the profile sky's
    /// reflection (zero for other skies).
    cache: Arc<Mutex<HashMap<u64, Arc<[ZenithTerms]>>>>,
    /// A sky that depends on azimuth (cie-clear, table), with its volume rings.
    pub(super) polarized_sky: Option<PreparedSky>,
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
pub(super) type PreparedSky = (Arc<dyn SkyRadiance + Send>, Arc<[(f64, f64)]>);

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
}

/// A sky with its volume rings, computed once ([`volume_rings`]).
fn prepare(sky: Arc<dyn SkyRadiance + Send>) -> PreparedSky {
    let rings: Arc<[(f64, f64)]> = volume_rings(sky.as_ref()).into();
    (sky, rings)
}
