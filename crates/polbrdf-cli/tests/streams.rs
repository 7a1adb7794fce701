//! One stream for summaries (docs/cli-conventions.md, Streams): every command of the clap
//! definition, run on a small case, writes only its data result on standard output (CSV or
//! JSON that parses, the completion script, the materials list; nothing for the commands whose
//! results are files) and its summary on standard error, so that `> file` captures the data
//! alone. The commands are walked from `polbrdf_cli::command()`: a new command without a case
//! here fails the test.

use crate::common::{polbrdf, stderr, write};
use std::io::BufRead;
use std::path::Path;
use std::process::{Command, Stdio};

/// What standard output must hold.
enum Data {
    /// Nothing: the results are files (`--out DIR`, `--output FILE`).
    Nothing,
    /// A CSV table whose header starts with this column, every row as wide as the header.
    Csv(&'static str),
    /// One JSON document.
    Json,
    /// Text holding this (the materials list, a completion script).
    Text(&'static str),
}

/// A command line, what its standard output must hold, and how its summary on standard error
/// starts (`None`: a command with no summary, whose standard error stays empty).
struct Case {
    args: Vec<String>,
    data: Data,
    summary: Option<&'static str>,
}

/// Commands with no case here, and why: their stream discipline is held by other tests.
const NOT_RUN: [(&str, &str); 1] = [(
    "bench",
    "a minute and a half of timing probes in a debug build; tests/bench.rs holds the same rule \
     (bench_table_goes_to_stderr_and_json_alone_to_stdout: the table on standard error, the \
     --json document alone on standard output)",
)];

fn example(name: &str) -> String {
    format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"))
}

/// The small case of `command` in the scratch directory `d`, or `None` for one of [`NOT_RUN`].
fn case(command: &str, d: &Path) -> Option<Case> {
    let p = |name: &str| d.join(name).display().to_string();
    let geometry = write(
        d,
        "g.csv",
        "theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg\n30,0,30,180\n",
    );
    let scene = write(
        d,
        "s.toml",
        "wavelength_um = 10\n[surface]\ntemperature_k = 300\n",
    );
    let lut = write(
        d,
        "lut.toml",
        "materials = [\"paint\"]\nwavelength_um = [0.55]\ntheta_i_deg = [0, 30]\n\
         theta_r_deg = [0]\ndphi_deg = [0]\nquantities = [\"dolp\"]\n",
    );
    let grid = ["--grid-deg", "30,90"];
    let (args, data, summary): (Vec<String>, Data, Option<&str>) = match command {
        "eval" => (
            vec![
                "--material".into(),
                "paint".into(),
                "--input".into(),
                geometry,
            ],
            Data::Csv("theta_i_deg"),
            None,
        ),
        "fit" => (
            vec![
                "--material".into(),
                example("paint-init.toml"),
                "--data".into(),
                example("paint-goniometer.csv"),
                "--free".into(),
                "rho_d".into(),
                "--starts".into(),
                "0".into(),
            ],
            Data::Json,
            Some("polbrdf fit: "),
        ),
        "contrast" => (
            [
                "--target",
                "paint",
                "--background",
                "glass",
                "--sun-zenith-deg",
                "30",
            ]
            .iter()
            .chain(&grid)
            .map(|s| s.to_string())
            .chain(["--out".into(), p("contrast")])
            .collect(),
            Data::Nothing,
            Some("polbrdf contrast: "),
        ),
        "detect" => (
            vec![
                "--scene".into(),
                example("detect-daylight-scene.toml"),
                "--sensor".into(),
                example("sensors/sony-imx250mzr-dofp.toml"),
                "--theta-deg".into(),
                "45".into(),
                "--phi-deg".into(),
                "0".into(),
                "--ranges-m".into(),
                "400".into(),
                "--out".into(),
                p("detect"),
            ],
            Data::Nothing,
            Some("polbrdf detect: "),
        ),
        "albedo" => (
            vec![
                "--material".into(),
                "paint".into(),
                "--theta-i-deg".into(),
                "0,30".into(),
            ],
            Data::Csv("theta_i_deg"),
            Some("polbrdf albedo: "),
        ),
        "emission" => (
            vec![
                "--material".into(),
                "paint".into(),
                "--theta-deg".into(),
                "0,30".into(),
            ],
            Data::Csv("theta_deg"),
            Some("polbrdf emission: "),
        ),
        "radiance" => (
            vec![
                "--material".into(),
                "paint".into(),
                "--scene".into(),
                scene,
                "--theta-deg".into(),
                "10".into(),
            ],
            Data::Csv("theta_r_deg"),
            Some("polbrdf radiance: "),
        ),
        "map" => (
            ["--material", "paint", "--sun-zenith-deg", "30"]
                .iter()
                .chain(&grid)
                .map(|s| s.to_string())
                .chain(["--out".into(), p("map")])
                .collect(),
            Data::Nothing,
            Some("polbrdf map: "),
        ),
        "spectrum" => (
            vec![
                "--material".into(),
                "paint".into(),
                "--points".into(),
                "2".into(),
                "--out".into(),
                p("spectrum"),
            ],
            Data::Nothing,
            Some("polbrdf spectrum: "),
        ),
        "lut" => (
            vec!["--config".into(), lut, "--out".into(), p("lut")],
            Data::Nothing,
            Some("polbrdf lut: "),
        ),
        "check" => (
            vec![
                "--material".into(),
                "paint".into(),
                "--grid-deg".into(),
                "30".into(),
            ],
            Data::Nothing,
            Some("polbrdf check: "),
        ),
        "export" => (
            vec![
                "--material".into(),
                "paint".into(),
                "--grid".into(),
                "9,7,8".into(),
                "--output".into(),
                p("t.pbsdf"),
            ],
            Data::Nothing,
            Some("polbrdf export: "),
        ),
        "sun" => (
            [
                "--date-time",
                "2026-06-21T12:00:00Z",
                "--latitude-deg",
                "48",
                "--longitude-deg",
                "16",
            ]
            .map(String::from)
            .to_vec(),
            Data::Json,
            None,
        ),
        "daytime" => (
            [
                "--scene",
                &example("daytime-scene.toml"),
                "--times",
                "13:00",
            ]
            .iter()
            .chain(&grid)
            .map(|s| s.to_string())
            .chain(["--out".into(), p("daytime")])
            .collect(),
            Data::Nothing,
            Some("polbrdf daytime: "),
        ),
        "reproduce" => (
            vec!["--out".into(), p("reproduce")],
            Data::Nothing,
            Some("polbrdf reproduce: "),
        ),
        "materials" => (Vec::new(), Data::Text("paint"), None),
        "completions" => (vec!["bash".into()], Data::Text("_polbrdf()"), None),
        _ => return None,
    };
    let args = std::iter::once(command.to_string()).chain(args).collect();
    Some(Case {
        args,
        data,
        summary,
    })
}

/// Standard output holds `data` alone.
fn check_data(what: &str, stdout: &[u8], data: &Data) {
    let text = String::from_utf8_lossy(stdout);
    match data {
        Data::Nothing => assert!(stdout.is_empty(), "{what}: standard output holds {text:?}"),
        Data::Csv(first) => {
            let mut reader = csv::Reader::from_reader(stdout);
            let header = reader.headers().expect("a CSV header").clone();
            assert_eq!(header.get(0), Some(*first), "{what}: {text}");
            let rows: Vec<csv::StringRecord> = reader
                .records()
                .collect::<Result<_, _>>()
                .unwrap_or_else(|e| panic!("{what}: not one CSV table ({e}): {text}"));
            assert!(!rows.is_empty(), "{what}: {text}");
            for r in &rows {
                assert_eq!(r.len(), header.len(), "{what}: {text}");
            }
        }
        Data::Json => {
            serde_json::from_slice::<serde_json::Value>(stdout)
                .unwrap_or_else(|e| panic!("{what}: not one JSON document ({e}): {text}"));
        }
        Data::Text(needle) => assert!(text.contains(needle), "{what}: {text}"),
    }
}

/// Every command on its small case: the data result on standard output, the summary on
/// standard error.
#[test]
fn every_command_writes_its_data_on_stdout_and_its_summary_on_stderr() {
    let dir = tempfile::tempdir().unwrap();
    let mut ran = Vec::new();
    for sub in polbrdf_cli::command().get_subcommands() {
        let name = sub.get_name();
        if name == "explore" {
            explore_prints_its_address_on_stderr(dir.path());
            ran.push(name.to_string());
            continue;
        }
        let Some(c) = case(name, dir.path()) else {
            assert!(
                NOT_RUN.iter().any(|(n, _)| *n == name),
                "`polbrdf {name}` has no case in tests/streams.rs: add one (or list it in \
                 NOT_RUN with the reason)"
            );
            continue;
        };
        let args: Vec<&str> = c.args.iter().map(String::as_str).collect();
        let o = polbrdf(&args);
        let what = args.join(" ");
        assert!(o.status.success(), "{what}: {}", stderr(&o));
        check_data(&what, &o.stdout, &c.data);
        match c.summary {
            Some(start) => assert!(
                stderr(&o).starts_with(start),
                "{what}: the summary on standard error: {}",
                stderr(&o)
            ),
            None => assert!(o.stderr.is_empty(), "{what}: {}", stderr(&o)),
        }
        ran.push(name.to_string());
    }
    for (name, _) in NOT_RUN {
        assert!(
            !ran.contains(&name.to_string()),
            "{name} is run: drop it from NOT_RUN"
        );
    }
    assert!(ran.len() >= 18, "{ran:?}");
}

/// `polbrdf explore` serves until stopped: its address is the first line on standard error and
/// nothing reaches standard output.
fn explore_prints_its_address_on_stderr(d: &Path) {
    let dist = d.join("dist");
    std::fs::create_dir_all(dist.join("pkg")).unwrap();
    for f in ["index.html", "explorer.js", "pkg/polbrdf_wasm_bg.wasm"] {
        std::fs::write(dist.join(f), "x").unwrap();
    }
    let mut child = Command::new(env!("CARGO_BIN_EXE_polbrdf"))
        .args(["explore", "--port", "0", "--dir"])
        .arg(&dist)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut line = String::new();
    std::io::BufReader::new(child.stderr.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    child.kill().unwrap();
    let o = child.wait_with_output().unwrap();
    assert!(
        line.starts_with("polbrdf explorer: http://127.0.0.1:"),
        "{line:?}"
    );
    assert!(
        o.stdout.is_empty(),
        "{}",
        String::from_utf8_lossy(&o.stdout)
    );
}
