//! Scene files: each sky model and the sun read into the expected structs, sky tables in any
//! row order, files found relative to the scene file, and a table of bad inputs whose messages
//! name file, line and key.

use polbrdf::analysis::scene::Sun;
use polbrdf::analysis::sky::{SkyRadiance, TableSky, ZenithProfile};
use polbrdf::analysis::{Atmosphere, SkyModel, ThermalScene};
use polbrdf::{Band, Spectrum, Stokes};
use polbrdf_io::{parse_scene, parse_sky_table_csv, read_scene, Error, Scene, SceneObject};
use std::path::{Path, PathBuf};

const BAND: &str = "wavelength_um,response\n8,0\n9,1\n11,1\n12,0\n";
const SKY: &str = "zenith_deg,radiance\n0,1.0\n45,1.5\n90,3.0\n";
/// A sky table on the grid [0, 45, 90] × [0, 180], θ-major; s0 = 1 + θ/90 + φ/360.
const SKY_TABLE: &str = "theta_deg,phi_deg,s0,s1,s2,s3\n0,0,1,0,0,0\n0,180,1.5,0,0,0\n\
                         45,0,1.5,0.5,0,0\n45,180,2,0,0.5,0\n90,0,2,0,0,0.5\n90,180,2.5,-1,1,0\n";

fn parse(text: &str) -> Result<Scene, Error> {
    parse_scene(text, Path::new("scene.toml"))
}

/// A folder holding `files`, and the scene file `name` in it holding `scene`.
fn folder(files: &[(&str, &[u8])], name: &str, scene: &[u8]) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    for (f, content) in files.iter().chain([&(name, scene)]) {
        let p = dir.path().join(f);
        std::fs::create_dir_all(p.parent().unwrap()).unwrap();
        std::fs::write(&p, content).unwrap();
    }
    let p = dir.path().join(name);
    (dir, p)
}

fn no_sky(surface: Option<f64>) -> ThermalScene {
    ThermalScene {
        surface_temperature_k: surface,
        sky: SkyModel::None,
        atmosphere: Atmosphere::default(),
        sun: None,
    }
}

#[test]
fn no_sky_one_wavelength() {
    let s = parse("wavelength_um = 10.0\n[surface]\ntemperature_k = 300\n").unwrap();
    assert_eq!(s.path, Path::new("scene.toml"));
    assert_eq!(s.spectrum, Spectrum::Wavelength(10.0));
    assert_eq!(s.thermal, no_sky(Some(300.0)), "integers are numbers");
    assert_eq!(s.target, SceneObject::default());
    assert_eq!(s.background, SceneObject::default());
    // model = "none" said out loud, and no [surface]: no emission.
    let s = parse("wavelength_um = 4\n[sky]\nmodel = \"none\"\n").unwrap();
    assert_eq!(s.thermal, no_sky(None));
}

#[test]
fn uniform_sky_and_atmosphere() {
    let s = parse(
        "wavelength_um = 10\n[surface]\ntemperature_k = 310.5\n[sky]\nmodel = \"uniform\"\n\
         radiance = 1.5\n[atmosphere]\ntransmittance = 0.9\npath_radiance = 0.2\n",
    )
    .unwrap();
    assert_eq!(
        s.thermal,
        ThermalScene {
            surface_temperature_k: Some(310.5),
            sky: SkyModel::Uniform { radiance: 1.5 },
            atmosphere: Atmosphere {
                transmittance: 0.9,
                path_radiance: 0.2,
            },
            sun: None,
        }
    );
    // An inline table, a zero radiance, a BOM and CRLF line ends.
    let s = parse(
        "\u{feff}wavelength_um = 10\r\nsky = { model = \"uniform\", radiance = 0 }\r\n\
         [atmosphere]\r\ntransmittance = 0\r\n",
    )
    .unwrap();
    assert_eq!(s.thermal.sky, SkyModel::Uniform { radiance: 0.0 });
    assert_eq!(s.thermal.atmosphere.transmittance, 0.0);
    assert_eq!(s.thermal.atmosphere.path_radiance, 0.0, "default");
}

#[test]
fn thermal_sky() {
    let s =
        parse("wavelength_um = 8.5\n[sky]\nmodel = \"thermal\"\ntemperature_k = 250\n").unwrap();
    assert_eq!(s.spectrum, Spectrum::Wavelength(8.5));
    assert_eq!(
        s.thermal.sky,
        SkyModel::Thermal {
            temperature_k: 250.0
        }
    );
    assert_eq!(s.thermal.atmosphere, Atmosphere::default());
}

#[test]
fn sun_with_every_key() {
    let s = parse(
        "wavelength_um = 0.55\n[sun]\nzenith_deg = 40\nazimuth_deg = -30\nirradiance = 1000\n\
         stokes = [2, 1, 0, -0.5]\n",
    )
    .unwrap();
    assert_eq!(
        s.thermal,
        ThermalScene {
            sun: Some(Sun {
                zenith: 40f64.to_radians(),
                azimuth: (-30f64).to_radians(),
                irradiance: 1000.0,
                stokes: Stokes([1.0, 0.5, 0.0, -0.25]),
            }),
            ..no_sky(None)
        },
        "degrees in radians, the Stokes vector normalized to s0 = 1"
    );
    s.thermal.validate().unwrap();
    // A fully polarized sun, integers, an inline table.
    let s = parse(
        "wavelength_um = 0.55\nsun = { zenith_deg = 0, irradiance = 1, stokes = [4, 0, 0, 4] }\n",
    )
    .unwrap();
    let sun = s.thermal.sun.unwrap();
    assert_eq!(sun.stokes, Stokes([1.0, 0.0, 0.0, 1.0]));
    assert_eq!((sun.zenith, sun.azimuth), (0.0, 0.0));
    // A DoP above 1 by less than `--stokes` tolerates (1e-9) is brought to 1.
    let s = parse(
        "wavelength_um = 0.55\n[sun]\nzenith_deg = 10\nirradiance = 1\n\
         stokes = [1, 1.0000000001, 0, 0]\n",
    )
    .unwrap();
    assert_eq!(s.thermal.sun.unwrap().stokes, Stokes([1.0, 1.0, 0.0, 0.0]));
    s.thermal.validate().unwrap();
}

#[test]
fn sun_defaults() {
    // Without azimuth and Stokes vector: azimuth 0, unpolarized; 0 irradiance is a sun too;
    // a zenith angle just below 90° is above the horizon.
    let s = parse("wavelength_um = 0.55\n[sun]\nzenith_deg = 89.9\nirradiance = 0\n").unwrap();
    assert_eq!(
        s.thermal.sun,
        Some(Sun::unpolarized(89.9f64.to_radians(), 0.0, 0.0))
    );
    assert!(
        !s.thermal.is_azimuth_independent(),
        "a sun breaks the symmetry"
    );
    // No [sun]: no sun.
    let s = parse("wavelength_um = 0.55\n").unwrap();
    assert_eq!(s.thermal.sun, None);
    assert!(s.thermal.is_azimuth_independent());
}

#[test]
fn clear_sky() {
    let s = parse(
        "wavelength_um = 0.55\n[sun]\nzenith_deg = 30\nazimuth_deg = 90\nirradiance = 900\n\
         [sky]\nmodel = \"cie-clear\"\nirradiance = 80\n",
    )
    .unwrap();
    assert_eq!(
        s.thermal.sky,
        SkyModel::ClearSky {
            irradiance: 80.0,
            dop_max: 0.75
        },
        "dop_max defaults to 0.75"
    );
    assert_eq!(
        s.thermal.sun,
        Some(Sun::unpolarized(
            30f64.to_radians(),
            90f64.to_radians(),
            900.0
        ))
    );
    s.thermal.validate().unwrap();
    // The sky before the sun in the file, dop_max given, a zero irradiance, a sun of zero
    // irradiance (the sky takes its position only).
    let s = parse(
        "wavelength_um = 0.55\n[sky]\nmodel = \"cie-clear\"\ndop_max = 0.5\nirradiance = 0\n\
         [sun]\nzenith_deg = 60\nirradiance = 0\n",
    )
    .unwrap();
    assert_eq!(
        s.thermal.sky,
        SkyModel::ClearSky {
            irradiance: 0.0,
            dop_max: 0.5
        }
    );
}

#[test]
fn table_sky_rows_in_any_order() {
    let grid = TableSky::new(
        vec![0.0, 45.0, 90.0],
        vec![0.0, 180.0],
        vec![
            Stokes([1.0, 0.0, 0.0, 0.0]),
            Stokes([1.5, 0.0, 0.0, 0.0]),
            Stokes([1.5, 0.5, 0.0, 0.0]),
            Stokes([2.0, 0.0, 0.5, 0.0]),
            Stokes([2.0, 0.0, 0.0, 0.5]),
            Stokes([2.5, -1.0, 1.0, 0.0]),
        ],
    )
    .unwrap();
    let (_d, p) = folder(
        &[("sky.csv", SKY_TABLE.as_bytes())],
        "scene.toml",
        b"wavelength_um = 0.55\n[sky]\nmodel = \"table\"\nfile = \"sky.csv\"\n",
    );
    let s = read_scene(&p).unwrap();
    assert_eq!(s.thermal.sky, SkyModel::Table(grid.clone()));
    assert!(!s.thermal.is_azimuth_independent());
    assert_eq!(s.thermal.sun, None, "a table sky needs no sun");
    // The same nodes shuffled, the columns reordered with an extra one, −0, a BOM and CRLF.
    let shuffled = "\u{feff}s3,label,s1,phi_deg,s0,theta_deg,s2\r\n0,a,-1,180,2.5,90,1\r\n\
                    0,b,0,-0,1,0,0\r\n0,c,0.5,0,1.5,45,0\r\n0.5,d,0,0,2,90,0\r\n\
                    0,e,0,180,1.5,-0,0\r\n0,f,0,180,2,45,0.5\r\n";
    let t = parse_sky_table_csv(shuffled.as_bytes(), Path::new("t.csv")).unwrap();
    assert_eq!(t, grid);
    // One azimuth: an azimuth-independent table.
    let t = parse_sky_table_csv(
        b"theta_deg,phi_deg,s0,s1,s2,s3\n90,10,3,0,0,0\n0,10,1,0,0,0\n",
        Path::new("t.csv"),
    )
    .unwrap();
    assert_eq!(t.grid(), (&[0.0, 90.0][..], &[10.0][..]));
    let l = t.stokes(45f64.to_radians(), 4.0);
    assert!((l.0[0] - 2.0).abs() < 1e-12, "{l:?}");
}

#[test]
fn profile_sky_band_and_materials() {
    let (dir, p) = folder(
        &[
            ("lwir.csv", BAND.as_bytes()),
            ("sky.csv", SKY.as_bytes()),
            (
                "paint.toml",
                b"name = \"olive paint\"\nn = 1.6\nsigma_deg = 12\n",
            ),
            ("soil.toml", b"n = 1.4\nsigma_deg = 30\nrho_d = 0.1\n"),
        ],
        "scene.toml",
        b"[band]\nresponse = \"lwir.csv\"\nstep_um = 0.05\n\n[surface]\ntemperature_k = 300\n\n\
          [target]\nmaterial = \"paint.toml\"\ntemperature_k = 305\n[background]\n\
          material = \"soil.toml\"\ntemperature_k = 295\n\n[sky]\nmodel = \"profile\"\n\
          file = \"sky.csv\"\n",
    );
    let s = read_scene(&p).unwrap();
    assert_eq!(s.path, p);
    let band = Band::new(
        "lwir.csv",
        vec![8.0, 9.0, 11.0, 12.0],
        vec![0.0, 1.0, 1.0, 0.0],
    )
    .unwrap();
    assert_eq!(s.spectrum, Spectrum::Band(band, Some(0.05)));
    let profile = ZenithProfile::new(vec![0.0, 45.0, 90.0], vec![1.0, 1.5, 3.0]).unwrap();
    assert_eq!(
        s.thermal,
        ThermalScene {
            surface_temperature_k: Some(300.0),
            sky: SkyModel::Profile(profile),
            atmosphere: Atmosphere::default(),
            sun: None,
        }
    );
    s.thermal.validate().unwrap();
    let paint = polbrdf_io::load_material(dir.path().join("paint.toml").to_str().unwrap()).unwrap();
    let soil = polbrdf_io::load_material(dir.path().join("soil.toml").to_str().unwrap()).unwrap();
    assert_eq!(
        s.target,
        SceneObject {
            material: Some((paint, "olive paint".into())),
            temperature_k: Some(305.0),
        },
        "the display name is the material's name"
    );
    assert_eq!(
        s.background,
        SceneObject {
            material: Some((soil, "soil".into())),
            temperature_k: Some(295.0),
        },
        "without a name: the file stem"
    );
    // A band without a step takes the default one; a preset is a material.
    let (_d, p) = folder(
        &[("lwir.csv", BAND.as_bytes())],
        "s.toml",
        b"[band]\nresponse = \"lwir.csv\"\n[target]\nmaterial = \"glass\"\n",
    );
    let s = read_scene(&p).unwrap();
    assert!(matches!(s.spectrum, Spectrum::Band(_, None)));
    assert_eq!(
        s.target.material,
        Some((polbrdf::preset("glass").unwrap(), "glass".into()))
    );
    assert_eq!(s.target.temperature_k, None);
}

#[test]
fn relative_files_are_found_from_the_scene_folder() {
    // The scene two folders down, naming files beside it, below it and above it; the working
    // directory (the crate's folder) holds none of them.
    let (dir, p) = folder(
        &[
            ("a/b/data/lwir.csv", BAND.as_bytes()),
            ("a/sky.csv", SKY.as_bytes()),
            ("a/b/m.toml", b"n = 1.5\nsigma_deg = 5\n"),
        ],
        "a/b/scene.toml",
        b"[band]\nresponse = \"data/lwir.csv\"\n[target]\nmaterial = \"m.toml\"\n\
          [sky]\nmodel = \"profile\"\nfile = \"../sky.csv\"\n",
    );
    let s = read_scene(&p).unwrap();
    assert!(matches!(&s.spectrum, Spectrum::Band(b, None) if b.name() == "lwir.csv"));
    assert!(matches!(&s.thermal.sky, SkyModel::Profile(z) if z.table().0 == [0.0, 45.0, 90.0]));
    assert_eq!(s.target.material.as_ref().unwrap().1, "m");
    // An absolute path is taken as it is.
    let abs = dir.path().join("a/sky.csv");
    let text = format!(
        "wavelength_um = 10\n[sky]\nmodel = \"profile\"\nfile = {:?}\n",
        abs.to_str().unwrap()
    );
    let (_d, p) = folder(&[], "elsewhere/scene.toml", text.as_bytes());
    assert!(matches!(
        read_scene(&p).unwrap().thermal.sky,
        SkyModel::Profile(_)
    ));
    // The same scene text parsed with a path in another folder does not find them.
    let text = std::fs::read_to_string(dir.path().join("a/b/scene.toml")).unwrap();
    let e = parse_scene(&text, &dir.path().join("scene.toml")).unwrap_err();
    assert!(e.to_string().contains("data/lwir.csv: cannot read"), "{e}");
}

#[test]
fn files_given_as_texts_read_as_the_same_files_on_disk() {
    // The scene the web explorer writes: its band and materials beside it, given as texts.
    let scene = "[band]\nresponse = \"band.csv\"\nstep_um = 0.5\n[target]\n\
                 material = \"target.toml\"\ntemperature_k = 305\n[background]\n\
                 material = \"glass\"\n[sky]\nmodel = \"profile\"\nfile = \"sky.csv\"\n";
    let target = "name = \"panel\"\nn = 1.5\nk = 0.1\nsigma_deg = 5\n";
    let (_d, p) = folder(
        &[
            ("band.csv", BAND.as_bytes()),
            ("target.toml", target.as_bytes()),
            ("sky.csv", SKY.as_bytes()),
        ],
        "scene.toml",
        scene.as_bytes(),
    );
    let on_disk = read_scene(&p).unwrap();
    let texts: std::collections::BTreeMap<PathBuf, String> = [
        ("band.csv", BAND),
        ("target.toml", target),
        ("sky.csv", SKY),
    ]
    .into_iter()
    .map(|(f, t)| (PathBuf::from(f), t.to_string()))
    .collect();
    let given = polbrdf_io::parse_scene_with_files(scene, Path::new("scene.toml"), &texts).unwrap();
    assert_eq!(given.spectrum, on_disk.spectrum);
    assert_eq!(given.thermal, on_disk.thermal);
    assert_eq!(given.target, on_disk.target);
    assert_eq!(given.background, on_disk.background);
    assert_eq!(given.target.material.as_ref().unwrap().1, "panel");
    // An error inside a given file names that file and its line, within the scene's key.
    let mut bad = texts.clone();
    bad.insert(
        "band.csv".into(),
        "wavelength_um,response\n8,1\n7,1\n".into(),
    );
    let e = polbrdf_io::parse_scene_with_files(scene, Path::new("scene.toml"), &bad)
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("scene.toml:2: field `band.response`: band.csv:3"),
        "{e}"
    );
    // A file the scene names that is not given: an error naming it and the files given.
    let mut bad = texts.clone();
    bad.remove(Path::new("sky.csv"));
    let e = polbrdf_io::parse_scene_with_files(scene, Path::new("scene.toml"), &bad)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("field `sky.file`")
            && e.contains("sky.csv: no such file (the files given: band.csv, target.toml)"),
        "{e}"
    );
}

/// One bad input: the scene text (and files beside it), where the error points and what it
/// says.
struct Case {
    what: &'static str,
    scene: &'static [u8],
    files: &'static [(&'static str, &'static [u8])],
    /// The line of the scene file the message starts with (`None`: the file as a whole).
    line: Option<usize>,
    /// The key it names (`field `…``), if any.
    key: Option<&'static str>,
    /// Fragments the message must contain; `{d}` is the scene's folder.
    says: &'static [&'static str],
}

const fn case(
    what: &'static str,
    scene: &'static [u8],
    line: Option<usize>,
    key: Option<&'static str>,
    says: &'static [&'static str],
) -> Case {
    Case {
        what,
        scene,
        files: &[],
        line,
        key,
        says,
    }
}

const fn with_files(
    files: &'static [(&'static str, &'static [u8])],
    what: &'static str,
    scene: &'static [u8],
    line: Option<usize>,
    key: Option<&'static str>,
    says: &'static [&'static str],
) -> Case {
    Case {
        what,
        scene,
        files,
        line,
        key,
        says,
    }
}

const GOOD_BAND: &[(&str, &[u8])] = &[("b.csv", b"wavelength_um,response\n8,0\n9,1\n10,0\n")];

fn cases() -> Vec<Case> {
    vec![
        // Unknown keys and tables.
        case(
            "unknown top-level key",
            b"wavelength_um = 10\ncolour = \"red\"\n",
            Some(2),
            Some("colour"),
            &["unknown key", "`wavelength_um`", "[sky]"],
        ),
        case(
            "unknown table",
            b"wavelength_um = 10\n\n[moon]\nzenith_deg = 30\n",
            Some(3),
            Some("moon"),
            &[
                "unknown table [moon]",
                "known tables: [band], [surface]",
                "[sun], [sky]",
            ],
        ),
        with_files(
            GOOD_BAND,
            "unknown key in [band]",
            b"[band]\nresponse = \"b.csv\"\nstep = 0.1\n",
            Some(3),
            Some("band.step"),
            &["unknown key in [band]", "response, step_um"],
        ),
        case(
            "unknown key in [surface]",
            b"wavelength_um = 10\n[surface]\ntemperature = 300\n",
            Some(3),
            Some("surface.temperature"),
            &["unknown key in [surface]", "temperature_k"],
        ),
        case(
            "unknown key in [target]",
            b"wavelength_um = 10\n[target]\nmaterial_file = \"p.toml\"\n",
            Some(3),
            Some("target.material_file"),
            &["unknown key in [target]", "material, temperature_k"],
        ),
        case(
            "unknown key in [background]",
            b"wavelength_um = 10\n[background]\ntemp_k = 290\n",
            Some(3),
            Some("background.temp_k"),
            &["unknown key in [background]", "material, temperature_k"],
        ),
        case(
            "unknown key in [sky]",
            b"wavelength_um = 10\n[sky]\nmodel = \"uniform\"\nradiance = 1\nbrightness = 2\n",
            Some(5),
            Some("sky.brightness"),
            &[
                "unknown key in [sky]",
                "model, radiance, temperature_k, file",
            ],
        ),
        case(
            "unknown key in [atmosphere]",
            b"wavelength_um = 10\n[atmosphere]\ntau = 0.5\n",
            Some(3),
            Some("atmosphere.tau"),
            &["unknown key in [atmosphere]", "transmittance, path_radiance"],
        ),
        case(
            "a table inside [sky]",
            b"wavelength_um = 10\n[sky]\nmodel = \"none\"\n[sky.extra]\nx = 1\n",
            Some(4),
            Some("sky.extra"),
            &["unknown key in [sky]"],
        ),
        // Wrong types.
        case(
            "wavelength as a string",
            b"wavelength_um = \"10\"\n",
            Some(1),
            Some("wavelength_um"),
            &["expected a number (one wavelength, µm), got string"],
        ),
        case(
            "temperature as a string",
            b"wavelength_um = 10\n[surface]\ntemperature_k = \"300\"\n",
            Some(3),
            Some("surface.temperature_k"),
            &["expected a number (the surface temperature, K), got string"],
        ),
        case(
            "material as a number",
            b"wavelength_um = 10\n[target]\nmaterial = 3\n",
            Some(3),
            Some("target.material"),
            &["expected a string (a material file or a preset name), got integer"],
        ),
        case(
            "sky model as a boolean",
            b"wavelength_um = 10\n[sky]\nmodel = true\n",
            Some(3),
            Some("sky.model"),
            &["expected a string", "got boolean"],
        ),
        case(
            "sky as a number",
            b"wavelength_um = 10\nsky = 1\n",
            Some(2),
            Some("sky"),
            &["expected a table (the sky), got integer"],
        ),
        case(
            "sky as an array of tables",
            b"wavelength_um = 10\n[[sky]]\nmodel = \"none\"\n",
            Some(2),
            Some("sky"),
            &["expected a table", "got array"],
        ),
        case(
            "wavelength as a table",
            b"[wavelength_um]\nvalue = 10\n",
            Some(1),
            Some("wavelength_um"),
            &["expected a number", "got table"],
        ),
        // The spectrum.
        with_files(
            GOOD_BAND,
            "both wavelength_um and [band]",
            b"wavelength_um = 10\n[band]\nresponse = \"b.csv\"\n",
            Some(1),
            Some("wavelength_um"),
            &["give either `wavelength_um`", "[band] table (line 2)", "not both"],
        ),
        case(
            "neither wavelength_um nor [band]",
            b"[surface]\ntemperature_k = 300\n",
            None,
            None,
            &["no spectrum", "`wavelength_um`", "[band]"],
        ),
        case(
            "wavelength 0",
            b"# a comment\nwavelength_um = 0\n",
            Some(2),
            Some("wavelength_um"),
            &["0: a wavelength must be finite and > 0 (µm)"],
        ),
        case(
            "negative wavelength",
            b"wavelength_um = -1.5\n",
            Some(1),
            Some("wavelength_um"),
            &["-1.5: a wavelength must be finite and > 0"],
        ),
        case(
            "NaN wavelength",
            b"wavelength_um = nan\n",
            Some(1),
            Some("wavelength_um"),
            &["NaN: a wavelength must be finite"],
        ),
        case(
            "infinite wavelength",
            b"wavelength_um = inf\n",
            Some(1),
            Some("wavelength_um"),
            &["inf: a wavelength must be finite"],
        ),
        with_files(
            GOOD_BAND,
            "step 0",
            b"[band]\nresponse = \"b.csv\"\nstep_um = 0\n",
            Some(3),
            Some("band.step_um"),
            &["0: a quadrature step must be finite and > 0 (µm)"],
        ),
        with_files(
            GOOD_BAND,
            "negative step",
            b"[band]\nresponse = \"b.csv\"\nstep_um = -0.1\n",
            Some(3),
            Some("band.step_um"),
            &["-0.1: a quadrature step must be finite and > 0"],
        ),
        case(
            "[band] without response",
            b"[surface]\ntemperature_k = 300\n[band]\nstep_um = 0.1\n",
            Some(3),
            Some("band"),
            &["missing required key `response`", "wavelength_um,response"],
        ),
        case(
            "empty band file name",
            b"[band]\nresponse = \"\"\n",
            Some(2),
            Some("band.response"),
            &["expected the path of a file, got an empty string"],
        ),
        case(
            "band file missing",
            b"[band]\nresponse = \"nope.csv\"\n",
            Some(2),
            Some("band.response"),
            &["{d}/nope.csv: cannot read"],
        ),
        with_files(
            &[("b.csv", b"wavelength_um,response\n8,0\n9,x\n10,0\n")],
            "band file with a bad number",
            b"[band]\nresponse = \"b.csv\"\n",
            Some(2),
            Some("band.response"),
            &["{d}/b.csv:3: field `response`: expected a number, got \"x\""],
        ),
        with_files(
            &[(
                "b.csv",
                b"response,wavelength_um\n0,8\n1,9\n-1,10\n",
            )],
            "band file with a negative response",
            b"[band]\nresponse = \"b.csv\"\n",
            Some(2),
            Some("band.response"),
            &["{d}/b.csv:4: field `response`", "must be finite and >= 0"],
        ),
        with_files(
            &[("b.csv", b"wavelength_um,response\n8,0\n9,1\n9,0\n")],
            "band file with a repeated wavelength",
            b"[band]\nresponse = \"b.csv\"\n",
            Some(2),
            Some("band.response"),
            &["{d}/b.csv:4: field `wavelength_um`", "increase strictly"],
        ),
        with_files(
            &[("b.csv", b"lambda,response\n8,0\n9,1\n")],
            "band file without its wavelength column",
            b"[band]\nresponse = \"b.csv\"\n",
            Some(2),
            Some("band.response"),
            &["{d}/b.csv: missing column(s) wavelength_um"],
        ),
        // Sky models.
        case(
            "unknown sky model",
            b"wavelength_um = 10\n[sky]\nmodel = \"cloudy\"\n",
            Some(3),
            Some("sky.model"),
            &[
                "unknown sky model \"cloudy\"",
                "\"none\", \"uniform\", \"thermal\", \"profile\"",
            ],
        ),
        case(
            "radiance with the thermal model",
            b"wavelength_um = 10\n[sky]\nmodel = \"thermal\"\ntemperature_k = 250\nradiance = 1\n",
            Some(5),
            Some("sky.radiance"),
            &[
                "`radiance` is not a key of sky model \"thermal\"",
                "whose keys are temperature_k",
                "belongs to model = \"uniform\"",
            ],
        ),
        case(
            "temperature_k with the uniform model",
            b"wavelength_um = 10\n[sky]\ntemperature_k = 250\nmodel = \"uniform\"\nradiance = 1\n",
            Some(3),
            Some("sky.temperature_k"),
            &[
                "not a key of sky model \"uniform\" (whose keys are radiance)",
                "belongs to model = \"thermal\"",
            ],
        ),
        case(
            "a profile file with the default model",
            b"wavelength_um = 10\n[sky]\nfile = \"sky.csv\"\n",
            Some(3),
            Some("sky.file"),
            &[
                "not a key of sky model \"none\" (the default, which takes no keys)",
                "belongs to model = \"profile\"",
            ],
        ),
        case(
            "uniform without radiance",
            b"wavelength_um = 10\n[sky]\nmodel = \"uniform\"\n",
            Some(3),
            Some("sky.model"),
            &["sky model \"uniform\" requires the key `radiance`", "W·m⁻²·sr⁻¹·µm⁻¹"],
        ),
        case(
            "thermal without temperature",
            b"wavelength_um = 10\n[sky]\n\nmodel = \"thermal\"\n",
            Some(4),
            Some("sky.model"),
            &["sky model \"thermal\" requires the key `temperature_k`"],
        ),
        case(
            "profile without file",
            b"wavelength_um = 10\n[sky]\nmodel = \"profile\"\n",
            Some(3),
            Some("sky.model"),
            &["sky model \"profile\" requires the key `file`", "zenith_deg,radiance"],
        ),
        case(
            "negative sky radiance",
            b"wavelength_um = 10\n[sky]\nmodel = \"uniform\"\nradiance = -1\n",
            Some(4),
            Some("sky.radiance"),
            &["invalid parameter `sky.radiance` = -1: must be finite, >= 0 and at most 1e150"],
        ),
        case(
            "sky temperature 0",
            b"wavelength_um = 10\n[sky]\nmodel = \"thermal\"\ntemperature_k = 0\n",
            Some(4),
            Some("sky.temperature_k"),
            &["`sky.temperature_k` = 0: a temperature must be finite and > 0 K"],
        ),
        // Temperatures and the atmosphere.
        case(
            "surface temperature 0",
            b"wavelength_um = 10\n[surface]\ntemperature_k = 0\n",
            Some(3),
            Some("surface.temperature_k"),
            &["invalid parameter `surface.temperature_k` = 0: a temperature must be finite and > 0 K"],
        ),
        case(
            "negative surface temperature",
            b"wavelength_um = 10\n[surface]\ntemperature_k = -5\n",
            Some(3),
            Some("surface.temperature_k"),
            &["`surface.temperature_k` = -5"],
        ),
        case(
            "negative target temperature",
            b"wavelength_um = 10\n[target]\nmaterial = \"paint\"\ntemperature_k = -1\n",
            Some(4),
            Some("target.temperature_k"),
            &["`target.temperature_k` = -1: a temperature must be finite and > 0 K"],
        ),
        case(
            "NaN background temperature",
            b"wavelength_um = 10\n[background]\ntemperature_k = nan\n",
            Some(3),
            Some("background.temperature_k"),
            &["`background.temperature_k` = NaN"],
        ),
        case(
            "transmittance 1.5",
            b"wavelength_um = 10\n[atmosphere]\npath_radiance = 0\ntransmittance = 1.5\n",
            Some(4),
            Some("atmosphere.transmittance"),
            &["`atmosphere.transmittance` = 1.5: must lie in [0, 1]"],
        ),
        case(
            "negative transmittance",
            b"wavelength_um = 10\n[atmosphere]\ntransmittance = -0.1\n",
            Some(3),
            Some("atmosphere.transmittance"),
            &["must lie in [0, 1]"],
        ),
        case(
            "negative path radiance",
            b"wavelength_um = 10\n[atmosphere]\npath_radiance = -0.2\n",
            Some(3),
            Some("atmosphere.path_radiance"),
            &["`atmosphere.path_radiance` = -0.2: must be finite, >= 0 and at most 1e150"],
        ),
        // Sky profile files.
        with_files(
            &[("sky.csv", b"zenith_deg,radiance\n10,1\n90,2\n")],
            "profile not starting at 0°",
            b"wavelength_um = 10\n[sky]\nmodel = \"profile\"\nfile = \"sky.csv\"\n",
            Some(4),
            Some("sky.file"),
            &["{d}/sky.csv: a sky profile must cover the whole sky: from zenith 0° to 90°"],
        ),
        with_files(
            &[("sky.csv", b"zenith_deg,radiance\n0,1\n80,2\n")],
            "profile not ending at 90°",
            b"wavelength_um = 10\n[sky]\nmodel = \"profile\"\nfile = \"sky.csv\"\n",
            Some(4),
            Some("sky.file"),
            &["{d}/sky.csv: a sky profile must cover the whole sky"],
        ),
        with_files(
            &[("sky.csv", b"radiance,zenith_deg\r\n1,0\r\n2,50\r\n3,40\r\n4,90\r\n")],
            "non-increasing zenith",
            b"wavelength_um = 10\n[sky]\nmodel = \"profile\"\nfile = \"sky.csv\"\n",
            Some(4),
            Some("sky.file"),
            &["{d}/sky.csv:4: field `zenith_deg`", "= 40", "increase strictly"],
        ),
        with_files(
            &[("sky.csv", b"\xef\xbb\xbfzenith_deg,radiance\n0,1\n45,-2\n90,1\n")],
            "negative radiance in the profile",
            b"wavelength_um = 10\n[sky]\nmodel = \"profile\"\nfile = \"sky.csv\"\n",
            Some(4),
            Some("sky.file"),
            &["{d}/sky.csv:3: field `radiance`", "= -2", "must be finite, >= 0 and at most 1e150"],
        ),
        with_files(
            &[("sky.csv", b"zenith_deg,radiance\n0,1\n95,1\n")],
            "zenith beyond 90°",
            b"wavelength_um = 10\n[sky]\nmodel = \"profile\"\nfile = \"sky.csv\"\n",
            Some(4),
            Some("sky.file"),
            &["{d}/sky.csv:3: field `zenith_deg`", "must lie in [0°, 90°]"],
        ),
        with_files(
            &[("sky.csv", b"zenith_deg\n0\n90\n")],
            "profile without its radiance column",
            b"wavelength_um = 10\n[sky]\nmodel = \"profile\"\nfile = \"sky.csv\"\n",
            Some(4),
            Some("sky.file"),
            &["{d}/sky.csv: missing column(s) radiance"],
        ),
        case(
            "profile file missing",
            b"wavelength_um = 10\n[sky]\nmodel = \"profile\"\nfile = \"sky.csv\"\n",
            Some(4),
            Some("sky.file"),
            &["{d}/sky.csv: cannot read"],
        ),
        // The sun.
        case(
            "unknown key in [sun]",
            b"wavelength_um = 0.55\n[sun]\nzenith_deg = 30\nirradiance = 1000\nelevation_deg = 60\n",
            Some(5),
            Some("sun.elevation_deg"),
            &[
                "unknown key in [sun]",
                "zenith_deg, azimuth_deg, date_time, latitude_deg, longitude_deg, elevation_m, pressure_hpa, temperature_c, delta_t_s, phi0_azimuth_deg, irradiance, stokes",
            ],
        ),
        case(
            "sun on the horizon",
            b"wavelength_um = 0.55\n[sun]\nzenith_deg = 90\nirradiance = 1000\n",
            Some(3),
            Some("sun.zenith_deg"),
            &["invalid parameter `sun.zenith_deg` = 90: the sun must be above the horizon: in [0, 90) degrees"],
        ),
        case(
            "sun below the horizon",
            b"wavelength_um = 0.55\n[sun]\nirradiance = 1000\nzenith_deg = 95\n",
            Some(4),
            Some("sun.zenith_deg"),
            &["`sun.zenith_deg` = 95: the sun must be above the horizon"],
        ),
        case(
            "sun below the horizon with a clear sky",
            b"wavelength_um = 0.55\n[sky]\nmodel = \"cie-clear\"\nirradiance = 50\n[sun]\n\
              zenith_deg = 95\nirradiance = 1000\n",
            Some(6),
            Some("sun.zenith_deg"),
            &["`sun.zenith_deg` = 95: the sun must be above the horizon: in [0, 90) degrees"],
        ),
        case(
            "negative sun zenith",
            b"wavelength_um = 0.55\n[sun]\nzenith_deg = -5\nirradiance = 1000\n",
            Some(3),
            Some("sun.zenith_deg"),
            &["`sun.zenith_deg` = -5"],
        ),
        case(
            "NaN sun zenith",
            b"wavelength_um = 0.55\n[sun]\nzenith_deg = nan\nirradiance = 1000\n",
            Some(3),
            Some("sun.zenith_deg"),
            &["`sun.zenith_deg` = NaN"],
        ),
        case(
            "infinite sun azimuth",
            b"wavelength_um = 0.55\n[sun]\nzenith_deg = 30\nazimuth_deg = -inf\nirradiance = 1\n",
            Some(4),
            Some("sun.azimuth_deg"),
            &["`sun.azimuth_deg` = -inf: must be finite"],
        ),
        case(
            "[sun] without zenith",
            b"wavelength_um = 0.55\n\n[sun]\nirradiance = 1000\n",
            Some(3),
            Some("sun"),
            &["missing required key `zenith_deg`", "in [0, 90)"],
        ),
        case(
            "[sun] without irradiance",
            b"wavelength_um = 0.55\n[sun]\nzenith_deg = 30\n",
            Some(2),
            Some("sun"),
            &["missing required key `irradiance`", "normal to its beam, W·m⁻²·µm⁻¹"],
        ),
        case(
            "negative sun irradiance",
            b"wavelength_um = 0.55\n[sun]\nzenith_deg = 30\nirradiance = -1000\n",
            Some(4),
            Some("sun.irradiance"),
            &["invalid parameter `sun.irradiance` = -1000: must be finite and >= 0"],
        ),
        case(
            "sun irradiance as a string",
            b"wavelength_um = 0.55\n[sun]\nzenith_deg = 30\nirradiance = \"bright\"\n",
            Some(4),
            Some("sun.irradiance"),
            &["expected a number", "got string"],
        ),
        case(
            "sun Stokes vector of 3 numbers",
            b"wavelength_um = 0.55\n[sun]\nzenith_deg = 30\nirradiance = 1\nstokes = [1, 0, 0]\n",
            Some(5),
            Some("sun.stokes"),
            &["expected 4 numbers [s0, s1, s2, s3], got 3 ([1, 0, 0])"],
        ),
        case(
            "sun Stokes vector of DoP above 1",
            b"wavelength_um = 0.55\n[sun]\nzenith_deg = 30\nirradiance = 1\nstokes = [1, 0.8, 0.8, 0]\n",
            Some(5),
            Some("sun.stokes"),
            &["[1, 0.8, 0.8, 0]: the degree of polarization", "exceeds 1"],
        ),
        case(
            "sun Stokes vector of s0 0",
            b"wavelength_um = 0.55\n[sun]\nzenith_deg = 30\nirradiance = 1\nstokes = [0, 0, 0, 0]\n",
            Some(5),
            Some("sun.stokes"),
            &["s0 (the intensity) must be > 0"],
        ),
        case(
            "sun Stokes vector with a NaN",
            b"wavelength_um = 0.55\n[sun]\nzenith_deg = 30\nirradiance = 1\nstokes = [1, nan, 0, 0]\n",
            Some(5),
            Some("sun.stokes"),
            &["[1, NaN, 0, 0]: every Stokes parameter must be finite"],
        ),
        case(
            "sun Stokes vector holding a string",
            b"wavelength_um = 0.55\n[sun]\nzenith_deg = 30\nirradiance = 1\nstokes = [1, \"0\", 0, 0]\n",
            Some(5),
            Some("sun.stokes"),
            &["expected an array of numbers", "got an array holding a string"],
        ),
        case(
            "sun Stokes vector as a number",
            b"wavelength_um = 0.55\n[sun]\nzenith_deg = 30\nirradiance = 1\nstokes = 1\n",
            Some(5),
            Some("sun.stokes"),
            &["expected an array of numbers (the sun's Stokes vector [s0, s1, s2, s3]), got integer"],
        ),
        // The clear sky.
        case(
            "cie-clear without a sun",
            b"wavelength_um = 0.55\n[sky]\nmodel = \"cie-clear\"\nirradiance = 50\n",
            Some(3),
            Some("sky.model"),
            &["sky model \"cie-clear\" requires a [sun] table", "sun's position"],
        ),
        case(
            "cie-clear without irradiance",
            b"wavelength_um = 0.55\n[sun]\nzenith_deg = 30\nirradiance = 1\n[sky]\nmodel = \"cie-clear\"\n",
            Some(6),
            Some("sky.model"),
            &["sky model \"cie-clear\" requires the key `irradiance`", "horizontal"],
        ),
        case(
            "cie-clear negative irradiance",
            b"wavelength_um = 0.55\n[sun]\nzenith_deg = 30\nirradiance = 1\n[sky]\nmodel = \"cie-clear\"\nirradiance = -50\n",
            Some(7),
            Some("sky.irradiance"),
            &["invalid parameter `sky.irradiance` = -50: must be finite, >= 0 and at most 1e150"],
        ),
        case(
            "cie-clear dop_max 1.5",
            b"wavelength_um = 0.55\n[sun]\nzenith_deg = 30\nirradiance = 1\n[sky]\nmodel = \"cie-clear\"\nirradiance = 50\ndop_max = 1.5\n",
            Some(8),
            Some("sky.dop_max"),
            &["invalid parameter `sky.dop_max` = 1.5: must lie in [0, 1]"],
        ),
        case(
            "dop_max with the uniform model",
            b"wavelength_um = 0.55\n[sky]\nmodel = \"uniform\"\nradiance = 1\ndop_max = 0.5\n",
            Some(5),
            Some("sky.dop_max"),
            &["`dop_max` is not a key of sky model \"uniform\"", "belongs to model = \"cie-clear\""],
        ),
        // Sky tables.
        case(
            "table without file",
            b"wavelength_um = 0.55\n[sky]\nmodel = \"table\"\n",
            Some(3),
            Some("sky.model"),
            &["sky model \"table\" requires the key `file`", "theta_deg,phi_deg,s0,s1,s2,s3"],
        ),
        case(
            "table file missing",
            b"wavelength_um = 0.55\n[sky]\nmodel = \"table\"\nfile = \"sky.csv\"\n",
            Some(4),
            Some("sky.file"),
            &["{d}/sky.csv: cannot read"],
        ),
        with_files(
            &[("sky.csv", b"theta_deg,phi_deg,s0,s1,s2,s3\n0,0,1,0,0,0\n0,180,1,0,0,0\n45,0,1,0,0,0\n90,0,1,0,0,0\n90,180,1,0,0,0\n")],
            "table with a hole",
            b"wavelength_um = 0.55\n[sky]\nmodel = \"table\"\nfile = \"sky.csv\"\n",
            Some(4),
            Some("sky.file"),
            &[
                "{d}/sky.csv: the sky table has a hole: no row for the node (theta_deg = 45, phi_deg = 180)",
                "zenith angles [0, 45, 90] × azimuths [0, 180] has 6 nodes",
                "1 of them is missing (5 rows given)",
            ],
        ),
        with_files(
            &[("sky.csv", b"theta_deg,phi_deg,s0,s1,s2,s3\n0,0,1,0,0,0\n90,0,1,0,0,0\n0,0.0,2,0,0,0\n")],
            "table with a node given twice",
            b"wavelength_um = 0.55\n[sky]\nmodel = \"table\"\nfile = \"sky.csv\"\n",
            Some(4),
            Some("sky.file"),
            &["{d}/sky.csv:4: field `theta_deg,phi_deg`: the node (theta_deg = 0, phi_deg = 0) is given twice: at lines 2 and 4"],
        ),
        with_files(
            &[("sky.csv", b"theta_deg,phi_deg,s0,s1,s2,s3\n0,0,1,0,0,0\n0,90,1,0,0,0\n80,0,1,0,0,0\n80,90,1,0,0,0\n")],
            "table not reaching zenith 90",
            b"wavelength_um = 0.55\n[sky]\nmodel = \"table\"\nfile = \"sky.csv\"\n",
            Some(4),
            Some("sky.file"),
            &["{d}/sky.csv: a sky table must cover the whole sky: zenith angles from 0° to 90°"],
        ),
        with_files(
            &[("sky.csv", b"theta_deg,phi_deg,s0,s1,s2,s3\n0,0,1,0,0,0\n90,0,1,0,0,0\n0,90,1,0,0,0\n90,90,-0.5,0,0,0\n")],
            "table with s0 below 0",
            b"wavelength_um = 0.55\n[sky]\nmodel = \"table\"\nfile = \"sky.csv\"\n",
            Some(4),
            Some("sky.file"),
            &["{d}/sky.csv:5: field `s0`: invalid parameter `s0` = -0.5 (at the node theta_deg = 90, phi_deg = 90): must be >= 0"],
        ),
        with_files(
            &[("sky.csv", b"phi_deg,theta_deg,s0,s1,s2,s3\n0,0,1,0,0,0\n0,90,1,0.6,0.8,0.1\n")],
            "table with a DoP above 1",
            b"wavelength_um = 0.55\n[sky]\nmodel = \"table\"\nfile = \"sky.csv\"\n",
            Some(4),
            Some("sky.file"),
            &["{d}/sky.csv:3: field `s0`", "degree of polarization", "exceeds 1"],
        ),
        with_files(
            &[("sky.csv", b"theta_deg,phi_deg,s0,s1,s2,s3\n0,0,1,0,0,0\n90,0,-1e300,0,0,0\n")],
            "table with a huge negative s0 (shown in exponent form)",
            b"wavelength_um = 0.55\n[sky]\nmodel = \"table\"\nfile = \"sky.csv\"\n",
            Some(4),
            Some("sky.file"),
            &["{d}/sky.csv:3: field `s0`: invalid parameter `s0` = -1e300 (at the node theta_deg = 90, phi_deg = 0)"],
        ),
        with_files(
            &[("sky.csv", b"theta_deg,phi_deg,s0,s1,s2,s3\n0,0,1,0,0,0\n90,0,1,0,0,0\n90,1e-300,1,0,0,0\n")],
            "table with a hole at a tiny azimuth (shown in exponent form)",
            b"wavelength_um = 0.55\n[sky]\nmodel = \"table\"\nfile = \"sky.csv\"\n",
            Some(4),
            Some("sky.file"),
            &["no row for the node (theta_deg = 0, phi_deg = 1e-300)", "azimuths [0, 1e-300]"],
        ),
        with_files(
            &[("sky.csv", b"theta_deg,phi_deg,s0,s1,s2,s3\n0,0,1,0,0,0\n90,0,1,0,0,0\n0,360,1,0,0,0\n90,360,1,0,0,0\n")],
            "table with azimuth 360",
            b"wavelength_um = 0.55\n[sky]\nmodel = \"table\"\nfile = \"sky.csv\"\n",
            Some(4),
            Some("sky.file"),
            &["{d}/sky.csv:4: field `phi_deg`: 360: an azimuth must lie in [0°, 360°)", "give 360° as 0°"],
        ),
        with_files(
            &[("sky.csv", b"theta_deg,phi_deg,s0,s1,s2,s3\n0,0,1,0,0,0\n91,0,1,0,0,0\n")],
            "table with zenith 91",
            b"wavelength_um = 0.55\n[sky]\nmodel = \"table\"\nfile = \"sky.csv\"\n",
            Some(4),
            Some("sky.file"),
            &["{d}/sky.csv:3: field `theta_deg`: 91: a zenith angle must lie in [0°, 90°]"],
        ),
        with_files(
            &[("sky.csv", b"theta_deg,phi_deg,s0,s1,s2\n0,0,1,0,0\n90,0,1,0,0\n")],
            "table without s3",
            b"wavelength_um = 0.55\n[sky]\nmodel = \"table\"\nfile = \"sky.csv\"\n",
            Some(4),
            Some("sky.file"),
            &["{d}/sky.csv: missing column(s) s3"],
        ),
        with_files(
            &[("sky.csv", b"theta_deg,phi_deg,s0,s1,s2,s3\n")],
            "table without rows",
            b"wavelength_um = 0.55\n[sky]\nmodel = \"table\"\nfile = \"sky.csv\"\n",
            Some(4),
            Some("sky.file"),
            &["{d}/sky.csv: no rows"],
        ),
        with_files(
            &[("sky.csv", b"theta_deg,phi_deg,s0,s1,s2,s3\n0,0,1,0,0,0\n90,0,bright,0,0,0\n")],
            "table with a word for a number",
            b"wavelength_um = 0.55\n[sky]\nmodel = \"table\"\nfile = \"sky.csv\"\n",
            Some(4),
            Some("sky.file"),
            &["{d}/sky.csv:3: field `s0`: expected a number, got \"bright\""],
        ),
        with_files(
            &[("sky.csv", b"zenith_deg,radiance\n0,1\n90,2\n")],
            "a profile file for a table",
            b"wavelength_um = 0.55\n[sky]\nmodel = \"table\"\nfile = \"sky.csv\"\n",
            Some(4),
            Some("sky.file"),
            &["{d}/sky.csv: missing column(s) theta_deg, phi_deg, s0, s1, s2, s3"],
        ),
        // Materials.
        case(
            "neither a material file nor a preset",
            b"wavelength_um = 10\n[target]\nmaterial = \"pant\"\n",
            Some(3),
            Some("target.material"),
            &["pant: not a preset material", "paint"],
        ),
        with_files(
            &[("m.toml", b"n = 1.5\nsigma = 5\n")],
            "a material file with a bad key",
            b"wavelength_um = 10\n[background]\nmaterial = \"m.toml\"\n",
            Some(3),
            Some("background.material"),
            &["{d}/m.toml:2: field `sigma`: unknown key"],
        ),
        case(
            "empty material",
            b"wavelength_um = 10\n[target]\nmaterial = \"\"\n",
            Some(3),
            Some("target.material"),
            &["got an empty string"],
        ),
        // Syntax.
        case(
            "binary garbage",
            b"wavelength_um = 10\n\x00\xff\xfe\x89PNG\r\n",
            Some(2),
            None,
            &["not valid UTF-8"],
        ),
        case(
            "control characters",
            b"\x01\x02\x03\x7f",
            Some(1),
            None,
            &["invalid"],
        ),
        case(
            "a control character in a comment (found by fuzzing: the toml crate's message is \
             empty)",
            b"wavelength_um = 10\n# a\x00b\n",
            Some(2),
            None,
            &["invalid character '\\0': TOML allows no control characters"],
        ),
        case(
            "empty file",
            b"",
            None,
            None,
            &["no spectrum"],
        ),
        case(
            "duplicated key",
            b"wavelength_um = 10\nwavelength_um = 11\n",
            Some(2),
            None,
            &["duplicate key `wavelength_um`"],
        ),
        case(
            "duplicated table",
            b"wavelength_um = 10\n[sky]\nmodel = \"none\"\n[sky]\nmodel = \"none\"\n",
            Some(4),
            None,
            &["duplicate key `sky`"],
        ),
        case(
            "duplicated key in a table",
            b"wavelength_um = 10\n[atmosphere]\ntransmittance = 1\ntransmittance = 0.5\n",
            Some(4),
            None,
            &["duplicate key `transmittance`"],
        ),
        case(
            "a dotted key",
            b"wavelength_um = 10\nsky.model = \"uniform\"\n",
            Some(2),
            Some("sky.model"),
            &["dotted keys", "not supported", "[table]"],
        ),
        case(
            "a value missing",
            b"wavelength_um = \n",
            Some(1),
            None,
            &["invalid string"],
        ),
    ]
}

#[test]
fn bad_inputs_name_file_line_and_key() {
    let cases = cases();
    assert!(cases.len() >= 30);
    let mut failures = Vec::new();
    for c in &cases {
        let (dir, p) = folder(c.files, "scene.toml", c.scene);
        let d = dir.path().display().to_string();
        let outcome = std::panic::catch_unwind(|| read_scene(&p));
        let msg = match outcome {
            Err(_) => {
                failures.push(format!("{}: panicked", c.what));
                continue;
            }
            Ok(Ok(_)) => {
                failures.push(format!("{}: accepted", c.what));
                continue;
            }
            Ok(Err(e)) => e.to_string(),
        };
        let mut head = match c.line {
            Some(l) => format!("{}:{l}: ", p.display()),
            None => format!("{}: ", p.display()),
        };
        if let Some(k) = c.key {
            head += &format!("field `{k}`: ");
        }
        // Without a key, no key is named either.
        let mut ok = msg
            .strip_prefix(&head)
            .is_some_and(|rest| c.key.is_some() || !rest.starts_with("field `"));
        for s in c.says {
            ok &= msg.contains(&s.replace("{d}", &d));
        }
        if !ok {
            failures.push(format!(
                "{}:\n  got      {msg}\n  expected {head}… {:?}",
                c.what, c.says
            ));
        }
    }
    assert!(failures.is_empty(), "\n{}", failures.join("\n"));
}

#[test]
fn errors_are_data_errors_with_structure() {
    // The parsed error carries the key and line as fields, not only in its text.
    match parse("wavelength_um = 10\n[sky]\nmodel = \"uniform\"\nradiance = -1\n").unwrap_err() {
        Error::Field {
            path, line, field, ..
        } => {
            assert_eq!(path, Path::new("scene.toml"));
            assert_eq!((line, field.as_str()), (4, "sky.radiance"));
        }
        other => panic!("expected a field error, got {other}"),
    }
    assert!(matches!(parse("").unwrap_err(), Error::File { .. }));
    assert!(matches!(
        read_scene(Path::new("/no/such/scene.toml")).unwrap_err(),
        Error::Read { .. }
    ));
    // A missing referenced file is the scene's data error, naming both files.
    let e = parse("[band]\nresponse = \"missing.csv\"\n").unwrap_err();
    assert!(e.is_data_error());
    assert!(
        e.to_string()
            .starts_with("scene.toml:2: field `band.response`: missing.csv: cannot read"),
        "{e}"
    );
}

#[test]
fn scene_keys_as_given_with_file_names_joined_to_the_folder() {
    let (dir, path) = folder(
        &[
            ("b/band.csv", BAND.as_bytes()),
            ("m.toml", b"n = 1.5\nsigma_deg = 10\n"),
        ],
        "scene.toml",
        b"[band]\nresponse = \"b/band.csv\"\nstep_um = 1\n[target]\nmaterial = \"m.toml\"\n\
          [background]\nmaterial = \"paint\"\ntemperature_k = 300\n[sun]\nzenith_deg = 30\n\
          irradiance = 2\nstokes = [1, 0.5, 0, 0]\n[sky]\nmodel = \"cie-clear\"\nirradiance = 1\n",
    );
    let (scene, keys) = polbrdf_io::read_scene_keys(&path).unwrap();
    assert_eq!(scene, read_scene(&path).unwrap());
    use polbrdf_io::SceneValue::{Number, Numbers, Text};
    let joined = |f: &str| Text(dir.path().join(f).to_string_lossy().into_owned());
    assert_eq!(
        keys,
        vec![
            ("band.response", joined("b/band.csv")),
            ("band.step_um", Number(1.0)),
            ("target.material", joined("m.toml")),
            // A preset name is no file name: as given.
            ("background.material", Text("paint".into())),
            ("background.temperature_k", Number(300.0)),
            ("sun.zenith_deg", Number(30.0)),
            ("sun.irradiance", Number(2.0)),
            ("sun.stokes", Numbers(vec![1.0, 0.5, 0.0, 0.0])),
            ("sky.model", Text("cie-clear".into())),
            ("sky.irradiance", Number(1.0)),
        ]
    );
    // The default dop_max is the core's.
    assert!(matches!(
        scene.thermal.sky,
        SkyModel::ClearSky { dop_max, .. }
            if dop_max == polbrdf::analysis::sky::ClearSky::DEFAULT_DOP_MAX
    ));
    // A bad file is the reader's error.
    std::fs::write(&path, "wavelength_um = -1\n").unwrap();
    let e = polbrdf_io::read_scene_keys(&path).unwrap_err().to_string();
    assert_eq!(e, read_scene(&path).unwrap_err().to_string());
}

#[test]
fn key_and_sky_model_names() {
    let keys: Vec<_> = polbrdf_io::scene::key_names().collect();
    assert_eq!(keys.len(), 41);
    assert_eq!(
        keys[..4],
        ["wavelength_um", "band", "band.response", "band.step_um"]
    );
    let skies: Vec<_> = polbrdf_io::scene::sky_model_names().collect();
    assert_eq!(
        skies,
        [
            "none",
            "uniform",
            "thermal",
            "profile",
            "cie-clear",
            "table"
        ]
    );
    // Every model has a kind, each its own; a model parses (with its keys) by that name.
    let kinds: Vec<_> = skies
        .iter()
        .map(|m| polbrdf_io::scene::sky_kind(m).unwrap())
        .collect();
    assert!(kinds
        .iter()
        .enumerate()
        .all(|(i, k)| !kinds[..i].contains(k)));
    assert_eq!(polbrdf_io::scene::sky_kind("cloudy"), None);
    for model in skies {
        let e = parse(&format!("wavelength_um = 1\n[sky]\nmodel = \"{model}\"\n"));
        if let Err(e) = e {
            assert!(!e.to_string().contains("unknown sky model"), "{e}");
        }
    }
}
