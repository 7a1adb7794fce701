//! Every case of the shared test vectors (docs/model.md §13), through the library.

use crate::common::{assert_matches, cases, f, geometry, matrix, spec_of};

#[test]
fn all_test_vectors_match_through_the_library() {
    let cases = cases();
    assert!(cases.len() >= 40, "test vectors loaded: {}", cases.len());
    for c in &cases {
        let material = spec_of(&c.inputs).build().unwrap();
        let e = material.evaluate(&geometry(&c.inputs));
        assert_matches(
            &c.id,
            e.brdf(),
            f(&c.outputs["f"]),
            &e.pbrdf.0,
            &matrix(&c.outputs["F"]),
            e.dolp(),
            f(&c.outputs["dolp"]),
        );
        let rel = |got: f64, want: f64| (got - want).abs() <= 1e-9 * want.abs() + 1e-12;
        assert!(rel(e.surface, f(&c.outputs["f_s"])), "{}: f_s", c.id);
        assert!(rel(e.volume, f(&c.outputs["f_v"])), "{}: f_v", c.id);
    }
}

#[test]
fn normalization_reproduces_the_vectors_a() {
    for c in cases() {
        if c.inputs["a_source"].as_str() != Some("hemisphere") {
            continue;
        }
        let m = spec_of(&c.inputs).build().unwrap();
        let (a, a_ref) = (m.distribution().a(), f(&c.inputs["a"]));
        assert!(
            (a / a_ref - 1.0).abs() < 1e-11,
            "{}: a = {a}, expected {a_ref}",
            c.id
        );
        let (b, b_ref) = (m.distribution().b(), f(&c.inputs["b"]));
        assert!(
            (b / b_ref - 1.0).abs() < 1e-13,
            "{}: b = {b}, expected {b_ref}",
            c.id
        );
    }
}

#[test]
fn intermediates_match() {
    let mut checked = 0;
    for c in cases() {
        let Some(im) = &c.intermediates else { continue };
        let material = spec_of(&c.inputs).build().unwrap();
        let e = material.evaluate(&geometry(&c.inputs));
        let t = e.terms.expect("above the horizon");
        let deg = |x: f64| x.to_degrees();
        let close = |got: f64, want: f64, what: &str| {
            assert!(
                (got - want).abs() <= 1e-9 * want.abs().max(1.0),
                "{}: {what} = {got}, expected {want}",
                c.id
            )
        };
        close(deg(t.angles.theta_n), f(&im["thetaN_deg"]), "thetaN_deg");
        close(deg(t.angles.beta), f(&im["beta_deg"]), "beta_deg");
        close(deg(t.angles.phi_n), f(&im["phiN_deg"]), "phiN_deg");
        close(t.d, f(&im["D"]), "D");
        close(t.r_f, f(&im["R_F"]), "R_F");
        close(t.so, f(&im["SO"]), "SO");
        // η is an angle: compare on the circle (±180° are the same rotation).
        for (got, key) in [(t.angles.eta_i, "eta_i_deg"), (t.angles.eta_r, "eta_r_deg")] {
            let d = (deg(got) - f(&im[key])).rem_euclid(360.0);
            assert!(
                d.min(360.0 - d) < 1e-9,
                "{}: {key} = {}, expected {}",
                c.id,
                deg(got),
                f(&im[key])
            );
        }
        checked += 1;
    }
    assert!(checked >= 40);
}
