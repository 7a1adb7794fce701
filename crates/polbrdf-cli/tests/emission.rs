//! `polbrdf emission`, `polbrdf radiance` and `polbrdf contrast --scene` against physics
//! computed here, independently of the library: the Fresnel equations, Planck's law from the
//! CODATA constants, Kirchhoff's law in an isothermal enclosure, the atmosphere's linear map and
//! the polarization null (docs/model.md §16–§17). Coarse grids and few angles: fast.

use crate::common::{parse_csv, polbrdf, stderr, write};
use crate::contrast::Table;
use serde_json::Value;
use std::path::Path;

// CODATA 2018 (exact SI values).
const H: f64 = 6.626_070_15e-34; // J·s
const C: f64 = 299_792_458.0; // m/s
const K_B: f64 = 1.380_649e-23; // J/K

/// Planck's spectral radiance B_λ(λ, T) in W·m⁻²·sr⁻¹·µm⁻¹, λ in µm.
fn planck(lambda_um: f64, t: f64) -> f64 {
    let l = lambda_um * 1e-6;
    2.0 * H * C * C / l.powi(5) / (H * C / (l * K_B * t)).exp_m1() * 1e-6
}

/// The temperature whose Planck radiance at `lambda_um` is `radiance` (Planck inverted).
fn brightness_temperature(lambda_um: f64, radiance: f64) -> f64 {
    let l = lambda_um * 1e-6;
    let c1 = 2.0 * H * C * C / l.powi(5) * 1e-6;
    H * C / (l * K_B) / (c1 / radiance).ln_1p()
}

/// Composite Simpson's rule of `f` over [a, b] with `n` (even) intervals.
fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
    let h = (b - a) / n as f64;
    let inner: f64 = (1..n)
        .map(|i| f(a + h * i as f64) * if i % 2 == 1 { 4.0 } else { 2.0 })
        .sum();
    (f(a) + f(b) + inner) * h / 3.0
}

/// Fresnel power reflectances (R_s, R_p) of a dielectric of real index `n` at incidence θ (rad).
fn fresnel(n: f64, theta: f64) -> (f64, f64) {
    let ci = theta.cos();
    let st = theta.sin() / n;
    let ct = (1.0 - st * st).sqrt();
    let rs = (ci - n * ct) / (ci + n * ct);
    let rp = (n * ci - ct) / (n * ci + ct);
    (rs * rs, rp * rp)
}

/// Runs the binary; asserts success and returns standard output.
fn run(args: &[&str]) -> String {
    let o = polbrdf(args);
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    String::from_utf8(o.stdout).unwrap()
}

/// A CSV text of numbers (with `true`/`false` as 1/0) as a table.
fn table(text: &str) -> Table {
    let (header, rows) = parse_csv(text);
    let rows = rows
        .iter()
        .map(|r| {
            r.iter()
                .map(|v| match v.as_str() {
                    "true" => 1.0,
                    "false" => 0.0,
                    _ => v.parse().unwrap_or_else(|_| panic!("{v:?} in {text}")),
                })
                .collect()
        })
        .collect();
    Table { header, rows }
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

const EMISSION_COLUMNS: &str =
    "theta_deg,eps0,eps1,eps2,eps3,eps_s,eps_p,dolp,reciprocity_residual,valid";
const RADIANCE_COLUMNS: &str = "theta_r_deg,phi_r_deg,s0,s1,s2,s3,dolp,aolp_deg";

/// A smooth dielectric, no volume term, no shadowing: the Fresnel limit.
const SMOOTH: &str = "n = 1.5\nsigma_deg = 0.05\nshadowing = false\n";

// ---------------------------------------------------------------------------------------------
// emission

#[test]
fn emission_table_has_its_columns_and_90_default_rows_that_agree() {
    let text = run(&["emission", "--material", "paint"]);
    assert_eq!(text.lines().next(), Some(EMISSION_COLUMNS));
    let t = table(&text);
    assert_eq!(t.rows.len(), 90);
    let theta = t.col("theta_deg");
    assert!(theta.iter().enumerate().all(|(k, v)| *v == k as f64));
    let (e0, e1, e2, e3) = (t.col("eps0"), t.col("eps1"), t.col("eps2"), t.col("eps3"));
    let (es, ep, dolp) = (t.col("eps_s"), t.col("eps_p"), t.col("dolp"));
    let valid = t.col("valid");
    for k in 0..90 {
        // Mirror symmetry of an isotropic surface: no ε2, ε3; emission is p-polarized.
        assert_eq!((e2[k], e3[k]), (0.0, 0.0), "θ = {k}");
        assert!(e1[k] <= 1e-12, "θ = {k}: ε1 = {}", e1[k]);
        assert!(close(es[k], e0[k] + e1[k], 1e-12) && close(ep[k], e0[k] - e1[k], 1e-12));
        if e0[k] > 0.0 {
            assert!(close(
                dolp[k],
                (ep[k] - es[k]).abs() / (ep[k] + es[k]),
                1e-12
            ));
        }
        // The standard form is reciprocal node by node: both routes agree to rounding.
        assert!(t.col("reciprocity_residual")[k] < 1e-12);
        // `valid` says whether both emissivities lie in [0, 1] (to the quadrature's 1e-6).
        let inside = |e: f64| (-1e-6..=1.0 + 1e-6).contains(&e);
        assert_eq!(valid[k] == 1.0, inside(es[k]) && inside(ep[k]), "θ = {k}");
    }
    // The paper's paint reflects more than it receives only at grazing view (its albedo
    // exceeds 1 at 89°: `polbrdf albedo`), never below 85°.
    assert!(valid[..=85].iter().all(|v| *v == 1.0));
    assert_eq!(valid[89], 0.0);
    // The emission DoLP grows toward the horizon.
    assert!(dolp[0] < 1e-9 && dolp[30] < dolp[60] && dolp[60] < dolp[85]);
}

#[test]
fn smooth_dielectric_emissivities_are_one_minus_fresnel() {
    let dir = tempfile::tempdir().unwrap();
    let m = write(dir.path(), "smooth.toml", SMOOTH);
    let brewster = 1.5f64.atan().to_degrees().to_string();
    let angles = format!("0,20,40,{brewster},60,75,85");
    let t = table(&run(&[
        "emission",
        "--material",
        &m,
        "--theta-deg",
        &angles,
    ]));
    assert_eq!(t.rows.len(), 7);
    for (k, deg) in t.col("theta_deg").iter().enumerate() {
        let (rs, rp) = fresnel(1.5, deg.to_radians());
        let tol = if *deg <= 60.0 { 1e-6 } else { 1e-4 };
        let (es, ep) = (t.col("eps_s")[k], t.col("eps_p")[k]);
        assert!(
            close(es, 1.0 - rs, tol),
            "θ = {deg}: ε_s {es} vs {}",
            1.0 - rs
        );
        assert!(
            close(ep, 1.0 - rp, tol),
            "θ = {deg}: ε_p {ep} vs {}",
            1.0 - rp
        );
        let want = (rs - rp).abs() / (2.0 - rs - rp);
        assert!(close(t.col("dolp")[k], want, tol), "θ = {deg}: DoLP");
        assert_eq!((t.col("eps2")[k], t.col("eps3")[k]), (0.0, 0.0));
    }
    // At Brewster's angle the p-polarized emissivity is 1.
    assert!(close(t.col("eps_p")[3], 1.0, 1e-6));
}

#[test]
fn emission_output_file_is_written_atomically() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("emission.csv");
    let args = ["emission", "--material", "glass", "--theta-deg", "10,50"];
    let to_stdout = run(&args);
    let o = polbrdf(&[&args[..], &["--output", out.to_str().unwrap()]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(o.stdout.is_empty(), "stdout with --output");
    assert_eq!(std::fs::read_to_string(&out).unwrap(), to_stdout);
    let names: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    assert_eq!(names, ["emission.csv"], "temporary files left");
}

#[test]
fn emission_over_a_band_is_the_response_and_planck_weighted_mean() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // n(λ) linear from 1.2 at 2 µm to 3.0 at 20 µm, k = 0; smooth: ε(0°) = 1 − ((n−1)/(n+1))².
    write(
        d,
        "lin.yml",
        "DATA:\n  - type: tabulated n\n    data: |\n        2 1.2\n        20 3.0\n",
    );
    let m = write(
        d,
        "sp.toml",
        "index = \"lin.yml\"\nsigma_deg = 0.05\nshadowing = false\n",
    );
    let band = write(d, "wide.csv", "wavelength_um,response\n2,1\n20,1\n");
    let eps = |l: f64| {
        let n = 1.2 + (l - 2.0) / 18.0 * 1.8;
        1.0 - ((n - 1.0) / (n + 1.0)).powi(2)
    };
    let mut got = Vec::new();
    for t in [None, Some(200.0), Some(3000.0)] {
        let mut args = vec![
            "emission",
            "--material",
            &m,
            "--band",
            &band,
            "--theta-deg",
            "0",
        ];
        let ts = t.map(|t: f64| t.to_string());
        if let Some(ts) = &ts {
            args.extend(["--temperature-k", ts.as_str()]);
        }
        let e0 = table(&run(&args)).col("eps0")[0];
        let w = |l: f64| t.map_or(1.0, |t| planck(l, t));
        let want = simpson(|l| w(l) * eps(l), 2.0, 20.0, 4000) / simpson(w, 2.0, 20.0, 4000);
        assert!(close(e0, want, 1e-6), "T = {t:?}: ε0 {e0} vs {want}");
        got.push(e0);
    }
    // A cold surface emits at long wavelengths (high n, low ε), a hot one at short ones.
    assert!(got[1] < got[0] && got[0] < got[2], "{got:?}");

    // A constant index: the band changes nothing, with or without a temperature.
    let single = run(&["emission", "--material", "paint", "--theta-deg", "0,45,80"]);
    for extra in [&[][..], &["--temperature-k", "300"][..]] {
        let args = [
            &[
                "emission",
                "--material",
                "paint",
                "--theta-deg",
                "0,45,80",
                "--band",
                &band,
            ][..],
            extra,
        ]
        .concat();
        let b = table(&run(&args));
        let s = table(&single);
        for c in ["eps0", "eps1", "eps_s", "eps_p", "dolp"] {
            for (x, y) in b.col(c).iter().zip(s.col(c)) {
                assert!(close(*x, y, 1e-12), "{extra:?} {c}: {x} vs {y}");
            }
        }
    }
}

#[test]
fn emission_temperature_requires_a_band() {
    let o = polbrdf(&["emission", "--material", "paint", "--temperature-k", "300"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--band"), "{}", stderr(&o));
    assert!(o.stdout.is_empty());
}

// ---------------------------------------------------------------------------------------------
// radiance

/// Writes `scene.toml` (and nothing else) into `d` and returns its path.
fn scene(d: &Path, text: &str) -> String {
    write(d, "scene.toml", text)
}

fn radiance(material: &str, scene: &str, views: &[&str]) -> Table {
    let args = [
        &["radiance", "--material", material, "--scene", scene][..],
        views,
    ]
    .concat();
    let text = run(&args);
    assert_eq!(text.lines().next(), Some(RADIANCE_COLUMNS));
    table(&text)
}

const VIEWS: [&str; 4] = ["--theta-deg", "0,30,60,85", "--phi-deg", "0,45,200"];

#[test]
fn an_isothermal_enclosure_is_a_blackbody_at_every_view() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let smooth = write(d, "smooth.toml", SMOOTH);
    for (lambda, t) in [(10.0, 300.0), (4.0, 500.0)] {
        let s = scene(
            d,
            &format!(
                "wavelength_um = {lambda}\n[surface]\ntemperature_k = {t}\n\
                 [sky]\nmodel = \"thermal\"\ntemperature_k = {t}\n"
            ),
        );
        let b = planck(lambda, t);
        for m in ["paint", "iron", smooth.as_str()] {
            let r = radiance(m, &s, &VIEWS);
            assert_eq!(r.rows.len(), 12);
            for (k, s0) in r.col("s0").iter().enumerate() {
                assert!(close(*s0, b, 1e-6 * b), "{m} λ {lambda}: s0 {s0} vs B {b}");
                for c in ["s1", "s2", "s3"] {
                    assert!(r.col(c)[k].abs() <= 1e-6 * b, "{m}: {c} = {}", r.col(c)[k]);
                }
                assert!(r.col("dolp")[k] <= 1e-6);
            }
        }
    }
}

#[test]
fn without_a_sky_the_surface_emits_planck_times_its_emissivity() {
    let dir = tempfile::tempdir().unwrap();
    let s = scene(
        dir.path(),
        "wavelength_um = 10\n[surface]\ntemperature_k = 300\n",
    );
    let b = planck(10.0, 300.0);
    let e = table(&run(&[
        "emission",
        "--material",
        "paint",
        "--theta-deg",
        "0,30,60,85",
    ]));
    let r = radiance("paint", &s, &VIEWS);
    for (k, row) in r.rows.iter().enumerate() {
        let j = k / 3; // three azimuths per zenith
        assert_eq!(row[0], e.col("theta_deg")[j]);
        // 1e-8: the library's Planck constants are CODATA's rounded to 10 digits.
        assert!(close(row[2], b * e.col("eps0")[j], 1e-8 * b), "row {k}");
        assert!(close(row[3], b * e.col("eps1")[j], 1e-8 * b), "row {k}");
        assert_eq!((row[4], row[5]), (0.0, 0.0));
        if row[0] > 0.0 {
            assert_eq!(row[7], 90.0, "thermal emission is p-polarized");
        }
    }
}

#[test]
fn a_uniform_sky_adds_its_reflection_by_kirchhoff() {
    // S = L·e0 + (B(T) − L)·ε: what is not emitted is reflected.
    let dir = tempfile::tempdir().unwrap();
    let s = scene(
        dir.path(),
        "wavelength_um = 10\n[surface]\ntemperature_k = 290\n[sky]\nmodel = \"uniform\"\nradiance = 3.5\n",
    );
    let (b, l) = (planck(10.0, 290.0), 3.5);
    let e = table(&run(&[
        "emission",
        "--material",
        "paint",
        "--theta-deg",
        "0,30,60,85",
    ]));
    let r = radiance("paint", &s, &VIEWS);
    for (k, row) in r.rows.iter().enumerate() {
        let j = k / 3;
        assert!(
            close(row[2], l + (b - l) * e.col("eps0")[j], 1e-8 * b),
            "row {k}"
        );
        assert!(
            close(row[3], (b - l) * e.col("eps1")[j], 1e-8 * b),
            "row {k}"
        );
    }
}

#[test]
fn a_profile_sky_of_constant_radiance_is_the_uniform_sky() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write(d, "flat.csv", "zenith_deg,radiance\n0,5\n90,5\n");
    let head = "wavelength_um = 10\n[surface]\ntemperature_k = 280\n[sky]\n";
    let u = radiance(
        "paint",
        &scene(d, &format!("{head}model = \"uniform\"\nradiance = 5\n")),
        &VIEWS,
    );
    let p = radiance(
        "paint",
        &scene(
            d,
            &format!("{head}model = \"profile\"\nfile = \"flat.csv\"\n"),
        ),
        &VIEWS,
    );
    for (a, b) in u.rows.iter().zip(&p.rows) {
        for c in 2..6 {
            assert!(close(a[c], b[c], 1e-7 * a[2]), "{a:?} vs {b:?}");
        }
    }
}

#[test]
fn the_atmosphere_maps_s_to_tau_s_plus_unpolarized_path_radiance() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let head = "wavelength_um = 10\n[surface]\ntemperature_k = 300\n[sky]\nmodel = \"thermal\"\ntemperature_k = 250\n";
    let bare = radiance("paint", &scene(d, head), &VIEWS);
    let (tau, path) = (0.8, 1.5);
    let seen = radiance(
        "paint",
        &scene(
            d,
            &format!("{head}[atmosphere]\ntransmittance = {tau}\npath_radiance = {path}\n"),
        ),
        &VIEWS,
    );
    for (a, b) in bare.rows.iter().zip(&seen.rows) {
        assert_eq!((a[0], a[1]), (b[0], b[1]));
        assert!(close(b[2], tau * a[2] + path, 1e-12 * b[2]));
        for c in 3..6 {
            assert!(close(b[c], tau * a[c], 1e-12 * b[2]));
        }
        if a[6] > 1e-9 {
            assert!(close(b[7], a[7], 1e-9), "the AoLP is unchanged");
        }
    }
}

#[test]
fn the_polarization_flips_when_the_sky_is_brighter_than_the_surface() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let views = ["--theta-deg", "20,40,60,80", "--phi-deg", "0,120"];
    let sky = |t: f64| {
        format!(
            "wavelength_um = 10\n[surface]\ntemperature_k = 300\n[sky]\nmodel = \"thermal\"\ntemperature_k = {t}\n"
        )
    };
    let cold = radiance("paint", &scene(d, &sky(250.0)), &views);
    let hot = radiance("paint", &scene(d, &sky(350.0)), &views);
    for (c, h) in cold.rows.iter().zip(&hot.rows) {
        assert!(
            c[3] < 0.0 && h[3] > 0.0,
            "s1 {} (cold sky), {} (hot sky)",
            c[3],
            h[3]
        );
        assert_eq!((c[7], h[7]), (90.0, 0.0), "AoLP turns by 90°");
    }
}

#[test]
fn at_the_null_temperature_a_uniform_sky_leaves_no_polarization() {
    let dir = tempfile::tempdir().unwrap();
    let l = 6.0;
    let t = brightness_temperature(10.0, l);
    let s = scene(
        dir.path(),
        &format!(
            "wavelength_um = 10\n[surface]\ntemperature_k = {t}\n[sky]\nmodel = \"uniform\"\nradiance = {l}\n"
        ),
    );
    for m in ["paint", "iron"] {
        let r = radiance(m, &s, &VIEWS);
        for row in &r.rows {
            assert!(close(row[2], l, 1e-7 * l), "{m}: s0 {} vs L {l}", row[2]);
            assert!(row[6] < 1e-7, "{m}: DoLP {} at {:?}", row[6], &row[..2]);
        }
    }
}

#[test]
fn a_views_file_gives_the_rows_of_the_equivalent_options() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let s = scene(
        d,
        "wavelength_um = 10\n[surface]\ntemperature_k = 300\n[sky]\nmodel = \"thermal\"\ntemperature_k = 260\n",
    );
    // Columns in another order, an extra column, CRLF line ends.
    let mut csv = String::from("label,phi_r_deg,theta_r_deg\r\n");
    for t in ["0", "35", "70"] {
        for p in ["-30", "90"] {
            csv.push_str(&format!("x,{p},{t}\r\n"));
        }
    }
    let views = write(d, "views.csv", &csv);
    let from_file = run(&[
        "radiance",
        "--material",
        "paint",
        "--scene",
        &s,
        "--input",
        &views,
    ]);
    let from_options = run(&[
        "radiance",
        "--material",
        "paint",
        "--scene",
        &s,
        "--theta-deg",
        "0,35,70",
        "--phi-deg",
        "-30,90",
    ]);
    assert_eq!(from_file, from_options);
    assert_eq!(from_file.lines().count(), 7);
}

#[test]
fn band_radiance_integrates_planck_over_the_response() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // A triangular response 8–10–12 µm: ∫R dλ = 2 µm.
    write(d, "lwir.csv", "wavelength_um,response\n8,0\n10,1\n12,0\n");
    let r = |l: f64| 1.0 - (l - 10.0).abs() / 2.0;
    let head = "[band]\nresponse = \"lwir.csv\"\n[surface]\ntemperature_k = 300\n\
                [sky]\nmodel = \"thermal\"\ntemperature_k = 300\n";
    let want = simpson(|l| r(l) * planck(l, 300.0), 8.0, 10.0, 2000)
        + simpson(|l| r(l) * planck(l, 300.0), 10.0, 12.0, 2000);
    // ≈ B(10 µm, 300 K) · 2 µm: W·m⁻²·sr⁻¹, not per µm.
    assert!(close(want, 2.0 * planck(10.0, 300.0), 0.05 * want));
    let iso = radiance("paint", &scene(d, head), &VIEWS);
    for row in &iso.rows {
        assert!(
            close(row[2], want, 1e-6 * want),
            "s0 {} vs ∫R·B {want}",
            row[2]
        );
        assert!(row[3].abs() <= 1e-6 * want);
    }
    // The path radiance is spectral, constant over the band: it adds L·∫R dλ.
    let seen = radiance(
        "paint",
        &scene(
            d,
            &format!("{head}[atmosphere]\ntransmittance = 0.5\npath_radiance = 1.0\n"),
        ),
        &VIEWS,
    );
    for (a, b) in iso.rows.iter().zip(&seen.rows) {
        assert!(close(b[2], 0.5 * a[2] + 1.0 * 2.0, 1e-9 * a[2]), "{b:?}");
    }
}

// ---------------------------------------------------------------------------------------------
// contrast --scene

/// Runs `contrast --scene` on a coarse grid without refinement; returns the CSV and best.json.
fn scene_contrast(scene: &str, out: &Path, grid: &str) -> (Table, Value) {
    run(&[
        "contrast",
        "--scene",
        scene,
        "--grid-deg",
        grid,
        "--no-refine",
        "--top",
        "3",
        "--out",
        out.to_str().unwrap(),
    ]);
    let best: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("best.json")).unwrap()).unwrap();
    (Table::read(&out.join("contrast.csv")), best)
}

#[test]
fn identical_surfaces_in_a_scene_have_no_contrast() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let s = scene(
        d,
        "wavelength_um = 10\n[target]\nmaterial = \"paint\"\ntemperature_k = 300\n\
         [background]\nmaterial = \"paint\"\ntemperature_k = 300\n\
         [sky]\nmodel = \"thermal\"\ntemperature_k = 260\n",
    );
    let out = d.join("out");
    let (csv, best) = scene_contrast(&s, &out, "10,30");
    assert_eq!(
        csv.header.last().map(String::as_str),
        Some("radiance_difference")
    );
    assert_eq!(csv.rows.len(), 9 * 12);
    for c in [
        "radiance_difference",
        "delta_dolp",
        "aolp_difference_deg",
        "polarization_contrast",
    ] {
        assert!(csv.col(c).iter().all(|v| *v == 0.0), "{c}");
    }
    assert!(csv.col("intensity_ratio").iter().all(|v| *v == 1.0));
    assert!(out.join("radiance_difference.png").is_file());
    assert!(out.join("radiance_difference.svg").is_file());

    let sc = &best["scene"];
    assert_eq!(sc["target_temperature_k"], 300.0);
    assert_eq!(sc["background_temperature_k"], 300.0);
    assert_eq!(sc["transmittance"], 1.0);
    assert_eq!(sc["path_radiance"], 0.0);
    assert!(sc["file"].as_str().unwrap().ends_with("scene.toml"));
    assert_eq!(sc["sky"]["model"], "thermal", "{sc}");
    assert_eq!(sc["sky"]["temperature_k"], 260.0, "{sc}");
    assert!(sc["units"].as_str().unwrap().contains("W·m⁻²·sr⁻¹·µm⁻¹"));
    assert_eq!(best["spectrum"]["wavelength_um"], 10.0);
    let null = &best["polarization_null"];
    // A thermal sky: the null temperature is its brightness temperature. Under a uniform sky
    // S1 = (B(T) − L)·ε1 has one sign at every view: no locus on the maps.
    let t = null["uniform_sky_null_temperature_k"].as_f64().unwrap();
    assert!(close(t, 260.0, 1e-9 * 260.0), "{t}");
    assert_eq!(null["target"], serde_json::json!([]));
    assert_eq!(null["background"], serde_json::json!([]));
}

#[test]
fn scene_contrast_compares_the_observed_radiances() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write(d, "smooth.toml", SMOOTH);
    let sky = "[sky]\nmodel = \"thermal\"\ntemperature_k = 240\n\
               [atmosphere]\ntransmittance = 0.9\npath_radiance = 0.3\n";
    let s = scene(
        d,
        &format!(
            "wavelength_um = 10\n[target]\nmaterial = \"smooth.toml\"\ntemperature_k = 310\n\
             [background]\nmaterial = \"paint\"\ntemperature_k = 290\n{sky}"
        ),
    );
    let (csv, best) = scene_contrast(&s, &d.join("out"), "20,90");
    assert_eq!(best["target"]["name"], "smooth");
    // Each surface alone, through `radiance` with the same sky and atmosphere.
    let alone = |m: &str, t: f64| {
        let s = write(
            d,
            "alone.toml",
            &format!("wavelength_um = 10\n[surface]\ntemperature_k = {t}\n{sky}"),
        );
        radiance(
            m,
            &s,
            &["--theta-deg", "0,20,40,60,80", "--phi-deg", "0,90,180,270"],
        )
    };
    let target = alone(&d.join("smooth.toml").to_string_lossy(), 310.0);
    let background = alone("paint", 290.0);
    assert_eq!(csv.rows.len(), target.rows.len());
    let col = |t: &Table, c: &str| t.col(c);
    for k in 0..csv.rows.len() {
        assert_eq!(csv.col("theta_r_deg")[k], target.col("theta_r_deg")[k]);
        assert_eq!(csv.col("phi_r_deg")[k], target.col("phi_r_deg")[k]);
        let (st, sb) = (col(&target, "s0")[k], col(&background, "s0")[k]);
        assert!(close(csv.col("intensity_target")[k], st, 1e-12 * st));
        assert!(close(csv.col("intensity_background")[k], sb, 1e-12 * sb));
        assert!(close(
            csv.col("radiance_difference")[k],
            st - sb,
            1e-12 * st
        ));
        assert!(close(
            csv.col("dolp_target")[k],
            col(&target, "dolp")[k],
            1e-12
        ));
        assert!(close(
            csv.col("dolp_background")[k],
            col(&background, "dolp")[k],
            1e-12
        ));
    }
    // The hotter, more emissive-at-normal smooth target is the brighter one at normal view.
    assert!(csv.col("radiance_difference")[0] > 0.0);
}

#[test]
fn the_null_temperature_is_the_skys_brightness_temperature() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let objects = |t: f64| {
        format!(
            "[target]\nmaterial = \"paint\"\ntemperature_k = {t}\n\
             [background]\nmaterial = \"iron\"\ntemperature_k = 300\n"
        )
    };
    // A thermal sky over a band: ∫R·B(T) = ∫R·B(T_sky) at T = T_sky.
    write(
        d,
        "lwir.csv",
        "wavelength_um,response\n8,0.5\n10,1\n12,0.2\n",
    );
    let s = scene(
        d,
        &format!(
            "[band]\nresponse = \"lwir.csv\"\n{}[sky]\nmodel = \"thermal\"\ntemperature_k = 270\n",
            objects(280.0)
        ),
    );
    let (_, best) = scene_contrast(&s, &d.join("out1"), "30,90");
    let t = best["polarization_null"]["uniform_sky_null_temperature_k"]
        .as_f64()
        .unwrap();
    assert!(close(t, 270.0, 1e-6 * 270.0), "{t}");
    assert!(best["scene"]["units"]
        .as_str()
        .unwrap()
        .contains("band-integrated"));
    assert_eq!(best["spectrum"]["band"], "lwir.csv");

    // A uniform sky of radiance L at one wavelength: Planck inverted; a target at that
    // temperature is unpolarized in every direction, the background at 300 K is not.
    let l = 4.0;
    let t_null = brightness_temperature(10.0, l);
    let s = scene(
        d,
        &format!(
            "wavelength_um = 10\n{}[sky]\nmodel = \"uniform\"\nradiance = {l}\n",
            objects(t_null)
        ),
    );
    let (csv, best) = scene_contrast(&s, &d.join("out2"), "10,45");
    let t = best["polarization_null"]["uniform_sky_null_temperature_k"]
        .as_f64()
        .unwrap();
    assert!(close(t, t_null, 1e-9 * t_null), "{t} vs {t_null}");
    assert!(csv.col("dolp_target").iter().all(|v| *v < 1e-7));
    assert!(csv.col("dolp_background").iter().any(|v| *v > 1e-3));

    // A non-uniform sky has no single null temperature.
    write(d, "sky.csv", "zenith_deg,radiance\n0,2\n90,14\n");
    let s = scene(
        d,
        &format!(
            "wavelength_um = 10\n{}[sky]\nmodel = \"profile\"\nfile = \"sky.csv\"\n",
            objects(300.0)
        ),
    );
    let (_, best) = scene_contrast(&s, &d.join("out3"), "30,90");
    assert_eq!(
        best["polarization_null"]["uniform_sky_null_temperature_k"],
        Value::Null
    );
}

#[test]
fn the_null_locus_of_a_smooth_surface_is_where_the_sky_matches_its_temperature() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write(
        d,
        "smooth.toml",
        "n = 1.5\nsigma_deg = 2\nshadowing = false\n",
    );
    // Sky radiance linear in zenith angle, 2 at the zenith to 14 at the horizon.
    write(d, "sky.csv", "zenith_deg,radiance\n0,2\n90,14\n");
    let s = scene(
        d,
        "wavelength_um = 10\n[target]\nmaterial = \"smooth.toml\"\ntemperature_k = 300\n\
         [background]\nmaterial = \"smooth.toml\"\ntemperature_k = 270\n\
         [sky]\nmodel = \"profile\"\nfile = \"sky.csv\"\n",
    );
    let (_, best) = scene_contrast(&s, &d.join("out"), "5,90");
    // A near-specular surface reflects the sky at its own view zenith: S1 ∝ (B(T) − L(θ))·ε1
    // vanishes where L(θ) = B(T).
    let at = |t: f64| 90.0 * (planck(10.0, t) - 2.0) / 12.0;
    for (key, t) in [("target", 300.0), ("background", 270.0)] {
        let locus = best["polarization_null"][key].as_array().unwrap();
        assert_eq!(locus.len(), 4, "{key}: one null per azimuth: {locus:?}");
        for p in locus {
            let theta = p[0].as_f64().unwrap();
            assert!(
                close(theta, at(t), 1.0),
                "{key}: null at {theta}°, want {}°",
                at(t)
            );
        }
    }
}
