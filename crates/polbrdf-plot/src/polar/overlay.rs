//! The overlay of one polar map: title, polar grid and its labels, marks, colour bar and legend,
//! drawn over the map's raster.

use super::color_bar::draw_color_bar;
use super::marks::draw_mark;
use super::panel::{PolarPanel, BAR_AREA_W, LEGEND_H, TITLE_H};
use super::text::{boxed_text, centered, font, pt};
use super::{Disk, PolarMark};
use crate::encode::DrawResult;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// Draws everything of panel `p` but its raster, in this order (later layers cover earlier
/// ones): the title, the polar grid with its labels, the marks and their labels, the colour bar
/// and the legend. The panel's top-left corner is `(ox, oy)`, its size `(w, h)` pixels, its
/// map inside `disk`.
pub(super) fn draw_panel_overlay<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    p: &PolarPanel,
    (ox, oy): (f64, f64),
    (w, h): (u32, u32),
    disk: &Disk,
) -> DrawResult
where
    DB::ErrorType: 'static,
{
    let (w, h) = (f64::from(w), f64::from(h));
    root.draw(&Text::new(
        p.title.clone(),
        pt(ox + w / 2.0, oy + TITLE_H / 2.0 + 2.0),
        centered(21.0),
    ))?;
    draw_polar_grid(root, disk)?;
    draw_marks(root, &p.marks, disk)?;
    let bx = ox + w - BAR_AREA_W + 8.0;
    draw_color_bar(
        root,
        &p.scale,
        bx,
        (disk.cy - disk.r, disk.cy + disk.r),
        ox + w - 12.0,
    )?;
    draw_legend(
        root,
        &p.marks,
        (ox + 14.0, oy + h - LEGEND_H / 2.0 - 2.0),
        ox + w - 10.0,
    )
}

/// The polar grid over `disk`: circles at θ = 30°, 60°, spokes every 30° of φ, the azimuth
/// labels outside the rim, the rim (θ = 90°) and the θ labels of the two circles. Each grid line
/// is a light halo under a dark line, so it shows on dark and light colours.
fn draw_polar_grid<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, disk: &Disk) -> DrawResult
where
    DB::ErrorType: 'static,
{
    let halo = ShapeStyle::from(&WHITE.mix(0.25)).stroke_width(3);
    let grid = ShapeStyle::from(&RGBColor(20, 20, 20).mix(0.55)).stroke_width(1);
    for style in [halo, grid] {
        for theta in [30.0, 60.0] {
            root.draw(&Circle::new(
                pt(disk.cx, disk.cy),
                (disk.r * theta / 90.0).round() as i32,
                style,
            ))?;
        }
        for k in 0..12 {
            let phi = 30.0 * f64::from(k);
            let (x0, y0) = disk.position(30.0 / 8.0, phi);
            let (x1, y1) = disk.position(90.0, phi);
            root.draw(&PathElement::new(vec![pt(x0, y0), pt(x1, y1)], style))?;
        }
    }
    for k in 0..12 {
        let phi = 30.0 * f64::from(k);
        let (lx, ly) = disk.position(90.0 * (disk.r + 20.0) / disk.r, phi);
        root.draw(&Text::new(format!("{phi:.0}°"), pt(lx, ly), centered(15.0)))?;
    }
    root.draw(&Circle::new(
        pt(disk.cx, disk.cy),
        disk.r.round() as i32,
        ShapeStyle::from(&BLACK).stroke_width(2),
    ))?;
    for theta in [30.0, 60.0] {
        let (x, y) = disk.position(theta, 285.0);
        boxed_text(root, &format!("{theta:.0}°"), (x, y), 13.0)?;
    }
    Ok(())
}

/// The marks at their directions on `disk`, then their labels (on white boxes, up and to the
/// right of each mark) so that no mark covers a label.
fn draw_marks<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    marks: &[PolarMark],
    disk: &Disk,
) -> DrawResult
where
    DB::ErrorType: 'static,
{
    for m in marks {
        draw_mark(root, m.shape, disk.position(m.theta_deg, m.phi_deg))?;
    }
    for m in marks {
        if !m.label.is_empty() {
            let (x, y) = disk.position(m.theta_deg, m.phi_deg);
            boxed_text(root, &m.label, (x + 16.0, y - 14.0), 13.0)?;
        }
    }
    Ok(())
}

/// The legend strip, left to right from `(x, ly)`: one entry (mark and text) per distinct
/// legend text of `marks`, then how to read the axes, right-aligned at `right` when it fits
/// beside the entries.
fn draw_legend<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    marks: &[PolarMark],
    (mut x, ly): (f64, f64),
    right: f64,
) -> DrawResult
where
    DB::ErrorType: 'static,
{
    let text_style = font(14.0).pos(Pos::new(HPos::Left, VPos::Center));
    let mut seen: Vec<&str> = Vec::new();
    for m in marks {
        if m.legend.is_empty() || seen.contains(&m.legend.as_str()) {
            continue;
        }
        seen.push(&m.legend);
        draw_mark(root, m.shape, (x + 16.0, ly))?;
        root.draw(&Text::new(
            m.legend.clone(),
            pt(x + 36.0, ly),
            text_style.clone(),
        ))?;
        let (tw, _) = root.estimate_text_size(&m.legend, &text_style)?;
        x += 36.0 + f64::from(tw) + 16.0;
    }
    let axes = "radius θr, angle φr";
    let (tw, _) = root.estimate_text_size(axes, &text_style)?;
    let ax = right - f64::from(tw);
    if ax < x {
        return Ok(()); // no room left beside the legend
    }
    root.draw(&Text::new(
        axes.to_string(),
        pt(ax, ly),
        font(14.0)
            .color(&RGBColor(90, 90, 90))
            .pos(Pos::new(HPos::Left, VPos::Center)),
    ))?;
    Ok(())
}
