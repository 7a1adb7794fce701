//! The explorer's job: the full-Mueller map against the hemisphere job and the plane of
//! incidence, its mirror symmetry, materials from text as from files, and the contrast of
//! materials already read as the contrast of their files.

use crate::common::write;
use polbrdf_tasks::contrast::{contrast, contrast_of, ContrastRequest, RankRequest, SourceRequest};
use polbrdf_tasks::explore::{in_plane, mueller_map, IN_PLANE_STEP_DEG};
use polbrdf_tasks::hemisphere::{hemisphere, HemisphereRequest, LightRequest};
use polbrdf_tasks::spectrum::{NamedMaterial, SpectralRequest};

const PAINT: &str = "n = 1.65\nsigma_deg = 12\nrho_d = 0.03\nrho_v = 0.01\n";

fn close(a: f64, b: f64, scale: f64) -> bool {
    (a - b).abs() <= 1e-12 * a.abs().max(b.abs()).max(scale)
}

#[test]
fn the_mueller_map_is_the_hemisphere_map_with_the_whole_matrix() {
    let dir = tempfile::tempdir().unwrap();
    let file = write(dir.path(), "paint.toml", PAINT);
    let light = LightRequest {
        sun_zenith_deg: Some(35.0),
        sun_azimuth_deg: 20.0,
        stokes: Some([1.0, 0.3, -0.5, 0.2]),
    };
    let h = hemisphere(&HemisphereRequest {
        material: file.display().to_string(),
        light,
        grid_deg: (3.0, 6.0),
        spectral: SpectralRequest::default(),
    })
    .unwrap();
    let m = NamedMaterial::parse(PAINT, "paint.toml", "material").unwrap();
    let map = mueller_map(&m, &light, (3.0, 6.0), &SpectralRequest::default()).unwrap();
    assert_eq!(map.grid.len(), h.samples.len());
    let rows: Vec<Vec<f64>> = map.rows().collect();
    let hrows: Vec<Vec<f64>> = h.rows().collect();
    for (r, hr) in rows.iter().zip(&hrows) {
        assert_eq!(r.len(), 9 + 16);
        assert_eq!(r[..2], hr[..2], "the same directions");
        for k in 2..9 {
            assert!(
                close(r[k], hr[k], if k == 8 { 90.0 } else { hr[2] }),
                "{k}: {r:?} {hr:?}"
            );
        }
        // S_out = F·S_in with the normalized incident vector.
        let s_in = map.light.stokes().0;
        for (i, s) in r[3..7].iter().enumerate() {
            let f = &r[9 + 4 * i..13 + 4 * i];
            let fs: f64 = f.iter().zip(&s_in).map(|(a, b)| a * b).sum();
            assert!(close(*s, fs, r[9]));
        }
    }
}

#[test]
fn under_unpolarized_light_the_map_is_mirror_symmetric_about_the_plane_of_incidence() {
    let m = NamedMaterial::parse(PAINT, "paint.toml", "material").unwrap();
    let light = LightRequest::sun(40.0, 0.0);
    let map = mueller_map(&m, &light, (1.0, 2.0), &SpectralRequest::default()).unwrap();
    assert_eq!(map.grid.len(), 16_200);
    let (nt, np) = (map.grid.n_theta(), map.grid.n_phi());
    for k in (1..nt).step_by(7) {
        for j in 1..np {
            let (a, b) = (k * np + j, k * np + np - j);
            let (sa, sb) = (map.stokes[a], map.stokes[b]);
            let scale = sa.0[0];
            assert!(close(sa.0[0], sb.0[0], scale) && close(sa.0[1], sb.0[1], scale));
            assert!(
                close(sa.0[2], -sb.0[2], scale),
                "S2 changes sign in the mirror"
            );
            assert!(close(sa.dolp(), sb.dolp(), 1.0));
        }
    }
}

#[test]
fn the_in_plane_curves_are_the_map_in_the_plane_and_the_specular_curve_meets_them() {
    let m = NamedMaterial::parse(PAINT, "paint.toml", "material").unwrap();
    let light = LightRequest::sun(30.0, 0.0);
    let spectral = SpectralRequest::default();
    let c = in_plane(&m, &light, &spectral).unwrap();
    let map = mueller_map(&m, &light, (1.0, 2.0), &spectral).unwrap();
    let at = |t: f64| {
        let i = c.theta_r_deg.iter().position(|x| *x == t).unwrap();
        (c.brdf[i], c.dolp[i])
    };
    for t in [10.0, 30.0, 55.0] {
        // Specular side (φr = 180°) and source side (φr = 0°).
        for (signed, phi_index) in [(t, 90), (-t, 0)] {
            let node = (t as usize) * map.grid.n_phi() + phi_index;
            let (b, d) = at(signed);
            assert!(close(b, map.mueller[node][0], b), "{signed}");
            assert!(close(d, map.stokes[node].dolp(), 1.0), "{signed}");
        }
    }
    // The specular curve at θi = 30° is the plane's point θr = +30°.
    let i = c.theta_i_deg.iter().position(|x| *x == 30.0).unwrap();
    assert!(close(c.specular_dolp[i], at(30.0).1, 1.0));
    assert_eq!(
        c.theta_r_deg.len(),
        2 * (89.5 / IN_PLANE_STEP_DEG) as usize + 1
    );
    // Fresnel: unpolarized light reflected at Brewster's angle (n = 1.65: 58.8°) is nearly
    // fully polarized without a volume term.
    let smooth = NamedMaterial::parse("n = 1.65\nsigma_deg = 5\n", "s.toml", "m").unwrap();
    let c = in_plane(&smooth, &light, &spectral).unwrap();
    let brewster = 1.65_f64.atan().to_degrees();
    let i = c
        .theta_i_deg
        .iter()
        .position(|x| (x - brewster).abs() <= 0.25)
        .unwrap();
    assert!(c.specular_dolp[i] > 0.99, "{}", c.specular_dolp[i]);
}

#[test]
fn a_material_from_text_is_the_material_of_its_file_with_the_same_messages() {
    let dir = tempfile::tempdir().unwrap();
    let bad = "n = 1.5\nsigma_deg = -3\n";
    let file = write(dir.path(), "coat.toml", bad);
    let from_file = NamedMaterial::load(&file.display().to_string(), "target").unwrap_err();
    let from_text = NamedMaterial::parse(bad, "coat.toml", "target").unwrap_err();
    let (f, t) = (from_file.to_string(), from_text.to_string());
    assert_eq!(
        f.split_once("coat.toml").unwrap().1,
        t.split_once("coat.toml").unwrap().1
    );
    assert!(
        t.starts_with("target: coat.toml:2: field `sigma_deg`"),
        "{t}"
    );
    let good = NamedMaterial::parse(PAINT, "coat.toml", "target").unwrap();
    assert_eq!(good.name, "coat");
    assert_eq!(
        good.spec,
        polbrdf_io::parse_material(PAINT, "x.toml".as_ref()).unwrap()
    );
}

#[test]
fn the_contrast_of_materials_read_is_the_contrast_of_their_files() {
    let dir = tempfile::tempdir().unwrap();
    let glass = "n = 1.52\nsigma_deg = 5\n";
    let (t, b) = (
        write(dir.path(), "t.toml", PAINT),
        write(dir.path(), "b.toml", glass),
    );
    let light = LightRequest::sun(50.0, 10.0);
    let spectral = SpectralRequest::default();
    let rank = RankRequest {
        top: 4,
        ..RankRequest::default()
    };
    let files = contrast(&ContrastRequest {
        target: Some(t.display().to_string()),
        background: Some(b.display().to_string()),
        source: SourceRequest::Collimated {
            light,
            spectral: spectral.clone(),
        },
        grid_deg: (2.0, 4.0),
        rank,
    })
    .unwrap();
    let read = contrast_of(
        NamedMaterial::parse(PAINT, "t.toml", "target").unwrap(),
        NamedMaterial::parse(glass, "b.toml", "background").unwrap(),
        &light,
        &spectral,
        (2.0, 4.0),
        rank,
    )
    .unwrap();
    assert_eq!(files.top, read.top);
    assert_eq!(files.map.samples, read.map.samples);
    assert_eq!(files.best_json()["top"], read.best_json()["top"]);
    let e = contrast_of(
        NamedMaterial::parse(PAINT, "t.toml", "target").unwrap(),
        NamedMaterial::parse(glass, "b.toml", "background").unwrap(),
        &light,
        &spectral,
        (2.0, 4.0),
        RankRequest { top: 0, ..rank },
    )
    .unwrap_err();
    assert_eq!(e.to_string(), "top: must be at least 1");
}

#[test]
fn a_band_from_text_is_the_band_of_its_file_with_the_same_messages() {
    use polbrdf_tasks::spectrum::{SpectralText, SpectrumSource};
    let file = crate::common::example("lwir-8-12um.csv");
    let text = std::fs::read_to_string(&file).unwrap();
    let by_file = SpectralRequest {
        band: Some(file.clone()),
        band_step_um: Some(0.25),
        ..SpectralRequest::default()
    };
    let by_text = SpectralText {
        band: Some(("lwir-8-12um.csv".into(), text)),
        band_step_um: Some(0.25),
        ..SpectralText::default()
    };
    assert_eq!(
        SpectrumSource::spectrum(&by_text).unwrap(),
        by_file.spectrum().unwrap()
    );
    // The explorer's map over the band: the same numbers from either (bit for bit).
    let soil = NamedMaterial::load(
        crate::common::example("soil-lwir.toml").to_str().unwrap(),
        "material",
    )
    .unwrap();
    let light = LightRequest::sun(30.0, 0.0);
    let a = mueller_map(&soil, &light, (5.0, 10.0), &by_file).unwrap();
    let b = mueller_map(&soil, &light, (5.0, 10.0), &by_text).unwrap();
    assert_eq!(a.mueller, b.mueller);
    // A band the file reader refuses (wavelengths not increasing): its message, naming the
    // file and the line; and the step's, naming the field.
    let bad = SpectralText {
        band: Some((
            "band.csv".into(),
            "wavelength_um,response\n9,1\n8,1\n".into(),
        )),
        ..SpectralText::default()
    };
    let e = mueller_map(&soil, &light, (5.0, 10.0), &bad)
        .unwrap_err()
        .to_string();
    let dir = tempfile::tempdir().unwrap();
    let on_disk = SpectralRequest {
        band: Some(write(
            dir.path(),
            "band.csv",
            "wavelength_um,response\n9,1\n8,1\n",
        )),
        ..SpectralRequest::default()
    };
    let f = on_disk.spectrum().unwrap_err().to_string();
    assert!(e.starts_with("band.csv:3"), "{e}");
    assert_eq!(
        e.split_once("band.csv").unwrap().1,
        f.split_once("band.csv").unwrap().1
    );
    let step = SpectralText {
        band_step_um: Some(-1.0),
        ..by_text.clone()
    };
    assert_eq!(
        SpectrumSource::spectrum(&step).unwrap_err().to_string(),
        "band_step_um: -1: must be finite and > 0 (µm)"
    );
}

#[test]
fn a_scene_from_text_with_its_files_given_is_the_scene_of_the_files() {
    // The scene the web explorer writes: a band, a sun, a sky, both temperatures, and the
    // materials and the band beside it.
    let dir = tempfile::tempdir().unwrap();
    let scene = "[band]\nresponse = \"band.csv\"\nstep_um = 0.5\n[sun]\nzenith_deg = 30\n\
                 azimuth_deg = 20\nirradiance = 10\nstokes = [1, 0, 0, 0]\n[sky]\n\
                 model = \"thermal\"\ntemperature_k = 250\n[atmosphere]\ntransmittance = 0.9\n\
                 path_radiance = 0.5\n[target]\nmaterial = \"target.toml\"\ntemperature_k = 305\n\
                 [background]\nmaterial = \"background.toml\"\ntemperature_k = 300\n";
    let band = "wavelength_um,response\n8,1\n12,1\n";
    let glass = "n = 1.52\nsigma_deg = 5\n";
    let path = write(dir.path(), "scene.toml", scene);
    write(dir.path(), "band.csv", band);
    write(dir.path(), "target.toml", PAINT);
    write(dir.path(), "background.toml", glass);
    let rank = RankRequest {
        top: 3,
        ..RankRequest::default()
    };
    let request = |source| ContrastRequest {
        target: None,
        background: None,
        source,
        grid_deg: (5.0, 10.0),
        rank,
    };
    let files = contrast(&request(SourceRequest::Scene(path))).unwrap();
    let given = [
        ("target.toml", PAINT),
        ("background.toml", glass),
        ("band.csv", band),
    ]
    .map(|(n, t)| (n.to_string(), t.to_string()));
    let loaded = polbrdf_tasks::scene::parse_scene_with_files(scene, "scene.toml", &given).unwrap();
    let texts = contrast(&request(SourceRequest::Loaded(Box::new(loaded)))).unwrap();
    assert!(texts.is_scene());
    assert_eq!(files.map.samples, texts.map.samples);
    assert_eq!(files.top, texts.top);
    // Emission: the warmer target is brighter than the background at the nadir's neighbours.
    let s = &texts.map.samples[texts.map.grid.n_phi() + 1];
    assert!(s.radiance_difference() > 0.0, "{s:?}");
    // A temperature the reader refuses: its message, naming the scene's line and key.
    let bad = scene.replace("temperature_k = 305", "temperature_k = -5");
    let e = polbrdf_tasks::scene::parse_scene_with_files(&bad, "scene.toml", &given)
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("scene.toml:17: field `target.temperature_k`"),
        "{e}"
    );
}
