//! `polbrdf fit` on the shipped example, and its refusals.

use crate::common::{polbrdf, stderr, write};
use serde_json::Value;

fn example(name: &str) -> String {
    format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn the_readme_example_recovers_the_known_paint() {
    let dir = tempfile::tempdir().unwrap();
    let json_path = dir.path().join("fit.json");
    let toml_path = dir.path().join("fitted.toml");
    let out = polbrdf(&[
        "fit",
        "--material",
        &example("paint-init.toml"),
        "--data",
        &example("paint-goniometer.csv"),
        "--free",
        "n,sigma_deg,rho_d,rho_v",
        "--output",
        json_path.to_str().unwrap(),
        "--material-out",
        toml_path.to_str().unwrap(),
        "--plot",
        dir.path().join("residuals.svg").to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("converged"),
        "summary on the terminal"
    );
    let v: Value = serde_json::from_str(&std::fs::read_to_string(&json_path).unwrap()).unwrap();
    // The data were generated from n = 1.58, σ = 11°, ρ_D = 0.025, ρ_V = 0.012 with noise.
    for (name, truth) in [
        ("n", 1.58),
        ("sigma_deg", 11.0),
        ("rho_d", 0.025),
        ("rho_v", 0.012),
    ] {
        let p = &v["parameters"][name];
        let (value, se) = (p["value"].as_f64().unwrap(), p["stderr"].as_f64().unwrap());
        assert!(
            (value - truth).abs() < 4.0 * se,
            "{name} = {value} ± {se}, truth {truth}"
        );
    }
    for key in [
        "covariance",
        "correlation",
        "chi2",
        "reduced_chi2",
        "dof",
        "converged",
        "iterations",
        "message",
    ] {
        assert!(!v[key].is_null(), "fit.json has {key}");
    }
    assert_eq!(v["covariance"].as_array().unwrap().len(), 4);
    assert_eq!(v["converged"], Value::Bool(true));
    // The residual figure shows the model against the data too (issue 36), then the residuals,
    // for each kind of measurement.
    let svg = std::fs::read_to_string(dir.path().join("residuals.svg")).unwrap();
    for title in [
        "BRDF: fitted model and data",
        "DoLP: fitted model and data",
        "BRDF: ",
        "RMS",
    ] {
        assert!(svg.contains(title), "residuals.svg lacks {title:?}");
    }
    assert!(svg.find("BRDF: fitted model and data") < svg.find("DoLP: fitted model and data"));
    // The fitted material loads back into eval.
    let geo = write(
        dir.path(),
        "g.csv",
        "theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg\n30,0,30,180\n",
    );
    let out = polbrdf(&[
        "eval",
        "--material",
        toml_path.to_str().unwrap(),
        "--input",
        &geo,
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
}

#[test]
fn refusals_are_clear_with_exit_codes_2_and_3() {
    let dir = tempfile::tempdir().unwrap();
    let two = write(
        dir.path(),
        "two.csv",
        "theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg,brdf\n30,0,30,180,1.0\n40,0,40,180,2.0\n",
    );
    // A bad --free list is a usage error (2), too few measurements for it invalid input (3).
    let cases: [(&str, &str, &str, i32); 4] = [
        (&two, "n,sigma_deg,rho_d", "too few measurements", 3),
        (&two, "n,colour", "unknown parameter `colour`", 2),
        (&two, "b,sigma_deg", "same roughness", 2),
        (&example("paint-goniometer.csv"), "n,n", "twice", 2),
    ];
    for (data, free, fragment, code) in cases {
        let out = polbrdf(&["fit", "--material", "paint", "--data", data, "--free", free]);
        assert_eq!(out.status.code(), Some(code), "{free}: {}", stderr(&out));
        assert!(stderr(&out).contains(fragment), "{free}: {}", stderr(&out));
    }
    // Every point specular at one angle: the roughness has no effect when `a` is free.
    let spec = write(
        dir.path(),
        "spec.csv",
        &("theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg,brdf\n".to_string()
            + &"40,0,40,180,3.0\n".repeat(8)),
    );
    let out = polbrdf(&[
        "fit",
        "--material",
        "paint",
        "--data",
        &spec,
        "--free",
        "a,sigma_deg",
    ]);
    assert_eq!(out.status.code(), Some(3), "{}", stderr(&out));
    assert!(stderr(&out).contains("sigma_deg") && stderr(&out).contains("cannot be determined"));
    // A malformed row is an error with its line, never dropped.
    let bad = write(
        dir.path(),
        "bad.csv",
        "theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg,brdf,sigma_brdf\n30,0,30,180,1.0,0.1\n40,0,40,180,2.0,0\n",
    );
    let out = polbrdf(&["fit", "--material", "paint", "--data", &bad, "--free", "n"]);
    assert_eq!(out.status.code(), Some(3));
    assert!(
        stderr(&out).contains("bad.csv:3") && stderr(&out).contains("sigma_brdf"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn a_parameter_pushed_to_its_bound_is_reported_with_an_upper_limit() {
    // A dielectric (k = 0) measured without noise, k free: the best k is 0, its bound.
    let dir = tempfile::tempdir().unwrap();
    let mut truth = polbrdf::MaterialSpec::new(1.5, 10.0);
    truth.rho_d = 0.02;
    let m = truth.build().unwrap();
    let mut csv = String::from(
        "theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg,brdf,sigma_brdf,dolp,sigma_dolp\n",
    );
    for ti in [10.0, 30.0, 50.0, 70.0] {
        for k in 0..24 {
            let (tr, pr) = (f64::from(k % 8) * 10.0 + 2.0, f64::from(k) * 15.0);
            let g = polbrdf::Geometry::from_degrees(ti, 0.0, tr, pr).unwrap();
            let e = m.evaluate(&g);
            let (b, d) = (e.brdf(), e.dolp());
            csv += &format!("{ti},0,{tr},{pr},{b:?},{:?},{d:?},0.005\n", 0.02 * b);
        }
    }
    let data = write(dir.path(), "dielectric.csv", &csv);
    let start = write(
        dir.path(),
        "start.toml",
        "n = 1.45\nk = 0.05\nsigma_deg = 12\nrho_d = 0.02\n",
    );
    let json_path = dir.path().join("fit.json");
    let out = polbrdf(&[
        "fit",
        "--material",
        &start,
        "--data",
        &data,
        "--free",
        "n,k,sigma_deg",
        "--output",
        json_path.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("at its lower bound"),
        "{}",
        stderr(&out)
    );
    let v: Value = serde_json::from_str(&std::fs::read_to_string(&json_path).unwrap()).unwrap();
    let k = &v["parameters"]["k"];
    assert_eq!(k["bound"], "lower");
    assert_eq!(k["value"].as_f64(), Some(0.0));
    assert!(k["stderr"].is_null());
    let limit = k["upper_limit_95"].as_f64().expect("an upper limit");
    assert!(limit > 0.0 && limit < 0.5, "{limit}");
    let corr = &k["correlation_at_limit"];
    assert!((corr["k"].as_f64().unwrap() - 1.0).abs() < 1e-9);
    assert!(corr["n"].as_f64().unwrap().abs() <= 1.0);
    assert_eq!(v["parameters"]["n"]["bound"], "interior");
    assert!((v["parameters"]["n"]["value"].as_f64().unwrap() - 1.5).abs() < 1e-6);
    assert!(
        v["covariance"][1][0].is_null(),
        "k's covariance row is not defined"
    );
}

/// Issue 33: `fit`'s options are checked against each other before any file is read — a
/// material and data that do not exist are never reached — and nothing is written.
#[test]
fn option_conflicts_are_refused_before_any_file_is_read() {
    let dir = tempfile::tempdir().unwrap();
    let json = dir.path().join("fit.json");
    let index = dir.path().join("index.yml");
    let (json_s, index_s) = (json.to_str().unwrap(), index.to_str().unwrap());
    let missing = dir.path().join("missing.csv");
    let missing = missing.to_str().unwrap();
    let cases: [(&[&str], &str); 3] = [
        (
            &[
                "--free",
                "rho_d",
                "--per-wavelength",
                "--index-out",
                index_s,
            ],
            "--index-out needs `n` among the free parameters (--free)",
        ),
        (
            &["--free", "n", "--subsample", "2"],
            "--subsample applies to a .pbsdf table only",
        ),
        (
            &["--free", "n", "--exclude-inadmissible"],
            "--exclude-inadmissible applies to a .pbsdf table only",
        ),
    ];
    for (extra, message) in cases {
        for data in [missing, &example("paint-goniometer.csv")] {
            let mut args = vec![
                "fit",
                "--material",
                "/nonexistent-polbrdf/m.toml",
                "--data",
                data,
                "--output",
                json_s,
            ];
            args.extend(extra);
            let o = polbrdf(&args);
            assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
            assert!(stderr(&o).contains(message), "{args:?}: {}", stderr(&o));
            assert!(
                !json.exists() && !index.exists(),
                "{args:?}: a file was written"
            );
        }
    }
}
