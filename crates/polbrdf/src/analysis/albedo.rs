//! Directional–hemispherical reflectance (albedo) of the model, to check energy conservation.
//!
//! `ρ(θi) = ∫_hemisphere f(θi, φi; θr, φr) cosθr dΩ_r`. The surface term is integrated over the
//! facet normal `h` instead of the viewing direction: `w_r = 2(w_i·h)h − w_i` and
//! `dΩ_r = 4(w_i·h) dΩ_h`, so the specular lobe becomes the facet distribution D(θN) centred on
//! the macro normal, whatever its width — a lobe of σ = 0.1° is resolved as well as one of 60°.

use crate::engine::Engine;
use crate::geometry::GeometryBatch;
use crate::model::Material;
use crate::numeric::quadrature::{composite, integrate};
use std::f64::consts::{FRAC_PI_2, PI};

/// Albedo at one incidence angle, split into its terms.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Albedo {
    /// Incidence zenith angle θi (rad).
    pub theta_i: f64,
    /// Surface (facet) part.
    pub surface: f64,
    /// Volume part, `∫ (ρ_D + 2ρ_V/(cosθi + cosθr)) cosθr dΩ_r`.
    pub volume: f64,
}

impl Albedo {
    /// Total directional–hemispherical reflectance; above 1 the parameters create energy.
    pub fn total(&self) -> f64 {
        self.surface + self.volume
    }

    /// True when the total exceeds 1 by more than `tol`.
    pub fn violates_energy_conservation(&self, tol: f64) -> bool {
        self.total() > 1.0 + tol
    }
}

/// The directional–hemispherical reflectance of `material` for light incident at `theta_i`
/// (rad, `0 ≤ θi < π/2`; 0 beyond). Accurate to ~1e-6 relative for σ from 0.05° to 80°.
pub fn directional_hemispherical(material: &Material, theta_i: f64) -> Albedo {
    let zero = Albedo {
        theta_i,
        surface: 0.0,
        volume: 0.0,
    };
    if !(0.0..FRAC_PI_2).contains(&theta_i) {
        return zero;
    }
    let (si, ci) = theta_i.sin_cos();
    let w_i = [si, 0.0, ci];
    // The quadrature nodes of the surface integral in h-space: viewing directions and weights.
    let mut theta_r = Vec::new();
    let mut phi_r = Vec::new();
    let mut weight = Vec::new();
    let mut node = |theta_n: f64, phi_n: f64, w: f64| {
        let (sn, cn) = theta_n.sin_cos();
        let (sp, cp) = phi_n.sin_cos();
        let h = [sn * cp, sn * sp, cn];
        let cos_beta = w_i[0] * h[0] + w_i[1] * h[1] + w_i[2] * h[2];
        if cos_beta <= 0.0 {
            return; // the facet faces away from the source
        }
        let w_r = [
            2.0 * cos_beta * h[0] - w_i[0],
            2.0 * cos_beta * h[1] - w_i[1],
            2.0 * cos_beta * h[2] - w_i[2],
        ];
        if w_r[2] <= 0.0 {
            return; // reflected below the horizon
        }
        theta_r.push(w_r[0].hypot(w_r[1]).atan2(w_r[2]));
        phi_r.push(w_r[1].atan2(w_r[0]));
        // f_s cosθr dΩ_r = f_s · w_r·z · 4 cosβ dΩ_h
        weight.push(w * w_r[2] * 4.0 * cos_beta);
    };
    // θN quadrature: dense over the lobe (8σ), then the rest of the hemisphere.
    let sigma = material.distribution().sigma();
    let lobe = (8.0 * sigma).min(FRAC_PI_2);
    // On the ring of facet normals at θN the reflected ray is above the horizon for
    // |φN| < φmax: w_r·z = 2cosβ·cosθN − cosθi > 0 with cosβ = sinθi sinθN cosφN + cosθi cosθN.
    // Integrating over that arc only (the integrand is smooth there, and even in φN) avoids the
    // horizon's discontinuity.
    let phi_max = |theta_n: f64| -> f64 {
        let (sn, cn) = theta_n.sin_cos();
        let denom = 2.0 * si * sn * cn;
        if denom > 0.0 {
            (ci * (1.0 - 2.0 * cn * cn) / denom).clamp(-1.0, 1.0).acos()
        } else if cn * cn > 0.5 {
            PI // θi = 0 or θN = 0: the whole ring, if any, is visible
        } else {
            0.0
        }
    };
    // The arc starts being cut (φmax < π) at θN = π/4 − θi/2 and vanishes at θN = π/4 + θi/2:
    // the ring integral has kinks there, so the θN quadrature is split at them and at the lobe.
    let mut cuts = vec![
        0.0,
        lobe,
        PI / 4.0 - theta_i / 2.0,
        PI / 4.0 + theta_i / 2.0,
        FRAC_PI_2,
    ];
    cuts.retain(|c| (0.0..=FRAC_PI_2).contains(c));
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    for w in cuts.windows(2) {
        for (theta_n, w_n) in composite(w[0], w[1], 8) {
            let pm = phi_max(theta_n);
            if pm == 0.0 {
                continue;
            }
            // The ring is even in φN: twice the half ring, times sinθN of dΩ_h.
            let ring = 2.0 * w_n * theta_n.sin();
            for (phi_n, w_p) in composite(0.0, pm, 4) {
                node(theta_n, phi_n, ring * w_p);
            }
        }
    }
    // f_s at every node through the engine (F00 of the material without its volume term).
    let zeros = vec![0.0; theta_r.len()];
    let ti = vec![theta_i; theta_r.len()];
    let batch = GeometryBatch::new(&ti, &zeros, &theta_r, &phi_r)
        .expect("directions above the horizon by construction");
    let mut f_s = vec![0.0; theta_r.len()];
    let mut dolp = vec![0.0; theta_r.len()];
    Engine::new(&material.surface_only())
        .brdf_dolp_into(&batch, &mut f_s, &mut dolp)
        .expect("lengths match");
    let surface: f64 = f_s.iter().zip(&weight).map(|(f, w)| f * w).sum();
    // Volume term: no azimuth dependence.
    let (rho_d, rho_v) = (material.rho_d(), material.rho_v());
    // Only the volume term remains: ρ_D·π + ∫ 2ρ_V/(cosθi + cosθr) cosθr dΩ_r.
    let volume = PI * rho_d
        + if rho_v > 0.0 {
            2.0 * PI
                * integrate(
                    |t: f64| 2.0 * rho_v / (ci + t.cos()) * t.cos() * t.sin(),
                    0.0,
                    FRAC_PI_2,
                    8,
                )
        } else {
            0.0
        };
    Albedo {
        theta_i,
        surface,
        volume,
    }
}
