//! The interactive explorer's job (the web page, docs/explorer.md): one material under a
//! collimated source over the viewing hemisphere — the full pBRDF `F` at every grid direction
//! with the BRDF and the reflected Stokes vector (and its DoLP and AoLP) — and the in-plane
//! curves (the paper's Figs. 2–4: the plane of incidence, and the specular direction against
//! the angle of incidence). Materials come as [`NamedMaterial`]s, e.g. parsed from the text of
//! a material file ([`NamedMaterial::parse`]); the contrast against a background is
//! [`crate::contrast::contrast_of`].

use crate::error::TaskResult;
use crate::hemisphere::{deg, view_grid, LightRequest};
use crate::spectrum::{material_at, NamedMaterial, SpectrumSource};
use polbrdf::analysis::contrast::{Illumination, ViewGrid};
use polbrdf::{Engine, GeometryBatch, Material, Mueller, Spectrum, Stokes};
use std::f64::consts::{FRAC_PI_2, PI};

/// The full-Mueller map of [`mueller_map`]: for grid node `i` (zenith-major, as
/// [`ViewGrid::direction`]), `mueller[i]` is `F` (row-major, psps basis, sr⁻¹; the weighted
/// sum over the spectrum's nodes) and `stokes[i] = F·S_in` per unit irradiance.
#[derive(Debug, Clone)]
pub struct MuellerMap {
    /// The source.
    pub light: Illumination,
    /// The spectrum the material was evaluated at.
    pub spectrum: Option<Spectrum>,
    /// The viewing grid.
    pub grid: ViewGrid,
    /// `F` at each node, row-major.
    pub mueller: Vec<[f64; 16]>,
    /// The reflected Stokes vector `F·S_in` at each node.
    pub stokes: Vec<Stokes>,
}

impl MuellerMap {
    /// The columns of [`MuellerMap::rows`] (the page's map CSV): the hemisphere map's columns
    /// ([`crate::hemisphere::Hemisphere::COLUMNS`]), then `m00 … m33`.
    pub fn columns() -> Vec<String> {
        let mut c: Vec<String> = crate::hemisphere::Hemisphere::COLUMNS
            .iter()
            .map(|s| s.to_string())
            .collect();
        c.extend(Mueller::COLUMNS.map(String::from));
        c
    }

    /// One row per node ([`MuellerMap::row`]).
    pub fn rows(&self) -> impl Iterator<Item = Vec<f64>> + '_ {
        (0..self.grid.len()).filter_map(|i| self.row(i))
    }

    /// Node `i`'s values of [`MuellerMap::columns`]: θr, φr (degrees), BRDF `F00`, S0…S3,
    /// DoLP, AoLP (degrees), `F`; `None` beyond the grid.
    pub fn row(&self, i: usize) -> Option<Vec<f64>> {
        let (f, s) = (self.mueller.get(i)?, self.stokes.get(i)?);
        let (t, p) = self.grid.direction(i);
        let mut r = vec![deg(t), deg(p), f[0]];
        r.extend(s.0);
        r.extend([s.dolp(), s.aolp().to_degrees()]);
        r.extend(f);
        Some(r)
    }
}

/// The full pBRDF of `material` over the grid of steps `grid_deg` under `light`, at the
/// wavelength or over the band of `spectral`, through the batch engine.
///
/// # Errors
/// As [`LightRequest::illumination`], [`view_grid`], [`SpectrumSource::spectrum`] and
/// [`material_at`] (validated in that order).
pub fn mueller_map(
    material: &NamedMaterial,
    light: &LightRequest,
    grid_deg: (f64, f64),
    spectral: &impl SpectrumSource,
) -> TaskResult<MuellerMap> {
    let light = light.illumination()?;
    let grid = view_grid(grid_deg)?;
    let spectrum = spectral.spectrum()?;
    let nodes = material_at(material, spectrum.as_ref())?;
    let dirs: Vec<(f64, f64)> = (0..grid.len()).map(|i| grid.direction(i)).collect();
    let mueller = mueller_sum(&nodes, &light, &dirs)?;
    let stokes = mueller
        .iter()
        .map(|f| Mueller::from_row_major(f).apply(&light.stokes()))
        .collect();
    Ok(MuellerMap {
        light,
        spectrum,
        grid,
        mueller,
        stokes,
    })
}

/// `Σ w·F` over the spectral nodes at each viewing direction `(θr, φr)` (rad) under `light`.
fn mueller_sum(
    nodes: &[(f64, Material)],
    light: &Illumination,
    dirs: &[(f64, f64)],
) -> TaskResult<Vec<[f64; 16]>> {
    let n = dirs.len();
    let tr: Vec<f64> = dirs.iter().map(|d| d.0.clamp(0.0, FRAC_PI_2)).collect();
    let pr: Vec<f64> = dirs.iter().map(|d| d.1).collect();
    mueller_sum_at(
        nodes,
        [&vec![light.theta_i(); n], &vec![light.phi_i(); n], &tr, &pr],
    )
}

/// `Σ w·F` over the spectral nodes at the geometries of the angle columns `[θi, φi, θr, φr]`
/// (rad).
fn mueller_sum_at(
    nodes: &[(f64, Material)],
    [ti, pi, tr, pr]: [&[f64]; 4],
) -> TaskResult<Vec<[f64; 16]>> {
    let n = ti.len();
    let batch = GeometryBatch::new(ti, pi, tr, pr)?;
    let mut sum = vec![[0.0; 16]; n];
    let mut f = vec![[0.0; 16]; n];
    for (w, m) in nodes {
        Engine::new(m).mueller_into(&batch, &mut f)?;
        for (s, f) in sum.iter_mut().zip(&f) {
            for (s, f) in s.iter_mut().zip(f) {
                *s += w * f;
            }
        }
    }
    Ok(sum)
}

/// The in-plane curves of [`in_plane`].
#[derive(Debug, Clone, PartialEq)]
pub struct InPlane {
    /// Signed view zenith angles in the plane of incidence, degrees: positive on the specular
    /// side (φr = φi + 180°), negative on the source's side (φr = φi).
    pub theta_r_deg: Vec<f64>,
    /// The BRDF `F00` at each of them (sr⁻¹).
    pub brdf: Vec<f64>,
    /// The DoLP of the reflected beam `F·S_in` at each of them.
    pub dolp: Vec<f64>,
    /// Angles of incidence for the specular curve, degrees (θr = θi, φr = φi + 180°).
    pub theta_i_deg: Vec<f64>,
    /// The DoLP of the specularly reflected beam at each angle of incidence.
    pub specular_dolp: Vec<f64>,
}

/// The step of the in-plane curves, degrees.
pub const IN_PLANE_STEP_DEG: f64 = 0.5;

/// The in-plane curves of `material` under `light` (its incident Stokes vector for the
/// specular curve too), at the wavelength or over the band of `spectral`: BRDF and DoLP in the
/// plane of incidence from −89.5° to 89.5°, and the specular DoLP for θi from 0° to 89.5°, in
/// steps of [`IN_PLANE_STEP_DEG`].
///
/// # Errors
/// As [`mueller_map`].
pub fn in_plane(
    material: &NamedMaterial,
    light: &LightRequest,
    spectral: &impl SpectrumSource,
) -> TaskResult<InPlane> {
    let light = light.illumination()?;
    let spectrum = spectral.spectrum()?;
    let nodes = material_at(material, spectrum.as_ref())?;
    let last = (89.5 / IN_PLANE_STEP_DEG).round() as i32;
    let theta_r_deg: Vec<f64> = (-last..=last)
        .map(|k| f64::from(k) * IN_PLANE_STEP_DEG)
        .collect();
    let dirs: Vec<(f64, f64)> = theta_r_deg
        .iter()
        .map(|t| {
            let side = if *t >= 0.0 { PI } else { 0.0 };
            (t.abs().to_radians(), light.phi_i() + side)
        })
        .collect();
    let plane = mueller_sum(&nodes, &light, &dirs)?;
    let s_in = light.stokes();
    let (brdf, dolp) = plane
        .iter()
        .map(|f| (f[0], Mueller::from_row_major(f).apply(&s_in).dolp()))
        .unzip();
    let theta_i_deg: Vec<f64> = (0..=last)
        .map(|k| f64::from(k) * IN_PLANE_STEP_DEG)
        .collect();
    let theta: Vec<f64> = theta_i_deg.iter().map(|t| t.to_radians()).collect();
    let n = theta.len();
    let specular = mueller_sum_at(
        &nodes,
        [
            &theta,
            &vec![light.phi_i(); n],
            &theta,
            &vec![light.phi_i() + PI; n],
        ],
    )?;
    let specular_dolp = specular
        .iter()
        .map(|f| Mueller::from_row_major(f).apply(&s_in).dolp())
        .collect();
    Ok(InPlane {
        theta_r_deg,
        brdf,
        dolp,
        theta_i_deg,
        specular_dolp,
    })
}
