//! Encoding: a layered figure (rasters under a vector overlay — the polar maps and the images)
//! to PNG and SVG, PNG bytes from an RGB buffer, raster images embedded in SVG, and the result
//! and error of drawing onto a plotters backend. The leaf the figures draw through.

use crate::error::{Error, Result};
use plotters::coord::Shift;
use plotters::prelude::*;

/// The result of drawing onto a plotters backend.
pub(crate) type DrawResult = std::result::Result<(), Box<dyn std::error::Error + Send + Sync>>;

/// A raster under a figure's vector overlay: its top-left corner, its size and each pixel's
/// colour, row-major (`None`: the white background shows).
pub(crate) struct Raster {
    pub x0: i64,
    pub y0: i64,
    pub w: u32,
    pub h: u32,
    pub pixels: Vec<Option<[u8; 3]>>,
}

/// A figure of rasters (the maps, the images) under vector text and lines: the polar maps
/// ([`crate::PolarFigure`]) and the images ([`crate::HeatmapFigure`]) render through
/// [`layered_png`] and [`layered_svg`].
pub(crate) trait Layered {
    /// The figure's size, pixels.
    fn size(&self) -> (u32, u32);
    /// The rasters, drawn in this order.
    fn rasters(&self) -> Vec<Raster>;
    /// Everything drawn above the rasters.
    fn draw_overlay<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static;
}

/// A layered figure as a PNG file: the rasters drawn into a white bitmap (clipped to it), the
/// overlay above them.
///
/// # Errors
/// [`Error::Font`], [`Error::Draw`] or [`Error::Encode`].
pub(crate) fn layered_png(fig: &impl Layered) -> Result<Vec<u8>> {
    crate::font::register()?;
    let (w, h) = fig.size();
    let mut rgb = vec![255u8; (w as usize) * (h as usize) * 3];
    for r in fig.rasters() {
        for row in 0..i64::from(r.h) {
            for col in 0..i64::from(r.w) {
                let (x, y) = (r.x0 + col, r.y0 + row);
                let Some(c) = r.pixels[(row * i64::from(r.w) + col) as usize] else {
                    continue;
                };
                if x >= 0 && y >= 0 && (x as u32) < w && (y as u32) < h {
                    let at = 3 * (y as usize * w as usize + x as usize);
                    rgb[at..at + 3].copy_from_slice(&c);
                }
            }
        }
    }
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (w, h)).into_drawing_area();
        fig.draw_overlay(&root).map_err(draw_err)?;
        root.present().map_err(draw_err)?;
    }
    encode_png(&rgb, w, h)
}

/// A layered figure as an SVG document: the overlay as vector elements above the rasters,
/// each embedded as a PNG `<image>` (its transparent pixels white).
///
/// # Errors
/// [`Error::Font`], [`Error::Draw`] or [`Error::Encode`].
pub(crate) fn layered_svg(fig: &impl Layered) -> Result<String> {
    crate::font::register()?;
    let mut text = String::new();
    {
        let root = SVGBackend::with_string(&mut text, fig.size()).into_drawing_area();
        root.fill(&WHITE).map_err(draw_err)?;
        fig.draw_overlay(&root).map_err(draw_err)?;
        root.present().map_err(draw_err)?;
    }
    let mut images = String::new();
    for r in fig.rasters() {
        let rgb: Vec<u8> = r
            .pixels
            .iter()
            .flat_map(|c| c.unwrap_or([255, 255, 255]))
            .collect();
        let png = encode_png(&rgb, r.w, r.h)?;
        images += &svg_image(r.x0 as i32, r.y0 as i32, r.w, r.h, &png);
    }
    insert_after_background(&mut text, &images)?;
    Ok(text)
}

/// Maps a plotters drawing error to [`Error::Draw`].
pub(crate) fn draw_err<E: std::fmt::Display>(e: E) -> Error {
    Error::Draw(e.to_string())
}

/// Encodes an 8-bit RGB buffer (`w·h·3` bytes, row-major) as a PNG file.
///
/// # Errors
/// [`Error::Encode`] when the buffer does not match the size.
pub fn encode_png(rgb: &[u8], w: u32, h: u32) -> Result<Vec<u8>> {
    use image::codecs::png::{CompressionType, FilterType, PngEncoder};
    let mut out = Vec::new();
    image::ImageEncoder::write_image(
        PngEncoder::new_with_quality(&mut out, CompressionType::Default, FilterType::Adaptive),
        rgb,
        w,
        h,
        image::ColorType::Rgb8,
    )
    .map_err(|e| Error::Encode(e.to_string()))?;
    Ok(out)
}

/// Standard base64 (RFC 4648, with padding).
pub(crate) fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            chunk.get(1).copied().unwrap_or(0),
            chunk.get(2).copied().unwrap_or(0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                s.push(ALPHABET[((n >> (18 - 6 * k)) & 63) as usize] as char);
            } else {
                s.push('=');
            }
        }
    }
    s
}

/// An `<image>` element showing `png` at `(x, y)` with size `w × h` user units.
pub(crate) fn svg_image(x: i32, y: i32, w: u32, h: u32, png: &[u8]) -> String {
    format!(
        "<image x=\"{x}\" y=\"{y}\" width=\"{w}\" height=\"{h}\" preserveAspectRatio=\"none\" \
         style=\"image-rendering:optimizeSpeed\" href=\"data:image/png;base64,{}\"/>\n",
        base64(png)
    )
}

/// Inserts `elements` right after the background (the first element after the `<svg>` tag), so
/// that everything drawn afterwards lies above them.
///
/// # Errors
/// [`Error::Draw`] when `svg` does not have that shape.
pub(crate) fn insert_after_background(svg: &mut String, elements: &str) -> Result<()> {
    let open = svg
        .find("<svg")
        .and_then(|i| svg[i..].find('>').map(|j| i + j + 1))
        .ok_or_else(|| Error::Draw("SVG output has no <svg> tag".into()))?;
    let bg_end = svg[open..]
        .find("/>")
        .map(|j| open + j + 2)
        .ok_or_else(|| Error::Draw("SVG output has no background element".into()))?;
    let at = if svg[bg_end..].starts_with('\n') {
        bg_end + 1
    } else {
        bg_end
    };
    svg.insert_str(at, elements);
    Ok(())
}
