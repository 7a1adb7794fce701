//! `polbrdf contrast`: files, best.json against the CSV and a brute-force search, maps that
//! show what the CSV holds, symmetry, and refusals.

use crate::common::{parse_csv, polbrdf, stderr};
use polbrdf_plot::{ColorScale, Colormap, PolarGrid};
use serde_json::Value;
use std::path::Path;

fn example(name: &str) -> String {
    format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"))
}

/// A CSV file as named columns of numbers.
pub struct Table {
    pub header: Vec<String>,
    pub rows: Vec<Vec<f64>>,
}

impl Table {
    pub fn read(path: &Path) -> Table {
        let (header, rows) = parse_csv(&std::fs::read_to_string(path).unwrap());
        let rows = rows
            .iter()
            .map(|r| r.iter().map(|v| v.parse::<f64>().unwrap()).collect())
            .collect();
        Table { header, rows }
    }
    pub fn col(&self, name: &str) -> Vec<f64> {
        let k = self.header.iter().position(|h| h == name).unwrap();
        self.rows.iter().map(|r| r[k]).collect()
    }
    /// The values of `name` as a polar grid (rows ordered zenith-major, as written).
    pub fn grid(&self, name: &str) -> PolarGrid {
        let theta = self.col("theta_r_deg");
        let phi = self.col("phi_r_deg");
        let n_phi = theta.iter().filter(|&&t| t == theta[0]).count();
        let thetas: Vec<f64> = theta.iter().step_by(n_phi).copied().collect();
        let phis: Vec<f64> = phi[..n_phi].to_vec();
        for (i, (t, p)) in theta.iter().zip(&phi).enumerate() {
            assert_eq!((*t, *p), (thetas[i / n_phi], phis[i % n_phi]), "row {i}");
        }
        PolarGrid::new(thetas, phis, self.col(name)).unwrap()
    }
}

pub fn decode(path: &Path) -> (u32, u32, Vec<u8>) {
    let bytes = std::fs::read(path).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "{}", path.display());
    let mut reader = png::Decoder::new(bytes.as_slice()).read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    buf.truncate(info.buffer_size());
    (info.width, info.height, buf)
}

/// Fraction of the sampled pixels inside the map's disk whose colour is what `scale` gives
/// the grid's value at the pixel centre (the rest lie under grid lines, labels and marks).
pub fn fraction_shown(png: &Path, grid: &PolarGrid, scale: &ColorScale) -> f64 {
    let (w, h, rgb) = decode(png);
    let disk = polbrdf_plot::polar::panel_disk((w, h));
    let (mut n, mut ok) = (0, 0);
    for py in (0..h).step_by(5) {
        for px in (0..w).step_by(5) {
            let (x, y) = (f64::from(px) + 0.5, f64::from(py) + 0.5);
            let Some((t, p)) = disk.direction(x, y) else {
                continue;
            };
            if t > 88.0 {
                continue; // the rim line
            }
            n += 1;
            let want = scale.color(grid.value_at(t, p, scale.period));
            let at = 3 * (py as usize * w as usize + px as usize);
            let got = &rgb[at..at + 3];
            if [want.0, want.1, want.2]
                .iter()
                .zip(got)
                .all(|(a, b)| (i32::from(*a) - i32::from(*b)).abs() <= 2)
            {
                ok += 1;
            }
        }
    }
    assert!(n > 5000, "{n} pixels sampled");
    f64::from(ok) / f64::from(n)
}

fn run_default(out: &Path) -> std::process::Output {
    polbrdf(&[
        "contrast",
        "--target",
        &example("olive-paint.toml"),
        "--background",
        &example("dry-soil.toml"),
        "--sun-zenith-deg",
        "50",
        "--sun-azimuth-deg",
        "20",
        "--out",
        out.to_str().unwrap(),
    ])
}

const FIGURES: [&str; 7] = [
    "dolp_target",
    "dolp_background",
    "delta_dolp",
    "intensity_ratio",
    "aolp_difference",
    "polarization_contrast",
    "overview",
];

fn angle_between(a: (f64, f64), b: (f64, f64)) -> f64 {
    let v = |(t, p): (f64, f64)| {
        let (t, p) = (t.to_radians(), p.to_radians());
        [t.sin() * p.cos(), t.sin() * p.sin(), t.cos()]
    };
    let (x, y) = (v(a), v(b));
    let dot: f64 = (0..3).map(|k| x[k] * y[k]).sum();
    dot.clamp(-1.0, 1.0).acos().to_degrees()
}

#[test]
fn writes_maps_csv_and_best_json_that_agree() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let o = run_default(&out);
    assert!(o.status.success(), "{}", stderr(&o));
    let summary = stderr(&o);
    assert!(summary.contains("best directions by |ΔDoLP|"), "{summary}");

    let mut names: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    let mut want: Vec<String> = FIGURES
        .iter()
        .flat_map(|f| [format!("{f}.png"), format!("{f}.svg")])
        .chain([
            "contrast.csv".into(),
            "best.json".into(),
            "_COMPLETE".into(),
        ])
        .collect();
    want.sort();
    assert_eq!(names, want, "exactly these files, no temporaries");
    for f in FIGURES {
        let (w, h, rgb) = decode(&out.join(format!("{f}.png")));
        assert!(w >= 600 && h >= 500);
        let colours: std::collections::BTreeSet<&[u8]> = rgb.chunks(3).collect();
        assert!(colours.len() > 100, "{f}.png has {} colours", colours.len());
        let svg = std::fs::read_to_string(out.join(format!("{f}.svg"))).unwrap();
        assert!(svg.starts_with("<svg") && svg.contains("data:image/png;base64,"));
    }

    let t = Table::read(&out.join("contrast.csv"));
    assert_eq!(
        t.header,
        [
            "theta_r_deg",
            "phi_r_deg",
            "dolp_target",
            "dolp_background",
            "delta_dolp",
            "intensity_target",
            "intensity_background",
            "intensity_ratio",
            "aolp_target_deg",
            "aolp_background_deg",
            "aolp_difference_deg",
            "polarization_contrast"
        ]
    );
    assert_eq!(t.rows.len(), 90 * 180, "default grid 1° × 2°");
    for r in &t.rows {
        assert_eq!(r[4], r[2] - r[3]);
        assert!((r[7] - r[5] / r[6]).abs() <= 1e-12 * r[7]);
        assert!(r[10] > -90.0 && r[10] <= 90.0);
    }

    // best.json: the refined best is at least as good as every grid node within the zenith
    // limit, and within one grid cell of the best node (or of its mirror image in the plane of
    // incidence, φ → 2·20° − φ).
    let doc: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("best.json")).unwrap()).unwrap();
    let best = &doc["best"];
    assert_eq!(best, &doc["top"][0]);
    let top = doc["top"].as_array().unwrap();
    assert_eq!(top.len(), 10);
    let f = |v: &Value, k: &str| v[k].as_f64().unwrap();
    let (theta, phi, delta) = (
        t.col("theta_r_deg"),
        t.col("phi_r_deg"),
        t.col("delta_dolp"),
    );
    let (k, node_best) = delta
        .iter()
        .enumerate()
        .filter(|(i, _)| theta[*i] <= 80.0)
        .map(|(i, d)| (i, d.abs()))
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap();
    assert!(f(best, "delta_dolp").abs() >= node_best);
    assert!(f(best, "delta_dolp").abs() < node_best + 0.01);
    let b = (f(best, "theta_r_deg"), f(best, "phi_r_deg"));
    let d = angle_between(b, (theta[k], phi[k])).min(angle_between(b, (theta[k], 40.0 - phi[k])));
    assert!(d <= 2.3, "best.json {b:?} is {d}° from the best grid node");
    assert_eq!(
        f(best, "delta_dolp"),
        f(best, "dolp_target") - f(best, "dolp_background")
    );
    for (i, a) in top.iter().enumerate() {
        for b in &top[..i] {
            let sep = angle_between(
                (f(a, "theta_r_deg"), f(a, "phi_r_deg")),
                (f(b, "theta_r_deg"), f(b, "phi_r_deg")),
            );
            // 10° apart on the grid; refinement moves each by less than one cell.
            assert!(sep > 10.0 - 2.0 * 2.3, "{sep}");
        }
        assert!(f(a, "delta_dolp").abs() <= f(best, "delta_dolp").abs());
    }
    assert_eq!(doc["ranking"]["by"], "delta-dolp");
    assert_eq!(doc["grid"]["directions"], 16200);
    assert_eq!(
        doc["illumination"]["stokes_normalized"],
        serde_json::json!([1.0, 0.0, 0.0, 0.0])
    );

    // The maps show what the CSV holds (and not some other column).
    let dolp = ColorScale::linear(Colormap::Viridis, 0.0, 1.0, "DoLP");
    let shown = fraction_shown(&out.join("dolp_target.png"), &t.grid("dolp_target"), &dolp);
    assert!(
        shown > 0.85,
        "dolp_target.png matches the CSV at {shown:.3} of the pixels"
    );
    let shown = fraction_shown(
        &out.join("dolp_background.png"),
        &t.grid("dolp_background"),
        &dolp,
    );
    assert!(shown > 0.85, "dolp_background.png: {shown:.3}");
    let wrong = fraction_shown(
        &out.join("dolp_target.png"),
        &t.grid("dolp_background"),
        &dolp,
    );
    assert!(
        wrong < 0.6,
        "the check can tell the columns apart: {wrong:.3}"
    );
    // The colour limits come from the ranked directions (θr ≤ --max-zenith-deg, default 80°).
    let lim = polbrdf_plot::nice_ceil(
        delta
            .iter()
            .zip(&theta)
            .filter(|(_, t)| **t <= 80.0)
            .fold(0.0f64, |m, (d, _)| m.max(d.abs())),
    );
    let diverging = ColorScale::linear(Colormap::Diverging, -lim, lim, "ΔDoLP");
    let shown = fraction_shown(
        &out.join("delta_dolp.png"),
        &t.grid("delta_dolp"),
        &diverging,
    );
    assert!(shown > 0.85, "delta_dolp.png: {shown:.3}");
}

#[test]
fn the_best_direction_agrees_with_a_finer_grid() {
    let dir = tempfile::tempdir().unwrap();
    let run = |grid: &str, out: &str| {
        let out = dir.path().join(out);
        let o = polbrdf(&[
            "contrast",
            "--target",
            &example("olive-paint.toml"),
            "--background",
            "paint",
            "--sun-zenith-deg",
            "35",
            "--grid-deg",
            grid,
            "--no-refine",
            "--top",
            "1",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let doc: Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("best.json")).unwrap()).unwrap();
        let b = &doc["best"];
        (
            b["theta_r_deg"].as_f64().unwrap(),
            b["phi_r_deg"].as_f64().unwrap(),
            b["delta_dolp"].as_f64().unwrap().abs(),
        )
    };
    let (t1, p1, d1) = run("2,4", "coarse");
    let (t2, p2, d2) = run("0.5", "fine");
    let d = angle_between((t1, p1), (t2, p2)).min(angle_between((t1, p1), (t2, -p2)));
    assert!(
        d <= 4.5,
        "2° × 4° grid best ({t1}, {p1}) vs 0.5° grid best ({t2}, {p2})"
    );
    assert!(d1 <= d2 + 1e-12 && d1 > d2 - 0.02, "{d1} vs {d2}");
}

#[test]
fn swapping_target_and_background_negates_delta_dolp() {
    let dir = tempfile::tempdir().unwrap();
    let run = |t: &str, b: &str, out: &str| {
        let out = dir.path().join(out);
        let o = polbrdf(&[
            "contrast",
            "--target",
            t,
            "--background",
            b,
            "--sun-zenith-deg",
            "40",
            "--sun-azimuth-deg",
            "-30",
            "--grid-deg",
            "3,6",
            "--stokes",
            "1,-0.3,0.2,0.1",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        Table::read(&out.join("contrast.csv"))
    };
    let olive = example("olive-paint.toml");
    let ab = run(&olive, "gold", "ab");
    let ba = run("gold", &olive, "ba");
    let (x, y) = (ab.col("delta_dolp"), ba.col("delta_dolp"));
    assert!(x.iter().any(|v| v.abs() > 0.1));
    for (a, b) in x.iter().zip(&y) {
        assert_eq!(*a, -b);
    }
    for (a, b) in ab
        .col("intensity_ratio")
        .iter()
        .zip(ba.col("intensity_ratio"))
    {
        assert!((a * b - 1.0).abs() < 1e-12);
    }
    assert_eq!(
        ab.col("polarization_contrast"),
        ba.col("polarization_contrast")
    );

    // Identical materials: no contrast anywhere.
    let same = run(&olive, &olive, "same");
    assert!(same.col("delta_dolp").iter().all(|&d| d == 0.0));
    assert!(same.col("intensity_ratio").iter().all(|&r| r == 1.0));
    assert!(same.col("aolp_difference_deg").iter().all(|&a| a == 0.0));
}

#[test]
fn bad_inputs_exit_3_bad_options_2_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let olive = example("olive-paint.toml");
    let bad_key = dir.path().join("bad.toml");
    std::fs::write(&bad_key, "n = 1.5\nsigma_deg = 10\ncolour = 3\n").unwrap();
    let bad_key = bad_key.to_str().unwrap().to_string();
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec!["--target", "no-such-paint"], "--target"),
        (vec!["--background", "no-such-soil"], "--background"),
        (vec!["--background", &bad_key], "colour"),
        (vec!["--sun-zenith-deg", "-5"], "--sun-zenith-deg"),
        (vec!["--sun-zenith-deg=-0.5"], "--sun-zenith-deg"),
        (vec!["--sun-zenith-deg", "90"], "--sun-zenith-deg"),
        (vec!["--sun-zenith-deg", "120"], "--sun-zenith-deg"),
        (vec!["--sun-zenith-deg", "NaN"], "--sun-zenith-deg"),
        (vec!["--grid-deg", "0"], "--grid-deg"),
        (vec!["--grid-deg", "-1"], "--grid-deg"),
        (vec!["--grid-deg", "0.01"], "--grid-deg"),
        (vec!["--stokes", "1,0.9,0.9,0"], "--stokes"),
        (vec!["--stokes", "1,0"], "--stokes"),
        (vec!["--top", "0"], "--top"),
        (vec!["--max-zenith-deg", "90"], "--max-zenith-deg"),
        (vec!["--min-separation-deg", "-1"], "--min-separation-deg"),
    ];
    for (extra, needle) in cases {
        let out = dir.path().join("out");
        let mut args = vec![
            "contrast",
            "--target",
            &olive,
            "--background",
            "paint",
            "--sun-zenith-deg",
            "30",
        ];
        // Later options override earlier ones (each is given once at most).
        for pair in extra.chunks(2) {
            if let Some(i) = args.iter().position(|a| *a == pair[0]) {
                args[i + 1] = pair[1];
            } else {
                args.extend_from_slice(pair);
            }
        }
        if extra[0].starts_with("--sun-zenith-deg=") {
            let i = args.iter().position(|a| *a == "--sun-zenith-deg").unwrap();
            args.drain(i..i + 2);
        }
        let out_s = out.to_str().unwrap().to_string();
        args.extend(["--out", &out_s]);
        let o = polbrdf(&args);
        // A bad material file is invalid input (3); a bad option value a usage error (2).
        let code = if ["--target", "--background", "colour"].contains(&needle) {
            3
        } else {
            2
        };
        assert_eq!(o.status.code(), Some(code), "{extra:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(needle), "{extra:?}: {}", stderr(&o));
        assert!(!out.exists(), "{extra:?}: output directory created");
    }
}

#[test]
fn a_malformed_grid_is_a_usage_error_and_writes_nothing() {
    // A value clap cannot parse is a usage error (exit 2), like every malformed option value.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    for grid in ["abc", "1,2,3", ""] {
        let o = polbrdf(&[
            "contrast",
            "--target",
            "paint",
            "--background",
            "paint",
            "--sun-zenith-deg",
            "30",
            "--grid-deg",
            grid,
            "--out",
            out.to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(2), "{grid:?}: {}", stderr(&o));
        assert!(
            stderr(&o).contains("--grid-deg"),
            "{grid:?}: {}",
            stderr(&o)
        );
        assert!(!out.exists(), "{grid:?}: output directory created");
    }
}

#[test]
fn an_unwritable_output_directory_is_an_io_error() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("a-file");
    std::fs::write(&file, "x").unwrap();
    let o = polbrdf(&[
        "contrast",
        "--target",
        "paint",
        "--background",
        "glass",
        "--sun-zenith-deg",
        "30",
        "--grid-deg",
        "5,10",
        "--out",
        file.join("sub").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(4), "{}", stderr(&o));
}

#[test]
fn ranking_by_polarization_contrast_marks_its_own_map() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("pc");
    let o = polbrdf(&[
        "contrast",
        "--target",
        "aluminium",
        "--background",
        &example("dry-soil.toml"),
        "--sun-zenith-deg",
        "40",
        "--grid-deg",
        "2,4",
        "--stokes",
        "1,0.5,0,0",
        "--rank-by",
        "polarization-contrast",
        "--top",
        "3",
        "--min-separation-deg",
        "20",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let doc: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("best.json")).unwrap()).unwrap();
    assert_eq!(doc["ranking"]["by"], "polarization-contrast");
    let top = doc["top"].as_array().unwrap();
    assert_eq!(top.len(), 3);
    let pc = |v: &Value| v["polarization_contrast"].as_f64().unwrap();
    assert!(pc(&top[0]) >= pc(&top[1]) && pc(&top[1]) >= pc(&top[2]));
    let t = Table::read(&out.join("contrast.csv"));
    let theta = t.col("theta_r_deg");
    let node_best = t
        .col("polarization_contrast")
        .iter()
        .zip(&theta)
        .filter(|(_, t)| **t <= 80.0)
        .map(|(v, _)| *v)
        .fold(0.0, f64::max);
    assert!(pc(&top[0]) >= node_best);
    // A metal against a dielectric under polarized light: the AoLPs differ (the metal's
    // retardance). Under unpolarized light both AoLPs are set by the geometry alone.
    assert!(t.col("aolp_difference_deg").iter().any(|d| d.abs() > 5.0));
}

/// Issue 33: `contrast --scene` and a large `eval` draw a progress bar only on a terminal: with
/// standard error a pipe (a log), it holds the notes alone — no bar, no carriage return.
#[test]
fn a_piped_standard_error_gets_no_progress_bar() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let o = polbrdf(&[
        "contrast",
        "--scene",
        &example("daylight-scene.toml"),
        "--grid-deg",
        "10,30",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    // A large eval: 500 000 rows of a .npy table (the row count known in advance).
    let cols = ["theta_i_deg", "phi_i_deg", "theta_r_deg", "phi_r_deg"];
    let rows: Vec<f64> = (0..500_000)
        .flat_map(|k| [30.0, 0.0, (k % 80) as f64, 180.0])
        .collect();
    let input = dir.path().join("big.npy");
    std::fs::write(&input, polbrdf_io::npy::npy_bytes(&cols, &rows).unwrap()).unwrap();
    let e = polbrdf(&[
        "eval",
        "--material",
        "paint",
        "--input",
        input.to_str().unwrap(),
        "--output",
        dir.path().join("out.npy").to_str().unwrap(),
    ]);
    assert!(e.status.success(), "{}", stderr(&e));
    // The bars' labels (the summary, on standard error too, counts viewing directions).
    for err in [stderr(&o), stderr(&e)] {
        assert!(
            !err.contains('\r')
                && !err.contains("eval: rows")
                && !err.contains("contrast: viewing directions"),
            "{err:?}"
        );
    }
}

#[test]
fn the_maps_mark_where_each_model_is_flagged_invalid() {
    // Paint reflects more than it receives seen near grazing (its emissivity leaves [0, 1]
    // from 88°); glass only at 89°, off this 2° grid. As `polbrdf map` marks paint's map, the target's DoLP map and the maps
    // comparing the two carry the ring of dots; the background's does not (issue 36 review).
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("inv");
    let o = polbrdf(&[
        "contrast",
        "--target",
        "paint",
        "--background",
        "glass",
        "--sun-zenith-deg",
        "40",
        "--grid-deg",
        "2,30",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let flagged = |name: &str| -> Vec<f64> {
        let m = polbrdf::preset(name).unwrap().build().unwrap();
        (0..45)
            .map(|k| 2.0 * f64::from(k))
            .filter(|t| {
                !polbrdf::analysis::emissivity(&m, t.to_radians())
                    .unwrap()
                    .is_valid()
            })
            .collect()
    };
    let (paint, glass) = (flagged("paint"), flagged("glass"));
    assert!(!paint.is_empty() && glass.is_empty(), "{paint:?} {glass:?}");
    let summary = stderr(&o);
    assert!(
        summary.contains(&format!(
            "target model flagged invalid (emissivity outside [0, 1]) at {} zenith(s) from θr = \
             {}° (marked on the maps)",
            paint.len(),
            paint[0]
        )),
        "{summary}"
    );
    assert!(!summary.contains("background model flagged"), "{summary}");
    let legend = "model invalid here";
    for (figure, marked) in [
        ("dolp_target", true),
        ("dolp_background", false),
        ("delta_dolp", true),
        ("intensity_ratio", true),
        ("aolp_difference", true),
        ("polarization_contrast", true),
        ("overview", true),
    ] {
        let svg = std::fs::read_to_string(out.join(format!("{figure}.svg"))).unwrap();
        assert_eq!(svg.contains(legend), marked, "{figure}.svg");
    }
}
