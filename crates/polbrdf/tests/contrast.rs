//! Target against background over the viewing hemisphere (`polbrdf::analysis::contrast`).

use polbrdf::analysis::contrast::{self, hemisphere, separation};
use polbrdf::{Contrast, ContrastSample, Illumination, Material, MaterialSpec, RankOptions};
use polbrdf::{Error, Ranking, Stokes, ViewGrid};

/// A smooth olive paint and a rough, more diffuse background.
fn materials() -> (Material, Material) {
    let mut t = MaterialSpec::new(1.65, 12.0);
    t.rho_d = 0.025;
    t.rho_v = 0.01;
    let mut b = MaterialSpec::new(1.5, 30.0);
    b.rho_d = 0.06;
    b.rho_v = 0.02;
    (t.build().unwrap(), b.build().unwrap())
}

fn deg(x: f64) -> f64 {
    x.to_degrees()
}

/// Great-circle distance (degrees) from `a` to the nearer of `b` and `b` mirrored in the plane
/// of incidence (unpolarized light: the maps are symmetric about that plane, so maxima come in
/// mirror pairs whose order is decided by rounding).
fn distance_mod_mirror(a: &ContrastSample, b: &ContrastSample, phi_i: f64) -> f64 {
    let wa = a.direction();
    let mirrored = ContrastSample {
        phi_r: 2.0 * phi_i - b.phi_r,
        ..*b
    };
    deg(separation(&wa, &b.direction()).min(separation(&wa, &mirrored.direction())))
}

#[test]
fn the_best_direction_agrees_with_a_brute_force_search_on_a_finer_grid() {
    let (t, b) = materials();
    let grid = ViewGrid::from_degrees(1.0, 2.0).unwrap();
    let fine = ViewGrid::from_degrees(0.25, 0.25).unwrap();
    for (sun, by) in [
        (30.0, Ranking::DeltaDolp),
        (45.0, Ranking::DeltaDolp),
        (60.0, Ranking::PolarizationContrast),
        (45.0, Ranking::PolarizationContrast),
    ] {
        let light = Illumination::from_degrees(sun, 20.0, Stokes::unpolarized()).unwrap();
        let c = Contrast::new(&t, &b, light);
        let coarse = RankOptions {
            by,
            refine: false,
            ..RankOptions::default()
        };
        let grid_best = c.rank(&c.map(&grid), &coarse)[0];
        let refined = c.rank(
            &c.map(&grid),
            &RankOptions {
                by,
                ..RankOptions::default()
            },
        )[0];
        let brute = c.rank(&c.map(&fine), &RankOptions { count: 1, ..coarse })[0];
        let (g, r, f) = (grid_best.score(by), refined.score(by), brute.score(by));
        // Within the grid resolution: one cell diagonal of the 1° × 2° grid at most.
        let d = distance_mod_mirror(&grid_best, &brute, light.phi_i());
        assert!(
            d <= 2.3,
            "sun {sun}°, {by:?}: grid best {d:.3}° from the brute-force best"
        );
        assert!(
            g <= f + 1e-12 && g > f - 0.01,
            "sun {sun}°: scores {g} (grid) vs {f} (fine)"
        );
        // Refinement reaches (at least) the brute-force optimum, at its place.
        let d = distance_mod_mirror(&refined, &brute, light.phi_i());
        assert!(r >= f - 1e-6, "sun {sun}°: refined {r} < brute force {f}");
        assert!(
            d <= 0.5,
            "sun {sun}°: refined best {d:.3}° from the brute-force best"
        );
    }
}

#[test]
fn ranked_directions_are_sorted_distinct_and_within_the_zenith_limit() {
    let (t, b) = materials();
    let light = Illumination::from_degrees(45.0, 0.0, Stokes::unpolarized()).unwrap();
    let c = Contrast::new(&t, &b, light);
    let map = c.map(&ViewGrid::from_degrees(1.0, 2.0).unwrap());
    for min_sep in [5.0f64, 10.0, 25.0] {
        let opts = RankOptions {
            min_separation: min_sep.to_radians(),
            refine: false,
            ..RankOptions::default()
        };
        let top = c.rank(&map, &opts);
        assert_eq!(top.len(), 10);
        for w in top.windows(2) {
            assert!(w[0].score(opts.by) >= w[1].score(opts.by));
        }
        for (i, a) in top.iter().enumerate() {
            assert!(a.theta_r <= 80f64.to_radians() + 1e-12);
            for b in &top[..i] {
                let d = deg(separation(&a.direction(), &b.direction()));
                assert!(d >= min_sep - 1e-9, "{d}° < {min_sep}°");
            }
        }
        // Nothing in the map beats the first entry.
        let best = map
            .samples
            .iter()
            .filter(|s| s.theta_r <= opts.max_zenith)
            .map(|s| s.delta_dolp().abs())
            .fold(0.0, f64::max);
        assert_eq!(top[0].delta_dolp().abs(), best);
    }
}

#[test]
fn swapping_target_and_background_negates_delta_dolp() {
    let (t, b) = materials();
    let light = Illumination::from_degrees(40.0, 30.0, Stokes::unpolarized()).unwrap();
    let grid = ViewGrid::from_degrees(3.0, 6.0).unwrap();
    let ab = Contrast::new(&t, &b, light).map(&grid);
    let ba = Contrast::new(&b, &t, light).map(&grid);
    let mut nonzero = 0;
    for (x, y) in ab.samples.iter().zip(&ba.samples) {
        assert_eq!(x.delta_dolp(), -y.delta_dolp());
        assert!((x.intensity_ratio() * y.intensity_ratio() - 1.0).abs() < 1e-12);
        let (da, db) = (x.aolp_difference(), y.aolp_difference());
        assert!(
            (da + db).abs() < 1e-12 || (da.abs() - std::f64::consts::FRAC_PI_2).abs() < 1e-12,
            "{da} vs {db}"
        );
        assert_eq!(x.polarization_contrast(), y.polarization_contrast());
        nonzero += usize::from(x.delta_dolp().abs() > 0.05);
    }
    assert!(nonzero > 100, "the two materials differ visibly: {nonzero}");
}

#[test]
fn identical_materials_show_no_contrast_anywhere() {
    let (t, _) = materials();
    let light = Illumination::from_degrees(50.0, -40.0, Stokes::linear(0.3)).unwrap();
    let map = Contrast::new(&t, &t.clone(), light).map(&ViewGrid::from_degrees(2.0, 4.0).unwrap());
    for s in &map.samples {
        assert_eq!(s.delta_dolp(), 0.0);
        assert_eq!(s.intensity_ratio(), 1.0);
        assert_eq!(s.aolp_difference(), 0.0);
        assert_eq!(s.polarization_contrast(), 0.0);
    }
}

#[test]
fn contrast_samples_are_the_materials_own_hemispherical_maps() {
    let (t, b) = materials();
    let grid = ViewGrid::from_degrees(5.0, 10.0).unwrap();
    for stokes in [Stokes::unpolarized(), Stokes([2.0, 0.0, 1.0, 0.5])] {
        let light = Illumination::from_degrees(35.0, 10.0, stokes).unwrap();
        let map = Contrast::new(&t, &b, light).map(&grid);
        let ht = hemisphere(&t, &light, &grid);
        let hb = hemisphere(&b, &light, &grid);
        for ((s, x), y) in map.samples.iter().zip(&ht).zip(&hb) {
            assert_eq!((s.theta_r, s.phi_r), (x.theta_r, x.phi_r));
            assert_eq!(s.target, x.stokes);
            assert_eq!(s.background, y.stokes);
            let g = light.geometry(s.theta_r, s.phi_r);
            // The maps come from the engine: the same numbers as its single-element path, and
            // the one-geometry path's to within the engine's 1e-12·F00.
            let single = polbrdf::engine::Kernel::new(&t).pbrdf(&g);
            assert_eq!(x.brdf, single[(0, 0)]);
            assert!((x.brdf - t.brdf(&g)).abs() <= 1e-12 * x.brdf);
            // Per unit irradiance: the input is normalized to S0 = 1.
            let unit = Stokes(stokes.0.map(|v| v / stokes.0[0]));
            assert_eq!(x.stokes, single.apply(&unit));
            let f = t.pbrdf(&g).apply(&unit);
            for k in 0..4 {
                assert!((x.stokes[k] - f[k]).abs() <= 4e-12 * x.brdf, "{k}");
            }
            if stokes == Stokes::unpolarized() {
                assert_eq!(x.stokes.0[0], x.brdf);
            }
        }
    }
    assert_eq!(grid.len(), 18 * 36);
    assert_eq!(grid.direction(37), (5f64.to_radians(), 10f64.to_radians()));
}

#[test]
fn polarization_contrast_reduces_to_delta_dolp_and_weighs_intensity() {
    let s = |i: f64, p: f64, psi: f64| {
        let (sn, cs) = (2.0 * psi).sin_cos();
        Stokes([i, i * p * cs, i * p * sn, 0.0])
    };
    let sample = |t, b| ContrastSample {
        theta_r: 0.5,
        phi_r: 0.0,
        target: t,
        background: b,
    };
    // Equal intensity and AoLP: |ΔDoLP|.
    let x = sample(s(0.3, 0.7, 0.2), s(0.3, 0.2, 0.2));
    assert!((x.polarization_contrast() - 0.5).abs() < 1e-12);
    assert!((x.delta_dolp() - 0.5).abs() < 1e-12);
    // Equal DoLP, AoLP 30° apart: 2·p·|sin 30°| = p, while ΔDoLP = 0.
    let y = sample(s(1.0, 0.4, 0.0), s(1.0, 0.4, 30f64.to_radians()));
    assert!((y.polarization_contrast() - 0.4).abs() < 1e-12);
    assert!(y.delta_dolp().abs() < 1e-15);
    assert!((y.aolp_difference() + 30f64.to_radians()).abs() < 1e-12);
    // A dark target: same ΔDoLP, less polarization contrast.
    let z = sample(s(0.03, 0.7, 0.2), s(0.3, 0.2, 0.2));
    assert!(z.polarization_contrast() < 0.5 * x.polarization_contrast());
    // Orthogonal full polarizations: the maximum, 2; AoLP difference folds to +90°.
    let o = sample(s(1.0, 1.0, 0.0), s(1.0, 1.0, std::f64::consts::FRAC_PI_2));
    assert!((o.polarization_contrast() - 2.0).abs() < 1e-12);
    assert!((o.aolp_difference() - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
    assert_eq!(
        sample(s(0.0, 0.0, 0.0), s(0.0, 0.0, 0.0)).polarization_contrast(),
        0.0
    );
    assert_eq!(
        sample(s(0.5, 0.1, 0.0), s(0.0, 0.0, 0.0)).intensity_ratio(),
        f64::INFINITY
    );
}

#[test]
fn bad_illumination_and_grids_are_refused_with_their_names() {
    let u = Stokes::unpolarized();
    for (z, a) in [(-5.0, 0.0), (90.0, 0.0), (95.0, 0.0), (f64::NAN, 0.0)] {
        match Illumination::from_degrees(z, a, u) {
            Err(Error::InvalidAngle { name, .. }) => assert_eq!(name, "sun_zenith_deg"),
            other => panic!("zenith {z}: {other:?}"),
        }
    }
    assert!(matches!(
        Illumination::from_degrees(30.0, f64::INFINITY, u),
        Err(Error::InvalidAngle {
            name: "sun_azimuth_deg",
            ..
        })
    ));
    for s in [
        [0.0, 0.0, 0.0, 0.0],
        [1.0, 0.8, 0.8, 0.0],
        [1.0, f64::NAN, 0.0, 0.0],
    ] {
        assert!(matches!(
            Illumination::from_degrees(30.0, 0.0, Stokes(s)),
            Err(Error::InvalidParameter { name: "stokes", .. })
        ));
    }
    for (a, b) in [
        (0.0, 2.0),
        (-1.0, 2.0),
        (1.0, f64::NAN),
        (45.0, 2.0),
        (1.0, 120.0),
        (0.01, 0.01),
    ] {
        assert!(
            matches!(
                ViewGrid::from_degrees(a, b),
                Err(Error::InvalidParameter {
                    name: "grid_deg",
                    ..
                })
            ),
            "{a}, {b}"
        );
    }
    // The azimuth step is rounded to divide the full turn.
    let g = ViewGrid::from_degrees(1.0, 0.7).unwrap();
    assert_eq!(g.n_phi(), 514);
    assert_eq!(g.n_theta(), 90);
    assert!(g.len() <= contrast::MAX_GRID_DIRECTIONS);
}
