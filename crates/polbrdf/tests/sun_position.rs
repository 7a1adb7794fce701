//! The sun's position (docs/sun-position.md): SPA against its published example, and the
//! geometry every solar position must obey (equinox noon at the equator, polar night and
//! midnight sun, the azimuth's compass convention, the surface frame's φ).

use polbrdf::analysis::sun_position::{
    sun_position, surface_phi_deg, CivilTime, Site, SunPosition,
};
use polbrdf::Error;

fn time(date: (i32, u32, u32), hms: (u32, u32, f64), utc_offset_min: i32) -> CivilTime {
    CivilTime {
        year: date.0,
        month: date.1,
        day: date.2,
        hour: hms.0,
        minute: hms.1,
        second: hms.2,
        utc_offset_min,
    }
}

fn at(date: (i32, u32, u32), hms: (u32, u32, f64), offset: i32, site: &Site) -> SunPosition {
    sun_position(&time(date, hms, offset), site, None).unwrap()
}

/// Reda & Andreas (2008), Table A4.1 inputs and A5.1 results, as NREL's spa_tester.c prints
/// them (zenith 50.111622°, azimuth 194.340241°, Julian day 2452930.312847): Golden,
/// Colorado, 17 October 2003 12:30:30 at UTC−7, ΔT = 67 s, 1830.14 m, 820 mbar, 11 °C.
#[test]
fn spa_published_example() {
    let site = Site {
        latitude_deg: 39.742476,
        longitude_deg: -105.1786,
        elevation_m: 1830.14,
        pressure_hpa: 820.0,
        temperature_c: 11.0,
    };
    let p = sun_position(
        &time((2003, 10, 17), (12, 30, 30.0), -420),
        &site,
        Some(67.0),
    )
    .unwrap();
    assert!((p.julian_day - 2452930.312847).abs() < 5e-7, "{p:?}");
    assert!((p.zenith_deg - 50.111622).abs() < 5e-7, "{p:?}");
    assert!((p.azimuth_deg - 194.340241).abs() < 5e-7, "{p:?}");
    assert_eq!(p.delta_t_s, 67.0);
    // The same instant written in UTC.
    let q = sun_position(&time((2003, 10, 17), (19, 30, 30.0), 0), &site, Some(67.0)).unwrap();
    assert!((q.zenith_deg - p.zenith_deg).abs() < 1e-9);
    assert!((q.azimuth_deg - p.azimuth_deg).abs() < 1e-9);
    // Without refraction the sun is lower, by Bennett's formula at h = 39.87°:
    // 1.02′/tan(h + 10.3/(h + 5.11)) · (820/1010) · (283/284) = 0.9795′ = 0.01633°.
    let bare = Site {
        pressure_hpa: 0.0,
        ..site
    };
    let r = sun_position(
        &time((2003, 10, 17), (12, 30, 30.0), -420),
        &bare,
        Some(67.0),
    )
    .unwrap();
    let lift = r.zenith_deg - p.zenith_deg;
    assert!((lift - 0.01633).abs() < 0.00002, "refraction {lift}");
}

/// On the March equinox the sun passes within 0.4° of the zenith at the equator at local
/// solar noon (its declination is below 0.4° that day), rising in the east and setting in the
/// west.
#[test]
fn equinox_noon_at_the_equator() {
    let site = Site {
        pressure_hpa: 0.0,
        ..Site::at(0.0, 0.0)
    };
    let noon = (0..=240)
        .map(|m| at((2026, 3, 20), (10 + m / 60, m % 60, 0.0), 0, &site))
        .min_by(|a, b| a.zenith_deg.total_cmp(&b.zenith_deg))
        .unwrap();
    assert!(noon.zenith_deg < 0.4, "{noon:?}");
    // The equation of time on 20 March is about −7.5 min: noon at Greenwich near 12:07 UTC.
    let morning = at((2026, 3, 20), (7, 0, 0.0), 0, &site);
    let evening = at((2026, 3, 20), (17, 0, 0.0), 0, &site);
    assert!((morning.azimuth_deg - 90.0).abs() < 0.5, "{morning:?}");
    assert!((evening.azimuth_deg - 270.0).abs() < 0.5, "{evening:?}");
    // Five hours from noon the sun is 75° from the zenith (15° per hour), within the
    // equation of time's 7.5 min (1.9°).
    assert!((morning.zenith_deg - 75.0).abs() < 2.5, "{morning:?}");
    assert!(morning.is_up() && evening.is_up());
}

/// At 78° N (Longyearbyen) the sun stays below the horizon all day at the December solstice
/// (at most 90° − 78.2° − 23.4° = −11.7° high) and above it all day at the June solstice.
#[test]
fn polar_night_and_midnight_sun() {
    let site = Site::at(78.22, 15.63);
    for h in 0..24 {
        let winter = at((2025, 12, 21), (h, 0, 0.0), 60, &site);
        assert!(
            !winter.is_up() && winter.elevation_deg() < -11.0,
            "{h}: {winter:?}"
        );
        let summer = at((2026, 6, 21), (h, 0, 0.0), 120, &site);
        assert!(
            summer.is_up() && summer.elevation_deg() > 11.0,
            "{h}: {summer:?}"
        );
    }
}

/// Azimuths are compass bearings: the noon sun is due south north of the tropics and due
/// north south of them; east in the morning, west in the afternoon.
#[test]
fn azimuth_is_a_compass_bearing() {
    // Vienna, 21 June 2026 (UTC+2): solar noon near 12:56 local.
    let vienna = Site::at(48.21, 16.37);
    let noon = at((2026, 6, 21), (12, 56, 0.0), 120, &vienna);
    assert!((noon.azimuth_deg - 180.0).abs() < 2.0, "{noon:?}");
    // Noon zenith = latitude − declination (23.44°) on the solstice, plus a little refraction.
    assert!((noon.zenith_deg - (48.21 - 23.44)).abs() < 0.1, "{noon:?}");
    let morning = at((2026, 6, 21), (8, 0, 0.0), 120, &vienna);
    let afternoon = at((2026, 6, 21), (18, 0, 0.0), 120, &vienna);
    assert!((45.0..135.0).contains(&morning.azimuth_deg), "{morning:?}");
    assert!(
        (225.0..315.0).contains(&afternoon.azimuth_deg),
        "{afternoon:?}"
    );
    // Sydney, same instant as Vienna's noon: the sun in the north, low (winter solstice).
    let sydney = Site::at(-33.87, 151.21);
    let north = at((2026, 6, 21), (11, 57, 0.0), 600, &sydney);
    assert!(
        north.azimuth_deg < 3.0 || north.azimuth_deg > 357.0,
        "{north:?}"
    );
    assert!(
        (north.zenith_deg - (33.87 + 23.44)).abs() < 0.1,
        "{north:?}"
    );
}

/// φ = phi0 − azimuth: the surface frame is right-handed with z up, so φ turns
/// counterclockwise seen from above while a compass bearing turns clockwise.
#[test]
fn surface_frame_azimuth() {
    // φ = 0 to the north: the west is φ = 90° (y = z × x = up × north = west).
    assert_eq!(surface_phi_deg(270.0, 0.0), 90.0);
    assert_eq!(surface_phi_deg(90.0, 0.0), 270.0);
    assert_eq!(surface_phi_deg(0.0, 0.0), 0.0);
    // φ = 0 to the east: the sun in the east is at φ = 0, in the south at φ = 270°.
    assert_eq!(surface_phi_deg(90.0, 90.0), 0.0);
    assert_eq!(surface_phi_deg(180.0, 90.0), 270.0);
    // Always in [0, 360), also for a phi0 a hair below the azimuth.
    let phi = surface_phi_deg(10.0, 10.0 - 1e-15);
    assert!((0.0..360.0).contains(&phi), "{phi}");
    // The direction vector (cos φ, sin φ) in (x, y) = (north, west) points at the bearing.
    for bearing in [0.0_f64, 37.0, 120.0, 250.0, 359.0] {
        let phi = surface_phi_deg(bearing, 0.0).to_radians();
        let (north, west) = (phi.cos(), phi.sin());
        let east = -west;
        let back = east.atan2(north).to_degrees().rem_euclid(360.0);
        assert!((back - bearing).abs() < 1e-9, "{bearing} -> {back}");
    }
}

/// Bad input is an error naming the scene file's key, never a position.
#[test]
fn invalid_inputs_name_their_key() {
    let name = |t: CivilTime, s: Site, dt: Option<f64>| match sun_position(&t, &s, dt) {
        Err(Error::InvalidParameter { name, .. }) => name,
        other => panic!("{other:?}"),
    };
    let t = time((2026, 6, 21), (12, 0, 0.0), 0);
    let s = Site::at(48.0, 16.0);
    assert_eq!(
        name(time((2026, 2, 29), (12, 0, 0.0), 0), s, None),
        "sun.date_time"
    );
    assert!(sun_position(&time((2024, 2, 29), (12, 0, 0.0), 0), &s, None).is_ok());
    assert_eq!(
        name(time((2026, 6, 21), (12, 0, 60.0), 0), s, None),
        "sun.date_time"
    );
    assert_eq!(
        name(time((2026, 6, 21), (12, 0, 0.0), 1440), s, None),
        "sun.date_time"
    );
    assert_eq!(
        name(time((7000, 6, 21), (12, 0, 0.0), 0), s, None),
        "sun.date_time"
    );
    // SPA holds from −2000, ΔT estimates from −500: before that ΔT must be given.
    assert_eq!(
        name(time((-1000, 6, 21), (12, 0, 0.0), 0), s, None),
        "sun.date_time"
    );
    assert!(sun_position(&time((-1000, 6, 21), (12, 0, 0.0), 0), &s, Some(25_000.0)).is_ok());
    assert_eq!(name(t, Site::at(90.5, 0.0), None), "sun.latitude_deg");
    assert_eq!(name(t, Site::at(f64::NAN, 0.0), None), "sun.latitude_deg");
    assert_eq!(name(t, Site::at(0.0, 181.0), None), "sun.longitude_deg");
    let high = Site {
        elevation_m: 2e5,
        ..s
    };
    assert_eq!(name(t, high, None), "sun.elevation_m");
    let vacuum = Site {
        pressure_hpa: -1.0,
        ..s
    };
    assert_eq!(name(t, vacuum, None), "sun.pressure_hpa");
    let hot = Site {
        temperature_c: 150.0,
        ..s
    };
    assert_eq!(name(t, hot, None), "sun.temperature_c");
    assert_eq!(name(t, s, Some(f64::INFINITY)), "sun.delta_t_s");
    // The estimated ΔT is the one reported (about 69–75 s in 2026).
    let p = sun_position(&t, &s, None).unwrap();
    assert!((65.0..80.0).contains(&p.delta_t_s), "{p:?}");
}
