//! Every code snippet of README.md and the book (docs/*.md) runs, so none can go stale:
//!
//! - shell blocks (```` ```sh ````, ```` ```console ````, ```` ```bash ````) run here, with
//!   bash (`-euo pipefail`), against the built binary (first on `PATH`), in a temporary
//!   directory holding a link to the repository's `examples/`;
//! - Python blocks run in python/tests/test_doc_snippets.py, with the installed package;
//! - Rust blocks are doc-tests of this crate (`src/lib.rs` includes each file that has one).
//!
//! A block that must not run has a marker on the line before its fence, with the reason:
//! `<!-- snippet: skip (reason) -->` or `<!-- snippet: synopsis -->` (a command's synopsis: its
//! placeholders are not files); a Python block needing an optional peer says
//! `<!-- snippet: needs MODULE -->`. Any other marker is an error.

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// One fenced code block of a Markdown file.
#[derive(Debug)]
struct Block {
    file: String,
    /// 1-based line of the opening fence.
    line: usize,
    lang: String,
    marker: Option<String>,
    code: String,
}

/// The Markdown files whose snippets must run: README.md and every chapter of the book but the
/// generated CLI reference.
fn documents() -> Vec<PathBuf> {
    let mut files = vec![root().join("README.md")];
    let mut docs: Vec<PathBuf> = std::fs::read_dir(root().join("docs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "md") && !p.ends_with("cli.md"))
        .collect();
    docs.sort();
    files.extend(docs);
    files
}

fn blocks(path: &Path) -> Vec<Block> {
    let text = std::fs::read_to_string(path).unwrap();
    let file = path
        .strip_prefix(root())
        .unwrap_or(path)
        .display()
        .to_string();
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < lines.len() {
        let Some(info) = lines[i].trim_start().strip_prefix("```") else {
            i += 1;
            continue;
        };
        let lang = info.trim().to_string();
        let marker = lines[..i]
            .iter()
            .rev()
            .find(|l| !l.trim().is_empty())
            .and_then(|l| l.trim().strip_prefix("<!-- snippet:"))
            .and_then(|l| l.strip_suffix("-->"))
            .map(|m| m.trim().to_string());
        let start = i;
        i += 1;
        let mut code = String::new();
        while i < lines.len() && !lines[i].trim_start().starts_with("```") {
            code.push_str(lines[i]);
            code.push('\n');
            i += 1;
        }
        i += 1;
        out.push(Block {
            file: file.clone(),
            line: start + 1,
            lang,
            marker,
            code,
        });
    }
    out
}

fn all_blocks() -> Vec<Block> {
    documents().iter().flat_map(|p| blocks(p)).collect()
}

/// Whether a marker is well formed: a skip with a reason, a synopsis, or a Python peer.
fn marker_ok(marker: &str) -> bool {
    let reason = |m: &str| m.starts_with('(') && m.ends_with(')') && m.len() > 2;
    marker == "synopsis"
        || marker.strip_prefix("skip ").is_some_and(reason)
        || marker
            .strip_prefix("needs ")
            .is_some_and(|m| !m.is_empty() && !m.contains(' '))
}

#[test]
fn every_snippet_marker_is_known_and_gives_its_reason() {
    let bad: Vec<String> = all_blocks()
        .iter()
        .filter_map(|b| {
            let m = b.marker.as_deref()?;
            (!marker_ok(m)).then(|| format!("{}:{}: `<!-- snippet: {m} -->`", b.file, b.line))
        })
        .collect();
    assert!(
        bad.is_empty(),
        "unknown markers (skip (reason), synopsis, needs MODULE):\n{}",
        bad.join("\n")
    );
}

fn is_shell(lang: &str) -> bool {
    matches!(lang, "sh" | "console" | "bash")
}

#[test]
fn every_shell_snippet_runs_against_the_binary() {
    let bin = PathBuf::from(env!("CARGO_BIN_EXE_polbrdf"));
    let path = std::env::join_paths(std::iter::once(bin.parent().unwrap().to_path_buf()).chain(
        std::env::split_paths(&std::env::var_os("PATH").unwrap_or_default()),
    ))
    .unwrap();
    let mut ran = 0;
    let mut failures = Vec::new();
    for b in all_blocks() {
        if !is_shell(&b.lang) || b.marker.is_some() {
            continue;
        }
        let dir = tempfile::tempdir().unwrap();
        std::os::unix::fs::symlink(root().join("examples"), dir.path().join("examples")).unwrap();
        let out = Command::new("bash")
            .args(["-euo", "pipefail", "-c", &b.code])
            .current_dir(dir.path())
            .env("PATH", &path)
            .output()
            .unwrap();
        ran += 1;
        if !out.status.success() {
            let stderr = String::from_utf8_lossy(&out.stderr);
            let tail: Vec<&str> = stderr.lines().rev().take(6).collect();
            failures.push(format!(
                "{}:{} ({}):\n{}\n  {}",
                b.file,
                b.line,
                out.status,
                b.code.trim_end(),
                tail.into_iter().rev().collect::<Vec<_>>().join("\n  ")
            ));
        }
    }
    assert!(
        ran >= 5,
        "only {ran} shell snippets found: is the extractor broken?"
    );
    assert!(
        failures.is_empty(),
        "{} of {ran} shell snippets failed:\n\n{}",
        failures.len(),
        failures.join("\n\n")
    );
}

#[test]
fn every_file_with_a_rust_snippet_is_a_doctest_of_the_crate() {
    let lib = std::fs::read_to_string(root().join("crates/polbrdf-cli/src/lib.rs")).unwrap();
    let missing: Vec<String> = all_blocks()
        .iter()
        .filter(|b| b.lang == "rust" && b.marker.is_none())
        .map(|b| b.file.clone())
        .filter(|f| !lib.contains(&format!("include_str!(\"../../../{f}\")")))
        .collect();
    assert!(
        missing.is_empty(),
        "Rust snippets in files that src/lib.rs does not include as doc-tests: {missing:?}"
    );
}
