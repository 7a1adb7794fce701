//! Polarized thermal emission (docs/model.md §16, §17): the Fresnel limit, the two routes of
//! Kirchhoff's law, the symmetry of ε, the accuracy of the quadrature, the observed radiance
//! under uniform and tabulated skies, validity flags, and Planck's law.

use polbrdf::analysis::emission::{emissivities, emissivity, emissivity_with};
use polbrdf::analysis::facets::FacetRule;
use polbrdf::analysis::scene::{observed_radiance, Atmosphere, SkyModel, ThermalScene};
use polbrdf::analysis::sky::{sky_reflection, ProfileSky, UniformSky, ZenithProfile};
use polbrdf::analysis::thermal::{planck, C1L, C2};
use polbrdf::{directional_hemispherical, AzimuthTerm, Form, MaterialSpec, Spectrum};
use std::f64::consts::PI;

fn spec(n: f64, k: f64, sigma: f64) -> MaterialSpec {
    let mut s = MaterialSpec::new(n, sigma);
    s.k = k;
    s
}

#[test]
fn smooth_limit_is_the_fresnel_emissivity_at_rate_sigma_squared() {
    // σ → 0, no volume term, no shadowing: ε_s → 1 − R_s(θr), ε_p → 1 − R_p(θr), and the
    // emission DoLP → |R_s − R_p|/(2 − R_s − R_p). The gap shrinks like σ² at oblique views
    // (×11.1 from σ = 1° to 0.3°, ×9 from 0.3° to 0.1°: e.g. n = 1.5 at 60°, 1.1e-4, 1.0e-5,
    // 1.1e-6, 1.0e-7) and like σ⁴ at normal view, where the first-order term vanishes by
    // symmetry (3.0e-9, 2.4e-11, 3.0e-13).
    for (n, k) in [(1.5, 0.0), (1.37, 7.62), (2.4, 0.3)] {
        for t in [0.0f64, 30.0, 60.0, 80.0] {
            let tr = t.to_radians();
            let f = polbrdf::RefractiveIndex::new(n, k).unwrap().amplitudes(tr);
            let (rs, rp) = (f.reflectance_s(), f.reflectance_p());
            let mut gaps = Vec::new();
            for sigma in [1.0, 0.3, 0.1, 0.03] {
                let mut s = spec(n, k, sigma);
                s.shadowing = false;
                let e = emissivity(&s.build().unwrap(), tr).unwrap();
                let gap = (e.eps_s() - (1.0 - rs))
                    .abs()
                    .max((e.eps_p() - (1.0 - rp)).abs());
                gaps.push(gap);
                if sigma == 0.03 {
                    let dolp = (rs - rp).abs() / (2.0 - rs - rp);
                    assert!((e.dolp() - dolp).abs() < 1e-5, "n = {n}, θ = {t}: DoLP");
                }
            }
            eprintln!("n = {n}, k = {k}, θ = {t}°: gaps at σ = 1°, 0.3°, 0.1°, 0.03°: {gaps:?}");
            assert!(gaps[3] < 1.5e-6, "n = {n}, k = {k}, θ = {t}°: {gaps:?}");
            if gaps[1] > 1e-12 {
                // At least σ²: ×(1/0.3)² = 11.1 and ×9 per step.
                let r1 = gaps[0] / gaps[1];
                let r2 = gaps[1] / gaps[2];
                assert!(r1 > 9.0 && r2 > 7.5, "{n} {t}: σ² rate? {gaps:?}");
            }
        }
    }
}

#[test]
fn routes_a_and_b_agree_for_the_reciprocal_form_and_eps2_eps3_vanish() {
    let thetas: Vec<f64> = (0..90)
        .step_by(7)
        .map(|d| (d as f64).to_radians())
        .collect();
    for (n, k, sigma) in [
        (1.5, 0.0, 10.0),
        (0.5, 0.0, 30.0),
        (1.37, 7.62, 3.0),
        (1.6, 0.1, 60.0),
    ] {
        let mut s = spec(n, k, sigma);
        s.rho_d = 0.02;
        s.rho_v = 0.01;
        for e in emissivities(&s.build().unwrap(), &thetas).unwrap() {
            assert!(e.reciprocity_residual() < 1e-12, "{n} {sigma}: {e:?}");
            assert!(
                e.eps.0[2].abs() < 1e-15 && e.eps.0[3].abs() < 1e-15,
                "{e:?}"
            );
            assert!(
                e.eps_b.0[2].abs() < 1e-15 && e.eps_b.0[3].abs() < 1e-15,
                "{e:?}"
            );
            // Thermal emission is p-polarized for dielectrics: ε1 ≤ 0.
            if k == 0.0 && n > 1.0 {
                assert!(e.eps.0[1] <= 1e-15, "{e:?}");
            }
        }
    }
    // The eq3 azimuth factor is not reciprocal: the residual measures it.
    let mut s = spec(1.5, 0.0, 20.0);
    s.azimuth_term = AzimuthTerm::Eq3;
    let e = emissivity(&s.build().unwrap(), 60f64.to_radians()).unwrap();
    assert!(e.reciprocity_residual() > 1e-4, "{e:?}");
}

#[test]
fn route_b_is_one_minus_the_albedo() {
    // ε_B0 = 1 − ρ(θ): the directional–hemispherical reflectance of light incident from w_r,
    // computed by the albedo's own (half-ring) rule.
    for (n, k, sigma) in [(1.5, 0.0, 10.0), (0.5, 0.0, 45.0), (1.37, 7.62, 30.0)] {
        let mut s = spec(n, k, sigma);
        s.rho_d = 0.03;
        s.rho_v = 0.01;
        let m = s.build().unwrap();
        for t in [0.0f64, 40.0, 75.0, 88.0] {
            let e = emissivity(&m, t.to_radians()).unwrap();
            let a = directional_hemispherical(&m, t.to_radians()).total();
            assert!((e.eps_b.0[0] - (1.0 - a)).abs() < 1e-9, "{n} {sigma} {t}");
        }
    }
}

#[test]
fn the_quadrature_reaches_1e_6_from_sigma_005_to_80_degrees() {
    let mut worst = 0.0f64;
    for (n, k) in [(0.5, 0.0), (1.5, 0.0), (1.5, 3.0)] {
        for sigma in [0.05, 0.5, 5.0, 20.0, 45.0, 80.0] {
            for (shadowing, eq3) in [(true, false), (false, false), (true, true)] {
                let mut s = spec(n, k, sigma);
                s.shadowing = shadowing;
                s.rho_d = 0.01;
                s.rho_v = 0.005;
                if eq3 {
                    s.azimuth_term = AzimuthTerm::Eq3;
                }
                let m = s.build().unwrap();
                for t in [0.0f64, 30.0, 60.0, 85.0, 89.0] {
                    let a = emissivity(&m, t.to_radians()).unwrap();
                    let b =
                        emissivity_with(&m, t.to_radians(), FacetRule::for_material(&m).refined(4))
                            .unwrap();
                    for j in 0..4 {
                        let d = (a.eps.0[j] - b.eps.0[j]).abs();
                        worst = worst.max(d);
                        assert!(
                            d < 1e-6,
                            "n {n} k {k} σ {sigma} SO {shadowing} eq3 {eq3} θ {t}: ε{j} {d:e}"
                        );
                    }
                }
            }
        }
    }
    eprintln!("largest difference from the rule refined 4×: {worst:.2e}");
}

#[test]
fn emissivity_against_brute_force_over_the_incidence_hemisphere() {
    // An independent quadrature: the midpoint rule in (θi, φi), for a broad lobe.
    let mut s = spec(1.6, 0.05, 25.0);
    s.rho_d = 0.02;
    let m = s.build().unwrap();
    let tr = 50f64.to_radians();
    let (nt, np) = (600, 1200);
    let (dt, dp) = (0.5 * PI / nt as f64, 2.0 * PI / np as f64);
    let mut col = [0.0; 4];
    for a in 0..nt {
        let ti = (a as f64 + 0.5) * dt;
        let w = ti.cos() * ti.sin() * dt * dp;
        for b in 0..np {
            let g = polbrdf::Geometry::new(ti, (b as f64 + 0.5) * dp, tr, 0.0).unwrap();
            let f = m.pbrdf(&g);
            for j in 0..4 {
                col[j] += w * f[(j, 0)];
            }
        }
    }
    let e = emissivity(&m, tr).unwrap();
    assert!(
        (e.eps.0[0] - (1.0 - col[0])).abs() < 2e-5,
        "{e:?} vs {col:?}"
    );
    assert!((e.eps.0[1] + col[1]).abs() < 2e-5, "{e:?} vs {col:?}");
    assert!(col[2].abs() < 1e-12 && col[3].abs() < 1e-12);
}

#[test]
fn invalid_parameter_sets_are_flagged_not_clipped() {
    // A huge volume term: reflectance above 1, ε0 < 0 — reported, never clipped.
    let mut s = spec(1.5, 0.0, 10.0);
    s.rho_d = 0.5;
    let e = emissivity(&s.build().unwrap(), 0.3).unwrap();
    assert!(e.eps.0[0] < 0.0 && !e.is_valid(), "{e:?}");
    // The paint preset is valid up to 87° and not beyond: toward grazing view its standard
    // form (1/cosθr) and volume term reflect more than 1 of s-polarized light (ε_s < 0 at 88°).
    let paint = polbrdf::preset("paint").unwrap().build().unwrap();
    let thetas: Vec<f64> = (0..90).map(|d| (d as f64).to_radians()).collect();
    let e = emissivities(&paint, &thetas).unwrap();
    assert!(e[..88].iter().all(|e| e.is_valid()));
    assert!(!e[88].is_valid() && e[88].eps_s() < 0.0 && !e[89].is_valid());
    // The paper form has no emissivity (divergent integral): an error, not a number.
    let mut p = spec(1.5, 0.0, 10.0);
    p.form = Form::Paper;
    assert!(emissivity(&p.build().unwrap(), 0.3).is_err());
    // A view below the horizon is an error.
    assert!(emissivity(&paint, 1.6).is_err());
}

fn thermal_scene(t_surface: f64, t_sky: f64) -> ThermalScene {
    ThermalScene {
        surface_temperature_k: Some(t_surface),
        sky: SkyModel::Thermal {
            temperature_k: t_sky,
        },
        atmosphere: Atmosphere::default(),
        sun: None,
    }
}

#[test]
fn an_isothermal_enclosure_gives_unpolarized_blackbody_radiance() {
    // T_sky = T: S = B(T)·e0 exactly (to rounding), whatever the material and view.
    let views: Vec<(f64, f64)> = [(0.0, 0.0), (0.5, 1.0), (1.2, 3.0), (1.5, -2.0)].to_vec();
    for s in [
        spec(1.5, 0.0, 10.0),
        spec(1.37, 7.62, 30.0),
        polbrdf::preset("paint").unwrap(),
    ] {
        for (lambda, t) in [(10.0, 300.0), (4.0, 350.0)] {
            let r = observed_radiance(
                &s,
                &thermal_scene(t, t),
                &Spectrum::Wavelength(lambda),
                &views,
            )
            .unwrap();
            let b = planck(lambda, t);
            for x in r {
                assert!((x.stokes.0[0] / b - 1.0).abs() < 1e-12, "{x:?}");
                for j in 1..4 {
                    assert!(x.stokes.0[j].abs() < 1e-12 * b, "{x:?}");
                }
            }
        }
    }
}

#[test]
fn s1_flips_sign_when_the_sky_is_brighter_than_the_surface() {
    // S = L_d·e0 + (B(T) − L_d)·ε with ε1 < 0 (p-polarized emission): S1 > 0 for a sky
    // brighter than the surface, < 0 for a colder sky; the AoLP turns by 90°.
    let s = spec(1.5, 0.02, 15.0);
    let views = [(60f64.to_radians(), 0.0)];
    let w = Spectrum::Wavelength(10.0);
    let warm_sky = observed_radiance(&s, &thermal_scene(280.0, 320.0), &w, &views).unwrap()[0];
    let cold_sky = observed_radiance(&s, &thermal_scene(300.0, 230.0), &w, &views).unwrap()[0];
    assert!(warm_sky.stokes.0[1] > 0.0 && cold_sky.stokes.0[1] < 0.0);
    let d = (warm_sky.stokes.aolp() - cold_sky.stokes.aolp()).abs();
    assert!((d - PI / 2.0).abs() < 1e-12, "AoLP difference {d}");
}

#[test]
fn the_general_sky_integral_reproduces_kirchhoff_for_a_uniform_sky() {
    for (n, k, sigma, rho_d, rho_v) in [
        (1.5, 0.0, 10.0, 0.03, 0.01),
        (0.5, 0.0, 30.0, 0.0, 0.02),
        (1.37, 7.62, 2.0, 0.0, 0.0),
    ] {
        let mut s = spec(n, k, sigma);
        s.rho_d = rho_d;
        s.rho_v = rho_v;
        let m = s.build().unwrap();
        for t in [0.0f64, 35.0, 70.0, 85.0] {
            let tr = t.to_radians();
            let e = emissivity(&m, tr).unwrap().eps;
            let closed = [1.0 - e.0[0], -e.0[1], -e.0[2], -e.0[3]];
            for sky in [
                Box::new(UniformSky(1.0)) as Box<dyn polbrdf::analysis::sky::SkyRadiance>,
                Box::new(ProfileSky {
                    profile: ZenithProfile::new(vec![0.0, 45.0, 90.0], vec![1.0; 3]).unwrap(),
                    scale: 1.0,
                }),
            ] {
                for phi in [0.0, 2.0] {
                    let r = sky_reflection(&m, tr, phi, sky.as_ref()).unwrap();
                    for j in 0..4 {
                        assert!(
                            (r.0[j] - closed[j]).abs() < 1e-7 * closed[0].max(1e-3),
                            "{n} {sigma} θ {t} φ {phi}: S{j} {} vs {}",
                            r.0[j],
                            closed[j]
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn a_profile_sky_brighter_at_the_horizon_reflects_more_at_grazing_view() {
    // A sky twice as bright at the horizon as at the zenith: a smooth mirror-like surface
    // seen at 80° reflects the sky near 80° zenith, more than seen at normal incidence.
    let mut s = spec(1.5, 0.0, 0.5);
    s.shadowing = false;
    let profile = ZenithProfile::new(vec![0.0, 90.0], vec![1.0, 2.0]).unwrap();
    let scene = ThermalScene {
        surface_temperature_k: None,
        sky: SkyModel::Profile(profile.clone()),
        atmosphere: Atmosphere {
            transmittance: 0.5,
            path_radiance: 0.25,
        },
        sun: None,
    };
    let views = [(0.0, 0.0), (80f64.to_radians(), 0.0)];
    let r = observed_radiance(&s, &scene, &Spectrum::Wavelength(10.0), &views).unwrap();
    // Near specular: the reflected radiance ≈ R_F(θ)·L(θ).
    for (x, t) in r.iter().zip([0.0f64, 80.0]) {
        let f = polbrdf::RefractiveIndex::new(1.5, 0.0)
            .unwrap()
            .amplitudes(t.to_radians());
        let want = f.reflectance() * profile.at(t.to_radians());
        assert!(
            (x.reflected.0[0] / want - 1.0).abs() < 0.01,
            "{x:?} vs {want}"
        );
        // The atmosphere: τ·S + L_path.
        assert!((x.stokes.0[0] - (0.5 * x.reflected.0[0] + 0.25)).abs() < 1e-15);
    }
}

#[test]
fn planck_against_tabulated_and_integral_values() {
    // Values from the formula evaluated independently (Python decimal, 30 digits, with the
    // same CODATA 2018 constants): W·m⁻²·sr⁻¹·µm⁻¹.
    let table = [
        (10.0, 300.0, 9.924_033_343_570_319),
        (4.0, 300.0, 0.721_976_425_361_926),
        (0.5, 5772.0, 26_238_540.605_977_19),
        (12.0, 250.0, 3.988_246_424_724_44),
    ];
    for (l, t, want) in table {
        let b = planck(l, t);
        assert!(
            (b / want - 1.0).abs() < 1e-14,
            "B({l}, {t}) = {b}, want {want}"
        );
    }
    // Stefan–Boltzmann: ∫ B_λ dλ = σT⁴/π, σ = 2π⁵k⁴/(15h³c²) = π⁵·c1L/(15·c2⁴) in these
    // units (5.670374419e-8 W·m⁻²·K⁻⁴, CODATA 2018).
    let sigma = PI.powi(5) * C1L / (15.0 * C2.powi(4));
    assert!((sigma / 5.670_374_419e-8 - 1.0).abs() < 1e-8, "σ = {sigma}");
    let t = 300.0;
    // ∫ over λ by the substitution x = c2/(λT): ∫_0^∞ x³/(e^x − 1) dx = π⁴/15.
    let n = 200_000;
    let (lo, hi) = (0.5f64.ln(), 2000f64.ln());
    let h = (hi - lo) / n as f64;
    let integral: f64 = (0..n)
        .map(|i| {
            let l = (lo + (i as f64 + 0.5) * h).exp();
            planck(l, t) * l * h
        })
        .sum();
    assert!(
        (integral / (sigma * t.powi(4) / PI) - 1.0).abs() < 1e-6,
        "{integral}"
    );
    // Wien's displacement law: the peak at λ·T = 2897.771955 µm·K.
    let peak = (0..20_000)
        .map(|i| 9.0 + i as f64 * 1e-4)
        .max_by(|a, b| planck(*a, t).total_cmp(&planck(*b, t)))
        .unwrap();
    assert!((peak * t - 2897.771955).abs() < 0.05, "{peak}");
}

#[test]
fn an_observed_profile_sky_is_the_direct_sky_integral_at_every_azimuth() {
    // The observer computes each zenith once (at φ = 0) and reuses it at every azimuth and in
    // later calls: that rests on the sky's and the model's symmetry about the normal. Check it
    // against the sky integral taken at each view's own azimuth, and a second call against the
    // first, bit for bit.
    let mut s = spec(1.6, 0.05, 20.0);
    s.rho_d = 0.02;
    let m = s.build().unwrap();
    let profile = ZenithProfile::new(vec![0.0, 60.0, 90.0], vec![1.0, 1.4, 3.0]).unwrap();
    let scene = ThermalScene {
        surface_temperature_k: Some(290.0),
        sky: SkyModel::Profile(profile.clone()),
        atmosphere: Atmosphere::default(),
        sun: None,
    };
    let observer =
        polbrdf::analysis::scene::Observer::new(&s, &scene, &Spectrum::Wavelength(10.0)).unwrap();
    let views: Vec<(f64, f64)> =
        [(0.3, 0.0), (0.3, 2.5), (1.2, -1.0), (1.2, 4.0), (0.3, 6.0)].to_vec();
    let first = observer.observe(&views);
    let again = observer.observe(&views);
    assert_eq!(first, again);
    let sky = ProfileSky {
        profile,
        scale: 1.0,
    };
    for (x, &(t, p)) in first.iter().zip(&views) {
        let direct = sky_reflection(&m, t, p, &sky).unwrap();
        for j in 0..4 {
            assert!(
                (x.reflected.0[j] - direct.0[j]).abs() < 1e-12 * direct.0[0],
                "θ {t} φ {p}: S{j} {} vs {}",
                x.reflected.0[j],
                direct.0[j]
            );
        }
        let e = emissivity(&m, t).unwrap().eps;
        let b = planck(10.0, 290.0);
        for j in 0..4 {
            assert!((x.emitted.0[j] - b * e.0[j]).abs() < 1e-12 * b);
        }
    }
}

#[test]
fn a_scene_contrast_ranks_rings_of_view_zeniths() {
    // Symmetric about the normal: the best directions are listed at φ = 0, at distinct
    // zeniths at least the separation apart, each refined to a score no worse than its
    // grid node's, and the refined score is that of a fresh evaluation there.
    use polbrdf::analysis::scene::Observer;
    use polbrdf::analysis::{Contrast, RankOptions, ViewGrid};
    let w = Spectrum::Wavelength(10.0);
    let paint = spec(1.5, 0.05, 15.0);
    let soil = spec(1.8, 0.3, 35.0);
    let target = Observer::new(&paint, &thermal_scene(305.0, 250.0), &w).unwrap();
    let background = Observer::new(&soil, &thermal_scene(300.0, 250.0), &w).unwrap();
    let c = Contrast::scene(target, background);
    assert!(c.is_azimuth_independent());
    let grid = ViewGrid::from_degrees(5.0, 30.0).unwrap();
    let map = c.map(&grid);
    let opts = RankOptions {
        count: 4,
        ..RankOptions::default()
    };
    let top = c.rank(&map, &opts);
    assert!(!top.is_empty());
    for (k, s) in top.iter().enumerate() {
        assert_eq!(s.phi_r, 0.0);
        let fresh = c.at(s.theta_r, 0.0);
        assert_eq!(fresh.delta_dolp(), s.delta_dolp());
        // No better grid node at φ = 0 within one step of it.
        let step = grid.theta_step();
        for g in map.samples.iter().filter(|g| g.phi_r == 0.0) {
            if (g.theta_r - s.theta_r).abs() <= step * 0.999 && k == 0 {
                assert!(g.delta_dolp().abs() <= s.delta_dolp().abs() + 1e-15);
            }
        }
        // The same score at every azimuth.
        let other = c.at(s.theta_r, 2.0);
        assert!((other.delta_dolp() - s.delta_dolp()).abs() < 1e-15);
    }
}
