//! The one TOML reader of the input files: material, scene, sensor and lookup-table
//! configuration files all read their text through [`TomlDoc`], so that every file gives the
//! same errors in the same words, each naming the file, the line and the key.
//!
//! A format is a list of [`Key`]s ([`key`]): each with its name (`table.key` inside a table),
//! the [`Kind`] of value it holds and what it is, in words, for messages. A format with a key
//! of kind [`Kind::Table`] has tables (one level: `[sun]` or `sun = { … }`, holding the keys
//! `sun.*`); a format without is flat.
//!
//! [`TomlDoc::parse`] reads the text (a UTF-8 BOM skipped, an old Mac line end `\r` counted as
//! one) with `toml_edit`'s spans and checks every key before the format's reader sees any:
//! - malformed TOML (duplicate keys included): [`Error::Syntax`] at the line of the error;
//! - a dotted key (`a.b = 1`): [`Error::Field`] at its line, asking for the table written out
//!   (a format with tables) or a plain key (a flat format, where a `[table]` is refused the
//!   same way);
//! - an unknown key or table: [`Error::Field`] listing the known ones (`unknown key (known
//!   keys: …)`, `unknown table [x] (known tables: …)`, `unknown key in [t] (known keys: …)`);
//! - a value not of its key's kind: [`Error::Field`], `expected a number (what it is), got
//!   string`.
//!
//! The format's reader then takes the values with the typed getters — [`TomlDoc::number`]
//! (an integer read as a float), [`TomlDoc::numbers`], [`TomlDoc::text`], [`TomlDoc::bool`],
//! [`TomlDoc::value`] (any value, for keys of [`Kind::Any`] that the reader checks itself) —
//! asks [`TomlDoc::has`] and [`TomlDoc::line`], and builds its errors with
//! [`TomlDoc::error`] (a key's value, at its line), [`TomlDoc::missing`] (a required key),
//! [`TomlDoc::file_error`] (the file as a whole) and [`TomlDoc::core_error`] (a core error at
//! the line of the key it names). Files a key names are found relative to the file's folder
//! ([`TomlDoc::resolve`]) and read by [`TomlDoc::read_file`], which records them
//! ([`TomlDoc::files`]: inputs an output must not replace).

use crate::csv_io::{line_of, short_message, short_name};
use crate::error::{Error, Result};
use std::cell::RefCell;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use toml::Value;

/// What a key holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// A number: a TOML float or integer.
    Number,
    /// An array of numbers (of any length: the format's reader checks it).
    Numbers,
    /// A string.
    Text,
    /// `true` or `false`.
    Bool,
    /// A date-time: a TOML date-time or a string holding one.
    DateTime,
    /// A table of the format's keys `name.*` (`[name]` or an inline table).
    Table,
    /// Any value: the format's reader checks it ([`TomlDoc::value`]).
    Any,
}

impl Kind {
    /// The kind in words, for messages (`a number`).
    pub fn word(self) -> &'static str {
        match self {
            Kind::Number => "a number",
            Kind::Numbers => "an array of numbers",
            Kind::Text => "a string",
            Kind::Bool => "true or false",
            Kind::DateTime => "a date-time",
            Kind::Table => "a table",
            Kind::Any => "a value",
        }
    }

    fn holds(self, value: &Value) -> bool {
        match (self, value) {
            (Kind::Any, _) => true,
            (Kind::Numbers, Value::Array(a)) => a.iter().all(is_number),
            _ => matches!(
                (self, value),
                (Kind::Number, Value::Float(_) | Value::Integer(_))
                    | (Kind::Text, Value::String(_))
                    | (Kind::Bool, Value::Boolean(_))
                    | (Kind::DateTime, Value::String(_) | Value::Datetime(_))
                    | (Kind::Table, Value::Table(_))
            ),
        }
    }
}

fn is_number(value: &Value) -> bool {
    matches!(value, Value::Float(_) | Value::Integer(_))
}

/// One key of a format.
#[derive(Debug, Clone, Copy)]
pub struct Key {
    /// Its name; `table.key` inside a table (as messages spell it).
    pub name: &'static str,
    /// What it holds.
    pub kind: Kind,
    /// What it is, in words (for messages).
    pub what: &'static str,
}

/// A [`Key`] (for `const` tables of keys).
pub const fn key(name: &'static str, kind: Kind, what: &'static str) -> Key {
    Key { name, kind, what }
}

/// A file format: what its files are called and its keys.
#[derive(Debug, Clone, Copy)]
pub struct Format<'k> {
    /// The file in words, for messages: `"material file"`.
    pub noun: &'static str,
    /// A plain key as an example, for the messages of a flat format: `` "`n = 1.5`" ``.
    pub example: &'static str,
    /// Every key and table, tables before their keys.
    pub keys: &'k [Key],
}

impl Format<'_> {
    fn has_tables(&self) -> bool {
        self.keys.iter().any(|k| k.kind == Kind::Table)
    }

    /// The key named `name` in `table` (`None`: the top level).
    fn known(&self, table: Option<&str>, name: &str) -> Option<Key> {
        self.keys
            .iter()
            .find(|k| split(k.name) == (table, name))
            .copied()
    }

    /// The names of the keys of `table` (without the table's prefix).
    fn keys_of(&self, table: Option<&str>) -> Vec<&'static str> {
        self.keys
            .iter()
            .map(|k| split(k.name))
            .filter(|(t, _)| *t == table)
            .map(|(_, k)| k)
            .collect()
    }

    /// `[a], [b]`: the tables.
    fn tables(&self) -> String {
        self.keys
            .iter()
            .filter(|k| k.kind == Kind::Table)
            .map(|k| format!("[{}]", k.name))
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// The message of an unknown key `name` in `table`, whose value is a table or not.
    fn unknown(&self, table: Option<&str>, name: &str, is_table: bool) -> (String, String) {
        let name = short_name(name);
        match table {
            Some(t) => (
                format!("{}.{name}", short_name(t)),
                format!(
                    "unknown key in [{}] (known keys: {})",
                    short_name(t),
                    self.keys_of(Some(t)).join(", ")
                ),
            ),
            None if !self.has_tables() => (
                name,
                format!(
                    "unknown key (known keys: {})",
                    self.keys_of(None).join(", ")
                ),
            ),
            None if is_table => {
                let message = format!("unknown table [{name}] (known tables: {})", self.tables());
                (name, message)
            }
            None => {
                let plain: Vec<String> = self
                    .keys
                    .iter()
                    .filter(|k| k.kind != Kind::Table && split(k.name).0.is_none())
                    .map(|k| format!("`{}`", k.name))
                    .collect();
                (
                    name,
                    format!(
                        "unknown key (known: {} and the tables {})",
                        plain.join(", "),
                        self.tables()
                    ),
                )
            }
        }
    }

    /// The message of a dotted key (or, in a flat format, a table).
    fn dotted(&self) -> String {
        if self.has_tables() {
            format!(
                "dotted keys (`table.key = …`) are not supported in {}s: write the table out \
                 (`[table]`, then `key = …`)",
                self.noun
            )
        } else {
            format!(
                "dotted keys (`a.b = …`) and tables are not allowed in a {}: every key is a \
                 plain name ({})",
                self.noun, self.example
            )
        }
    }
}

/// The table a dotted key name belongs to (`None` at the top level) and its name inside it.
pub fn split(name: &str) -> (Option<&str>, &str) {
    match name.split_once('.') {
        Some((table, key)) => (Some(table), key),
        None => (None, name),
    }
}

/// A TOML file read and checked against its [`Format`] (module documentation).
#[derive(Debug)]
pub struct TomlDoc<'a> {
    path: &'a Path,
    /// The folder relative file names are found in (`None`: the working directory).
    folder: Option<&'a Path>,
    format: Format<'a>,
    /// Every key given, by its name: its line and its value (tables: an empty table at the
    /// line of their header).
    found: BTreeMap<&'static str, (usize, Value)>,
    /// The files read so far ([`TomlDoc::read_file`]).
    files: RefCell<Vec<PathBuf>>,
    /// The named files' texts by their resolved path ([`TomlDoc::with_files`]): read from here
    /// rather than from the file system. `None`: the file system.
    texts: Option<&'a BTreeMap<PathBuf, String>>,
}

/// One key/value pair of the text: the key's name, its byte position and its item.
type Item<'t> = (&'t str, usize, &'t toml_edit::Item);

impl<'a> TomlDoc<'a> {
    /// Reads `text` as a file of `format`; `path` names it in messages, and its folder is where
    /// [`TomlDoc::resolve`] finds relative file names.
    ///
    /// # Errors
    /// [`Error::Syntax`] for malformed TOML; [`Error::Field`] naming the line and the key for a
    /// dotted key (or a table in a flat format), an unknown key or table, or a value not of
    /// its key's kind.
    pub fn parse(text: &str, path: &'a Path, format: Format<'a>) -> Result<Self> {
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        let text = &*crate::csv_io::lone_cr_to_lf(text);
        let mut doc = TomlDoc {
            path,
            folder: path.parent().filter(|p| !p.as_os_str().is_empty()),
            format,
            found: BTreeMap::new(),
            files: RefCell::new(Vec::new()),
            texts: None,
        };
        let parsed = toml_edit::ImDocument::parse(text).map_err(|e| Error::Syntax {
            path: path.to_path_buf(),
            line: e.span().map_or(1, |s| line_of(text, s.start)),
            message: toml_message(e.message(), e.span(), text),
        })?;
        let root = parsed.as_table();
        for (name, pos, item) in items(root.iter().filter_map(|(k, _)| root.get_key_value(k))) {
            let line = line_of(text, pos);
            let is_table = doc.format.known(None, name).map(|k| k.kind) == Some(Kind::Table);
            let inner = match item {
                toml_edit::Item::Table(t) if t.is_dotted() || !doc.format.has_tables() => {
                    return Err(doc.field(line, &dotted_name(name, item), doc.format.dotted()))
                }
                toml_edit::Item::Table(t) if is_table => {
                    items(t.iter().filter_map(|(k, _)| t.get_key_value(k)))
                }
                toml_edit::Item::Value(toml_edit::Value::InlineTable(t)) if is_table => {
                    items(t.iter().filter_map(|(k, _)| t.get_key_value(k)))
                }
                item => {
                    doc.insert(None, name, line, to_value(item))?;
                    continue;
                }
            };
            let table = doc.insert(None, name, line, Value::Table(Default::default()))?;
            for (name, pos, item) in inner {
                let line = line_of(text, pos);
                if matches!(item, toml_edit::Item::Table(t) if t.is_dotted()) {
                    let dotted = format!("{table}.{}", dotted_name(name, item));
                    return Err(doc.field(line, &dotted, doc.format.dotted()));
                }
                doc.insert(Some(table), name, line, to_value(item))?;
            }
        }
        Ok(doc)
    }

    /// Records `name` of `table` (checked: known, of its kind) and returns its full name.
    fn insert(
        &mut self,
        table: Option<&str>,
        name: &str,
        line: usize,
        value: Value,
    ) -> Result<&'static str> {
        let Some(key) = self.format.known(table, name) else {
            let is_table = matches!(value, Value::Table(_));
            let (field, message) = self.format.unknown(table, name, is_table);
            return Err(self.field(line, &field, message));
        };
        if !key.kind.holds(&value) {
            let message = format!(
                "expected {} ({}), got {}",
                key.kind.word(),
                key.what,
                type_of(key.kind, &value)
            );
            return Err(self.field(line, key.name, message));
        }
        self.found.insert(key.name, (line, value));
        Ok(key.name)
    }

    fn field(&self, line: usize, field: &str, message: String) -> Error {
        Error::Field {
            path: self.path.to_path_buf(),
            line,
            field: short_name(field),
            message,
        }
    }

    /// The file's path.
    pub fn path(&self) -> &Path {
        self.path
    }

    /// Whether `key` (or table) is given.
    pub fn has(&self, key: &str) -> bool {
        self.found.contains_key(key)
    }

    /// The line of `key`, or of its table when only that is given (1 when neither is).
    pub fn line(&self, key: &str) -> usize {
        self.found
            .get(key)
            .or_else(|| split(key).0.and_then(|t| self.found.get(t)))
            .map_or(1, |(line, _)| *line)
    }

    /// The given keys (tables as empty tables) with their lines, in file order.
    pub fn keys(&self) -> Vec<(&'static str, usize, &Value)> {
        let mut keys: Vec<_> = self
            .found
            .iter()
            .map(|(k, (line, v))| (*k, *line, v))
            .collect();
        keys.sort_by_key(|(_, line, _)| *line);
        keys
    }

    /// The value of `key`, as given.
    pub fn value(&self, key: &str) -> Option<&Value> {
        self.found.get(key).map(|(_, v)| v)
    }

    /// The number `key` (an integer read as a float).
    pub fn number(&self, key: &str) -> Option<f64> {
        match self.value(key)? {
            Value::Float(x) => Some(*x),
            Value::Integer(i) => Some(*i as f64),
            _ => None,
        }
    }

    /// The array of numbers `key` (integers read as floats).
    pub fn numbers(&self, key: &str) -> Option<Vec<f64>> {
        match self.value(key)? {
            Value::Array(a) => a
                .iter()
                .map(|v| match v {
                    Value::Float(x) => Some(*x),
                    Value::Integer(i) => Some(*i as f64),
                    _ => None,
                })
                .collect(),
            _ => None,
        }
    }

    /// The string `key`.
    pub fn text(&self, key: &str) -> Option<&str> {
        match self.value(key)? {
            Value::String(s) => Some(s),
            _ => None,
        }
    }

    /// The boolean `key`.
    pub fn bool(&self, key: &str) -> Option<bool> {
        match self.value(key)? {
            Value::Boolean(b) => Some(*b),
            _ => None,
        }
    }

    /// What `key` is, in words (its [`Key::what`]; empty for an unknown key).
    pub fn what(&self, key: &str) -> &'static str {
        self.format
            .keys
            .iter()
            .find(|k| k.name == key)
            .map_or("", |k| k.what)
    }

    /// An error of the value of `key`, at its line ([`TomlDoc::line`]).
    pub fn error(&self, key: &str, message: impl Into<String>) -> Error {
        Error::Field {
            path: self.path.to_path_buf(),
            line: self.line(key),
            field: key.to_string(),
            message: message.into(),
        }
    }

    /// An error of the file as a whole.
    pub fn file_error(&self, message: impl Into<String>) -> Error {
        Error::File {
            path: self.path.to_path_buf(),
            message: message.into(),
        }
    }

    /// `missing required key `name` (what)`: for a key inside a table at the table's line,
    /// naming the table; for a top-level key an error of the file.
    pub fn missing(&self, key: &str) -> Error {
        let (table, name) = split(key);
        let message = format!("missing required key `{name}` ({})", self.what(key));
        match table {
            Some(t) => self.error(t, message),
            None => self.file_error(message),
        }
    }

    /// The number `key`, required ([`TomlDoc::missing`] when absent).
    pub fn required_number(&self, key: &str) -> Result<f64> {
        self.number(key).ok_or_else(|| self.missing(key))
    }

    /// A core error at the line of the key it names (an invalid parameter whose name is a
    /// given key), else an error of the file.
    pub fn core_error(&self, e: polbrdf::Error) -> Error {
        match &e {
            polbrdf::Error::InvalidParameter { name, .. } if self.has(name) => {
                self.error(name, e.to_string())
            }
            _ => self.file_error(e.to_string()),
        }
    }

    /// `name` relative to the file's folder (unless absolute).
    pub fn resolve(&self, name: &str) -> PathBuf {
        match self.folder {
            Some(dir) if Path::new(name).is_relative() => dir.join(name),
            _ => PathBuf::from(name),
        }
    }

    /// Records `file` as read ([`TomlDoc::files`]).
    pub fn record(&self, file: PathBuf) {
        self.files.borrow_mut().push(file);
    }

    /// The same document, with the files its keys name taken from `texts` (their texts by the
    /// path [`TomlDoc::resolve`] gives) instead of the file system, by [`TomlDoc::load`] and
    /// [`TomlDoc::read_file_or_text`]: for an adapter without a file system (the web explorer).
    #[must_use]
    pub fn with_files(mut self, texts: &'a BTreeMap<PathBuf, String>) -> Self {
        self.texts = Some(texts);
        self
    }

    /// The file `file`: read by `read` from the file system, or parsed by `parse` from its
    /// text given to [`TomlDoc::with_files`] (a file not given there is an error naming it).
    ///
    /// # Errors
    /// `read`'s or `parse`'s error; [`Error::File`] for a file missing from the texts given.
    pub fn load<T>(
        &self,
        file: &Path,
        read: impl FnOnce(&Path) -> Result<T>,
        parse: impl FnOnce(&[u8], &Path) -> Result<T>,
    ) -> Result<T> {
        let Some(texts) = self.texts else {
            return read(file);
        };
        match texts.get(file) {
            Some(text) => parse(text.as_bytes(), file),
            None => Err(Error::File {
                path: file.to_path_buf(),
                message: format!(
                    "no such file (the files given: {})",
                    texts
                        .keys()
                        .map(|k| k.display().to_string())
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            }),
        }
    }

    /// [`TomlDoc::read_file`], the file read by `read` or parsed by `parse` from the texts
    /// given to [`TomlDoc::with_files`] ([`TomlDoc::load`]).
    ///
    /// # Errors
    /// As [`TomlDoc::read_file`].
    pub fn read_file_or_text<T>(
        &self,
        key: &str,
        read: impl FnOnce(&Path) -> Result<T>,
        parse: impl FnOnce(&[u8], &Path) -> Result<T>,
    ) -> Result<Option<T>> {
        self.read_file(key, |file| self.load(file, read, parse))
    }

    /// The file that the string `key` names ([`TomlDoc::resolve`]), recorded and read by
    /// `read`; its errors wrapped in one naming `key`. `None` when `key` is absent.
    ///
    /// # Errors
    /// An empty name; `read`'s error, inside one naming `key` at its line.
    pub fn read_file<T>(
        &self,
        key: &str,
        read: impl FnOnce(&Path) -> Result<T>,
    ) -> Result<Option<T>> {
        let Some(name) = self.text(key) else {
            return Ok(None);
        };
        if name.is_empty() {
            return Err(self.error(key, "expected the path of a file, got an empty string"));
        }
        let file = self.resolve(name);
        self.record(file.clone());
        read(&file)
            .map(Some)
            .map_err(|e| self.error(key, e.to_string()))
    }

    /// The files read ([`TomlDoc::read_file`], [`TomlDoc::record`]), in order.
    pub fn files(&self) -> Vec<PathBuf> {
        self.files.borrow().clone()
    }
}

/// The key/value pairs of a table in file order, with their keys' positions (a key without a
/// position, which the parser always gives, sorts first at byte 0).
fn items<'t>(
    pairs: impl Iterator<Item = (&'t toml_edit::Key, &'t toml_edit::Item)>,
) -> Vec<Item<'t>> {
    let mut out: Vec<Item<'t>> = pairs
        .map(|(k, v)| (k.get(), k.span().map_or(0, |s| s.start), v))
        .collect();
    out.sort_by_key(|(_, pos, _)| *pos);
    out
}

/// The full name of a dotted key `name.…` (its first key in file order), as written.
fn dotted_name(name: &str, item: &toml_edit::Item) -> String {
    let mut out = name.to_string();
    let mut item = item;
    while let toml_edit::Item::Table(t) = item {
        if !t.is_dotted() {
            break;
        }
        let Some((next, _, inner)) = items(t.iter().filter_map(|(k, _)| t.get_key_value(k)))
            .into_iter()
            .next()
        else {
            break;
        };
        out = format!("{out}.{next}");
        item = inner;
    }
    out
}

/// An item as a `toml` value (a table of any kind as a table).
fn to_value(item: &toml_edit::Item) -> Value {
    match item {
        toml_edit::Item::None => Value::Table(Default::default()),
        toml_edit::Item::Value(v) => to_value_of(v),
        toml_edit::Item::Table(t) => Value::Table(
            t.iter()
                .map(|(k, v)| (k.to_string(), to_value(v)))
                .collect(),
        ),
        toml_edit::Item::ArrayOfTables(a) => Value::Array(
            a.iter()
                .map(|t| {
                    Value::Table(
                        t.iter()
                            .map(|(k, v)| (k.to_string(), to_value(v)))
                            .collect(),
                    )
                })
                .collect(),
        ),
    }
}

fn to_value_of(value: &toml_edit::Value) -> Value {
    use toml_edit::Value as V;
    match value {
        V::String(s) => Value::String(s.value().clone()),
        V::Integer(i) => Value::Integer(*i.value()),
        V::Float(x) => Value::Float(*x.value()),
        V::Boolean(b) => Value::Boolean(*b.value()),
        V::Datetime(d) => Value::Datetime(*d.value()),
        V::Array(a) => Value::Array(a.iter().map(to_value_of).collect()),
        V::InlineTable(t) => Value::Table(
            t.iter()
                .map(|(k, v)| (k.to_string(), to_value_of(v)))
                .collect(),
        ),
    }
}

/// What `value` is, for messages: its TOML type, and for an array where numbers are expected
/// what it holds that is no number.
fn type_of(kind: Kind, value: &Value) -> String {
    match value {
        Value::Array(a) if kind == Kind::Numbers => match a.iter().find(|v| !is_number(v)) {
            Some(v) => format!("an array holding a {}", v.type_str()),
            None => "array".into(),
        },
        v => v.type_str().into(),
    }
}

/// The message of a TOML syntax error in `text`, bounded. The parser names no control
/// character (in a comment, a key, or anywhere outside a string: it says nothing, or `invalid
/// key`), so an error at one names the character.
fn toml_message(message: &str, span: Option<std::ops::Range<usize>>, text: &str) -> String {
    let m = message.trim();
    let c = span.and_then(|s| text.get(s.start..)?.chars().next());
    let named = |c: Option<char>| {
        format!(
            "invalid character {:?}: TOML allows no control characters, not even in comments",
            c.unwrap_or('?')
        )
    };
    match c {
        _ if m.is_empty() => named(c),
        Some(c) if c.is_control() && !matches!(c, '\t' | '\n' | '\r') => named(Some(c)),
        _ => short_message(m),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const TABLES: &[Key] = &[
        key("top", Kind::Number, "a number at the top"),
        key("t", Kind::Table, "a table"),
        key("t.x", Kind::Number, "x"),
        key("t.s", Kind::Text, "s"),
        key("t.v", Kind::Numbers, "v"),
        key("u", Kind::Table, "another table"),
        key("u.b", Kind::Bool, "b"),
    ];
    const FLAT: &[Key] = &[
        key("a", Kind::Number, "a"),
        key("any", Kind::Any, "anything"),
    ];

    fn parse(text: &str, keys: &'static [Key]) -> Result<TomlDoc<'static>> {
        let format = Format {
            noun: "test file",
            example: "`a = 1`",
            keys,
        };
        TomlDoc::parse(text, Path::new("f.toml"), format)
    }

    /// `(line, field, message)` of a field error.
    fn field(r: Result<TomlDoc<'static>>) -> (usize, String, String) {
        match r.unwrap_err() {
            Error::Field {
                line,
                field,
                message,
                ..
            } => (line, field, message),
            other => panic!("{other}"),
        }
    }

    #[test]
    fn keys_in_tables_inline_tables_and_values_have_their_lines() {
        let text =
            "\u{feff}top = 2\r\n# c\n[t]\nx = 1.5\n\ns = \"a\"\rv = [1, 2.5]\nu = { b = true }\n";
        // `u` after `[t]` is a key of [t]: unknown there.
        let (line, f, m) = field(parse(text, TABLES));
        assert_eq!((line, f.as_str()), (8, "t.u"));
        assert_eq!(m, "unknown key in [t] (known keys: x, s, v)");
        let text = "top = 2\r\nu = { b = true }\n# c\n[t]\nx = 1.5\n\ns = \"a\"\rv = [1, 2.5]\n";
        let doc = parse(text, TABLES).unwrap();
        assert_eq!(doc.number("top"), Some(2.0));
        assert_eq!(doc.number("t.x"), Some(1.5));
        assert_eq!(doc.text("t.s"), Some("a"));
        assert_eq!(doc.numbers("t.v"), Some(vec![1.0, 2.5]));
        assert_eq!(doc.bool("u.b"), Some(true));
        let lines: Vec<(&str, usize)> = doc.keys().iter().map(|(k, l, _)| (*k, *l)).collect();
        assert_eq!(
            lines,
            [
                ("top", 1),
                ("u", 2),
                ("u.b", 2),
                ("t", 4),
                ("t.x", 5),
                ("t.s", 7),
                ("t.v", 8)
            ]
        );
        // A key absent from a given table is at the table's line; an absent table at line 1.
        assert_eq!(doc.line("t.nothing"), 4);
        assert_eq!(doc.line("w.nothing"), 1);
        assert_eq!(
            doc.missing("u.c").to_string(),
            "f.toml:2: field `u`: missing required key `c` ()"
        );
        assert_eq!(
            doc.missing("top2").to_string(),
            "f.toml: missing required key `top2` ()"
        );
    }

    #[test]
    fn every_error_names_file_line_and_key() {
        let cases: [(&str, &'static [Key], usize, &str, &str); 9] = [
            ("top = 1\ncolour = 3\n", TABLES, 2, "colour", "unknown key (known: `top` and the tables [t], [u])"),
            ("top = 1\n[moon]\nx = 1\n", TABLES, 2, "moon", "unknown table [moon] (known tables: [t], [u])"),
            ("[t]\nx = \"1\"\n", TABLES, 2, "t.x", "expected a number (x), got string"),
            ("[t]\nv = [1, \"2\"]\n", TABLES, 2, "t.v", "expected an array of numbers (v), got an array holding a string"),
            ("top = 1\n\nt.x = 1\n", TABLES, 3, "t.x", "dotted keys (`table.key = …`) are not supported in test files: write the table out (`[table]`, then `key = …`)"),
            ("[t]\nx.y.z = 1\n", TABLES, 2, "t.x.y.z", "dotted keys"),
            ("a = 1\nb = 2\n", FLAT, 2, "b", "unknown key (known keys: a, any)"),
            ("a = 1\n[any]\nx = 1\n", FLAT, 2, "any", "dotted keys (`a.b = …`) and tables are not allowed in a test file: every key is a plain name (`a = 1`)"),
            ("a = 1\rany.x = 1\r", FLAT, 2, "any.x", "dotted keys"),
        ];
        for (text, keys, line, key, says) in cases {
            let (l, f, m) = field(parse(text, keys));
            assert_eq!((l, f.as_str()), (line, key), "{text:?}: {m}");
            assert!(m.starts_with(says), "{text:?}: {m}");
        }
        // Any value for a key of `Kind::Any`, inline tables included.
        let doc = parse("any = { start = 0, count = 3 }\n", FLAT).unwrap();
        assert!(matches!(doc.value("any"), Some(Value::Table(t)) if t.len() == 2));
        // Syntax: duplicate keys, at the line of the second.
        match parse("a = 1\n\na = 2\n", FLAT).unwrap_err() {
            Error::Syntax { line, message, .. } => {
                assert_eq!(line, 3);
                assert!(message.contains("duplicate key"), "{message}");
            }
            other => panic!("{other}"),
        }
        // A control character: the message names it, in a comment or a key.
        let e = parse("a = 1 # \u{7}\n", FLAT).unwrap_err().to_string();
        assert!(e.starts_with("f.toml:1: invalid character '\\u{7}'"), "{e}");
        let e = parse("a = 1\r\u{0}x = 1\n", FLAT).unwrap_err().to_string();
        assert!(e.starts_with("f.toml:2: invalid character '\\0'"), "{e}");
    }
}
