//! A data block's keys and values, read by the block, table and formula steps alike: the keys
//! with what their errors name, what a block gives, its range as given, and the numbers of a
//! block's values.

use super::yaml::{Ctx, Entry, Node};
use crate::error::{Error, Result};
use polbrdf::optics::dispersion::Dispersion;

/// A data block's keys, with what its errors name: its line and its type.
pub(super) struct BlockKeys<'a> {
    pub(super) entries: &'a [Entry],
    /// The line of the block (its first key).
    pub(super) line: usize,
    /// Its `type`, blanks normalized.
    pub(super) type_name: &'a str,
    pub(super) ctx: &'a Ctx<'a>,
}

impl<'a> BlockKeys<'a> {
    /// The entry of `key`, if given.
    pub(super) fn get(&self, key: &str) -> Option<&'a Entry> {
        self.entries.iter().find(|e| e.key == key)
    }

    /// The error for a missing `key` of the block, `what` saying what it holds.
    pub(super) fn missing(&self, key: &str, what: &str) -> Error {
        self.ctx.field(
            self.line,
            key,
            format!("the `{}` block has no `{key}` ({what})", self.type_name),
        )
    }
}

/// The (n, k) a block gives, each `None` when it gives no such quantity.
pub(super) type Gives = (Option<Dispersion>, Option<Dispersion>);

/// A wavelength range as given (`wavelength_range` or `range`), with its entry.
pub(super) type GivenRange<'a> = Option<(&'a Entry, (f64, f64))>;

/// A range `λ_min λ_max` (µm) with 0 < λ_min < λ_max.
pub(super) fn range_of(e: &Entry, ctx: &Ctx<'_>) -> Result<(f64, f64)> {
    let r = numbers(e, ctx)?;
    let &[lo, hi] = r.as_slice() else {
        return Err(ctx.field(
            e.line,
            &e.key,
            format!("expected two numbers `λ_min λ_max` (µm), got {}", r.len()),
        ));
    };
    if !(lo > 0.0 && lo < hi) {
        return Err(ctx.field(
            e.line,
            &e.key,
            format!("the range must have 0 < λ_min < λ_max (µm), got {lo} {hi}"),
        ));
    }
    Ok((lo, hi))
}

/// A key's value as text (it must be a scalar).
pub(super) fn scalar<'a>(e: &'a Entry, ctx: &Ctx<'_>) -> Result<&'a str> {
    match &e.value {
        Node::Scalar { text, .. } => Ok(text),
        other => Err(ctx.field(
            e.line,
            &e.key,
            format!("expected text, got {}", other.kind()),
        )),
    }
}

/// A number of a file (finite).
pub(super) fn number(cell: &str) -> std::result::Result<f64, String> {
    match cell.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => Err(format!("`{cell}` is not a finite number")),
        Err(_) => Err(format!("`{cell}` is not a number")),
    }
}

/// Blank-separated numbers (coefficients, a range).
pub(super) fn numbers(e: &Entry, ctx: &Ctx<'_>) -> Result<Vec<f64>> {
    let text = scalar(e, ctx)?;
    let v = text
        .split_whitespace()
        .map(number)
        .collect::<std::result::Result<Vec<_>, _>>()
        .map_err(|m| ctx.field(e.line, &e.key, m))?;
    if v.is_empty() {
        return Err(ctx.field(e.line, &e.key, "empty: expected numbers".into()));
    }
    Ok(v)
}
