//! Polarized thermal emission by Kirchhoff's law (docs/model.md §16): the emissivity Stokes
//! vector of a surface seen from a direction.
//!
//! An opaque surface inside an isothermal enclosure of unpolarized blackbody radiance `B` must
//! send `B·e0` (`e0 = (1, 0, 0, 0)`) into every direction: what it reflects of the enclosure
//! plus what it emits. Hence the emissivity Stokes vector toward `w_r`:
//!
//! - **route A** (the definition, any form): `ε(w_r) = e0 − ∫_H F(w_i, w_r)[:, 0] cosθi dω_i`,
//!   the first column of F integrated over the incidence hemisphere — what every result uses;
//! - **route B** (reciprocity): `ε_B(w_r) = e0 − P·∫_H F(w_r, w_o)[0, :]ᵀ cosθo dω_o` with
//!   `P = diag(1, 1, −1, 1)`: the directional–hemispherical reflectance of light incident from
//!   `w_r`, for each input state.
//!
//! `max |ε − ε_B|` is the **reciprocity residual**: rounding and quadrature error for the
//! reciprocal `standard` form without the azimuth factor, the model's non-reciprocity for
//! `azimuth_term = "eq3"`. `ε_s = ε0 + ε1`, `ε_p = ε0 − ε1`, emission DoLP
//! `sqrt(ε1² + ε2²)/ε0`; `ε2 = ε3 = 0` for this isotropic model by mirror symmetry about the
//! plane (z, w_r), computed anyway (both halves of every ring) as a check of the frames.
//!
//! **Quadrature**: the surface term over facet normals around `w_r` ([`crate::analysis::facets`],
//! both routes on the same nodes), the volume term in closed form
//! ([`crate::analysis::albedo::volume_hemispherical`]; it adds to ε0 only). 1e-6 absolute on
//! every component from σ = 0.05° to 80° (`tests/emission.rs`).
//!
//! **No clamping.** The model is not energy-conserving: light that SO removes counts as
//! absorbed and raises ε (a property of single-scattering shadowing models), and parameter sets
//! whose reflectance exceeds 1 for some input state give `ε0 − |(ε1, ε2, ε3)| < 0` or
//! `ε0 + |(ε1, ε2, ε3)| > 1` — reported as physically invalid ([`Emissivity::is_valid`]), never
//! clipped. The `paper` form's hemispherical integrals diverge (its `f·cosθ ∝ 1/cosθ` at the
//! horizon), so it has no emissivity: an error.

use crate::analysis::albedo::{surface_integral_diverges, volume_hemispherical};
use crate::analysis::facets::{FacetNode, FacetRule};
use crate::engine::Kernel;
use crate::error::{Error, Result};
use crate::geometry::GeometryBatch;
use crate::model::Material;
use crate::optics::stokes::Stokes;
use std::f64::consts::FRAC_PI_2;

/// How far outside `[0, 1]` a directional emissivity may lie before the direction is reported
/// physically invalid: the quadrature's stated accuracy.
pub const VALIDITY_TOLERANCE: f64 = 1e-6;

/// The emissivity toward one viewing direction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Emissivity {
    /// View zenith angle θr (rad).
    pub theta_r: f64,
    /// The emissivity Stokes vector by route A (the definition).
    pub eps: Stokes,
    /// The same by route B (the reflectance of light incident from the view direction).
    pub eps_b: Stokes,
}

impl Emissivity {
    /// `ε_s = ε0 + ε1`: emissivity for the s component (psps basis).
    pub fn eps_s(&self) -> f64 {
        self.eps.0[0] + self.eps.0[1]
    }

    /// `ε_p = ε0 − ε1`.
    pub fn eps_p(&self) -> f64 {
        self.eps.0[0] - self.eps.0[1]
    }

    /// Degree of linear polarization of the emitted light, `sqrt(ε1² + ε2²)/ε0`.
    pub fn dolp(&self) -> f64 {
        self.eps.dolp()
    }

    /// `max_j |ε_j − ε_B,j|`.
    pub fn reciprocity_residual(&self) -> f64 {
        (0..4)
            .map(|j| (self.eps.0[j] - self.eps_b.0[j]).abs())
            .fold(0.0, f64::max)
    }

    /// Whether the emissivity of every polarization state lies in `[0, 1]` (to
    /// [`VALIDITY_TOLERANCE`]): `ε0 − |(ε1, ε2, ε3)| ≥ 0` and `ε0 + |(ε1, ε2, ε3)| ≤ 1` (for
    /// this model, `ε_s` and `ε_p` in `[0, 1]`).
    pub fn is_valid(&self) -> bool {
        let [e0, e1, e2, e3] = self.eps.0;
        let v = (e1 * e1 + e2 * e2 + e3 * e3).sqrt();
        e0.is_finite()
            && v.is_finite()
            && e0 - v >= -VALIDITY_TOLERANCE
            && e0 + v <= 1.0 + VALIDITY_TOLERANCE
    }
}

/// The emissivity of `material` toward the view zenith `theta_r` (rad, `0 ≤ θr < π/2`), by
/// both routes with the default rule.
///
/// # Errors
/// [`Error::InvalidAngle`] (`theta_r`) outside `[0, π/2)`; [`Error::InconsistentParameters`]
/// for the `paper` form, whose hemispherical integral diverges.
pub fn emissivity(material: &Material, theta_r: f64) -> Result<Emissivity> {
    emissivity_with(material, theta_r, FacetRule::for_material(material))
}

/// As [`emissivity`] with a given rule (e.g. refined, for convergence studies); the rule is
/// used on both halves of every ring.
///
/// # Errors
/// As [`emissivity`].
pub fn emissivity_with(material: &Material, theta_r: f64, rule: FacetRule) -> Result<Emissivity> {
    Ok(emissivities_with(material, &[theta_r], rule)?[0])
}

/// The emissivity toward each view zenith of `theta_r` (rad), all quadrature nodes of all
/// directions in one engine call per route (a table of 90 angles runs in parallel as one
/// batch).
///
/// # Errors
/// As [`emissivity`], naming the position of a bad angle.
pub fn emissivities(material: &Material, theta_r: &[f64]) -> Result<Vec<Emissivity>> {
    emissivities_with(material, theta_r, FacetRule::for_material(material))
}

/// As [`emissivities`] with a given rule.
///
/// # Errors
/// As [`emissivity`].
pub fn emissivities_with(
    material: &Material,
    theta_r: &[f64],
    rule: FacetRule,
) -> Result<Vec<Emissivity>> {
    let both = routes(material, theta_r, rule, true)?;
    Ok(theta_r
        .iter()
        .zip(both)
        .map(|(&t, (eps, eps_b))| Emissivity {
            theta_r: t,
            eps,
            eps_b: eps_b.expect("route B requested"),
        })
        .collect())
}

/// The emissivity Stokes vector ε by route A only (the definition; half the work of
/// [`emissivities`]) toward each view zenith of `theta_r` (rad), with the default rule: what
/// the observed radiance of a scene needs.
///
/// # Errors
/// As [`emissivities`].
pub fn emissivity_vectors(material: &Material, theta_r: &[f64]) -> Result<Vec<Stokes>> {
    let rule = FacetRule::for_material(material);
    Ok(routes(material, theta_r, rule, false)?
        .into_iter()
        .map(|(a, _)| a)
        .collect())
}

/// Route A, and route B when `route_b`, at every view zenith of `theta_r`.
fn routes(
    material: &Material,
    theta_r: &[f64],
    rule: FacetRule,
    route_b: bool,
) -> Result<Vec<(Stokes, Option<Stokes>)>> {
    use rayon::prelude::*;
    for (i, &t) in theta_r.iter().enumerate() {
        if !(t.is_finite() && (0.0..FRAC_PI_2).contains(&t)) {
            return Err(Error::InvalidAngle {
                name: "theta_r",
                value: t,
                degrees: false,
                index: (theta_r.len() > 1).then_some(i),
                problem: crate::error::AngleProblem::ViewBelowHorizon,
            });
        }
    }
    if surface_integral_diverges(material) {
        return Err(Error::InconsistentParameters(
            "the `paper` form has no emissivity: its f·cosθ grows like 1/cosθ toward the \
             horizon, so the hemispherical integrals of Kirchhoff's law diverge (use form = \
             \"standard\")"
                .into(),
        ));
    }
    let rule = rule.full();
    let surface = material.surface_only();
    let kernel = Kernel::new(&surface);
    let p = [1.0, 1.0, -1.0, 1.0];
    // Directions in parallel; within one direction, the nodes in parallel chunks (so a single
    // direction uses every core too). Only the needed column and row are kept: no matrix per
    // node is stored.
    let out = theta_r
        .par_iter()
        .map(|&t| {
            let nodes = rule.nodes(t);
            let m = nodes.len();
            let fixed = vec![t; m];
            let zeros = vec![0.0; m];
            let node_t: Vec<f64> = nodes.iter().map(|n| n.theta).collect();
            let node_p: Vec<f64> = nodes.iter().map(|n| n.phi).collect();
            let volume = volume_hemispherical(material, t.cos());
            // Route A: F(w_i, w_r), w_i at the nodes, w_r = (θr, 0): the first column.
            let a = GeometryBatch::new(&node_t, &node_p, &fixed, &zeros)
                .expect("directions above the horizon by construction");
            let col = weighted_sums(&kernel, &a, &nodes, |f| [f[0], f[4], f[8], f[12]]);
            let eps = Stokes([1.0 - col[0] - volume, -col[1], -col[2], -col[3]]);
            // Route B: F(w_r, w_o), w_o at the nodes: the first row.
            let eps_b = route_b.then(|| {
                let b = GeometryBatch::new(&fixed, &zeros, &node_t, &node_p)
                    .expect("directions above the horizon by construction");
                let row = weighted_sums(&kernel, &b, &nodes, |f| [f[0], f[1], f[2], f[3]]);
                Stokes([
                    1.0 - row[0] - volume,
                    -p[1] * row[1],
                    -p[2] * row[2],
                    -p[3] * row[3],
                ])
            });
            (eps, eps_b)
        })
        .collect();
    Ok(out)
}

/// `Σ weight·pick(F)` over the nodes of `batch`, in parallel chunks of a fixed size summed in
/// order (the result does not depend on the thread count).
fn weighted_sums(
    kernel: &Kernel<'_>,
    batch: &GeometryBatch<'_>,
    nodes: &[FacetNode],
    pick: impl Fn(&[f64; 16]) -> [f64; 4] + Sync,
) -> [f64; 4] {
    use rayon::prelude::*;
    const CHUNK: usize = 512;
    let partial: Vec<[f64; 4]> = nodes
        .par_chunks(CHUNK)
        .enumerate()
        .map(|(c, chunk)| {
            // Only as many entries as the chunk has nodes (a stack buffer of CHUNK entries
            // cost more to zero than a short direction's kernel calls).
            let mut out = vec![[0.0; 16]; chunk.len()];
            kernel.mueller_into(batch, c * CHUNK, &mut out);
            let mut s = [0.0; 4];
            for (f, n) in out.iter().zip(chunk) {
                let v = pick(f);
                for j in 0..4 {
                    s[j] += n.weight * v[j];
                }
            }
            s
        })
        .collect();
    partial.iter().fold([0.0; 4], |mut acc, s| {
        for j in 0..4 {
            acc[j] += s[j];
        }
        acc
    })
}
