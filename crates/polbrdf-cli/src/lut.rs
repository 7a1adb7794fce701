//! `polbrdf lut --config FILE --out DIR`: a lookup table over materials × wavelengths ×
//! in-plane geometries, written by the task layer (`polbrdf_tasks::lut`, docs/scaling.md) as
//! `DIR/table.npy` plus `DIR/attrs.json` — the table of the Python `polbrdf.lut`, for users
//! without Python; `polbrdf.xarray.open_lut(DIR)` opens it as the same `xarray.Dataset`.

use crate::error::CliError;
use std::path::Path;

/// Runs `polbrdf lut --config FILE --out DIR`.
pub fn run(config: &Path, out: &Path) -> Result<(), CliError> {
    let cfg = polbrdf_io::lut::read_lut_config(config)?;
    let bar = crate::progress::Progress::new(cfg.rows(), "lut: rows");
    Ok(polbrdf_tasks::lut::write_lut_with_progress(
        &cfg,
        out,
        &mut |done, total| bar.set(done, total, None),
    )?)
}
