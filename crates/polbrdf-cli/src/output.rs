//! Where results go: an output target of `polbrdf_io` (a regular file written atomically, a
//! device, FIFO or `/dev/fd/N` written directly, `-` for standard output), or standard output.

use crate::error::CliError;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Writes `bytes` to `output` atomically, or to standard output when `None`.
pub fn write_output(output: Option<&Path>, bytes: &[u8]) -> Result<(), CliError> {
    match output {
        Some(path) => Ok(polbrdf_io::write_atomic(path, bytes)?),
        None => {
            let mut out = std::io::stdout().lock();
            out.write_all(bytes)
                .and_then(|_| out.flush())
                .map_err(CliError::Output)
        }
    }
}

/// Prints a note (a summary, a progress line) on standard error, ignoring a closed or broken
/// standard error: a note is never worth a lost result or an abort.
pub fn note(text: &str) {
    let mut err = std::io::stderr().lock();
    let _ = err.write_all(text.as_bytes()).and_then(|()| err.flush());
}

/// `eprintln!` that never panics: a line on standard error through [`note`].
#[macro_export]
macro_rules! note {
    ($($arg:tt)*) => {
        $crate::output::note(&format!("{}\n", format_args!($($arg)*)))
    };
}

/// Prints warnings about suspicious units (polbrdf-io's `units`) as notes:
/// `polbrdf: warning: <message>` on standard error. The command goes on.
pub fn unit_warnings(warnings: &[polbrdf_io::UnitWarning]) {
    for w in warnings {
        note!("polbrdf: warning: {w}");
    }
}

/// `polbrdf_io::load_material`, with the material's unit warnings printed ([`unit_warnings`]).
pub fn load_material(arg: &str) -> Result<polbrdf::MaterialSpec, CliError> {
    let spec = polbrdf_io::load_material(arg)?;
    unit_warnings(&polbrdf_io::material_warnings(&spec, arg));
    Ok(spec)
}

/// A file to write: name in the output directory and content.
pub type OutputFile = (String, Vec<u8>);

/// Creates `dir` and writes every file atomically; returns the paths.
pub fn write_all(dir: &Path, files: &[OutputFile]) -> Result<Vec<PathBuf>, CliError> {
    Ok(polbrdf_io::write_files(dir, files)?)
}

/// A CSV document from a header and rows of numbers (shortest round-trip form).
pub fn csv(header: &[&str], rows: impl Iterator<Item = Vec<f64>>) -> Vec<u8> {
    polbrdf_io::CsvTable::document(header, rows)
}

/// What a path option of a command names.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// A file read (a material option names a file or a preset; a preset is not a file).
    Input,
    /// A file written (through `polbrdf_io::Output`).
    File,
    /// A directory of files written as a set (polbrdf-io's `write_set`; an existing one keeps
    /// every file not of the set).
    Dir,
}

/// Every option of every command that names a file or directory, with its role. `main` checks
/// the outputs against the inputs and each other through the output layer
/// ([`polbrdf_io::check_distinct`]) before any command runs, and a unit test of `main` walks
/// the command-line definitions so that no path option is missing here: a new writer cannot
/// bypass the checks.
pub const PATH_OPTIONS: &[(&str, &str, Role)] = &[
    ("eval", "material", Role::Input),
    ("eval", "input", Role::Input),
    ("eval", "output", Role::File),
    ("fit", "material", Role::Input),
    ("fit", "data", Role::Input),
    ("fit", "output", Role::File),
    ("fit", "material_out", Role::File),
    ("fit", "plot", Role::File),
    ("fit", "index_out", Role::File),
    ("reproduce", "out", Role::Dir),
    ("contrast", "target", Role::Input),
    ("contrast", "background", Role::Input),
    ("contrast", "scene", Role::Input),
    ("contrast", "band", Role::Input),
    ("contrast", "out", Role::Dir),
    ("detect", "scene", Role::Input),
    ("detect", "sensor", Role::Input),
    ("detect", "target", Role::Input),
    ("detect", "background", Role::Input),
    ("detect", "target_fit", Role::Input),
    ("detect", "background_fit", Role::Input),
    ("detect", "out", Role::Dir),
    ("albedo", "material", Role::Input),
    ("albedo", "band", Role::Input),
    ("albedo", "output", Role::File),
    ("emission", "material", Role::Input),
    ("emission", "band", Role::Input),
    ("emission", "output", Role::File),
    ("radiance", "material", Role::Input),
    ("radiance", "scene", Role::Input),
    ("radiance", "input", Role::Input),
    ("radiance", "output", Role::File),
    ("map", "material", Role::Input),
    ("map", "band", Role::Input),
    ("map", "out", Role::Dir),
    ("spectrum", "material", Role::Input),
    ("spectrum", "out", Role::Dir),
    ("lut", "config", Role::Input),
    ("lut", "out", Role::Dir),
    ("check", "material", Role::Input),
    ("check", "band", Role::Input),
    ("check", "output", Role::File),
    ("export", "material", Role::Input),
    ("export", "output", Role::File),
    ("daytime", "scene", Role::Input),
    ("daytime", "sensor", Role::Input),
    ("daytime", "target", Role::Input),
    ("daytime", "background", Role::Input),
    ("daytime", "out", Role::Dir),
    // The explorer's built page: a folder only read (served), never written.
    ("explore", "dir", Role::Input),
];

/// The paths of `command`'s options of `role` given on its command line `m`.
pub fn paths_of(command: &str, m: &clap::ArgMatches, role: Role) -> Vec<PathBuf> {
    PATH_OPTIONS
        .iter()
        .filter(|(c, _, r)| *c == command && *r == role)
        .filter_map(|(_, id, _)| m.try_get_raw(id).ok().flatten())
        .flatten()
        .map(PathBuf::from)
        .collect()
}

/// The files named inside an input of option `id`: those a scene names (band, sky table and
/// profile, materials and their index files), or the index file a material names. An input
/// that cannot be read names none here (the command reports it); nor does standard input.
fn named_inside(id: &str, path: &Path) -> Vec<PathBuf> {
    // Standard input is read by the command, once.
    if path.as_os_str() == "-" {
        return Vec::new();
    }
    match id {
        "scene" => polbrdf_io::read_scene(path).map_or_else(|_| Vec::new(), |s| s.files),
        "sensor" => polbrdf_io::read_sensor(path).map_or_else(|_| Vec::new(), |s| s.files),
        "material" | "target" | "background" => path
            .to_str()
            .and_then(|arg| polbrdf_io::load_material(arg).ok())
            .and_then(|spec| polbrdf_io::material::index_file(&spec))
            .into_iter()
            .collect(),
        _ => Vec::new(),
    }
}

/// The output layer's checks of a command line, before the command runs: no output file is an
/// input, a file named inside an input (scene, material), or another output (compared by
/// device and inode); an output directory that exists is a directory.
pub fn check_paths(command: &str, m: &clap::ArgMatches) -> Result<(), CliError> {
    let mut inputs = paths_of(command, m, Role::Input);
    let files = paths_of(command, m, Role::File);
    if !files.is_empty() {
        for (_, id, _) in PATH_OPTIONS
            .iter()
            .filter(|(c, _, r)| *c == command && *r == Role::Input)
        {
            let given: Vec<PathBuf> = m
                .try_get_raw(id)
                .ok()
                .flatten()
                .into_iter()
                .flatten()
                .map(PathBuf::from)
                .collect();
            for p in given {
                inputs.extend(named_inside(id, &p));
            }
        }
    }
    let ins: Vec<&Path> = inputs.iter().map(PathBuf::as_path).collect();
    let outs: Vec<&Path> = files.iter().map(PathBuf::as_path).collect();
    polbrdf_io::check_distinct(&ins, &outs)?;
    for dir in paths_of(command, m, Role::Dir) {
        if dir.exists() && !dir.is_dir() {
            return Err(CliError::Io(polbrdf_io::Error::Write {
                path: dir,
                source: std::io::Error::new(
                    std::io::ErrorKind::AlreadyExists,
                    "exists and is not a directory: refusing to replace it (this option names \
                     a directory of outputs)",
                ),
            }));
        }
    }
    Ok(())
}
