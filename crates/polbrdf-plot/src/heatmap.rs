//! Images as heat maps: values on a rectangular pixel grid (a camera frame, a Stokes image),
//! each data pixel drawn as a block of screen pixels of one colour (nearest neighbour, no
//! smoothing, so the pixels of the data stay visible), with a title, a labelled colour bar and
//! an optional outline (e.g. where the target is). PNG output draws the raster into the bitmap;
//! SVG output embeds the same raster as a PNG `<image>` under the vector text.

use crate::encode::{layered_png, layered_svg, DrawResult, Layered, Raster};
use crate::error::{Error, Result};
use crate::polar::{centered, draw_color_bar, pt, ColorScale};
use plotters::coord::Shift;
use plotters::prelude::*;

/// Height of the title strip at the top of each panel, pixels.
const TITLE_H: f64 = 46.0;
/// Width of the colour bar area at the right of each panel, pixels.
const BAR_AREA_W: f64 = 128.0;
/// Margin around the image, pixels.
const MARGIN: f64 = 12.0;

/// One image: `width × height` values, row-major, row 0 at the top.
#[derive(Debug, Clone, PartialEq)]
pub struct HeatmapPanel {
    /// Title above the image.
    pub title: String,
    width: usize,
    height: usize,
    values: Vec<f64>,
    /// Colours and colour bar (NaN values are drawn grey).
    pub scale: ColorScale,
    /// A rectangle drawn over the image, `[x0, y0, x1, y1]` in data pixels (x1, y1 exclusive).
    pub outline: Option<[usize; 4]>,
}

impl HeatmapPanel {
    /// An image of `width × height` values, row-major.
    ///
    /// # Errors
    /// [`Error::Invalid`] for an empty image or a value count that is not `width·height`.
    pub fn new(
        title: impl Into<String>,
        width: usize,
        height: usize,
        values: Vec<f64>,
        scale: ColorScale,
    ) -> Result<Self> {
        if width == 0 || height == 0 || width.checked_mul(height) != Some(values.len()) {
            return Err(Error::Invalid(format!(
                "image: an image of {width} × {height} pixels needs that many values, got {}",
                values.len()
            )));
        }
        Ok(Self {
            title: title.into(),
            width,
            height,
            values,
            scale,
            outline: None,
        })
    }

    /// Width, data pixels.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height, data pixels.
    pub fn height(&self) -> usize {
        self.height
    }

    /// The values, row-major.
    pub fn values(&self) -> &[f64] {
        &self.values
    }
}

/// Images on a grid of equally sized panels (row by row).
#[derive(Debug, Clone, PartialEq)]
pub struct HeatmapFigure {
    /// Pixel size of one panel.
    pub panel_size: (u32, u32),
    /// Panels per row.
    pub columns: usize,
    /// The panels.
    pub panels: Vec<HeatmapPanel>,
}

/// Where an image lies in the figure: top-left corner and screen pixels per data pixel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placement {
    /// Left edge, pixels.
    pub x0: f64,
    /// Top edge, pixels.
    pub y0: f64,
    /// Screen pixels per data pixel (the same along x and y: data pixels stay square).
    pub scale: f64,
}

impl HeatmapFigure {
    /// The figure's pixel size.
    pub fn size(&self) -> (u32, u32) {
        let cols = self.columns.max(1);
        let rows = self.panels.len().div_ceil(cols).max(1);
        (
            self.panel_size.0 * cols as u32,
            self.panel_size.1 * rows as u32,
        )
    }

    /// Where panel `k`'s image lies (a pure function of the panel size, position and the
    /// image's shape, so a reader of the figure can find the data pixels).
    pub fn placement(&self, k: usize) -> Placement {
        let cols = self.columns.max(1);
        let (pw, ph) = (f64::from(self.panel_size.0), f64::from(self.panel_size.1));
        let (ox, oy) = (pw * (k % cols) as f64, ph * (k / cols) as f64);
        let p = &self.panels[k];
        let (aw, ah) = (
            (pw - BAR_AREA_W - 2.0 * MARGIN).max(1.0),
            (ph - TITLE_H - MARGIN).max(1.0),
        );
        let scale = (aw / p.width as f64).min(ah / p.height as f64);
        let (w, h) = (scale * p.width as f64, scale * p.height as f64);
        Placement {
            x0: (ox + MARGIN + (aw - w) / 2.0).round(),
            y0: (oy + TITLE_H + (ah - h) / 2.0).round(),
            scale,
        }
    }

    /// Panel `k`'s raster: one screen pixel per block of the data pixel it shows.
    fn raster(&self, k: usize) -> Raster {
        let p = &self.panels[k];
        let at = self.placement(k);
        let w = (at.scale * p.width as f64).round().max(1.0) as u32;
        let h = (at.scale * p.height as f64).round().max(1.0) as u32;
        let mut pixels = Vec::with_capacity(w as usize * h as usize);
        for y in 0..h {
            let row = ((f64::from(y) + 0.5) / at.scale) as usize;
            for x in 0..w {
                let col = ((f64::from(x) + 0.5) / at.scale) as usize;
                let v = p.values[row.min(p.height - 1) * p.width + col.min(p.width - 1)];
                let c = p.scale.colormap.rgb(p.scale.position(p.scale.forward(v)));
                pixels.push(Some([c.0, c.1, c.2]));
            }
        }
        Raster {
            x0: at.x0 as i64,
            y0: at.y0 as i64,
            w,
            h,
            pixels,
        }
    }

    /// The figure as a PNG file.
    ///
    /// # Errors
    /// [`Error::Font`], [`Error::Draw`] or [`Error::Encode`].
    pub fn png(&self) -> Result<Vec<u8>> {
        layered_png(self)
    }

    /// The figure as an SVG document (the images are embedded PNG rasters).
    ///
    /// # Errors
    /// [`Error::Font`], [`Error::Draw`] or [`Error::Encode`].
    pub fn svg(&self) -> Result<String> {
        layered_svg(self)
    }
}

impl Layered for HeatmapFigure {
    fn size(&self) -> (u32, u32) {
        HeatmapFigure::size(self)
    }

    fn rasters(&self) -> Vec<Raster> {
        (0..self.panels.len()).map(|k| self.raster(k)).collect()
    }

    fn draw_overlay<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        let cols = self.columns.max(1);
        let (pw, ph) = (f64::from(self.panel_size.0), f64::from(self.panel_size.1));
        for (k, p) in self.panels.iter().enumerate() {
            let (ox, oy) = (pw * (k % cols) as f64, ph * (k / cols) as f64);
            root.draw(&Text::new(
                p.title.clone(),
                pt(ox + (pw - BAR_AREA_W) / 2.0, oy + TITLE_H / 2.0 + 2.0),
                centered(21.0),
            ))?;
            let at = self.placement(k);
            let (w, h) = (at.scale * p.width as f64, at.scale * p.height as f64);
            root.draw(&Rectangle::new(
                [pt(at.x0 - 1.0, at.y0 - 1.0), pt(at.x0 + w, at.y0 + h)],
                ShapeStyle::from(&BLACK).stroke_width(1),
            ))?;
            if let Some([x0, y0, x1, y1]) = p.outline {
                let xy = |x: usize, y: usize| {
                    pt(at.x0 + at.scale * x as f64, at.y0 + at.scale * y as f64)
                };
                for (style, width) in [(WHITE, 3), (BLACK, 1)] {
                    root.draw(&Rectangle::new(
                        [xy(x0, y0), xy(x1, y1)],
                        ShapeStyle::from(&style).stroke_width(width),
                    ))?;
                }
            }
            draw_color_bar(
                root,
                &p.scale,
                ox + pw - BAR_AREA_W + 8.0,
                (at.y0, at.y0 + h),
                ox + pw - 12.0,
            )?;
        }
        Ok(())
    }
}
