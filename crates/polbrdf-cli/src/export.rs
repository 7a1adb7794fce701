//! `polbrdf export`: a material as a Mitsuba 3 `measured_polarized` table (`.pbsdf`,
//! docs/model.md §20), which the stock plugin renders. The table is computed and written by
//! the task layer (`polbrdf_tasks::pbsdf::export`); this module parses the options.

use crate::error::CliError;
use polbrdf_tasks::pbsdf::{ExportRequest, MAX_EXPORT_BYTES};
use std::path::PathBuf;

/// The task layer's default bands ([`polbrdf_tasks::pbsdf::DEFAULT_BANDS_NM`]) as the option's
/// text (a unit test holds them equal).
pub const DEFAULT_BANDS: &str = "450,500,550,600,650";
/// The task layer's default grid ([`polbrdf_tasks::pbsdf::DEFAULT_GRID`]) as the option's text.
pub const DEFAULT_GRID: &str = "37,46,91";

/// `polbrdf export` arguments.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The material: a TOML file or a preset name.
    #[arg(long, value_name = "FILE.toml|PRESET")]
    pub material: String,
    /// The .pbsdf file to write (atomically; `-` for standard output).
    #[arg(long, value_name = "model.pbsdf")]
    pub output: PathBuf,
    /// The old spelling of --output, refused with the new name: `--out` names a directory in
    /// every command (docs/cli-conventions.md).
    #[arg(long = "out", hide = true, value_name = "FILE", value_parser = renamed)]
    pub old_out: Option<String>,
    /// Band wavelengths in nm (integers, increasing: the table's `wvls` field is in nm, unlike
    /// every other wavelength option, which is in µm). Mitsuba's plugin reads exactly five.
    #[arg(long, value_name = "NM,...", default_value = DEFAULT_BANDS, value_delimiter = ',',
          value_parser = band_nm)]
    pub bands_nm: Vec<u16>,
    /// Grid nodes along φ_d ∈ [−180°, 180°], θ_d ∈ [0°, 90°], θ_h ∈ [0°, 90°] (uniform, each
    /// 2–4096; the table at most 4 GiB: the KAIST files are 361,91,91 — about 1 GB).
    #[arg(long, value_name = "P,D,H", default_value = DEFAULT_GRID, value_parser = grid)]
    pub grid: [usize; 3],
}

/// `--out`: renamed to `--output` (a usage error naming the new option).
fn renamed(_: &str) -> Result<String, String> {
    Err(
        "`export --out` is now `--output FILE` (in every command `--out` names a directory \
         and `--output` a file)"
            .into(),
    )
}

/// One band of `--bands-nm`: a wavelength in whole nanometres, 1–65535.
fn band_nm(text: &str) -> Result<u16, String> {
    text.trim()
        .parse::<u16>()
        .ok()
        .filter(|&x| x > 0)
        .ok_or_else(|| format!("`{text}` is not a wavelength in nm (integer 1–65535)"))
}

/// `--grid`: three node counts, each in [`polbrdf_tasks::pbsdf::GRID_NODES`].
fn grid(text: &str) -> Result<[usize; 3], String> {
    let bad = || "three node counts P,D,H, each 2–4096, are required".to_string();
    let v: Vec<usize> = text
        .split(',')
        .map(|t| t.trim().parse::<usize>().ok())
        .collect::<Option<_>>()
        .ok_or_else(bad)?;
    let g: [usize; 3] = v.try_into().map_err(|_| bad())?;
    if g.iter()
        .all(|n| polbrdf_tasks::pbsdf::GRID_NODES.contains(n))
    {
        Ok(g)
    } else {
        Err(bad())
    }
}

/// Runs `polbrdf export`: every option validated (the table's size against its bound) before
/// the material is loaded; a refused option is a usage error (exit code 2).
pub fn run(args: &Args) -> Result<(), CliError> {
    let req = ExportRequest {
        bands_nm: args.bands_nm.clone(),
        grid: args.grid,
    };
    let [p, d, h] = req.grid;
    if req.matrix_bytes() > MAX_EXPORT_BYTES {
        return Err(CliError::Usage(format!(
            "--grid {p},{d},{h}: {:.1} GB of table ({} bands); at most {MAX_EXPORT_BYTES} bytes \
             (4 GiB) are written (the limit of this option; see docs/reliability.md)",
            req.matrix_bytes() as f64 / 1e9,
            req.bands_nm.len()
        )));
    }
    // The request holds options only (the bands' order and count): a refusal is a usage error.
    req.validate().map_err(CliError::usage)?;
    let spec = crate::output::load_material(&args.material)?;
    let bar = crate::progress::Progress::new(p as u64, "export: φ_d slabs");
    let bytes = polbrdf_tasks::pbsdf::export_with_progress(
        &spec,
        &req,
        &args.output,
        &mut |done, total| {
            bar.set(done as u64, total as u64, None);
        },
    )?;
    drop(bar);
    crate::note!(
        "polbrdf export: {} ({p}×{d}×{h} cells × {} bands, {:.1} MB)",
        args.output.display(),
        req.bands_nm.len(),
        bytes as f64 / 1e6
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_defaults_are_the_task_layers() {
        let bands: Vec<u16> = DEFAULT_BANDS
            .split(',')
            .map(|b| band_nm(b).unwrap())
            .collect();
        assert_eq!(bands, polbrdf_tasks::pbsdf::DEFAULT_BANDS_NM);
        assert_eq!(
            grid(DEFAULT_GRID).unwrap(),
            polbrdf_tasks::pbsdf::DEFAULT_GRID
        );
        assert!(grid("1,46,91").is_err() && band_nm("0").is_err());
    }
}
