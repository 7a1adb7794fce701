//! Spectral setup: requests validated with the field named, materials at the band's nodes.

use polbrdf_tasks::spectrum::{materials_at, NamedMaterial, SpectralRequest};
use polbrdf_tasks::TaskError;

fn field_of(e: &TaskError) -> &str {
    match e {
        TaskError::Invalid { field, .. } | TaskError::Usage { field, .. } => field,
        other => panic!("not a request error: {other}"),
    }
}

#[test]
fn bad_spectral_values_name_their_field() {
    for (request, field) in [
        (SpectralRequest::wavelength(0.0), "wavelength_um"),
        (SpectralRequest::wavelength(f64::NAN), "wavelength_um"),
        (
            SpectralRequest {
                band: Some(crate::common::example("lwir-8-12um.csv")),
                band_step_um: Some(-1.0),
                ..SpectralRequest::default()
            },
            "band_step_um",
        ),
        (
            SpectralRequest {
                wavelength_um: Some(1.0),
                band: Some(crate::common::example("lwir-8-12um.csv")),
                band_step_um: None,
            },
            "wavelength_um",
        ),
    ] {
        let e = request.spectrum().unwrap_err();
        assert_eq!(field_of(&e), field, "{e}");
    }
}

#[test]
fn band_weights_are_a_mean_and_a_spectral_material_needs_a_spectrum() {
    let band = SpectralRequest {
        band: Some(crate::common::example("lwir-8-12um.csv")),
        ..SpectralRequest::default()
    }
    .spectrum()
    .unwrap();
    let soil = NamedMaterial::load(
        crate::common::example("soil-lwir.toml").to_str().unwrap(),
        "material",
    )
    .unwrap();
    let nodes = materials_at(&[&soil], band.as_ref()).unwrap();
    assert!(nodes.len() > 10);
    let total: f64 = nodes.iter().map(|(w, _)| w).sum();
    assert!(
        (total - 1.0).abs() < 1e-12,
        "weights of a mean sum to 1: {total}"
    );
    // Every node inside the band, each material at its own wavelength.
    for (_, ms) in &nodes {
        let l = ms[0].wavelength_um().unwrap();
        assert!((7.8..=12.2).contains(&l), "{l}");
    }
    let e = materials_at(&[&soil], None).unwrap_err();
    assert_eq!(field_of(&e), "material");
    assert!(e.to_string().contains("spectral index"), "{e}");
}

#[test]
fn an_unknown_preset_names_the_field_and_is_a_data_error() {
    let e = NamedMaterial::load("no-such-preset", "target").unwrap_err();
    assert_eq!(field_of(&e), "target");
    assert!(e.to_string().contains("no-such-preset"), "{e}");
}
