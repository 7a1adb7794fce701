//! The marks drawn on a map (sun, specular direction, best directions, locus points): their
//! shapes and how each is drawn.

use super::text::pt;
use crate::encode::DrawResult;
use plotters::coord::Shift;
use plotters::prelude::*;

/// Shapes of the marks drawn on a map.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MarkShape {
    /// A sun: gold disc with rays (the direction toward the source).
    Sun,
    /// An open diamond (the specular direction).
    Specular,
    /// A ring with a centre dot (the best direction).
    Best,
    /// A small ring (further ranked directions).
    Ring,
    /// A small white dot with a black rim (points of a locus, e.g. the polarization null).
    Dot,
}

/// A mark at a direction, with an optional text beside it and an optional legend entry.
#[derive(Debug, Clone, PartialEq)]
pub struct PolarMark {
    /// Zenith angle, degrees.
    pub theta_deg: f64,
    /// Azimuth, degrees.
    pub phi_deg: f64,
    /// Shape.
    pub shape: MarkShape,
    /// Text drawn beside the mark (empty: none).
    pub label: String,
    /// Legend text (empty: no legend entry; entries with the same text appear once).
    pub legend: String,
}

/// Draws the mark `shape` centred on the pixel position `(x, y)`.
pub(super) fn draw_mark<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    shape: MarkShape,
    (x, y): (f64, f64),
) -> DrawResult
where
    DB::ErrorType: 'static,
{
    let black = ShapeStyle::from(&BLACK).stroke_width(2);
    match shape {
        MarkShape::Sun => {
            for k in 0..8 {
                let a = f64::from(k) * std::f64::consts::FRAC_PI_4;
                let (s, c) = a.sin_cos();
                root.draw(&PathElement::new(
                    vec![
                        pt(x + 10.0 * c, y + 10.0 * s),
                        pt(x + 15.0 * c, y + 15.0 * s),
                    ],
                    black,
                ))?;
            }
            root.draw(&Circle::new(pt(x, y), 7, RGBColor(255, 196, 0).filled()))?;
            root.draw(&Circle::new(pt(x, y), 7, black))?;
        }
        MarkShape::Specular => {
            let d = 8.0;
            let pts = vec![
                pt(x, y - d),
                pt(x + d, y),
                pt(x, y + d),
                pt(x - d, y),
                pt(x, y - d),
            ];
            root.draw(&Polygon::new(pts.clone(), WHITE.filled()))?;
            root.draw(&PathElement::new(pts, black))?;
        }
        MarkShape::Best => {
            root.draw(&Circle::new(
                pt(x, y),
                10,
                ShapeStyle::from(&WHITE).stroke_width(5),
            ))?;
            root.draw(&Circle::new(pt(x, y), 10, black))?;
            root.draw(&Circle::new(pt(x, y), 3, BLACK.filled()))?;
        }
        MarkShape::Dot => {
            root.draw(&Circle::new(pt(x, y), 3, WHITE.filled()))?;
            root.draw(&Circle::new(
                pt(x, y),
                3,
                ShapeStyle::from(&BLACK).stroke_width(1),
            ))?;
        }
        MarkShape::Ring => {
            root.draw(&Circle::new(
                pt(x, y),
                6,
                ShapeStyle::from(&WHITE).stroke_width(4),
            ))?;
            root.draw(&Circle::new(
                pt(x, y),
                6,
                ShapeStyle::from(&BLACK).stroke_width(1),
            ))?;
        }
    }
    Ok(())
}
