//! Names, lists and numbers as error messages quote them: each cut to a bounded length, so that
//! every message stays short whatever the file holds.

/// The most characters of one name (CSV column, TOML key) quoted in a message; longer names are
/// cut with `…` so that every message stays under the project's 2 kB bound.
pub const MAX_NAME_IN_MESSAGE: usize = 80;

/// The most characters of a list of names (the header, the keys of a table) in a message.
pub const MAX_LIST_IN_MESSAGE: usize = 1000;

/// `name` for a message: at most [`MAX_NAME_IN_MESSAGE`] characters.
pub fn short_name(name: &str) -> String {
    cut(name, MAX_NAME_IN_MESSAGE)
}

/// `names` joined by `, ` for a message: at most [`MAX_LIST_IN_MESSAGE`] characters, each name
/// shortened, and the number of names left out said.
pub fn short_list<S: AsRef<str>>(names: &[S]) -> String {
    let mut out = String::new();
    for (i, n) in names.iter().enumerate() {
        let n = short_name(n.as_ref());
        if out.len() + n.len() > MAX_LIST_IN_MESSAGE {
            out.push_str(&format!(" … and {} more", names.len() - i));
            break;
        }
        if i > 0 {
            out.push_str(", ");
        }
        out.push_str(&n);
    }
    out
}

/// A message from another crate (the TOML parser's, which may quote a key), cut to 1000
/// characters.
pub(crate) fn short_message(m: &str) -> String {
    cut(m, MAX_LIST_IN_MESSAGE)
}

pub(super) fn cut(s: &str, max: usize) -> String {
    if s.chars().count() > max {
        s.chars().take(max).collect::<String>() + "…"
    } else {
        s.to_string()
    }
}

/// A number in a message: as it would be written, in exponent form when very large or small
/// (as the core's messages show values).
pub(crate) fn show(v: f64) -> String {
    if v == 0.0 || !v.is_finite() || (1e-5..1e16).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}
