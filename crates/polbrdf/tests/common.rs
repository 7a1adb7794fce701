//! Shared helpers: loading the reference test vectors.

use polbrdf::{AzimuthTerm, Form, Geometry, MaterialSpec};
use serde_json::Value;

pub struct Case {
    pub id: String,
    pub inputs: Value,
    pub outputs: Value,
    pub intermediates: Option<Value>,
}

pub fn cases() -> Vec<Case> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../tests/data/test-vectors.json"
    );
    let text = std::fs::read_to_string(path).expect("test vectors present in tests/data");
    let doc: Value = serde_json::from_str(&text).expect("valid JSON");
    doc["cases"]
        .as_array()
        .expect("cases array")
        .iter()
        .map(|c| Case {
            id: c["id"].as_str().unwrap().to_string(),
            inputs: c["inputs"].clone(),
            outputs: c["outputs"].clone(),
            intermediates: c.get("intermediates").filter(|v| !v.is_null()).cloned(),
        })
        .collect()
}

pub fn f(v: &Value) -> f64 {
    v.as_f64().expect("number")
}

/// The geometry of a case (its four angles in degrees).
pub fn geometry(inp: &Value) -> Geometry {
    Geometry::from_degrees(
        f(&inp["theta_i_deg"]),
        f(&inp["phi_i_deg"]),
        f(&inp["theta_r_deg"]),
        f(&inp["phi_r_deg"]),
    )
    .unwrap()
}

/// The material of a case, as a user would write it: σ when given with the hemispherical
/// normalization (so `a` is recomputed by the library), explicit `a`, `b` otherwise.
pub fn spec_of(inp: &Value) -> MaterialSpec {
    let hemisphere = inp["a_source"].as_str() == Some("hemisphere");
    MaterialSpec {
        name: None,
        n: f(&inp["N"][0]),
        k: f(&inp["N"][1]),
        sigma_deg: if hemisphere {
            Some(f(&inp["sigma_deg"]))
        } else {
            None
        },
        b: if hemisphere { None } else { Some(f(&inp["b"])) },
        a: if hemisphere { None } else { Some(f(&inp["a"])) },
        form: match inp["form"].as_str().unwrap() {
            "paper" => Form::Paper,
            _ => Form::Standard,
        },
        shadowing: inp["shadow"].as_bool().unwrap(),
        tau_deg: f(&inp["tau_deg"]),
        omega_deg: f(&inp["Omega_deg"]),
        azimuth_term: match inp["azimuth_term"].as_str().unwrap() {
            "eq3" => AzimuthTerm::Eq3,
            _ => AzimuthTerm::None,
        },
        rho_d: f(&inp["rho_D"]),
        rho_v: f(&inp["rho_V"]),
        spectral: None,
    }
}

pub fn matrix(v: &Value) -> [[f64; 4]; 4] {
    let mut m = [[0.0; 4]; 4];
    for (i, row) in m.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            *x = f(&v[i][j]);
        }
    }
    m
}

/// The spec's comparison (§7): f to rtol 1e-9; F entries relative to F00 (abs 1e-12 when
/// F00 = 0); DoLP to 1e-9 absolute.
pub fn assert_matches(
    id: &str,
    f_got: f64,
    f_ref: f64,
    m_got: &[[f64; 4]; 4],
    m_ref: &[[f64; 4]; 4],
    dolp_got: f64,
    dolp_ref: f64,
) {
    let close = |got: f64, want: f64, scale: f64| (got - want).abs() <= 1e-9 * scale.abs() + 1e-12;
    assert!(
        close(f_got, f_ref, f_ref),
        "{id}: f = {f_got}, expected {f_ref}"
    );
    let f00 = m_ref[0][0];
    for i in 0..4 {
        for j in 0..4 {
            assert!(
                close(m_got[i][j], m_ref[i][j], f00),
                "{id}: F[{i}][{j}] = {}, expected {}",
                m_got[i][j],
                m_ref[i][j]
            );
        }
    }
    assert!(
        (dolp_got - dolp_ref).abs() <= 1e-9,
        "{id}: dolp = {dolp_got}, expected {dolp_ref}"
    );
}
