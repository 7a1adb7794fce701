//! The sun's position from a date, a time and a place (docs/sun-position.md): NREL's Solar
//! Position Algorithm (SPA; Reda & Andreas, *Solar Energy* 76(5), 577–589, 2004, corrected
//! 2008; NREL/TP-560-34302), as implemented by the `solar-positioning` crate (pure, no I/O),
//! with the project's inputs checked and named here.
//!
//! SPA's stated uncertainty is ±0.0003° in zenith and azimuth for the years −2000 to 6000,
//! given the right ΔT (TT − UT1). Without one, ΔT is estimated from the date (Espenak & Meeus
//! polynomials, updated fits from 2015; −500 to 3000); an error of 1 s in ΔT moves the sun by
//! about 0.004° at most. UTC is taken for UT1 (|UT1 − UTC| < 0.9 s, ≤ 0.004°). Refraction is
//! SPA's (Bennett's formula with pressure and temperature), applied above −0.8334° of
//! elevation as SPA does; a pressure of 0 turns it off (no atmosphere).
//!
//! Conventions: the zenith angle from the local vertical; the azimuth of the sun as a compass
//! bearing, from north toward east (SPA's topocentric azimuth Φ). The surface frame of the
//! model (docs/model.md §1: `w = (sinθ cosφ, sinθ sinφ, cosθ)`, z up) is tied to the ground by
//! the compass azimuth `phi0` of its φ = 0 axis: φ grows counterclockwise seen from above, so
//! a direction at compass azimuth `A` has `φ = phi0 − A` (mod 360°); with `phi0 = 0`, φ = 0
//! points north and φ = 90° west.

use crate::error::{Error, Result};
use solar_positioning::time::JulianDate;
use solar_positioning::{Location, RefractionCorrection, SolarPositions};

/// A date and a time of day on a clock `utc_offset_min` minutes ahead of UTC (the local civil
/// time of a place: UTC−7 is −420), proleptic Gregorian calendar.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CivilTime {
    /// Year, in [−2000, 6000] (SPA's range; year 0 is 1 BCE).
    pub year: i32,
    /// Month, 1–12.
    pub month: u32,
    /// Day of the month, 1 to the month's length (29 February only in a leap year).
    pub day: u32,
    /// Hour, 0–23.
    pub hour: u32,
    /// Minute, 0–59.
    pub minute: u32,
    /// Second, in [0, 60) (no leap second: UTC is taken for UT1).
    pub second: f64,
    /// Minutes the clock is ahead of UTC, |offset| < 24 h.
    pub utc_offset_min: i32,
}

/// Where the sun is seen from, and the air that refracts it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Site {
    /// Geodetic latitude, degrees, in [−90, 90] (north positive).
    pub latitude_deg: f64,
    /// Longitude, degrees, in [−180, 180] (east positive).
    pub longitude_deg: f64,
    /// Height above the ellipsoid (≈ sea level), m, in [−1000, 100 000].
    pub elevation_m: f64,
    /// Mean local air pressure, hPa (mbar), in [0, 2000]; 0: no refraction.
    pub pressure_hpa: f64,
    /// Mean local air temperature, °C, in [−100, 100].
    pub temperature_c: f64,
}

impl Site {
    /// The pressure when none is given: the standard atmosphere at sea level, hPa.
    pub const DEFAULT_PRESSURE_HPA: f64 = 1013.25;
    /// The temperature when none is given, °C.
    pub const DEFAULT_TEMPERATURE_C: f64 = 15.0;

    /// A site at sea level under the standard atmosphere.
    pub fn at(latitude_deg: f64, longitude_deg: f64) -> Self {
        Self {
            latitude_deg,
            longitude_deg,
            elevation_m: 0.0,
            pressure_hpa: Self::DEFAULT_PRESSURE_HPA,
            temperature_c: Self::DEFAULT_TEMPERATURE_C,
        }
    }
}

/// The sun seen from a site at a time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SunPosition {
    /// Topocentric zenith angle, degrees, in [0, 180] (refracted unless the pressure is 0).
    pub zenith_deg: f64,
    /// Topocentric azimuth, degrees from north toward east, in [0, 360).
    pub azimuth_deg: f64,
    /// The ΔT used (TT − UT1), s: as given, or estimated from the date.
    pub delta_t_s: f64,
    /// The Julian day of the instant (UT).
    pub julian_day: f64,
}

impl SunPosition {
    /// The elevation above the horizon, degrees (`90° − zenith`).
    pub fn elevation_deg(&self) -> f64 {
        90.0 - self.zenith_deg
    }

    /// Whether the sun's centre is above the horizon (zenith angle below 90°).
    pub fn is_up(&self) -> bool {
        self.zenith_deg < 90.0
    }

    /// The sun's azimuth φ in the surface frame, degrees in [0, 360), when that frame's
    /// φ = 0 axis points to compass azimuth `phi0_azimuth_deg` (see [`surface_phi_deg`]).
    pub fn phi_deg(&self, phi0_azimuth_deg: f64) -> f64 {
        surface_phi_deg(self.azimuth_deg, phi0_azimuth_deg)
    }
}

/// The surface-frame azimuth φ (degrees, in [0, 360)) of a direction at compass azimuth
/// `azimuth_deg` (from north toward east), when the frame's φ = 0 axis points to compass
/// azimuth `phi0_azimuth_deg`: `φ = phi0 − azimuth` (φ turns counterclockwise seen from above,
/// a compass bearing clockwise).
pub fn surface_phi_deg(azimuth_deg: f64, phi0_azimuth_deg: f64) -> f64 {
    let phi = (phi0_azimuth_deg - azimuth_deg).rem_euclid(360.0);
    // rem_euclid of a tiny negative number rounds to 360.
    if phi >= 360.0 {
        0.0
    } else {
        phi + 0.0
    }
}

fn invalid(name: &'static str, value: f64, reason: &'static str) -> Error {
    Error::InvalidParameter {
        name,
        value,
        reason,
    }
}

fn is_leap(year: i32) -> bool {
    (year % 4 == 0 && year % 100 != 0) || year % 400 == 0
}

fn month_length(year: i32, month: u32) -> u32 {
    match month {
        2 if is_leap(year) => 29,
        2 => 28,
        4 | 6 | 9 | 11 => 30,
        _ => 31,
    }
}

impl CivilTime {
    /// Checks every field (the error names `sun.date_time`, the key that holds them).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `sun.date_time` with the offending value.
    pub fn validate(&self) -> Result<()> {
        const KEY: &str = "sun.date_time";
        if !(-2000..=6000).contains(&self.year) {
            return Err(invalid(
                KEY,
                f64::from(self.year),
                "the year must lie in [-2000, 6000] (the range of the solar position algorithm)",
            ));
        }
        if !(1..=12).contains(&self.month) {
            return Err(invalid(
                KEY,
                f64::from(self.month),
                "the month must be 1 to 12",
            ));
        }
        if !(1..=month_length(self.year, self.month)).contains(&self.day) {
            return Err(invalid(
                KEY,
                f64::from(self.day),
                "no such day in that month (29 February only in a leap year)",
            ));
        }
        if self.hour > 23 || self.minute > 59 {
            return Err(invalid(
                KEY,
                f64::from(self.hour * 100 + self.minute),
                "the time must be 00:00 to 23:59 (as hhmm)",
            ));
        }
        if !(self.second.is_finite() && (0.0..60.0).contains(&self.second)) {
            return Err(invalid(
                KEY,
                self.second,
                "the seconds must lie in [0, 60) (leap seconds are not supported)",
            ));
        }
        if self.utc_offset_min.abs() >= 24 * 60 {
            return Err(invalid(
                KEY,
                f64::from(self.utc_offset_min),
                "the UTC offset must be less than 24 h in magnitude (in minutes)",
            ));
        }
        Ok(())
    }

    /// The Julian day (UT) of the instant. Call on a validated time.
    pub fn julian_day(&self) -> f64 {
        // The civil date as if it were UTC, then shifted by the offset: a date that rolls
        // over in UTC needs no calendar arithmetic.
        let local = JulianDate::from_utc(
            self.year,
            self.month,
            self.day,
            self.hour,
            self.minute,
            self.second,
            0.0,
        )
        .map_or(f64::NAN, |jd| jd.julian_date());
        local - f64::from(self.utc_offset_min) / 1440.0
    }
}

impl Site {
    /// Checks every field (the errors name the scene file's keys, `sun.latitude_deg`, …).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming the key.
    pub fn validate(&self) -> Result<()> {
        let checks: [(&'static str, f64, f64, f64, &'static str); 5] = [
            (
                "sun.latitude_deg",
                self.latitude_deg,
                -90.0,
                90.0,
                "must lie in [-90, 90] degrees (north positive)",
            ),
            (
                "sun.longitude_deg",
                self.longitude_deg,
                -180.0,
                180.0,
                "must lie in [-180, 180] degrees (east positive)",
            ),
            (
                "sun.elevation_m",
                self.elevation_m,
                -1000.0,
                100_000.0,
                "must lie in [-1000, 100000] m",
            ),
            (
                "sun.pressure_hpa",
                self.pressure_hpa,
                0.0,
                2000.0,
                "must lie in [0, 2000] hPa (0: no refraction)",
            ),
            (
                "sun.temperature_c",
                self.temperature_c,
                -100.0,
                100.0,
                "must lie in [-100, 100] °C",
            ),
        ];
        for (name, value, lo, hi, reason) in checks {
            if !(value.is_finite() && (lo..=hi).contains(&value)) {
                return Err(invalid(name, value, reason));
            }
        }
        Ok(())
    }
}

/// The largest ΔT accepted, s (ΔT was about 47 000 s in −2000).
pub const MAX_DELTA_T_S: f64 = 100_000.0;

/// The sun seen from `site` at `time`, by SPA; `delta_t_s` (TT − UT1, s) estimated from the
/// date when `None`.
///
/// # Errors
/// [`Error::InvalidParameter`] naming `sun.date_time`, a key of [`Site`] or `sun.delta_t_s`
/// (also when ΔT cannot be estimated: before −500 or after 3000).
pub fn sun_position(time: &CivilTime, site: &Site, delta_t_s: Option<f64>) -> Result<SunPosition> {
    time.validate()?;
    site.validate()?;
    let delta_t = match delta_t_s {
        Some(dt) if dt.is_finite() && dt.abs() <= MAX_DELTA_T_S => dt,
        Some(dt) => {
            return Err(invalid(
                "sun.delta_t_s",
                dt,
                "must be finite and at most 100000 s in magnitude",
            ))
        }
        None => {
            solar_positioning::delta_t::estimate_from_date(time.year, time.month).map_err(|_| {
                invalid(
                    "sun.date_time",
                    f64::from(time.year),
                    "ΔT can be estimated for the years -500 to 3000 only: give `delta_t_s`",
                )
            })?
        }
    };
    let julian_day = time.julian_day();
    let jd = JulianDate::new(julian_day, delta_t)
        .map_err(|_| invalid("sun.date_time", julian_day, "not a valid instant"))?;
    let refraction = if site.pressure_hpa > 0.0 {
        Some(
            RefractionCorrection::new(site.pressure_hpa, site.temperature_c)
                .map_err(|_| invalid("sun.pressure_hpa", site.pressure_hpa, "out of range"))?,
        )
    } else {
        None
    };
    let location = Location {
        latitude: site.latitude_deg,
        longitude: site.longitude_deg,
    };
    let position = SolarPositions::new()
        .at_from_julian(jd, location, site.elevation_m, refraction)
        .map_err(|_| {
            invalid(
                "sun.date_time",
                julian_day,
                "outside the range of the solar position algorithm",
            )
        })?;
    Ok(SunPosition {
        zenith_deg: position.zenith_angle(),
        azimuth_deg: position.azimuth(),
        delta_t_s: delta_t,
        julian_day,
    })
}

/// A sun given by date, time and place (a scene's `[sun]` with `date_time`): where it is, and
/// how the surface frame lies on the ground.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SunTime {
    /// The instant, on the local clock.
    pub time: CivilTime,
    /// The place.
    pub site: Site,
    /// ΔT (TT − UT1), s; `None`: estimated from the date.
    pub delta_t_s: Option<f64>,
    /// The compass azimuth (degrees from north toward east) of the surface frame's φ = 0
    /// axis, in [0, 360).
    pub phi0_azimuth_deg: f64,
}

impl SunTime {
    /// The compass azimuth of φ = 0 when none is given: north.
    pub const DEFAULT_PHI0_AZIMUTH_DEG: f64 = 0.0;

    /// The sun's position ([`sun_position`]).
    ///
    /// # Errors
    /// As [`sun_position`].
    pub fn position(&self) -> Result<SunPosition> {
        sun_position(&self.time, &self.site, self.delta_t_s)
    }

    /// The same place and frame at another time.
    pub fn at(&self, time: CivilTime) -> Self {
        Self { time, ..*self }
    }

    /// The sun's direction in the surface frame, `(θs, φs)` in radians, or `None` when it is
    /// not above the horizon (its zenith angle, in radians, not below π/2).
    ///
    /// # Errors
    /// As [`sun_position`].
    pub fn surface_direction(&self) -> Result<(SunPosition, Option<(f64, f64)>)> {
        let p = self.position()?;
        let zenith = p.zenith_deg.to_radians() + 0.0;
        let above = p.is_up() && zenith < std::f64::consts::FRAC_PI_2;
        let phi = p.phi_deg(self.phi0_azimuth_deg).to_radians();
        Ok((p, above.then_some((zenith, phi))))
    }
}
