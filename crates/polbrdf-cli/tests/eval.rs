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
        eval_matches_vector(c, &mat, &geo, 0);
    }
}

/// `eval` of the material file `mat` on the one-row table `geo` (whose column `id_col` holds
/// the case's id) agrees with test-vector case `c`: BRDF, the 16 entries and the DoLP.
fn eval_matches_vector(c: &Value, mat: &str, geo: &str, id_col: usize) {
    let id = c["id"].as_str().unwrap();
    let out = polbrdf(&["eval", "--material", mat, "--input", geo]);
    assert!(out.status.success(), "{id}: {}", stderr(&out));
    let (header, rows) = parse_csv(&String::from_utf8(out.stdout).unwrap());
    assert_eq!(rows.len(), 1);
    let col = |name: &str| -> f64 {
        let k = header.iter().position(|h| h == name).unwrap();
        rows[0][k].parse().unwrap()
    };
    assert_eq!(rows[0][id_col], id, "pass-through column copied unchanged");
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

/// The direction vector of `(θ, φ)` in degrees, as a renderer would give it (unit length;
/// at θ = 90°, `z = 0` exactly: `cos(π/2)` in f64 is 6·10⁻¹⁷, above the horizon).
fn vector(theta_deg: f64, phi_deg: f64) -> [f64; 3] {
    let mut w = polbrdf::geometry::direction(theta_deg.to_radians(), phi_deg.to_radians());
    if theta_deg == 90.0 {
        w[2] = 0.0;
    }
    w
}

#[test]
fn every_test_vector_matches_through_eval_from_direction_vectors() {
    // The direction columns instead of the angles (out of order, with a pass-through column
    // and vectors of any length): the same test vectors, through the direction entry point.
    let dir = tempfile::tempdir().unwrap();
    let mut checked = 0;
    for c in &vectors() {
        let id = c["id"].as_str().unwrap();
        let inp = &c["inputs"];
        let deg = |k: &str| inp[k].as_f64().unwrap();
        let (ti, pi, tr, pr) = (
            deg("theta_i_deg"),
            deg("phi_i_deg"),
            deg("theta_r_deg"),
            deg("phi_r_deg"),
        );
        // A vector along the normal has no azimuth (φ = 0, docs/model.md §9.11): a case whose
        // frame needs one cannot be written as vectors.
        let no_azimuth = |t: f64, p: f64| t == 0.0 && p.rem_euclid(360.0) != 0.0;
        if no_azimuth(ti, pi) || no_azimuth(tr, pr) {
            continue;
        }
        let (wi, wr) = (
            vector(ti, pi).map(|x| 3.0 * x),
            vector(tr, pr).map(|x| 0.5 * x),
        );
        let mat = write(dir.path(), "m.toml", &material_toml(inp));
        let geo = write(
            dir.path(),
            "g.csv",
            &format!(
                "w_r_z,id,w_i_x,w_i_y,w_i_z,w_r_x,w_r_y\n{},{id},{},{},{},{},{}\n",
                wr[2], wi[0], wi[1], wi[2], wr[0], wr[1]
            ),
        );
        eval_matches_vector(c, &mat, &geo, 1);
        checked += 1;
    }
    assert!(checked >= 30, "only {checked} cases as vectors");
}

#[test]
fn direction_tables_agree_across_formats_and_with_angles() {
    // The same geometries as angles (CSV) and as vectors (CSV, .npy): the vectors' results are
    // the direction entry point's (the same bits in every format, within 1e-12·F00 of the
    // angles'), and a vector below the horizon is a zero row, not an error.
    let dir = tempfile::tempdir().unwrap();
    let geoms = [
        (30.0, 0.0, 30.0, 180.0),
        (60.0, 10.0, 45.0, 200.0),
        (5.0, 300.0, 80.0, 90.0),
    ];
    let mut angles = String::from("theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg\n");
    let mut data = Vec::new();
    for (ti, pi, tr, pr) in geoms {
        angles += &format!("{ti},{pi},{tr},{pr}\n");
        data.extend(vector(ti, pi));
        data.extend(vector(tr, pr));
    }
    // Below the horizon: w_r with z < 0.
    data.extend([0.5, 0.0, 0.8, 0.3, 0.1, -0.2]);
    let names = polbrdf_io::csv_io::DIRECTION_COLUMNS;
    let mut csv = names.join(",") + "\n";
    for row in data.chunks(6) {
        csv += &row
            .iter()
            .map(|x| format!("{x}"))
            .collect::<Vec<_>>()
            .join(",");
        csv += "\n";
    }
    let npy = dir.path().join("g.npy");
    std::fs::write(&npy, polbrdf_io::npy::npy_bytes(&names, &data).unwrap()).unwrap();
    let run = |input: &str| {
        let out = polbrdf(&["eval", "--material", "paint", "--input", input]);
        assert!(out.status.success(), "{input}: {}", stderr(&out));
        parse_csv(&String::from_utf8(out.stdout).unwrap())
    };
    let (h_a, r_a) = run(&write(dir.path(), "a.csv", &angles));
    let (h_c, r_c) = run(&write(dir.path(), "d.csv", &csv));
    let (h_n, r_n) = run(npy.to_str().unwrap());
    assert_eq!((r_c.len(), r_n.len()), (4, 4));
    let entries = |h: &[String], r: &[String]| -> Vec<f64> {
        let k = h.iter().position(|c| c == "m00").unwrap();
        r[k..k + 16].iter().map(|v| v.parse().unwrap()).collect()
    };
    for k in 0..4 {
        let (c, n) = (entries(&h_c, &r_c[k]), entries(&h_n, &r_n[k]));
        assert_eq!(c, n, "row {k}: CSV and .npy give the same bits");
        if k == 3 {
            assert!(c.iter().all(|v| *v == 0.0), "below the horizon: {c:?}");
            continue;
        }
        let a = entries(&h_a, &r_a[k]);
        for (x, y) in c.iter().zip(&a) {
            assert!((x - y).abs() <= 1e-12 * a[0], "row {k}: {x} vs {y}");
        }
    }
}

/// Issue 35: `eval`'s brdf, dolp and aolp_deg are the core's one definition of them,
/// `Engine::brdf_dolp_aolp_into` (what `lut` and the Python module write), bit for bit: the
/// DoLP of the matrix's first column differed from it in the last bit in about a third of the
/// rows.
#[test]
fn eval_brdf_dolp_aolp_are_the_engines_bit_for_bit() {
    use polbrdf::{Engine, GeometryBatch};
    let dir = tempfile::tempdir().unwrap();
    let rows: Vec<[f64; 4]> = (0..300)
        .map(|k| {
            let k = f64::from(k);
            [
                (k * 7.3) % 89.0,
                (k * 13.1) % 360.0,
                (k * 3.7) % 89.0,
                (k * 29.9) % 360.0,
            ]
        })
        .collect();
    let mut csv = String::from("theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg\n");
    for r in &rows {
        csv += &format!("{},{},{},{}\n", r[0], r[1], r[2], r[3]);
    }
    let input = write(dir.path(), "g.csv", &csv);
    let output = dir.path().join("o.csv");
    let out = polbrdf(&[
        "eval",
        "--material",
        "paint",
        "--input",
        &input,
        "--output",
        output.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let (header, got) = parse_csv(&std::fs::read_to_string(&output).unwrap());
    assert_eq!(header[4..7], ["brdf", "dolp", "aolp_deg"]);
    let rad = |j: usize| rows.iter().map(|r| r[j].to_radians()).collect::<Vec<f64>>();
    let (ti, pi, tr, pr) = (rad(0), rad(1), rad(2), rad(3));
    let batch = GeometryBatch::new(&ti, &pi, &tr, &pr).unwrap();
    let m = polbrdf::preset("paint").unwrap().build().unwrap();
    let n = rows.len();
    let (mut b, mut d, mut a) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    Engine::new(&m)
        .brdf_dolp_aolp_into(&batch, &mut b, &mut d, &mut a)
        .unwrap();
    // The CSV writes −0 as 0 (`+ 0.0`).
    for (k, row) in got.iter().enumerate() {
        let v = |j: usize| row[j].parse::<f64>().unwrap().to_bits();
        assert_eq!(v(4), (b[k] + 0.0).to_bits(), "row {k}: brdf");
        assert_eq!(v(5), (d[k] + 0.0).to_bits(), "row {k}: dolp");
        assert_eq!(
            v(6),
            (a[k].to_degrees() + 0.0).to_bits(),
            "row {k}: aolp_deg"
        );
    }
}
