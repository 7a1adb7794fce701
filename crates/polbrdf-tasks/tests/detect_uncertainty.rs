//! The detection range's uncertainty from the materials' fits (docs/detection.md,
//! "Uncertainty of the range"): against a closed form where the range is linear in the
//! parameters (no path, ideal analyzers, constant noise), against Monte Carlo over parameters
//! drawn from a fit's covariance (small: agreement; large: the linearization departs), and the
//! checks of a fit against its material.

use crate::common::{example, write};
use polbrdf::analysis::detection::statistics::required_d_prime;
use polbrdf::analysis::detection::{Feature, MaxRange};
use polbrdf::sample::SplitMix64;
use polbrdf_fit::Param;
use polbrdf_tasks::detect::RangeUncertainty;
use polbrdf_tasks::detect::{detect, DetectRequest, FitSource, SceneSource, SensorSource, Views};
use polbrdf_tasks::fit_covariance::FitCovariance;
use polbrdf_tasks::TaskError;

fn fit(params: &[Param], values: &[f64], covariance: &[f64]) -> Option<FitSource> {
    Some(FitSource::Loaded(Box::new(FitCovariance {
        source: "<test>".into(),
        params: params.to_vec(),
        values: values.to_vec(),
        covariance: covariance.to_vec(),
        held_fixed: Vec::new(),
    })))
}

fn interval(u: Option<RangeUncertainty>) -> (f64, f64, f64) {
    match u {
        Some(RangeUncertainty::Interval {
            sigma_m,
            lo_m,
            hi_m,
        }) => (sigma_m, lo_m, hi_m),
        other => panic!("no interval: {other:?}"),
    }
}

/// Sun only, no path; two matte surfaces (`a = 0`: no facet term) whose BRDF is the volume
/// term `ρ_D + 2ρ_V/(cosθi + cosθr)`; an ideal DoFP camera with a constant NEL. Then `S0` is
/// `K·f`, `d'` of S0 is `|ΔS0|/NEL` and `R_max = √(A·cosθr)·d'/(IFOV·d'_req)`: linear in the
/// four parameters, with `∂R/∂ρ_D = ±R/Δf` and `∂R/∂ρ_V = ±g·R/Δf`, `g = 2/(cosθi + cosθr)`.
#[test]
fn the_propagated_sigma_is_the_closed_form_where_the_range_is_linear_in_the_parameters() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write(
        d,
        "t.toml",
        "n = 1.5\na = 0\nsigma_deg = 10\nrho_d = 0.09\nrho_v = 0.02\n",
    );
    write(
        d,
        "b.toml",
        "n = 1.5\na = 0\nsigma_deg = 10\nrho_d = 0.05\nrho_v = 0.01\n",
    );
    let scene = write(
        d,
        "s.toml",
        "wavelength_um = 0.55\n[sun]\nzenith_deg = 30\nirradiance = 1000\n\
         [target]\nmaterial = \"t.toml\"\n[background]\nmaterial = \"b.toml\"\n",
    );
    let nel = 0.02;
    let sensor = write(
        d,
        "c.toml",
        &format!(
            "noise_model = \"nel\"\nnel_w_per_m2_sr = {nel}\nextinction_ratio = inf\n\
             pixel_pitch_um = 10\nfocal_length_mm = 50\nband_lo_um = 0.5\nband_hi_um = 0.6\n"
        ),
    );
    let (theta_r, theta_i) = (40f64.to_radians(), 30f64.to_radians());
    let g = 2.0 / (theta_i.cos() + theta_r.cos());
    // Target: σ(ρ_D) = 0.004, σ(ρ_V) = 0.003, correlation −0.6; background: 0.002, 0.001, 0.3.
    let ct = [1.6e-5, -0.6 * 0.004 * 0.003, -0.6 * 0.004 * 0.003, 9e-6];
    let cb = [4e-6, 0.3 * 0.002 * 0.001, 0.3 * 0.002 * 0.001, 1e-6];
    let free = [Param::RhoD, Param::RhoV];
    let s = detect(&DetectRequest {
        views: Views::List(vec![(40.0, 90.0)]),
        features: vec![Feature::S0],
        range_limit_m: 1e7,
        area_m2: 2.0,
        target_fit: fit(&free, &[0.09, 0.02], &ct),
        background_fit: fit(&free, &[0.05, 0.01], &cb),
        ..DetectRequest::new(SceneSource::File(scene), SensorSource::File(sensor))
    })
    .unwrap();
    let v = &s.views[0];
    let Some(MaxRange::At { range_m: r, .. }) = v.max_range else {
        panic!("{:?}", v.max_range)
    };
    // The range itself is the closed form (d' of S0 with the ideal camera's var S0 = NEL²).
    let ifov = 2.0 * 10e-6 / 50e-3;
    let ds0 = v.target.0[0] - v.background.0[0];
    let closed =
        (2.0 * theta_r.cos()).sqrt() * ds0.abs() / (nel * ifov * required_d_prime(0.9, 1e-6));
    assert!((r - closed).abs() < 1e-8 * closed, "{r} {closed}");
    // S0 ∝ f: the study's radiances are in the ratio of the volume terms.
    let (ft, fb) = (0.09 + g * 0.02, 0.05 + g * 0.01);
    assert!((v.target.0[0] / v.background.0[0] - ft / fb).abs() < 1e-12);
    // J·Σ·Jᵀ with the analytic J.
    let k = r / (ft - fb);
    let quad = |c: &[f64; 4]| c[0] + 2.0 * g * c[1] + g * g * c[3];
    let sigma = k.abs() * (quad(&ct) + quad(&cb)).sqrt();
    let (s_r, lo, hi) = interval(v.range_uncertainty);
    assert!((s_r - sigma).abs() < 1e-6 * sigma, "{s_r} {sigma}");
    let z = 1.959_963_984_540_054;
    assert!((lo - (r - z * s_r)).abs() < 1e-9 * r && (hi - (r + z * s_r)).abs() < 1e-9 * r);
    // A fit of the background only: only its block contributes.
    let s = detect(&DetectRequest {
        views: Views::List(vec![(40.0, 90.0)]),
        features: vec![Feature::S0],
        range_limit_m: 1e7,
        area_m2: 2.0,
        background_fit: fit(&free, &[0.05, 0.01], &cb),
        ..DetectRequest::new(
            SceneSource::File(d.join("s.toml")),
            SensorSource::File(d.join("c.toml")),
        )
    })
    .unwrap();
    let (s_b, ..) = interval(s.views[0].range_uncertainty);
    assert!((s_b - k.abs() * quad(&cb).sqrt()).abs() < 1e-6 * s_b);
}

/// The daylight example at θr = 24°, φr = 180° (toward the specular direction of the 40° sun,
/// where the paint's S0 is close to the soil's and its DoLP carries the detection): the
/// paint's `ρ_D` and roughness drawn from a fit's covariance (seeded; a draw with `ρ_D < 0` is
/// not a material and is drawn again), the detection range searched for each draw.
fn daylight(cov: [f64; 4], draws: usize, seed: u64) -> (f64, f64, Vec<f64>) {
    let mut scene = polbrdf_io::read_scene(&example("detect-daylight-scene.toml")).unwrap();
    let spec = scene.target.material.clone().unwrap().0;
    let p0 = [0.03, 15.0];
    let request = |scene: &polbrdf_io::Scene, fits: bool| DetectRequest {
        views: Views::List(vec![(24.0, 180.0)]),
        range_limit_m: 50_000.0,
        target_fit: fits
            .then(|| fit(&[Param::RhoD, Param::SigmaDeg], &p0, &cov))
            .flatten(),
        ..DetectRequest::new(
            SceneSource::Loaded(Box::new(scene.clone())),
            SensorSource::File(example("sensors/sony-imx250mzr-dofp.toml")),
        )
    };
    let s = detect(&request(&scene, true)).unwrap();
    let Some(MaxRange::At { range_m, .. }) = s.views[0].max_range else {
        panic!()
    };
    let (sigma, ..) = interval(s.views[0].range_uncertainty);
    let l00 = cov[0].sqrt();
    let l10 = cov[2] / l00;
    let l11 = (cov[3] - l10 * l10).sqrt();
    let mut rng = SplitMix64::new(seed);
    let mut ranges = Vec::with_capacity(draws);
    while ranges.len() < draws {
        let (z0, z1) = (rng.normal(), rng.normal());
        let mut m = spec.clone();
        m.rho_d = p0[0] + l00 * z0;
        m.sigma_deg = Some(p0[1] + l10 * z0 + l11 * z1);
        if m.rho_d < 0.0 {
            continue; // Outside the domain (the large covariance's far tail): not a material.
        }
        scene.target.material.as_mut().unwrap().0 = m;
        match detect(&request(&scene, false)).unwrap().views[0].max_range {
            Some(MaxRange::At { range_m, .. }) => ranges.push(range_m),
            other => panic!("{other:?}"),
        }
    }
    (range_m, sigma, ranges)
}

fn mean_sd(x: &[f64]) -> (f64, f64) {
    let n = x.len() as f64;
    let mean = x.iter().sum::<f64>() / n;
    let var = x.iter().map(|r| (r - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, var.sqrt())
}

#[test]
fn the_linear_sigma_is_the_spread_of_the_range_over_a_fit_s_covariance_while_it_is_small() {
    // A fit as `polbrdf fit` gives the example paint (σ(ρ_D) ≈ 3 %, σ(σ) ≈ 0.4 %), correlated.
    let small = [1e-6, -0.3 * 1e-3 * 0.06, -0.3 * 1e-3 * 0.06, 3.6e-3];
    let n = 300;
    let (r, sigma, ranges) = daylight(small, n, 7);
    let (mean, sd) = mean_sd(&ranges);
    // The sample sd's standard error is sd/√(2n) (4.1 %): within 4 of them; the mean within 4
    // standard errors of the range at the fit.
    let se = 1.0 / (2.0 * n as f64).sqrt();
    assert!((sd / sigma - 1.0).abs() < 4.0 * se, "sd {sd}, σ_R {sigma}");
    assert!(
        (mean - r).abs() < 4.0 * sigma / (n as f64).sqrt(),
        "{mean} {r}"
    );

    // Ten times the standard deviations (ρ_D ± 33 %): the range is visibly non-linear in the
    // parameters — its mean moves off the range at the fit by many standard errors, and its
    // spread departs from σ_R (docs/detection.md, where it is measured).
    let large = small.map(|c| 100.0 * c);
    let (r, sigma, ranges) = daylight(large, n, 7);
    let (mean, sd) = mean_sd(&ranges);
    assert!(
        (mean - r).abs() > 6.0 * sd / (n as f64).sqrt(),
        "mean {mean}, R {r}, sd {sd}"
    );
    assert!((sd / sigma - 1.0).abs() > 2.0 * se, "sd {sd}, σ_R {sigma}");
}

#[test]
fn a_fit_of_another_material_a_missing_search_and_no_range_are_told() {
    let base = || {
        DetectRequest::new(
            SceneSource::File(example("detect-daylight-scene.toml")),
            SensorSource::File(example("sensors/sony-imx250mzr-dofp.toml")),
        )
    };
    // The soil's values given as the paint's fit.
    let e = detect(&DetectRequest {
        views: Views::List(vec![(20.0, 0.0)]),
        target_fit: fit(&[Param::RhoD], &[0.07], &[1e-6]),
        ..base()
    })
    .unwrap_err();
    let text = e.to_string();
    assert!(matches!(e, TaskError::Io(_)), "{text}");
    assert!(
        text.contains("<test>") && text.contains("`parameters.rho_d.value` = 0.07"),
        "{text}"
    );
    assert!(
        text.contains("target material") && text.contains("`rho_d` = 0.03"),
        "{text}"
    );
    // Without the range search there is no range to give an interval.
    let e = detect(&DetectRequest {
        views: Views::List(vec![(20.0, 0.0)]),
        search: false,
        background_fit: fit(&[Param::RhoD], &[0.07], &[1e-6]),
        ..base()
    })
    .unwrap_err();
    assert!(
        matches!(&e, TaskError::Usage { field, .. } if field == "background_fit"),
        "{e}"
    );
    // A view beyond the range limit has no range, hence no interval; one whose perturbed
    // parameter leaves its domain (ρ_D − σ/10 < 0) has an undefined one.
    let s = detect(&DetectRequest {
        views: Views::List(vec![(20.0, 0.0)]),
        range_limit_m: 100.0,
        target_fit: fit(&[Param::RhoD], &[0.03], &[1e-6]),
        ..base()
    })
    .unwrap();
    assert_eq!(s.views[0].max_range, Some(MaxRange::Beyond));
    assert_eq!(s.views[0].range_uncertainty, None);
    let s = detect(&DetectRequest {
        views: Views::List(vec![(20.0, 0.0)]),
        range_limit_m: 50_000.0,
        target_fit: fit(&[Param::RhoD], &[0.03], &[0.1]),
        ..base()
    })
    .unwrap();
    assert_eq!(
        s.views[0].range_uncertainty,
        Some(RangeUncertainty::Undefined)
    );
    let best = s.best_json();
    assert_eq!(best["views"][0]["uncertainty"], "undefined");
    assert!(best["views"][0]["max_range_sigma_m"].is_null());
}

#[test]
fn only_the_best_ranked_views_get_an_interval_unless_every_view_is_asked() {
    let request = |n: Option<usize>| DetectRequest {
        views: Views::Grid((30.0, 90.0)),
        uncertainty_views: n,
        target_fit: fit(&[Param::RhoD], &[0.03], &[1e-6]),
        range_limit_m: 50_000.0,
        ..DetectRequest::new(
            SceneSource::File(example("detect-daylight-scene.toml")),
            SensorSource::File(example("sensors/sony-imx250mzr-dofp.toml")),
        )
    };
    let s = detect(&request(Some(2))).unwrap();
    let with: Vec<bool> = s
        .ranked()
        .iter()
        .map(|v| v.range_uncertainty.is_some())
        .collect();
    assert_eq!(with.iter().filter(|w| **w).count(), 2);
    assert!(with[0] && with[1]);
    let all = detect(&request(None)).unwrap();
    assert!(all.views.iter().all(|v| v.range_uncertainty.is_some()));
    // The same interval for a view either way, and the CSV's columns carry it.
    let best = s.ranked()[0];
    let same = all
        .views
        .iter()
        .find(|v| (v.theta_r, v.phi_r) == (best.theta_r, best.phi_r))
        .unwrap();
    assert_eq!(best.range_uncertainty, same.range_uncertainty);
    let csv = String::from_utf8(s.csv()).unwrap();
    assert!(csv
        .lines()
        .next()
        .unwrap()
        .ends_with(",max_range_sigma_m,max_range_lo95_m,max_range_hi95_m"));
    assert_eq!(
        csv.lines().filter(|l| l.ends_with(",,,")).count(),
        s.views.len() - 2
    );
}
