//! `polbrdf export`: a material as a Mitsuba 3 `measured_polarized` table (`.pbsdf`,
//! docs/model.md §20), which the stock plugin renders.

use crate::error::CliError;
use polbrdf::geometry::rusinkiewicz::{cell_geometry, to_reflection_frame};
use polbrdf::{Engine, GeometryBatch, Material, Mueller};
use std::path::PathBuf;

/// The KAIST wavelengths (nm), the only band count the stock plugin reads.
pub const DEFAULT_BANDS: &str = "450,500,550,600,650";
/// The default grid: φ_d 10°, θ_d 2°, θ_h 1° (about 50 MB).
pub const DEFAULT_GRID: &str = "37,46,91";

/// `polbrdf export` arguments.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The material: a TOML file or a preset name.
    #[arg(long, value_name = "FILE.toml|PRESET")]
    pub material: String,
    /// The .pbsdf file to write (atomically).
    #[arg(long, value_name = "model.pbsdf")]
    pub out: PathBuf,
    /// Band wavelengths in nm (integers, increasing). Mitsuba's plugin reads exactly five.
    #[arg(long, value_name = "NM,...", default_value = DEFAULT_BANDS)]
    pub bands: String,
    /// Grid nodes along φ_d ∈ [−180°, 180°], θ_d ∈ [0°, 90°], θ_h ∈ [0°, 90°] (uniform; the
    /// KAIST files are 361,91,91 — about 1 GB).
    #[arg(long, value_name = "P,D,H", default_value = DEFAULT_GRID)]
    pub grid: String,
}

/// Parses `--bands`.
pub fn parse_bands(s: &str) -> Result<Vec<u16>, CliError> {
    let bad = |m: String| CliError::Invalid(format!("--bands `{s}`: {m}"));
    let v = s
        .split(',')
        .map(|t| {
            t.trim()
                .parse::<u16>()
                .ok()
                .filter(|&x| x > 0)
                .ok_or_else(|| bad(format!("`{t}` is not a wavelength in nm (integer 1–65535)")))
        })
        .collect::<Result<Vec<_>, _>>()?;
    if v.windows(2).any(|w| w[1] <= w[0]) {
        return Err(bad("the wavelengths must increase".into()));
    }
    if v.len() != 5 {
        return Err(bad(format!(
            "{} band(s): Mitsuba's measured_polarized plugin reads exactly five wavelengths",
            v.len()
        )));
    }
    Ok(v)
}

/// Parses `--grid`.
pub fn parse_grid(s: &str) -> Result<[usize; 3], CliError> {
    let bad = || {
        CliError::Invalid(format!(
            "--grid `{s}`: three node counts P,D,H, each 2–4096, are required"
        ))
    };
    let v: Vec<usize> = s
        .split(',')
        .map(|t| {
            t.trim()
                .parse::<usize>()
                .ok()
                .filter(|n| (2..=4096).contains(n))
        })
        .collect::<Option<_>>()
        .ok_or_else(bad)?;
    v.try_into().map_err(|_| bad())
}

/// `n` uniform nodes from `a` to `b`.
pub fn linspace(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| a + (b - a) * i as f64 / (n - 1) as f64)
        .collect()
}

/// The slab of φ_d node `phi_d` (C order `[theta_d, theta_h, band, 4, 4]`, float32): every cell
/// of the slab in one batch call per band, rotated to the plane-of-reflection frame; zero
/// below the horizon.
pub fn slab(
    materials: &[Material],
    phi_d: f64,
    theta_d: &[f64],
    theta_h: &[f64],
) -> Result<Vec<f32>, CliError> {
    let mut geoms = Vec::with_capacity(theta_d.len() * theta_h.len());
    for &td in theta_d {
        for &th in theta_h {
            geoms.push(cell_geometry(phi_d, td, th).map_err(CliError::Model)?);
        }
    }
    let cols: [Vec<f64>; 4] = [
        geoms.iter().map(|g| g.theta_i()).collect(),
        geoms.iter().map(|g| g.phi_i()).collect(),
        geoms.iter().map(|g| g.theta_r()).collect(),
        geoms.iter().map(|g| g.phi_r()).collect(),
    ];
    let batch =
        GeometryBatch::new(&cols[0], &cols[1], &cols[2], &cols[3]).map_err(CliError::Model)?;
    let vars: Vec<_> = geoms.iter().map(|g| g.angle_variables()).collect();
    let nb = materials.len();
    let mut out = vec![0f32; geoms.len() * nb * 16];
    for (b, m) in materials.iter().enumerate() {
        let f = Engine::new(m).mueller(&batch).map_err(CliError::Model)?;
        for (c, (fc, v)) in f.iter().zip(&vars).enumerate() {
            let Some(v) = v else { continue };
            let t = to_reflection_frame(&Mueller::from_row_major(fc), v).to_row_major();
            let at = (c * nb + b) * 16;
            for (o, x) in out[at..at + 16].iter_mut().zip(t) {
                *o = x as f32;
            }
        }
    }
    Ok(out)
}

/// Runs `polbrdf export`.
pub fn run(args: &Args) -> Result<(), CliError> {
    let spec = polbrdf_io::load_material(&args.material)?;
    let bands = parse_bands(&args.bands)?;
    let [p, d, h] = parse_grid(&args.grid)?;
    let materials = bands
        .iter()
        .map(|&nm| spec.build_at(f64::from(nm) / 1000.0))
        .collect::<Result<Vec<_>, _>>()
        .map_err(CliError::Model)?;
    // The nodes as stored (float32), so that each cell holds the model at the node the plugin
    // and the reader see, not at a point 1e-8 rad away (which matters next to the horizon).
    let pi = std::f64::consts::PI;
    let stored = |v: Vec<f64>| -> Vec<f64> { v.into_iter().map(|x| f64::from(x as f32)).collect() };
    let phi_d = stored(linspace(-pi, pi, p));
    let theta_d = stored(linspace(0.0, pi / 2.0, d));
    let theta_h = stored(linspace(0.0, pi / 2.0, h));
    polbrdf_io::write_pbsdf(&args.out, &phi_d, &theta_d, &theta_h, &bands, |k| {
        slab(&materials, phi_d[k], &theta_d, &theta_h)
    })?;
    eprintln!(
        "polbrdf export: {} ({p}×{d}×{h} cells × {} bands, {:.1} MB)",
        args.out.display(),
        bands.len(),
        (p * d * h * bands.len() * 64) as f64 / 1e6
    );
    Ok(())
}
