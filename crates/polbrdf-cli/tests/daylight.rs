//! `polbrdf radiance` in daylight scenes (`[sun]`, `[sky] model = "cie-clear"` or `"table"`)
//! against what the scene's terms must be: the sun's reflection is `E·cosθs·F(w_s, w_r)·s`
//! with F from `polbrdf eval` of the same geometry, a clear sky of zero irradiance adds
//! nothing, the model is isotropic (turning the sun and the views by one azimuth changes
//! nothing), and a sky table of one unpolarized radiance is the uniform sky. Few views: fast.

use crate::common::{parse_csv, polbrdf, stderr, write};
use std::path::Path;

const RADIANCE_COLUMNS: &str = "theta_r_deg,phi_r_deg,s0,s1,s2,s3,dolp,aolp_deg";

fn example(name: &str) -> String {
    format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"))
}

/// Runs the binary; asserts success and returns standard output.
fn run(args: &[&str]) -> String {
    let o = polbrdf(args);
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    String::from_utf8(o.stdout).unwrap()
}

/// The rows of a CSV of numbers, checking its header.
fn numbers(text: &str, header: &str) -> Vec<Vec<f64>> {
    assert_eq!(text.lines().next(), Some(header), "{text}");
    parse_csv(text)
        .1
        .iter()
        .map(|r| r.iter().map(|v| v.parse().unwrap()).collect())
        .collect()
}

/// `polbrdf radiance` of `material` in the scene `text` (written to `d/name`), its CSV text.
fn radiance(d: &Path, name: &str, text: &str, material: &str, views: &[&str]) -> String {
    let scene = write(d, name, text);
    let args = [
        &["radiance", "--material", material, "--scene", &scene][..],
        views,
    ]
    .concat();
    run(&args)
}

const SUN: &str = "wavelength_um = 0.55\n[sun]\nzenith_deg = 40\nirradiance = 1000\n";

#[test]
fn the_sun_alone_reflects_e_cos_theta_s_f_s() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let paint = example("olive-paint.toml");
    // The specular view and two others, for an unpolarized and a polarized sun.
    let views = [(40.0, 180.0), (20.0, 150.0), (65.0, 300.0)];
    let mut geo = String::from("theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg\n");
    for (t, p) in views {
        geo += &format!("40,0,{t},{p}\n");
    }
    let g = write(d, "g.csv", &geo);
    let eval = run(&["eval", "--material", &paint, "--input", &g]);
    let (header, rows) = parse_csv(&eval);
    let m = |row: &[String], ij: &str| -> f64 {
        let k = header.iter().position(|h| h == ij).unwrap();
        row[k].parse().unwrap()
    };
    let e_cos = 1000.0 * 40f64.to_radians().cos();
    for (stokes, s_in) in [
        ("", [1.0, 0.0, 0.0, 0.0]),
        // Normalized to s0 = 1: (1, 0.3, -0.4, 0.5).
        ("stokes = [2, 0.6, -0.8, 1.0]\n", [1.0, 0.3, -0.4, 0.5]),
    ] {
        for (k, (t, p)) in views.iter().enumerate() {
            let out = radiance(
                d,
                "sun.toml",
                &format!("{SUN}{stokes}"),
                &paint,
                &["--theta-deg", &t.to_string(), "--phi-deg", &p.to_string()],
            );
            let r = &numbers(&out, RADIANCE_COLUMNS)[0];
            assert_eq!((r[0], r[1]), (*t, *p));
            for i in 0..4 {
                let expected: f64 = (0..4)
                    .map(|j| e_cos * m(&rows[k], &format!("m{i}{j}")) * s_in[j])
                    .sum();
                let tol = 1e-12 * r[2].abs().max(1e-300);
                assert!(
                    (r[2 + i] - expected).abs() <= tol,
                    "view ({t}, {p}) {stokes:?}: s{i} = {} vs E·cosθs·(F·s)_{i} = {expected}",
                    r[2 + i]
                );
            }
            if k == 0 && stokes.is_empty() {
                // At the specular view: s0 = E·cos 40°·F00, F00 the BRDF `eval` prints.
                assert!(r[2] > 0.0);
                assert!((r[2] - e_cos * m(&rows[0], "brdf")).abs() <= 1e-12 * r[2]);
            }
        }
    }
}

const VIEWS: [&str; 4] = ["--theta-deg", "0,20,40,60,85", "--phi-deg", "0,90,180,270"];

#[test]
fn a_clear_sky_of_zero_irradiance_adds_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let paint = example("olive-paint.toml");
    let sun_only = radiance(d, "a.toml", SUN, &paint, &VIEWS);
    let with_sky = radiance(
        d,
        "b.toml",
        &format!("{SUN}[sky]\nmodel = \"cie-clear\"\nirradiance = 0\n"),
        &paint,
        &VIEWS,
    );
    assert_eq!(numbers(&sun_only, RADIANCE_COLUMNS).len(), 20);
    assert_eq!(sun_only, with_sky, "byte-identical");
    // A clear sky of some irradiance adds a positive radiance everywhere.
    let lit = radiance(
        d,
        "c.toml",
        &format!("{SUN}[sky]\nmodel = \"cie-clear\"\nirradiance = 100\n"),
        &paint,
        &VIEWS,
    );
    for (a, b) in numbers(&sun_only, RADIANCE_COLUMNS)
        .iter()
        .zip(&numbers(&lit, RADIANCE_COLUMNS))
    {
        assert!(b[2] > a[2], "{a:?} vs {b:?}");
    }
}

/// `VIEWS` with every azimuth turned by `by` degrees.
fn turned(by: f64) -> [String; 4] {
    let phis: Vec<String> = [0.0, 90.0, 180.0, 270.0]
        .iter()
        .map(|p| (p + by).to_string())
        .collect();
    [
        VIEWS[0].into(),
        VIEWS[1].into(),
        VIEWS[2].into(),
        phis.join(","),
    ]
}

#[test]
fn turning_the_sun_and_the_views_by_one_azimuth_changes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let paint = example("olive-paint.toml");
    // A polarized sun alone, and with the clear sky it sets.
    for sky in [
        "",
        "[sky]\nmodel = \"cie-clear\"\nirradiance = 100\ndop_max = 0.8\n",
    ] {
        let at = |sun_azimuth: f64, views: &[String]| {
            let v: Vec<&str> = views.iter().map(String::as_str).collect();
            let text = format!(
                "wavelength_um = 0.55\n[sun]\nzenith_deg = 40\nazimuth_deg = {sun_azimuth}\n\
                 irradiance = 1000\nstokes = [1, 0.3, 0.2, -0.1]\n{sky}"
            );
            numbers(&radiance(d, "s.toml", &text, &paint, &v), RADIANCE_COLUMNS)
        };
        let base = at(0.0, &turned(0.0));
        for by in [73.0, -200.0] {
            let rot = at(by, &turned(by));
            assert_eq!(base.len(), rot.len());
            for (a, b) in base.iter().zip(&rot) {
                assert!(a[2] > 0.0);
                for c in 2..6 {
                    assert!(
                        (a[c] - b[c]).abs() <= 1e-9 * a[2],
                        "{sky:?} turned by {by}°: {a:?} vs {b:?}"
                    );
                }
            }
        }
    }
}

#[test]
fn a_sky_table_of_one_unpolarized_radiance_is_the_uniform_sky() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // A coarse grid, rows from the horizon down to the zenith.
    let mut csv = String::from("theta_deg,phi_deg,s0,s1,s2,s3\n");
    for t in [90, 60, 30, 0] {
        for p in [0, 120, 240] {
            csv += &format!("{t},{p},5,0,0,0\n");
        }
    }
    write(d, "sky.csv", &csv);
    let head = "wavelength_um = 10\n[surface]\ntemperature_k = 280\n[sky]\n";
    let views = ["--theta-deg", "0,30,60,85", "--phi-deg", "0,45,200"];
    let u = radiance(
        d,
        "u.toml",
        &format!("{head}model = \"uniform\"\nradiance = 5\n"),
        "paint",
        &views,
    );
    let t = radiance(
        d,
        "t.toml",
        &format!("{head}model = \"table\"\nfile = \"sky.csv\"\n"),
        "paint",
        &views,
    );
    let (u, t) = (numbers(&u, RADIANCE_COLUMNS), numbers(&t, RADIANCE_COLUMNS));
    assert_eq!(u.len(), 12);
    for (a, b) in u.iter().zip(&t) {
        for c in 2..6 {
            // The table's quadrature reproduces Kirchhoff's exact L·(e0 − ε) to ~1e-11.
            assert!((a[c] - b[c]).abs() <= 1e-9 * a[2], "{a:?} vs {b:?}");
        }
    }
}

/// A radiance bounded by the work it implies (issue 35): 1000 × 1000 views (within the 10⁶
/// views of `--theta-deg × --phi-deg`) under a clear sky are 10⁶ sky integrals, about 20 minutes
/// on one core: refused before anything is computed, naming the options and the limit (exit 2).
/// The same grid's first 10 × 10 views are computed.
#[test]
fn a_radiance_above_its_work_budget_is_refused_before_computing() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let scene = write(
        d,
        "clear.toml",
        &format!("{SUN}[sky]\nmodel = \"cie-clear\"\nirradiance = 100\n"),
    );
    let grid = |n: usize, step: f64| {
        (0..n)
            .map(|k| format!("{}", k as f64 * step))
            .collect::<Vec<_>>()
            .join(",")
    };
    let (thetas, phis) = (grid(1000, 0.089), grid(1000, 0.36));
    let paint = example("olive-paint.toml");
    let args = |t: &str, p: &str| {
        [
            "radiance",
            "--material",
            &paint,
            "--scene",
            &scene,
            "--theta-deg",
            t,
            "--phi-deg",
            p,
        ]
        .map(String::from)
    };
    let big = args(&thetas, &phis);
    let o = polbrdf(&big.each_ref().map(String::as_str));
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(o.stdout.is_empty());
    let e = stderr(&o);
    assert!(
        e.contains("polbrdf: error: --theta-deg × --phi-deg (or --input): 1000000 view(s) × 1 spectral node(s) under an azimuth-dependent sky")
            && e.contains("imply 1.000e9 units of work, at most 1e8"),
        "{e}"
    );
    let small = args(&grid(10, 0.089), &grid(10, 0.36));
    let text = run(&small.each_ref().map(String::as_str));
    assert_eq!(numbers(&text, RADIANCE_COLUMNS).len(), 100);
}
