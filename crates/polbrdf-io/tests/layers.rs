//! The modules of the table formats depend one way (issue 33's cycle `stream ↔ csv_io ↔ npy ↔
//! arrow`, broken in issue 35): `stream` dispatches to the format readers, which share the
//! types of `table` and never use `stream`; `table` uses none of them.

/// The modules of the crate a source file names through `crate::` or `use crate::`.
fn uses(source: &str) -> Vec<String> {
    let mut out: Vec<String> = source
        .match_indices("crate::")
        .map(|(i, _)| {
            source[i + 7..]
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
