//! Options before data (issue 35): for every command with a numeric or enumerated option, an
//! invalid value given with input files that do not exist is reported as the option's error,
//! naming the option, and no file is read. Only the binary's argument checks run: fast.

use crate::common::{polbrdf, stderr};

/// A file that does not exist.
const MISSING: &str = "/nonexistent-polbrdf-input/x";

/// Per command: the command line (`{}` is a missing input file) and what the error names.
const CASES: &[(&[&str], &str)] = &[
    (
        &[
            "eval",
            "--material",
            "{}",
            "--input",
            "{}",
            "--theta-i-deg",
            "x",
        ],
        "--theta-i-deg",
    ),
    (
        &["fit", "--material", "{}", "--data", "{}", "--free", "bogus"],
        "unknown parameter `bogus`",
    ),
    (
        &[
            "fit",
            "--material",
            "{}",
            "--data",
            "{}",
            "--free",
            "n",
            "--starts",
            "10001",
        ],
        "--starts",
    ),
    (
        &[
            "fit",
            "--material",
            "{}",
            "--data",
            "{}.pbsdf",
            "--free",
            "n",
            "--starts",
            "10001",
        ],
        "--starts",
    ),
    (
        &[
            "radiance",
            "--material",
            "{}",
            "--scene",
            "{}",
            "--theta-deg",
            "95",
        ],
        "--theta-deg",
    ),
    (
        &[
            "radiance",
            "--material",
            "{}",
            "--scene",
            "{}",
            "--phi-deg",
            "nan",
        ],
        "--phi-deg",
    ),
    (
        &[
            "emission",
            "--material",
            "{}",
            "--band",
            "{}",
            "--theta-deg",
            "95",
        ],
        "--theta-deg",
    ),
    (
        &[
            "albedo",
            "--material",
            "{}",
            "--band",
            "{}",
            "--theta-i-deg",
            "95",
        ],
        "--theta-i-deg",
    ),
    (
        &[
            "map",
            "--material",
            "{}",
            "--band",
            "{}",
            "--sun-zenith-deg",
            "95",
        ],
        "sun_zenith_deg",
    ),
    (
        &[
            "map",
            "--material",
            "{}",
            "--band",
            "{}",
            "--sun-zenith-deg",
            "30",
            "--grid-deg",
            "0",
        ],
        "grid_deg",
    ),
    (
        &[
            "contrast",
            "--target",
            "{}",
            "--background",
            "{}",
            "--scene",
            "{}",
            "--top",
            "0",
        ],
        "--top",
    ),
    (
        &[
            "contrast",
            "--target",
            "{}",
            "--background",
            "{}",
            "--scene",
            "{}",
            "--grid-deg",
            "0",
        ],
        "grid_deg",
    ),
    (
        &[
            "contrast",
            "--target",
            "{}",
            "--background",
            "{}",
            "--scene",
            "{}",
            "--rank-by",
            "bogus",
        ],
        "--rank-by",
    ),
    (
        &[
            "spectrum",
            "--material",
            "{}",
            "--points",
            "1000001",
            "--out",
            "{}.dir",
        ],
        "--points",
    ),
    (
        &["check", "--material", "{}", "--grid-deg", "0"],
        "--grid-deg",
    ),
    (&["explore", "--dir", "{}", "--port", "70000"], "--port"),
    (
        &[
            "export",
            "--material",
            "{}",
            "--grid",
            "1,1,1",
            "--output",
            "{}.pbsdf",
        ],
        "--grid",
    ),
];

#[test]
fn an_invalid_option_is_reported_before_any_input_is_read() {
    for (args, names) in CASES {
        let args: Vec<String> = args.iter().map(|a| a.replace("{}", MISSING)).collect();
        let refs: Vec<&str> = args.iter().map(String::as_str).collect();
        let o = polbrdf(&refs);
        let e = stderr(&o);
        // Issue 33: every bad option value is a usage error (2), none invalid input (3).
        assert_eq!(o.status.code(), Some(2), "{args:?}: {e}");
        // The option named as such (`--sun-zenith-deg`) or as its request field.
        let option = format!("--{}", names.replace('_', "-"));
        assert!(e.contains(names) || e.contains(&option), "{args:?}: {e}");
        assert!(!e.contains("nonexistent-polbrdf-input"), "{args:?}: {e}");
    }
}

#[test]
fn completions_print_a_script_and_refuse_an_unknown_shell() {
    let o = polbrdf(&["completions", "bash"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let script = String::from_utf8(o.stdout).unwrap();
    assert!(script.starts_with("_polbrdf()"), "{script}");
    assert!(script.contains("--grid-deg"));
    let o = polbrdf(&["completions", "tcsh"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("possible values: bash"),
        "{}",
        stderr(&o)
    );
}
