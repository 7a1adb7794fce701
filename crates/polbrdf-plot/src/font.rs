//! The embedded font: DejaVu Sans 2.37 (Bitstream Vera / Arev license, see
//! `assets/DejaVuSans-LICENSE.txt`), registered with plotters' `ab_glyph` text renderer, so no
//! system font library is needed.

use crate::error::{Error, Result};
use plotters::style::FontStyle;
use std::sync::OnceLock;

static FONT: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");

/// The family name every figure uses.
pub const FAMILY: &str = "sans-serif";

/// Registers the embedded font for every style plotters may ask for (once per process).
pub fn register() -> Result<()> {
    static DONE: OnceLock<bool> = OnceLock::new();
    let ok = *DONE.get_or_init(|| {
        [
            FontStyle::Normal,
            FontStyle::Bold,
            FontStyle::Italic,
            FontStyle::Oblique,
        ]
        .into_iter()
        .all(|style| plotters::style::register_font(FAMILY, style, FONT).is_ok())
    });
    if ok {
        Ok(())
    } else {
        Err(Error::Font)
    }
}
