//! The radiance of one surface in a scene: Kirchhoff's enclosure, band emission against
//! Planck's law, and a contrast scene refused.

use crate::common::{band_scene, example, write};
use polbrdf::analysis::thermal::planck;
use polbrdf_tasks::emission::{emission, EmissionRequest};
use polbrdf_tasks::radiance::{radiance, RadianceRequest, Views};
use polbrdf_tasks::spectrum::SpectralRequest;
use polbrdf_tasks::TaskError;

fn views() -> Views {
    Views::Grid {
        theta_deg: vec![0.0, 30.0, 60.0, 75.0],
        phi_deg: vec![0.0, 90.0],
    }
}

#[test]
fn an_isothermal_enclosure_is_unpolarized_blackbody_radiance() {
    // Sky and surface at 280 K: S = L_d·e0 + (B − L_d)·ε = B·e0 at every view.
    let dir = tempfile::tempdir().unwrap();
    let scene = write(
        dir.path(),
        "enclosure.toml",
        "wavelength_um = 10\n[surface]\ntemperature_k = 280\n[sky]\nmodel = \"thermal\"\n\
         temperature_k = 280\n",
    );
    let t = radiance(&RadianceRequest {
        material: example("soil-lwir.toml").display().to_string(),
        scene,
        views: views(),
    })
    .unwrap();
    let b = planck(10.0, 280.0);
    assert_eq!(t.rows.len(), 8);
    for (_, _, s) in &t.rows {
        assert!((s.0[0] / b - 1.0).abs() < 1e-9, "{s:?} vs {b}");
        assert!(s.dolp() < 1e-9, "{s:?}");
    }
}

#[test]
fn band_emission_of_a_constant_emissivity_is_epsilon_times_band_planck() {
    // A constant-index material has one emissivity at every wavelength: seen through a band
    // without sky, S = ∫R(λ)·B_λ(λ, T)·ε dλ = ε·∫R·B dλ.
    let dir = tempfile::tempdir().unwrap();
    let scene = band_scene(dir.path(), "b.toml", "[surface]\ntemperature_k = 300\n");
    let material = example("painted-aluminium-lwir.toml").display().to_string();
    let t = radiance(&RadianceRequest {
        material: material.clone(),
        scene,
        views: Views::List(vec![(0.0, 0.0), (60.0, 0.0)]),
    })
    .unwrap();
    let eps = emission(&EmissionRequest {
        material,
        theta_deg: vec![0.0, 60.0],
        temperature_k: None,
        spectral: SpectralRequest::wavelength(10.0),
    })
    .unwrap();
    // ∫R·B dλ of the trapezoid response 7.8–8–12–12.2 µm, by a fine midpoint rule.
    let response = |l: f64| {
        ((l - 7.8) / 0.2)
            .clamp(0.0, 1.0)
            .min(((12.2 - l) / 0.2).clamp(0.0, 1.0))
    };
    let n = 200_000;
    let h = (12.2 - 7.8) / f64::from(n);
    let band_planck: f64 = (0..n)
        .map(|i| {
            let l = 7.8 + (f64::from(i) + 0.5) * h;
            response(l) * planck(l, 300.0) * h
        })
        .sum();
    for ((_, _, s), e) in t.rows.iter().zip(&eps.rows) {
        for k in 0..2 {
            let want = e.emissivity.eps.0[k] * band_planck;
            let tol = 1e-5 * band_planck;
            assert!(
                (s.0[k] - want).abs() < tol,
                "S{k} {} vs ε·∫RB {want}",
                s.0[k]
            );
        }
    }
    // And with a band and a temperature, the emission job's Planck-weighted mean of a constant
    // emissivity is that emissivity.
    let weighted = emission(&EmissionRequest {
        material: example("painted-aluminium-lwir.toml").display().to_string(),
        theta_deg: vec![0.0, 60.0],
        temperature_k: Some(300.0),
        spectral: SpectralRequest {
            band: Some(example("lwir-8-12um.csv")),
            ..SpectralRequest::default()
        },
    })
    .unwrap();
    for (w, e) in weighted.rows.iter().zip(&eps.rows) {
        for k in 0..4 {
            assert!((w.emissivity.eps.0[k] - e.emissivity.eps.0[k]).abs() < 1e-12);
        }
    }
}

#[test]
fn a_contrast_scene_given_to_radiance_is_an_error_naming_file_and_table() {
    let dir = tempfile::tempdir().unwrap();
    for (name, extra, table) in [
        (
            "t.toml",
            "[target]\nmaterial = \"paint\"\ntemperature_k = 305\n",
            "[target]",
        ),
        (
            "b.toml",
            "[background]\ntemperature_k = 300\n",
            "[background]",
        ),
        (
            "s.toml",
            "[surface]\ntemperature_k = 300\n[target]\ntemperature_k = 305\n",
            "[target]",
        ),
    ] {
        let scene = write(
            dir.path(),
            name,
            &format!(
                "wavelength_um = 10\n[sky]\nmodel = \"thermal\"\ntemperature_k = 250\n{extra}"
            ),
        );
        let e = radiance(&RadianceRequest {
            material: "paint".into(),
            scene,
            views: views(),
        })
        .unwrap_err();
        let text = e.to_string();
        assert!(
            matches!(&e, TaskError::Io(io) if io.is_data_error()),
            "{e:?}"
        );
        assert!(text.contains(name) && text.contains(table), "{text}");
    }
}

#[test]
fn view_angles_are_checked() {
    let e = Views::Grid {
        theta_deg: vec![90.0],
        phi_deg: vec![],
    }
    .directions()
    .unwrap_err();
    assert!(
        matches!(&e, TaskError::Invalid { field, .. } if field == "theta_deg"),
        "{e}"
    );
    let d = Views::Grid {
        theta_deg: vec![],
        phi_deg: vec![],
    }
    .directions()
    .unwrap();
    assert_eq!(d.len(), 18, "default 0, 5, …, 85 at φ = 0");
}

/// The observer of `material` in the scene file `scene`.
fn observer_of(material: &str, scene: &std::path::Path) -> polbrdf::analysis::scene::Observer {
    let scene = polbrdf_tasks::scene::read_scene(scene).unwrap();
    let m = polbrdf_tasks::spectrum::NamedMaterial::load(material, "material").unwrap();
    polbrdf_tasks::scene::observer(&m, &scene, None, ("material", material)).unwrap()
}

/// The work bound (issue 35): a sky integral per view and spectral node under a clear sky, one
/// evaluation per view and node without one; refused above `MAX_WORK`, accepted at it, and
/// `radiance` refuses 1000 × 1000 views under a clear sky before computing any.
#[test]
fn radiance_is_bounded_by_the_work_its_views_imply() {
    use polbrdf_tasks::radiance::{check_work, MAX_WORK};
    let dir = tempfile::tempdir().unwrap();
    let paint = example("olive-paint.toml").display().to_string();
    let sun = "wavelength_um = 0.55\n[sun]\nzenith_deg = 40\nirradiance = 1000\n";
    let clear = write(
        dir.path(),
        "clear.toml",
        &format!("{sun}[sky]\nmodel = \"cie-clear\"\nirradiance = 100\n"),
    );
    let o = observer_of(&paint, &clear);
    assert!(o.has_azimuth_sky());
    let at_limit = (MAX_WORK / polbrdf::analysis::scene::SKY_INTEGRAL_WORK) as usize;
    assert_eq!(at_limit, 100_000);
    assert!(check_work(&o, at_limit).is_ok());
    match check_work(&o, at_limit + 1) {
        Err(TaskError::Usage { field, message }) => {
            assert_eq!(field, "views");
            assert!(
                message.contains("100001 view(s) × 1 spectral node(s)"),
                "{message}"
            );
        }
        other => panic!("{other:?}"),
    }
    // Without an azimuth-dependent sky, over a band: views × nodes evaluations.
    let band = band_scene(dir.path(), "band.toml", "[surface]\ntemperature_k = 300\n");
    let lwir = example("painted-aluminium-lwir.toml").display().to_string();
    let o = observer_of(&lwir, &band);
    assert!(!o.has_azimuth_sky());
    let nodes = o.spectral_nodes();
    assert!(nodes > 1);
    let at_limit = (MAX_WORK / nodes as f64).floor() as usize;
    assert!(check_work(&o, at_limit).is_ok());
    assert!(check_work(&o, at_limit + 1).is_err());
    // The job itself refuses before observing.
    let grid: Vec<f64> = (0..1000).map(|k| f64::from(k) * 0.089).collect();
    let e = radiance(&RadianceRequest {
        material: paint,
        scene: clear,
        views: Views::Grid {
            theta_deg: grid.clone(),
            phi_deg: grid,
        },
    })
    .unwrap_err();
    assert!(
        matches!(&e, TaskError::Usage { field, message }
            if field == "views" && message.contains("1000000 view(s)")),
        "{e:?}"
    );
}
