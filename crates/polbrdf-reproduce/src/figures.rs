//! The figures, as declarations for [`polbrdf_plot`].

use crate::analysis::Analysis;
use crate::params::*;
use polbrdf_plot::{Figure, LegendAt, Line, Marker, Markers, Panel, RGBColor, PALETTE};

const BLACK: RGBColor = RGBColor(0, 0, 0);
const GREY: RGBColor = RGBColor(90, 90, 90);

fn brewster_deg() -> f64 {
    N.atan().to_degrees()
}

fn roughness_label(r: f64) -> String {
    if r == 0.0 {
        "σ → 0 (smooth)".into()
    } else {
        format!("σ = {r:.1} rad ({:.1}°)", r.to_degrees())
    }
}

/// Makes curves that overlap distinguishable (issue 36: in Fig. 2(b) the shadowing curves of
/// θi ≥ 30° nearly coincide): the i-th of n curves is drawn `2 + (n − 1 − i)` px wide, widest
/// first, so a curve lying on another leaves a coloured rim of the one below; and each carries
/// markers (discs and squares in turn) at every `len/8`-th point, shifted by curve so that the
/// markers of coinciding curves sit side by side instead of on top of each other.
fn distinguish(lines: &mut [Line]) -> Vec<Markers> {
    let n = lines.len();
    let mut markers = Vec::with_capacity(n);
    for (i, line) in lines.iter_mut().enumerate() {
        line.width = 2 + (n - 1 - i) as u32;
        let step = (line.points.len() / 8).max(1);
        let offset = step / 2 + i * step / n.max(1);
        let points: Vec<(f64, f64)> = line
            .points
            .iter()
            .skip(offset.min(line.points.len()))
            .step_by(step)
            .copied()
            .collect();
        markers.push(Markers {
            label: String::new(),
            colors: vec![line.color; points.len()],
            points,
            legend_color: line.color,
            marker: if i % 2 == 0 {
                Marker::Disc
            } else {
                Marker::Square
            },
        });
    }
    markers
}

/// Fig. 2: BRDF vs θN (log axis) and the shadowing factor.
pub fn fig2(a: &Analysis) -> Figure {
    let f = &a.fig2;
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    for c in &f.brdf {
        for &v in c {
            lo = lo.min(v.log10());
            hi = hi.max(v.log10());
        }
    }
    let mut lines_a: Vec<Line> = f
        .thetas_deg
        .iter()
        .zip(&f.brdf)
        .enumerate()
        .map(|(i, (t, c))| Line {
            label: format!("θi = θr = {t:.0}°"),
            points: f
                .theta_n_deg
                .iter()
                .zip(c)
                .map(|(&x, &y)| (x, y.log10()))
                .collect(),
            color: PALETTE[i],
            dashed: false,
            width: 2,
        })
        .collect();
    let mut lines_b: Vec<Line> = f
        .thetas_deg
        .iter()
        .enumerate()
        .map(|(i, t)| Line {
            label: format!("θi = θr = {t:.0}°"),
            points: f
                .theta_n_deg
                .iter()
                .zip(f.brdf[i].iter().zip(&f.brdf_no_shadow[i]))
                .map(|(&x, (&on, &off))| (x, on / off))
                .collect(),
            color: PALETTE[i],
            dashed: false,
            width: 2,
        })
        .collect();
    let markers_a = distinguish(&mut lines_a);
    let markers_b = distinguish(&mut lines_b);
    lines_b.push(Line {
        label: "shadowing off (every θi)".into(),
        points: vec![(0.0, 1.0), (FIG2_THETA_N_MAX_DEG, 1.0)],
        color: BLACK,
        dashed: true,
        width: 2,
    });
    Figure {
        size: (1700, 760),
        panels: vec![
            Panel {
                title: format!(
                    "(a) BRDF, eq. 6, specular (β = θi), σ = {FIG2_SIGMA_DEG:.0}°, n = {N}"
                ),
                x_desc: "facet tilt θN (deg)".into(),
                y_desc: "BRDF f (sr⁻¹), log scale".into(),
                x_range: (0.0, FIG2_THETA_N_MAX_DEG),
                y_range: (lo.floor(), hi.ceil() + 1.0),
                log_y: true,
                log_x: false,
                x_ticks: 7,
                y_ticks: 20,
                lines: lines_a,
                markers: markers_a,
                vlines: vec![],
                legend: LegendAt::UpperRight,
            },
            Panel {
                title:
                    "(b) shadowing: f / f(shadowing off) = SO(θN, β = θi); θi ≥ 30° nearly coincide"
                        .into(),
                x_desc: "facet tilt θN (deg)".into(),
                y_desc: "ratio to the unshadowed BRDF".into(),
                x_range: (0.0, FIG2_THETA_N_MAX_DEG),
                y_range: (0.3, 1.05),
                log_y: false,
                log_x: false,
                x_ticks: 7,
                y_ticks: 9,
                lines: lines_b,
                markers: markers_b,
                vlines: vec![],
                legend: LegendAt::LowerLeft,
            },
        ],
    }
}

/// Fig. 3: smooth-surface DoLP vs incidence angle, with Table 1's row 0 for comparison.
pub fn fig3(a: &Analysis) -> Figure {
    Figure {
        size: (1100, 760),
        panels: vec![Panel {
            title: format!("DoLP of specular reflection, smooth surface, n = {N}"),
            x_desc: "incidence angle θi = θr (deg)".into(),
            y_desc: "DoLP (unpolarized input)".into(),
            x_range: (0.0, 90.0),
            y_range: (0.0, 1.08),
            log_y: false,
            log_x: false,
            x_ticks: 10,
            y_ticks: 12,
            lines: vec![Line {
                label: "this model (Fresnel, eq. 9–13)".into(),
                points: a.fig3.clone(),
                color: PALETTE[0],
                dashed: false,
                width: 2,
            }],
            markers: row0_markers(
                "paper's Table 1, roughness 0 (its model)",
                "paper's Table 1, roughness 0 (Lawrence/Wolff)",
                100.0,
            ),
            vlines: vec![(brewster_deg(), format!(" Brewster {:.2}°", brewster_deg()))],
            legend: LegendAt::UpperLeft,
        }],
    }
}

/// Fig. 4: DoLP vs incidence angle for the roughness values (primary interpretation).
pub fn fig4(a: &Analysis) -> Figure {
    let lines = ROUGHNESS
        .iter()
        .zip(&a.fig4)
        .enumerate()
        .map(|(i, (&r, c))| Line {
            label: roughness_label(r),
            points: a
                .dolp_angles
                .iter()
                .copied()
                .zip(c.iter().copied())
                .collect(),
            color: PALETTE[i],
            dashed: false,
            width: 2,
        })
        .collect();
    Figure {
        size: (1100, 760),
        panels: vec![Panel {
            title: format!(
                "DoLP at specular, roughness = σ of D, volume term ρD = {RHO_D}, ρV = {RHO_V} sr⁻¹"
            ),
            x_desc: "incidence angle θi = θr (deg)".into(),
            y_desc: "DoLP (unpolarized input)".into(),
            x_range: (0.0, 90.0),
            y_range: (0.0, 1.08),
            log_y: false,
            log_x: false,
            x_ticks: 10,
            y_ticks: 12,
            lines,
            markers: vec![],
            vlines: vec![(brewster_deg(), format!(" Brewster {:.2}°", brewster_deg()))],
            legend: LegendAt::UpperLeft,
        }],
    }
}

/// Fig. 5: our curves over Table 1's points, and the smooth-row hypotheses.
pub fn fig5(a: &Analysis) -> Figure {
    Figure {
        size: (1800, 780),
        panels: vec![fig5_ours_vs_table(a), fig5_smooth_row(a)],
    }
}

/// Fig. 5(a): the primary interpretation's DoLP curves (%) for every roughness, over Table 1's
/// cells of both columns as markers coloured by roughness.
fn fig5_ours_vs_table(a: &Analysis) -> Panel {
    let lines_a: Vec<Line> = ROUGHNESS
        .iter()
        .zip(&a.fig4)
        .enumerate()
        .map(|(i, (&r, c))| Line {
            label: format!("ours, {}", roughness_label(r)),
            points: a
                .dolp_angles
                .iter()
                .zip(c)
                .map(|(&x, &y)| (x, 100.0 * y))
                .collect(),
            color: PALETTE[i],
            dashed: false,
            width: 2,
        })
        .collect();
    Panel {
        title: "(a) ours (lines) vs Table 1 (markers, same colour = same roughness)".into(),
        x_desc: "incidence angle θi = θr (deg)".into(),
        y_desc: "DoLP (%)".into(),
        x_range: (0.0, 90.0),
        y_range: (0.0, 108.0),
        log_y: false,
        log_x: false,
        x_ticks: 10,
        y_ticks: 12,
        lines: lines_a,
        markers: table1_markers(),
        vlines: vec![],
        legend: LegendAt::UpperLeft,
    }
}

/// Table 1's cells (DoLP, %) as two marker sets, the paper's model column left of each angle
/// and the Lawrence/Wolff column right of it, coloured by roughness row.
/// The paper's Table 1 row 0 (roughness 0) as markers: its model's values (discs) and the
/// Lawrence/Wolff values (grey squares), with their legend labels; the table's DoLP (%) divided
/// by `per` (100: a fraction; 1: percent).
fn row0_markers(model: &str, lawrence: &str, per: f64) -> Vec<Markers> {
    let row0 = |t: &[[f64; 5]; 6]| -> Vec<(f64, f64)> {
        TABLE_ANGLES_DEG
            .iter()
            .zip(&t[0])
            .map(|(&x, &y)| (x, y / per))
            .collect()
    };
    vec![
        Markers {
            label: model.into(),
            points: row0(&TABLE_PAPER_MODEL),
            colors: vec![PALETTE[3]; 5],
            legend_color: PALETTE[3],
            marker: Marker::Disc,
        },
        Markers {
            label: lawrence.into(),
            points: row0(&TABLE_PAPER_LAWRENCE),
            colors: vec![GREY; 5],
            legend_color: GREY,
            marker: Marker::Square,
        },
    ]
}

fn table1_markers() -> Vec<Markers> {
    let table_points = |t: &[[f64; 5]; 6]| -> (Vec<(f64, f64)>, Vec<RGBColor>) {
        let mut pts = Vec::new();
        let mut cols = Vec::new();
        for (i, row) in t.iter().enumerate() {
            for (&x, &y) in TABLE_ANGLES_DEG.iter().zip(row) {
                // Rows spread by 0.4° each so that equal values stay visible.
                pts.push((x + 0.4 * (i as f64 - 2.5), y));
                cols.push(PALETTE[i]);
            }
        }
        (pts, cols)
    };
    let (pm, cm) = table_points(&TABLE_PAPER_MODEL);
    let (pl, cl) = table_points(&TABLE_PAPER_LAWRENCE);
    let shift = |v: Vec<(f64, f64)>, dx: f64| v.into_iter().map(|(x, y)| (x + dx, y)).collect();
    vec![
        Markers {
            label: "paper's model (Table 1)".into(),
            points: shift(pm, -1.3),
            colors: cm,
            legend_color: BLACK,
            marker: Marker::Disc,
        },
        Markers {
            label: "Lawrence/Wolff (Table 1)".into(),
            points: shift(pl, 1.3),
            colors: cl,
            legend_color: BLACK,
            marker: Marker::Square,
        },
    ]
}

/// Fig. 5(b): Table 1's roughness-0 row (both columns, %) against the smooth-surface
/// hypotheses' curves (reflection and emission, each at the paper's n and at the best fit).
fn fig5_smooth_row(a: &Analysis) -> Panel {
    let hyp_colors = [PALETTE[0], PALETTE[0], PALETTE[1], PALETTE[1]];
    let lines_b = a
        .hypothesis_curves
        .iter()
        .enumerate()
        .map(|(i, (label, y))| Line {
            label: label.clone(),
            points: a
                .dolp_angles
                .iter()
                .zip(y)
                .map(|(&x, &v)| (x, 100.0 * v))
                .collect(),
            color: hyp_colors[i],
            dashed: i % 2 == 1,
            width: 2,
        })
        .collect();
    Panel {
        title: "(b) Table 1 roughness-0 row vs smooth-surface hypotheses".into(),
        x_desc: "incidence (reflection) or emission angle θ (deg)".into(),
        y_desc: "DoLP (%)".into(),
        x_range: (0.0, 90.0),
        y_range: (0.0, 108.0),
        log_y: false,
        log_x: false,
        x_ticks: 10,
        y_ticks: 12,
        lines: lines_b,
        markers: row0_markers(
            "Table 1 row 0, paper's model",
            "Table 1 row 0, Lawrence/Wolff",
            1.0,
        ),
        vlines: vec![],
        legend: LegendAt::UpperLeft,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coinciding_curves_get_their_own_widths_and_marker_positions() {
        // Seven identical curves (Fig. 2(b)'s θi ≥ 30° are nearly so): each must stay visible.
        let mut lines: Vec<Line> = (0..7)
            .map(|i| Line {
                label: format!("{i}"),
                points: (0..600).map(|k| (f64::from(k) * 0.1, 1.0)).collect(),
                color: PALETTE[i],
                dashed: false,
                width: 2,
            })
            .collect();
        let markers = distinguish(&mut lines);
        for i in 0..7 {
            assert!(markers[i].points.len() >= 7, "{}", markers[i].points.len());
            assert!(markers[i].label.is_empty(), "no second legend entry");
            for j in 0..i {
                // Wider curves are drawn first (underneath).
                assert!(lines[j].width > lines[i].width);
                assert!(markers[j].marker != markers[i].marker || i - j >= 2);
                for p in &markers[i].points {
                    assert!(
                        markers[j].points.iter().all(|q| (q.0 - p.0).abs() > 0.5),
                        "markers of curves {j} and {i} coincide at x = {}",
                        p.0
                    );
                }
            }
        }
    }
}
