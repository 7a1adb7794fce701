//! Issue 18's fit diagnostics: an outlier is blamed on the data, degenerate data warn, and the
//! number of starts is bounded before anything is allocated.

use polbrdf::sample::SplitMix64;
use polbrdf::{Geometry, MaterialSpec};
use polbrdf_fit::synthetic::{measurements, random_geometries};
use polbrdf_fit::{fit, FitError, FitOptions, Observable, Param};

fn paint() -> MaterialSpec {
    let mut s = MaterialSpec::new(1.55, 12.0);
    s.rho_d = 0.02;
    s
}

fn data(count: usize) -> Vec<polbrdf_fit::Measurement> {
    let m = paint().build().unwrap();
    let mut rng = SplitMix64::new(5);
    let geoms = random_geometries(count, 70.0, &mut rng);
    measurements(&m, &geoms, &[Observable::Brdf], 0.01, 0.0, false, &mut rng)
}

#[test]
fn an_outlier_that_overflows_chi2_is_named_as_data() {
    let mut d = data(20);
    d[7].value = 1e300;
    match fit(&paint(), &[Param::N], &d, &FitOptions::default()).unwrap_err() {
        FitError::DataOutOfRange { index, .. } => assert_eq!(index, 7),
        other => panic!("{other}"),
    }
    // With σ: the weighted value counts.
    let mut d = data(20);
    d[3].value = 1e120;
    d[3].sigma = Some(1e10);
    assert!(matches!(
        fit(&paint(), &[Param::N], &d, &FitOptions::default()),
        Err(FitError::DataOutOfRange { index: 3, .. })
    ));
}

#[test]
fn repeated_rows_warn_that_the_uncertainties_mean_nothing() {
    let one = data(1)[0];
    let d = vec![one; 50];
    let r = fit(&paint(), &[Param::N], &d, &FitOptions::default()).unwrap();
    assert_eq!(r.warnings.len(), 1, "{:?}", r.warnings);
    assert!(
        r.warnings[0].contains("not meaningful"),
        "{}",
        r.warnings[0]
    );
    // Two quantities at one geometry for one parameter: determined, but by one geometry.
    let g = Geometry::from_degrees(30.0, 0.0, 30.0, 180.0).unwrap();
    let m = paint().build().unwrap();
    let mut rng = SplitMix64::new(1);
    let d = measurements(
        &m,
        &[g, g, g],
        &[Observable::Brdf, Observable::Dolp],
        0.01,
        0.0,
        false,
        &mut rng,
    );
    let r = fit(&paint(), &[Param::N], &d, &FitOptions::default()).unwrap();
    assert!(r.warnings[0].contains("same geometry"), "{:?}", r.warnings);
    // Well-posed data: no warning.
    let r = fit(&paint(), &[Param::N], &data(30), &FitOptions::default()).unwrap();
    assert!(r.warnings.is_empty(), "{:?}", r.warnings);
}

#[test]
fn starts_are_bounded_before_allocation() {
    let opts = FitOptions {
        extra_starts: usize::MAX,
        ..FitOptions::default()
    };
    assert!(matches!(
        fit(&paint(), &[Param::N], &data(20), &opts),
        Err(FitError::TooManyStarts(usize::MAX))
    ));
}
