//! Dates and times as scene files and the command line write them (docs/sun-position.md):
//! an RFC 3339 date-time with its UTC offset (`2026-06-21T12:00:00Z`,
//! `2003-10-17T12:30:30-07:00`, as a TOML date-time or a string), a date (`2026-06-21`) and a
//! clock time (`06:30`, `06:30:15`). Parsed by the TOML reader's own date-time grammar, then
//! checked by the core ([`CivilTime::validate`]: real calendar days, no leap second).

use polbrdf::analysis::sun_position::CivilTime;
use toml::value::{Datetime, Offset};

/// What `date_time` must look like, for messages.
pub const DATE_TIME_FORM: &str = "an RFC 3339 date-time with its UTC offset, e.g. \
    \"2026-06-21T12:00:00Z\" (UTC) or \"2026-06-21T14:00:00+02:00\" (local time at UTC+2)";

fn datetime(text: &str) -> Option<Datetime> {
    text.trim().parse::<Datetime>().ok()
}

/// A date-time with its UTC offset, from a TOML date-time (already parsed).
///
/// # Errors
/// A sentence saying what is missing or wrong (the caller names the key or option).
pub fn from_toml(d: &Datetime) -> Result<CivilTime, String> {
    let (Some(date), Some(time)) = (d.date, d.time) else {
        return Err(format!(
            "{d} is not a date with a time of day: expected {DATE_TIME_FORM}"
        ));
    };
    let Some(offset) = d.offset else {
        return Err(format!(
            "{d} has no UTC offset: append `Z` for UTC or the local offset (`-07:00`); expected \
             {DATE_TIME_FORM}"
        ));
    };
    let civil = CivilTime {
        year: i32::from(date.year),
        month: u32::from(date.month),
        day: u32::from(date.day),
        hour: u32::from(time.hour),
        minute: u32::from(time.minute),
        second: f64::from(time.second) + f64::from(time.nanosecond) * 1e-9,
        utc_offset_min: match offset {
            Offset::Z => 0,
            Offset::Custom { minutes } => i32::from(minutes),
        },
    };
    civil
        .validate()
        .map_err(|e| format!("{d}: {}", reason(&e)))?;
    Ok(civil)
}

/// The reason of a core error about a date-time (its name is the caller's to give).
fn reason(e: &polbrdf::Error) -> String {
    match e {
        polbrdf::Error::InvalidParameter { reason, .. } => (*reason).to_string(),
        other => other.to_string(),
    }
}

/// A date-time with its UTC offset from text ([`DATE_TIME_FORM`]).
///
/// # Errors
/// A sentence saying what is wrong.
pub fn parse_date_time(text: &str) -> Result<CivilTime, String> {
    match datetime(text) {
        Some(d) => from_toml(&d),
        None => Err(format!("{text:?} is not {DATE_TIME_FORM}")),
    }
}

/// A calendar date `YYYY-MM-DD`: `(year, month, day)`, a real day of the calendar.
///
/// # Errors
/// A sentence saying what is wrong.
pub fn parse_date(text: &str) -> Result<(i32, u32, u32), String> {
    let form = || format!("{text:?} is not a date YYYY-MM-DD (e.g. 2026-06-21)");
    let d = datetime(text).ok_or_else(form)?;
    let (Some(date), None) = (d.date, d.time) else {
        return Err(form());
    };
    let day = (
        i32::from(date.year),
        u32::from(date.month),
        u32::from(date.day),
    );
    let check = CivilTime {
        year: day.0,
        month: day.1,
        day: day.2,
        hour: 0,
        minute: 0,
        second: 0.0,
        utc_offset_min: 0,
    };
    check
        .validate()
        .map_err(|e| format!("{text}: {}", reason(&e)))?;
    Ok(day)
}

/// A clock time `HH:MM` or `HH:MM:SS` (00:00 to 23:59:59), in seconds after midnight.
///
/// # Errors
/// A sentence saying what is wrong.
pub fn parse_clock(text: &str) -> Result<f64, String> {
    let form = || format!("{text:?} is not a time of day HH:MM or HH:MM:SS (e.g. 06:30)");
    let t = text.trim();
    // TOML's local time needs the seconds.
    let full = if t.len() == 5 {
        format!("{t}:00")
    } else {
        t.to_string()
    };
    let d = datetime(&full).ok_or_else(form)?;
    let (None, Some(time)) = (d.date, d.time) else {
        return Err(form());
    };
    if time.second > 59 {
        return Err(format!("{text}: the seconds must be 00 to 59"));
    }
    Ok(f64::from(time.hour) * 3600.0
        + f64::from(time.minute) * 60.0
        + f64::from(time.second)
        + f64::from(time.nanosecond) * 1e-9)
}

/// `time` with its date replaced by `date` and its clock by `seconds` after midnight (in
/// [0, 86400)), its UTC offset kept.
pub fn at_clock(time: &CivilTime, date: (i32, u32, u32), seconds: f64) -> CivilTime {
    let whole = seconds.floor();
    let s = whole as u32;
    CivilTime {
        year: date.0,
        month: date.1,
        day: date.2,
        hour: s / 3600,
        minute: s / 60 % 60,
        second: f64::from(s % 60) + (seconds - whole),
        utc_offset_min: time.utc_offset_min,
    }
}

/// `time` as RFC 3339 text with its offset (seconds shown to the millisecond when not whole).
pub fn format_date_time(time: &CivilTime) -> String {
    let sec = if time.second.fract() == 0.0 {
        format!("{:02}", time.second as u32)
    } else {
        format!("{:06.3}", time.second)
    };
    let off = match time.utc_offset_min {
        0 => "Z".to_string(),
        m => format!(
            "{}{:02}:{:02}",
            if m < 0 { '-' } else { '+' },
            m.abs() / 60,
            m.abs() % 60
        ),
    };
    format!(
        "{:04}-{:02}-{:02}T{:02}:{:02}:{sec}{off}",
        time.year, time.month, time.day, time.hour, time.minute
    )
}
