//! Running the binary.

use std::path::Path;
use std::process::{Command, Output};

pub fn polbrdf(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_polbrdf"))
        .args(args)
        .output()
        .expect("the polbrdf binary runs")
}

pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

pub fn write(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_string()
}

/// Parses a CSV produced by `eval` into header and rows of fields.
pub fn parse_csv(text: &str) -> (Vec<String>, Vec<Vec<String>>) {
    let mut lines = text.lines();
    let header = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_string)
        .collect();
    let rows = lines
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect();
    (header, rows)
}

/// Runs the binary with its address space limited to `kib` KiB (`ulimit -v` in `sh`), so that
/// an allocation sized by a claim instead of by the data aborts the run.
pub fn polbrdf_limited(kib: u64, args: &[&str]) -> Output {
    Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -v {kib} && exec \"$0\" \"$@\""))
        .arg(env!("CARGO_BIN_EXE_polbrdf"))
        .args(args)
        .output()
        .expect("sh runs")
}
