//! One material over the viewing hemisphere under a collimated source: the map of its BRDF and
//! reflected Stokes vector.

use super::{Illumination, ViewGrid};
use crate::engine::Engine;
use crate::geometry::Geometry;
use crate::model::Material;
use crate::optics::stokes::Stokes;

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
            o.stokes = o.stokes.combine(1.0, &f.apply(&light.stokes()), *w);
        }
    }
    out
}
