//! The residual figure of a fit: per kind of measurement, the fitted model against the data,
//! then the normalized residuals `(model − data)/σ`; written as PNG or SVG (by the file's
//! extension) through the output layer.

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

/// Per kind of measurement (BRDF, DoLP, s/p BRDF, Mueller entries), two panels: the model and
/// the data against the measurement number ([`comparison_panel`]), and the normalized residuals
/// `(model − data)/σ` with ±1σ and ±2σ guides.
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
            let residuals = Panel {
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
            };
            [comparison_panel(r, data, k, &kind), residuals]
        })
        .collect::<Vec<_>>()
        .concat();
    Figure {
        size: (560 * panels.len() as u32, 480),
        panels,
    }
}

/// The fitted model (open squares) and the data (discs) of one kind of measurement against the
/// measurement number: where they part, the residual panel beside it says by how many σ. A
/// logarithmic axis when the values are positive and span more than two decades (a BRDF).
fn comparison_panel(
    r: &FitResult,
    data: &[Measurement],
    k: &str,
    kind: &dyn Fn(&Observable) -> &'static str,
) -> polbrdf_plot::Panel {
    use polbrdf_plot::{LegendAt, Marker, Markers, Panel, PALETTE};
    let of_kind: Vec<_> = r
        .residuals
        .iter()
        .filter(|res| kind(&data[res.index].observable) == k)
        .collect();
    let at = |f: &dyn Fn(f64, f64) -> f64| -> Vec<(f64, f64)> {
        of_kind
            .iter()
            .map(|res| (res.index as f64 + 1.0, f(res.model, res.data)))
            .collect()
    };
    let (model, measured) = (at(&|m, _| m), at(&|_, d| d));
    let all = || model.iter().chain(&measured).map(|p| p.1);
    let (lo, hi) = all().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
        (a.min(v), b.max(v))
    });
    let log_y = lo > 0.0 && hi / lo > 100.0;
    let y_range = if log_y {
        (lo / 1.5, hi * 1.5)
    } else {
        let pad = 0.05 * (hi - lo).max(hi.abs().max(1e-12) * 0.1);
        (lo - pad, hi + pad)
    };
    let n = data.len() as f64;
    let set = |label: &str, points: Vec<(f64, f64)>, c: usize, marker: Marker| Markers {
        label: label.into(),
        colors: vec![PALETTE[c]; points.len()],
        points,
        legend_color: PALETTE[c],
        marker,
    };
    Panel {
        title: format!("{k}: fitted model and data"),
        x_desc: "measurement number (file order)".into(),
        y_desc: if k == "DoLP" {
            k.into()
        } else {
            format!("{k} (sr⁻¹)")
        },
        x_range: (0.0, n + 1.0),
        y_range,
        log_y,
        log_x: false,
        x_ticks: 8,
        y_ticks: 9,
        lines: vec![],
        markers: vec![
            set("data", measured, 0, Marker::Disc),
            set("model", model, 1, Marker::Square),
        ],
        vlines: vec![],
        legend: LegendAt::UpperLeft,
    }
}
