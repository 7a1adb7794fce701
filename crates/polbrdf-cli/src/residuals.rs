//! The residual figure of a fit: normalized residuals `(model − data)/σ`, written as PNG or SVG
//! (by the file's extension) through the output layer.

use crate::error::CliError;
use polbrdf_fit::{FitResult, Measurement, Observable};
use std::path::Path;

/// Draws the residuals of `r` on `data` and writes them to `path` (`.svg`: SVG; else PNG).
pub fn write_plot(path: &Path, r: &FitResult, data: &[Measurement]) -> Result<(), CliError> {
    let fig = residual_figure(r, data);
    let bytes = match path.extension().and_then(|e| e.to_str()) {
        Some("svg") => fig.svg().map_err(CliError::Plot)?.into_bytes(),
        _ => fig.png().map_err(CliError::Plot)?,
    };
    Ok(polbrdf_io::write_atomic(path, &bytes)?)
}

/// Normalized residuals `(model − data)/σ` against the measurement number, one panel per kind of
/// measurement (BRDF, DoLP, s/p BRDF, Mueller entries), with ±1σ and ±2σ guides.
fn residual_figure(r: &FitResult, data: &[Measurement]) -> polbrdf_plot::Figure {
    use polbrdf_plot::{Figure, LegendAt, Line, Marker, Markers, Panel, PALETTE};
    let kind = |o: &Observable| match o {
        Observable::Brdf => "BRDF",
        Observable::Dolp => "DoLP",
        Observable::BrdfS | Observable::BrdfP => "s/p BRDF",
        Observable::Mueller(..) => "Mueller entries",
    };
    let mut kinds: Vec<&str> = Vec::new();
    for d in data {
        if !kinds.contains(&kind(&d.observable)) {
            kinds.push(kind(&d.observable));
        }
    }
    let n = data.len() as f64;
    let panels = kinds
        .iter()
        .map(|k| {
            let points: Vec<(f64, f64)> = r
                .residuals
                .iter()
                .filter(|res| kind(&data[res.index].observable) == *k)
                .map(|res| (res.index as f64 + 1.0, (res.model - res.data) / res.sigma))
                .collect();
            let rms = (points.iter().map(|p| p.1 * p.1).sum::<f64>() / points.len() as f64).sqrt();
            let top = points
                .iter()
                .map(|p| p.1.abs())
                .fold(3.0f64, f64::max)
                .ceil();
            let guide = |y: f64, label: &str| Line {
                label: label.to_string(),
                points: vec![(0.0, y), (n + 1.0, y)],
                color: if y == 0.0 { PALETTE[7] } else { PALETTE[3] },
                dashed: y != 0.0,
                width: 1,
            };
            Panel {
                title: format!("{k}: {} values, RMS {rms:.2}σ", points.len()),
                x_desc: "measurement number (file order)".into(),
                y_desc: "(model − data) / σ".into(),
                x_range: (0.0, n + 1.0),
                y_range: (-top, top),
                log_y: false,
                log_x: false,
                x_ticks: 8,
                y_ticks: 9,
                lines: vec![
                    guide(0.0, ""),
                    guide(1.0, "±1σ, ±2σ"),
                    guide(-1.0, ""),
                    guide(2.0, ""),
                    guide(-2.0, ""),
                ],
                markers: vec![Markers {
                    label: "residual".into(),
                    colors: vec![PALETTE[0]; points.len()],
                    points,
                    legend_color: PALETTE[0],
                    marker: Marker::Disc,
                }],
                vlines: vec![],
                legend: LegendAt::UpperRight,
            }
        })
        .collect::<Vec<_>>();
    Figure {
        size: (620 * panels.len() as u32, 480),
        panels,
    }
}
