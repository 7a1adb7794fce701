//! Suspicious units warn on standard error and the command goes on (issue 36): a roughness
//! below 1° in a material, a geometry or measurement file whose degree columns hold radians.

use crate::common::{polbrdf, stderr, write};

#[test]
fn a_roughness_below_one_degree_warns_and_eval_still_runs() {
    let dir = tempfile::tempdir().unwrap();
    let mat = write(dir.path(), "m.toml", "n = 1.5\nsigma_deg = 0.26\n");
    let geo = write(
        dir.path(),
        "g.csv",
        "theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg\n30,0,30,180\n",
    );
    let out = polbrdf(&["eval", "--material", &mat, "--input", &geo]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(
        stderr(&out).contains(&format!(
            "polbrdf: warning: {mat}: sigma_deg = 0.26 is below 1°, a near-mirror; if 0.26 is \
             in radians, write sigma_deg = 14.8969"
        )),
        "{}",
        stderr(&out)
    );
    assert!(!out.stdout.is_empty(), "the result is still written");
    // A roughness in degrees: no warning.
    let out = polbrdf(&["eval", "--material", "paint", "--input", &geo]);
    assert!(out.status.success());
    assert!(!stderr(&out).contains("warning"), "{}", stderr(&out));
}

#[test]
fn radians_in_the_degree_columns_warn() {
    let dir = tempfile::tempdir().unwrap();
    let geo = write(
        dir.path(),
        "g.csv",
        "theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg\n0.5236,0,0.5236,3.1416\n1.2,0,0.9,3.1416\n",
    );
    let out = polbrdf(&["eval", "--material", "paint", "--input", &geo]);
    assert!(out.status.success(), "{}", stderr(&out));
    let err = stderr(&out);
    assert!(
        err.contains(&format!(
            "polbrdf: warning: {geo}: every angle in theta_i_deg, phi_i_deg, theta_r_deg, \
             phi_r_deg is small"
        )) && err.contains("over 2 rows"),
        "{err}"
    );
    // The same geometries in degrees: no warning.
    let deg = write(
        dir.path(),
        "d.csv",
        "theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg\n30,0,30,180\n68.75,0,51.57,180\n",
    );
    let out = polbrdf(&["eval", "--material", "paint", "--input", &deg]);
    assert!(!stderr(&out).contains("warning"), "{}", stderr(&out));
}

#[test]
fn fit_warns_about_radians_in_its_measurements() {
    let dir = tempfile::tempdir().unwrap();
    let mut csv = String::from("theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg,brdf\n");
    for k in 1..=12 {
        let t = 0.1 * f64::from(k);
        csv += &format!("{t},0,{t},3.14159,{}\n", 0.1 + 0.01 * f64::from(k));
    }
    let data = write(dir.path(), "data.csv", &csv);
    let out = polbrdf(&[
        "fit",
        "--material",
        "paint",
        "--data",
        &data,
        "--free",
        "rho_d",
    ]);
    assert!(
        stderr(&out).contains(&format!("polbrdf: warning: {data}: every angle in")),
        "{}",
        stderr(&out)
    );
}
