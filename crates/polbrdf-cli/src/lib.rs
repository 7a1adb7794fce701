//! The `polbrdf` command line as a library: [`main_with_args`] parses a command line, runs it
//! and maps every error to a documented exit code: 0 success, 1 internal error, 2 usage error,
//! 3 invalid input data, 4 I/O failure, 5 fit did not converge. The `polbrdf` binary
//! (`src/bin/polbrdf.rs`) and the Python package's `polbrdf` command (`polbrdf._polbrdf.cli_main`)
//! both call it, so they are the same program. [`command`] is the clap definition, from which
//! the book's CLI reference (docs/cli.md) is generated.

use clap::{CommandFactory, FromArgMatches, Parser, Subcommand};
use std::ffi::OsString;
use std::path::PathBuf;

mod albedo;
mod bench;
mod check;
mod closed_set;
mod completions;
mod contrast;
mod daytime;
mod detect;
mod detect_frame;
mod emission;
mod error;
mod eval;
mod explore;
mod export;
mod figures;
mod fit;
mod limits;
mod lut;
mod map;
mod materials;
mod measured;
mod output;
mod progress;
mod radiance;
mod reproduce;
mod residuals;
mod spectrum;
mod sun;
mod sweep;
mod values;
mod view;

use error::CliError;

/// Polarimetric BRDF toolkit: the simplified Maxwell–Beard pBRDF (Zhuansun et al. 2015).
#[derive(Parser)]
#[command(name = "polbrdf", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Evaluate the pBRDF at every geometry of a table (CSV, .npy, Arrow IPC).
    ///
    /// Output: the input columns, then brdf, dolp, aolp_deg, m00 … m33 (F row-major, psps basis,
    /// sr⁻¹), with full f64 precision. Formats by extension, for --input and --output alike:
    /// .npy (a structured NumPy array), .arrow/.feather (Arrow IPC file), .arrows (Arrow IPC
    /// stream), anything else CSV.
    Eval {
        /// Material: a TOML file, or a preset name (see `polbrdf materials`).
        #[arg(long, value_name = "FILE.toml|PRESET")]
        material: String,
        /// Geometry table (CSV, .npy, .arrow, .feather, .arrows) with columns theta_i_deg,
        /// phi_i_deg, theta_r_deg, phi_r_deg (any order; other columns are copied through) or
        /// the direction vectors w_i_x, w_i_y, w_i_z, w_r_x, w_r_y, w_r_z, and wavelength_um
        /// (µm) for a material with a spectral index. `-` reads CSV from standard input.
        #[arg(long, value_name = "geometry.csv|.npy|.arrow|.arrows")]
        input: PathBuf,
        /// Output table (written atomically; CSV, .npy, .arrow, .feather or .arrows by
        /// extension); CSV on standard output when absent or `-`.
        #[arg(long, value_name = "out.csv|.npy|.arrow|.arrows")]
        output: Option<PathBuf>,
    },
    /// Fit material parameters to measurements (Levenberg–Marquardt), with uncertainties.
    ///
    /// Prints a summary on standard error; writes fit.json (parameters with standard errors,
    /// covariance, correlation, χ²) to --output or standard output. Exit code 5 when the fit
    /// did not converge (results still written, flagged).
    Fit {
        /// Start values and fixed parameters: a TOML file or a preset name.
        #[arg(long, value_name = "INIT.toml|PRESET")]
        material: String,
        /// Measurements: the four angle columns plus any of brdf, dolp, brdf_s, brdf_p, m00 …
        /// m33, each optionally with `sigma_<column>` (1-σ), and wavelength_um (µm) for spectral
        /// data. Empty cells mean "not measured".
        #[arg(long, value_name = "MEAS.csv")]
        data: PathBuf,
        /// Free parameters, comma-separated: any of n, k, a, b|sigma_deg, rho_d, rho_v,
        /// tau_deg, omega_deg.
        #[arg(long, value_name = "LIST", value_parser = values::free_parameters())]
        free: String,
        /// fit.json destination (written atomically); standard output when absent.
        #[arg(long, value_name = "fit.json")]
        output: Option<PathBuf>,
        /// Also write the fitted material as a TOML file that `polbrdf eval` loads.
        #[arg(long, value_name = "fitted.toml")]
        material_out: Option<PathBuf>,
        /// Extra starts scattered around the start values (the best fit is kept).
        #[arg(long, default_value_t = 2, value_parser = values::count(0, limits::STARTS))]
        starts: usize,
        /// Seed of the extra starts.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Also draw the normalized residuals (model − data)/σ: a .png or .svg file.
        #[arg(long, value_name = "residuals.png|.svg")]
        plot: Option<PathBuf>,
        /// Fit the free parameters separately at each wavelength of the data (needs a
        /// wavelength_um column): e.g. an effective index n(λ), k(λ). fit.json then holds one
        /// fit per wavelength.
        #[arg(long)]
        per_wavelength: bool,
        /// With --per-wavelength and n free: write the fitted n(λ), k(λ) as a refractiveindex.info
        /// YAML file (tabulated nk), usable as `index = "FILE.yml"` in a material file.
        #[arg(long, value_name = "index.yml", requires = "per_wavelength")]
        index_out: Option<PathBuf>,
        /// With a .pbsdf table: keep every N-th node along each of φ_d, θ_d, θ_h (default: the
        /// smallest N keeping at most 20 000 cells).
        #[arg(long, value_name = "N", value_parser = values::count(1, usize::MAX))]
        subsample: Option<usize>,
        /// With a .pbsdf table: leave out the cells whose matrix is not physically realizable
        /// (they are always counted and reported).
        #[arg(long)]
        exclude_inadmissible: bool,
    },
    /// Regenerate the paper's Figs. 2–5 and Table 1 (PNG, SVG, CSV) with report.md, which
    /// checks each of the paper's claims against the computation.
    Reproduce {
        /// Output directory (created if missing).
        #[arg(long, value_name = "DIR", default_value = "reproduce-out")]
        out: PathBuf,
    },
    /// Target against background: polarization contrast over the viewing hemisphere and the
    /// best viewing directions.
    ///
    /// Writes into --out: contrast.csv (one row per viewing direction), best.json (the best
    /// direction and the best distinct ones), and polar maps (PNG and SVG) of the DoLP of target
    /// and background, ΔDoLP, the intensity ratio, the AoLP difference and the polarization
    /// contrast, with overview.png/svg.
    Contrast(contrast::Args),
    /// Detection: will a polarization sensor see the target on its background, from which
    /// view, by which feature (S0, DoLP or both), and out to what range (docs/detection.md).
    ///
    /// Writes into --out: detect.csv (one row per view and range), best.json (the views ranked
    /// by detection range) and, on a grid, polar maps (PNG and SVG) of the detection range and
    /// of P_d at the first --ranges-m.
    Detect(detect::Args),
    /// Directional–hemispherical reflectance (albedo) at a set of incidence angles; values
    /// above 1 (energy created by the parameters) are flagged.
    ///
    /// Output CSV (standard output, or --output): theta_i_deg, albedo, surface, volume,
    /// exceeds_one; the table with its verdict goes to standard error.
    Albedo(albedo::Args),
    /// Polarized thermal emission by Kirchhoff's law: the emissivity Stokes vector at a set of
    /// view zenith angles, by route A (the definition) and route B (reciprocity).
    ///
    /// Output CSV (standard output, or --output): theta_deg, eps0, eps1, eps2, eps3, eps_s,
    /// eps_p, dolp, reciprocity_residual, valid.
    Emission(emission::Args),
    /// The observed Stokes radiance of a surface in a scene (thermal emission, reflected sky,
    /// atmosphere) at a set of view directions.
    ///
    /// Output CSV (standard output, or --output): theta_r_deg, phi_r_deg, s0, s1, s2, s3, dolp,
    /// aolp_deg — W·m⁻²·sr⁻¹·µm⁻¹ at one wavelength, W·m⁻²·sr⁻¹ over a band.
    Radiance(radiance::Args),
    /// Polar maps of the BRDF, DoLP and AoLP of one material over the viewing hemisphere.
    ///
    /// Writes into --out: map.csv (one row per viewing direction), brdf, dolp, aolp and
    /// overview (PNG and SVG).
    Map(map::Args),
    /// BRDF, DoLP and AoLP of one or more materials at one geometry over a range of
    /// wavelengths (spectral indices from the library or refractiveindex.info files).
    ///
    /// Writes into --out: spectrum.csv (wavelength_um, material, n, k, brdf, dolp, aolp_deg)
    /// and spectrum.png/svg (the DoLP against wavelength).
    Spectrum(sweep::Args),
    /// Throughput of the batch API (random valid geometries of `paint`): full-Mueller and
    /// BRDF+DoLP evaluations per second on one thread and on all threads (medians of several
    /// repeats), single-evaluation latency, a checksum and the CPU (with its SIMD level).
    Bench(bench::Args),
    /// A lookup table over materials × wavelengths × in-plane geometries (θi, θr, Δφ = φr − φi)
    /// from a TOML configuration (see docs/scaling.md).
    ///
    /// Writes into --out: table.npy (one row per material, wavelength, θi, θr, Δφ in C order;
    /// columns m00 … m33, brdf, dolp, aolp_deg as asked) and attrs.json (dimensions,
    /// coordinates, conventions, materials). Python: polbrdf.xarray.open_lut(DIR).
    Lut {
        /// The table's configuration (TOML: materials, wavelength_um, theta_i_deg,
        /// theta_r_deg, dphi_deg, quantities).
        #[arg(long, value_name = "lut.toml")]
        config: PathBuf,
        /// Output directory (created if missing; in an existing one, the table's files are
        /// replaced and no other file is touched).
        #[arg(long, value_name = "DIR")]
        out: PathBuf,
    },
    /// Check that a parameter set is physically valid: F realizable (coherency matrix positive
    /// semidefinite) over a dense grid, albedo ≤ 1 at every incidence angle, and reciprocity where
    /// the model form has it. Exit code 6 when a check fails.
    ///
    /// The report goes to standard error; --output writes the whole document as JSON (`-`:
    /// standard output).
    Check {
        /// A TOML file or a preset name.
        #[arg(long, value_name = "FILE.toml|PRESET")]
        material: String,
        /// Zenith step of the grid in degrees (the relative azimuth uses twice this step).
        #[arg(long, value_name = "DEG", default_value_t = polbrdf_tasks::check::DEFAULT_GRID_DEG,
              value_parser = values::number(values::Range::open_closed(0.0, 30.0)))]
        grid_deg: f64,
        /// Also write every check at every spectral node as JSON (written atomically, also
        /// when a check fails): the document of Python's `polbrdf.check`.
        #[arg(long, value_name = "check.json")]
        output: Option<PathBuf>,
        #[command(flatten)]
        spectral: spectrum::SpectralArgs,
    },
    /// Write a material as a Mitsuba 3 `measured_polarized` table (.pbsdf), which the stock
    /// plugin renders (docs/model.md §20).
    Export(export::Args),
    /// Serve the web explorer (built by scripts/build-web into web/dist) on localhost and print
    /// its address: polar maps of the Mueller matrix, BRDF, DoLP and AoLP, in-plane curves and
    /// the contrast against a background, computed in the browser (docs/explorer.md).
    Explore {
        /// The built page's folder (default: web/dist here, else beside the repository the
        /// binary was built in).
        #[arg(long, value_name = "DIR")]
        dir: Option<PathBuf>,
        /// Port on 127.0.0.1 (0: any free port).
        #[arg(long, value_name = "PORT", default_value_t = 8737)]
        port: u16,
    },
    /// The sun's position at a date, time and place (NREL SPA, ±0.0003°): zenith angle,
    /// compass azimuth (from north toward east) and the azimuth φ in the surface frame, as JSON.
    Sun(sun::Args),
    /// A scene whose sun is placed by date, time and place, swept through the local times of
    /// a day: writes into --out daytime.csv (per time: the sun, the best view's and a fixed
    /// view's ΔDoLP and polarization contrast, and with --sensor their detection ranges) and
    /// daytime.png/svg (against local time).
    Daytime(daytime::Args),
    /// List the built-in materials.
    Materials {
        /// Print one preset as a material file (TOML) instead of the list.
        #[arg(long, value_name = "PRESET")]
        show: Option<String>,
    },
    /// Print the shell completion script of `polbrdf` to standard output (e.g. `polbrdf
    /// completions bash > ~/.local/share/bash-completion/completions/polbrdf`).
    Completions {
        /// The shell.
        #[arg(value_enum)]
        shell: clap_complete::Shell,
    },
}

/// The Rust snippets of the book run as doc-tests of this crate (tests/doc_snippets.rs checks
/// that every file with one is included here).
#[cfg(doctest)]
#[doc = include_str!("../../../docs/guide-eval.md")]
pub struct BookSnippets;

/// The command line's definition (every command, option and help text), as clap holds it.
pub fn command() -> clap::Command {
    Cli::command()
}

/// Runs the command line `args` (the program name first, as `std::env::args_os` gives it) and
/// returns the process exit code. Installs the signal cleanup and the panic hook of a `polbrdf`
/// process: call it once, as a process's main function.
pub fn main_with_args<I, T>(args: I) -> u8
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    // SIGINT/SIGTERM/SIGHUP remove this run's named temporaries (before any thread starts).
    polbrdf_io::install_signal_cleanup();
    // A panic is a bug: say so, and exit with the documented code 1 (not Rust's 101).
    // Except a closed standard output (`polbrdf … | head`): `print!` panics on a broken pipe,
    // and a reader that stopped reading is no bug: exit quietly with 141 (128 + SIGPIPE), as
    // every command does for a closed standard output. Files are written before standard
    // output, so they are complete by then. The hook never prints with a panicking macro
    // (a broken standard error would abort).
    std::panic::set_hook(Box::new(|info| {
        let message = info.to_string();
        if message.contains("failed printing to stdout") {
            std::process::exit(141);
        }
        output::note(&format!(
            "polbrdf: internal error (a bug, please report it): {info}\n"
        ));
        std::process::exit(1);
    }));
    let parsed = Cli::command()
        .try_get_matches_from(args)
        .and_then(|m| Cli::from_arg_matches(&m).map(|cli| (m, cli)));
    let (matches, cli) = match parsed {
        Ok(parsed) => parsed,
        Err(e) => {
            let _ = e.print();
            return if e.use_stderr() { 2 } else { 0 };
        }
    };
    match checked_run(&matches, cli) {
        Ok(()) => 0,
        Err(e) if e.is_broken_pipe() => 141,
        Err(e) => {
            output::note(&format!("polbrdf: error: {e}\n"));
            e.exit_code()
        }
    }
}

/// Runs the command after the output layer's checks of its path options
/// ([`output::check_paths`]).
fn checked_run(matches: &clap::ArgMatches, cli: Cli) -> Result<(), CliError> {
    if let Some((name, m)) = matches.subcommand() {
        output::check_paths(name, m)?;
    }
    run(cli)
}

/// The checks of `fit`'s options against each other, before any file is read (a `.pbsdf`
/// table is known by its extension): `--index-out` needs `n` free, and the `.pbsdf` options
/// do not apply to a measurement CSV (never dropped silently).
fn fit_options(args: &fit::Args<'_>, pbsdf: bool) -> Result<(), CliError> {
    let free = polbrdf_fit::Param::parse_list(args.free)
        .map_err(|e| CliError::Usage(format!("--free: {e}")))?;
    if args.index_out.is_some() && !free.contains(&polbrdf_fit::Param::N) {
        return Err(CliError::Usage(
            "--index-out needs `n` among the free parameters (--free)".into(),
        ));
    }
    if !pbsdf {
        let given = [
            ("--subsample", args.subsample.is_some()),
            ("--exclude-inadmissible", args.exclude_inadmissible),
        ];
        if let Some((name, _)) = given.iter().find(|(_, on)| *on) {
            return Err(CliError::Usage(format!(
                "{name} applies to a .pbsdf table only, not to a measurement CSV ({})",
                args.data.display()
            )));
        }
    }
    Ok(())
}

fn run(cli: Cli) -> Result<(), CliError> {
    match cli.command {
        Command::Eval {
            material,
            input,
            output,
        } => eval::run(&material, &input, output.as_deref()),
        Command::Fit {
            material,
            data,
            free,
            output,
            material_out,
            starts,
            seed,
            plot,
            per_wavelength,
            index_out,
            subsample,
            exclude_inadmissible,
        } => {
            let args = fit::Args {
                material: &material,
                data: &data,
                free: &free,
                output: output.as_deref(),
                material_out: material_out.as_deref(),
                starts,
                seed,
                plot: plot.as_deref(),
                per_wavelength,
                index_out: index_out.as_deref(),
                subsample,
                exclude_inadmissible,
            };
            let pbsdf = polbrdf_tasks::pbsdf::is_pbsdf(&data);
            fit_options(&args, pbsdf)?;
            if pbsdf {
                measured::run(&args)
            } else {
                fit::run(&args)
            }
        }
        Command::Reproduce { out } => reproduce::run(&out),
        Command::Check {
            material,
            grid_deg,
            output,
            spectral,
        } => check::run(&material, grid_deg, output.as_deref(), &spectral),
        Command::Materials { show } => materials::run(show.as_deref()),
        Command::Explore { dir, port } => explore::run(dir.as_deref(), port),
        Command::Completions { shell } => completions::run(shell, &mut Cli::command()),
        Command::Contrast(args) => contrast::run(&args),
        Command::Detect(args) => detect::run(&args),
        Command::Albedo(args) => albedo::run(&args),
        Command::Emission(args) => emission::run(&args),
        Command::Radiance(args) => radiance::run(&args),
        Command::Map(args) => map::run(&args),
        Command::Bench(args) => bench::run(&args),
        Command::Lut { config, out } => lut::run(&config, &out),
        Command::Spectrum(args) => sweep::run(&args),
        Command::Export(args) => export::run(&args),
        Command::Sun(args) => sun::run(&args),
        Command::Daytime(args) => daytime::run(&args),
    }
}

#[cfg(test)]
mod tests {

    #[test]
    fn completions_cover_every_command_in_every_shell() {
        use clap::ValueEnum;
        let names: Vec<String> = Cli::command()
            .get_subcommands()
            .map(|c| c.get_name().to_string())
            .collect();
        assert!(names.contains(&"completions".to_string()));
        for shell in clap_complete::Shell::value_variants() {
            let mut script = Vec::new();
            clap_complete::generate(*shell, &mut Cli::command(), "polbrdf", &mut script);
            let script = String::from_utf8(script).unwrap();
            for name in &names {
                assert!(script.contains(name.as_str()), "{shell}: {name} missing");
            }
        }
    }

    use super::*;
    use output::{Role, PATH_OPTIONS};

    /// A path no run can read: a command line's inputs point here, so that a run stops at its
    /// first file (after every option check) with an error naming it.
    const NOWHERE: &str = "/nonexistent-polbrdf-probe/x";

    /// Command lines of each command whose inputs do not exist, in order of preference: an
    /// option probed by the next test is set in the first one that admits it (clap's
    /// `requires`/`conflicts_with` differ between them).
    fn probe_templates(command: &str) -> Vec<Vec<String>> {
        let x = NOWHERE;
        let lines: Vec<Vec<&str>> = match command {
            "eval" => vec![vec!["--material", x, "--input", x]],
            "fit" => vec![vec!["--material", x, "--data", x, "--free", "rho_d"]],
            "contrast" => vec![
                vec!["--target", x, "--background", x, "--sun-zenith-deg", "30"],
                vec![
                    "--target",
                    x,
                    "--background",
                    x,
                    "--sun-zenith-deg",
                    "30",
                    "--band",
                    x,
                ],
                vec!["--target", x, "--background", x, "--scene", x],
            ],
            "map" | "albedo" | "emission" | "check" => vec![
                vec!["--material", x, "--sun-zenith-deg", "30"],
                vec!["--material", x],
                vec!["--material", x, "--sun-zenith-deg", "30", "--band", x],
                vec!["--material", x, "--band", x],
            ],
            "detect" => vec![
                vec!["--scene", x, "--sensor", x],
                vec!["--scene", x, "--sensor", x, "--frame"],
            ],
            "daytime" => vec![vec!["--scene", x, "--sensor", x]],
            "radiance" => vec![vec!["--material", x, "--scene", x]],
            "spectrum" => vec![vec!["--material", x]],
            "export" => vec![vec![
                "--material",
                x,
                "--output",
                "/nonexistent-polbrdf-probe/t.pbsdf",
            ]],
            "explore" => vec![vec!["--dir", x]],
            "sun" => vec![vec![
                "--date-time",
                "2026-06-21T12:00:00Z",
                "--latitude-deg",
                "48",
                "--longitude-deg",
                "16",
            ]],
            "bench" => vec![vec!["--count", "1000"]],
            _ => vec![vec![]],
        };
        lines
            .into_iter()
            .map(|l| {
                std::iter::once("polbrdf")
                    .chain(std::iter::once(command))
                    .chain(l)
                    .map(String::from)
                    .collect()
            })
            .collect()
    }

    /// The exit code and message of a command line, as `main_with_args` gives them (without
    /// its process-wide hooks), or clap's refusal of the line.
    fn outcome(args: &[String]) -> Result<(u8, String), clap::Error> {
        let matches = Cli::command().try_get_matches_from(args)?;
        let cli = Cli::from_arg_matches(&matches)?;
        // `bench` and `sun` read no file, so a run would be the whole job (seconds of
        // benchmark, JSON on standard output): parsed only. Neither refuses an option after
        // parsing but as a usage error (`sun` maps its task's refusals so; `bench` has none).
        if matches!(args[1].as_str(), "bench" | "sun") {
            return Ok((0, String::new()));
        }
        Ok(match checked_run(&matches, cli) {
            Ok(()) => (0, String::new()),
            Err(e) => (e.exit_code(), e.to_string()),
        })
    }

    /// Issue 33: every numeric option of every command (found by walking the clap tree: every
    /// option whose values parse to one of `values::numeric_types`) is fed invalid and
    /// out-of-range values. A value its parser refuses is a usage error naming the option (exit
    /// code 2) before anything runs; a value its parser accepts is accepted by the command: the
    /// run goes on to its first input file (which does not exist) and stops there, never
    /// refusing the value later as invalid input (exit code 3) or failing on it.
    #[test]
    fn every_numeric_option_refuses_a_bad_value_with_exit_code_2() {
        const PROBES: [&str; 9] = [
            "nan",
            "inf",
            "-1",
            "0",
            "90",
            "1e300",
            "-1e300",
            "99999999999999999999",
            "x",
        ];
        let cli = Cli::command();
        let numeric = values::numeric_types();
        let mut probed = 0;
        for sub in cli.get_subcommands() {
            let name = sub.get_name();
            for arg in sub.get_arguments().filter(|a| !a.is_positional()) {
                let value_type = arg.get_value_parser().type_id();
                if !numeric.iter().any(|t| value_type == *t) {
                    continue;
                }
                let long = format!("--{}", arg.get_long().expect("a long option"));
                for probe in PROBES {
                    let given = format!("{long}={probe}");
                    let mut ran = false;
                    for mut line in probe_templates(name) {
                        if let Some(k) = line.iter().position(|a| *a == long) {
                            line.drain(k..k + 2);
                        }
                        line.push(given.clone());
                        match outcome(&line) {
                            // Refused by the option's value parser.
                            Err(e) if e.kind() == clap::error::ErrorKind::ValueValidation => {
                                assert_eq!(e.exit_code(), 2, "{line:?}");
                                assert!(e.to_string().contains(&long), "{line:?}: {e}");
                            }
                            // The template does not admit the option: try the next one.
                            Err(_) => continue,
                            Ok((code, message)) => assert!(
                                code != 1
                                    && (code != 3 || message.contains(NOWHERE))
                                    && !(message.contains(&long) && code != 2),
                                "{line:?}: accepted by the option's parser, then refused as \
                                 exit code {code}: {message}"
                            ),
                        }
                        ran = true;
                        break;
                    }
                    assert!(ran, "polbrdf {name} {given}: no template admits it");
                    probed += 1;
                }
            }
        }
        assert!(probed > 300, "{probed} probes");
    }

    /// The text options with a closed syntax, each with values that break it: their value
    /// parsers (`values::date`, `clock`, `date_time`, `free_parameters`) refuse every one with
    /// exit code 2 naming the option, before any file is read.
    const SYNTAX_PROBES: &[(&str, &str, &[&str])] = &[
        (
            "daytime",
            "date",
            &[
                "2026-13-01",
                "2026-02-30",
                "21.06.2026",
                "2026-06-21T12:00:00Z",
                "x",
            ],
        ),
        (
            "daytime",
            "from",
            &["24:00", "12:60", "7", "noon", "12:00:61"],
        ),
        (
            "daytime",
            "to",
            &["24:00", "12:60", "7", "noon", "12:00:61"],
        ),
        ("daytime", "times", &["07:00,25:00", "12:60", "7", "noon"]),
        (
            "sun",
            "date_time",
            &["2026-06-21", "2026-06-21T12:00:00", "2026-06-21 12:00", "x"],
        ),
        ("fit", "free", &["colour", "n,n", "b,sigma_deg", "n;k"]),
    ];

    /// Text options that name something whose content decides (a preset), or that refuse any
    /// value (a renamed option): no syntax to check at parsing.
    const NAME_IDS: &[(&str, &str)] = &[("materials", "show"), ("export", "old_out")];

    /// Issue 33: every text option of every command (walking the clap tree) is a path or
    /// material, a name of [`NAME_IDS`], or an option with a syntax in [`SYNTAX_PROBES`]; each
    /// value of the latter that breaks its syntax is refused by clap with exit code 2 naming the
    /// option, before anything runs (a run would first stop at its input file, exit 3).
    #[test]
    fn every_text_option_with_a_syntax_refuses_a_bad_value_with_exit_code_2() {
        let cli = Cli::command();
        let mut probed = 0;
        for sub in cli.get_subcommands() {
            let name = sub.get_name();
            for arg in sub.get_arguments().filter(|a| !a.is_positional()) {
                if arg.get_value_parser().type_id() != std::any::TypeId::of::<String>() {
                    continue;
                }
                let id = arg.get_id().as_str();
                if MATERIAL_IDS.contains(&id) || NAME_IDS.contains(&(name, id)) {
                    continue;
                }
                let Some((_, _, bad)) = SYNTAX_PROBES
                    .iter()
                    .find(|(c, i, _)| *c == name && *i == id)
                else {
                    panic!(
                        "`polbrdf {name} --{id}` is text: give it a value parser in values.rs \
                         and probes in SYNTAX_PROBES, or list it in NAME_IDS"
                    );
                };
                let long = format!("--{}", arg.get_long().expect("a long option"));
                for probe in *bad {
                    let mut line = probe_templates(name).remove(0);
                    if let Some(k) = line.iter().position(|a| *a == long) {
                        line.drain(k..k + 2);
                    }
                    line.push(format!("{long}={probe}"));
                    match outcome(&line) {
                        Err(e) if e.kind() == clap::error::ErrorKind::ValueValidation => {
                            assert_eq!(e.exit_code(), 2, "{line:?}");
                            assert!(e.to_string().contains(&long), "{line:?}: {e}");
                        }
                        other => panic!(
                            "{line:?}: not refused by the option's parser: {:?}",
                            other.map_err(|e| e.to_string())
                        ),
                    }
                    probed += 1;
                }
            }
        }
        assert_eq!(
            probed,
            SYNTAX_PROBES.iter().map(|(_, _, b)| b.len()).sum::<usize>(),
            "every probe of SYNTAX_PROBES names an option of a command"
        );
    }

    use std::path::Path;

    /// Options taking a material file or preset name (a `String`, which may name a file).
    const MATERIAL_IDS: [&str; 3] = ["material", "target", "background"];

    /// Every path option of every command (from the clap definitions) is classified in
    /// [`PATH_OPTIONS`], and every entry there exists.
    #[test]
    fn every_path_option_of_every_command_is_classified() {
        let cli = Cli::command();
        let mut seen = Vec::new();
        for sub in cli.get_subcommands() {
            for arg in sub.get_arguments() {
                let id = arg.get_id().as_str();
                let is_path = arg.get_value_parser().type_id() == std::any::TypeId::of::<PathBuf>();
                if !(is_path || MATERIAL_IDS.contains(&id)) {
                    continue;
                }
                let name = sub.get_name();
                assert!(
                    PATH_OPTIONS.iter().any(|(c, i, _)| *c == name && *i == id),
                    "`polbrdf {name} --{id}` names a path: classify it in output::PATH_OPTIONS \
                     (input, file or directory output) so the output layer checks it"
                );
                seen.push((name.to_string(), id.to_string()));
            }
        }
        for (c, i, _) in PATH_OPTIONS {
            assert!(
                seen.iter().any(|(sc, si)| sc == c && si == i),
                "output::PATH_OPTIONS lists `{c} --{i}`, which no command has"
            );
        }
    }

    /// A command line of `command` that writes its option `id` to `{X}`, with the material
    /// file `{m}` as an input (None when the test lacks one: the test then fails).
    fn template(command: &str, id: &str) -> Option<Vec<&'static str>> {
        let v: &[&str] = match (command, id) {
            ("eval", "output") => &[
                "eval",
                "--material",
                "{m}",
                "--input",
                "{g}",
                "--output",
                "{X}",
            ],
            ("fit", "output") => &[
                "fit",
                "--material",
                "{m}",
                "--data",
                "{f}",
                "--free",
                "rho_d",
                "--output",
                "{X}",
            ],
            ("fit", "material_out") => &[
                "fit",
                "--material",
                "{m}",
                "--data",
                "{f}",
                "--free",
                "rho_d",
                "--material-out",
                "{X}",
            ],
            ("fit", "plot") => &[
                "fit",
                "--material",
                "{m}",
                "--data",
                "{f}",
                "--free",
                "rho_d",
                "--plot",
                "{X}",
            ],
            ("fit", "index_out") => &[
                "fit",
                "--material",
                "{m}",
                "--data",
                "{f}",
                "--free",
                "n",
                "--per-wavelength",
                "--index-out",
                "{X}",
            ],
            ("reproduce", "out") => &["reproduce", "--out", "{X}"],
            ("contrast", "out") => &[
                "contrast",
                "--target",
                "{m}",
                "--background",
                "paint",
                "--sun-zenith-deg",
                "30",
                "--out",
                "{X}",
            ],
            ("detect", "out") => &[
                "detect", "--scene", "{s}", "--sensor", "{m}", "--out", "{X}",
            ],
            ("albedo", "output") => &["albedo", "--material", "{m}", "--output", "{X}"],
            ("emission", "output") => &["emission", "--material", "{m}", "--output", "{X}"],
            ("radiance", "output") => &[
                "radiance",
                "--material",
                "{m}",
                "--scene",
                "{s}",
                "--output",
                "{X}",
            ],
            ("map", "out") => &[
                "map",
                "--material",
                "{m}",
                "--sun-zenith-deg",
                "30",
                "--out",
                "{X}",
            ],
            ("spectrum", "out") => &["spectrum", "--material", "{m}", "--out", "{X}"],
            ("lut", "out") => &["lut", "--config", "{m}", "--out", "{X}"],
            ("export", "output") => &["export", "--material", "{m}", "--output", "{X}"],
            ("check", "output") => &["check", "--material", "{m}", "--output", "{X}"],
            ("daytime", "out") => &["daytime", "--scene", "{s}", "--out", "{X}"],
            _ => return None,
        };
        Some(v.to_vec())
    }

    /// Every output option, pointed at an input file, is refused before anything is written,
    /// and the input is left as it was.
    #[test]
    fn every_output_option_refuses_to_replace_an_input() {
        let dir = tempfile::tempdir().unwrap();
        let m = dir.path().join("m.toml");
        let material = polbrdf_io::material_to_toml(&polbrdf::preset("paint").unwrap());
        let files = [
            ("{m}", m.clone(), material.clone()),
            ("{g}", dir.path().join("g.csv"), "theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg\n30,0,30,180\n".into()),
            ("{f}", dir.path().join("f.csv"), "theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg,brdf,wavelength_um\n30,0,30,180,1,0.5\n".into()),
            ("{s}", dir.path().join("s.toml"), "wavelength_um = 10\n[surface]\ntemperature_k = 300\n".into()),
        ];
        for (_, path, text) in &files {
            std::fs::write(path, text).unwrap();
        }
        for (command, id, role) in PATH_OPTIONS {
            if *role == Role::Input {
                continue;
            }
            let Some(args) = template(command, id) else {
                panic!(
                    "no test command line for `polbrdf {command} --{id}`: add one to template()"
                );
            };
            let args: Vec<String> = std::iter::once("polbrdf")
                .chain(args)
                .map(|a| {
                    let a = a.replace("{X}", "{m}");
                    files
                        .iter()
                        .find(|(k, ..)| *k == a)
                        .map_or(a.clone(), |(_, p, _)| p.display().to_string())
                })
                .collect();
            let matches = Cli::command().try_get_matches_from(&args).unwrap();
            let cli = Cli::from_arg_matches(&matches).unwrap();
            let e = checked_run(&matches, cli).expect_err(&args.join(" "));
            let text = e.to_string();
            assert!(
                text.contains("same file as the input") || text.contains("not a directory"),
                "{}: {text}",
                args.join(" ")
            );
            assert_eq!(
                std::fs::read_to_string(&m).unwrap(),
                material,
                "{}",
                args.join(" ")
            );
            assert!(Path::new(&m).is_file());
        }
    }
}
