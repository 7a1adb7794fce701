//! Physical validity of a parameter set over a dense grid of geometries: is `F` realizable
//! everywhere, does the model conserve energy, and is it reciprocal where its form should be?

use crate::analysis::albedo::{directional_hemispherical, Albedo};
use crate::engine::Engine;
use crate::geometry::Geometry;
use crate::model::{AzimuthTerm, Material};
use crate::optics::mueller::Mueller;
use rayon::prelude::*;

/// The grid of [`physical_validity`]: zenith angles `0, step, …` below 90° for source and
/// detector, relative azimuths `0, 2·step, …` below 360° (the model depends on φr − φi only).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CheckGrid {
    /// Zenith step (rad).
    pub zenith_step: f64,
    /// Relative-azimuth step (rad).
    pub azimuth_step: f64,
}

impl Default for CheckGrid {
    fn default() -> Self {
        Self {
            zenith_step: 5f64.to_radians(),
            azimuth_step: 10f64.to_radians(),
        }
    }
}

/// What [`physical_validity`] found.
#[derive(Debug, Clone, PartialEq)]
pub struct ValidityReport {
    /// Geometries examined.
    pub geometries: usize,
    /// Smallest coherency eigenvalue relative to F00 over the grid (≥ −1e-9 when realizable),
    /// and where.
    pub min_coherency: (f64, Geometry),
    /// Directional–hemispherical reflectance at θi = 0°, 5°, …, 85°.
    pub albedo: Vec<Albedo>,
    /// Whether the model form should be reciprocal (no `eq3` azimuth factor).
    pub reciprocity_expected: bool,
    /// Largest relative deviation from reciprocity of the scalar BRDF, `|f(i→r) − f(r→i)|/f`,
    /// and of the whole matrix, `max|F(i→r) − P·F(r→i)ᵀ·P|/F00` with `P = diag(1, 1, −1, 1)`,
    /// with the geometry of the worst case.
    pub reciprocity: (f64, f64, Geometry),
}

impl ValidityReport {
    /// True when F is realizable (coherency PSD to 1e-9·F00) at every grid point.
    pub fn realizable(&self) -> bool {
        self.min_coherency.0 >= -1e-9
    }

    /// The largest albedo and its incidence angle.
    pub fn max_albedo(&self) -> Albedo {
        self.albedo
            .iter()
            .copied()
            .max_by(|a, b| a.total().total_cmp(&b.total()))
            .expect("albedo is computed at 18 angles")
    }

    /// True when no albedo exceeds 1.
    pub fn conserves_energy(&self) -> bool {
        self.albedo
            .iter()
            .all(|a| !a.violates_energy_conservation(0.0))
    }

    /// True when reciprocity holds to 1e-9 where it is expected (always true otherwise).
    pub fn reciprocal(&self) -> bool {
        !self.reciprocity_expected || self.reciprocity.0.max(self.reciprocity.1) <= 1e-9
    }

    /// All three checks pass.
    pub fn passes(&self) -> bool {
        self.realizable() && self.conserves_energy() && self.reciprocal()
    }
}

/// Checks `material` over `grid`: realizability (coherency matrix positive semidefinite),
/// energy conservation (albedo ≤ 1 at θi = 0…85°) and reciprocity (when the form has it).
pub fn physical_validity(material: &Material, grid: &CheckGrid) -> ValidityReport {
    let zeniths: Vec<f64> = (0..)
        .map(|k| k as f64 * grid.zenith_step)
        .take_while(|t| *t < std::f64::consts::FRAC_PI_2)
        .collect();
    let azimuths: Vec<f64> = (0..)
        .map(|k| k as f64 * grid.azimuth_step)
        .take_while(|p| *p < 2.0 * std::f64::consts::PI - 1e-12)
        .collect();
    let mut geoms = Vec::with_capacity(zeniths.len() * zeniths.len() * azimuths.len());
    for &ti in &zeniths {
        for &tr in &zeniths {
            for &d in &azimuths {
                geoms.push(Geometry::new(ti, 0.0, tr, d).expect("grid angles are valid"));
            }
        }
    }
    // F at every grid geometry and at its reciprocal, through the engine.
    let engine = Engine::new(material);
    let forward = engine.pbrdf_of(&geoms).expect("no per-element index");
    let reciprocal: Vec<Geometry> = geoms.iter().map(Geometry::reciprocal).collect();
    let backward = engine.pbrdf_of(&reciprocal).expect("no per-element index");
    let p = [1.0, 1.0, -1.0, 1.0];
    let per_geometry: Vec<(f64, f64, f64, Geometry)> = (0..geoms.len())
        .into_par_iter()
        .map(|k| {
            let (f, r): (&Mueller, &Mueller) = (&forward[k], &backward[k]);
            let f00 = f.m00();
            let min_ev = if f00 > 0.0 {
                f.coherency_eigenvalues()[0] / f00
            } else {
                0.0
            };
            let scale = f00.max(r.m00()).max(f64::MIN_POSITIVE);
            let scalar = (f00 - r.m00()).abs() / scale;
            let mut matrix: f64 = 0.0;
            for i in 0..4 {
                for j in 0..4 {
                    matrix = matrix.max((f[(i, j)] - p[i] * r[(j, i)] * p[j]).abs() / scale);
                }
            }
            (min_ev, scalar, matrix, geoms[k])
        })
        .collect();
    let min_coherency = per_geometry
        .iter()
        .map(|x| (x.0, x.3))
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .expect("non-empty grid");
    let reciprocity = per_geometry
        .iter()
        .map(|x| (x.1, x.2, x.3))
        .max_by(|a, b| a.0.max(a.1).total_cmp(&b.0.max(b.1)))
        .expect("non-empty grid");
    let albedo = (0..18)
        .into_par_iter()
        .map(|k| directional_hemispherical(material, (5.0 * k as f64).to_radians()))
        .collect();
    ValidityReport {
        geometries: geoms.len(),
        min_coherency,
        albedo,
        reciprocity_expected: material
            .shadowing()
            .is_none_or(|s| s.azimuth_term() == AzimuthTerm::None),
        reciprocity,
    }
}
