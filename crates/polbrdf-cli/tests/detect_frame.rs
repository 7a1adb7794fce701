//! `polbrdf detect --frame`: the simulated camera frame's files, seeded; refusals.

use crate::common::{polbrdf, stderr};
use std::path::Path;

fn example(name: &str) -> String {
    format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"))
}

fn frame(out: &Path, sensor: &str, seed: &str) -> std::process::Output {
    polbrdf(&[
        "detect",
        "--scene",
        &example("detect-daylight-scene.toml"),
        "--sensor",
        &example(sensor),
        "--theta-deg",
        "45",
        "--phi-deg",
        "0",
        "--ranges-m",
        "400",
        "--frame",
        "--seed",
        seed,
        "--out",
        out.to_str().unwrap(),
    ])
}

const NPY: [&str; 5] = [
    "frame_raw_counts.npy",
    "frame_saturated.npy",
    "frame_s0.npy",
    "frame_dolp.npy",
    "frame_aolp_deg.npy",
];

#[test]
fn frame_files_are_written_and_seeded() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b, c) = (
        dir.path().join("a"),
        dir.path().join("b"),
        dir.path().join("c"),
    );
    let o = frame(&a, "sensors/sony-imx250mzr-dofp.toml", "1");
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stderr(&o);
    assert!(
        text.contains("frame: θr = 45°, φr = 0°, 400 m, seed 1"),
        "{text}"
    );
    let png = std::fs::read(a.join("frame.png")).unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    assert!(a.join("frame.svg").exists());
    let raw = std::fs::read(a.join("frame_raw_counts.npy")).unwrap();
    let header = String::from_utf8_lossy(&raw[..128]).to_string();
    assert!(header.contains("'descr': '<f8', 'fortran_order': False, 'shape': (128, 128)"));
    // The same seed gives the same files; another seed another frame.
    assert!(frame(&b, "sensors/sony-imx250mzr-dofp.toml", "1")
        .status
        .success());
    assert!(frame(&c, "sensors/sony-imx250mzr-dofp.toml", "2")
        .status
        .success());
    for name in NPY {
        let x = std::fs::read(a.join(name)).unwrap();
        assert_eq!(x, std::fs::read(b.join(name)).unwrap(), "{name}");
        if name != "frame_saturated.npy" {
            assert_ne!(x, std::fs::read(c.join(name)).unwrap(), "{name}");
        }
    }
}

#[test]
fn frame_refusals() {
    let dir = tempfile::tempdir().unwrap();
    // A thermal (NEL/NETD) sensor has no electrons to draw: an invalid value, exit 3, nothing
    // written.
    let out = dir.path().join("lwir");
    let o = frame(&out, "sensors/lwir-microbolometer-dofp.toml", "1");
    assert_eq!(o.status.code(), Some(3), "{}", stderr(&o));
    assert!(stderr(&o).contains("--frame: a simulated frame needs a photon-counting camera"));
    assert!(!out.exists());
    // --seed needs --frame: a usage error.
    let o = polbrdf(&[
        "detect",
        "--scene",
        &example("detect-daylight-scene.toml"),
        "--sensor",
        &example("sensors/sony-imx250mzr-dofp.toml"),
        "--seed",
        "1",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--frame"));
}
