//! The bad-input table (issue 8): every command against malformed, out-of-range and hostile
//! input. Each case checks the exit code, that the message names what is wrong (file, line,
//! field), that no output appears, and that no temporary file is left behind. A few valid but
//! unusual inputs are in the table too, with exit code 0.

use crate::common::{polbrdf, stderr};
use std::path::Path;

const GEO: &str = "theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg\n30,0,30,180\n";
const MEAS: &str = "theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg,brdf\n20,0,20,180,1.0\n30,0,30,180,0.5\n40,0,40,180,0.4\n50,0,50,180,0.5\n";

struct Case {
    what: &'static str,
    /// Files to create in the case's directory: (name, content).
    files: Vec<(&'static str, Vec<u8>)>,
    /// Arguments; `{d}` is replaced by the case's directory.
    args: Vec<&'static str>,
    code: i32,
    /// Fragments the standard error must contain (all of them).
    says: Vec<&'static str>,
}

fn case(
    what: &'static str,
    files: Vec<(&'static str, Vec<u8>)>,
    args: &[&'static str],
    code: i32,
    says: &[&'static str],
) -> Case {
    Case {
        what,
        files,
        args: args.to_vec(),
        code,
        says: says.to_vec(),
    }
}

fn t(s: &str) -> Vec<u8> {
    s.as_bytes().to_vec()
}

/// `eval` with a material file `m.toml` holding `toml`.
fn eval_material(what: &'static str, toml: &str, code: i32, says: &[&'static str]) -> Case {
    case(
        what,
        vec![("m.toml", t(toml)), ("g.csv", t(GEO))],
        &[
            "eval",
            "--material",
            "{d}/m.toml",
            "--input",
            "{d}/g.csv",
            "--output",
            "{d}/out.csv",
        ],
        code,
        says,
    )
}

/// `eval` of the paint preset on a geometry file `g.csv` holding `csv`.
fn eval_geometry(what: &'static str, csv: Vec<u8>, code: i32, says: &[&'static str]) -> Case {
    case(
        what,
        vec![("g.csv", csv)],
        &[
            "eval",
            "--material",
            "paint",
            "--input",
            "{d}/g.csv",
            "--output",
            "{d}/out.csv",
        ],
        code,
        says,
    )
}

/// `fit` of the paint preset (n free) on a measurement file `d.csv` holding `csv`.
fn fit_data(what: &'static str, csv: &str, code: i32, says: &[&'static str]) -> Case {
    case(
        what,
        vec![("d.csv", t(csv))],
        &[
            "fit",
            "--material",
            "paint",
            "--data",
            "{d}/d.csv",
            "--free",
            "n",
            "--output",
            "{d}/out.json",
        ],
        code,
        says,
    )
}

fn table() -> Vec<Case> {
    let long_field = "7".repeat(100_000) + "x";
    vec![
        // Material files.
        eval_material("TOML syntax", "n = \nsigma_deg = 5\n", 3, &["m.toml:1"]),
        eval_material("unknown key", "n = 1.5\nsigma_deg = 5\ncolour = 3\n", 3, &["m.toml:3", "`colour`", "unknown key"]),
        eval_material("duplicated key", "n = 1.5\nsigma_deg = 5\nn = 1.6\n", 3, &["m.toml:3", "duplicate"]),
        eval_material("string for a number", "n = \"1.5\"\nsigma_deg = 5\n", 3, &["m.toml:1", "`n`", "expected a number"]),
        eval_material("string for a bool", "n = 1.5\nsigma_deg = 5\nshadowing = \"yes\"\n", 3, &["m.toml:3", "`shadowing`"]),
        eval_material("nested table", "n = 1.5\nsigma_deg = 5\n[paint]\nk = 1\n", 3, &["m.toml:3", "`paint`"]),
        eval_material("empty material file", "", 3, &["m.toml", "missing required key `n`"]),
        eval_material("n = nan", "n = nan\nsigma_deg = 5\n", 3, &["m.toml:1", "`n`", "NaN"]),
        eval_material("n = inf", "n = inf\nsigma_deg = 5\n", 3, &["m.toml:1", "`n`", "inf"]),
        eval_material("n = 0", "n = 0\nsigma_deg = 5\n", 3, &["m.toml:1", "`n`", "> 0"]),
        eval_material("n = 1e308", "n = 1e308\nsigma_deg = 5\n", 3, &["m.toml:1", "`n`", "1e308"]),
        eval_material("negative k", "n = 1.5\nk = -0.1\nsigma_deg = 5\n", 3, &["m.toml:2", "`k`", "-0.1"]),
        eval_material("zero sigma", "n = 1.5\nsigma_deg = 0\n", 3, &["m.toml:2", "`sigma_deg`"]),
        eval_material("negative b", "n = 1.5\nb = -1\n", 3, &["m.toml:2", "`b`"]),
        eval_material("negative a", "n = 1.5\nsigma_deg = 5\na = -1\n", 3, &["m.toml:3", "`a`"]),
        eval_material("negative rho_d", "n = 1.5\nsigma_deg = 5\nrho_d = -0.01\n", 3, &["m.toml:3", "`rho_d`"]),
        eval_material("zero tau", "n = 1.5\nsigma_deg = 5\ntau_deg = 0\n", 3, &["m.toml:3", "`tau_deg`"]),
        eval_material("negative omega", "n = 1.5\nsigma_deg = 5\nomega_deg = -40\n", 3, &["m.toml:3", "`omega_deg`"]),
        eval_material("unknown form", "n = 1.5\nsigma_deg = 5\nform = \"fancy\"\n", 3, &["m.toml:3", "`form`", "standard"]),
        eval_material("unknown azimuth term", "n = 1.5\nsigma_deg = 5\nazimuth_term = \"eq4\"\n", 3, &["m.toml:3", "`azimuth_term`", "eq3"]),
        eval_material("sigma and b", "n = 1.5\nsigma_deg = 5\nb = 3\n", 3, &["m.toml:3", "`b`", "exactly one"]),
        eval_material("no roughness", "n = 1.5\n", 3, &["m.toml", "sigma_deg"]),
        case("binary material file", vec![("m.toml", vec![0, 159, 146, 150, 255, 0xfe]), ("g.csv", t(GEO))],
            &["eval", "--material", "{d}/m.toml", "--input", "{d}/g.csv", "--output", "{d}/out.csv"], 3, &["m.toml:1", "UTF-8"]),
        eval_material("BOM, CRLF, k = 0, rho = 0, huge sigma (valid)", "\u{feff}n = 1.5\r\nk = 0\r\nsigma_deg = 1e6\r\nrho_d = 0\r\n", 0, &[]),
        // Geometry files.
        eval_geometry("empty geometry file", vec![], 3, &["g.csv", "empty"]),
        eval_geometry("header only (valid: no rows)", t("theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg\n"), 0, &[]),
        eval_geometry("missing column", t("theta_i_deg,phi_i_deg,theta_r_deg\n30,0,30\n"), 3, &["g.csv", "missing column", "phi_r_deg"]),
        eval_geometry("duplicated column", t("theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg,phi_r_deg\n1,2,3,4,5\n"), 3, &["g.csv:1", "twice"]),
        eval_geometry("text for a number", t("theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg\n30,0,30,180\n30,0,thirty,180\n"), 3, &["g.csv:3", "`theta_r_deg`", "thirty"]),
        eval_geometry("NaN angle", t("theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg\n30,NaN,30,180\n"), 3, &["g.csv:2", "`phi_i_deg`", "finite"]),
        eval_geometry("infinite angle", t("theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg\n30,0,30,-inf\n"), 3, &["g.csv:2", "`phi_r_deg`"]),
        eval_geometry("negative zenith", t("theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg\n-1,0,30,180\n"), 3, &["g.csv:2", "`theta_i_deg`", "-1"]),
        eval_geometry("zenith above 180", t("theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg\n30,0,180.5,180\n"), 3, &["g.csv:2", "`theta_r_deg`", "180.5"]),
        eval_geometry("zenith 1e308", t("theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg\n1e308,0,30,180\n"), 3, &["g.csv:2", "`theta_i_deg`", "1e308"]),
        eval_geometry("ragged row", t("theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg\n30,0,30,180\n30,0,30\n"), 3, &["g.csv:3", "fields"]),
        eval_geometry("binary garbage", vec![0x89, b'P', b'N', b'G', 0, 0xff, 0xfe, b'\n', 1, 2], 3, &["g.csv:1", "UTF-8"]),
        eval_geometry("a 100 kB field in an angle column", t(&format!("theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg\n30,0,30,{long_field}\n")), 3, &["g.csv:2", "`phi_r_deg`", "…"]),
        eval_geometry("-0, 90 and 180 degrees (valid)", t("theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg\n-0,-0,-0,0\n90,0,30,180\n30,0,180,0\n"), 0, &[]),
        eval_geometry("output column name clash", t("theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg,brdf\n30,0,30,180,1\n"), 3, &["g.csv", "`brdf`"]),
        case("input is a directory", vec![], &["eval", "--material", "paint", "--input", "{d}", "--output", "{d}/out.csv"], 4, &["cannot read"]),
        case("output directory missing", vec![("g.csv", t(GEO))], &["eval", "--material", "paint", "--input", "{d}/g.csv", "--output", "{d}/no/such/out.csv"], 4, &["cannot write", "out.csv"]),
        case("unknown preset", vec![("g.csv", t(GEO))], &["eval", "--material", "unobtainium", "--input", "{d}/g.csv", "--output", "{d}/out.csv"], 3, &["unobtainium", "paint"]),
        // Measurement files and fit.
        fit_data("zero sigma", "theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg,brdf,sigma_brdf\n20,0,20,180,1.0,0.1\n30,0,30,180,0.5,0\n", 3, &["d.csv:3", "`sigma_brdf`", "> 0"]),
        fit_data("sigma without its quantity", "theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg,brdf,sigma_dolp\n20,0,20,180,1.0,0.1\n", 3, &["d.csv", "`sigma_dolp`"]),
        fit_data("no measured column", "theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg,label\n20,0,20,180,x\n", 3, &["d.csv", "no measured column"]),
        fit_data("NaN measurement", "theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg,dolp\n20,0,20,180,nan\n", 3, &["d.csv:2", "`dolp`", "finite"]),
        fit_data("value without its sigma", "theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg,brdf,sigma_brdf\n20,0,20,180,1.0,\n", 3, &["d.csv:2", "`sigma_brdf`", "missing"]),
        case("unknown free parameter", vec![("d.csv", t(MEAS))], &["fit", "--material", "paint", "--data", "{d}/d.csv", "--free", "n,gloss", "--output", "{d}/out.json"], 3, &["`gloss`"]),
        case("more parameters than values", vec![("d.csv", t(MEAS))], &["fit", "--material", "paint", "--data", "{d}/d.csv", "--free", "n,k,sigma_deg,rho_d", "--output", "{d}/out.json"], 3, &["too few"]),
        // The other commands.
        case("check: zero grid step", vec![], &["check", "--material", "paint", "--grid-deg", "0"], 3, &["--grid-deg"]),
        case("contrast: sun below the horizon", vec![], &["contrast", "--target", "paint", "--background", "glass", "--sun-zenith-deg", "95", "--out", "{d}/out"], 3, &["95"]),
        case("contrast: unknown background", vec![], &["contrast", "--target", "paint", "--background", "nope", "--sun-zenith-deg", "30", "--out", "{d}/out"], 3, &["nope"]),
        case("map: negative sun zenith", vec![], &["map", "--material", "paint", "--sun-zenith-deg", "-5", "--out", "{d}/out"], 3, &["-5"]),
        case("albedo: incidence at 90", vec![], &["albedo", "--material", "paint", "--theta-i-deg", "90", "--output", "{d}/out.csv"], 3, &["90"]),
        case("reproduce: output is a file", vec![("out", t("x"))], &["reproduce", "--out", "{d}/out"], 4, &["out"]),
        // Usage errors (clap).
        case("unknown subcommand", vec![], &["frobnicate"], 2, &["frobnicate"]),
        case("missing required option", vec![], &["eval", "--material", "paint"], 2, &["--input"]),
        case("option value not a number", vec![], &["check", "--material", "paint", "--grid-deg", "five"], 2, &["five"]),
    ]
}

#[test]
fn every_bad_input_fails_cleanly() {
    let cases = table();
    assert!(cases.len() >= 40, "{} cases", cases.len());
    for c in cases {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path().to_str().unwrap().to_string();
        for (name, content) in &c.files {
            std::fs::write(dir.path().join(name), content).unwrap();
        }
        let args: Vec<String> = c.args.iter().map(|a| a.replace("{d}", &d)).collect();
        let argv: Vec<&str> = args.iter().map(String::as_str).collect();
        let out = polbrdf(&argv);
        let msg = stderr(&out);
        assert_eq!(out.status.code(), Some(c.code), "{}: {msg}", c.what);
        for s in &c.says {
            assert!(msg.contains(s), "{}: message {msg:?} lacks {s:?}", c.what);
        }
        assert!(!msg.contains("panicked"), "{}: {msg}", c.what);
        assert!(
            msg.len() < 2_000,
            "{}: message of {} bytes",
            c.what,
            msg.len()
        );
        if c.code != 0 {
            for out_name in ["out.csv", "out.json"] {
                assert!(
                    !dir.path().join(out_name).exists(),
                    "{}: {out_name} written",
                    c.what
                );
            }
            if !c.files.iter().any(|(n, _)| *n == "out") {
                assert!(
                    !dir.path().join("out").exists(),
                    "{}: output directory created",
                    c.what
                );
            }
        }
        let leftovers: Vec<String> = walk(dir.path())
            .into_iter()
            .filter(|n| n.ends_with(".tmp") || n.contains(".polbrdf-"))
            .collect();
        assert!(
            leftovers.is_empty(),
            "{}: temporary files left: {leftovers:?}",
            c.what
        );
    }
}

fn walk(dir: &Path) -> Vec<String> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir).unwrap() {
        let e = e.unwrap();
        let p = e.path();
        if p.is_dir() {
            out.extend(walk(&p));
        } else {
            out.push(p.file_name().unwrap().to_string_lossy().into_owned());
        }
    }
    out
}
