//! The text of a `.npy` header: the Python dict literal `{'descr': [...], 'fortran_order':
//! False, 'shape': (N,), }`, parsed by a small recursive-descent parser (nesting bounded) into
//! the header's columns, dtypes and row count.

use super::{file_err, Dtype, NpyHeader};
use crate::error::Result;
use std::path::Path;

/// A Python literal, as much of it as a `.npy` header uses.
#[derive(Debug, Clone, PartialEq)]
enum Lit {
    Str(String),
    Int(u64),
    Bool(bool),
    Tuple(Vec<Lit>),
    List(Vec<Lit>),
    Dict(Vec<(Lit, Lit)>),
}

impl Lit {
    fn kind(&self) -> &'static str {
        match self {
            Lit::Str(_) => "a string",
            Lit::Int(_) => "an integer",
            Lit::Bool(_) => "a boolean",
            Lit::Tuple(_) => "a tuple",
            Lit::List(_) => "a list",
            Lit::Dict(_) => "a dict",
        }
    }
}

/// The recursive-descent parser of a header's literal. Nesting is bounded.
struct LitParser<'a> {
    s: &'a [char],
    i: usize,
    depth: usize,
}

const MAX_DEPTH: usize = 16;

impl LitParser<'_> {
    fn skip_ws(&mut self) {
        while self.i < self.s.len() && self.s[self.i].is_whitespace() {
            self.i += 1;
        }
    }

    fn peek(&mut self) -> Option<char> {
        self.skip_ws();
        self.s.get(self.i).copied()
    }

    fn expect(&mut self, c: char) -> std::result::Result<(), String> {
        match self.peek() {
            Some(x) if x == c => {
                self.i += 1;
                Ok(())
            }
            Some(x) => Err(format!(
                "expected `{c}` at character {}, found `{x}`",
                self.i
            )),
            None => Err(format!("expected `{c}`, found the end of the header")),
        }
    }

    fn value(&mut self) -> std::result::Result<Lit, String> {
        if self.depth >= MAX_DEPTH {
            return Err("the header nests too deeply".into());
        }
        self.depth += 1;
        let v = match self.peek() {
            None => Err("the header ends where a value was expected".into()),
            Some('\'' | '"') => self.string().map(Lit::Str),
            Some('(') => self.seq('(', ')').map(|(v, _)| Lit::Tuple(v)),
            Some('[') => self.seq('[', ']').map(|(v, _)| Lit::List(v)),
            Some('{') => self.dict(),
            Some(c) if c.is_ascii_digit() => self.int(),
            Some(c) if c.is_alphabetic() => {
                let start = self.i;
                while self.i < self.s.len() && self.s[self.i].is_alphanumeric() {
                    self.i += 1;
                }
                let w: String = self.s[start..self.i].iter().collect();
                match w.as_str() {
                    "True" => Ok(Lit::Bool(true)),
                    "False" => Ok(Lit::Bool(false)),
                    _ => Err(format!("unexpected word `{}`", truncate(&w))),
                }
            }
            Some(c) => Err(format!(
                "unexpected character `{c}` at character {}",
                self.i
            )),
        };
        self.depth -= 1;
        v
    }

    fn int(&mut self) -> std::result::Result<Lit, String> {
        let start = self.i;
        let mut v: u64 = 0;
        while self.i < self.s.len() && (self.s[self.i].is_ascii_digit() || self.s[self.i] == '_') {
            if let Some(d) = self.s[self.i].to_digit(10) {
                v = v
                    .checked_mul(10)
                    .and_then(|v| v.checked_add(u64::from(d)))
                    .ok_or_else(|| {
                        let w: String = self.s[start..].iter().take(30).collect();
                        format!("integer {w}… is too large")
                    })?;
            }
            self.i += 1;
        }
        // A trailing `L` (Python 2's long) is accepted, as numpy does.
        if self.s.get(self.i) == Some(&'L') {
            self.i += 1;
        }
        Ok(Lit::Int(v))
    }

    fn string(&mut self) -> std::result::Result<String, String> {
        let q = self.s[self.i];
        self.i += 1;
        let mut out = String::new();
        loop {
            let Some(&c) = self.s.get(self.i) else {
                return Err("unterminated string in the header".into());
            };
            self.i += 1;
            if c == q {
                return Ok(out);
            }
            if c == '\n' {
                return Err("unterminated string in the header".into());
            }
            if c != '\\' {
                out.push(c);
                continue;
            }
            let Some(&e) = self.s.get(self.i) else {
                return Err("unterminated string in the header".into());
            };
            self.i += 1;
            let hex = |p: &mut Self, n: usize| -> std::result::Result<char, String> {
                let digits: String = p.s.get(p.i..p.i + n).unwrap_or(&[]).iter().collect();
                p.i += n;
                u32::from_str_radix(&digits, 16)
                    .ok()
                    .filter(|_| digits.len() == n)
                    .and_then(char::from_u32)
                    .ok_or_else(|| "bad escape in a string of the header".to_string())
            };
            out.push(match e {
                '\\' => '\\',
                '\'' => '\'',
                '"' => '"',
                'n' => '\n',
                'r' => '\r',
                't' => '\t',
                '0' => '\0',
                'x' => hex(self, 2)?,
                'u' => hex(self, 4)?,
                'U' => hex(self, 8)?,
                _ => {
                    return Err(format!(
                        "unsupported escape `\\{e}` in a string of the header"
                    ))
                }
            });
        }
    }

    /// A bracketed sequence; also says whether it had a trailing comma.
    fn seq(&mut self, open: char, close: char) -> std::result::Result<(Vec<Lit>, bool), String> {
        self.expect(open)?;
        let mut items = Vec::new();
        let mut trailing = false;
        loop {
            if self.peek() == Some(close) {
                self.i += 1;
                return Ok((items, trailing));
            }
            items.push(self.value()?);
            trailing = false;
            match self.peek() {
                Some(',') => {
                    self.i += 1;
                    trailing = true;
                }
                Some(c) if c == close => {}
                Some(c) => return Err(format!("expected `,` or `{close}`, found `{c}`")),
                None => return Err(format!("expected `{close}`, found the end of the header")),
            }
        }
    }

    fn dict(&mut self) -> std::result::Result<Lit, String> {
        self.expect('{')?;
        let mut items = Vec::new();
        loop {
            if self.peek() == Some('}') {
                self.i += 1;
                return Ok(Lit::Dict(items));
            }
            let k = self.value()?;
            self.expect(':')?;
            let v = self.value()?;
            items.push((k, v));
            match self.peek() {
                Some(',') => self.i += 1,
                Some('}') => {}
                Some(c) => return Err(format!("expected `,` or `}}`, found `{c}`")),
                None => return Err("expected `}`, found the end of the header".into()),
            }
        }
    }
}

fn truncate(s: &str) -> String {
    if s.chars().count() > 40 {
        s.chars().take(40).collect::<String>() + "…"
    } else {
        s.to_string()
    }
}

/// Parses the header's dict literal into columns and row count (version and offset left 0).
pub(super) fn parse_header_text(text: &str, path: &Path) -> Result<NpyHeader> {
    let err = |m: String| bad(path, m);
    let items = header_dict(text, path)?;
    let (descr, order, shape) = header_keys(items, path)?;
    let shape = match shape {
        Lit::Tuple(v) => v
            .into_iter()
            .map(|d| match d {
                Lit::Int(n) => Ok(n),
                other => Err(err(format!("shape holds {}, not an integer", other.kind()))),
            })
            .collect::<Result<Vec<u64>>>()?,
        other => return Err(err(format!("shape is {}, not a tuple", other.kind()))),
    };
    check_order(order, path)?;
    let fields = match descr {
        Lit::List(fields) => fields,
        Lit::Str(d) => {
            return Err(err(format!(
                "the array has the plain dtype `{}` and shape {shape:?}: a table needs named \
                 columns — save a structured array (e.g. numpy.rec.fromarrays(columns, \
                 names=[...]))",
                truncate(&d)
            )))
        }
        other => return Err(err(format!("descr is {}, not a list", other.kind()))),
    };
    let rows = match shape.as_slice() {
        [n] => *n,
        _ => {
            return Err(err(format!(
                "shape {shape:?}: a table is a one-dimensional structured array"
            )))
        }
    };
    let (columns, dtypes) = columns(&fields, path)?;
    Ok(NpyHeader {
        version: (0, 0),
        columns,
        dtypes,
        rows,
        data_offset: 0,
    })
}

/// An error of the header of `path`.
fn bad(path: &Path, m: String) -> crate::error::Error {
    file_err(path, format!(".npy header: {m}"))
}

/// The items of the header's literal, which must be one dict and nothing after it.
fn header_dict(text: &str, path: &Path) -> Result<Vec<(Lit, Lit)>> {
    let chars: Vec<char> = text.chars().collect();
    let mut p = LitParser {
        s: &chars,
        i: 0,
        depth: 0,
    };
    let lit = p.value().map_err(|m| bad(path, m))?;
    if p.peek().is_some() {
        return Err(bad(path, "text after the header's dict".into()));
    }
    let Lit::Dict(items) = lit else {
        return Err(bad(path, format!("expected a dict, found {}", lit.kind())));
    };
    Ok(items)
}

/// The values of `descr`, `fortran_order` and `shape`: each given once, no other key.
fn header_keys(items: Vec<(Lit, Lit)>, path: &Path) -> Result<(Lit, Lit, Lit)> {
    let (mut descr, mut order, mut shape) = (None, None, None);
    for (k, v) in items {
        let Lit::Str(k) = k else {
            return Err(bad(path, format!("a key is {}, not a string", k.kind())));
        };
        let slot = match k.as_str() {
            "descr" => &mut descr,
            "fortran_order" => &mut order,
            "shape" => &mut shape,
            other => {
                return Err(bad(
                    path,
                    format!(
                        "unknown key `{}` (expected descr, fortran_order, shape)",
                        truncate(other)
                    ),
                ))
            }
        };
        if slot.replace(v).is_some() {
            return Err(bad(path, format!("key `{k}` appears twice")));
        }
    }
    let (Some(descr), Some(order), Some(shape)) = (descr, order, shape) else {
        return Err(bad(
            path,
            "the keys descr, fortran_order and shape are all required".into(),
        ));
    };
    Ok((descr, order, shape))
}

/// `fortran_order` must be `False` (C order).
fn check_order(order: Lit, path: &Path) -> Result<()> {
    match order {
        Lit::Bool(false) => Ok(()),
        Lit::Bool(true) => Err(bad(
            path,
            "Fortran order is not supported (save a C-ordered structured array)".into(),
        )),
        other => Err(bad(
            path,
            format!("fortran_order is {}, not a boolean", other.kind()),
        )),
    }
}

/// The column names and dtypes of the `descr` list: at least one field, each a (name, type)
/// pair of a non-empty name given once and a supported scalar type.
fn columns(fields: &[Lit], path: &Path) -> Result<(Vec<String>, Vec<Dtype>)> {
    let err = |m: String| bad(path, m);
    if fields.is_empty() {
        return Err(err("the dtype has no fields".into()));
    }
    let mut columns = Vec::with_capacity(fields.len());
    let mut dtypes = Vec::with_capacity(fields.len());
    // Repeated names by hashing: linear in the fields (a list search was quadratic: 50 000
    // fields took seconds, issue 35).
    let mut seen = std::collections::HashSet::with_capacity(fields.len());
    for f in fields {
        let Lit::Tuple(parts) = f else {
            return Err(err(format!(
                "a field is {}, not a (name, type) tuple",
                f.kind()
            )));
        };
        match parts.as_slice() {
            [Lit::Str(name), Lit::Str(t)] => {
                let Some(d) = Dtype::parse(t) else {
                    return Err(err(format!(
                        "column `{}` has type `{}`; supported are <f8, >f8, <f4, >f4",
                        truncate(name),
                        truncate(t)
                    )));
                };
                if name.is_empty() {
                    return Err(err("a column has an empty name".into()));
                }
                if !seen.insert(name.as_str()) {
                    return Err(err(format!("column `{}` appears twice", truncate(name))));
                }
                columns.push(name.clone());
                dtypes.push(d);
            }
            [Lit::Str(name), _, _] => {
                return Err(err(format!(
                    "column `{}` is a sub-array; only scalar columns are supported",
                    truncate(name)
                )))
            }
            _ => return Err(err("a field is not a (name, type) pair of strings".into())),
        }
    }
    Ok((columns, dtypes))
}
