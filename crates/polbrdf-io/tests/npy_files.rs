//! `.npy` tables against numpy itself, when a Python with numpy is at hand (`POLBRDF_PYTHON`,
//! else `python3`): numpy reads what polbrdf writes, and polbrdf reads what numpy writes.

use polbrdf_io::npy::{npy_bytes, parse_npy, NpyWriter};
use std::path::Path;
use std::process::Command;

fn python() -> Option<String> {
    let py = std::env::var("POLBRDF_PYTHON").unwrap_or_else(|_| "python3".into());
    let ok = Command::new(&py)
        .args(["-c", "import numpy"])
        .output()
        .is_ok_and(|o| o.status.success());
    if ok {
        Some(py)
    } else {
        eprintln!("skipped: no Python with numpy ({py}); set POLBRDF_PYTHON");
        None
    }
}

#[test]
fn numpy_reads_what_polbrdf_writes_and_back() {
    let Some(py) = python() else { return };
    let dir = tempfile::tempdir().unwrap();
    let ours = dir.path().join("ours.npy");
    let cols = ["theta_i_deg", "it's", "θ", "m00"];
    let data: Vec<f64> = (0..400).map(|k| f64::from(k) * 0.1 - 3.0).collect();
    // Streamed with a patched header, as `eval` writes it.
    let f = std::fs::File::create(&ours).unwrap();
    let mut w = NpyWriter::new_patchable(std::io::BufWriter::new(f), &cols).unwrap();
    for chunk in data.chunks(12) {
        w.write_rows(chunk).unwrap();
    }
    w.finish_patched().unwrap();
    let theirs = dir.path().join("theirs.npy");
    let script = r#"
import sys, numpy as np
a = np.load(sys.argv[1])
assert a.dtype.names == ("theta_i_deg", "it's", "θ", "m00"), a.dtype
assert a.shape == (100,), a.shape
assert all(a.dtype[n] == np.dtype("<f8") for n in a.dtype.names)
flat = np.array([list(r) for r in a]).ravel()
assert np.array_equal(flat, np.arange(400) * 0.1 - 3.0), flat[:8]
b = np.zeros(3, dtype=[("x", ">f8"), ("y", "<f4")])
b["x"] = [1.5, -2.0, 1e300]; b["y"] = [0.25, 3.0, -1.0]
np.save(sys.argv[2], b)
"#;
    let out = Command::new(&py)
        .args(["-c", script])
        .arg(&ours)
        .arg(&theirs)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let t = parse_npy(&std::fs::read(&theirs).unwrap(), &theirs).unwrap();
    assert_eq!(t.columns, ["x", "y"]);
    assert_eq!(t.data, [1.5, 0.25, -2.0, 3.0, 1e300, -1.0]);
    // And a whole table in one call is the same bytes as the streamed one.
    let whole = npy_bytes(&cols, &data).unwrap();
    assert_eq!(whole, std::fs::read(&ours).unwrap());
    assert!(parse_npy(&whole, Path::new("w.npy")).is_ok());
}

/// Issue 35: repeated column names were found by a list search, quadratic in the fields
/// (50 000 fields took 8–10 s). A header of 45 000 fields (near the 1 MiB header limit) is
/// written and read back with every name, and a name repeated as the last field is refused by
/// the reader and the writer, named.
#[test]
fn a_header_of_45000_fields_is_read_and_a_repeat_among_them_named() {
    let names: Vec<String> = (0..45_000).map(|k| format!("c{k:05}")).collect();
    let data: Vec<f64> = (0..names.len()).map(|k| k as f64).collect();
    let bytes = npy_bytes(&names, &data).unwrap();
    let t = parse_npy(&bytes, Path::new("wide.npy")).unwrap();
    assert_eq!(t.columns, names);
    assert_eq!(t.data, data);
    // The last name made the first's: the same header length.
    let at = bytes.windows(8).position(|w| w == b"'c44999'").unwrap();
    let mut bad = bytes.clone();
    bad[at..at + 8].copy_from_slice(b"'c00000'");
    let e = parse_npy(&bad, Path::new("wide.npy"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("column `c00000` appears twice"), "{e}");
    let mut repeated = names.clone();
    repeated[44_999] = "c00000".into();
    let e = npy_bytes(&repeated, &data).unwrap_err().to_string();
    assert!(e.contains("column `c00000` appears twice"), "{e}");
}
