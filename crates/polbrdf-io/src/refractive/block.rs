//! A data block of `DATA` (`- type: …` with its keys): its type, the keys it may hold, its
//! range, and what it gives (n, k or both), read by the table or formula steps.

use super::formula::formula_block;
use super::table::{table_block, Columns};
use super::values::{range_of, scalar, BlockKeys, GivenRange};
use super::yaml::{Ctx, Entry, Node};
use crate::error::Result;
use polbrdf::optics::dispersion::Dispersion;

/// A parsed data block: what it gives.
pub(super) struct Block {
    pub(super) type_name: String,
    pub(super) type_line: usize,
    pub(super) n: Option<Dispersion>,
    pub(super) k: Option<Dispersion>,
}

/// What a block's type makes of it.
#[derive(Clone, Copy)]
enum Kind {
    Table(Columns),
    Formula(u8),
}

const KNOWN_TYPES: &str = "tabulated nk, tabulated n, tabulated k, formula 1 … formula 9";

/// Parses one item of `DATA`: its type, then the keys of that type (no others), its range, and
/// the table or formula it gives.
pub(super) fn parse_block(item: &Node, ctx: &Ctx<'_>) -> Result<Block> {
    let Node::Map { entries, line } = item else {
        return Err(ctx.field(
            item.line(),
            "DATA",
            format!(
                "a data block must be a mapping (`- type: …` with its keys), got {}",
                item.kind()
            ),
        ));
    };
    let ty = entries.iter().find(|e| e.key == "type").ok_or_else(|| {
        ctx.field(
            *line,
            "type",
            format!("the data block has no `type` (one of: {KNOWN_TYPES})"),
        )
    })?;
    let type_name = scalar(ty, ctx)?
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ");
    let kind = block_kind(ty, &type_name, ctx)?;
    let keys = BlockKeys {
        entries,
        line: *line,
        type_name: &type_name,
        ctx,
    };
    check_keys(&keys, kind)?;
    let range = block_range(&keys)?;
    let (n, k) = match kind {
        Kind::Table(columns) => table_block(&keys, columns, range)?,
        Kind::Formula(kind) => formula_block(&keys, kind, range)?,
    };
    Ok(Block {
        type_name,
        type_line: ty.line,
        n,
        k,
    })
}

/// The kind of a block of type `type_name` (its `type` entry `ty`): a table of its columns or
/// a formula 1–9; `tabulated n2` and unknown types are errors.
fn block_kind(ty: &Entry, type_name: &str, ctx: &Ctx<'_>) -> Result<Kind> {
    Ok(match type_name {
        "tabulated nk" => Kind::Table(Columns::Nk),
        "tabulated n" => Kind::Table(Columns::N),
        "tabulated k" => Kind::Table(Columns::K),
        "tabulated n2" => {
            return Err(ctx.field(
                ty.line,
                "type",
                "`tabulated n2` is the nonlinear index n₂ (the database's n2 catalogue), not a \
                 linear refractive index"
                    .into(),
            ))
        }
        t => match t.strip_prefix("formula ").map(str::as_bytes) {
            Some(&[d @ b'1'..=b'9']) => Kind::Formula(d - b'0'),
            _ => {
                return Err(ctx.field(
                    ty.line,
                    "type",
                    format!("unknown type `{t}` (known: {KNOWN_TYPES})"),
                ))
            }
        },
    })
}

/// The block holds only the keys of its kind (the first other one is an error).
fn check_keys(keys: &BlockKeys<'_>, kind: Kind) -> Result<()> {
    let allowed: &[&str] = match kind {
        Kind::Table(_) => &["type", "data", "wavelength_range", "range"],
        Kind::Formula(_) => &["type", "coefficients", "wavelength_range", "range"],
    };
    if let Some(e) = keys
        .entries
        .iter()
        .find(|e| !allowed.contains(&e.key.as_str()))
    {
        return Err(keys.ctx.field(
            e.line,
            &e.key,
            format!(
                "not a key of a `{}` block (its keys: {})",
                keys.type_name,
                allowed
                    .iter()
                    .filter(|k| **k != "range")
                    .copied()
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        ));
    }
    Ok(())
}

/// The block's range, `wavelength_range` or its older name `range` (not both), if given.
fn block_range<'a>(keys: &BlockKeys<'a>) -> Result<GivenRange<'a>> {
    Ok(match (keys.get("wavelength_range"), keys.get("range")) {
        (Some(a), Some(b)) => {
            return Err(keys.ctx.field(
                b.line,
                "range",
                format!(
                    "both `range` and `wavelength_range` (line {}) are given; give one",
                    a.line
                ),
            ))
        }
        (Some(r), None) | (None, Some(r)) => Some((r, range_of(r, keys.ctx)?)),
        (None, None) => None,
    })
}
