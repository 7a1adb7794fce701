//! Spectral materials on the command line: `eval` with a wavelength column, `spectrum`, band
//! options, `materials`, and an effective index fitted per wavelength and read back.

use crate::common::{parse_csv, polbrdf, stderr, write};
use polbrdf::{Geometry, MaterialSpec};

fn au(lambda: f64) -> MaterialSpec {
    let idx = polbrdf_io::library::load("Au/Johnson")
        .unwrap()
        .at(lambda)
        .unwrap();
    let mut s = MaterialSpec::new(idx.n(), 10.0);
    s.k = idx.k();
    s
}

#[test]
fn eval_takes_the_index_at_each_rows_wavelength() {
    let dir = tempfile::tempdir().unwrap();
    let m = write(
        dir.path(),
        "au.toml",
        "index = \"library:Au/Johnson\"\nsigma_deg = 10\n",
    );
    let rows = [(30.0, 0.45), (30.0, 0.6328), (60.0, 1.2), (10.0, 0.6328)];
    let mut csv = "theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg,wavelength_um\n".to_string();
    for (t, l) in rows {
        csv += &format!("{t},0,{t},170,{l}\n");
    }
    let g = write(dir.path(), "g.csv", &csv);
    let o = polbrdf(&["eval", "--material", &m, "--input", &g]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (header, out) = parse_csv(&String::from_utf8(o.stdout).unwrap());
    assert_eq!(header[4], "wavelength_um", "passed through like the angles");
    let m00 = header.iter().position(|h| h == "m00").unwrap();
    let m01 = header.iter().position(|h| h == "m01").unwrap();
    for ((t, l), row) in rows.iter().zip(&out) {
        let g = Geometry::from_degrees(*t, 0.0, *t, 170.0).unwrap();
        let want = au(*l).build().unwrap().evaluate(&g).pbrdf;
        for (col, w) in [(m00, want.m00()), (m01, want[(0, 1)])] {
            let got: f64 = row[col].parse().unwrap();
            assert!(
                (got - w).abs() <= 1e-12 * want.m00(),
                "λ = {l}: {got} vs {w}"
            );
        }
    }
}

#[test]
fn spectrum_writes_the_table_and_the_figure() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("s");
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/");
    let (al, water) = (
        format!("{root}aluminium-spectral.toml"),
        format!("{root}water.toml"),
    );
    let o = polbrdf(&[
        "spectrum",
        "--material",
        &al,
        "--material",
        &water,
        "--theta-deg",
        "45",
        "--points",
        "50",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(out.join("spectrum.csv")).unwrap();
    let (header, rows) = parse_csv(&text);
    assert_eq!(
        header,
        [
            "wavelength_um",
            "material",
            "n",
            "k",
            "brdf",
            "dolp",
            "aolp_deg"
        ]
    );
    assert_eq!(rows.len(), 100);
    assert_eq!(rows[0][0], "0.4");
    assert_eq!(rows[49][0], "14.0");
    // Water at 45° specular: the DoLP of the Fresnel reflectances at its index (the volume
    // term is zero, so roughness plays no part at specular, docs/model.md §10).
    for row in rows.iter().filter(|r| r[1].starts_with("water")) {
        let (n, k): (f64, f64) = (row[2].parse().unwrap(), row[3].parse().unwrap());
        let f = polbrdf::RefractiveIndex::new(n, k)
            .unwrap()
            .amplitudes(45f64.to_radians());
        let (rs, rp) = (f.reflectance_s(), f.reflectance_p());
        let want = (rs - rp) / (rs + rp);
        let got: f64 = row[5].parse().unwrap();
        assert!(
            (got - want).abs() < 1e-12,
            "λ = {}: {got} vs {want}",
            row[0]
        );
    }
    for f in ["spectrum.png", "spectrum.svg"] {
        assert!(std::fs::metadata(out.join(f)).unwrap().len() > 1000, "{f}");
    }
}

#[test]
fn materials_lists_the_library_with_ranges() {
    let o = polbrdf(&["materials"]);
    assert!(o.status.success());
    let text = String::from_utf8(o.stdout).unwrap();
    for id in ["Au/Johnson", "H2O/Hale", "illite/Querry", "SiO2/Malitson"] {
        assert!(text.contains(id), "{id}");
    }
    assert!(text.contains("0.1879–1.937"), "Au/Johnson's range");
}

#[test]
fn a_band_result_states_its_quadrature() {
    let dir = tempfile::tempdir().unwrap();
    let m = write(
        dir.path(),
        "au.toml",
        "index = \"library:Au/Johnson\"\nsigma_deg = 10\n",
    );
    let band = write(
        dir.path(),
        "vis.csv",
        "wavelength_um,response\n0.45,0\n0.55,1\n0.65,0\n",
    );
    let out = dir.path().join("c");
    let o = polbrdf(&[
        "contrast",
        "--target",
        &m,
        "--background",
        "paint",
        "--sun-zenith-deg",
        "40",
        "--grid-deg",
        "10,20",
        "--band",
        &band,
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let best: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("best.json")).unwrap()).unwrap();
    let s = &best["spectrum"];
    assert_eq!(s["band"], "vis.csv");
    assert!((s["step_um"].as_f64().unwrap() - 0.2 / 16.0).abs() < 1e-15);
    assert!(s["nodes"].as_u64().unwrap() >= 48);
    assert_eq!(s["integrated"], "Stokes vectors, response-weighted mean");
}

#[test]
fn an_effective_index_per_wavelength_round_trips_through_yaml() {
    // s/p BRDF of a paint whose index changes with λ, fitted per wavelength for n and k; the
    // fitted index written as a refractiveindex.info file and read back as a material's index.
    let truth = [(0.45, 1.70, 0.05), (0.55, 1.62, 0.03), (0.65, 1.58, 0.01)];
    let mut csv =
        "theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg,wavelength_um,brdf_s,sigma_brdf_s,brdf_p,sigma_brdf_p\n"
            .to_string();
    for (l, n, k) in truth {
        let mut s = MaterialSpec::new(n, 8.0);
        s.k = k;
        s.rho_d = 0.01;
        let m = s.build().unwrap();
        for t in [20.0, 35.0, 50.0, 60.0, 70.0] {
            let f = m
                .evaluate(&Geometry::from_degrees(t, 0.0, t, 180.0).unwrap())
                .pbrdf;
            let (bs, bp) = (f.m00() + f[(0, 1)], f.m00() - f[(0, 1)]);
            csv += &format!("{t},0,{t},180,{l},{bs},{},{bp},{}\n", 1e-3 * bs, 1e-3 * bp);
        }
    }
    let dir = tempfile::tempdir().unwrap();
    let data = write(dir.path(), "sp.csv", &csv);
    let init = write(
        dir.path(),
        "init.toml",
        "n = 1.5\nk = 0.02\nsigma_deg = 8\nrho_d = 0.01\n",
    );
    let yml = dir.path().join("effective.yml");
    let o = polbrdf(&[
        "fit",
        "--material",
        &init,
        "--data",
        &data,
        "--free",
        "n,k",
        "--per-wavelength",
        "--index-out",
        yml.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let doc: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let fits = doc["per_wavelength"].as_array().unwrap();
    assert_eq!(fits.len(), 3);
    let index = polbrdf_io::read_refractiveindex_yaml(&yml).unwrap();
    for ((l, n, k), f) in truth.iter().zip(fits) {
        assert_eq!(f["wavelength_um"].as_f64().unwrap(), *l);
        let p = &f["parameters"];
        assert!((p["n"]["value"].as_f64().unwrap() - n).abs() < 1e-6, "{f}");
        assert!((p["k"]["value"].as_f64().unwrap() - k).abs() < 1e-6, "{f}");
        let at = index.at(*l).unwrap();
        assert_eq!(at.n(), p["n"]["value"].as_f64().unwrap());
        assert_eq!(at.k(), p["k"]["value"].as_f64().unwrap());
    }
}
