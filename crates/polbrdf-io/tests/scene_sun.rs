//! `[sun]` by date, time and place (docs/sun-position.md): the sun SPA places, in the surface
//! frame the file orients; the two ways of giving the sun exclude each other; bad dates,
//! places and a sun below the horizon are errors naming file, line and key.

use polbrdf::analysis::sun_position::{sun_position, CivilTime, Site, SunTime};
use polbrdf_io::date_time::{at_clock, format_date_time, parse_clock, parse_date, parse_date_time};
use polbrdf_io::{parse_scene, Error, Scene};
use std::path::Path;

fn parse(text: &str) -> Result<Scene, Error> {
    parse_scene(text, Path::new("scene.toml"))
}

/// SPA's published example (Golden, Colorado) as a scene: the sun is at zenith 50.111622°,
/// compass azimuth 194.340241°, and in a surface frame whose φ = 0 points east (phi0 = 90°)
/// at φ = 90° − 194.340241° + 360° = 255.659759°.
const GOLDEN: &str = "wavelength_um = 0.55\n[sun]\ndate_time = \"2003-10-17T12:30:30-07:00\"\n\
    latitude_deg = 39.742476\nlongitude_deg = -105.1786\nelevation_m = 1830.14\n\
    pressure_hpa = 820\ntemperature_c = 11\ndelta_t_s = 67\nphi0_azimuth_deg = 90\n\
    irradiance = 1000\n";

#[test]
fn date_time_places_the_sun_in_the_surface_frame() {
    let s = parse(GOLDEN).unwrap();
    let sun = s.thermal.sun.unwrap();
    assert!(
        (sun.zenith.to_degrees() - 50.111622).abs() < 5e-7,
        "{sun:?}"
    );
    assert!(
        (sun.azimuth.to_degrees() - 255.659759).abs() < 5e-7,
        "{sun:?}"
    );
    assert_eq!(sun.irradiance, 1000.0);
    let t = s.sun_time.unwrap();
    assert_eq!(t.phi0_azimuth_deg, 90.0);
    assert_eq!(t.delta_t_s, Some(67.0));
    assert_eq!(format_date_time(&t.time), "2003-10-17T12:30:30-07:00");
    // A TOML date-time (unquoted) is the same instant as the string.
    let native = GOLDEN.replace("\"2003-10-17T12:30:30-07:00\"", "2003-10-17T12:30:30-07:00");
    assert_eq!(parse(&native).unwrap().thermal, s.thermal);
    // The same instant in UTC: the same sun.
    let utc = GOLDEN.replace("12:30:30-07:00", "19:30:30Z");
    let u = parse(&utc).unwrap().thermal.sun.unwrap();
    assert!((u.zenith - sun.zenith).abs() < 1e-12 && (u.azimuth - sun.azimuth).abs() < 1e-12);
}

#[test]
fn defaults_sea_level_standard_air_phi0_north() {
    let s = parse(
        "wavelength_um = 0.55\n[sun]\ndate_time = \"2026-06-21T12:56:00+02:00\"\n\
         latitude_deg = 48.21\nlongitude_deg = 16.37\nirradiance = 1\n",
    )
    .unwrap();
    let t = s.sun_time.unwrap();
    assert_eq!(t.site, Site::at(48.21, 16.37));
    assert_eq!((t.delta_t_s, t.phi0_azimuth_deg), (None, 0.0));
    let p = sun_position(&t.time, &t.site, None).unwrap();
    let sun = s.thermal.sun.unwrap();
    assert_eq!(sun.zenith, p.zenith_deg.to_radians());
    // The noon sun near the south: with φ = 0 to the north it is near φ = 180°.
    assert!((sun.azimuth.to_degrees() - 180.0).abs() < 2.0, "{sun:?}");
    assert!((sun.azimuth.to_degrees() - (360.0 - p.azimuth_deg)).abs() < 1e-12);
    // The angles of the sun without date_time: no sun_time.
    let s = parse("wavelength_um = 0.55\n[sun]\nzenith_deg = 30\nirradiance = 1\n").unwrap();
    assert_eq!(s.sun_time, None);
}

#[test]
fn a_sun_time_at_another_clock_time() {
    let t = SunTime {
        time: parse_date_time("2026-06-21T12:00:00+02:00").unwrap(),
        site: Site::at(48.21, 16.37),
        delta_t_s: None,
        phi0_azimuth_deg: 0.0,
    };
    let later = t.at(at_clock(&t.time, (2026, 6, 22), 6.5 * 3600.0 + 0.25));
    assert_eq!(
        format_date_time(&later.time),
        "2026-06-22T06:30:00.250+02:00"
    );
    assert_eq!(parse_clock("06:30").unwrap(), 23400.0);
    assert_eq!(parse_clock("23:59:59").unwrap(), 86399.0);
    assert!(parse_clock("24:00").is_err() && parse_clock("6h").is_err());
    assert!(parse_clock("2026-06-21").is_err());
    assert_eq!(parse_date("2024-02-29").unwrap(), (2024, 2, 29));
    assert!(parse_date("2026-02-29").is_err() && parse_date("2026-13-01").is_err());
    assert!(parse_date("2026-06-21T12:00:00Z").is_err());
    // Below the horizon: no direction, the position still reported.
    let night = t.at(parse_date_time("2026-06-21T00:30:00+02:00").unwrap());
    let (p, dir) = night.surface_direction().unwrap();
    assert!(dir.is_none() && p.elevation_deg() < -10.0, "{p:?}");
    let c: CivilTime = parse_date_time("2026-06-21T12:00:00.5-03:30").unwrap();
    assert_eq!((c.second, c.utc_offset_min), (0.5, -210));
}

/// `(scene text, line, key, what the message says)`.
type Bad = (&'static str, usize, &'static str, &'static [&'static str]);

const BAD: &[Bad] = &[
    (
        "[sun]\ndate_time = \"2026-06-21T12:00:00\"\nlatitude_deg = 0\nlongitude_deg = 0\nirradiance = 1\n",
        3,
        "sun.date_time",
        &["has no UTC offset", "append `Z`"],
    ),
    (
        "[sun]\ndate_time = 2026-06-21T12:00:00\nlatitude_deg = 0\nlongitude_deg = 0\nirradiance = 1\n",
        3,
        "sun.date_time",
        &["has no UTC offset"],
    ),
    (
        "[sun]\ndate_time = \"21/06/2026 12:00\"\nlatitude_deg = 0\nlongitude_deg = 0\nirradiance = 1\n",
        3,
        "sun.date_time",
        &["is not an RFC 3339 date-time"],
    ),
    (
        "[sun]\ndate_time = \"2026-02-30T12:00:00Z\"\nlatitude_deg = 0\nlongitude_deg = 0\nirradiance = 1\n",
        3,
        "sun.date_time",
        &["is not an RFC 3339"],
    ),
    (
        "[sun]\ndate_time = 2026-06-21\nlatitude_deg = 0\nlongitude_deg = 0\nirradiance = 1\n",
        3,
        "sun.date_time",
        &["not a date with a time of day"],
    ),
    (
        "[sun]\ndate_time = 12\nlatitude_deg = 0\nlongitude_deg = 0\nirradiance = 1\n",
        3,
        "sun.date_time",
        &["expected a date-time", "got integer"],
    ),
    (
        "[sun]\ndate_time = \"2026-06-21T12:00:00Z\"\nlongitude_deg = 0\nirradiance = 1\n",
        2,
        "sun",
        &["missing required key `latitude_deg`"],
    ),
    (
        "[sun]\ndate_time = \"2026-06-21T12:00:00Z\"\nlatitude_deg = 95\nlongitude_deg = 0\nirradiance = 1\n",
        4,
        "sun.latitude_deg",
        &["`sun.latitude_deg` = 95: must lie in [-90, 90]"],
    ),
    (
        "[sun]\ndate_time = \"2026-06-21T12:00:00Z\"\nlatitude_deg = 0\nlongitude_deg = 200\nirradiance = 1\n",
        5,
        "sun.longitude_deg",
        &["must lie in [-180, 180]"],
    ),
    (
        "[sun]\ndate_time = \"2026-06-21T12:00:00Z\"\nlatitude_deg = 0\nlongitude_deg = 0\npressure_hpa = -5\nirradiance = 1\n",
        6,
        "sun.pressure_hpa",
        &["0: no refraction"],
    ),
    (
        "[sun]\ndate_time = \"2026-06-21T12:00:00Z\"\nlatitude_deg = 0\nlongitude_deg = 0\ndelta_t_s = nan\nirradiance = 1\n",
        6,
        "sun.delta_t_s",
        &["must be finite"],
    ),
    (
        "[sun]\ndate_time = \"2026-06-21T12:00:00Z\"\nlatitude_deg = 0\nlongitude_deg = 0\nphi0_azimuth_deg = inf\nirradiance = 1\n",
        6,
        "sun.phi0_azimuth_deg",
        &["must be finite"],
    ),
    (
        "[sun]\ndate_time = \"2026-06-21T12:00:00Z\"\nlatitude_deg = 0\nlongitude_deg = 0\nzenith_deg = 30\nirradiance = 1\n",
        6,
        "sun.zenith_deg",
        &["give either `zenith_deg`", "or `date_time` (line 3", "not both"],
    ),
    (
        "[sun]\nazimuth_deg = 10\ndate_time = \"2026-06-21T12:00:00Z\"\nlatitude_deg = 0\nlongitude_deg = 0\nirradiance = 1\n",
        3,
        "sun.azimuth_deg",
        &["give either `azimuth_deg`", "not both"],
    ),
    (
        "[sun]\nzenith_deg = 30\nlatitude_deg = 10\nirradiance = 1\n",
        4,
        "sun.latitude_deg",
        &["`latitude_deg` places the sun by date, time and place: give `date_time` too"],
    ),
    (
        "[sun]\ndate_time = \"2026-06-21T00:30:00+02:00\"\nlatitude_deg = 48.21\nlongitude_deg = 16.37\nirradiance = 1\n",
        3,
        "sun.date_time",
        &[
            "the sun is not above the horizon at 2026-06-21T00:30:00+02:00 at latitude 48.21°, \
             longitude 16.37°",
            "check the date, the UTC offset and the place",
        ],
    ),
    (
        "[sun]\ndate_time = \"2026-06-21T12:00:00Z\"\nlatitude_deg = 0\nlongitude_deg = 0\n",
        2,
        "sun",
        &["missing required key `irradiance`"],
    ),
    (
        "[sun]\nirradiance = 1\n",
        2,
        "sun",
        &["missing required key `zenith_deg`", "or place the sun by `date_time`"],
    ),
];

#[test]
fn bad_sun_keys_name_file_line_and_key() {
    let mut failures = Vec::new();
    for (text, line, key, says) in BAD {
        let text = format!("wavelength_um = 0.55\n{text}");
        let msg = match parse(&text) {
            Ok(_) => {
                failures.push(format!("accepted:\n{text}"));
                continue;
            }
            Err(e) => e.to_string(),
        };
        let head = format!("scene.toml:{line}: field `{key}`: ");
        if !msg.starts_with(&head) || !says.iter().all(|s| msg.contains(s)) {
            failures.push(format!(
                "{text}\n  got      {msg}\n  expected {head}… {says:?}"
            ));
        }
    }
    assert!(failures.is_empty(), "\n{}", failures.join("\n"));
}
