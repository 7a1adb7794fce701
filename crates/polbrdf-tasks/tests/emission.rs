//! Band emission: validation and the invalid angles reported, not clipped.

use crate::common::example;
use polbrdf_tasks::emission::{emission, EmissionRequest};
use polbrdf_tasks::spectrum::SpectralRequest;
use polbrdf_tasks::TaskError;

#[test]
fn emissivity_is_p_polarized_and_kirchhoff_bounded() {
    let t = emission(&EmissionRequest {
        material: example("painted-aluminium-lwir.toml").display().to_string(),
        theta_deg: vec![0.0, 30.0, 60.0, 85.0],
        temperature_k: None,
        spectral: SpectralRequest::default(),
    })
    .unwrap();
    assert!(t.invalid_angles().is_empty());
    let e: Vec<_> = t.rows.iter().map(|r| r.emissivity).collect();
    assert!(e[0].dolp() < 1e-9, "normal view: unpolarized");
    for w in e.windows(2) {
        // Increasingly p-polarized toward grazing (Wolff): ε1 < 0, DoLP growing.
        assert!(w[1].eps.0[1] < 0.0 && w[1].dolp() > w[0].dolp());
    }
    for r in &e {
        assert!(r.eps_s() >= 0.0 && r.eps_p() <= 1.0);
        assert!(r.reciprocity_residual() < 1e-9);
    }
}

#[test]
fn the_paint_presets_grazing_emissivity_is_reported_invalid() {
    // The `paint` preset's ε_s < 0 beyond 87° (README): reported, never clipped.
    let t = emission(&EmissionRequest {
        material: "paint".into(),
        theta_deg: vec![10.0, 89.0],
        temperature_k: None,
        spectral: SpectralRequest::default(),
    })
    .unwrap();
    assert_eq!(t.invalid_angles(), vec![89.0]);
    assert!(t.rows[1].emissivity.eps_s() < 0.0);
}

#[test]
fn emission_requests_are_validated() {
    let base = EmissionRequest {
        material: "paint".into(),
        theta_deg: vec![95.0],
        temperature_k: None,
        spectral: SpectralRequest::default(),
    };
    let field = |r: &EmissionRequest| match emission(r).unwrap_err() {
        TaskError::Invalid { field, .. } | TaskError::Usage { field, .. } => field,
        e => panic!("{e}"),
    };
    assert_eq!(field(&base), "theta_deg");
    let no_band = EmissionRequest {
        theta_deg: vec![10.0],
        temperature_k: Some(300.0),
        ..base.clone()
    };
    assert_eq!(field(&no_band), "temperature_k");
    let cold = EmissionRequest {
        spectral: SpectralRequest {
            band: Some(example("lwir-8-12um.csv")),
            ..SpectralRequest::default()
        },
        temperature_k: Some(-1.0),
        ..no_band
    };
    assert_eq!(field(&cold), "temperature_k");
}
