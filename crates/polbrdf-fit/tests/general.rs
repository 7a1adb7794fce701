//! The general Levenberg–Marquardt fit: round trips, coverage of the reported uncertainties,
//! and refusals.

use polbrdf::sample::SplitMix64;
use polbrdf::{Geometry, MaterialSpec};
use polbrdf_fit::synthetic::{measurements, random_geometries};
use polbrdf_fit::{fit, FitError, FitOptions, Observable, Param};

fn truth() -> MaterialSpec {
    let mut s = MaterialSpec::new(1.55, 12.0);
    s.rho_d = 0.02;
    s.rho_v = 0.01;
    s
}

#[test]
fn noiseless_data_are_fitted_exactly_from_a_distant_start() {
    let t = truth();
    let m = t.build().unwrap();
    let mut rng = SplitMix64::new(3);
    let geoms = random_geometries(300, 80.0, &mut rng);
    let data = measurements(
        &m,
        &geoms,
        &[Observable::Brdf, Observable::Dolp],
        0.0,
        0.0,
        false,
        &mut rng,
    );
    let mut start = t.clone();
    start.n = 1.3;
    start.sigma_deg = Some(25.0);
    start.rho_d = 0.0; // exactly at the bound: the fit must still move
    start.rho_v = 0.05;
    let free = [Param::N, Param::SigmaDeg, Param::RhoD, Param::RhoV];
    let r = fit(&start, &free, &data, &FitOptions::default()).unwrap();
    assert!(r.converged, "{}", r.message);
    for (p, v) in free.iter().zip(&r.values) {
        let want = p.value(&t).unwrap();
        assert!((v / want - 1.0).abs() < 1e-6, "{}: {v} vs {want}", p.name());
    }
    assert!(r.chi2 < 1e-12, "χ² = {}", r.chi2);
    // The fitted material loads back as a material spec with the fitted values.
    assert!((r.spec.n - 1.55).abs() < 1e-6);
}

#[test]
fn one_sigma_intervals_cover_the_truth_about_68_percent_of_the_time() {
    let t = truth();
    let m = t.build().unwrap();
    let free = [Param::N, Param::SigmaDeg, Param::RhoD];
    let mut covered = 0;
    let mut total = 0;
    let trials = 120;
    for seed in 0..trials {
        let mut rng = SplitMix64::new(1000 + seed);
        let geoms = random_geometries(60, 75.0, &mut rng);
        let data = measurements(
            &m,
            &geoms,
            &[Observable::Brdf, Observable::Dolp],
            0.05,
            1e-3,
            true,
            &mut rng,
        );
        let opts = FitOptions {
            extra_starts: 0,
            ..FitOptions::default()
        };
        let r = fit(&t, &free, &data, &opts).unwrap();
        assert!(r.converged, "seed {seed}: {}", r.message);
        assert!(!r.scaled_by_residuals);
        for (k, p) in free.iter().enumerate() {
            let want = p.value(&t).unwrap();
            let z = (r.values[k] - want).abs() / r.stderr[k];
            assert!(z < 5.0, "seed {seed}: {} off by {z:.1} σ", p.name());
            covered += usize::from(z <= 1.0);
            total += 1;
        }
        // χ²/dof of a correct model with correct σ is near 1.
        assert!(
            (0.5..2.0).contains(&r.reduced_chi2),
            "seed {seed}: χ²/dof = {}",
            r.reduced_chi2
        );
    }
    let coverage = covered as f64 / total as f64;
    // 360 intervals: binomial sd ≈ 0.025 around 0.683.
    assert!((0.60..=0.77).contains(&coverage), "coverage = {coverage}");
}

#[test]
fn without_sigmas_the_uncertainty_comes_from_the_residuals() {
    let t = truth();
    let m = t.build().unwrap();
    let mut rng = SplitMix64::new(11);
    let geoms = random_geometries(400, 75.0, &mut rng);
    // Absolute noise 0.01 on every value, σ not reported.
    let data = measurements(&m, &geoms, &[Observable::Brdf], 0.0, 0.01, false, &mut rng);
    let free = [Param::N, Param::SigmaDeg];
    let r = fit(&t, &free, &data, &FitOptions::default()).unwrap();
    assert!(r.scaled_by_residuals);
    // χ²/dof estimates the noise variance.
    assert!(
        (r.reduced_chi2.sqrt() / 0.01 - 1.0).abs() < 0.15,
        "σ̂ = {}",
        r.reduced_chi2.sqrt()
    );
    for (k, p) in free.iter().enumerate() {
        let want = p.value(&t).unwrap();
        assert!(
            (r.values[k] - want).abs() < 4.0 * r.stderr[k],
            "{}",
            p.name()
        );
    }
}

#[test]
fn mueller_entries_are_fitted_jointly_with_dolp() {
    let mut t = truth();
    t.k = 0.8; // absorbing: F22, F23 carry the phase
    let m = t.build().unwrap();
    let mut rng = SplitMix64::new(5);
    let geoms = random_geometries(200, 70.0, &mut rng);
    let obs = [
        Observable::Dolp,
        Observable::Mueller(2, 3),
        Observable::Mueller(1, 0),
    ];
    let data = measurements(&m, &geoms, &obs, 0.0, 1e-3, true, &mut rng);
    let mut start = t.clone();
    start.n = 1.9;
    start.k = 0.3;
    let r = fit(&start, &[Param::N, Param::K], &data, &FitOptions::default()).unwrap();
    assert!((r.values[0] - 1.55).abs() < 4.0 * r.stderr[0]);
    assert!((r.values[1] - 0.8).abs() < 4.0 * r.stderr[1]);
    assert!(r.stderr[0] < 0.05 && r.stderr[1] < 0.05);
}

#[test]
fn unidentifiable_parameters_are_refused_with_their_names() {
    // Every point specular at one angle: θN = 0, so D(0) = a whatever b is.
    let mut t = truth();
    t.a = Some(5.0);
    let m = t.build().unwrap();
    let g = Geometry::specular(40f64.to_radians(), 0.0).unwrap();
    let mut rng = SplitMix64::new(1);
    let data = measurements(&m, &[g; 10], &[Observable::Brdf], 0.0, 1e-3, true, &mut rng);
    let e = fit(
        &t,
        &[Param::A, Param::SigmaDeg],
        &data,
        &FitOptions::default(),
    )
    .unwrap_err();
    match e {
        FitError::Unidentifiable(names) => assert!(names.contains("sigma_deg"), "{names}"),
        other => panic!("expected Unidentifiable, got {other}"),
    }
    // a and n from the BRDF at one specular angle: only a·R_F(n) is determined.
    let e = fit(&t, &[Param::A, Param::N], &data, &FitOptions::default()).unwrap_err();
    match e {
        FitError::Unidentifiable(names) => {
            assert!(names.contains("`a`") && names.contains("`n`"), "{names}")
        }
        other => panic!("expected Unidentifiable, got {other}"),
    }
}

#[test]
fn too_few_points_and_bad_lists_are_refused() {
    let t = truth();
    let m = t.build().unwrap();
    let mut rng = SplitMix64::new(1);
    let geoms = random_geometries(2, 60.0, &mut rng);
    let data = measurements(&m, &geoms, &[Observable::Brdf], 0.0, 1e-3, true, &mut rng);
    let e = fit(
        &t,
        &[Param::N, Param::SigmaDeg],
        &data,
        &FitOptions::default(),
    )
    .unwrap_err();
    assert!(
        matches!(
            e,
            FitError::TooFewPoints {
                measurements: 2,
                parameters: 2
            }
        ),
        "{e}"
    );
    assert!(Param::parse_list("n,n").is_err());
    assert!(Param::parse_list("b,sigma_deg").is_err());
    assert!(Param::parse_list("").is_err());
    assert!(
        matches!(Param::parse_list("n,colour"), Err(FitError::UnknownParameter(s)) if s == "colour")
    );
    assert_eq!(
        Param::parse_list(" n , rho_d").unwrap(),
        vec![Param::N, Param::RhoD]
    );
}

#[test]
fn zero_bistatic_data_give_the_start() {
    // Backscatter BRDF at many angles plus a few bistatic DoLP points; the roughness starts far
    // off, and the zero-bistatic inversion supplies a start near the truth.
    let t = truth();
    let m = t.build().unwrap();
    let mut rng = SplitMix64::new(2);
    let back: Vec<Geometry> = (0..15)
        .map(|k| Geometry::backscatter((3.0 * k as f64 + 1.0).to_radians(), 0.0).unwrap())
        .collect();
    let data = measurements(&m, &back, &[Observable::Brdf], 0.01, 0.0, true, &mut rng);
    let mut start = t.clone();
    start.sigma_deg = Some(60.0);
    let r = fit(&start, &[Param::SigmaDeg], &data, &FitOptions::default()).unwrap();
    let z = r.zero_bistatic.as_ref().expect("zero-bistatic start used");
    assert!((z.b.sqrt().recip().to_degrees() - 12.0).abs() < 1.0);
    assert!((r.values[0] - 12.0).abs() < 4.0 * r.stderr[0]);
}

/// The data set of the weakly-absorbing-dielectric scenario: 5000 geometries × (BRDF, DoLP),
/// 2 % noise, of n = 1.5, σ = 10°, ρ_D = 0.02, ρ_V = 0.01 sr⁻¹ and the given k.
fn dielectric_data(k: f64, seed: u64) -> (MaterialSpec, Vec<polbrdf_fit::Measurement>) {
    let mut truth = MaterialSpec::new(1.5, 10.0);
    (truth.k, truth.rho_d, truth.rho_v) = (k, 0.02, 0.01);
    let m = truth.build().unwrap();
    let mut rng = SplitMix64::new(seed);
    let geoms = random_geometries(5000, 80.0, &mut rng);
    let obs = [Observable::Brdf, Observable::Dolp];
    let data = measurements(&m, &geoms, &obs, 0.02, 1e-4, true, &mut rng);
    (truth, data)
}

const FIVE: [Param; 5] = [
    Param::N,
    Param::K,
    Param::SigmaDeg,
    Param::RhoD,
    Param::RhoV,
];

/// Every parameter but k inside its domain and within 4σ of the truth.
fn others_recovered(r: &polbrdf_fit::FitResult) {
    use polbrdf_fit::Bound;
    for (j, want) in [(0, 1.5), (2, 10.0), (3, 0.02), (4, 0.01)] {
        assert_eq!(r.bounds[j], Bound::Interior);
        assert!(
            (r.values[j] - want).abs() < 4.0 * r.stderr[j],
            "{}: {} ± {} vs {want}",
            FIVE[j].name(),
            r.values[j],
            r.stderr[j]
        );
    }
}

/// The scenario: a weakly absorbing dielectric (true k = 0.03), all five of n, k, σ,
/// ρ_D, ρ_V free, started at the truth. k is weakly determined (standard error ≈ 0.04,
/// strongly anti-correlated with n); the fit answers with an estimate inside the domain or,
/// when the data push k to 0, with the bound and an upper limit — never with a refusal.
#[test]
fn a_weakly_determined_k_gets_an_answer() {
    use polbrdf_fit::Bound;
    for seed in [42, 7, 8] {
        let (truth, data) = dielectric_data(0.03, seed);
        let r = fit(&truth, &FIVE, &data, &FitOptions::default()).expect("no refusal");
        assert!(r.converged, "{}", r.message);
        match &r.bounds[1] {
            Bound::Interior => {
                let (k, sk) = (r.values[1], r.stderr[1]);
                assert!(sk > 0.01 && sk < 0.1, "standard error of k: {sk}");
                assert!(
                    r.correlation[0][1] < -0.9,
                    "corr(n, k) = {}",
                    r.correlation[0][1]
                );
                assert!((k - 0.03).abs() < 4.0 * sk, "k = {k} ± {sk}");
            }
            Bound::AtLowerBound { upper_limit_95, .. } => {
                assert!(upper_limit_95.expect("bounded") > 0.03);
            }
        }
        others_recovered(&r);
    }
}

/// A dielectric with k = 0 and k free: the best k is 0 for most data sets. The result is the
/// bound, NaN for its standard error and covariance row, a one-sided 95 % upper limit from the
/// profile of χ² of the order of the scatter, and k's correlation with n at that limit.
#[test]
fn a_parameter_at_its_bound_gets_an_upper_limit_and_its_correlations() {
    use polbrdf_fit::Bound;
    let mut limits = Vec::new();
    for seed in [1, 2, 3, 4] {
        let (truth, data) = dielectric_data(0.0, seed);
        let r = fit(&truth, &FIVE, &data, &FitOptions::default()).expect("no refusal");
        assert!(r.converged, "{}", r.message);
        others_recovered(&r);
        match &r.bounds[1] {
            Bound::Interior => assert!(r.values[1] < 4.0 * r.stderr[1]),
            Bound::AtLowerBound {
                upper_limit_95,
                correlation_at_limit,
            } => {
                assert_eq!(r.values[1], 0.0);
                assert!(r.stderr[1].is_nan() && r.covariance[1][0].is_nan());
                let u = upper_limit_95.expect("the data bound k from above");
                limits.push(u);
                let c = correlation_at_limit
                    .as_ref()
                    .expect("correlations at the limit");
                assert!((c[1] - 1.0).abs() < 1e-9 && c[0] < -0.9, "{c:?}");
                // At the limit χ² is 2.706 above the best: check the profile independently.
                let mut at = r.spec.clone();
                at.k = u;
                let again = fit(
                    &at,
                    &[Param::N, Param::SigmaDeg, Param::RhoD, Param::RhoV],
                    &data,
                    &FitOptions::default(),
                )
                .unwrap();
                let rise = again.chi2 - r.chi2;
                assert!((rise - 2.706).abs() < 0.1, "profile rise {rise}");
            }
        }
    }
    assert!(
        !limits.is_empty(),
        "k at its bound for none of the data sets"
    );
    eprintln!("upper limits of k: {limits:?}");
}

/// The fit on the engine and the fit evaluated one geometry at a time (as before the engine)
/// give the same answer: χ² to 1e-9 relative and every parameter within 1e-6 of its error.
#[test]
fn the_engine_and_the_one_geometry_path_fit_the_same() {
    use polbrdf_fit::Evaluator;
    let mut truth = MaterialSpec::new(1.55, 12.0);
    (truth.k, truth.rho_d, truth.rho_v) = (0.02, 0.02, 0.01);
    let m = truth.build().unwrap();
    let mut rng = SplitMix64::new(7);
    let geoms = random_geometries(2000, 80.0, &mut rng);
    let obs = [
        Observable::Brdf,
        Observable::Dolp,
        Observable::Mueller(2, 1),
    ];
    let data = measurements(&m, &geoms, &obs, 0.02, 1e-4, true, &mut rng);
    let mut start = truth.clone();
    (start.n, start.sigma_deg, start.rho_d, start.rho_v, start.k) =
        (1.4, Some(20.0), 0.05, 0.0, 0.05);
    let free = [
        Param::N,
        Param::K,
        Param::SigmaDeg,
        Param::RhoD,
        Param::RhoV,
    ];
    let run = |evaluator| {
        let opts = FitOptions {
            evaluator,
            ..FitOptions::default()
        };
        fit(&start, &free, &data, &opts).unwrap()
    };
    let (a, b) = (run(Evaluator::Engine), run(Evaluator::OneGeometry));
    assert!(
        (a.chi2 - b.chi2).abs() <= 1e-9 * b.chi2,
        "{} vs {}",
        a.chi2,
        b.chi2
    );
    for (j, p) in free.iter().enumerate() {
        assert!(
            (a.values[j] - b.values[j]).abs() <= 1e-6 * b.stderr[j],
            "{}: {} vs {} (σ {})",
            p.name(),
            a.values[j],
            b.values[j],
            b.stderr[j]
        );
    }
}

#[test]
fn quantity_names_round_trip_and_use_the_core_s_mueller_columns() {
    let all = Observable::all();
    let names: Vec<String> = all.iter().map(Observable::name).collect();
    assert_eq!(names[..4], ["brdf", "dolp", "brdf_s", "brdf_p"]);
    assert_eq!(names[4..], polbrdf::Mueller::COLUMNS.map(String::from));
    for (o, n) in all.iter().zip(&names) {
        assert_eq!(Observable::parse(n), Some(*o), "{n}");
    }
    for bad in ["m44", "m4", "m000", "M00", "aolp", ""] {
        assert_eq!(Observable::parse(bad), None, "{bad}");
    }
}
