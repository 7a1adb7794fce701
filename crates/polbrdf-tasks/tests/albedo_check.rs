//! Albedo and the validity check: energy conservation and its violations.

use crate::common::write;
use polbrdf_tasks::albedo::{albedo, AlbedoRequest, Verdict};
use polbrdf_tasks::check::{check, CheckRequest};
use polbrdf_tasks::spectrum::SpectralRequest;
use polbrdf_tasks::TaskError;

#[test]
fn a_physical_preset_conserves_energy_and_the_paper_form_diverges() {
    let t = albedo(&AlbedoRequest {
        material: "paint".into(),
        theta_i_deg: vec![],
        spectral: SpectralRequest::default(),
    })
    .unwrap();
    assert_eq!(t.rows.len(), 18, "default 0, 5, …, 85");
    match t.verdict() {
        Verdict::Conserves { largest } => assert!(largest > 0.0 && largest <= 1.0),
        v => panic!("{v:?}"),
    }
    let dir = tempfile::tempdir().unwrap();
    let paper = write(
        dir.path(),
        "paper.toml",
        "n = 1.65\nsigma_deg = 15\nform = \"paper\"\nrho_d = 0.03\n",
    );
    let t = albedo(&AlbedoRequest {
        material: paper.display().to_string(),
        theta_i_deg: vec![0.0, 60.0],
        spectral: SpectralRequest::default(),
    })
    .unwrap();
    assert_eq!(t.verdict(), Verdict::Diverges { count: 2 });
    let c = check(&CheckRequest {
        material: paper.display().to_string(),
        grid_deg: 15.0,
        spectral: SpectralRequest::default(),
    })
    .unwrap();
    assert!(!c.passes());
    assert!(!c.worst_energy().1.conserves_energy());
    assert!(c.worst_realizability().1.realizable());
    let ok = check(&CheckRequest {
        material: "paint".into(),
        grid_deg: 15.0,
        spectral: SpectralRequest::default(),
    })
    .unwrap();
    assert!(ok.passes(), "the paint preset is physically valid");
}

#[test]
fn bad_angles_and_grids_name_their_field() {
    let e = albedo(&AlbedoRequest {
        material: "paint".into(),
        theta_i_deg: vec![90.0],
        spectral: SpectralRequest::default(),
    })
    .unwrap_err();
    assert!(
        matches!(&e, TaskError::Invalid { field, .. } if field == "theta_i_deg"),
        "{e}"
    );
    for g in [0.0, -1.0, 31.0, f64::NAN] {
        let e = check(&CheckRequest {
            material: "paint".into(),
            grid_deg: g,
            spectral: SpectralRequest::default(),
        })
        .unwrap_err();
        assert!(
            matches!(&e, TaskError::Invalid { field, .. } if field == "grid_deg"),
            "{e}"
        );
    }
}
