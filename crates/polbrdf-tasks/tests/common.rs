//! Shared fixtures: the repository's examples and scratch scene files.

use std::path::{Path, PathBuf};

/// A file of the repository's `examples/`.
pub fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name)
}

/// Writes `text` as `name` in `dir`, returning its path.
pub fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).expect("scratch file");
    p
}

/// A scene file in `dir` whose band is the example LWIR band (copied next to it).
pub fn band_scene(dir: &Path, name: &str, rest: &str) -> PathBuf {
    std::fs::copy(example("lwir-8-12um.csv"), dir.join("lwir.csv")).expect("band copy");
    write(
        dir,
        name,
        &format!("[band]\nresponse = \"lwir.csv\"\n{rest}"),
    )
}
