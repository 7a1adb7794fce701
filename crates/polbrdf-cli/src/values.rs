//! The value parsers of the numeric options, each carrying its option's range, and of the text
//! options with a closed syntax (dates, times, parameter lists): clap refuses a value outside
//! its range or syntax as a usage error naming the option (exit code 2), before any file is
//! read.
//! One parser per option, written at the option (`value_parser = values::zenith()`); the
//! ranges are the task layer's (which checks its requests again, for Python).
//!
//! A unit test of `lib.rs` walks the clap command tree, feeds every option of a numeric type
//! (the types of [`numeric_types`]) invalid and out-of-range values, and holds each refused by
//! its parser with exit code 2 or accepted by the command (never refused later as input data).

/// A range of `f64`: both ends, each closed or open; always finite.
#[derive(Debug, Clone, Copy)]
pub struct Range {
    lo: f64,
    lo_closed: bool,
    hi: f64,
    hi_closed: bool,
}

impl Range {
    /// `[lo, hi]`.
    pub const fn closed(lo: f64, hi: f64) -> Self {
        Range {
            lo,
            lo_closed: true,
            hi,
            hi_closed: true,
        }
    }

    /// `(lo, hi)`.
    pub const fn open(lo: f64, hi: f64) -> Self {
        Range {
            lo,
            lo_closed: false,
            hi,
            hi_closed: false,
        }
    }

    /// `[lo, hi)`.
    pub const fn closed_open(lo: f64, hi: f64) -> Self {
        Range {
            lo,
            lo_closed: true,
            hi,
            hi_closed: false,
        }
    }

    /// `(lo, hi]`.
    pub const fn open_closed(lo: f64, hi: f64) -> Self {
        Range {
            lo,
            lo_closed: false,
            hi,
            hi_closed: true,
        }
    }

    /// Any finite number.
    pub const FINITE: Range = Range::closed(f64::MIN, f64::MAX);
    /// A zenith angle, degrees: `[0, 90)`.
    pub const ZENITH: Range = Range::closed_open(0.0, 90.0);
    /// An azimuth, degrees: finite, at most [`polbrdf::MAX_AZIMUTH_DEG`] in magnitude.
    pub const AZIMUTH: Range = Range::closed(-polbrdf::MAX_AZIMUTH_DEG, polbrdf::MAX_AZIMUTH_DEG);
    /// Finite and > 0.
    pub const POSITIVE: Range = Range::open_closed(0.0, f64::MAX);
    /// A probability strictly between 0 and 1.
    pub const PROBABILITY: Range = Range::open(0.0, 1.0);

    /// `x` inside the range.
    pub fn contains(&self, x: f64) -> bool {
        x.is_finite()
            && (if self.lo_closed {
                x >= self.lo
            } else {
                x > self.lo
            })
            && (if self.hi_closed {
                x <= self.hi
            } else {
                x < self.hi
            })
    }

    /// The range in words, for a message.
    fn describe(&self) -> String {
        let big = |x: f64| x.abs() == f64::MAX;
        match (big(self.lo), big(self.hi)) {
            (true, true) => "a finite number".into(),
            (false, true) if self.lo_closed => format!("a finite number ≥ {}", self.lo),
            (false, true) => format!("a finite number > {}", self.lo),
            _ => format!(
                "in {}{}, {}{}",
                if self.lo_closed { '[' } else { '(' },
                self.lo,
                self.hi,
                if self.hi_closed { ']' } else { ')' }
            ),
        }
    }

    /// `text` as a number in the range, or the message of clap's usage error.
    pub fn parse(&self, text: &str) -> Result<f64, String> {
        let x: f64 = text
            .trim()
            .parse()
            .map_err(|_| format!("{text:?} is not a number"))?;
        if self.contains(x) {
            Ok(x)
        } else {
            Err(format!("{x} is out of range: expected {}", self.describe()))
        }
    }
}

/// A parser of one number in `range`.
pub fn number(range: Range) -> impl Fn(&str) -> Result<f64, String> + Clone + Send + Sync {
    move |text| range.parse(text)
}

/// A zenith angle in degrees, `[0, 90)`.
pub fn zenith() -> impl Fn(&str) -> Result<f64, String> + Clone + Send + Sync {
    number(Range::ZENITH)
}

/// An azimuth in degrees (finite, at most 1e8° in magnitude).
pub fn azimuth() -> impl Fn(&str) -> Result<f64, String> + Clone + Send + Sync {
    number(Range::AZIMUTH)
}

/// A finite number > 0.
pub fn positive() -> impl Fn(&str) -> Result<f64, String> + Clone + Send + Sync {
    number(Range::POSITIVE)
}

/// A probability in (0, 1).
pub fn probability() -> impl Fn(&str) -> Result<f64, String> + Clone + Send + Sync {
    number(Range::PROBABILITY)
}

/// A count in `lo..=hi`.
pub fn count(lo: usize, hi: usize) -> impl Fn(&str) -> Result<usize, String> + Clone + Send + Sync {
    move |text| {
        let n: usize = text
            .trim()
            .parse()
            .map_err(|_| format!("{text:?} is not a whole number"))?;
        if (lo..=hi).contains(&n) {
            Ok(n)
        } else if n < lo || hi == usize::MAX {
            Err(format!(
                "{n} is out of range: expected a whole number ≥ {lo}"
            ))
        } else {
            Err(format!(
                "{n} is out of range: at most {hi} (the limit of this option; see \
                 docs/reliability.md)"
            ))
        }
    }
}

/// Numbers separated by commas, `ranges.len()` of them, each in its range.
fn numbers(text: &str, ranges: &[Range], what: &str) -> Result<Vec<f64>, String> {
    let fields: Vec<&str> = text.split(',').collect();
    if fields.len() != ranges.len() {
        return Err(format!(
            "expected {what}: {} numbers separated by commas",
            ranges.len()
        ));
    }
    fields.iter().zip(ranges).map(|(t, r)| r.parse(t)).collect()
}

/// Two numbers `A,B`, each in its range.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pair(pub f64, pub f64);

/// A parser of `A,B` (`what` names them in the message).
pub fn pair(
    a: Range,
    b: Range,
    what: &'static str,
) -> impl Fn(&str) -> Result<Pair, String> + Clone + Send + Sync {
    move |text| numbers(text, &[a, b], what).map(|v| Pair(v[0], v[1]))
}

/// Four numbers `A,B,C,D`, each in its range.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Quad(pub [f64; 4]);

/// A parser of `A,B,C,D`.
pub fn quad(
    ranges: [Range; 4],
    what: &'static str,
) -> impl Fn(&str) -> Result<Quad, String> + Clone + Send + Sync {
    move |text| numbers(text, &ranges, what).map(|v| Quad([v[0], v[1], v[2], v[3]]))
}

/// An incident Stokes vector `S0,S1,S2,S3`, physical (S0 > 0, degree of polarization ≤ 1) as
/// the core's illumination accepts it (`Illumination::from_degrees`, the one rule).
pub fn stokes() -> impl Fn(&str) -> Result<Quad, String> + Clone + Send + Sync {
    |text| {
        let q = quad([Range::FINITE; 4], "S0,S1,S2,S3")(text)?;
        polbrdf::analysis::contrast::Illumination::from_degrees(0.0, 0.0, polbrdf::Stokes(q.0))
            .map_err(|e| e.to_string())?;
        Ok(q)
    }
}

/// The viewing grid's steps `DTHETA[,DPHI]` in degrees (one value: both), as the task layer's
/// view grid accepts them (`polbrdf_tasks::hemisphere::view_grid`: the one rule). Its
/// [`std::fmt::Display`] shows a default in the help.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GridDeg(pub (f64, f64));

impl std::fmt::Display for GridDeg {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{},{}", self.0 .0, self.0 .1)
    }
}

impl std::str::FromStr for GridDeg {
    type Err = String;

    fn from_str(text: &str) -> Result<Self, String> {
        let what = "DTHETA or DTHETA,DPHI in degrees";
        let v: Vec<f64> = text
            .split(',')
            .map(|t| Range::POSITIVE.parse(t))
            .collect::<Result<_, _>>()?;
        let steps = match v[..] {
            [a] => (a, a),
            [a, b] => (a, b),
            _ => return Err(format!("expected {what}")),
        };
        polbrdf_tasks::hemisphere::view_grid(steps).map_err(|e| e.to_string())?;
        Ok(GridDeg(steps))
    }
}

/// A parser of a text option with a closed syntax: `check` is the parser of the layer that
/// uses the value (polbrdf-io's `date_time`, polbrdf-fit's parameter list: one parser, not a
/// copy), so clap refuses a malformed value as a usage error naming the option (exit code 2)
/// before any file is read. The value is kept as text for the task's request, which checks it
/// again (for Python).
fn checked<T, E: std::fmt::Display>(
    check: fn(&str) -> Result<T, E>,
) -> impl Fn(&str) -> Result<String, String> + Clone + Send + Sync {
    move |text| {
        check(text)
            .map(|_| text.to_string())
            .map_err(|e| e.to_string())
    }
}

/// A calendar date `YYYY-MM-DD` ([`polbrdf_io::date_time::parse_date`]).
pub fn date() -> impl Fn(&str) -> Result<String, String> + Clone + Send + Sync {
    checked(polbrdf_io::date_time::parse_date)
}

/// A time of day `HH:MM[:SS]` ([`polbrdf_io::date_time::parse_clock`]).
pub fn clock() -> impl Fn(&str) -> Result<String, String> + Clone + Send + Sync {
    checked(polbrdf_io::date_time::parse_clock)
}

/// A date and time with its UTC offset, RFC 3339
/// ([`polbrdf_io::date_time::parse_date_time`]).
pub fn date_time() -> impl Fn(&str) -> Result<String, String> + Clone + Send + Sync {
    checked(polbrdf_io::date_time::parse_date_time)
}

/// A list of free fit parameters, `n,sigma_deg,…` ([`polbrdf_fit::Param::parse_list`]).
pub fn free_parameters() -> impl Fn(&str) -> Result<String, String> + Clone + Send + Sync {
    checked(polbrdf_fit::Param::parse_list)
}

/// The value types of the numeric options (the unit test of `lib.rs` probes every option of
/// one of these types).
#[cfg(test)]
pub fn numeric_types() -> [std::any::TypeId; 9] {
    use std::any::TypeId;
    [
        TypeId::of::<f64>(),
        TypeId::of::<usize>(),
        TypeId::of::<u64>(),
        TypeId::of::<u32>(),
        TypeId::of::<u16>(),
        TypeId::of::<Pair>(),
        TypeId::of::<Quad>(),
        TypeId::of::<GridDeg>(),
        TypeId::of::<[usize; 3]>(),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_hold_their_ends() {
        assert!(Range::ZENITH.contains(0.0) && !Range::ZENITH.contains(90.0));
        assert!(!Range::POSITIVE.contains(0.0) && Range::POSITIVE.contains(1e-300));
        assert!(!Range::FINITE.contains(f64::NAN) && !Range::FINITE.contains(f64::INFINITY));
        assert_eq!(
            zenith()("90").unwrap_err(),
            "90 is out of range: expected in [0, 90)"
        );
        assert_eq!(
            count(1, 10)("0").unwrap_err().split(':').next(),
            Some("0 is out of range")
        );
        assert_eq!(
            pair(Range::ZENITH, Range::AZIMUTH, "THETA,PHI")("10,-5"),
            Ok(Pair(10.0, -5.0))
        );
        assert!(pair(Range::ZENITH, Range::AZIMUTH, "THETA,PHI")("10").is_err());
        assert_eq!("2".parse::<GridDeg>(), Ok(GridDeg((2.0, 2.0))));
        assert!("0".parse::<GridDeg>().is_err());
    }

    #[test]
    fn text_options_keep_their_text_and_refuse_with_the_io_layer_s_message() {
        assert_eq!(date()("2026-06-21"), Ok("2026-06-21".into()));
        assert_eq!(
            date()("2026-02-30").unwrap_err(),
            polbrdf_io::date_time::parse_date("2026-02-30").unwrap_err()
        );
        assert_eq!(clock()("06:30"), Ok("06:30".into()));
        assert!(clock()("24:00").is_err() && clock()("6h").is_err());
        assert_eq!(
            date_time()("2026-06-21T12:00:00Z"),
            Ok("2026-06-21T12:00:00Z".into())
        );
        assert!(date_time()("2026-06-21T12:00:00").is_err());
        assert_eq!(free_parameters()("n,rho_d"), Ok("n,rho_d".into()));
        assert!(free_parameters()("n,colour")
            .unwrap_err()
            .contains("colour"));
    }
}
