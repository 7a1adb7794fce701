//! `polbrdf eval`: the shared test vectors through the command line, and its contract.

use crate::common::{parse_csv, polbrdf, stderr, write};
use serde_json::Value;

fn vectors() -> Vec<Value> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../tests/data/test-vectors.json"
    );
    let doc: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    doc["cases"].as_array().unwrap().clone()
}

/// A material file as a user would write it for a test-vector case.
fn material_toml(inp: &Value) -> String {
    let mut s = format!("n = {}\nk = {}\n", inp["N"][0], inp["N"][1]);
    if inp["a_source"] == "hemisphere" {
        s += &format!("sigma_deg = {}\n", inp["sigma_deg"]);
    } else {
        s += &format!("a = {}\nb = {}\n", inp["a"], inp["b"]);
    }
    s += &format!(
        "form = {}\nshadowing = {}\ntau_deg = {}\nomega_deg = {}\nazimuth_term = {}\nrho_d = {}\nrho_v = {}\n",
        inp["form"], inp["shadow"], inp["tau_deg"], inp["Omega_deg"], inp["azimuth_term"], inp["rho_D"], inp["rho_V"]
    );
    s
}

#[test]
fn every_test_vector_matches_through_eval() {
    let dir = tempfile::tempdir().unwrap();
    let cases = vectors();
    assert!(cases.len() >= 40);
    for c in &cases {
        let id = c["id"].as_str().unwrap();
        let inp = &c["inputs"];
        let mat = write(dir.path(), "m.toml", &material_toml(inp));
        // Columns deliberately out of order, with a pass-through column first.
        let geo = write(
            dir.path(),
            "g.csv",
            &format!(
                "id,phi_r_deg,theta_i_deg,theta_r_deg,phi_i_deg\n{id},{},{},{},{}\n",
                inp["phi_r_deg"], inp["theta_i_deg"], inp["theta_r_deg"], inp["phi_i_deg"]
            ),
        );
        let out = polbrdf(&["eval", "--material", &mat, "--input", &geo]);
        assert!(out.status.success(), "{id}: {}", stderr(&out));
        let (header, rows) = parse_csv(&String::from_utf8(out.stdout).unwrap());
        assert_eq!(rows.len(), 1);
        let col = |name: &str| -> f64 {
            let k = header.iter().position(|h| h == name).unwrap();
            rows[0][k].parse().unwrap()
        };
        assert_eq!(rows[0][0], id, "pass-through column copied unchanged");
        let f_ref = c["outputs"]["f"].as_f64().unwrap();
        let f00 = c["outputs"]["F"][0][0].as_f64().unwrap();
        assert!(
            (col("brdf") - f_ref).abs() <= 1e-9 * f_ref + 1e-12,
            "{id}: brdf"
        );
        for i in 0..4 {
            for j in 0..4 {
                let want = c["outputs"]["F"][i][j].as_f64().unwrap();
                let got = col(&format!("m{i}{j}"));
                assert!(
                    (got - want).abs() <= 1e-9 * f00 + 1e-12,
                    "{id}: m{i}{j} = {got}, expected {want}"
                );
            }
        }
        let dolp = c["outputs"]["dolp"].as_f64().unwrap();
        assert!((col("dolp") - dolp).abs() <= 1e-9, "{id}: dolp");
    }
}

#[test]
fn output_columns_follow_the_contract_and_values_round_trip() {
    let dir = tempfile::tempdir().unwrap();
    let geo = write(
        dir.path(),
        "g.csv",
        "theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg,note\n45,0,45,180,x y\n30,10,60,200,\"a,b\"\n",
    );
    let out_path = dir.path().join("out.csv");
    let out = polbrdf(&[
        "eval",
        "--material",
        "paint",
        "--input",
        &geo,
        "--output",
        out_path.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(
        out.stdout.is_empty(),
        "nothing on stdout when --output is given"
    );
    let text = std::fs::read_to_string(&out_path).unwrap();
    let header = text.lines().next().unwrap();
    let mut want =
        "theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg,note,brdf,dolp,aolp_deg".to_string();
    for k in 0..16 {
        want += &format!(",m{}{}", k / 4, k % 4);
    }
    assert_eq!(header, want);
    assert!(
        text.contains("\"a,b\""),
        "a quoted pass-through field stays one field"
    );
    // Full precision: the printed brdf parses back to exactly the library's value (that of the
    // batch API, which `eval` uses).
    let paint = polbrdf::preset("paint").unwrap().build().unwrap();
    let g = polbrdf::Geometry::from_degrees(45.0, 0.0, 45.0, 180.0).unwrap();
    let line2: Vec<&str> = text.lines().nth(1).unwrap().split(',').collect();
    let f = polbrdf::batch::pbrdf_of(&paint, &[g])[0].0[0][0];
    assert_eq!(line2[5].parse::<f64>().unwrap(), f);
}

#[test]
fn presets_are_listed_and_show_as_loadable_material_files() {
    let out = polbrdf(&["materials"]);
    assert!(out.status.success());
    let list = String::from_utf8(out.stdout).unwrap();
    for name in polbrdf::presets::names() {
        assert!(list.contains(name), "{name} listed");
        let shown = polbrdf(&["materials", "--show", name]);
        assert!(shown.status.success());
        let spec = polbrdf_io::parse_material(
            &String::from_utf8(shown.stdout).unwrap(),
            std::path::Path::new(name),
        )
        .unwrap();
        assert_eq!(spec, polbrdf::preset(name).unwrap());
    }
}

// The table of bad inputs for every command is in bad_inputs.rs.

#[test]
fn a_failed_run_leaves_an_existing_output_untouched() {
    let dir = tempfile::tempdir().unwrap();
    let out_path = dir.path().join("out.csv");
    std::fs::write(&out_path, "precious").unwrap();
    let geo = write(
        dir.path(),
        "g.csv",
        "theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg\n10,0,x,180\n",
    );
    let out = polbrdf(&[
        "eval",
        "--material",
        "paint",
        "--input",
        &geo,
        "--output",
        out_path.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(3));
    assert_eq!(std::fs::read_to_string(&out_path).unwrap(), "precious");
}

#[test]
fn unreadable_input_is_an_io_error_and_usage_errors_exit_2() {
    let out = polbrdf(&[
        "eval",
        "--material",
        "paint",
        "--input",
        "/nonexistent/g.csv",
    ]);
    assert_eq!(out.status.code(), Some(4), "{}", stderr(&out));
    assert!(stderr(&out).contains("/nonexistent/g.csv"));
    let out = polbrdf(&["eval", "--material", "paint"]);
    assert_eq!(out.status.code(), Some(2));
    let out = polbrdf(&["eval", "--material", "no-such-preset", "--input", "x.csv"]);
    assert_eq!(out.status.code(), Some(3));
    assert!(stderr(&out).contains("paint"), "lists the presets");
}

#[test]
fn bom_crlf_and_horizon_rows_are_accepted() {
    let dir = tempfile::tempdir().unwrap();
    let geo = write(
        dir.path(),
        "g.csv",
        "\u{feff}theta_i_deg, phi_i_deg, theta_r_deg, phi_r_deg\r\n90,0,30,180\r\n89.999,0,89.999,180\r\n",
    );
    let out = polbrdf(&["eval", "--material", "paint", "--input", &geo]);
    assert!(out.status.success(), "{}", stderr(&out));
    let (header, rows) = parse_csv(&String::from_utf8(out.stdout).unwrap());
    assert_eq!(header[0], "theta_i_deg");
    let brdf = header.iter().position(|h| h == "brdf").unwrap();
    assert_eq!(rows[0][brdf].trim(), "0.0", "θi = 90° reflects nothing");
    let v: f64 = rows[1][brdf].trim().parse().unwrap();
    assert!(v.is_finite() && v > 0.0);
}
