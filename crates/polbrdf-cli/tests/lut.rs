//! `polbrdf lut`: the table's rows are `polbrdf eval`'s values at the same geometries and
//! wavelengths, exactly, in C order over (material, wavelength, θi, θr, Δφ); the sidecar
//! holds the coordinates and the conventions.

use crate::common::{parse_csv, polbrdf, stderr, write};

#[test]
fn the_table_is_eval_at_every_grid_point() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write(
        d,
        "gold.toml",
        "name = \"gold\"\nindex = \"library:Au/Johnson\"\nsigma_deg = 8\n",
    );
    let config = write(
        d,
        "lut.toml",
        "materials = [\"paint\", \"gold.toml\"]\nwavelength_um = [0.55, 1.0]\n\
         theta_i_deg = { start = 0, stop = 60, count = 3 }\ntheta_r_deg = [0, 45, 95]\n\
         dphi_deg = [0, 180]\nquantities = [\"dolp\", \"mueller\", \"brdf\", \"aolp\"]\n",
    );
    let out = d.join("table");
    let o = polbrdf(&["lut", "--config", &config, "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let table = polbrdf_io::npy::read_npy(&out.join("table.npy")).unwrap();
    let mut want: Vec<String> = (0..4)
        .flat_map(|i| (0..4).map(move |j| format!("m{i}{j}")))
        .collect();
    want.extend(["brdf", "dolp", "aolp_deg"].map(String::from));
    assert_eq!(table.columns, want);
    assert_eq!(table.rows(), 2 * 2 * 3 * 3 * 2);
    let meta: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("attrs.json")).unwrap()).unwrap();
    assert_eq!(meta["shape"], serde_json::json!([2, 2, 3, 3, 2]));
    assert_eq!(
        meta["coords"]["theta_i"],
        serde_json::json!([0.0, 30.0, 60.0])
    );
    assert_eq!(
        meta["coords"]["material"],
        serde_json::json!(["paint", "gold"])
    );
    assert!(meta["attrs"]["stokes_basis"]
        .as_str()
        .unwrap()
        .contains("psps"));
    let materials: serde_json::Value =
        serde_json::from_str(meta["attrs"]["materials_json"].as_str().unwrap()).unwrap();
    assert_eq!(materials["gold"]["index"], "library:Au/Johnson");
    assert_eq!(materials["paint"]["n"], 1.65);

    // The same grid through `polbrdf eval`, per material.
    for (m, material) in ["paint", &format!("{}/gold.toml", d.display())]
        .iter()
        .enumerate()
    {
        let mut csv = String::from("theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg,wavelength_um\n");
        for l in [0.55, 1.0] {
            for ti in [0.0, 30.0, 60.0] {
                for tr in [0.0, 45.0, 95.0] {
                    for p in [0.0, 180.0] {
                        csv += &format!("{ti},0,{tr},{p},{l}\n");
                    }
                }
            }
        }
        let g = write(d, "g.csv", &csv);
        let o = polbrdf(&["eval", "--material", material, "--input", &g]);
        assert!(o.status.success(), "{}", stderr(&o));
        let (header, rows) = parse_csv(&String::from_utf8(o.stdout).unwrap());
        let per = rows.len();
        for (r, row) in rows.iter().enumerate() {
            let got = &table.data[(m * per + r) * 19..(m * per + r + 1) * 19];
            for (c, name) in want.iter().enumerate() {
                let k = header.iter().position(|h| h == name).unwrap();
                let v: f64 = row[k].parse().unwrap();
                // F and the BRDF exactly (the CSV prints −0 as 0; the Python suite checks the
                // bits against polbrdf.lut). `eval` takes DoLP and AoLP from the Stokes vector
                // of its F, the table (as Python's `dolp`) from the kernel's BRDF+DoLP+AoLP
                // path: the same formula in another order, equal to rounding.
                if name.starts_with('m') || name == "brdf" {
                    assert_eq!(got[c], v, "material {m} row {r} {name}");
                } else {
                    assert!(
                        (got[c] - v).abs() <= 1e-13 * v.abs().max(1e-300),
                        "{name}: {} {v}",
                        got[c]
                    );
                }
            }
        }
    }
    // No temporary directory is left beside the table.
    let left: Vec<String> = std::fs::read_dir(d)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(".polbrdf-"))
        .collect();
    assert!(left.is_empty(), "{left:?}");
}

/// Issue 35: staging directories left by killed runs (`.polbrdf-<pid>-<random>.tmp/`, and the
/// old `.polbrdf-<name>.partial-<pid>-<n>/`) are removed by the next `lut` writing next to them
/// when their process is gone; those of a running process are kept.
#[cfg(unix)]
#[test]
fn a_later_run_removes_the_staging_directories_of_killed_runs() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let mut child = std::process::Command::new("true").spawn().unwrap();
    let dead = child.id();
    child.wait().unwrap();
    let stale = [
        format!(".polbrdf-lut.partial-{dead}-0"),
        format!(".polbrdf-{dead}-0123456789abcdef.tmp"),
    ];
    let live = format!(".polbrdf-lut.partial-{}-0", std::process::id());
    for name in stale.iter().chain([&live]) {
        std::fs::create_dir(d.join(name)).unwrap();
        std::fs::write(d.join(name).join("table.npy"), vec![0u8; 1000]).unwrap();
    }
    let cfg = write(
        d,
        "l.toml",
        "materials = [\"paint\"]\nwavelength_um = [0.6]\ntheta_i_deg = [0]\ntheta_r_deg = [0]\n\
         dphi_deg = [180]\n",
    );
    let o = polbrdf(&[
        "lut",
        "--config",
        &cfg,
        "--out",
        d.join("out").to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    for name in &stale {
        assert!(!d.join(name).exists(), "{name} left");
    }
    assert!(d.join(&live).is_dir());
    assert!(d.join("out/table.npy").is_file());
}
