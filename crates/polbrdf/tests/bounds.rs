//! The parameter bounds that keep every output finite (docs/model.md §8): the largest accepted
//! values evaluate to finite numbers at the worst geometry, and one step beyond is an error.

use polbrdf::{Form, Geometry, MaterialSpec};

/// The worst geometries: next to the horizon (cos θ ≈ 1e-9, the paper form's 1/cos⁴), at and off
/// specular, and at backscatter.
fn worst_geometries() -> Vec<Geometry> {
    let t = 89.999_999_9f64;
    vec![
        Geometry::from_degrees(t, 0.0, t, 180.0).unwrap(),
        Geometry::from_degrees(t, 0.0, t, 0.0).unwrap(),
        Geometry::from_degrees(t, 0.0, 0.0, 0.0).unwrap(),
        Geometry::from_degrees(45.0, 10.0, 45.0, 190.0).unwrap(),
        // The largest f64 below π/2.
        Geometry::new(
            f64::from_bits(std::f64::consts::FRAC_PI_2.to_bits() - 1),
            0.0,
            0.3,
            3.0,
        )
        .unwrap(),
    ]
}

fn assert_finite(spec: &MaterialSpec) {
    let m = spec.build().unwrap_or_else(|e| panic!("{spec:?}: {e}"));
    for g in worst_geometries() {
        let e = m.evaluate(&g);
        assert!(
            e.pbrdf.0.iter().flatten().all(|v| v.is_finite()) && (0.0..=1.0).contains(&e.dolp()),
            "{spec:?} at {g:?}: {:?}",
            e.pbrdf
        );
    }
}

#[test]
fn the_largest_accepted_values_stay_finite_everywhere() {
    for form in [Form::Standard, Form::Paper] {
        for (n, k) in [
            (1e6, 0.0),
            (1e6, 1e6),
            (1e-300, 0.0),
            (1.5, 1e6),
            (0.05, 10.0),
        ] {
            let mut s = MaterialSpec::new(n, 10.0);
            s.k = k;
            s.form = form;
            s.rho_d = 1e100;
            s.rho_v = 1e100;
            assert_finite(&s);
        }
        let mut s = MaterialSpec::new(1.5, 10.0);
        s.form = form;
        s.a = Some(1e100);
        assert_finite(&s);
        let mut s = MaterialSpec::new(1.5, 10.0);
        s.form = form;
        s.sigma_deg = None;
        s.b = Some(1e100); // normalized a ≈ b/π
        assert_finite(&s);
        let mut s = MaterialSpec::new(1.5, 1e-48); // σ just above 1e-50 rad
        s.form = form;
        assert_finite(&s);
        let mut s = MaterialSpec::new(1.5, 1e6); // a huge σ: a → 1/π
        s.form = form;
        s.tau_deg = 1e-300;
        s.omega_deg = 1e300;
        assert_finite(&s);
    }
}

#[test]
fn one_step_beyond_is_an_error_naming_the_key() {
    type Edit = Box<dyn Fn(&mut MaterialSpec)>;
    let cases: Vec<(&str, Edit)> = vec![
        ("`n` = 1000001", Box::new(|s| s.n = 1e6 + 1.0)),
        ("`k` = 10000000", Box::new(|s| s.k = 1e7)),
        ("`a` = 1e101", Box::new(|s| s.a = Some(1e101))),
        ("`rho_d` = 1e101", Box::new(|s| s.rho_d = 1e101)),
        ("`rho_v` = 1e101", Box::new(|s| s.rho_v = 1e101)),
        (
            "`sigma_deg` = 1e-60",
            Box::new(|s| s.sigma_deg = Some(1e-60)),
        ),
        (
            "`b` = 1e101",
            Box::new(|s| {
                s.sigma_deg = None;
                s.b = Some(1e101)
            }),
        ),
    ];
    for (want, set) in cases {
        let mut s = MaterialSpec::new(1.5, 10.0);
        set(&mut s);
        let e = s.build().unwrap_err().to_string();
        assert!(e.contains(want), "{e:?} lacks {want:?}");
    }
}

#[test]
fn fuzzer_regression_subnormal_surface_term_keeps_dop_at_most_one() {
    // Found by `cargo fuzz run model`: a subnormal amplitude gave a surface matrix with ~5
    // significant bits and an output DoP of 1.000016. Such a term is now flushed to zero.
    let spec = MaterialSpec {
        name: None,
        n: 0.010000000000000004,
        k: 2.64184331452147e-310,
        sigma_deg: Some(10.000000000000002),
        b: None,
        a: Some(1.259867e-318),
        form: Form::Standard,
        shadowing: false,
        tau_deg: 0.10000000000000002,
        omega_deg: 0.10000000000000002,
        azimuth_term: polbrdf::AzimuthTerm::None,
        rho_d: 0.0,
        rho_v: 0.0,
        spectral: None,
    };
    let g = Geometry::new(
        2.18446115236903e-309,
        -12.566370614359172,
        0.0,
        -12.566370614359172,
    )
    .unwrap();
    let e = spec.build().unwrap().evaluate(&g);
    for psi in [0.0, 0.3, 1.0] {
        let out = e.pbrdf.apply(&polbrdf::Stokes::linear(psi));
        assert!(out.dop() <= 1.0, "DoP {}", out.dop());
    }
    assert_eq!(e.surface, 0.0);
}
