//! What a surface observes that depends on the view azimuth: the sun's reflection and an
//! azimuth-dependent sky's integral, per view, folded by the scene's mirror symmetry.

use super::{Observer, SkyModel, Sun};
use crate::analysis::sky::{sky_reflection_prepared, sky_reflections_at_zenith, Quality};
use crate::model::Material;
use crate::optics::stokes::Stokes;
use std::collections::HashMap;
use std::f64::consts::PI;

impl Observer {
    /// The sun's reflection `E·cosθs·F(w_s, w_r)·s` and an azimuth-dependent sky's
    /// `∫_H F(w, w_r)·L_sky(w) cosθ dω`, summed over the spectral nodes, per view (distinct
    /// views in parallel); `None` when there is neither.
    ///
    /// When the scene is mirror-symmetric about the sun's vertical plane (a clear sky or none,
    /// a sun whose Stokes vector has `s2 = s3 = 0`), a view at `φs − Δ` is the mirror image of
    /// the one at `φs + Δ`: the same Stokes vector with `s2` and `s3` negated (the mirror
    /// turns `s_out` into `−s_out'` and keeps `p_out`). Each view is folded to `Δ ∈ [0, π]` and
    /// every distinct folded view computed once.
    pub(super) fn azimuth_terms(
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
