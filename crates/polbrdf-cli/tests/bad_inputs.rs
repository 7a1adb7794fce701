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

/// A small valid refractiveindex.info file (0.4–0.8 µm).
const YML: &str =
    "DATA:\n  - type: tabulated nk\n    data: |\n        0.4 1.5 0.0\n        0.8 1.4 0.1\n";
const SPECTRAL: &str = "index = \"library:Au/Johnson\"\nsigma_deg = 10\n";
const GEO_WL: &str = "theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg,wavelength_um\n30,0,30,180,0.5\n";
const BAND: &str = "wavelength_um,response\n0.45,0\n0.55,1\n0.65,0\n";

/// `contrast` of a spectral target against paint with `extra` options and files.
fn spectral_contrast(
    what: &'static str,
    files: Vec<(&'static str, Vec<u8>)>,
    extra: &[&'static str],
    code: i32,
    says: &[&'static str],
) -> Case {
    let mut args = vec![
        "contrast",
        "--target",
        "{d}/m.toml",
        "--background",
        "paint",
        "--sun-zenith-deg",
        "40",
        "--out",
        "{d}/out",
    ];
    args.extend_from_slice(extra);
    let mut f = vec![("m.toml", t(SPECTRAL))];
    f.extend(files);
    case(what, f, &args, code, says)
}

/// `eval` of the spectral material on a geometry file `g.csv` holding `csv`.
fn eval_spectral(what: &'static str, csv: &str, code: i32, says: &[&'static str]) -> Case {
    case(
        what,
        vec![("m.toml", t(SPECTRAL)), ("g.csv", t(csv))],
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
        // Spectral indices in material files.
        eval_material("unknown library entry", "index = \"library:Au/Nobody\"\nsigma_deg = 5\n", 3, &["m.toml:1", "`index`", "Au/Johnson"]),
        eval_material("index and n", "index = \"library:Au/Johnson\"\nn = 1.5\nsigma_deg = 5\n", 3, &["m.toml:2", "`n`", "not both"]),
        eval_material("index is a number", "index = 5\nsigma_deg = 5\n", 3, &["m.toml:1", "`index`", "string"]),
        eval_material("index file missing", "index = \"nowhere.yml\"\nsigma_deg = 5\n", 3, &["m.toml:1", "`index`", "nowhere.yml"]),
        case("index file malformed", vec![("m.toml", t("index = \"y.yml\"\nsigma_deg = 5\n")), ("y.yml", t("DATA:\n  - type: tabulated nk\n    data: |\n        0.4 1.5 x\n")), ("g.csv", t(GEO_WL))],
            &["eval", "--material", "{d}/m.toml", "--input", "{d}/g.csv", "--output", "{d}/out.csv"], 3, &["m.toml:1", "y.yml:"]),
        case("index file relative to the material file (valid)", vec![("m.toml", t("index = \"y.yml\"\nsigma_deg = 5\n")), ("y.yml", t(YML)), ("g.csv", t(GEO_WL))],
            &["eval", "--material", "{d}/m.toml", "--input", "{d}/g.csv", "--output", "{d}/out.csv"], 0, &[]),
        // Wavelengths in geometry files.
        eval_spectral("spectral material, no wavelength column", GEO, 3, &["g.csv", "`wavelength_um`"]),
        eval_spectral("wavelength outside the data", "theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg,wavelength_um\n30,0,30,180,0.5\n30,0,30,180,3.0\n", 3, &["g.csv:3", "`wavelength_um`", "Au/Johnson", "1.937"]),
        eval_spectral("zero wavelength", "theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg,wavelength_um\n30,0,30,180,0\n", 3, &["g.csv:2", "`wavelength_um`", "> 0"]),
        eval_spectral("NaN wavelength", "theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg,wavelength_um\n30,0,30,180,NaN\n", 3, &["g.csv:2", "`wavelength_um`"]),
        eval_spectral("text wavelength", "theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg,wavelength_um\n30,0,30,180,green\n", 3, &["g.csv:2", "`wavelength_um`", "green"]),
        // Wavelength options and band files.
        spectral_contrast("spectral target without a wavelength", vec![], &[], 3, &["--target", "--wavelength-um", "--band"]),
        spectral_contrast("--wavelength-um 0", vec![], &["--wavelength-um", "0"], 3, &["--wavelength-um", "> 0"]),
        spectral_contrast("--wavelength-um outside the data", vec![], &["--wavelength-um", "5"], 3, &["--target", "Au/Johnson", "1.937"]),
        spectral_contrast("band and wavelength", vec![("b.csv", t(BAND))], &["--band", "{d}/b.csv", "--wavelength-um", "0.5"], 2, &["--band"]),
        spectral_contrast("band: no overlap with the data", vec![("b.csv", t("wavelength_um,response\n8,1\n12,1\n"))], &["--band", "{d}/b.csv"], 3, &["Au/Johnson", "1.937"]),
        spectral_contrast("band: missing column", vec![("b.csv", t("wavelength_um,weight\n0.5,1\n0.6,1\n"))], &["--band", "{d}/b.csv"], 3, &["b.csv", "response"]),
        spectral_contrast("band: wavelengths not increasing", vec![("b.csv", t("wavelength_um,response\n0.5,1\n0.6,1\n0.55,1\n"))], &["--band", "{d}/b.csv"], 3, &["b.csv:4", "`wavelength_um`", "increase"]),
        spectral_contrast("band: negative response", vec![("b.csv", t("wavelength_um,response\n0.5,1\n0.6,-1\n"))], &["--band", "{d}/b.csv"], 3, &["b.csv:3", "`response`"]),
        spectral_contrast("band: zero response", vec![("b.csv", t("wavelength_um,response\n0.5,0\n0.6,0\n"))], &["--band", "{d}/b.csv"], 3, &["b.csv", "zero everywhere"]),
        spectral_contrast("band: one row", vec![("b.csv", t("wavelength_um,response\n0.5,1\n"))], &["--band", "{d}/b.csv"], 3, &["b.csv", "two"]),
        spectral_contrast("band: empty file", vec![("b.csv", vec![])], &["--band", "{d}/b.csv"], 3, &["b.csv", "empty"]),
        spectral_contrast("band: text", vec![("b.csv", t("wavelength_um,response\n0.5,high\n0.6,1\n"))], &["--band", "{d}/b.csv"], 3, &["b.csv:2", "`response`", "high"]),
        spectral_contrast("band: missing file", vec![], &["--band", "{d}/none.csv"], 4, &["none.csv"]),
        spectral_contrast("band step 0", vec![("b.csv", t(BAND))], &["--band", "{d}/b.csv", "--band-step-um", "0"], 3, &["--band-step-um"]),
        spectral_contrast("band (valid)", vec![("b.csv", t(BAND))], &["--band", "{d}/b.csv"], 0, &[]),
        case("spectrum: bad range", vec![], &["spectrum", "--material", "paint", "--range-um", "2,1", "--out", "{d}/out"], 3, &["--range-um"]),
        case("spectrum: one point", vec![], &["spectrum", "--material", "paint", "--points", "1", "--out", "{d}/out"], 3, &["--points"]),
        case("spectrum: range outside the data", vec![("m.toml", t(SPECTRAL))], &["spectrum", "--material", "{d}/m.toml", "--range-um", "0.5,5", "--out", "{d}/out"], 3, &["Au/Johnson", "1.937"]),
        case("fit per wavelength without wavelengths", vec![("d.csv", t(MEAS))], &["fit", "--material", "paint", "--data", "{d}/d.csv", "--free", "n", "--per-wavelength", "--output", "{d}/out.json"], 3, &["wavelength_um"]),
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
