//! The `polbrdf` command line. `main` maps every error to a documented exit code:
//! 0 success, 1 internal error, 2 usage error, 3 invalid input data, 4 I/O failure.

use clap::{Parser, Subcommand};
use polbrdf::batch;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Polarimetric BRDF toolkit: the simplified Maxwell–Beard pBRDF (Zhuansun et al. 2015).
#[derive(Parser)]
#[command(name = "polbrdf", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Evaluate the pBRDF at every geometry of a CSV file.
    ///
    /// Output: the input columns, then brdf, dolp, aolp_deg, m00 … m33 (F row-major, psps basis,
    /// sr⁻¹), with full f64 precision.
    Eval {
        /// Material: a TOML file, or a preset name (see `polbrdf materials`).
        #[arg(long, value_name = "FILE.toml|PRESET")]
        material: String,
        /// Geometry CSV with columns theta_i_deg, phi_i_deg, theta_r_deg, phi_r_deg (any order;
        /// other columns are copied through). `-` reads standard input.
        #[arg(long, value_name = "geometry.csv")]
        input: PathBuf,
        /// Output CSV (written atomically); standard output when absent.
        #[arg(long, value_name = "out.csv")]
        output: Option<PathBuf>,
    },
    /// List the built-in materials.
    Materials {
        /// Print one preset as a material file (TOML) instead of the list.
        #[arg(long, value_name = "PRESET")]
        show: Option<String>,
    },
}

/// What can go wrong, each kind with its exit code.
#[derive(Debug)]
enum CliError {
    Io(polbrdf_io::Error),
    Model(polbrdf::Error),
    Output(std::io::Error),
}

impl CliError {
    fn exit_code(&self) -> u8 {
        match self {
            CliError::Io(e) if e.is_data_error() => 3,
            CliError::Io(_) => 4,
            CliError::Model(_) => 3,
            CliError::Output(_) => 4,
        }
    }
}

impl std::fmt::Display for CliError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            CliError::Io(e) => write!(f, "{e}"),
            CliError::Model(e) => write!(f, "{e}"),
            CliError::Output(e) => write!(f, "cannot write to standard output: {e}"),
        }
    }
}

impl From<polbrdf_io::Error> for CliError {
    fn from(e: polbrdf_io::Error) -> Self {
        CliError::Io(e)
    }
}

impl From<polbrdf::Error> for CliError {
    fn from(e: polbrdf::Error) -> Self {
        CliError::Model(e)
    }
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            let _ = e.print();
            return ExitCode::from(if e.use_stderr() { 2 } else { 0 });
        }
    };
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(CliError::Output(e)) if e.kind() == std::io::ErrorKind::BrokenPipe => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("polbrdf: error: {e}");
            ExitCode::from(e.exit_code())
        }
    }
}

fn run(cli: Cli) -> Result<(), CliError> {
    match cli.command {
        Command::Eval {
            material,
            input,
            output,
        } => eval(&material, &input, output.as_deref()),
        Command::Materials { show } => materials(show.as_deref()),
    }
}

fn eval(material: &str, input: &Path, output: Option<&Path>) -> Result<(), CliError> {
    let material = polbrdf_io::load_material(material)?.build()?;
    let table = polbrdf_io::read_geometry_csv(input)?;
    let pbrdf = batch::pbrdf_of(&material, &table.geometries);
    let bytes = polbrdf_io::csv_io::results_csv(&table, &pbrdf)?;
    write_output(output, &bytes)
}

fn write_output(output: Option<&Path>, bytes: &[u8]) -> Result<(), CliError> {
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

fn materials(show: Option<&str>) -> Result<(), CliError> {
    let text = match show {
        Some(name) => polbrdf_io::material_to_toml(&polbrdf::preset(name)?),
        None => {
            let mut text = String::from("Built-in materials (use the name with --material):\n\n");
            for p in polbrdf::presets::all() {
                text.push_str(&format!("  {:<13} {}\n", p.name, p.description));
            }
            text.push_str("\n`polbrdf materials --show NAME` prints one as a material file.\n");
            text
        }
    };
    write_output(None, text.as_bytes())
}
