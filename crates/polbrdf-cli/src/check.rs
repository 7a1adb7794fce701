//! `polbrdf check`: is a parameter set physically valid everywhere?

use crate::error::CliError;
use crate::spectrum::SpectralArgs;
use polbrdf_tasks::check::{check, CheckRequest};
use polbrdf_tasks::spectrum::describe;

/// Runs `polbrdf check`; exit code 6 when a check fails. Over a band, every check runs at each
/// of the band's spectral nodes and the worst one is reported.
pub fn run(material: &str, grid_deg: f64, spectral: &SpectralArgs) -> Result<(), CliError> {
    let request = CheckRequest {
        material: material.to_string(),
        grid_deg,
        spectral: spectral.request(),
    };
    // The grid's size (physical_validity's loops), bounded before it is allocated.
    let max = crate::limits::CHECK_GEOMETRIES;
    if grid_deg.is_finite() && grid_deg > 0.0 && request.geometries().is_none_or(|n| n > max) {
        return Err(CliError::Usage(format!(
            "--grid-deg = {grid_deg:e}: the grid would have more than {max} geometries (the \
             limit of this option, about 1 GB; see docs/reliability.md): give a \
             step of at least 0.9°"
        )));
    }
    let outcome = check(&request)?;
    let reports = &outcome.reports;
    let (l_real, r_real) = outcome.worst_realizability();
    let (l_energy, r_energy) = outcome.worst_energy();
    let (l_recip, r_recip) = outcome.worst_reciprocity();
    let at = |l: Option<f64>| l.map(|l| format!(" at λ = {l:.4} µm")).unwrap_or_default();
    let r = r_real;
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
        "polbrdf check: {}{} over {} geometries (zenith step {grid_deg}°, azimuth step {}°){}\n",
        outcome.name,
        describe(outcome.spectrum.as_ref()),
        r.geometries,
        2.0 * grid_deg,
        if reports.len() > 1 {
            format!(
                ", at {} wavelengths of the band (the worst shown)",
                reports.len()
            )
        } else {
            String::new()
        }
    );
    println!(
        "  {} realizable: smallest coherency eigenvalue / F00 = {:.3e} (at {}{})",
        mark(r.realizable()),
        r.min_coherency.0,
        deg(&r.min_coherency.1),
        at(*l_real)
    );
    let r = r_energy;
    let top = r.max_albedo();
    println!(
        "  {} energy: largest directional–hemispherical reflectance {:.6} at θi = {:.0}°{}",
        mark(r.conserves_energy()),
        top.total(),
        top.theta_i.to_degrees(),
        at(*l_energy)
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
    let r = r_recip;
    if r.reciprocity_expected {
        println!(
            "  {} reciprocity: largest deviation {:.3e} (scalar) / {:.3e} (F vs P·Fᵀ·P) at {}{}",
            mark(r.reciprocal()),
            r.reciprocity.0,
            r.reciprocity.1,
            deg(&r.reciprocity.2),
            at(*l_recip)
        );
    } else {
        println!(
            "  --   reciprocity: not expected (azimuth_term = \"eq3\" is not reciprocal); largest deviation {:.3e}",
            r.reciprocity.0.max(r.reciprocity.1)
        );
    }
    if outcome.passes() {
        Ok(())
    } else {
        Err(CliError::CheckFailed)
    }
}
