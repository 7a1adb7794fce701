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
//!
//! The reader by aspect: `refractive/yaml.rs` builds the YAML tree with the line of every node,
//! `block.rs` reads a data block's type and keys, `table.rs` its rows and `formula.rs` its
//! formula; this file reads the top level and takes n and k from the blocks.

mod block;
mod formula;
mod table;
mod values;
mod yaml;

use crate::error::{Error, Result};
use block::parse_block;
use polbrdf::optics::dispersion::{Dispersion, SpectralIndex};
use std::path::Path;
use yaml::{load_tree, Ctx, Entry, Node};

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
    let entries = top_level(&root, &ctx)?;
    let references = text_of(entries, "REFERENCES", &ctx)?;
    let comments = text_of(entries, "COMMENTS", &ctx)?;
    let (data, items) = data_blocks(entries, &ctx)?;
    let (n, k) = n_and_k(data, items, &ctx)?;
    Ok(SpectralIndex {
        name: name.to_string(),
        n,
        k,
        references,
        comments,
    })
}

/// The entries of the top-level mapping (any other top level is an error).
fn top_level<'a>(root: &'a Node, ctx: &Ctx<'_>) -> Result<&'a [Entry]> {
    let Node::Map { entries, .. } = root else {
        return Err(ctx.syntax(
            root.line(),
            format!(
                "the top level is {}; a refractiveindex.info file is a mapping with \
                 REFERENCES, COMMENTS and DATA",
                root.kind()
            ),
        ));
    };
    Ok(entries)
}

/// The text of top-level `key` (`REFERENCES`, `COMMENTS`), empty when absent.
fn text_of(entries: &[Entry], key: &str, ctx: &Ctx<'_>) -> Result<String> {
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
}

/// `DATA` and its items: a non-empty list of data blocks.
fn data_blocks<'a>(entries: &'a [Entry], ctx: &Ctx<'_>) -> Result<(&'a Entry, &'a [Node])> {
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
    Ok((data, items))
}

/// Where a quantity comes from, for the message when a second block gives it too.
struct Source {
    dispersion: Dispersion,
    type_name: String,
    line: usize,
}

/// n and k of the data blocks `items` of `data`: n from exactly one block, k from at most one,
/// their ranges overlapping (module docs, "One source per quantity").
fn n_and_k(
    data: &Entry,
    items: &[Node],
    ctx: &Ctx<'_>,
) -> Result<(Dispersion, Option<Dispersion>)> {
    let mut n: Option<Source> = None;
    let mut k: Option<Source> = None;
    for item in items {
        let block = parse_block(item, ctx)?;
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
    Ok((n.dispersion, k))
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
