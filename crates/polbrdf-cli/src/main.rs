//! The `polbrdf` command line. `main` maps every error to a documented exit code:
//! 0 success, 1 internal error, 2 usage error, 3 invalid input data, 4 I/O failure.

use clap::{Parser, Subcommand};
use std::path::PathBuf;

mod error;
mod eval;
mod materials;
mod output;

use error::CliError;
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

fn main() -> ExitCode {
    // A panic is a bug: say so, and exit with the documented code 1 (not Rust's 101).
    std::panic::set_hook(Box::new(|info| {
        eprintln!("polbrdf: internal error (a bug, please report it): {info}");
        std::process::exit(1);
    }));
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
        } => eval::run(&material, &input, output.as_deref()),
        Command::Materials { show } => materials::run(show.as_deref()),
    }
}
