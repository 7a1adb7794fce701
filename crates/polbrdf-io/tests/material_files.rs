//! Material TOML: round trip, defaults, and errors that name file, line and key.

use polbrdf::{AzimuthTerm, Form, MaterialSpec};
use polbrdf_io::{material_to_toml, parse_material, Error};
use std::path::Path;

fn parse(text: &str) -> Result<MaterialSpec, Error> {
    parse_material(text, Path::new("mat.toml"))
}

#[test]
fn defaults_follow_the_contract() {
    let s = parse("n = 2\nsigma_deg = 10\n").unwrap();
    assert_eq!(s.n, 2.0, "integers are accepted as numbers");
    assert_eq!((s.k, s.rho_d, s.rho_v), (0.0, 0.0, 0.0));
    assert_eq!((s.tau_deg, s.omega_deg), (15.0, 40.0));
    assert_eq!(s.form, Form::Standard);
    assert!(s.shadowing);
    assert_eq!(s.azimuth_term, AzimuthTerm::None);
    assert_eq!(s.a, None, "a absent = hemispherical normalization");
}

#[test]
fn every_key_round_trips() {
    let spec = MaterialSpec {
        name: Some("olive \"drab\" paint".into()),
        n: 1.55,
        k: 0.001,
        sigma_deg: None,
        b: Some(12.5),
        a: Some(4.25),
        form: Form::Paper,
        shadowing: false,
        tau_deg: 12.0,
        omega_deg: 35.0,
        azimuth_term: AzimuthTerm::Eq3,
        rho_d: 0.1 + 0.2,
        rho_v: 1e-300,
        spectral: None,
    };
    let text = material_to_toml(&spec);
    assert_eq!(parse(&text).unwrap(), spec, "{text}");
    for p in polbrdf::presets::all() {
        assert_eq!(parse(&material_to_toml(&p.spec)).unwrap(), p.spec);
    }
}

fn field_error(text: &str) -> (usize, String, String) {
    match parse(text).unwrap_err() {
        Error::Field {
            line,
            field,
            message,
            path,
        } => {
            assert_eq!(path, Path::new("mat.toml"));
            (line, field, message)
        }
        other => panic!("expected a field error, got {other}"),
    }
}

#[test]
fn value_errors_point_at_the_key_line() {
    let (line, field, msg) = field_error("# comment\nn = 1.5\n\nsigma_deg = -2\n");
    assert_eq!((line, field.as_str()), (4, "sigma_deg"));
    assert!(msg.contains("-2"), "{msg}");
    let (line, field, _) = field_error("n = 1.5\nsigma_deg = 5\nrho_v = -0.1\n");
    assert_eq!((line, field.as_str()), (3, "rho_v"));
    let (line, field, msg) = field_error("n = 1.5\nsigma_deg = 5\nform = \"fancy\"\n");
    assert_eq!((line, field.as_str()), (3, "form"));
    assert!(msg.contains("standard"), "{msg}");
    let (line, field, _) = field_error("n = 1.5\nsigma_deg = 5\nshadowing = 1\n");
    assert_eq!((line, field.as_str()), (3, "shadowing"));
    let (line, field, _) = field_error("n = 1.5\nsigma_deg = 5\n[extra]\nx = 1\n");
    assert_eq!((line, field.as_str()), (3, "extra"));
    let (_, field, msg) = field_error("n = 1.5\nsigma_deg = nan\n");
    assert_eq!(field, "sigma_deg");
    assert!(msg.contains("NaN"), "{msg}");
}

#[test]
fn syntax_errors_and_duplicates_name_the_line() {
    for (text, want_line) in [
        ("n = 1.5\nsigma_deg = \n", 2),
        ("n = 1.5\nn = 1.6\nsigma_deg = 3\n", 2),
    ] {
        match parse(text).unwrap_err() {
            Error::Syntax { line, .. } => assert_eq!(line, want_line, "{text:?}"),
            other => panic!("{text:?}: expected a syntax error, got {other}"),
        }
    }
}

#[test]
fn bom_and_crlf_are_accepted() {
    let s = parse("\u{feff}n = 1.5\r\nsigma_deg = 5\r\n").unwrap();
    assert_eq!(s.n, 1.5);
}
