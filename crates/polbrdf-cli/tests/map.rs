//! `polbrdf map`: one material over the viewing hemisphere.

use crate::common::{polbrdf, stderr};
use crate::contrast::{decode, fraction_shown, Table};
use polbrdf::{Geometry, Stokes};
use polbrdf_plot::{ColorScale, Colormap};

#[test]
fn map_writes_csv_and_maps_of_the_model() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("m");
    let o = polbrdf(&[
        "map",
        "--material",
        "paint",
        "--sun-zenith-deg",
        "45",
        "--sun-azimuth-deg",
        "30",
        "--grid-deg",
        "1.5,3",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let mut names: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "_COMPLETE",
            "aolp.png",
            "aolp.svg",
            "brdf.png",
            "brdf.svg",
            "dolp.png",
            "dolp.svg",
            "map.csv",
            "overview.png",
            "overview.svg"
        ]
    );
    // The set's completion marker lists the set.
    let marker = std::fs::read_to_string(out.join("_COMPLETE")).unwrap();
    assert_eq!(marker.lines().count(), 9);
    assert!(marker.lines().any(|l| l == "map.csv"));
    let t = Table::read(&out.join("map.csv"));
    assert_eq!(
        t.header,
        [
            "theta_r_deg",
            "phi_r_deg",
            "brdf",
            "s0",
            "s1",
            "s2",
            "s3",
            "dolp",
            "aolp_deg"
        ]
    );
    assert_eq!(t.rows.len(), 60 * 120);
    let paint = polbrdf::preset("paint").unwrap().build().unwrap();
    for r in t.rows.iter().step_by(97) {
        let g = Geometry::from_degrees(45.0, 30.0, r[0], r[1]).unwrap();
        let e = paint.evaluate(&g);
        assert!((r[2] - e.brdf()).abs() <= 1e-12 * e.brdf(), "{r:?}");
        assert_eq!(r[2], r[3], "unpolarized input: S0 is the BRDF");
        assert!((r[7] - e.dolp()).abs() < 1e-12, "{r:?}");
        let s = e.reflect(&Stokes::unpolarized());
        assert!((r[8] - s.aolp().to_degrees()).abs() < 1e-9);
    }
    let shown = fraction_shown(
        &out.join("dolp.png"),
        &t.grid("dolp"),
        &ColorScale::linear(Colormap::Viridis, 0.0, 1.0, "DoLP"),
    );
    assert!(
        shown > 0.85,
        "dolp.png shows map.csv at {shown:.3} of the pixels"
    );
    let (w, h, _) = decode(&out.join("overview.png"));
    assert_eq!((w, h), (3 * 620, 580));
    // Where the model is flagged invalid (its emissivity outside [0, 1]: paint reflects more
    // than it receives seen near grazing), the maps mark it and the summary says so (issue 36).
    let flagged: Vec<f64> = (0..60)
        .map(|k| 1.5 * f64::from(k))
        .filter(|t| {
            !polbrdf::analysis::emissivity(&paint, t.to_radians())
                .unwrap()
                .is_valid()
        })
        .collect();
    assert!(!flagged.is_empty() && flagged[0] > 80.0, "{flagged:?}");
    let summary = stderr(&o);
    assert!(
        summary.contains(&format!(
            "model flagged invalid (emissivity outside [0, 1]) at {} zenith(s) from θr = {}°",
            flagged.len(),
            flagged[0]
        )),
        "{summary}"
    );
    for panel in ["brdf.svg", "dolp.svg", "aolp.svg"] {
        let svg = std::fs::read_to_string(out.join(panel)).unwrap();
        assert!(
            svg.contains("model invalid here (emissivity outside [0, 1])"),
            "{panel} has no legend entry for the invalid region"
        );
    }
}

#[test]
fn map_refuses_a_bad_material_with_exit_3_and_a_bad_angle_with_2() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("m");
    for (args, code) in [
        (
            vec!["--material", "unobtainium", "--sun-zenith-deg", "30"],
            3,
        ),
        (vec!["--material", "paint", "--sun-zenith-deg", "-10"], 2),
        (vec!["--material", "paint", "--sun-zenith-deg", "90"], 2),
    ] {
        let mut a = vec!["map"];
        a.extend(&args);
        a.extend(["--out", out.to_str().unwrap()]);
        let o = polbrdf(&a);
        assert_eq!(o.status.code(), Some(code), "{args:?}: {}", stderr(&o));
        assert!(!out.exists());
    }
    // A malformed option value is a usage error (exit 2), and writes nothing either.
    let o = polbrdf(&[
        "map",
        "--material",
        "paint",
        "--sun-zenith-deg",
        "30",
        "--grid-deg",
        "x",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--grid-deg"), "{}", stderr(&o));
    assert!(!out.exists());
}
