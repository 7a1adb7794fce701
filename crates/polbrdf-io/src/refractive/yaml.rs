//! A small YAML tree with the line of every node, built from yaml-rust2's events, and the
//! errors of a refractive-index file (naming the file, the line and the key).

use crate::error::{Error, Result};
use std::path::Path;
use yaml_rust2::parser::{Event, Parser};
use yaml_rust2::scanner::TScalarStyle;

/// Deepest nesting of YAML collections accepted (the database needs 3).
const MAX_DEPTH: usize = 64;

/// A YAML node and its 1-based line.
#[derive(Debug)]
pub(super) enum Node {
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
pub(super) struct Entry {
    pub(super) key: String,
    pub(super) line: usize,
    pub(super) value: Node,
}

impl Node {
    pub(super) fn line(&self) -> usize {
        match self {
            Node::Scalar { line, .. } | Node::Seq { line, .. } | Node::Map { line, .. } => *line,
        }
    }

    pub(super) fn kind(&self) -> &'static str {
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
pub(super) fn load_tree(text: &str, ctx: &Ctx<'_>) -> Result<Option<Node>> {
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
pub(super) struct Ctx<'a> {
    /// The file.
    pub(super) path: &'a Path,
}

impl Ctx<'_> {
    pub(super) fn syntax(&self, line: usize, message: String) -> Error {
        Error::Syntax {
            path: self.path.to_path_buf(),
            line,
            message,
        }
    }

    pub(super) fn field(&self, line: usize, field: &str, message: String) -> Error {
        Error::Field {
            path: self.path.to_path_buf(),
            line,
            field: field.to_string(),
            message,
        }
    }

    pub(super) fn file(&self, message: &str) -> Error {
        Error::File {
            path: self.path.to_path_buf(),
            message: message.to_string(),
        }
    }
}
