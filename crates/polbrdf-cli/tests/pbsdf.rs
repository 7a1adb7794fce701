//! `polbrdf export` and `polbrdf fit --data table.pbsdf` (docs/model.md §20): the round trip,
//! export → read back → fit, recovers the exported parameters; the table's layout is checked
//! against its definition cell by cell.

use crate::common::{polbrdf, stderr, write};
use polbrdf::geometry::rusinkiewicz::{cell_geometry, to_reflection_frame};
use polbrdf_io::PbsdfTable;

#[test]
fn export_writes_the_model_in_the_reflection_frame() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("paint.pbsdf");
    let o = polbrdf(&[
        "export",
        "--material",
        "paint",
        "--output",
        out.to_str().unwrap(),
        "--grid",
        "9,7,11",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let mut t = PbsdfTable::open(&out).unwrap();
    assert_eq!(t.wavelengths_nm, vec![450, 500, 550, 600, 650]);
    assert_eq!(
        (t.phi_d.len(), t.theta_d.len(), t.theta_h.len()),
        (9, 7, 11)
    );
    assert!(
        (t.phi_d[0] + std::f64::consts::PI).abs() < 1e-6
            && (t.theta_h[10] - std::f64::consts::FRAC_PI_2).abs() < 1e-6
    );
    let m = polbrdf::preset("paint").unwrap().build_at(0.55).unwrap();
    let mut slab = Vec::new();
    let mut checked = 0;
    for p in 0..9 {
        t.read_slab(p, &mut slab).unwrap();
        for d in 0..7 {
            for h in 0..11 {
                let g = cell_geometry(t.phi_d[p], t.theta_d[d], t.theta_h[h]).unwrap();
                let want = match g.angle_variables() {
                    Some(v) => to_reflection_frame(&m.pbrdf(&g), &v).to_row_major(),
                    None => [0.0; 16],
                };
                for b in 0..5 {
                    let at = ((d * 11 + h) * 5 + b) * 16;
                    for k in 0..16 {
                        let got = f64::from(slab[at + k]);
                        // The axes are stored as float32: the geometry differs by ~1e-7 rad.
                        assert!(
                            (got - want[k]).abs() <= 2e-5 * want[0].abs().max(1e-3),
                            "cell {p},{d},{h} entry {k}: {got} vs {}",
                            want[k]
                        );
                    }
                }
                checked += 1;
            }
        }
    }
    assert_eq!(checked, 9 * 7 * 11);
}

#[test]
fn round_trip_recovers_the_parameters() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let truth = "n = 1.65\nsigma_deg = 15\nrho_d = 0.03\nrho_v = 0.01\n";
    let start = "n = 1.4\nsigma_deg = 25\nrho_d = 0.01\nrho_v = 0.03\n";
    let truth_p = write(d, "truth.toml", truth);
    let start_p = write(d, "start.toml", start);
    let table = d.join("t.pbsdf");
    let o = polbrdf(&[
        "export",
        "--material",
        &truth_p,
        "--output",
        table.to_str().unwrap(),
        "--grid",
        "19,24,46",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let json = d.join("fit.json");
    let plot = d.join("res.png");
    let o = polbrdf(&[
        "fit",
        "--material",
        &start_p,
        "--data",
        table.to_str().unwrap(),
        "--free",
        "n,sigma_deg,rho_d,rho_v",
        "--subsample",
        "2",
        "--output",
        json.to_str().unwrap(),
        "--plot",
        plot.to_str().unwrap(),
    ]);
    let msg = stderr(&o);
    assert!(o.status.success(), "{msg}");
    assert!(msg.contains("0 not physically realizable"), "{msg}");
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    let bands = v["per_band"].as_array().unwrap();
    assert_eq!(bands.len(), 5);
    for (b, nm) in bands.iter().zip([450, 500, 550, 600, 650]) {
        assert_eq!(b["wavelength_nm"], nm);
        assert!(d.join(format!("res_{nm}nm.png")).exists());
        let p = &b["parameters"];
        for (name, want) in [
            ("n", 1.65),
            ("sigma_deg", 15.0),
            ("rho_d", 0.03),
            ("rho_v", 0.01),
        ] {
            let got = p[name]["value"].as_f64().unwrap();
            // The cells hold the model at the stored (float32) nodes, rounded to float32: the
            // fit recovers the parameters to ~1e-6 relative (before the export used the float32
            // nodes, ρ_D came back 2e-3 off).
            assert!(
                (got - want).abs() < 1e-5 * want,
                "{nm} nm {name}: {got} vs {want}"
            );
        }
        assert!(b["table"]["cells_used"].as_u64().unwrap() > 1000);
    }
}

#[test]
fn inadmissible_cells_are_counted_and_excluded_on_request() {
    // A table whose every matrix has M11 > M00 (more polarized output than input) at one band.
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let table = d.join("t.pbsdf");
    let o = polbrdf(&[
        "export",
        "--material",
        "paint",
        "--output",
        table.to_str().unwrap(),
        "--grid",
        "7,8,10",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    // Rewrite it with M11 doubled in every cell (band-independent) through the library writer.
    let mut t = PbsdfTable::open(&table).unwrap();
    let mut slabs = Vec::new();
    for p in 0..7 {
        let mut s = Vec::new();
        t.read_slab(p, &mut s).unwrap();
        for cell in s.chunks_exact_mut(16) {
            cell[5] = 2.0 * cell[0];
        }
        slabs.push(s);
    }
    let bad = d.join("bad.pbsdf");
    polbrdf_io::write_pbsdf(
        &bad,
        &t.phi_d,
        &t.theta_d,
        &t.theta_h,
        &t.wavelengths_nm,
        |p, cells| Ok::<_, String>(slabs[p][cells.start * 80..cells.end * 80].to_vec()),
    )
    .unwrap();
    let run = |extra: &[&str]| {
        let mut args = vec![
            "fit",
            "--material",
            "paint",
            "--data",
            bad.to_str().unwrap(),
            "--free",
            "n",
            "--output",
            d.join("f.json").to_str().unwrap().to_string().leak(),
        ];
        args.extend_from_slice(extra);
        polbrdf(&args)
    };
    let o = run(&[]);
    let msg = stderr(&o);
    let v: serde_json::Value =
        serde_json::from_slice(&std::fs::read(d.join("f.json")).unwrap()).unwrap();
    let used = v["per_band"][0]["table"]["cells_used"].as_u64().unwrap();
    let inadm = v["per_band"][0]["table"]["inadmissible"].as_u64().unwrap();
    assert!(inadm > 0 && inadm == used, "{msg}");
    assert!(msg.contains("not physically realizable, kept"), "{msg}");
    let o = run(&["--exclude-inadmissible"]);
    let msg = stderr(&o);
    assert_eq!(o.status.code(), Some(3), "{msg}");
    assert!(msg.contains("excluded"), "{msg}");
}

/// Issue 35: a sparse file whose header claims 32768 × 32768 cells (68.7 GB of matrices in a
/// file of 260 KB of data) is fitted within 2 GB of address space: only the kept cells are
/// read (before, a whole φ_d slab was allocated from the header's claim and the run aborted).
#[cfg(unix)]
#[test]
fn a_fit_reads_only_the_cells_it_keeps() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("sparse.pbsdf");
    let n = 32768u64;
    let nodes = |k: u64| -> Vec<u8> {
        (0..k)
            .flat_map(|i| (1.5 * i as f32 / (k - 1) as f32).to_le_bytes())
            .collect()
    };
    let fields: Vec<(&str, u8, Vec<u64>, Vec<u8>)> = vec![
        ("phi_d", 10, vec![1, 1], 0f32.to_le_bytes().to_vec()),
        ("theta_d", 10, vec![1, n], nodes(n)),
        ("theta_h", 10, vec![1, n], nodes(n)),
        ("wvls", 3, vec![1], 550u16.to_le_bytes().to_vec()),
    ];
    let header: u64 = 18
        + fields
            .iter()
            .map(|f| 2 + f.0.len() as u64 + 3 + 8 + 8 * f.2.len() as u64)
            .sum::<u64>()
        + 2
        + 1
        + 3
        + 8
        + 8 * 6;
    let mut bytes = b"tensor_file\0\x01\x00".to_vec();
    bytes.extend(5u32.to_le_bytes());
    let mut at = header;
    let m_shape = [1, n, n, 1, 4, 4];
    let all = fields
        .iter()
        .map(|f| (f.0, f.1, f.2.clone(), f.3.len() as u64))
        .chain([("M", 10, m_shape.to_vec(), n * n * 64)]);
    for (name, dtype, shape, len) in all {
        bytes.extend((name.len() as u16).to_le_bytes());
        bytes.extend(name.as_bytes());
        bytes.extend((shape.len() as u16).to_le_bytes());
        bytes.push(dtype);
        bytes.extend(at.to_le_bytes());
        for d in shape {
            bytes.extend(d.to_le_bytes());
        }
        at += len;
    }
    assert_eq!(bytes.len() as u64, header);
    for f in &fields {
        bytes.extend(&f.3);
    }
    std::fs::write(&path, &bytes).unwrap();
    let f = std::fs::OpenOptions::new().write(true).open(&path).unwrap();
    f.set_len(at).unwrap();
    drop(f);
    let out = dir.path().join("fit.json");
    let o = std::process::Command::new("sh")
        .args(["-c", "ulimit -v 2000000 && exec \"$0\" \"$@\""])
        .arg(env!("CARGO_BIN_EXE_polbrdf"))
        .args([
            "fit",
            "--material",
            "paint",
            "--free",
            "n",
            "--subsample",
            "4096",
            "--data",
        ])
        .arg(&path)
        .arg("--output")
        .arg(&out)
        .output()
        .unwrap();
    let msg = stderr(&o);
    assert!(
        o.status.code().is_some_and(|c| c != 1),
        "{:?}: {msg}",
        o.status
    );
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
    assert_eq!(v["per_band"][0]["table"]["cells"], 64, "{msg}");
}

/// Standard error closed by its reader (EPIPE on every write).
fn broken_stderr() -> std::process::Stdio {
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    writer.into()
}

/// Issue 35: a broken standard error costs neither the result nor the exit status of
/// `export` and of a `.pbsdf` fit (their notes went through a panicking `eprintln!`).
#[test]
fn a_broken_standard_error_loses_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let table = d.join("t.pbsdf");
    let run = |args: &[&str]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_polbrdf"))
            .args(args)
            .stderr(broken_stderr())
            .output()
            .unwrap()
    };
    let o = run(&[
        "export",
        "--material",
        "paint",
        "--grid",
        "9,12,23",
        "--output",
        table.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0));
    assert!(PbsdfTable::open(&table).is_ok());
    let json = d.join("fit.json");
    let o = run(&[
        "fit",
        "--material",
        "paint",
        "--data",
        table.to_str().unwrap(),
        "--free",
        "rho_d",
        "--subsample",
        "2",
        "--output",
        json.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0));
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    assert_eq!(v["per_band"].as_array().unwrap().len(), 5);
}
