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
    pub out: PathBuf,
    /// Band wavelengths in nm (integers, increasing: the table's `wvls` field is in nm, unlike
    /// every other wavelength option, which is in µm). Mitsuba's plugin reads exactly five.
    #[arg(long, value_name = "NM,...", default_value = DEFAULT_BANDS)]
    pub bands_nm: String,
    /// Grid nodes along φ_d ∈ [−180°, 180°], θ_d ∈ [0°, 90°], θ_h ∈ [0°, 90°] (uniform, each
    /// 2–4096; the table at most 4 GiB: the KAIST files are 361,91,91 — about 1 GB).
    #[arg(long, value_name = "P,D,H", default_value = DEFAULT_GRID)]
    pub grid: String,
}

/// Parses `--bands-nm`.
pub fn parse_bands(s: &str) -> Result<Vec<u16>, CliError> {
    s.split(',')
        .map(|t| {
            t.trim()
                .parse::<u16>()
                .ok()
                .filter(|&x| x > 0)
                .ok_or_else(|| {
                    CliError::Invalid(format!(
                        "--bands-nm `{s}`: `{t}` is not a wavelength in nm (integer 1–65535)"
                    ))
                })
        })
        .collect()
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
        .map(|t| t.trim().parse::<usize>().ok())
        .collect::<Option<_>>()
        .ok_or_else(bad)?;
    v.try_into().map_err(|_| bad())
}

/// Runs `polbrdf export`: every option validated (the table's size against its bound) before
/// the material is loaded.
pub fn run(args: &Args) -> Result<(), CliError> {
    let req = ExportRequest {
        bands_nm: parse_bands(&args.bands_nm)?,
        grid: parse_grid(&args.grid)?,
    };
    let [p, d, h] = req.grid;
    if req
        .grid
        .iter()
        .all(|n| polbrdf_tasks::pbsdf::GRID_NODES.contains(n))
        && req.matrix_bytes() > MAX_EXPORT_BYTES
    {
        return Err(CliError::Usage(format!(
            "--grid {p},{d},{h}: {:.1} GB of table ({} bands); at most {MAX_EXPORT_BYTES} bytes \
             (4 GiB) are written (the limit of this option; see docs/reliability.md)",
            req.matrix_bytes() as f64 / 1e9,
            req.bands_nm.len()
        )));
    }
    req.validate()?;
    let spec = crate::output::load_material(&args.material)?;
    let bar = crate::progress::Progress::new(p as u64, "export: φ_d slabs");
    let bytes =
        polbrdf_tasks::pbsdf::export_with_progress(&spec, &req, &args.out, &mut |done, total| {
            bar.set(done as u64, total as u64, None);
        })?;
    drop(bar);
    crate::note!(
        "polbrdf export: {} ({p}×{d}×{h} cells × {} bands, {:.1} MB)",
        args.out.display(),
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
        let bands = parse_bands(DEFAULT_BANDS).unwrap();
        assert_eq!(bands, polbrdf_tasks::pbsdf::DEFAULT_BANDS_NM);
        assert_eq!(
            parse_grid(DEFAULT_GRID).unwrap(),
            polbrdf_tasks::pbsdf::DEFAULT_GRID
        );
    }
}
