//! Options whose values are a closed set of the core (`--rank-by`, `--features`): clap's
//! possible values, its help and its errors (exit code 2) are taken from the enum's `ALL` and
//! name function, the one source of the names ([`polbrdf::names`]), as the Python module's
//! `Literal` types are.

use clap::builder::{PossibleValuesParser, TypedValueParser};

/// The value parser of a closed set: the names of `all` (by `name`) are the possible values,
/// each parsed to its member.
pub(crate) fn parser<T>(
    all: &'static [T],
    name: fn(T) -> &'static str,
) -> impl TypedValueParser<Value = T>
where
    T: Copy + Send + Sync + 'static,
{
    PossibleValuesParser::new(all.iter().map(|&t| name(t))).map(move |s| {
        polbrdf::names::find(all, name, &s).expect("clap admits only the possible values")
    })
}
