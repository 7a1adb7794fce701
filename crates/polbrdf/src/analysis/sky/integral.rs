//! The sky integral `∫_H F(w, w_r)·L_sky(w) cosθ dω`: its surface term on the facet-normal rule
//! and its volume term on a hemispherical rule (the rules: [`crate::analysis::sky`]), toward one
//! view or toward every azimuth of one view zenith, at the accuracy of a [`Quality`].

use super::{direction, SkyRadiance};
use crate::analysis::albedo::surface_integral_diverges;
use crate::analysis::facets::{smoothstep_n, FacetRule};
use crate::engine::Kernel;
use crate::error::{Error, Result};
use crate::geometry::GeometryBatch;
use crate::model::Material;
use crate::optics::mueller::Mueller;
use crate::optics::stokes::Stokes;
use std::f64::consts::{FRAC_PI_2, PI};

/// Points of the volume term's hemispherical rule: θ panels, points per panel, φ points.
const VOLUME_THETA: (usize, usize) = (2, 14);
const VOLUME_PHI: usize = 72;

/// The Stokes radiance `material` reflects toward `(theta_r, phi_r)` (rad) of `sky`:
/// `∫_H F(w, w_r)·L_sky(w) cosθ dω` (the rules: [`crate::analysis::sky`]).
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
