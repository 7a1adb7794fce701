//! `polbrdf albedo`: the table, the CSV, and the energy-conservation flag.

use crate::common::{parse_csv, polbrdf, stderr, write};

#[test]
fn the_default_table_covers_0_to_85_degrees_and_matches_the_library() {
    let o = polbrdf(&["albedo", "--material", "paint"]);
    assert!(o.status.success(), "{}", stderr(&o));
    // The table for a person on standard error; the CSV that --output writes on standard output.
    let text = stderr(&o);
    let (header, csv_rows) = parse_csv(&String::from_utf8(o.stdout).unwrap());
    assert_eq!(
        header,
        ["theta_i_deg", "albedo", "surface", "volume", "exceeds_one"]
    );
    assert_eq!(csv_rows.len(), 18);
    let rows: Vec<Vec<f64>> = text
        .lines()
        .filter_map(|l| {
            let v: Vec<f64> = l.split_whitespace().map_while(|w| w.parse().ok()).collect();
            (v.len() == 4).then_some(v)
        })
        .collect();
    assert_eq!(rows.len(), 18, "{text}");
    let paint = polbrdf::preset("paint").unwrap().build().unwrap();
    for (k, r) in rows.iter().enumerate() {
        assert_eq!(r[0], 5.0 * k as f64);
        let a = polbrdf::directional_hemispherical(&paint, r[0].to_radians());
        assert!((r[1] - a.total()).abs() < 1e-6 && (r[2] - a.surface).abs() < 1e-6);
        assert!((r[1] - r[2] - r[3]).abs() < 2e-6);
        let c = &csv_rows[k];
        assert_eq!(c[0].parse::<f64>().unwrap(), r[0]);
        assert_eq!(c[1].parse::<f64>().unwrap(), a.total());
        assert_eq!(c[2].parse::<f64>().unwrap(), a.surface);
        assert_eq!(c[4], "false");
    }
    assert!(!text.contains("EXCEEDS"), "{text}");
    assert!(text.contains("at or below 1"), "{text}");
}

#[test]
fn an_albedo_above_one_is_flagged_with_its_excess() {
    let dir = tempfile::tempdir().unwrap();
    // ρ_D = 0.5 sr⁻¹ alone reflects π·0.5 ≈ 1.57 of the incident light.
    let m = write(
        dir.path(),
        "bright.toml",
        "n = 1.5\nsigma_deg = 20\nrho_d = 0.5\n",
    );
    let csv = dir.path().join("albedo.csv");
    let o = polbrdf(&[
        "albedo",
        "--material",
        &m,
        "--theta-i-deg",
        "0,30",
        "--theta-i-deg",
        "60",
        "--output",
        csv.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(o.stdout.is_empty(), "the CSV goes to --output only");
    let text = stderr(&o);
    assert_eq!(text.matches("EXCEEDS 1 by 0.6").count(), 3, "{text}");
    assert!(
        text.contains("WARNING") && text.contains("3 of 3"),
        "{text}"
    );
    let (header, rows) = parse_csv(&std::fs::read_to_string(&csv).unwrap());
    assert_eq!(
        header,
        ["theta_i_deg", "albedo", "surface", "volume", "exceeds_one"]
    );
    assert_eq!(rows.len(), 3);
    for r in &rows {
        assert_eq!(r[4], "true");
        let volume: f64 = r[3].parse().unwrap();
        assert!((volume - std::f64::consts::PI * 0.5).abs() < 1e-9);
    }
}

#[test]
fn bad_incidence_angles_exit_2_and_materials_3() {
    for (args, code) in [
        (vec!["--material", "paint", "--theta-i-deg", "90"], 2),
        (vec!["--material", "paint", "--theta-i-deg=-1"], 2),
        (vec!["--material", "paint", "--theta-i-deg", "NaN"], 2),
        (vec!["--material", "no-such-material"], 3),
    ] {
        let mut a = vec!["albedo"];
        a.extend(&args);
        let o = polbrdf(&a);
        assert_eq!(o.status.code(), Some(code), "{args:?}: {}", stderr(&o));
    }
}
