//! Detection (`polbrdf::analysis::detection`, the detection specification §1–5): closed forms
//! on constructed cases, the ideal camera's pseudo-inverse, the extinction ratio's effect on
//! DoLP, NETD→NEL against a finite difference, and a path that only attenuates.

use polbrdf::analysis::detection::noise::{
    band_planck, nel_from_netd, photon_band, photons_per_joule, solid_angle, H,
};
use polbrdf::analysis::detection::statistics::{
    d_prime_2d, phi, phi_inv, pixels_on_target, probability_of_detection,
};
use polbrdf::analysis::detection::{
    Analyzer, Criteria, Detector, Estimate, Feature, MaxRange, NoiseModel, Path, PhotonCounting,
    QuantumEfficiency, Sensor,
};
use polbrdf::{Band, Spectrum, Stokes};
use proptest::prelude::*;

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * a.abs().max(b.abs())
}

fn nel_sensor(analyzer: Analyzer, nel: f64) -> Sensor {
    Sensor {
        analyzer,
        noise: NoiseModel::Nel { nel },
        frames: 1,
        ifov_rad: 1e-3,
    }
}

fn camera() -> PhotonCounting {
    PhotonCounting {
        integration_time_s: 0.01,
        pixel_pitch_m: 3.45e-6,
        f_number: 2.8,
        optics_transmittance: 0.9,
        photons_per_joule: photons_per_joule(0.55),
        dark_current_e_per_s: 3.0,
        read_noise_e: 2.3,
        gain_e_per_count: 10_500.0 / 4096.0,
        full_well_e: 10_500.0,
    }
}

#[test]
fn phi_and_its_inverse_match_tabulated_values() {
    assert!(close(phi(1.0), 0.841_344_746_068_542_9, 1e-15));
    assert!(close(phi(-3.0), 1.349_898_031_630_094_6e-3, 1e-13));
    assert!(close(phi_inv(0.975), 1.959_963_984_540_054, 1e-14));
    assert!(close(phi_inv(0.9), 1.281_551_565_544_600_4, 1e-14));
    assert!(close(phi_inv(1e-6), -4.753_424_308_822_899, 1e-13));
    assert!(close(phi_inv(1e-300), -37.047_096_299_361_2, 1e-12));
    for p in [1e-12, 1e-6, 0.01, 0.3, 0.5, 0.77, 0.999] {
        assert!(close(phi(phi_inv(p)), p, 1e-13), "{p}");
    }
    assert!(phi_inv(1.5).is_nan());
}

#[test]
fn the_ideal_four_angle_camera_has_the_closed_form_pseudo_inverse() {
    let a = Analyzer::ideal_dofp();
    let c = a.pseudo_inverse();
    // S0 = (I0 + I45 + I90 + I135)/2, S1 = I0 − I90, S2 = I45 − I135 (detection.md §4).
    let want = [
        [0.5, 1.0, 0.0],
        [0.5, 0.0, 1.0],
        [0.5, -1.0, 0.0],
        [0.5, 0.0, -1.0],
    ];
    for (k, col) in c.iter().enumerate() {
        for i in 0..3 {
            assert!((col[i] - want[k][i]).abs() < 1e-14, "{k} {i}: {col:?}");
        }
    }
    // Equal channel variances σ²: Σ_S = σ²·diag(1, 2, 2).
    let sensor = nel_sensor(a, 0.3);
    let e = Estimate::of(&sensor, &Stokes::new(5.0, 1.0, -2.0, 0.0));
    let want = [[0.09, 0.0, 0.0], [0.0, 0.18, 0.0], [0.0, 0.0, 0.18]];
    for (got, want) in e.covariance.iter().flatten().zip(want.iter().flatten()) {
        assert!((got - want).abs() < 1e-15, "{:?}", e.covariance);
    }
    assert!(close(e.stokes[0], 5.0, 1e-15) && close(e.stokes[2], -2.0, 1e-15));
}

#[test]
fn angles_that_do_not_determine_s1_and_s2_are_refused() {
    let deg = |v: &[f64]| v.iter().map(|d: &f64| d.to_radians()).collect::<Vec<_>>();
    assert!(Analyzer::new(deg(&[0.0, 180.0, 360.0]), 1.0, 0.0, 0.0).is_err());
    assert!(Analyzer::new(deg(&[0.0, 90.0]), 1.0, 0.0, 0.0).is_err());
    assert!(Analyzer::new(deg(&[0.0, 60.0, 120.0]), 1.0, 0.0, 0.0).is_ok());
    assert!(Analyzer::new(deg(&[0.0, 60.0, 120.0]), 0.5, 0.5, 0.0).is_err());
    assert!(Analyzer::with_extinction_ratio(deg(&[0.0, 60.0, 120.0]), 1.0, 1.0, 0.0).is_err());
}

#[test]
fn the_roll_turns_the_analyzers_against_the_beam() {
    // Rolling the camera by ρ is measuring the beam with analyzers at α − ρ.
    let angles: Vec<f64> = [0.0f64, 45.0, 90.0, 135.0].map(f64::to_radians).to_vec();
    let rolled = Analyzer::new(angles.clone(), 1.0, 0.0, 30f64.to_radians()).unwrap();
    let turned = Analyzer::new(
        angles.iter().map(|a| a - 30f64.to_radians()).collect(),
        1.0,
        0.0,
        0.0,
    )
    .unwrap();
    let s = Stokes::linear(0.3);
    let (a, b) = (rolled.measure(&s), turned.measure(&s));
    assert!(a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-15));
}

#[test]
fn pd_and_range_follow_the_closed_form_without_a_path() {
    // Unpolarized target and background: only S0 tells them apart, d' = ΔS0/NEL (σ_S0 = NEL).
    let sensor = nel_sensor(Analyzer::ideal_dofp(), 0.1);
    let criteria = Criteria {
        range_limit_m: 1e5,
        ..Criteria::default()
    };
    let det = Detector::new(sensor, Path::none(), 1.0, criteria).unwrap();
    let (t, b) = (Stokes::new(2.0, 0.0, 0.0, 0.0), Stokes::unpolarized());
    let d = det.detect(&t, &b, 0.0, 500.0).unwrap();
    assert!(close(d.scores.s0, 10.0, 1e-12));
    assert_eq!(d.scores.dolp, 0.0);
    assert_eq!(d.feature, Feature::S0);
    // N = A/(R·IFOV)² = 1/(0.5)² = 4 at 500 m: d'_N = 20.
    assert!(close(d.pixels, 4.0, 1e-12));
    assert!(close(d.d_prime_n, 20.0, 1e-12));
    assert!(close(d.pd, phi(20.0 - 4.753_424_308_822_899), 1e-12));
    // R_max: 10·√N = D, N = 10⁶/R²  ⇒  R = 10⁴/D, D = Φ⁻¹(0.9) + Φ⁻¹(1 − 10⁻⁶).
    let need = 1.281_551_565_544_600_4 + 4.753_424_308_822_899;
    match det.max_range(&t, &b, 0.0).unwrap() {
        MaxRange::At { range_m, feature } => {
            assert!(close(range_m, 1e4 / need, 1e-9), "{range_m}");
            assert_eq!(feature, Feature::S0);
            let at = det.detect(&t, &b, 0.0, range_m).unwrap();
            assert!(close(at.pd, 0.9, 1e-8), "{}", at.pd);
        }
        other => panic!("{other:?}"),
    }
    // Tilted by 60°: half the pixels, R_max / √2.
    let MaxRange::At { range_m, .. } = det.max_range(&t, &b, 60f64.to_radians()).unwrap() else {
        panic!()
    };
    assert!(close(range_m, 1e4 / need / 2f64.sqrt(), 1e-9));
}

#[test]
fn beyond_and_not_detectable_are_reported_not_numbers() {
    let sensor = nel_sensor(Analyzer::ideal_dofp(), 0.1);
    let near = Criteria {
        range_limit_m: 100.0,
        ..Criteria::default()
    };
    let det = Detector::new(sensor.clone(), Path::none(), 1.0, near).unwrap();
    let (t, b) = (Stokes::new(2.0, 0.0, 0.0, 0.0), Stokes::unpolarized());
    assert_eq!(det.max_range(&t, &b, 0.0).unwrap(), MaxRange::Beyond);
    assert_eq!(det.max_range(&b, &b, 0.0).unwrap(), MaxRange::NotDetectable);
}

#[test]
fn a_polarization_only_target_is_detected_by_dolp() {
    // Same S0, DoLP 0.3 against 0.
    let sensor = nel_sensor(Analyzer::ideal_dofp(), 0.01);
    let det = Detector::new(sensor, Path::none(), 1.0, Criteria::default()).unwrap();
    let (t, b) = (Stokes::new(1.0, 0.3, 0.0, 0.0), Stokes::unpolarized());
    let d = det.detect(&t, &b, 0.0, 1000.0).unwrap();
    assert!(d.scores.s0 < 1e-12);
    // var DoLP_t = (P/S0)²σ²_S0 + σ²_S1/S0² = 0.09·1e-4 + 2e-4; var DoLP_b = (1e-4·2 + 1e-4·2)/2.
    let pooled: f64 = 0.5 * ((0.09 * 1e-4 + 2e-4) + 2e-4);
    assert!(close(d.scores.dolp, 0.3 / pooled.sqrt(), 1e-12));
    assert!(d.feature == Feature::Dolp || d.feature == Feature::Combined);
    let only = Criteria {
        features: vec![Feature::S0],
        ..Criteria::default()
    };
    let det = Detector::new(det.sensor.clone(), Path::none(), 1.0, only).unwrap();
    assert_eq!(det.max_range(&t, &b, 0.0).unwrap(), MaxRange::NotDetectable);
}

#[test]
fn an_extinction_ratio_of_ten_changes_dolp_snr_as_the_analysis_matrix_predicts() {
    // W₃ᵀW₃ = ¼·diag(4(q+r)², 2(q−r)², 2(q−r)²) for 0/45/90/135°, so with equal channel noise
    // σ: var S0 = σ²/(q+r)², var S1 = var S2 = 2σ²/(q−r)², and for a beam with S2 = 0
    // var DoLP = (σ/S0)²·(P²/(q+r)² + 2/(q−r)²).
    let angles: Vec<f64> = [0.0f64, 45.0, 90.0, 135.0].map(f64::to_radians).to_vec();
    let ideal = Analyzer::new(angles.clone(), 1.0, 0.0, 0.0).unwrap();
    let er10 = Analyzer::with_extinction_ratio(angles, 1.0, 10.0, 0.0).unwrap();
    let (t, b) = (
        Stokes::new(1.0, 0.2, 0.0, 0.0),
        Stokes::new(1.2, 0.06, 0.0, 0.0),
    );
    let sigma = 0.01;
    let var = |q: f64, r: f64, s: &Stokes| {
        let p = s.0[1] / s.0[0];
        (sigma / s.0[0]).powi(2) * (p * p / (q + r).powi(2) + 2.0 / (q - r).powi(2))
    };
    let predicted = |q: f64, r: f64| {
        let dp = 0.2 - 0.05;
        dp / (0.5 * (var(q, r, &t) + var(q, r, &b))).sqrt()
    };
    let dolp_snr = |a: Analyzer| {
        let s = nel_sensor(a, sigma);
        let det = Detector::new(s, Path::none(), 1.0, Criteria::default()).unwrap();
        det.detect(&t, &b, 0.0, 100.0).unwrap().scores.dolp
    };
    let (di, de) = (dolp_snr(ideal), dolp_snr(er10));
    assert!(close(di, predicted(1.0, 0.0), 1e-12), "{di}");
    assert!(close(de, predicted(1.0, 0.1), 1e-12), "{de}");
    // The loss is about the modulation (q − r)/(q + r)… here 0.86×.
    assert!(de < di && de > 0.8 * di);
}

#[test]
fn photon_counting_electrons_follow_the_radiometric_chain() {
    let cam = camera();
    let sensor = Sensor {
        analyzer: Analyzer::ideal_dofp(),
        noise: NoiseModel::PhotonCounting(cam),
        frames: 4,
        ifov_rad: 2.0 * 3.45e-6 / 0.025,
    };
    let radiance = 0.2; // W·m⁻²·sr⁻¹, unpolarized: every ideal channel sees I = 0.1
    let e = Estimate::of(&sensor, &Stokes::new(radiance, 0.0, 0.0, 0.0));
    let omega = std::f64::consts::PI / (4.0 * 2.8 * 2.8 + 1.0);
    assert!(close(solid_angle(2.8), omega, 1e-15));
    let n = 0.01 * 3.45e-6 * 3.45e-6 * omega * 0.9 * 0.55e-6 / (H * 299_792_458.0) * 0.1;
    // Ŝ0 = ½·ΣN_k = 2N; var N_k = N + dark + read² + g²/12, /M; var Ŝ0 = ¼·4·var N_k.
    assert!(close(e.stokes[0], 2.0 * n, 1e-12));
    let var_k = n + 0.03 + 2.3 * 2.3 + (10_500.0f64 / 4096.0).powi(2) / 12.0;
    assert!(close(e.covariance[0][0], var_k / 4.0, 1e-12));
    assert!(!e.saturated);
    let bright = Estimate::of(&sensor, &Stokes::new(radiance * 2e4 / n, 0.0, 0.0, 0.0));
    assert!(bright.saturated);
}

#[test]
fn the_photon_band_weighs_by_wavelength_and_quantum_efficiency() {
    let band = Band::new("v", vec![0.4, 0.7], vec![1.0, 1.0]).unwrap();
    let (p, k) = photon_band(&band, &QuantumEfficiency::Constant(0.5)).unwrap();
    assert!(close(k, photons_per_joule(0.55), 1e-15));
    // ∫ P dλ = 0.5 · ∫ λ/0.55 dλ over 0.4–0.7 µm = 0.5·(0.7² − 0.4²)/(2·0.55).
    let nodes = Spectrum::Band(p, None).integral_nodes(&[]);
    let total: f64 = nodes.iter().map(|n| n.1).sum();
    assert!(close(total, 0.5 * (0.49 - 0.16) / 1.1, 1e-12), "{total}");
    let table = QuantumEfficiency::Table(vec![(0.45, 0.6), (0.8, 0.2)]);
    assert!(photon_band(&band, &table).is_err());
}

#[test]
fn nel_from_netd_is_netd_times_the_band_radiance_derivative() {
    let band = Band::new("lwir", vec![8.0, 12.0], vec![1.0, 1.0]).unwrap();
    let nodes = Spectrum::Band(band, None).integral_nodes(&[]);
    let nel = nel_from_netd(0.05, 300.0, &nodes).unwrap();
    let h = 0.01;
    let fd = (band_planck(&nodes, 300.0 + h) - band_planck(&nodes, 300.0 - h)) / (2.0 * h);
    assert!(close(nel, 0.05 * fd, 1e-8), "{nel} {}", 0.05 * fd);
    // ~0.74 W·m⁻²·sr⁻¹·K⁻¹ for 8–12 µm at 300 K.
    assert!(fd > 0.6 && fd < 0.9, "{fd}");
    assert!(nel_from_netd(-1.0, 300.0, &nodes).is_err());
}

#[test]
fn the_path_follows_beer_lambert_koschmieder_and_its_table() {
    let p = Path::from_visibility(23_000.0, 50.0).unwrap();
    let (tau, l) = p.at(1000.0).unwrap();
    assert!(close(tau, (-3.912f64 / 23.0).exp(), 1e-15));
    assert!(close(l, (1.0 - tau) * 50.0, 1e-12));
    let s = p.apply(&Stokes::new(10.0, 2.0, 1.0, 0.0), 1000.0).unwrap();
    assert!(close(s.0[0], tau * 10.0 + l, 1e-15) && close(s.0[1], tau * 2.0, 1e-15));
    let t = Path::table(&[(100.0, 0.9, 1.0), (300.0, 0.5, 3.0)]).unwrap();
    let (tau, l) = t.at(200.0).unwrap();
    assert!(close(tau, 0.7, 1e-15) && close(l, 2.0, 1e-15));
    // From the exact point R = 0 (τ = 1, L = 0) to the first row.
    let (tau, l) = t.at(50.0).unwrap();
    assert!(close(tau, 0.95, 1e-15) && close(l, 0.5, 1e-15));
    assert!(t.at(300.0).is_ok() && t.at(300.1).is_err());
    assert!(Path::table(&[(100.0, 0.9, 1.0), (100.0, 0.5, 3.0)]).is_err());
    assert!(Path::table(&[(100.0, 1.1, 1.0)]).is_err());
    let sensor = nel_sensor(Analyzer::ideal_dofp(), 0.1);
    let far = Criteria {
        range_limit_m: 400.0,
        ..Criteria::default()
    };
    assert!(Detector::new(sensor, t, 1.0, far).is_err());
}

#[test]
fn the_combined_feature_is_the_fisher_discriminant() {
    // Uncorrelated components: d'² = d'_S0² + d'_DoLP².
    let t = ([2.0, 0.3], [[1.0, 0.0], [0.0, 0.01]]);
    let b = ([1.0, 0.1], [[1.0, 0.0], [0.0, 0.01]]);
    let d = d_prime_2d(t, b).unwrap();
    assert!(close(d, (1.0f64 + 4.0).sqrt(), 1e-12));
    assert!(close(pixels_on_target(2.0, 0.0, 100.0, 1e-3), 200.0, 1e-12));
    assert!(close(probability_of_detection(0.0, 0.5), 0.5, 1e-15));
}

fn stokes() -> impl Strategy<Value = Stokes> {
    (0.5f64..100.0, -1.0f64..1.0, 0.0f64..std::f64::consts::PI).prop_map(|(s0, p, a)| {
        Stokes::new(s0, s0 * p * (2.0 * a).cos(), s0 * p * (2.0 * a).sin(), 0.0)
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]
    /// A path that only attenuates (no path radiance) never makes the target more detectable.
    #[test]
    fn attenuation_never_helps(t in stokes(), b in stokes(), beta in 0.0f64..1e-2,
                               range in 1.0f64..5000.0, scale in 1e2f64..1e6) {
        let sensor = Sensor {
            analyzer: Analyzer::with_extinction_ratio(
                [0.0f64, 45.0, 90.0, 135.0].map(f64::to_radians).to_vec(), 0.8, 30.0, 0.1).unwrap(),
            noise: NoiseModel::PhotonCounting(PhotonCounting { full_well_e: 1e30, ..camera() }),
            frames: 1,
            ifov_rad: 1e-4,
        };
        let k = scale / sensor.noise.gain();
        let (t, b) = (Stokes(t.0.map(|x| x * k)), Stokes(b.0.map(|x| x * k)));
        let clear = Detector::new(sensor.clone(), Path::none(), 1.0, Criteria::default()).unwrap();
        let hazy = Detector::new(sensor, Path::homogeneous(beta, 0.0).unwrap(), 1.0,
                                 Criteria::default()).unwrap();
        let c = clear.detect(&t, &b, 0.3, range).unwrap();
        let h = hazy.detect(&t, &b, 0.3, range).unwrap();
        for f in Feature::ALL {
            prop_assert!(h.scores.get(f) <= c.scores.get(f) * (1.0 + 1e-12), "{:?}", f);
        }
        prop_assert!(h.pd <= c.pd * (1.0 + 1e-12) + 1e-300);
    }
}
