//! Polar heat maps of the viewing hemisphere.
//!
//! A [`PolarPanel`] shows one quantity given on a regular grid of viewing directions (zenith θ
//! from the centre, 0°, to the rim, 90°, azimuth φ counterclockwise from the right, as seen from
//! above the surface) with a colour bar, polar grid circles at θ = 30° and 60°, azimuth labels
//! every 30° and marks (sun, specular direction, best directions). The map is rasterized pixel
//! by pixel: each pixel inside the disk is turned into (θ, φ) and the grid is interpolated
//! bilinearly there (on the circle for periodic quantities such as angles, in log10 for a log
//! colour scale). PNG output draws it into the bitmap; SVG output embeds the same raster as a
//! PNG `<image>` under the vector grid, marks and text.

mod color_bar;
mod disk;
mod figure;
mod grid;
mod marks;
mod overlay;
mod panel;
mod scale;
mod text;

pub use disk::Disk;
pub use figure::PolarFigure;
pub use grid::PolarGrid;
pub use marks::{MarkShape, PolarMark};
pub use panel::{panel_disk, PolarPanel};
pub use scale::{nice_ceil, ColorScale};

pub(crate) use color_bar::draw_color_bar;
pub(crate) use text::{centered, pt};
