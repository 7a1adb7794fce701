//! The modules of the table formats depend one way (issue 33's cycle `stream ↔ csv_io ↔ npy ↔
//! arrow`, broken in issue 35): `stream` dispatches to the format readers, which share the
//! types of `table` and never use `stream`; `table` uses none of them.

/// The modules of the crate a source file names through `crate::` or `use crate::`.
fn uses(source: &str) -> Vec<String> {
    first_segments(source, "crate::")
}

/// The first segment after every `prefix` (`crate::`, `super::`) in `code`, sorted, once each
/// (`""` for a grouped `prefix{…}`).
fn first_segments(code: &str, prefix: &str) -> Vec<String> {
    let mut out: Vec<String> = code
        .match_indices(prefix)
        .map(|(i, _)| {
            code[i + prefix.len()..]
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect()
        })
        .collect();
    out.sort();
    out.dedup();
    out
}

#[test]
fn the_format_modules_do_not_use_the_dispatcher() {
    let files = [
        ("csv_io", include_str!("../src/csv_io.rs")),
        ("npy", include_str!("../src/npy.rs")),
        ("arrow", include_str!("../src/arrow.rs")),
        ("table", include_str!("../src/table.rs")),
    ];
    for (name, source) in files {
        let used = uses(source);
        assert!(
            !used.iter().any(|m| m == "stream"),
            "{name} uses stream: {used:?}"
        );
    }
    let table = uses(include_str!("../src/table.rs"));
    assert!(table.is_empty(), "table uses {table:?}");
    // And the dispatcher does use them (the test reads what it means to).
    let stream = uses(include_str!("../src/stream.rs"));
    for m in ["csv_io", "npy", "arrow", "table"] {
        assert!(
            stream.iter().any(|u| u == m),
            "stream does not use {m}: {stream:?}"
        );
    }
}

/// The source files of module `name` of the crate: `src/NAME.rs` and, when the module is split
/// into a directory, every `src/NAME/*.rs`, each with its path (relative to `src`).
fn module_files(name: &str) -> Vec<(String, String)> {
    let src = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut out = vec![(
        format!("{name}.rs"),
        std::fs::read_to_string(src.join(format!("{name}.rs"))).expect("module file"),
    )];
    if let Ok(dir) = std::fs::read_dir(src.join(name)) {
        let mut parts: Vec<_> = dir.map(|e| e.expect("dir entry").path()).collect();
        parts.sort();
        for p in parts
            .into_iter()
            .filter(|p| p.extension().is_some_and(|e| e == "rs"))
        {
            let text = std::fs::read_to_string(&p).expect("part file");
            out.push((
                format!("{name}/{}", p.file_name().unwrap().to_string_lossy()),
                text,
            ));
        }
    }
    out
}

/// `source` without its trailing unit tests and without comment lines: the code whose paths
/// are the file's `use` edges (a doc link is not one).
fn code(source: &str) -> String {
    let end = source
        .find("#[cfg(test)]\nmod tests")
        .unwrap_or(source.len());
    source[..end]
        .lines()
        .filter(|l| !l.trim_start().starts_with("//"))
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn the_format_modules_and_their_parts_use_one_another_one_way() {
    // Each module may use only modules ranked below it: `table` < `csv_io` < `npy`, `arrow`
    // (neither uses the other) < `stream`. A use upward would close a cycle.
    let rank = [
        ("table", 0),
        ("csv_io", 1),
        ("npy", 2),
        ("arrow", 2),
        ("stream", 3),
    ];
    let rank_of = |m: &str| rank.iter().find(|(n, _)| *n == m).map(|&(_, r)| r);
    for (module, r) in rank {
        for (file, source) in module_files(module) {
            for used in uses(&code(&source)) {
                if let Some(u) = rank_of(&used).filter(|_| used != module) {
                    assert!(u < r, "{file} (of `{module}`) uses `{used}`, not below it");
                }
            }
        }
    }
    // Within a module split into parts, a part uses its siblings by name (`super::part::…`),
    // never the module's own file (which only declares and re-exports them), and the edges
    // between the parts have no cycle.
    for module in ["csv_io", "stream"] {
        let files = module_files(module);
        let parts: Vec<String> = files[1..]
            .iter()
            .map(|(f, _)| f[module.len() + 1..f.len() - 3].to_string())
            .collect();
        let mut edges: Vec<(usize, usize)> = Vec::new();
        for (k, (file, source)) in files[1..].iter().enumerate() {
            for used in first_segments(&code(source), "super::") {
                let j = parts.iter().position(|p| *p == used);
                let j = j.unwrap_or_else(|| {
                    panic!("{file} uses `super::{used}`, not a sibling part of `{module}`")
                });
                edges.push((k, j));
            }
        }
        // (The test reads what it means to.)
        assert!(parts.len() >= 5, "the parts of {module}: {parts:?}");
        // No cycle: removing parts that use no remaining part empties the graph.
        let mut left: Vec<usize> = (0..parts.len()).collect();
        while let Some(pos) = left
            .iter()
            .position(|&k| !edges.iter().any(|&(a, b)| a == k && left.contains(&b)))
        {
            left.remove(pos);
        }
        let cycle: Vec<&String> = left.iter().map(|&k| &parts[k]).collect();
        assert!(
            cycle.is_empty(),
            "parts of {module} on a cycle, or using one: {cycle:?}"
        );
    }
}
