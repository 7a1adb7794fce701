//! `polbrdf daytime` and `polbrdf sun` (docs/sun-position.md): the files written, the task's
//! numbers in the CSV, and the worked examples of the chapter.

use crate::common::{polbrdf, stderr};
use std::path::Path;

fn examples() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

/// The chapter's worked example of `polbrdf daytime` (two times, a coarse grid).
#[test]
fn daytime_writes_the_csv_and_the_figure() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let scene = examples().join("daytime-scene.toml");
    let o = polbrdf(&[
        "daytime",
        "--scene",
        scene.to_str().unwrap(),
        "--times",
        "07:00,13:00,23:00",
        "--grid-deg",
        "30,90",
        "--fixed-view-deg",
        "30,0",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let csv = std::fs::read_to_string(out.join("daytime.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines.len(), 4, "{csv}");
    assert!(lines[0].starts_with("date_time,local_time_h,sun_zenith_deg,sun_azimuth_deg,"));
    assert!(
        lines[1].starts_with("2026-06-21T07:00:00+02:00,7.0,"),
        "{csv}"
    );
    // 23:00 in June at 48° N: the sun is down, the clear sky not evaluated.
    assert!(lines[3].ends_with(",0.0,NaN,NaN,NaN,NaN,NaN,NaN"), "{csv}");
    for f in ["daytime.png", "daytime.svg"] {
        assert!(std::fs::metadata(out.join(f)).unwrap().len() > 1000, "{f}");
    }
    // A detection option without a sensor is a usage error.
    let o = polbrdf(&[
        "daytime",
        "--scene",
        scene.to_str().unwrap(),
        "--pfa",
        "1e-3",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--pfa is a detection option: give --sensor too"));
}
