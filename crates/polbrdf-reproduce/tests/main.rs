//! Runs the reproduction once into a scratch directory and checks its outputs from the CSV data
//! it wrote (not from stored numbers), plus a few checks of the numerical tools.

use polbrdf::analysis::emission::emissivities;
use polbrdf::{Form, MaterialSpec};
use polbrdf_reproduce::analysis::EmissionNotes;
use polbrdf_reproduce::compute::{self, Interpretation, Roughness, Smooth};
use polbrdf_reproduce::{run, Error, Options, Summary};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

struct Run {
    dir: PathBuf,
    summary: Summary,
    progress: Vec<(String, usize, usize)>,
}

/// One run shared by all tests (the tests of this binary run in parallel threads).
fn fixture() -> &'static Run {
    static RUN: OnceLock<Run> = OnceLock::new();
    RUN.get_or_init(|| {
        let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("polbrdf-reproduce-test/nested/out");
        let _ = std::fs::remove_dir_all(&dir);
        let mut progress = Vec::new();
        let summary = run(
            &Options {
                out_dir: dir.clone(),
            },
            &mut |s, d, t| progress.push((s.to_string(), d, t)),
        )
        .expect("run succeeds");
        Run {
            dir,
            summary,
            progress,
        }
    })
}

struct Csv {
    header: Vec<String>,
    rows: Vec<Vec<f64>>,
}

fn read_csv(name: &str) -> Csv {
    let text = std::fs::read_to_string(fixture().dir.join(name)).expect("csv readable");
    let mut lines = text.lines();
    let header = lines
        .next()
        .expect("header")
        .split(',')
        .map(|s| s.trim().to_string())
        .collect();
    let rows = lines
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            l.split(',')
                .map(|c| c.trim().parse::<f64>().expect("number"))
                .collect()
        })
        .collect();
    Csv { header, rows }
}

const NAMES: [&str; 13] = [
    "fig2.csv",
    "fig2.png",
    "fig2.svg",
    "fig3.csv",
    "fig3.png",
    "fig3.svg",
    "fig4.csv",
    "fig4.png",
    "fig4.svg",
    "table1.csv",
    "fig5.png",
    "fig5.svg",
    "report.md",
];

#[test]
fn writes_every_file_non_empty_and_no_temporaries() {
    let r = fixture();
    let listed: Vec<String> = r
        .summary
        .files
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    for name in NAMES {
        assert!(listed.iter().any(|l| l == name), "{name} not in summary");
        let bytes = std::fs::read(r.dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(bytes.len() > 100, "{name} is nearly empty");
        if name.ends_with(".png") {
            assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "{name} is not a PNG");
            assert!(bytes.len() > 20_000, "{name} is suspiciously small");
        }
        if name.ends_with(".svg") {
            let text = String::from_utf8(bytes).unwrap();
            assert!(text.contains("<svg") && text.contains("</svg>"), "{name}");
            assert!(text.contains("<text"), "{name} has no text");
        }
    }
    for entry in std::fs::read_dir(&r.dir).unwrap() {
        let name = entry.unwrap().file_name().to_string_lossy().into_owned();
        assert!(!name.starts_with('.'), "temporary file left behind: {name}");
    }
}

#[test]
fn progress_reaches_its_total() {
    let p = &fixture().progress;
    assert!(!p.is_empty());
    let total = p[0].2;
    assert!(p.iter().all(|(_, _, t)| *t == total));
    assert!(p.windows(2).all(|w| w[1].1 >= w[0].1));
    assert_eq!(p.last().unwrap().1, total);
}

fn fig2_curves() -> BTreeMap<u64, Vec<(f64, f64)>> {
    let csv = read_csv("fig2.csv");
    assert_eq!(csv.header, ["theta_deg", "thetaN_deg", "brdf"]);
    let mut curves: BTreeMap<u64, Vec<(f64, f64)>> = BTreeMap::new();
    for r in &csv.rows {
        curves.entry(r[0].to_bits()).or_default().push((r[1], r[2]));
    }
    curves
}

#[test]
fn fig2_brdf_falls_with_theta_n_for_every_incidence_angle() {
    let curves = fig2_curves();
    assert!(
        curves.len() >= 5,
        "need incidence angles from near 0° to near 90°"
    );
    let thetas: Vec<f64> = curves.keys().map(|&b| f64::from_bits(b)).collect();
    assert!(thetas[0] <= 5.0 && *thetas.last().unwrap() >= 85.0);
    for (t, c) in &curves {
        assert!(c.iter().all(|&(tn, f)| tn > 0.0 && tn <= 60.0 && f > 0.0));
        assert!(c.last().unwrap().0 == 60.0);
        for w in c.windows(2).filter(|w| w[0].0 >= 1.0) {
            assert!(
                w[1].1 < w[0].1,
                "θ = {}: BRDF rises from θN = {} to {}",
                f64::from_bits(*t),
                w[0].0,
                w[1].0
            );
        }
    }
}

#[test]
fn fig2_ordering_by_incidence_angle_is_what_the_model_gives() {
    // The paper claims larger θi gives a larger BRDF at every θN. The model: true near the
    // specular peak and among θi ≥ 30°, but the θi = 15° curve drops below θi = 1° at large θN
    // (shadowing at β = 15° outweighs the R_F/cos⁴θ gain). The report must say so.
    let curves: Vec<(f64, Vec<(f64, f64)>)> = fig2_curves()
        .into_iter()
        .map(|(b, c)| (f64::from_bits(b), c))
        .collect();
    let value = |ci: usize, k: usize| curves[ci].1[k].1;
    let n = curves[0].1.len();
    for k in 0..n {
        let tn = curves[0].1[k].0;
        for i in 0..curves.len() - 1 {
            let (lo, hi) = (curves[i].0, curves[i + 1].0);
            if tn <= 5.0 || lo >= 30.0 {
                assert!(value(i + 1, k) > value(i, k), "θ {lo}→{hi} at θN = {tn}");
            }
        }
    }
    let i1 = curves
        .iter()
        .position(|c| c.0 == 1.0)
        .expect("θ = 1° curve");
    let i15 = curves
        .iter()
        .position(|c| c.0 == 15.0)
        .expect("θ = 15° curve");
    assert!(
        value(i15, n - 1) < value(i1, n - 1),
        "expected the 1° and 15° curves to cross"
    );
    let r = fixture();
    let c2 = r
        .summary
        .checks
        .iter()
        .find(|c| c.claim.starts_with("(2)"))
        .unwrap();
    assert!(!c2.confirmed);
    let report = std::fs::read_to_string(r.dir.join("report.md")).unwrap();
    assert!(report.contains("not ordered everywhere"));
}

#[test]
fn fig3_peaks_at_brewster_with_dolp_one() {
    let csv = read_csv("fig3.csv");
    assert_eq!(csv.header, ["theta_deg", "dolp"]);
    let (t, d) =
        csv.rows
            .iter()
            .map(|r| (r[0], r[1]))
            .fold(
                (f64::NAN, f64::NEG_INFINITY),
                |a, b| if b.1 > a.1 { b } else { a },
            );
    let brewster = 1.65f64.atan().to_degrees();
    assert!((t - brewster).abs() <= 0.5, "peak at {t}°");
    assert!((d - 1.0).abs() < 1e-9, "peak DoLP {d}");
    assert!(csv.rows[0][0] == 0.0 && csv.rows[0][1].abs() < 1e-12);
    assert!(csv.rows.iter().all(|r| (0.0..=1.0 + 1e-12).contains(&r[1])));
}

fn fig4_by_roughness() -> BTreeMap<u64, Vec<(f64, f64)>> {
    let csv = read_csv("fig4.csv");
    assert_eq!(csv.header, ["theta_deg", "roughness", "dolp"]);
    let mut m: BTreeMap<u64, Vec<(f64, f64)>> = BTreeMap::new();
    for r in &csv.rows {
        m.entry(r[1].to_bits()).or_default().push((r[0], r[2]));
    }
    m
}

#[test]
fn fig4_dolp_decreases_with_roughness_at_fixed_angle() {
    let m = fig4_by_roughness();
    let curves: Vec<&Vec<(f64, f64)>> = m.values().collect();
    assert_eq!(curves.len(), 6);
    for w in curves.windows(2) {
        assert_eq!(w[0].len(), w[1].len());
        for (a, b) in w[0].iter().zip(w[1].iter()) {
            assert_eq!(a.0, b.0);
            assert!(b.1 <= a.1 + 1e-12, "DoLP rises with roughness at {}°", a.0);
            if (5.0..=60.0).contains(&a.0) {
                assert!(b.1 < a.1, "DoLP unchanged by roughness at {}°", a.0);
            }
        }
    }
}

const PAPER_MODEL: [[f64; 5]; 6] = [
    [7.0, 15.0, 30.0, 58.0, 91.0],
    [7.0, 15.0, 30.0, 58.0, 88.0],
    [7.0, 15.0, 30.0, 56.0, 80.0],
    [7.0, 15.0, 30.0, 50.0, 69.0],
    [7.0, 15.0, 26.0, 42.0, 60.0],
    [6.0, 12.0, 20.0, 33.0, 50.0],
];
const PAPER_LAWRENCE: [[f64; 5]; 6] = [
    [7.0, 15.0, 30.0, 58.0, 93.0],
    [7.0, 15.0, 29.0, 56.0, 88.0],
    [7.0, 14.0, 28.0, 53.0, 83.0],
    [7.0, 14.0, 27.0, 50.0, 79.0],
    [6.0, 13.0, 26.0, 47.0, 74.0],
    [2.0, 12.0, 22.0, 44.0, 69.0],
];

#[test]
fn table1_has_30_rows_with_the_printed_values_and_matches_the_figures() {
    let csv = read_csv("table1.csv");
    assert_eq!(
        &csv.header[..5],
        [
            "roughness",
            "theta_deg",
            "dolp_model_pct",
            "dolp_paper_model_pct",
            "dolp_paper_lawrence_pct"
        ]
    );
    assert_eq!(csv.rows.len(), 30);
    let fig3: Vec<(f64, f64)> = read_csv("fig3.csv")
        .rows
        .iter()
        .map(|r| (r[0], r[1]))
        .collect();
    let fig4 = fig4_by_roughness();
    let angles = [20.0, 30.0, 45.0, 60.0, 80.0];
    let rough = [0.0, 0.1, 0.2, 0.3, 0.4, 0.5];
    for (i, row) in csv.rows.iter().enumerate() {
        let (ri, ci) = (i / 5, i % 5);
        assert_eq!(row[0], rough[ri]);
        assert_eq!(row[1], angles[ci]);
        assert_eq!(row[3], PAPER_MODEL[ri][ci]);
        assert_eq!(row[4], PAPER_LAWRENCE[ri][ci]);
        // Our value is the Fig. 4 curve at that angle (and, for the smooth row, Fig. 3).
        let f4 = fig4[&rough[ri].to_bits()]
            .iter()
            .find(|p| p.0 == angles[ci])
            .expect("table angle on the Fig. 4 grid")
            .1;
        assert!((row[2] - 100.0 * f4).abs() < 1e-5, "row {i}");
        if ri == 0 {
            let f3 = fig3.iter().find(|p| p.0 == angles[ci]).unwrap().1;
            assert!((row[2] - 100.0 * f3).abs() < 1e-5);
        }
        if row.len() >= 7 {
            assert!((row[5] - (row[2] - row[3])).abs() < 1e-5);
            assert!((row[6] - (row[2] - row[4])).abs() < 1e-5);
        }
    }
}

#[test]
fn report_embeds_figures_and_states_every_verdict() {
    let r = fixture();
    let report = std::fs::read_to_string(r.dir.join("report.md")).unwrap();
    for png in ["fig2.png", "fig3.png", "fig4.png", "fig5.png"] {
        assert!(report.contains(&format!("]({png})")), "{png} not embedded");
    }
    let verdicts: Vec<(String, bool)> = r
        .summary
        .checks
        .iter()
        .map(|c| (c.claim.chars().take(4).collect(), c.confirmed))
        .collect();
    let expect = [
        ("(1) ", true),
        ("(2) ", false),
        ("(3) ", true),
        ("(3′)", false),
        ("(4) ", true),
        ("(5) ", true),
        ("(6) ", false),
        ("(7) ", false),
    ];
    for (prefix, yes) in expect {
        let v = verdicts
            .iter()
            .find(|(p, _)| p == prefix)
            .unwrap_or_else(|| panic!("no check {prefix}"));
        assert_eq!(v.1, yes, "verdict of {prefix}");
    }
    for c in &r.summary.checks {
        assert!(report.contains(&c.claim), "report lacks claim {}", c.claim);
        assert!(!c.evidence.is_empty());
    }
}

#[test]
fn unwritable_output_directory_is_an_io_error_naming_the_path() {
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("a-file");
    std::fs::write(&file, b"x").unwrap();
    let target = file.join("sub");
    let err = run(
        &Options {
            out_dir: target.clone(),
        },
        &mut |_, _, _| {},
    )
    .unwrap_err();
    assert!(matches!(err, Error::Io { .. }), "{err:?}");
    assert!(
        err.to_string().contains(&*target.to_string_lossy()),
        "{err}"
    );
}

#[test]
fn index_scan_recovers_a_known_index() {
    for hyp in [Smooth::Reflection, Smooth::Emission] {
        let mut target = [0.0; 5];
        for (t, deg) in target.iter_mut().zip([20.0f64, 30.0, 45.0, 60.0, 80.0]) {
            *t = 100.0 * hyp.dolp(3.7, 0.0, deg.to_radians());
        }
        let fit = compute::fit_real_n(hyp, &target);
        assert!((fit.n - 3.7).abs() < 1e-4, "{hyp:?}: {}", fit.n);
        assert!(fit.rms < 1e-6);
    }
}

/// The index of interpretation (c): the best real n of row 0 as emission, Lawrence column.
fn emission_n() -> f64 {
    compute::fit_real_n(Smooth::Emission, &PAPER_LAWRENCE[0]).n
}

fn table_radians() -> Vec<f64> {
    [20.0f64, 30.0, 45.0, 60.0, 80.0]
        .iter()
        .map(|t| t.to_radians())
        .collect()
}

#[test]
fn emission_row0_is_the_fresnel_emission_dolp_and_the_model_tends_to_it() {
    let n = emission_n();
    let rad = table_radians();
    for shadowing in [true, false] {
        let it = Interpretation::new(Roughness::Emission(n, shadowing)).unwrap();
        assert!(it.material(0).is_none(), "row 0 is the σ → 0 limit");
        assert!(it.emissivities_at(0, &rad).is_none());
        for &t in &rad {
            // Exactly the Fresnel emission DoLP |Rs − Rp|/(2 − Rs − Rp).
            let (rs, rp) = compute::fresnel_rs_rp(n, 0.0, t);
            let fresnel = (rs - rp).abs() / (2.0 - rs - rp);
            assert_eq!(it.dolp(0, t), Smooth::Emission.dolp(n, 0.0, t));
            assert!((it.dolp(0, t) - fresnel).abs() < 1e-15);
        }
    }
    // The model at small σ tends to it: as σ² without shadowing, linearly in σ with it (SO's
    // loss (θN/Ω)(1 − exp(−2β/τ)) is first order in the facet tilt).
    let gap = |sigma_deg: f64, shadowing: bool| -> Vec<f64> {
        let m = compute::emission_material(n, sigma_deg.to_radians(), shadowing).unwrap();
        compute::emission_dolp(&m, &rad)
            .iter()
            .zip(&rad)
            .map(|(d, &t)| (d - Smooth::Emission.dolp(n, 0.0, t)).abs())
            .collect()
    };
    let (off1, off05) = (gap(0.1, false), gap(0.05, false));
    let (on1, on05) = (gap(0.1, true), gap(0.05, true));
    for j in 0..rad.len() {
        assert!(off05[j] < 3e-6, "SO off, column {j}: {}", off05[j]);
        let r = off1[j] / off05[j];
        assert!((3.5..4.5).contains(&r), "SO off: σ² rate? ratio {r}");
        assert!(on05[j] < 1e-2, "SO on, column {j}: {}", on05[j]);
        let r = on1[j] / on05[j];
        assert!((1.8..2.2).contains(&r), "SO on: linear rate? ratio {r}");
    }
}

#[test]
fn every_emission_value_comes_from_the_core_emissivities() {
    let a = polbrdf_reproduce::analysis::analyze(&mut |_| {}).unwrap();
    let c = a
        .interps
        .iter()
        .find(|i| matches!(i.how, Roughness::Emission(_, true)))
        .expect("interpretation (c)");
    let Roughness::Emission(n, _) = c.how else {
        unreachable!()
    };
    assert_eq!(n, a.emission_n);
    assert_eq!(n, emission_n());
    let rad = table_radians();
    for (ri, &r) in [0.0, 0.1, 0.2, 0.3, 0.4, 0.5].iter().enumerate().skip(1) {
        // A direct call of the core, one batch per roughness.
        let m = compute::emission_material(n, r, true).unwrap();
        let direct = emissivities(&m, &rad).unwrap();
        for (ci, e) in direct.iter().enumerate() {
            assert_eq!(c.cells[ri][ci], 100.0 * e.dolp(), "cell {r}/{ci}");
            assert_eq!(a.emission_notes.cells[ri - 1][ci], *e, "notes {r}/{ci}");
            // The DoLP of this model's emission is |ε_s − ε_p|/(ε_s + ε_p).
            let alt = (e.eps_s() - e.eps_p()).abs() / (e.eps_s() + e.eps_p());
            assert!((e.dolp() - alt).abs() < 1e-14);
            assert!(e.is_valid(), "cell {r}/{ci}: {e:?}");
            assert!(e.reciprocity_residual() < 1e-12, "cell {r}/{ci}: {e:?}");
        }
        let mut spec = MaterialSpec::new(n, r.to_degrees());
        spec.form = Form::Standard;
        spec.tau_deg = 15.0;
        spec.omega_deg = 40.0;
        assert_eq!(spec.build().unwrap(), m, "(c)'s material");
    }
    // The variant without shadowing breaks energy conservation at grazing view: flagged.
    let invalid = EmissionNotes::invalid(&a.emission_notes.cells_no_so);
    assert!(!invalid.is_empty());
    assert!(invalid.iter().all(|(_, ci, e)| *ci == 4 && e.eps_s() < 0.0));
    assert!(EmissionNotes::invalid(&a.emission_notes.cells).is_empty());
    assert!(EmissionNotes::max_residual(&a.emission_notes.cells) < 1e-12);
    assert!(EmissionNotes::max_residual(&a.emission_notes.cells_no_so) < 1e-12);
}

/// Route A by brute force: `ε = e0 − ∫ F(w_i, w_r)[:, 0] cosθi dω_i`, midpoint rule over the
/// incidence hemisphere (θi × φi), through the engine.
fn brute_force_emissivity(m: &polbrdf::Material, theta_r: f64, nt: usize, np: usize) -> [f64; 4] {
    use std::f64::consts::{FRAC_PI_2, PI};
    let (dt, dp) = (FRAC_PI_2 / nt as f64, 2.0 * PI / np as f64);
    let engine = polbrdf::Engine::new(m);
    let mut acc = [0.0; 4];
    for i in 0..nt {
        let ti = (i as f64 + 0.5) * dt;
        let geoms: Vec<polbrdf::Geometry> = (0..np)
            .map(|j| polbrdf::Geometry::new(ti, -PI + (j as f64 + 0.5) * dp, theta_r, 0.0).unwrap())
            .collect();
        let w = ti.cos() * ti.sin() * dt * dp;
        for f in engine.pbrdf_of(&geoms).unwrap() {
            for (k, a) in acc.iter_mut().enumerate() {
                *a += f[(k, 0)] * w;
            }
        }
    }
    [1.0 - acc[0], -acc[1], -acc[2], -acc[3]]
}

#[test]
fn emission_cell_against_a_brute_force_integral_over_the_incidence_hemisphere() {
    // σ = 0.1 rad at 80°: the cell that moved most (0.07 points) from this crate's former
    // private quadrature (no panel edges at the horizon cuts) to the core's rule.
    let n = emission_n();
    let m = compute::emission_material(n, 0.1, true).unwrap();
    let t = 80f64.to_radians();
    let e = emissivities(&m, &[t]).unwrap()[0];
    let b = brute_force_emissivity(&m, t, 1000, 2000);
    for (j, (x, y)) in e.eps.0.iter().zip(b).enumerate() {
        assert!((x - y).abs() < 2e-6, "ε{j}: {x} vs {y}");
    }
    let dolp_b = b[1].hypot(b[2]) / b[0];
    assert!((e.dolp() - dolp_b).abs() < 1e-5, "{} vs {dolp_b}", e.dolp());
    // Golden values of (c), checked against this brute force (1000 × 2000 and 4000 × 8000
    // nodes: 50.76618 and 50.76629 %) and the smooth limit above.
    let it = Interpretation::new(Roughness::Emission(n, true)).unwrap();
    let cells = compute::table_cells(&it);
    for (ri, ci, pct) in [(1, 4, 50.76628), (3, 3, 10.46732), (5, 0, 0.58734)] {
        assert!(
            (cells[ri][ci] - pct).abs() < 2e-4,
            "({ri}, {ci}): {} vs {pct}",
            cells[ri][ci]
        );
    }
}

#[test]
fn report_states_what_interpretation_c_gives() {
    let report = std::fs::read_to_string(fixture().dir.join("report.md")).unwrap();
    let at = report
        .find("### Interpretation (c): Table 1 as polarized thermal emission")
        .expect("section on (c)");
    let section = &report[at..];
    for needle in [
        "polbrdf::analysis::emission::emissivities",
        "reciprocity residual of",
        "**(c) does not reproduce Table 1**",
        "*invalid*",
        "What it shows about the paper",
    ] {
        assert!(section.contains(needle), "section lacks {needle}");
    }
}
