//! # polbrdf-plot — figures for polbrdf, rendered in memory
//!
//! Three kinds of figure, all declared as plain data and rendered to bytes — a PNG file
//! (`png()`) and an SVG document (`svg()`) — so the caller decides where and how to write them
//! (polbrdf writes them atomically with `polbrdf_io::write_atomic`):
//!
//! - [`Figure`]: line charts with markers, legends and log axes (the paper's figures);
//! - [`PolarFigure`]: heat maps of the viewing hemisphere ([`PolarPanel`]: θ radial from 0° to
//!   90°, φ counterclockwise), with perceptually uniform [`Colormap`]s, a labelled colour bar
//!   ([`ColorScale`]), polar grid circles, azimuth labels and marks ([`PolarMark`]) for the sun,
//!   the specular direction and the best directions;
//! - [`HeatmapFigure`]: images on a pixel grid ([`HeatmapPanel`]: a camera frame, a Stokes
//!   image), nearest neighbour, with the same colour maps and colour bars.
//!
//! Text is drawn with the embedded DejaVu Sans (no system font library is needed).
//!
//! ```
//! use polbrdf_plot::{ColorScale, Colormap, PolarFigure, PolarGrid, PolarPanel};
//! let theta: Vec<f64> = (0..=18).map(|i| 5.0 * i as f64).collect();
//! let phi: Vec<f64> = (0..36).map(|j| 10.0 * j as f64).collect();
//! let values = theta.iter().flat_map(|t| phi.iter().map(move |_| t / 90.0)).collect();
//! let fig = PolarFigure {
//!     panel_size: (560, 520),
//!     columns: 1,
//!     panels: vec![PolarPanel {
//!         title: "θ / 90°".into(),
//!         grid: PolarGrid::new(theta, phi, values)?,
//!         scale: ColorScale::linear(Colormap::Viridis, 0.0, 1.0, "value (1)"),
//!         marks: vec![],
//!     }],
//! };
//! let png: Vec<u8> = fig.png()?;
//! assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
//! # Ok::<(), polbrdf_plot::Error>(())
//! ```

#![warn(missing_docs)]

#[cfg(feature = "render")]
pub mod chart;
pub mod colormap;
#[cfg(feature = "render")]
mod encode;
pub mod error;
#[cfg(feature = "render")]
pub mod font;
#[cfg(feature = "render")]
pub mod heatmap;
#[cfg(feature = "render")]
pub mod polar;
#[cfg(feature = "render")]
mod render;

#[cfg(feature = "render")]
pub use chart::{power_of_ten, Figure, LegendAt, Line, Marker, Markers, Panel, PALETTE};
pub use colormap::Colormap;
#[cfg(feature = "render")]
pub use encode::encode_png;
pub use error::{Error, Result};
#[cfg(feature = "render")]
pub use heatmap::{HeatmapFigure, HeatmapPanel};
pub use plotters::style::RGBColor;
#[cfg(feature = "render")]
pub use polar::{
    nice_ceil, ColorScale, Disk, MarkShape, PolarFigure, PolarGrid, PolarMark, PolarPanel,
};
#[cfg(feature = "render")]
pub use render::{render_files, Files, Render};
