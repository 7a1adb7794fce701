//! `polbrdf lut --config FILE --out DIR`: a lookup table over materials × wavelengths ×
//! in-plane geometries, written by the task layer (`polbrdf_tasks::lut`, docs/scaling.md) as
//! `DIR/table.npy` plus `DIR/attrs.json` — the table of the Python `polbrdf.lut`, for users
//! without Python; `polbrdf.xarray.open_lut(DIR)` opens it as the same `xarray.Dataset`.

use crate::error::CliError;
use std::path::Path;

/// Runs `polbrdf lut --config FILE --out DIR`; its summary goes to standard error.
pub fn run(config: &Path, out: &Path) -> Result<(), CliError> {
    let cfg = polbrdf_io::lut::read_lut_config(config)?;
    let bar = crate::progress::Progress::new(cfg.rows(), "lut: rows");
    polbrdf_tasks::lut::write_lut_with_progress(&cfg, out, &mut |done, total| {
        bar.set(done, total, None)
    })?;
    drop(bar);
    let dims = [
        cfg.materials.len(),
        cfg.wavelength_um.len(),
        cfg.theta_i_deg.len(),
        cfg.theta_r_deg.len(),
        cfg.dphi_deg.len(),
    ];
    crate::note!(
        "polbrdf lut: {} rows (materials × wavelengths × θi × θr × Δφ = {}) × {} columns into \
         {} (table.npy, attrs.json)",
        cfg.rows(),
        dims.map(|n| n.to_string()).join(" × "),
        polbrdf_tasks::lut::columns(&cfg.quantities).len(),
        out.display()
    );
    Ok(())
}
