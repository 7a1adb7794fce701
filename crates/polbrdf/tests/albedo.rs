//! Directional–hemispherical reflectance against brute force and its analytic limits.

use polbrdf::{directional_hemispherical, Geometry, Material, MaterialSpec};
use std::f64::consts::{FRAC_PI_2, PI};

/// Midpoint rule over the viewing hemisphere (θr, φr).
fn brute_force(m: &Material, theta_i: f64, n: usize) -> f64 {
    let (dt, dp) = (FRAC_PI_2 / n as f64, 2.0 * PI / (4 * n) as f64);
    let mut s = 0.0;
    for a in 0..n {
        let tr = (a as f64 + 0.5) * dt;
        for b in 0..4 * n {
            let g = Geometry::new(theta_i, 0.0, tr, (b as f64 + 0.5) * dp).unwrap();
            s += m.brdf(&g) * tr.cos() * tr.sin();
        }
    }
    s * dt * dp
}

fn material(sigma_deg: f64, rho_d: f64, rho_v: f64) -> Material {
    let mut s = MaterialSpec::new(1.65, sigma_deg);
    s.rho_d = rho_d;
    s.rho_v = rho_v;
    s.build().unwrap()
}

#[test]
fn albedo_agrees_with_brute_force_integration() {
    for (sigma, rho_d, rho_v) in [(20.0, 0.0, 0.0), (30.0, 0.03, 0.01)] {
        let m = material(sigma, rho_d, rho_v);
        for ti in [0.0f64, 45.0, 80.0] {
            let a = directional_hemispherical(&m, ti.to_radians()).total();
            let b = brute_force(&m, ti.to_radians(), 300);
            assert!(
                (a / b - 1.0).abs() < 2e-5,
                "σ = {sigma}, θi = {ti}: {a} vs {b}"
            );
        }
    }
}

#[test]
fn a_narrow_lobe_at_normal_incidence_reflects_r_f_of_zero() {
    let rf0 = ((1.65f64 - 1.0) / 2.65).powi(2);
    let mut last_gap = f64::INFINITY;
    for sigma in [2.0, 0.5, 0.1, 0.02] {
        let a = directional_hemispherical(&material(sigma, 0.0, 0.0), 0.0).total();
        let gap = (a - rf0).abs();
        assert!(
            gap < last_gap,
            "σ = {sigma}: |albedo − R_F(0)| = {gap} does not shrink"
        );
        last_gap = gap;
    }
    assert!(
        last_gap / rf0 < 1e-5,
        "σ = 0.02°: relative gap {}",
        last_gap / rf0
    );
}

#[test]
fn volume_terms_integrate_analytically() {
    // ρ_D alone: π·ρ_D. ρ_V at normal incidence: 2π∫ 2ρ_V cosθ sinθ/(1 + cosθ) dθ
    // = 4πρ_V (1 − ln 2).
    let mut s = MaterialSpec::new(1.65, 10.0);
    s.a = Some(0.0); // no surface term
    s.rho_d = 0.05;
    s.rho_v = 0.02;
    let m = s.build().unwrap();
    let a = directional_hemispherical(&m, 0.0);
    assert_eq!(a.surface, 0.0);
    let want = PI * 0.05 + 4.0 * PI * 0.02 * (1.0 - 2f64.ln());
    assert!(
        (a.volume / want - 1.0).abs() < 1e-12,
        "{} vs {want}",
        a.volume
    );
}

#[test]
fn energy_creating_parameters_are_flagged() {
    let good = directional_hemispherical(&material(15.0, 0.03, 0.01), 30f64.to_radians());
    assert!(!good.violates_energy_conservation(0.0), "{}", good.total());
    let mut s = MaterialSpec::new(1.65, 15.0);
    s.rho_d = 0.4; // diffuse albedo π·0.4 ≈ 1.26
    let bad = directional_hemispherical(&s.build().unwrap(), 30f64.to_radians());
    assert!(bad.violates_energy_conservation(0.0), "{}", bad.total());
    // The paper form grows like 1/cos⁴: its albedo explodes toward grazing.
    let mut p = MaterialSpec::new(1.65, 20.0);
    p.form = polbrdf::Form::Paper;
    let grazing = directional_hemispherical(&p.build().unwrap(), 89f64.to_radians());
    assert!(
        grazing.violates_energy_conservation(0.0),
        "{}",
        grazing.total()
    );
    // Below the horizon nothing is reflected.
    assert_eq!(
        directional_hemispherical(&material(15.0, 0.03, 0.01), FRAC_PI_2).total(),
        0.0
    );
}

/// The surface albedo by the facet rule refined `refine` times (the library's own rule at
/// `refine = 1`).
fn surface_albedo(m: &Material, theta_i: f64, refine: usize) -> f64 {
    use polbrdf::analysis::facets::FacetRule;
    use polbrdf::{Engine, GeometryBatch};
    let nodes = FacetRule::for_material(m).refined(refine).nodes(theta_i);
    let tr: Vec<f64> = nodes.iter().map(|n| n.theta).collect();
    let pr: Vec<f64> = nodes.iter().map(|n| n.phi).collect();
    let (ti, zeros) = (vec![theta_i; tr.len()], vec![0.0; tr.len()]);
    let batch = GeometryBatch::new(&ti, &zeros, &tr, &pr).unwrap();
    let (mut f, mut d) = (vec![0.0; tr.len()], vec![0.0; tr.len()]);
    Engine::new(&m.surface_only())
        .brdf_dolp_into(&batch, &mut f, &mut d)
        .unwrap();
    f.iter().zip(&nodes).map(|(f, n)| f * n.weight).sum()
}

#[test]
fn total_internal_reflection_is_a_panel_edge() {
    // n = 0.5, σ = 45°, no shadowing, normal incidence: R_F has a square-root kink at
    // β = asin 0.5 = 30°. The converged integral is 0.372838 (the rule refined 8× and brute
    // force agree); a rule without that edge gave 0.372150.
    let mut s = MaterialSpec::new(0.5, 45.0);
    s.shadowing = false;
    let m = s.build().unwrap();
    let a = directional_hemispherical(&m, 0.0).surface;
    let fine = surface_albedo(&m, 0.0, 8);
    assert!((a - fine).abs() < 1e-9, "{a} vs {fine}");
    assert!((a - 0.372838).abs() < 5e-7, "{a}");
}

#[test]
fn albedo_converges_to_1e_6_over_sigma_and_incidence() {
    // Against the rule with 4× the panels, over the documented range σ = 0.05° … 80°, with and
    // without total internal reflection, metals, shadowing on and off, the eq3 azimuth factor,
    // up to grazing incidence.
    let mut worst = 0.0f64;
    for (n, k) in [(0.5, 0.0), (0.9, 0.0), (1.5, 0.0), (1.5, 3.0)] {
        for sigma in [0.05, 0.5, 5.0, 20.0, 45.0, 80.0] {
            for (shadowing, eq3) in [(true, false), (false, false), (true, true)] {
                let mut s = MaterialSpec::new(n, sigma);
                s.k = k;
                s.shadowing = shadowing;
                if eq3 {
                    s.azimuth_term = polbrdf::AzimuthTerm::Eq3;
                }
                let m = s.build().unwrap();
                for t in [0.0f64, 30.0, 60.0, 85.0, 89.0] {
                    let a = directional_hemispherical(&m, t.to_radians()).surface;
                    let b = surface_albedo(&m, t.to_radians(), 4);
                    worst = worst.max((a - b).abs());
                    assert!(
                        (a - b).abs() < 1e-6,
                        "n = {n}, k = {k}, σ = {sigma}°, SO {shadowing}, eq3 {eq3}, θi = {t}°: {a} vs {b}"
                    );
                }
            }
        }
    }
    eprintln!("largest difference from the 4× rule: {worst:.2e}");
}
