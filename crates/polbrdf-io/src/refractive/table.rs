//! The rows of a `tabulated` block: validated, sorted by wavelength and made a table of n or
//! k, repeated wavelengths resolved (module docs of `refractive`).

use super::values::{number, BlockKeys, GivenRange, Gives};
use super::yaml::{Ctx, Entry, Node};
use crate::error::Result;
use polbrdf::error::MAX_INDEX;
use polbrdf::optics::dispersion::Dispersion;

/// The columns of a table.
#[derive(Clone, Copy, PartialEq)]
pub(super) enum Columns {
    Nk,
    N,
    K,
}

impl Columns {
    pub(super) fn names(self) -> &'static [&'static str] {
        match self {
            Columns::Nk => &["λ", "n", "k"],
            Columns::N => &["λ", "n"],
            Columns::K => &["λ", "k"],
        }
    }
}

/// What a `tabulated` block of `columns` gives: its `data` rows as tables of n and/or k. A
/// range, if given, must be the table's first and last wavelengths.
pub(super) fn table_block(
    keys: &BlockKeys<'_>,
    columns: Columns,
    range: GivenRange<'_>,
) -> Result<Gives> {
    let data = keys.get("data").ok_or_else(|| {
        keys.missing(
            "data",
            &format!("rows `{}`, usually a `|` block", columns.names().join(" ")),
        )
    })?;
    let rows = parse_rows(data, columns, keys.ctx)?;
    if let Some((r, (lo, hi))) = range {
        let (a, b) = (rows[0][0], rows[rows.len() - 1][0]);
        let near = |x: f64, y: f64| (x - y).abs() <= 1e-9 * y;
        if !(near(lo, a) && near(hi, b)) {
            return Err(keys.ctx.field(
                r.line,
                &r.key,
                format!(
                    "{lo}–{hi} µm, but the table spans {a}–{b} µm (a table's \
                     range, if given, must be its first and last wavelengths)"
                ),
            ));
        }
    }
    let column = |c: usize| table(&rows, c);
    Ok(match columns {
        Columns::Nk => (Some(column(1)), Some(column(2))),
        Columns::N => (Some(column(1)), None),
        Columns::K => (None, Some(column(1))),
    })
}

/// The rows of a table as `[λ, first value, second value]`, validated and sorted by λ
/// (stably: rows with the same λ keep their order).
fn parse_rows(e: &Entry, columns: Columns, ctx: &Ctx<'_>) -> Result<Vec<[f64; 3]>> {
    let Node::Scalar {
        text,
        literal,
        line: start,
    } = &e.value
    else {
        return Err(ctx.field(
            e.line,
            "data",
            format!(
                "expected the rows as text (a `|` block), got {}",
                e.value.kind()
            ),
        ));
    };
    let names = columns.names();
    let mut rows = Vec::new();
    // yaml-rust2 marks a literal block at its first non-blank line, after the leading blank
    // lines that the text keeps as `\n`s; for other styles the rows cannot be placed exactly
    // (their line breaks are folded or escaped), so the scalar's line is given.
    let leading = text.bytes().take_while(|&b| b == b'\n').count();
    for (i, row) in text.split('\n').enumerate() {
        let line = if *literal {
            (start + i).saturating_sub(leading).max(1)
        } else {
            *start
        };
        let cells: Vec<&str> = row.split_whitespace().collect();
        if cells.is_empty() {
            continue;
        }
        let bad = |m: String| ctx.field(line, "data", m);
        if cells.len() != names.len() {
            return Err(bad(format!(
                "a row of {} column{}; `{}` rows have {} (`{}`)",
                cells.len(),
                if cells.len() == 1 { "" } else { "s" },
                match columns {
                    Columns::Nk => "tabulated nk",
                    Columns::N => "tabulated n",
                    Columns::K => "tabulated k",
                },
                names.len(),
                names.join(" ")
            )));
        }
        let mut v = [0.0; 3];
        for (j, cell) in cells.iter().enumerate() {
            let x = number(cell).map_err(|m| bad(format!("{} column: {m}", names[j])))?;
            let problem = match names[j] {
                "λ" if x <= 0.0 => Some("the wavelength must be > 0 µm"),
                "n" if x <= 0.0 => Some("n must be > 0"),
                "k" if x < 0.0 => Some("k must be ≥ 0"),
                "n" | "k" if x > MAX_INDEX => Some("must be ≤ 1e6"),
                _ => None,
            };
            if let Some(p) = problem {
                return Err(bad(format!("{} column: {p}, got {x}", names[j])));
            }
            v[j] = x;
        }
        rows.push(v);
    }
    if rows.is_empty() {
        return Err(ctx.field(e.line, "data", "empty table: no rows".into()));
    }
    rows.sort_by(|a, b| a[0].total_cmp(&b[0]));
    Ok(rows)
}

/// Column `c` of sorted rows as a table, with repeated wavelengths resolved as the module docs
/// say: equal values merge; different values make a jump, the first value stored one ulp
/// below the wavelength (when that is still above the previous wavelength; else it is dropped)
/// and the last at it.
fn table(rows: &[[f64; 3]], c: usize) -> Dispersion {
    let mut wavelengths: Vec<f64> = Vec::with_capacity(rows.len());
    let mut values = Vec::with_capacity(rows.len());
    let mut i = 0;
    while i < rows.len() {
        let l = rows[i][0];
        let j = i + rows[i..].iter().take_while(|r| r[0] == l).count();
        let (first, last) = (rows[i][c], rows[j - 1][c]);
        if first != last {
            let below = l.next_down();
            if wavelengths.last().is_some_and(|&p| p < below) {
                wavelengths.push(below);
                values.push(first);
            }
        }
        wavelengths.push(l);
        values.push(last);
        i = j;
    }
    Dispersion::Table {
        wavelengths,
        values,
    }
}
