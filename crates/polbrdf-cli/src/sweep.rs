//! `polbrdf spectrum`: BRDF, DoLP and AoLP of one or more materials at one geometry over a range
//! of wavelengths — one engine call per material, the spectral index looked up per element
//! inside the engine (docs/model.md §15). Writes spectrum.csv and a figure of the DoLP against
//! wavelength (logarithmic axis).

use crate::error::CliError;
use crate::output::{write_all, OutputFile as Output};
use crate::spectrum::load_spec;
use crate::values::{self, Pair, Quad, Range};
use polbrdf::engine::Engine;
use polbrdf::{Geometry, MaterialSpec};
use polbrdf_io::CsvTable;
use polbrdf_plot::{render_files, Figure, LegendAt, Line, Panel, Render, PALETTE};
use std::path::PathBuf;

/// `polbrdf spectrum`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// A material: a TOML file (with `index = …` for a spectral index) or a preset name.
    /// Repeat for several; each is one line of the figure.
    #[arg(long, value_name = "FILE.toml|PRESET", required = true)]
    pub material: Vec<String>,
    /// Specular geometry at this angle: θi = θr = ANGLE, φi = 0°, φr = 180°.
    #[arg(
        long,
        value_name = "DEG",
        conflicts_with = "geometry_deg",
        default_value_t = 45.0,
        value_parser = values::zenith()
    )]
    pub theta_deg: f64,
    /// Any geometry instead: θi,φi,θr,φr in degrees.
    #[arg(long, value_name = "TI,PI,TR,PR", allow_hyphen_values = true,
          value_parser = values::quad([Range::ZENITH, Range::AZIMUTH, Range::ZENITH, Range::AZIMUTH],
                                      "TI,PI,TR,PR in degrees"))]
    pub geometry_deg: Option<Quad>,
    /// Wavelength range in µm: λmin,λmax.
    #[arg(long, value_name = "MIN,MAX", default_value = "0.4,14",
          value_parser = values::pair(Range::POSITIVE, Range::POSITIVE, "MIN,MAX in µm"))]
    pub range_um: Pair,
    /// Number of wavelengths, spaced evenly in log λ over the range.
    #[arg(long, value_name = "N", default_value_t = 400,
          value_parser = values::count(2, crate::limits::SPECTRUM_POINTS))]
    pub points: usize,
    /// Output directory: spectrum.csv, spectrum.png, spectrum.svg.
    #[arg(long, value_name = "DIR", default_value = "spectrum-out")]
    pub out: PathBuf,
}

/// One material's spectrum.
struct Series {
    name: String,
    n: Vec<f64>,
    k: Vec<f64>,
    brdf: Vec<f64>,
    dolp: Vec<f64>,
    aolp: Vec<f64>,
}

/// The material at every wavelength through the engine: the spectral index's values as the
/// per-element index (a constant index: the material itself).
fn series(
    spec: &MaterialSpec,
    name: String,
    arg: &str,
    geometry: Geometry,
    wavelengths: &[f64],
) -> Result<Series, CliError> {
    let what = |e: polbrdf::Error| CliError::Invalid(format!("--material {arg}: {e}"));
    let (n, k) = spec.index_columns(wavelengths).map_err(|(_, e)| what(e))?;
    let material = spec.build_at(wavelengths[0]).map_err(what)?;
    let m = wavelengths.len();
    let (ti, pi, tr, pr) = (
        vec![geometry.theta_i(); m],
        vec![geometry.phi_i(); m],
        vec![geometry.theta_r(); m],
        vec![geometry.phi_r(); m],
    );
    let batch = polbrdf::GeometryBatch::new(&ti, &pi, &tr, &pr).map_err(what)?;
    let (mut brdf, mut dolp, mut aolp) = (vec![0.0; m], vec![0.0; m], vec![0.0; m]);
    Engine::new(&material)
        .with_wavelengths(wavelengths)
        .map_err(what)?
        .brdf_dolp_aolp_into(&batch, &mut brdf, &mut dolp, &mut aolp)
        .map_err(what)?;
    Ok(Series {
        name,
        n,
        k,
        brdf,
        dolp,
        aolp: aolp.iter().map(|a| a.to_degrees()).collect(),
    })
}

/// The wavelengths of `--range-um` and `--points`: evenly spaced in log λ, the last one
/// exactly λmax.
fn wavelengths(args: &Args) -> Result<Vec<f64>, CliError> {
    let Pair(lo, hi) = args.range_um;
    if hi <= lo {
        return Err(CliError::Usage(format!(
            "--range-um = {lo},{hi}: need 0 < λmin < λmax (µm)"
        )));
    }
    let step = (hi / lo).ln() / (args.points - 1) as f64;
    Ok((0..args.points)
        .map(|i| {
            if i + 1 == args.points {
                hi
            } else {
                lo * (step * i as f64).exp()
            }
        })
        .collect())
}

/// The geometry of `--geometry-deg`, else the specular one at `--theta-deg`.
fn geometry(args: &Args) -> Result<Geometry, CliError> {
    match &args.geometry_deg {
        Some(Quad([ti, pi, tr, pr])) => Geometry::from_degrees(*ti, *pi, *tr, *pr),
        None => Geometry::from_degrees(args.theta_deg, 0.0, args.theta_deg, 180.0),
    }
    // The options' ranges hold the angles above the horizon already.
    .map_err(|e| CliError::Usage(format!("--geometry-deg: {e}")))
}

/// spectrum.csv: one row per material and wavelength (full f64 precision).
fn table(all: &[Series], wavelengths: &[f64]) -> Vec<u8> {
    let mut table = CsvTable::new([
        "wavelength_um",
        "material",
        "n",
        "k",
        "brdf",
        "dolp",
        "aolp_deg",
    ]);
    for s in all {
        for (i, l) in wavelengths.iter().enumerate() {
            table.fields([
                format!("{l:?}"),
                s.name.clone(),
                format!("{:?}", s.n[i]),
                format!("{:?}", s.k[i]),
                format!("{:?}", s.brdf[i]),
                format!("{:?}", s.dolp[i]),
                format!("{:?}", s.aolp[i]),
            ]);
        }
    }
    table.into_bytes()
}

/// The geometry in words, for the caption and the summary.
fn describe_geometry(geometry: Geometry) -> String {
    let deg = |x: f64| x.to_degrees();
    format!(
        "θi = {}°, φi = {}°, θr = {}°, φr = {}°",
        round(deg(geometry.theta_i())),
        round(deg(geometry.phi_i())),
        round(deg(geometry.theta_r())),
        round(deg(geometry.phi_r()))
    )
}

/// The figure: the DoLP of each material against wavelength (logarithmic axis).
fn figure(all: &[Series], wavelengths: &[f64], geo: &str, (lo, hi): (f64, f64)) -> Figure {
    let top = all
        .iter()
        .flat_map(|s| s.dolp.iter().copied())
        .fold(0.0, f64::max);
    Figure {
        size: (1100, 650),
        panels: vec![Panel {
            title: format!("DoLP of the reflected light, unpolarized illumination ({geo})"),
            x_desc: "wavelength λ (µm)".into(),
            y_desc: "DoLP".into(),
            x_range: (lo, hi),
            y_range: (0.0, (1.1 * top).clamp(0.05, 1.0)),
            log_y: false,
            log_x: true,
            x_ticks: 12,
            y_ticks: 8,
            lines: all
                .iter()
                .enumerate()
                .map(|(j, s)| Line {
                    label: s.name.clone(),
                    points: wavelengths
                        .iter()
                        .copied()
                        .zip(s.dolp.iter().copied())
                        .collect(),
                    color: PALETTE[j % PALETTE.len()],
                    dashed: false,
                    width: 3,
                })
                .collect(),
            markers: Vec::new(),
            vlines: Vec::new(),
            legend: LegendAt::MiddleRight,
        }],
    }
}

/// The summary on standard error: the setting, each material's DoLP range, the files.
fn summary(args: &Args, all: &[Series], wavelengths: &[f64], geo: &str, files: usize) {
    let Pair(lo, hi) = args.range_um;
    crate::note!(
        "polbrdf spectrum: {} material(s) at {geo}, {} wavelengths {lo}–{hi} µm (log-spaced)",
        all.len(),
        args.points
    );
    for s in all {
        let (i, max) =
            s.dolp
                .iter()
                .copied()
                .enumerate()
                .fold(
                    (0, f64::NEG_INFINITY),
                    |a, (i, d)| if d > a.1 { (i, d) } else { a },
                );
        crate::note!(
            "  {:<24} DoLP {:.4} … {:.4} (largest at λ = {:.4} µm)",
            s.name,
            s.dolp.iter().copied().fold(f64::INFINITY, f64::min),
            max,
            wavelengths[i]
        );
    }
    crate::note!("Wrote {files} files to {}", args.out.display());
}

/// Runs `polbrdf spectrum`: the options checked, each material through the engine, the table
/// and the figure written, the summary.
pub fn run(args: &Args) -> Result<(), CliError> {
    let wavelengths = wavelengths(args)?;
    let geometry = geometry(args)?;
    let mut all = Vec::new();
    for arg in &args.material {
        let (spec, name) = load_spec(arg, "--material")?;
        all.push(series(&spec, name, arg, geometry, &wavelengths)?);
    }
    let geo = describe_geometry(geometry);
    let Pair(lo, hi) = args.range_um;
    let mut files: Vec<Output> = vec![("spectrum.csv".into(), table(&all, &wavelengths))];
    files.extend(
        render_files(&[(
            "spectrum",
            &figure(&all, &wavelengths, &geo, (lo, hi)) as &dyn Render,
        )])
        .map_err(|(_, e)| CliError::Plot(e))?,
    );
    let written = write_all(&args.out, &files)?;
    summary(args, &all, &wavelengths, &geo, written.len());
    Ok(())
}

/// A value for a caption: integers without decimals, else two.
fn round(x: f64) -> String {
    if (x - x.round()).abs() < 1e-9 {
        format!("{}", x.round())
    } else {
        format!("{x:.2}")
    }
}
