//! Text and pixel helpers shared by the figures' overlays: the fonts, pixel rounding and text
//! on a white box.

use crate::encode::DrawResult;
use crate::font::FAMILY;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// Black DejaVu Sans of `size` pixels.
pub(crate) fn font(size: f64) -> TextStyle<'static> {
    TextStyle::from((FAMILY, size).into_font()).color(&BLACK)
}

/// [`font`] centred on its anchor point.
pub(crate) fn centered(size: f64) -> TextStyle<'static> {
    font(size).pos(Pos::new(HPos::Center, VPos::Center))
}

/// A point in figure coordinates rounded to the nearest pixel.
pub(crate) fn pt(x: f64, y: f64) -> (i32, i32) {
    (x.round() as i32, y.round() as i32)
}

/// Text on a white box, for labels drawn over the map.
pub(super) fn boxed_text<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    text: &str,
    (x, y): (f64, f64),
    size: f64,
) -> DrawResult
where
    DB::ErrorType: 'static,
{
    let style = centered(size);
    let (tw, th) = root.estimate_text_size(text, &style)?;
    let (hw, hh) = (f64::from(tw) / 2.0 + 3.0, f64::from(th) / 2.0 + 1.0);
    root.draw(&Rectangle::new(
        [pt(x - hw, y - hh), pt(x + hw, y + hh)],
        WHITE.mix(0.8).filled(),
    ))?;
    root.draw(&Text::new(text.to_string(), pt(x, y), style))?;
    Ok(())
}
