//! `polbrdf check`: is a parameter set physically valid everywhere?

use crate::error::CliError;
use crate::spectrum::SpectralArgs;
use polbrdf_tasks::check::{check, CheckRequest};
use polbrdf_tasks::spectrum::describe;
use std::path::Path;

/// Runs `polbrdf check`; exit code 6 when a check fails. Over a band, every check runs at each
/// of the band's spectral nodes and the worst one is reported; `--output` holds them all.
pub fn run(
    material: &str,
    grid_deg: f64,
    output: Option<&Path>,
    spectral: &SpectralArgs,
) -> Result<(), CliError> {
    let request = CheckRequest {
        material: material.to_string(),
        grid_deg,
        spectral: spectral.request(),
    };
    let outcome = check(&request)?;
    if let Some(path) = output {
        let json = serde_json::to_string_pretty(&outcome.to_json()).expect("JSON of finite values");
        polbrdf_io::write_atomic(path, (json + "\n").as_bytes())?;
    }
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
    crate::note!(
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
    crate::note!(
        "  {} realizable: smallest coherency eigenvalue / F00 = {:.3e} (at {}{})",
        mark(r.realizable()),
        r.min_coherency.0,
        deg(&r.min_coherency.1),
        at(*l_real)
    );
    let r = r_energy;
    let top = r.max_albedo();
    crate::note!(
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
        crate::note!(
            "         albedo {:.6} > 1 at θi = {:.0}° (surface {:.6}, volume {:.6})",
            a.total(),
            a.theta_i.to_degrees(),
            a.surface,
            a.volume
        );
    }
    let r = r_recip;
    if r.reciprocity_expected {
        crate::note!(
            "  {} reciprocity: largest deviation {:.3e} (scalar) / {:.3e} (F vs P·Fᵀ·P) at {}{}",
            mark(r.reciprocal()),
            r.reciprocity.0,
            r.reciprocity.1,
            deg(&r.reciprocity.2),
            at(*l_recip)
        );
    } else {
        crate::note!(
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
