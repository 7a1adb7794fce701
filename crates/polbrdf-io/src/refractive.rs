//! Refractive-index files in the format of the refractiveindex.info database (its YAML files,
//! documented in the database's "Dispersion formulas"), read into the core's
//! [`SpectralIndex`]. Wavelengths are in µm.
//!
//! # The format
//!
//! A file is a YAML mapping. `REFERENCES` and `COMMENTS` (text) are carried into the
//! [`SpectralIndex`] as written; `DATA` is a list of blocks, each a mapping with a `type`:
//!
//! * `tabulated nk`, `tabulated n`, `tabulated k`: a `data` text (normally a `|` block) of
//!   rows `λ n k`, `λ n` or `λ k`, blank-separated; blank lines are skipped;
//! * `formula 1` … `formula 9`: `coefficients` (C1 C2 …, blank-separated) and
//!   `wavelength_range` (or its older name `range`): `λ_min λ_max`.
//!
//! Other top-level keys (`CONDITIONS`, `PROPERTIES`, `SPECS`, `NAMES`, `LINKS`, …) are ignored.
//! A block may hold only the keys of its type; a table may repeat its range as
//! `wavelength_range` (one database file does), which must then be its first and last
//! wavelengths.
//!
//! # Rules (where the format leaves a choice)
//!
//! * **One source per quantity.** n comes from one block (a formula, `tabulated n` or
//!   `tabulated nk`) and k from at most one (`tabulated k` or `tabulated nk`); a second block
//!   giving the same quantity is an error naming both lines (the database's own reader lets
//!   the last one win silently). Without a k block, k is absent and the core takes k = 0.
//!   A file with k but no n, or whose n and k ranges do not overlap, is an error.
//! * **`tabulated n2`** (the nonlinear index n₂ of the database's n2 catalogue) is refused: it
//!   is not a linear refractive index.
//! * **Unsorted tables** are sorted by wavelength, keeping each row's values together (a stable
//!   sort, as the database's reader does).
//! * **Repeated wavelengths** keep the database's behaviour. Rows that repeat a wavelength with
//!   the same value are merged. With different values (the database has a few dozen, e.g. where
//!   two spectrometers' ranges meet), the table jumps there, as with the database's reader
//!   (SciPy's linear `interp1d`, which calls NumPy's `interp`): below the wavelength it
//!   interpolates towards the first value, at it and above it from the last (rows in file
//!   order). The first value is stored one ulp below the wavelength, so the table stays
//!   strictly increasing; at the table's first wavelength only the last value is kept.
//! * **Values**: every number must be finite; wavelengths > 0; in tables 0 < n ≤ 10⁶ and
//!   0 ≤ k ≤ 10⁶ ([`polbrdf::error::MAX_INDEX`]). k < 0 (gain) is refused although a few
//!   database tables have it as measurement noise (Querry's sapphire and hematite, e.g.).
//! * **Formulas**: the range must have 0 < λ_min < λ_max, and the formula must give a valid n
//!   over all of it: a pole inside it is an error, and 0 < n ≤ 10⁶ is checked at both ends,
//!   at the geometric mean and at 2 × 1024 points spread linearly and logarithmically over
//!   it, `λ_min + (λ_max − λ_min)·(i/1024)` among them (formula 9 also at the extremes of its
//!   resonance term). Six database pages have a resonance pole inside their stated range and
//!   are refused so (`CS2/Chemnitz`, `GaSe/Chen-n-e`, `-o`, `GaSe/Kato-e`, `-o`,
//!   `Xe/Bideau-Mehu`).
//! * **Coefficient counts**: formulas 1, 2 and 3 take C1 then pairs (C2, C3), …, so an odd
//!   number up to 17; 5 and 6 likewise up to 11; 4 takes C1, C2–C5, C6–C9, then pairs from
//!   C10: 1, 5, or an odd number from 9 to 17; 7 and 9 take up to 6 and 8 up to 4 (missing
//!   trailing ones are 0: their terms are independent). An even count for a pair formula is
//!   an error, not a zero: the database's one such file, `AgGaSe2/Boyd-o` (formula 2, four
//!   coefficients), has lost its fifth (its `-e` sibling has 1600 there), and a zero would
//!   add a constant.
//! * **YAML**: one document; aliases (`*name`) are refused; nesting is limited to 64 levels.
//!
//! Every error names the file and, where there is one, the 1-based line and the field
//! (`DATA`, `type`, `data`, `coefficients`, `wavelength_range`, …).

use crate::error::{Error, Result};
use polbrdf::error::MAX_INDEX;
use polbrdf::optics::dispersion::{Dispersion, SpectralIndex};
use std::path::Path;
use yaml_rust2::parser::{Event, Parser};
use yaml_rust2::scanner::TScalarStyle;

/// Deepest nesting of YAML collections accepted (the database needs 3).
const MAX_DEPTH: usize = 64;

/// Points per spread (linear, then logarithmic) at which a formula is checked.
const CHECK_POINTS: usize = 1024;

/// Reads a refractiveindex.info YAML file. Its [`SpectralIndex::name`] is `<book>/<page>`
/// taken from the path: the file's stem, after the name of its folder, skipping a folder
/// named `nk` (the database lays its files out as `…/<book>/nk/<page>.yml`, the polbrdf
/// library as `<book>/<page>.yml`): `data/main/Au/nk/Johnson.yml` is `Au/Johnson`. A file
/// with no folder in its path is named by its stem.
///
/// # Errors
/// [`Error::Read`] if the file cannot be read; otherwise as
/// [`parse_refractiveindex_yaml_bytes`].
pub fn read_refractiveindex_yaml(path: &Path) -> Result<SpectralIndex> {
    let bytes = crate::csv_io::read_all(path)?;
    parse_refractiveindex_yaml_bytes(&bytes, path, &name_of(path))
}

/// `<book>/<page>` of a path (see [`read_refractiveindex_yaml`]).
fn name_of(path: &Path) -> String {
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| path.display().to_string());
    let folders: Vec<String> = path
        .parent()
        .into_iter()
        .flat_map(|p| p.components().rev())
        .filter_map(|c| match c {
            std::path::Component::Normal(s) => Some(s.to_string_lossy().into_owned()),
            _ => None,
        })
        .take(2)
        .collect();
    let book = match folders.as_slice() {
        [nk, book, ..] if nk == "nk" => Some(book),
        [folder, ..] => Some(folder),
        [] => None,
    };
    match book {
        Some(book) => format!("{book}/{stem}"),
        None => stem,
    }
}

/// Parses the bytes of a refractiveindex.info YAML file (the entry point for untrusted
/// input); `path` is used in messages only and `name` becomes [`SpectralIndex::name`].
///
/// # Errors
/// [`Error::Syntax`] if the bytes are not UTF-8 (with the line of the first bad byte);
/// otherwise as [`parse_refractiveindex_yaml`].
pub fn parse_refractiveindex_yaml_bytes(
    bytes: &[u8],
    path: &Path,
    name: &str,
) -> Result<SpectralIndex> {
    let text = std::str::from_utf8(bytes).map_err(|e| Error::Syntax {
        path: path.to_path_buf(),
        line: bytes[..e.valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count()
            + 1,
        message: "file is not valid UTF-8 text".into(),
    })?;
    parse_refractiveindex_yaml(text, path, name)
}

/// Parses the text of a refractiveindex.info YAML file (see the [module docs](self) for the
/// format and the rules); `path` is used in messages only and `name` becomes
/// [`SpectralIndex::name`] (the name the core's out-of-range errors give).
///
/// # Errors
/// [`Error::Syntax`] for malformed YAML (with its line); [`Error::Field`] for a key with a bad
/// value, naming its line and the key (`DATA`, `type`, `data`, `coefficients`,
/// `wavelength_range`, …); [`Error::File`] for an empty file or one without `DATA`.
pub fn parse_refractiveindex_yaml(text: &str, path: &Path, name: &str) -> Result<SpectralIndex> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let ctx = Ctx { path };
    let root = load_tree(text, &ctx)?.ok_or_else(|| ctx.file("empty file: no YAML content"))?;
    let Node::Map { entries, .. } = &root else {
        return Err(ctx.syntax(
            root.line(),
            format!(
                "the top level is {}; a refractiveindex.info file is a mapping with \
                 REFERENCES, COMMENTS and DATA",
                root.kind()
            ),
        ));
    };
    let text_of = |key: &str| -> Result<String> {
        match entries.iter().find(|e| e.key == key) {
            None => Ok(String::new()),
            Some(Entry {
                value: Node::Scalar { text, .. },
                ..
            }) => Ok(text.clone()),
            Some(e) => Err(ctx.field(
                e.line,
                key,
                format!("expected text, got {}", e.value.kind()),
            )),
        }
    };
    let references = text_of("REFERENCES")?;
    let comments = text_of("COMMENTS")?;
    let data = entries.iter().find(|e| e.key == "DATA").ok_or_else(|| {
        ctx.file(
            "no DATA: a refractiveindex.info file lists its data under `DATA:` \
             (`- type: tabulated nk`, `- type: formula 2`, …)",
        )
    })?;
    let Node::Seq { items, .. } = &data.value else {
        return Err(ctx.field(
            data.line,
            "DATA",
            format!(
                "expected a list of data blocks (`- type: …`), got {}",
                data.value.kind()
            ),
        ));
    };
    if items.is_empty() {
        return Err(ctx.field(data.line, "DATA", "the list of data blocks is empty".into()));
    }

    let mut n: Option<Source> = None;
    let mut k: Option<Source> = None;
    for item in items {
        let block = parse_block(item, &ctx)?;
        for (quantity, dispersion, slot) in [("n", block.n, &mut n), ("k", block.k, &mut k)] {
            let Some(dispersion) = dispersion else {
                continue;
            };
            if let Some(first) = slot {
                return Err(ctx.field(
                    block.type_line,
                    "type",
                    format!(
                        "a second block giving {quantity} (`{}`; the `{}` block at line {} \
                         already gives it): a file gives n once and k at most once",
                        block.type_name, first.type_name, first.line
                    ),
                ));
            }
            *slot = Some(Source {
                dispersion,
                type_name: block.type_name.clone(),
                line: block.type_line,
            });
        }
    }
    let Some(n) = n else {
        return Err(ctx.field(
            data.line,
            "DATA",
            "no block gives the real index n (only k is given)".into(),
        ));
    };
    let k = k.map(|k| k.dispersion);
    if let Some(k) = &k {
        let ((a, b), (c, d)) = (n.dispersion.range(), k.range());
        if a.max(c) > b.min(d) {
            return Err(ctx.field(
                data.line,
                "DATA",
                format!(
                    "the n data ({a}–{b} µm) and the k data ({c}–{d} µm) do not overlap: \
                     the index is defined nowhere"
                ),
            ));
        }
    }
    Ok(SpectralIndex {
        name: name.to_string(),
        n: n.dispersion,
        k,
        references,
        comments,
    })
}

/// The coefficient counts formula `kind` (1–9) accepts and their rule in words (module docs).
fn coefficient_counts(kind: u8) -> Option<(Vec<usize>, &'static str)> {
    let odd_to = |max: usize| (1..=max).step_by(2).collect::<Vec<_>>();
    Some(match kind {
        1..=3 => (
            odd_to(17),
            "C1, then pairs (C2, C3), (C4, C5), …: an odd number, at most 17",
        ),
        4 => (
            [1, 5].into_iter().chain((9..=17).step_by(2)).collect(),
            "C1, then C2–C5, C6–C9, then pairs (C10, C11), …: 1, 5, 9, 11, …, 17",
        ),
        5 | 6 => (
            odd_to(11),
            "C1, then pairs (C2, C3), (C4, C5), …: an odd number, at most 11",
        ),
        7 | 9 => ((1..=6).collect(), "C1 to C6 (missing ones are 0)"),
        8 => ((1..=4).collect(), "C1 to C4 (missing ones are 0)"),
        _ => return None,
    })
}

/// Where a quantity comes from, for the message when a second block gives it too.
struct Source {
    dispersion: Dispersion,
    type_name: String,
    line: usize,
}

/// A parsed data block: what it gives.
struct Block {
    type_name: String,
    type_line: usize,
    n: Option<Dispersion>,
    k: Option<Dispersion>,
}

/// The columns of a table.
#[derive(Clone, Copy, PartialEq)]
enum Columns {
    Nk,
    N,
    K,
}

impl Columns {
    fn names(self) -> &'static [&'static str] {
        match self {
            Columns::Nk => &["λ", "n", "k"],
            Columns::N => &["λ", "n"],
            Columns::K => &["λ", "k"],
        }
    }
}

enum Kind {
    Table(Columns),
    Formula(u8),
}

const KNOWN_TYPES: &str = "tabulated nk, tabulated n, tabulated k, formula 1 … formula 9";

fn parse_block(item: &Node, ctx: &Ctx<'_>) -> Result<Block> {
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
    let kind =
        match type_name.as_str() {
            "tabulated nk" => Kind::Table(Columns::Nk),
            "tabulated n" => Kind::Table(Columns::N),
            "tabulated k" => Kind::Table(Columns::K),
            "tabulated n2" => return Err(ctx.field(
                ty.line,
                "type",
                "`tabulated n2` is the nonlinear index n₂ (the database's n2 catalogue), not a \
                 linear refractive index"
                    .into(),
            )),
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
        };
    let allowed: &[&str] = match kind {
        Kind::Table(_) => &["type", "data", "wavelength_range", "range"],
        Kind::Formula(_) => &["type", "coefficients", "wavelength_range", "range"],
    };
    if let Some(e) = entries.iter().find(|e| !allowed.contains(&e.key.as_str())) {
        return Err(ctx.field(
            e.line,
            &e.key,
            format!(
                "not a key of a `{type_name}` block (its keys: {})",
                allowed
                    .iter()
                    .filter(|k| **k != "range")
                    .copied()
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        ));
    }
    let get = |key: &str| entries.iter().find(|e| e.key == key);
    let missing = |key: &str, what: &str| {
        ctx.field(
            *line,
            key,
            format!("the `{type_name}` block has no `{key}` ({what})"),
        )
    };
    let range = match (get("wavelength_range"), get("range")) {
        (Some(a), Some(b)) => {
            return Err(ctx.field(
                b.line,
                "range",
                format!(
                    "both `range` and `wavelength_range` (line {}) are given; give one",
                    a.line
                ),
            ))
        }
        (Some(r), None) | (None, Some(r)) => Some((r, range_of(r, ctx)?)),
        (None, None) => None,
    };
    let (n, k) = match kind {
        Kind::Table(columns) => {
            let data = get("data").ok_or_else(|| {
                missing(
                    "data",
                    &format!("rows `{}`, usually a `|` block", columns.names().join(" ")),
                )
            })?;
            let rows = parse_rows(data, columns, ctx)?;
            if let Some((r, (lo, hi))) = range {
                let (a, b) = (rows[0][0], rows[rows.len() - 1][0]);
                let near = |x: f64, y: f64| (x - y).abs() <= 1e-9 * y;
                if !(near(lo, a) && near(hi, b)) {
                    return Err(ctx.field(
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
            match columns {
                Columns::Nk => (Some(column(1)), Some(column(2))),
                Columns::N => (Some(column(1)), None),
                Columns::K => (None, Some(column(1))),
            }
        }
        Kind::Formula(kind) => {
            let coefficients = get("coefficients")
                .ok_or_else(|| missing("coefficients", "C1 C2 …, separated by blanks"))?;
            let Some((_, (lo, hi))) = range else {
                return Err(missing(
                    "wavelength_range",
                    "`λ_min λ_max` in µm, where the formula holds",
                ));
            };
            let c = numbers(coefficients, ctx)?;
            let (counts, rule) = coefficient_counts(kind).unwrap_or_default();
            if !counts.contains(&c.len()) {
                return Err(ctx.field(
                    coefficients.line,
                    "coefficients",
                    format!(
                        "{} coefficient{} for formula {kind}, which takes {rule}",
                        c.len(),
                        if c.len() == 1 { "" } else { "s" }
                    ),
                ));
            }
            let formula = Dispersion::Formula {
                kind,
                coefficients: c,
                range: (lo, hi),
            };
            check_formula(&formula).map_err(|m| {
                ctx.field(
                    coefficients.line,
                    "coefficients",
                    format!("formula {kind} {m} (its range is {lo}–{hi} µm)"),
                )
            })?;
            (Some(formula), None)
        }
    };
    Ok(Block {
        type_name,
        type_line: ty.line,
        n,
        k,
    })
}

/// A range `λ_min λ_max` (µm) with 0 < λ_min < λ_max.
fn range_of(e: &Entry, ctx: &Ctx<'_>) -> Result<(f64, f64)> {
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
fn scalar<'a>(e: &'a Entry, ctx: &Ctx<'_>) -> Result<&'a str> {
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
fn number(cell: &str) -> std::result::Result<f64, String> {
    match cell.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => Err(format!("`{cell}` is not a finite number")),
        Err(_) => Err(format!("`{cell}` is not a number")),
    }
}

/// Blank-separated numbers (coefficients, a range).
fn numbers(e: &Entry, ctx: &Ctx<'_>) -> Result<Vec<f64>> {
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

/// Checks that a formula gives a valid n over its range: no pole inside it, and
/// 0 < n ≤ 10⁶ at the ends, the geometric mean and `CHECK_POINTS` points spread linearly and
/// logarithmically (plus, for formula 9, the extremes of its resonance term). The message says
/// where not.
fn check_formula(f: &Dispersion) -> std::result::Result<(), String> {
    let Dispersion::Formula {
        kind,
        coefficients: c,
        range: (lo, hi),
    } = f
    else {
        return Ok(());
    };
    let (lo, hi) = (*lo, *hi);
    let at = |i: usize| c.get(i).copied().unwrap_or(0.0);
    // Poles: (λ where a denominator vanishes, which coefficient sets it).
    let mut poles: Vec<(f64, String)> = Vec::new();
    let pairs = (1..c.len()).step_by(2).map(|i| (i, at(i), at(i + 1)));
    match kind {
        1 => poles.extend(
            pairs
                .filter(|p| p.1 != 0.0)
                .map(|(i, _, b)| (b.abs(), format!("λ = |C{}|", i + 2))),
        ),
        2 => poles.extend(
            pairs
                .filter(|p| p.1 != 0.0 && p.2 > 0.0)
                .map(|(i, _, b)| (b.sqrt(), format!("λ² = C{}", i + 2))),
        ),
        6 => poles.extend(
            pairs
                .filter(|p| p.1 != 0.0 && p.2 > 0.0)
                .map(|(i, _, b)| (1.0 / b.sqrt(), format!("λ⁻² = C{}", i + 2))),
        ),
        4 => {
            for i in [1, 5] {
                let p = at(i + 2).powf(at(i + 3));
                if at(i) != 0.0 && p > 0.0 {
                    poles.push((p.sqrt(), format!("λ² = C{}^C{}", i + 3, i + 4)));
                }
            }
        }
        7 if at(1) != 0.0 || at(2) != 0.0 => poles.push((0.028f64.sqrt(), "λ² = 0.028".into())),
        8 | 9 if at(1) != 0.0 && at(2) > 0.0 => poles.push((at(2).sqrt(), "λ² = C3".into())),
        _ => {}
    }
    let mut extra = Vec::new();
    if *kind == 9 && at(3) != 0.0 {
        let (c5, c6) = (at(4), at(5));
        if c6 <= 0.0 {
            let r = (-c6).sqrt();
            poles.push((c5 - r, "(λ − C5)² + C6 = 0".into()));
            poles.push((c5 + r, "(λ − C5)² + C6 = 0".into()));
        } else {
            extra.extend([c5 - c6.sqrt(), c5 + c6.sqrt()]);
        }
    }
    if let Some((l, why)) = poles.iter().find(|(l, _)| *l >= lo && *l <= hi) {
        return Err(format!("has a pole at λ = {l} µm ({why}) inside its range"));
    }
    let n = CHECK_POINTS as f64;
    let linear = (0..=CHECK_POINTS).map(|i| lo + (hi - lo) * (i as f64 / n));
    let log = (0..=CHECK_POINTS).map(|i| lo * (hi / lo).powf(i as f64 / n));
    extra.push((lo * hi).sqrt());
    let inside = extra.into_iter().filter(|l| *l > lo && *l < hi);
    for l in linear.chain(log).chain(inside).chain([lo, hi]) {
        let l = l.clamp(lo, hi);
        match f.eval(l) {
            Some(v) if v.is_finite() && v > 0.0 && v <= MAX_INDEX => {}
            Some(v) if v.is_nan() => {
                return Err(format!(
                    "gives no real index at λ = {l} µm (n² < 0 or not finite there)"
                ))
            }
            Some(v) => return Err(format!("gives n = {v} at λ = {l} µm (must be in (0, 1e6])")),
            None => return Err(format!("cannot be evaluated at λ = {l} µm")),
        }
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------------
// A small YAML tree with the line of every node, built from yaml-rust2's events.

/// A YAML node and its 1-based line.
#[derive(Debug)]
enum Node {
    Scalar {
        text: String,
        /// A literal (`|`) block, whose lines map one to one onto the file's (`line` is that
        /// of its first non-blank line).
        literal: bool,
        line: usize,
    },
    Seq {
        items: Vec<Node>,
        line: usize,
    },
    Map {
        entries: Vec<Entry>,
        line: usize,
    },
}

/// A key of a mapping, its line and its value.
#[derive(Debug)]
struct Entry {
    key: String,
    line: usize,
    value: Node,
}

impl Node {
    fn line(&self) -> usize {
        match self {
            Node::Scalar { line, .. } | Node::Seq { line, .. } | Node::Map { line, .. } => *line,
        }
    }

    fn kind(&self) -> &'static str {
        match self {
            Node::Scalar { text, .. } if text.is_empty() => "nothing",
            Node::Scalar { .. } => "text",
            Node::Seq { .. } => "a list",
            Node::Map { .. } => "a mapping",
        }
    }
}

/// A collection being built.
enum Frame {
    Seq(Vec<Node>, usize),
    Map(Vec<Entry>, usize, Option<(String, usize)>),
}

/// The file's single YAML document as a tree (`None` for an empty stream).
fn load_tree(text: &str, ctx: &Ctx<'_>) -> Result<Option<Node>> {
    let mut parser = Parser::new_from_str(text);
    let mut stack: Vec<Frame> = Vec::new();
    let mut root = None;
    let mut documents = 0;
    loop {
        let (event, mark) = parser
            .next_token()
            .map_err(|e| ctx.syntax(e.marker().line().max(1), e.info().to_string()))?;
        let line = mark.line().max(1);
        let node = match event {
            Event::StreamEnd => break,
            Event::DocumentStart => {
                documents += 1;
                if documents > 1 {
                    return Err(ctx.syntax(
                        line,
                        "a second YAML document (`---`): a file holds one".into(),
                    ));
                }
                continue;
            }
            Event::Nothing | Event::StreamStart | Event::DocumentEnd => continue,
            Event::Alias(_) => {
                return Err(ctx.syntax(line, "YAML aliases (`*name`) are not supported".into()))
            }
            Event::Scalar(text, style, _, _) => Node::Scalar {
                text,
                literal: style == TScalarStyle::Literal,
                line,
            },
            Event::SequenceStart(..) | Event::MappingStart(..) => {
                if let Some(Frame::Map(_, _, None)) = stack.last() {
                    return Err(ctx.syntax(line, "a mapping key must be plain text".into()));
                }
                if stack.len() >= MAX_DEPTH {
                    return Err(ctx.syntax(line, format!("nesting deeper than {MAX_DEPTH} levels")));
                }
                stack.push(if matches!(event, Event::SequenceStart(..)) {
                    Frame::Seq(Vec::new(), line)
                } else {
                    Frame::Map(Vec::new(), line, None)
                });
                continue;
            }
            Event::SequenceEnd | Event::MappingEnd => match stack.pop() {
                Some(Frame::Seq(items, line)) => Node::Seq { items, line },
                Some(Frame::Map(entries, line, _)) => Node::Map { entries, line },
                None => return Err(ctx.syntax(line, "unbalanced YAML collection".into())),
            },
        };
        match stack.last_mut() {
            None => root = Some(node),
            Some(Frame::Seq(items, _)) => items.push(node),
            Some(Frame::Map(entries, _, key @ None)) => {
                let Node::Scalar { text, line, .. } = node else {
                    return Err(ctx.syntax(node.line(), "a mapping key must be plain text".into()));
                };
                if let Some(first) = entries.iter().find(|e| e.key == text) {
                    return Err(ctx.field(
                        line,
                        &text,
                        format!("duplicate key (first at line {})", first.line),
                    ));
                }
                *key = Some((text, line));
            }
            Some(Frame::Map(entries, _, key)) => {
                if let Some((key, line)) = key.take() {
                    entries.push(Entry {
                        key,
                        line,
                        value: node,
                    });
                }
            }
        }
    }
    Ok(root)
}

/// The file, for errors.
struct Ctx<'a> {
    path: &'a Path,
}

impl Ctx<'_> {
    fn syntax(&self, line: usize, message: String) -> Error {
        Error::Syntax {
            path: self.path.to_path_buf(),
            line,
            message,
        }
    }

    fn field(&self, line: usize, field: &str, message: String) -> Error {
        Error::Field {
            path: self.path.to_path_buf(),
            line,
            field: field.to_string(),
            message,
        }
    }

    fn file(&self, message: &str) -> Error {
        Error::File {
            path: self.path.to_path_buf(),
            message: message.to_string(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_follow_the_database_and_library_layouts() {
        let name = |p: &str| name_of(Path::new(p));
        assert_eq!(name("db/data/main/Au/nk/Johnson.yml"), "Au/Johnson");
        assert_eq!(name("library/Au/Johnson.yml"), "Au/Johnson");
        assert_eq!(name("/x/specs/schott/optical/N-BK7.yml"), "optical/N-BK7");
        assert_eq!(name("gold.yml"), "gold");
        assert_eq!(name("nk/gold.yml"), "nk/gold");
    }
}
