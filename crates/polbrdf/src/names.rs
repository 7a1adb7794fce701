//! Closed sets of names. Every enum of the core that files, the command line and the Python
//! module spell by name ([`crate::Form`], [`crate::AzimuthTerm`], [`crate::engine::Precision`],
//! [`crate::analysis::contrast::Ranking`], [`crate::analysis::detection::Feature`],
//! [`crate::analysis::detection::Layout`]) lists its members in `ALL` and names each with one
//! function; the reverse mapping and the messages are derived from those two here, so that a
//! name is written once. The CLI's value parsers and the Python module's `Literal` types take
//! the same two (docs/architecture.md, "One vocabulary").

/// The member of `all` named `s` (by `name`), or `None`.
pub fn find<T: Copy>(all: &[T], name: impl Fn(T) -> &'static str, s: &str) -> Option<T> {
    all.iter().copied().find(|&t| name(t) == s)
}

/// The names of `all`, quoted, for messages: `"a" or "b"`, `"a", "b" or "c"`.
pub fn quoted<T: Copy>(all: &[T], name: impl Fn(T) -> &'static str) -> String {
    let names: Vec<String> = all.iter().map(|&t| format!("{:?}", name(t))).collect();
    match names.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} or {last}", rest.join(", ")),
        Some((last, _)) => last.clone(),
        None => String::new(),
    }
}

/// The member of `all` named `s`, or the message `expected "a" or "b", got "s"`.
///
/// # Errors
/// That message, when no member is named `s`.
pub fn parse<T: Copy>(
    all: &[T],
    name: impl Fn(T) -> &'static str + Copy,
    s: &str,
) -> Result<T, String> {
    find(all, name, s).ok_or_else(|| format!("expected {}, got {s:?}", quoted(all, name)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::contrast::Ranking;
    use crate::analysis::detection::{Feature, Layout};
    use crate::engine::Precision;
    use crate::{AzimuthTerm, Form};

    /// Every member's name parses back to it, names are distinct, and an unknown name is
    /// refused with every name in the message.
    fn round_trip<T: Copy + PartialEq + std::fmt::Debug>(all: &[T], name: fn(T) -> &'static str) {
        for &t in all {
            assert_eq!(parse(all, name, name(t)), Ok(t));
            assert_eq!(all.iter().filter(|&&u| name(u) == name(t)).count(), 1);
        }
        let e = parse(all, name, "no-such-name").unwrap_err();
        for &t in all {
            assert!(e.contains(&format!("{:?}", name(t))), "{e}");
        }
    }

    #[test]
    fn every_closed_set_round_trips_through_its_names() {
        round_trip(&Form::ALL, |f| f.as_str());
        round_trip(&AzimuthTerm::ALL, |a| a.as_str());
        round_trip(&Precision::ALL, Precision::name);
        round_trip(&Ranking::ALL, |r| r.as_str());
        round_trip(&Feature::ALL, Feature::as_str);
        round_trip(&Layout::ALL, Layout::as_str);
        assert_eq!(
            parse(&Form::ALL, |f| f.as_str(), "fancy"),
            Err("expected \"standard\" or \"paper\", got \"fancy\"".into())
        );
        assert_eq!(
            quoted(&Feature::ALL, Feature::as_str),
            "\"s0\", \"dolp\" or \"s0+dolp\""
        );
        // The parsers of the enums are these.
        assert_eq!("eq3".parse::<AzimuthTerm>(), Ok(AzimuthTerm::Eq3));
        assert_eq!(
            "x".parse::<Ranking>(),
            Err("expected \"delta-dolp\" or \"polarization-contrast\", got \"x\"".into())
        );
        assert_eq!(Layout::parse("per-pixel"), Some(Layout::PerPixel));
        assert_eq!("f32".parse::<Precision>().ok(), Some(Precision::F32));
    }
}
