//! The figure: polar maps on a grid of equally sized panels (row by row), each panel's place
//! and disk in it, and its layered rendering (the maps' rasters under the overlays).

use super::disk::Disk;
use super::overlay::draw_panel_overlay;
use super::panel::{panel_disk, raster, PolarPanel};
use crate::encode::{layered_png, layered_svg, DrawResult, Layered, Raster};
#[cfg(doc)]
use crate::error::Error;
use crate::error::Result;
use plotters::coord::Shift;
use plotters::prelude::*;

/// Polar maps on a grid of equally sized panels (row by row).
#[derive(Debug, Clone, PartialEq)]
pub struct PolarFigure {
    /// Pixel size of one panel (the SVG uses the same user units).
    pub panel_size: (u32, u32),
    /// Panels per row.
    pub columns: usize,
    /// The panels.
    pub panels: Vec<PolarPanel>,
}

impl PolarFigure {
    /// The figure's pixel size.
    pub fn size(&self) -> (u32, u32) {
        let cols = self.columns.max(1);
        let rows = self.panels.len().div_ceil(cols).max(1);
        (
            self.panel_size.0 * cols as u32,
            self.panel_size.1 * rows as u32,
        )
    }

    /// Top-left corner of panel `k`.
    fn origin(&self, k: usize) -> (f64, f64) {
        let cols = self.columns.max(1);
        (
            f64::from(self.panel_size.0) * (k % cols) as f64,
            f64::from(self.panel_size.1) * (k / cols) as f64,
        )
    }

    /// The disk of panel `k` (a pure function of the panel size and position, so a reader of
    /// the image can find the map).
    pub fn disk(&self, k: usize) -> Disk {
        let (ox, oy) = self.origin(k);
        let d = panel_disk(self.panel_size);
        Disk {
            cx: ox + d.cx,
            cy: oy + d.cy,
            r: d.r,
        }
    }

    /// The figure as a PNG file.
    ///
    /// # Errors
    /// [`Error::Font`], [`Error::Draw`] or [`Error::Encode`].
    pub fn png(&self) -> Result<Vec<u8>> {
        layered_png(self)
    }

    /// The figure as an SVG document (the maps are embedded PNG rasters).
    ///
    /// # Errors
    /// [`Error::Font`], [`Error::Draw`] or [`Error::Encode`].
    pub fn svg(&self) -> Result<String> {
        layered_svg(self)
    }
}

impl Layered for PolarFigure {
    fn size(&self) -> (u32, u32) {
        PolarFigure::size(self)
    }

    fn rasters(&self) -> Vec<Raster> {
        (0..self.panels.len())
            .map(|k| raster(&self.panels[k], &self.disk(k)))
            .collect()
    }

    fn draw_overlay<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        for (k, p) in self.panels.iter().enumerate() {
            let (ox, oy) = self.origin(k);
            draw_panel_overlay(root, p, (ox, oy), self.panel_size, &self.disk(k))?;
        }
        Ok(())
    }
}
