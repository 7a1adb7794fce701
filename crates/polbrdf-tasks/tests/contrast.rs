//! Contrast studies: a material against itself, the ranking's order and separation, a scene
//! symmetric about the normal, the request's validation.

use crate::common::{band_scene, example, write};
use polbrdf::analysis::contrast::{separation, Ranking};
use polbrdf_tasks::contrast::{contrast, ContrastRequest, RankRequest, SourceRequest};
use polbrdf_tasks::hemisphere::{self, LightRequest};
use polbrdf_tasks::spectrum::SpectralRequest;
use polbrdf_tasks::TaskError;

fn collimated(target: &str, background: &str, rank: RankRequest) -> ContrastRequest {
    ContrastRequest {
        target: Some(target.into()),
        background: Some(background.into()),
        source: SourceRequest::Collimated {
            light: LightRequest::sun(40.0, 30.0),
            spectral: SpectralRequest::default(),
        },
        grid_deg: (5.0, 10.0),
        rank,
    }
}

#[test]
fn a_material_against_itself_has_no_contrast_anywhere() {
    let s = contrast(&collimated("paint", "paint", RankRequest::default())).unwrap();
    assert_eq!(s.map.samples.len(), 18 * 36);
    for x in &s.map.samples {
        assert_eq!(x.delta_dolp(), 0.0);
        assert_eq!(x.polarization_contrast(), 0.0);
        assert_eq!(x.aolp_difference(), 0.0);
        assert_eq!(x.intensity_ratio(), 1.0);
    }
    for row in s.rows() {
        assert_eq!(row[4], 0.0, "delta_dolp column");
    }
    assert!(s.nulls.is_none(), "no null loci under a collimated source");
}

#[test]
fn the_ranking_is_best_first_apart_and_below_the_zenith_limit() {
    let target = example("olive-paint.toml").display().to_string();
    let background = example("dry-soil.toml").display().to_string();
    for by in [Ranking::DeltaDolp, Ranking::PolarizationContrast] {
        let rank = RankRequest {
            by,
            top: 6,
            min_separation_deg: 15.0,
            max_zenith_deg: 70.0,
            refine: false,
        };
        let s = contrast(&collimated(&target, &background, rank)).unwrap();
        assert_eq!(s.top.len(), 6);
        let best_anywhere = s
            .map
            .samples
            .iter()
            .filter(|x| x.theta_r <= 70f64.to_radians() + 1e-12)
            .map(|x| x.score(by))
            .fold(0.0, f64::max);
        assert_eq!(
            s.top[0].score(by),
            best_anywhere,
            "{by:?}: the best node first"
        );
        for (k, a) in s.top.iter().enumerate() {
            assert!(a.theta_r <= 70f64.to_radians() + 1e-12);
            for b in &s.top[k + 1..] {
                assert!(a.score(by) >= b.score(by), "{by:?}: sorted");
                assert!(separation(&a.direction(), &b.direction()) >= 15f64.to_radians() - 1e-12);
            }
        }
        // The sun is at φ = 30°: the map is mirror-symmetric about that plane (φ ↦ 60° − φ
        // maps the 10° grid onto itself).
        let np = s.map.grid.n_phi();
        for (i, a) in s.map.samples.iter().enumerate() {
            let (k, j) = (i / np, i % np);
            let m = &s.map.samples[k * np + (np + 6 - j) % np];
            let (x, y) = (a.score(by), m.score(by));
            assert!(
                (x - y).abs() <= 1e-9 * x.abs().max(1e-12),
                "{by:?}: {a:?} vs {m:?}"
            );
        }
        let json = s.best_json();
        assert_eq!(json["top"].as_array().unwrap().len(), 6);
        assert_eq!(json["ranking"]["by"], by.as_str());
        assert_eq!(json["best"], json["top"][0]);
    }
}

#[test]
fn a_symmetric_scene_has_rings_and_an_isothermal_target_is_unpolarized() {
    // Under a uniform 280 K sky, a target at 280 K sits in an isothermal enclosure:
    // unpolarized at every view; the null temperature of the sky is its own.
    let dir = tempfile::tempdir().unwrap();
    let scene = band_scene(
        dir.path(),
        "sym.toml",
        &format!(
            "[sky]\nmodel = \"thermal\"\ntemperature_k = 280\n[target]\nmaterial = {:?}\n\
             temperature_k = 280\n[background]\nmaterial = {:?}\ntemperature_k = 300\n",
            example("painted-aluminium-lwir.toml").display().to_string(),
            example("painted-aluminium-lwir.toml").display().to_string(),
        ),
    );
    let s = contrast(&ContrastRequest {
        target: None,
        background: None,
        source: SourceRequest::Scene(scene),
        grid_deg: (5.0, 30.0),
        rank: RankRequest::default(),
    })
    .unwrap();
    assert!(s.problem.is_azimuth_independent());
    let nulls = s.nulls.as_ref().unwrap();
    let t = nulls.uniform_sky_temperature_k.unwrap();
    assert!((t - 280.0).abs() < 1e-6, "{t}");
    let json = s.best_json();
    assert_eq!(
        json["polarization_null"]["uniform_sky_null_temperature_k"],
        t
    );
    assert_eq!(json["ranking"]["azimuth_independent"], true);
    for x in &s.map.samples {
        assert!(x.dolp_target() < 1e-9, "{x:?}");
        // The background, warmer than the sky, emits p-polarized light (S1 < 0) off normal.
        assert!(x.theta_r < 1e-9 || x.background.0[1] < 0.0, "{x:?}");
    }
    assert!(
        nulls.background.is_empty(),
        "S1 < 0 everywhere: no null on the background"
    );
    // Rings: the same values at every azimuth of a zenith.
    let np = s.map.grid.n_phi();
    for ring in s.map.samples.chunks(np) {
        for x in ring {
            assert_eq!(x.background, ring[0].background);
        }
    }
    let first_phi = s.map.grid.phis()[0];
    assert!(
        s.top.iter().all(|x| x.phi_r == first_phi),
        "rings listed at the first azimuth"
    );
    assert!(s.warnings.is_empty());
}

#[test]
fn the_request_is_validated_with_its_fields() {
    let bad = |rank: RankRequest, field: &str| {
        let e = contrast(&collimated("paint", "glass", rank)).unwrap_err();
        assert!(
            matches!(&e, TaskError::Invalid { field: f, .. } if f == field),
            "{e}"
        );
    };
    let d = RankRequest::default();
    bad(RankRequest { top: 0, ..d }, "top");
    bad(
        RankRequest {
            min_separation_deg: 181.0,
            ..d
        },
        "min_separation_deg",
    );
    bad(
        RankRequest {
            max_zenith_deg: 90.0,
            ..d
        },
        "max_zenith_deg",
    );
    let mut r = collimated("paint", "glass", d);
    r.target = None;
    let e = contrast(&r).unwrap_err();
    assert!(
        matches!(&e, TaskError::Usage { field, .. } if field == "target"),
        "{e}"
    );
    r.target = Some("paint".into());
    r.source = SourceRequest::Collimated {
        light: LightRequest {
            sun_zenith_deg: None,
            sun_azimuth_deg: 0.0,
            stokes: None,
        },
        spectral: SpectralRequest::default(),
    };
    let e = contrast(&r).unwrap_err();
    assert!(
        matches!(&e, TaskError::Usage { field, .. } if field == "sun_zenith_deg"),
        "{e}"
    );
    assert_eq!(d.min_separation_deg, 10.0);
    assert_eq!(d.max_zenith_deg, 80.0);
}

#[test]
fn a_loaded_scene_gives_the_study_of_its_file() {
    let file = example("lwir-scene.toml");
    let request = |source| ContrastRequest {
        target: None,
        background: None,
        source,
        grid_deg: (5.0, 10.0),
        rank: RankRequest::default(),
    };
    let from_file = contrast(&request(SourceRequest::Scene(file.clone()))).unwrap();
    let scene = polbrdf_io::read_scene(&file).unwrap();
    let loaded = contrast(&request(SourceRequest::Loaded(Box::new(scene)))).unwrap();
    assert_eq!(from_file.best_json(), loaded.best_json());
    let bits = |s: &polbrdf_tasks::contrast::ContrastStudy| -> Vec<u64> {
        s.rows().flatten().map(f64::to_bits).collect()
    };
    assert_eq!(bits(&from_file), bits(&loaded));
    assert!(!bits(&loaded).is_empty());
}

/// Issue 33: a scene's map is computed in blocks with a progress report after each — from
/// `(0, n)` to `(n, n)`, never backwards — and the blocks give the one-call map bit for bit
/// (a daylight scene: sun and an azimuth-dependent sky, the slowest case).
#[test]
fn a_scene_study_reports_its_progress_to_completion_with_the_same_numbers() {
    let request = ContrastRequest {
        target: None,
        background: None,
        source: SourceRequest::Scene(example("daylight-scene.toml")),
        grid_deg: (10.0, 30.0),
        rank: RankRequest::default(),
    };
    let mut calls = Vec::new();
    let study = polbrdf_tasks::contrast::contrast_with_progress(&request, &mut |done, total| {
        calls.push((done, total))
    })
    .unwrap();
    let n = study.map.grid.len();
    assert_eq!(calls.first(), Some(&(0, n)));
    assert_eq!(calls.last(), Some(&(n, n)));
    assert!(calls.len() > 2, "{calls:?}");
    assert!(
        calls.windows(2).all(|w| w[1].0 > w[0].0 && w[1].1 == n),
        "{calls:?}"
    );
    let whole = study.problem.map(&study.map.grid);
    let bits = |s: &[polbrdf::analysis::contrast::ContrastSample]| -> Vec<u64> {
        s.iter()
            .flat_map(|s| {
                [s.theta_r, s.phi_r]
                    .into_iter()
                    .chain(s.target.0)
                    .chain(s.background.0)
            })
            .map(f64::to_bits)
            .collect()
    };
    assert_eq!(bits(&study.map.samples), bits(&whole.samples));
    // Under a collimated source: one report, at the end.
    let mut calls = Vec::new();
    let rank = RankRequest::default();
    polbrdf_tasks::contrast::contrast_with_progress(
        &collimated("paint", "paint", rank),
        &mut |done, total| calls.push((done, total)),
    )
    .unwrap();
    assert_eq!(calls.len(), 1);
    assert_eq!(calls[0].0, calls[0].1);
}

/// The grid zeniths (1° steps, degrees) where `material`'s emissivity leaves [0, 1]: the
/// model's validity flag evaluated directly.
fn flagged_by_emissivity(material: &str) -> Vec<f64> {
    let m = polbrdf::preset(material).unwrap().build().unwrap();
    (0..90)
        .map(f64::from)
        .filter(|t| {
            !polbrdf::analysis::emissivity(&m, t.to_radians())
                .unwrap()
                .is_valid()
        })
        .collect()
}

#[test]
fn each_model_is_flagged_invalid_where_its_emissivity_leaves_0_1_as_the_map_flags_it() {
    // Paint reflects more than it receives seen near grazing (88° and 89° on a 1° grid); glass
    // does not. The study flags each material's own zeniths, as `polbrdf map` flags them.
    let mut r = collimated("paint", "glass", RankRequest::default());
    r.grid_deg = (1.0, 30.0);
    let s = contrast(&r).unwrap();
    let deg = |v: &[f64]| -> Vec<f64> { v.iter().map(|&t| hemisphere::deg(t)).collect() };
    let paint = flagged_by_emissivity("paint");
    assert!(!paint.is_empty() && paint[0] > 80.0, "{paint:?}");
    assert_eq!(deg(&s.invalid_zeniths.target), paint);
    assert_eq!(
        deg(&s.invalid_zeniths.background),
        flagged_by_emissivity("glass")
    );
    let map = hemisphere::hemisphere(&hemisphere::HemisphereRequest {
        material: "paint".into(),
        light: LightRequest::sun(40.0, 30.0),
        grid_deg: (1.0, 30.0),
        spectral: SpectralRequest::default(),
    })
    .unwrap();
    assert_eq!(map.invalid_zeniths, s.invalid_zeniths.target);
    // Swapped, the flags swap; `either` is their union.
    let mut swapped = r.clone();
    swapped.target = Some("glass".into());
    swapped.background = Some("paint".into());
    let w = contrast(&swapped).unwrap();
    assert_eq!(w.invalid_zeniths.background, s.invalid_zeniths.target);
    assert_eq!(w.invalid_zeniths.target, s.invalid_zeniths.background);
    let mut union: Vec<f64> = paint
        .iter()
        .chain(&flagged_by_emissivity("glass"))
        .copied()
        .collect();
    union.sort_by(f64::total_cmp);
    union.dedup();
    assert_eq!(deg(&s.invalid_zeniths.either()), union);
}

#[test]
fn in_a_scene_the_flags_are_those_of_the_materials_at_the_scenes_nodes() {
    // Paint's index does not depend on the wavelength: in a 10 µm scene its flags are its
    // flags at any wavelength.
    let dir = tempfile::tempdir().unwrap();
    let scene = write(
        dir.path(),
        "s.toml",
        "wavelength_um = 10\n[sky]\nmodel = \"thermal\"\ntemperature_k = 250\n[target]\n\
         temperature_k = 305\n[background]\ntemperature_k = 300\n",
    );
    let s = contrast(&ContrastRequest {
        target: Some("paint".into()),
        background: Some(example("soil-lwir.toml").display().to_string()),
        source: SourceRequest::Scene(scene),
        grid_deg: (1.0, 90.0),
        rank: RankRequest::default(),
    })
    .unwrap();
    let deg: Vec<f64> = s
        .invalid_zeniths
        .target
        .iter()
        .map(|&t| hemisphere::deg(t))
        .collect();
    assert_eq!(deg, flagged_by_emissivity("paint"));
}
