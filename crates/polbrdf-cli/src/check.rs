//! `polbrdf check`: is a parameter set physically valid everywhere?

use crate::error::CliError;
use polbrdf::{physical_validity, CheckGrid};

/// Runs `polbrdf check`; exit code 6 when a check fails.
pub fn run(material: &str, grid_deg: f64) -> Result<(), CliError> {
    let spec = polbrdf_io::load_material(material)?;
    let m = spec.build()?;
    if !(grid_deg.is_finite() && grid_deg > 0.0 && grid_deg <= 30.0) {
        return Err(CliError::Invalid(format!(
            "--grid-deg = {grid_deg}: must lie in (0, 30]"
        )));
    }
    let grid = CheckGrid {
        zenith_step: grid_deg.to_radians(),
        azimuth_step: (2.0 * grid_deg).to_radians(),
    };
    let r = physical_validity(&m, &grid);
    let mark = |ok: bool| if ok { "ok  " } else { "FAIL" };
    let deg = |g: &polbrdf::Geometry| {
        format!(
            "θi = {:.1}°, θr = {:.1}°, φr − φi = {:.1}°",
            g.theta_i().to_degrees(),
            g.theta_r().to_degrees(),
            (g.phi_r() - g.phi_i()).to_degrees()
        )
    };
    println!(
        "polbrdf check: {} over {} geometries (zenith step {grid_deg}°, azimuth step {}°)\n",
        m.name().unwrap_or(material),
        r.geometries,
        2.0 * grid_deg
    );
    println!(
        "  {} realizable: smallest coherency eigenvalue / F00 = {:.3e} (at {})",
        mark(r.realizable()),
        r.min_coherency.0,
        deg(&r.min_coherency.1)
    );
    let top = r.max_albedo();
    println!(
        "  {} energy: largest directional–hemispherical reflectance {:.6} at θi = {:.0}°",
        mark(r.conserves_energy()),
        top.total(),
        top.theta_i.to_degrees()
    );
    for a in r
        .albedo
        .iter()
        .filter(|a| a.violates_energy_conservation(0.0))
    {
        println!(
            "         albedo {:.6} > 1 at θi = {:.0}° (surface {:.6}, volume {:.6})",
            a.total(),
            a.theta_i.to_degrees(),
            a.surface,
            a.volume
        );
    }
    if r.reciprocity_expected {
        println!(
            "  {} reciprocity: largest deviation {:.3e} (scalar) / {:.3e} (F vs P·Fᵀ·P) at {}",
            mark(r.reciprocal()),
            r.reciprocity.0,
            r.reciprocity.1,
            deg(&r.reciprocity.2)
        );
    } else {
        println!(
            "  --   reciprocity: not expected (azimuth_term = \"eq3\" is not reciprocal); largest deviation {:.3e}",
            r.reciprocity.0.max(r.reciprocity.1)
        );
    }
    if r.passes() {
        Ok(())
    } else {
        Err(CliError::CheckFailed)
    }
}
