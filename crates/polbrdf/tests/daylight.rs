//! Daylight (docs/model.md §18): the CIE clear sky with Rayleigh polarization, tabulated skies,
//! the sun as a collimated source, and the sky integral under them.

use polbrdf::analysis::facets::FacetRule;
use polbrdf::analysis::scene::{observed_radiance, Atmosphere, SkyModel, Sun, ThermalScene};
use polbrdf::analysis::sky::{
    relative_irradiance_with, sky_reflection, sky_reflection_with, ClearSky, SkyRadiance, TableSky,
};
use polbrdf::{Geometry, MaterialSpec, Spectrum, Stokes};
use std::f64::consts::PI;

fn v(theta: f64, phi: f64) -> [f64; 3] {
    [
        theta.sin() * phi.cos(),
        theta.sin() * phi.sin(),
        theta.cos(),
    ]
}

fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn unit(a: [f64; 3]) -> [f64; 3] {
    let n = dot(&a, &a).sqrt();
    [a[0] / n, a[1] / n, a[2] / n]
}

fn sky(sun_zenith_deg: f64, sun_azimuth_deg: f64) -> ClearSky {
    ClearSky::new(
        sun_zenith_deg.to_radians(),
        sun_azimuth_deg.to_radians(),
        100.0,
        0.75,
    )
    .unwrap()
}

#[test]
fn rayleigh_dolp_vanishes_toward_and_away_from_the_sun_and_peaks_at_90_degrees() {
    for (sz, sa) in [(40.0f64, 0.0f64), (10.0, 130.0), (75.0, -60.0)] {
        let s = sky(sz, sa);
        let (zt, za) = (sz.to_radians(), sa.to_radians());
        // Toward the sun, and the antisolar point (below the horizon: the formula still holds).
        assert!(s.stokes(zt, za).dolp() < 1e-12);
        assert!(s.stokes(PI - zt, za + PI).dolp() < 1e-12);
        // 90° from the sun: every point of that great circle above the horizon.
        let sun = v(zt, za);
        for k in 0..36 {
            let a = f64::from(k) * 10f64.to_radians();
            // A unit vector ⟂ sun: rotate a ⟂ basis.
            let e1 = unit(cross(&sun, &[0.0, 0.0, 1.0]));
            let e2 = cross(&sun, &e1);
            let w = [
                a.cos() * e1[0] + a.sin() * e2[0],
                a.cos() * e1[1] + a.sin() * e2[1],
                a.cos() * e1[2] + a.sin() * e2[2],
            ];
            if w[2] <= 0.01 {
                continue;
            }
            let (t, p) = (w[2].acos(), w[1].atan2(w[0]));
            assert!(
                (s.stokes(t, p).dolp() - 0.75).abs() < 1e-12,
                "{sz} {sa} {k}"
            );
        }
        // In between: δ_max·sin²γ/(1 + cos²γ).
        let g = 50f64.to_radians();
        assert!((s.dolp_at(g) - 0.75 * g.sin().powi(2) / (1.0 + g.cos().powi(2))).abs() < 1e-15);
    }
}

#[test]
fn the_e_vector_is_perpendicular_to_the_plane_of_sun_sky_point_and_observer() {
    // From the Stokes vector in the arriving beam's basis, rebuilt here from its geometric
    // definition (k = −w, s = unit(z × k), p = k × s), the electric vector
    // e = cosψ·s + sinψ·p (ψ = ½·atan2(S2, S1)) must be ⟂ w and ⟂ w_s.
    let s = sky(35.0, 20.0);
    let sun = v(35f64.to_radians(), 20f64.to_radians());
    for (t, p) in [
        (10.0f64, 200.0f64),
        (60.0, 20.0),
        (80.0, 110.0),
        (45.0, 300.0),
        (89.0, 5.0),
    ] {
        let (t, p) = (t.to_radians(), p.to_radians());
        let w = v(t, p);
        let k = [-w[0], -w[1], -w[2]];
        let sb = unit(cross(&[0.0, 0.0, 1.0], &k));
        let pb = cross(&k, &sb);
        let st = s.stokes(t, p);
        assert!(st.dolp() > 0.05);
        assert_eq!(st.0[3], 0.0);
        let psi = 0.5 * st.0[2].atan2(st.0[1]);
        let e = [
            psi.cos() * sb[0] + psi.sin() * pb[0],
            psi.cos() * sb[1] + psi.sin() * pb[1],
            psi.cos() * sb[2] + psi.sin() * pb[2],
        ];
        assert!(dot(&e, &w).abs() < 1e-12);
        assert!(dot(&e, &sun).abs() < 1e-12, "e·w_s = {}", dot(&e, &sun));
    }
}

#[test]
fn the_clear_sky_radiance_is_cie_type_12_scaled_to_its_horizontal_irradiance() {
    let s = sky(40.0, 0.0);
    // φ(Z) = 1 at the horizon and f(γ) as printed: the ratio of two radiances needs no scale.
    let (a, b, c, d, e) = ClearSky::CIE12;
    let f = |g: f64| 1.0 + c * ((d * g).exp() - (d * PI / 2.0).exp()) + e * g.cos().powi(2);
    let grad = |z: f64| 1.0 + a * (b / z.cos()).exp();
    let (t, p) = (20f64.to_radians(), 90f64.to_radians());
    let g = dot(&v(t, p), &v(40f64.to_radians(), 0.0)).acos();
    let want = s.scale() * f(g) * grad(t);
    assert!((s.stokes(t, p).0[0] / want - 1.0).abs() < 1e-12);
    // The irradiance integral converges fast with the sun (its one cone point) at a panel
    // corner: 1, 4 and 16 panels per segment.
    let coarse = relative_irradiance_with(&s, 1, 16);
    let default = s.relative_irradiance();
    let fine = relative_irradiance_with(&s, 16, 16);
    assert!((default / fine - 1.0).abs() < 1e-11, "{default} {fine}");
    assert!((coarse / fine - 1.0).abs() < 1e-6, "{coarse} {fine}");
    // And agrees with a plain product rule that ignores the sun, converging slowly to it.
    let mut prev = f64::INFINITY;
    for k in [1usize, 4, 16] {
        let plain = plain_irradiance(&s, 8 * k, 180 * k);
        let err = (plain / fine - 1.0).abs();
        assert!(err < prev, "{k}: {err:e}");
        prev = err;
    }
    assert!(prev < 5e-5, "{prev:e}");
    assert!((s.scale() * default / 100.0 - 1.0).abs() < 1e-12);
}

/// Midpoint rules in θ and φ over the hemisphere, blind to the sun.
fn plain_irradiance(s: &ClearSky, nt: usize, np: usize) -> f64 {
    let (dt, dp) = (PI / 2.0 / nt as f64, 2.0 * PI / np as f64);
    let mut total = 0.0;
    for i in 0..nt {
        let t = (i as f64 + 0.5) * dt;
        for j in 0..np {
            total += s.relative_radiance(t, (j as f64 + 0.5) * dp) * t.cos() * t.sin() * dt * dp;
        }
    }
    total
}

fn paint() -> MaterialSpec {
    let mut s = MaterialSpec::new(1.65, 15.0);
    s.rho_d = 0.03;
    s.rho_v = 0.01;
    s
}

fn day(sun: Option<Sun>, sky: SkyModel) -> ThermalScene {
    ThermalScene {
        surface_temperature_k: None,
        sky,
        atmosphere: Atmosphere::default(),
        sun,
    }
}

#[test]
fn a_sky_of_zero_radiance_gives_the_sun_only_result_bit_for_bit() {
    let sun = Sun::unpolarized(40f64.to_radians(), 0.0, 1000.0);
    let w = Spectrum::Wavelength(0.55);
    let views: Vec<(f64, f64)> = (0..12)
        .map(|k| (f64::from(k) * 0.13, f64::from(k) * 0.61))
        .collect();
    let only = observed_radiance(&paint(), &day(Some(sun), SkyModel::None), &w, &views).unwrap();
    let zero = observed_radiance(
        &paint(),
        &day(
            Some(sun),
            SkyModel::ClearSky {
                irradiance: 0.0,
                dop_max: 0.75,
            },
        ),
        &w,
        &views,
    )
    .unwrap();
    for (a, b) in only.iter().zip(&zero) {
        assert_eq!(a.stokes, b.stokes);
    }
    // And the sun term is E·cosθs·F(w_s, w_r)·s.
    let m = paint().build().unwrap();
    for (x, &(t, p)) in only.iter().zip(&views) {
        let f = m.pbrdf(&Geometry::new(40f64.to_radians(), 0.0, t, p).unwrap());
        let want = f.apply(&Stokes::unpolarized());
        for j in 0..4 {
            let e = 1000.0 * 40f64.to_radians().cos() * want.0[j];
            assert!((x.stokes.0[j] - e).abs() <= 1e-12 * e.abs().max(1e-3));
        }
    }
}

#[test]
fn turning_sun_and_views_together_leaves_the_observed_stokes_vector_unchanged() {
    let w = Spectrum::Wavelength(0.55);
    let scene = |az: f64| {
        day(
            Some(Sun {
                zenith: 40f64.to_radians(),
                azimuth: az,
                irradiance: 1000.0,
                stokes: Stokes([1.0, 0.3, -0.2, 0.1]),
            }),
            SkyModel::ClearSky {
                irradiance: 150.0,
                dop_max: 0.75,
            },
        )
    };
    let views = [(0.0, 0.0), (0.4, 1.0), (0.7, 3.3), (1.2, 5.0), (1.5, 2.0)];
    let base = observed_radiance(&paint(), &scene(0.0), &w, &views).unwrap();
    for turn in [0.7f64, 2.0, -1.3, 4.4] {
        let turned: Vec<(f64, f64)> = views.iter().map(|&(t, p)| (t, p + turn)).collect();
        let r = observed_radiance(&paint(), &scene(turn), &w, &turned).unwrap();
        for (a, b) in base.iter().zip(&r) {
            for j in 0..4 {
                let d = (a.stokes.0[j] - b.stokes.0[j]).abs();
                // The volume term's φ rule does not turn with the sun: 1e-9 of S0.
                assert!(d < 1e-9 * a.stokes.0[0], "turn {turn}: S{j} {a:?} {b:?}");
            }
        }
    }
}

#[test]
fn the_clear_sky_integral_converges_under_refinement() {
    // The surface term on the facet rule, refined 1×, 2×, 4×: the default rule is within
    // 1e-5 of the most refined one for lobes from σ = 0.05° to 80° (each component relative
    // to S0), and the differences shrink as the rule is refined.
    let s = sky(40.0, 0.0);
    for sigma in [0.05, 2.0, 15.0, 45.0, 80.0] {
        let mut spec = MaterialSpec::new(1.65, sigma);
        spec.shadowing = sigma < 60.0;
        let m = spec.build().unwrap();
        for (t, p) in [(30.0f64, 180.0f64), (60.0, 90.0), (80.0, 200.0)] {
            let (t, p) = (t.to_radians(), p.to_radians());
            let rule = FacetRule::for_material(&m);
            let r1 = sky_reflection(&m, t, p, &s).unwrap();
            let r2 = sky_reflection_with(&m, t, p, &s, rule.refined(2)).unwrap();
            let r4 = sky_reflection_with(&m, t, p, &s, rule.refined(4)).unwrap();
            let s0 = r4.0[0];
            let (mut e1, mut e2) = (0.0f64, 0.0f64);
            for j in 0..4 {
                e1 = e1.max((r1.0[j] - r4.0[j]).abs() / s0);
                e2 = e2.max((r2.0[j] - r4.0[j]).abs() / s0);
            }
            assert!(e1 < 1e-5, "σ {sigma} θ {t} φ {p}: default off by {e1:.2e}");
            assert!(e2 <= e1.max(1e-12) * 1.01, "σ {sigma}: {e1:.2e} → {e2:.2e}");
        }
    }
}

#[test]
fn a_table_sky_sampling_a_clear_sky_reflects_nearly_the_same() {
    // A radiative-transfer output on a 1° × 2° grid of the same sky: bilinear between the
    // nodes, so the reflection agrees to the interpolation error.
    let s = sky(40.0, 0.0);
    let thetas: Vec<f64> = (0..=90).map(f64::from).collect();
    let phis: Vec<f64> = (0..180).map(|k| 2.0 * f64::from(k)).collect();
    let mut st = Vec::new();
    for t in &thetas {
        for p in &phis {
            st.push(s.stokes(t.to_radians(), p.to_radians()));
        }
    }
    let table = TableSky::new(thetas, phis, st).unwrap();
    let m = paint().build().unwrap();
    for (t, p) in [(20.0f64, 180.0f64), (50.0, 90.0), (70.0, 300.0)] {
        let (t, p) = (t.to_radians(), p.to_radians());
        let a = sky_reflection(&m, t, p, &s).unwrap();
        let b = sky_reflection(&m, t, p, &table).unwrap();
        for j in 0..4 {
            assert!((a.0[j] - b.0[j]).abs() < 2e-3 * a.0[0], "S{j}: {a:?} {b:?}");
        }
    }
    // A hole in the grid is an error.
    assert!(TableSky::new(
        vec![0.0, 90.0],
        vec![0.0, 180.0],
        vec![Stokes::unpolarized(); 3]
    )
    .is_err());
}

#[test]
fn a_clear_sky_needs_a_sun_above_the_horizon() {
    let w = Spectrum::Wavelength(0.55);
    let clear = SkyModel::ClearSky {
        irradiance: 100.0,
        dop_max: 0.75,
    };
    assert!(observed_radiance(&paint(), &day(None, clear.clone()), &w, &[(0.3, 0.0)]).is_err());
    let low = Sun::unpolarized(90f64.to_radians(), 0.0, 1000.0);
    assert!(observed_radiance(&paint(), &day(Some(low), clear), &w, &[(0.3, 0.0)]).is_err());
    let neg = Sun::unpolarized(0.5, 0.0, -1.0);
    assert!(
        observed_radiance(&paint(), &day(Some(neg), SkyModel::None), &w, &[(0.3, 0.0)]).is_err()
    );
}

#[test]
fn the_map_rule_agrees_with_the_full_rule() {
    // Maps take the sky integral on the coarser rule with the Mueller matrices shared by all
    // azimuths of a view zenith; each view on the full rule: the two agree to 1e-3 of S0.
    use polbrdf::analysis::scene::Observer;
    use polbrdf::analysis::sky::Quality;
    let w = Spectrum::Wavelength(0.55);
    let scene = day(
        Some(Sun::unpolarized(40f64.to_radians(), 0.0, 1000.0)),
        SkyModel::ClearSky {
            irradiance: 150.0,
            dop_max: 0.75,
        },
    );
    let views: Vec<(f64, f64)> = (0..9)
        .flat_map(|i| {
            (0..12).map(move |j| {
                (
                    f64::from(i) * 0.17,
                    f64::from(j) * std::f64::consts::FRAC_PI_6,
                )
            })
        })
        .collect();
    let mut worst = 0.0f64;
    for sigma in [0.5, 5.0, 15.0, 35.0, 60.0] {
        let mut s = paint();
        s.sigma_deg = Some(sigma);
        let o = Observer::new(&s, &scene, &w).unwrap();
        let map = o.observe_with(&views, Quality::Map);
        let full = o.observe(&views);
        for (a, b) in map.iter().zip(&full) {
            // Against the sky's part only (the sun term is the same closed form in both).
            let sky0 = b.reflected.0[0];
            for j in 0..4 {
                worst = worst.max((a.stokes.0[j] - b.stokes.0[j]).abs() / sky0.max(1e-300));
            }
        }
    }
    println!("map rule: worst {worst:.2e} of S0");
    assert!(worst < 1e-3, "{worst:e}");
}

#[test]
fn fuzzer_regression_huge_sky_values_are_refused_not_overflowed() {
    // A table of s0 = f64::MAX interpolated to ∞ (weights summing to 1 + ε); a polarized node
    // of 1e155 was refused by a degree of polarization taken with overflowing squares.
    let grid = |v: Stokes| TableSky::new(vec![0.0, 90.0], vec![0.0, 180.0], vec![v; 4]);
    assert!(grid(Stokes([f64::MAX, 0.0, 0.0, 0.0])).is_err());
    assert!(grid(Stokes([1e149, 5e148, 5e148, 0.0])).is_ok());
    assert!(ClearSky::new(0.5, 0.0, 1.7e308, 0.75).is_err());
    let t = grid(Stokes([1e150, 0.0, 0.0, 0.0])).unwrap();
    for (a, b) in [(0.3, 0.2), (1.2, 3.0), (0.0, 6.2)] {
        assert!(t.stokes(a, b).0[0].is_finite());
    }
}

/// Issue 35 item 7: a sun at the documented azimuth bound (1e8°) panicked ("validated sun and
/// clamped view"): the views folded about its vertical plane went past the bound. Now it
/// observes what a sun at 1e8 mod 360 = 280° does (the same direction, to the rounding of 1e8°
/// in radians), and a sun beyond the bound is an error naming `sun.azimuth_deg`.
#[test]
fn a_sun_at_the_azimuth_bound_is_observed_and_beyond_it_refused() {
    let w = Spectrum::Wavelength(0.55);
    let views = [(0.3, 0.0), (0.7, 4.9), (1.1, 2.0), (1.4, -1.0)];
    let scene = |az_deg: f64, sky: SkyModel| {
        day(
            Some(Sun::unpolarized(
                40f64.to_radians(),
                az_deg.to_radians(),
                1000.0,
            )),
            sky,
        )
    };
    let clear = SkyModel::ClearSky {
        irradiance: 150.0,
        dop_max: 0.75,
    };
    for sky in [SkyModel::None, clear] {
        let near = observed_radiance(&paint(), &scene(280.0, sky.clone()), &w, &views).unwrap();
        for az in [1e8, -1e8 + 200.0, 360.0 * 1e5 + 280.0] {
            let far = observed_radiance(&paint(), &scene(az, sky.clone()), &w, &views).unwrap();
            for (a, b) in near.iter().zip(&far) {
                for j in 0..4 {
                    let d = (a.stokes.0[j] - b.stokes.0[j]).abs();
                    assert!(d <= 1e-6 * a.stokes.0[0], "{az}: S{j} {a:?} {b:?}");
                }
            }
        }
    }
    for az in [1.0000001e8, -1e9, 1e300] {
        let e = observed_radiance(&paint(), &scene(az, SkyModel::None), &w, &views).unwrap_err();
        match e {
            polbrdf::Error::InvalidParameter { name, .. } => assert_eq!(name, "sun.azimuth_deg"),
            other => panic!("{az}: {other:?}"),
        }
    }
}
