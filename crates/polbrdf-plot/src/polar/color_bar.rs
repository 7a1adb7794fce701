//! The colour bar: a vertical bar of a colour scale with its ticks and its rotated label
//! (shared by the polar maps and the images).

use super::scale::ColorScale;
use super::text::{font, pt};
use crate::encode::DrawResult;
use crate::font::FAMILY;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// A vertical colour bar of `scale` with its ticks and its rotated label: the bar's left edge at
/// `bx`, spanning `top` to `bottom` (pixels, y downward); the label no further right than
/// `right_limit`. Shared by the polar maps and the images ([`crate::heatmap`]).
pub(crate) fn draw_color_bar<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    scale: &ColorScale,
    bx: f64,
    (top, bottom): (f64, f64),
    right_limit: f64,
) -> DrawResult
where
    DB::ErrorType: 'static,
{
    let bw = 20.0;
    let height = bottom - top;
    let (it, ib) = (top.round() as i32, bottom.round() as i32);
    for yy in it..ib {
        let t = 1.0 - (f64::from(yy - it) + 0.5) / f64::from(ib - it);
        root.draw(&Rectangle::new(
            [(bx as i32, yy), ((bx + bw) as i32, yy + 1)],
            scale.colormap.rgb(t).filled(),
        ))?;
    }
    root.draw(&Rectangle::new(
        [(bx as i32, it), ((bx + bw) as i32, ib)],
        ShapeStyle::from(&BLACK).stroke_width(1),
    ))?;
    let tick_style = font(14.0).pos(Pos::new(HPos::Left, VPos::Center));
    let mut widest = 0u32;
    for (t, label) in scale.tick_marks() {
        widest = widest.max(root.estimate_text_size(&label, &tick_style)?.0);
        let y = bottom - t.clamp(0.0, 1.0) * height;
        root.draw(&PathElement::new(
            vec![pt(bx + bw, y), pt(bx + bw + 5.0, y)],
            ShapeStyle::from(&BLACK).stroke_width(1),
        ))?;
        root.draw(&Text::new(label, pt(bx + bw + 8.0, y), tick_style.clone()))?;
    }
    let label_style = TextStyle::from(
        (FAMILY, 16.0)
            .into_font()
            .transform(FontTransform::Rotate270),
    )
    .color(&BLACK)
    .pos(Pos::new(HPos::Center, VPos::Center));
    root.draw(&Text::new(
        scale.label.clone(),
        pt(
            (bx + bw + 8.0 + f64::from(widest) + 14.0).min(right_limit),
            0.5 * (top + bottom),
        ),
        label_style,
    ))?;
    Ok(())
}
