//! One panel: its map, colour scale and marks ([`PolarPanel`]), its layout (where the title,
//! disk, colour bar and legend go) and its map's raster drawn through the disk.

use super::disk::Disk;
use super::{ColorScale, PolarGrid, PolarMark};
use crate::encode::Raster;

/// Height of the title strip at the top of each panel, pixels.
pub(super) const TITLE_H: f64 = 46.0;
/// Height of the legend strip at the bottom of each panel, pixels.
pub(super) const LEGEND_H: f64 = 38.0;
/// Width of the colour bar area at the right of each panel, pixels.
pub(super) const BAR_AREA_W: f64 = 128.0;
/// Room between the rim and the panel edge for the azimuth labels, pixels.
const LABEL_MARGIN: f64 = 38.0;

/// One polar map.
#[derive(Debug, Clone, PartialEq)]
pub struct PolarPanel {
    /// Title above the map.
    pub title: String,
    /// The data.
    pub grid: PolarGrid,
    /// Colours and colour bar.
    pub scale: ColorScale,
    /// Marks drawn over the map.
    pub marks: Vec<PolarMark>,
}

/// The disk of a panel of the given size, relative to the panel's top-left corner.
pub fn panel_disk((w, h): (u32, u32)) -> Disk {
    let bw = f64::from(w) - BAR_AREA_W;
    let bh = f64::from(h) - TITLE_H - LEGEND_H;
    let r = (bw.min(bh) / 2.0 - LABEL_MARGIN).max(10.0).floor();
    Disk {
        cx: (bw / 2.0).round(),
        cy: (TITLE_H + bh / 2.0).round(),
        r,
    }
}

/// The map's pixels: the disk's bounding square (`None` outside the disk).
pub(super) fn raster(p: &PolarPanel, disk: &Disk) -> Raster {
    let x0 = (disk.cx - disk.r).floor() as i64 - 1;
    let y0 = (disk.cy - disk.r).floor() as i64 - 1;
    let side = (2.0 * disk.r).ceil() as u32 + 3;
    let values: Vec<f64> = p
        .grid
        .values()
        .iter()
        .map(|&v| p.scale.forward(v))
        .collect();
    let mut out = Vec::with_capacity((side * side) as usize);
    for row in 0..side {
        for col in 0..side {
            let (x, y) = (
                (x0 + col as i64) as f64 + 0.5,
                (y0 + row as i64) as f64 + 0.5,
            );
            out.push(disk.direction(x, y).map(|(theta, phi)| {
                let v = p.grid.interpolate(&values, theta, phi, p.scale.period);
                let c = p.scale.colormap.rgb(p.scale.position(v));
                [c.0, c.1, c.2]
            }));
        }
    }
    Raster {
        x0,
        y0,
        w: side,
        h: side,
        pixels: out,
    }
}
