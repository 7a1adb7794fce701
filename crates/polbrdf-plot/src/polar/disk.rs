//! The projection of the viewing hemisphere onto a disk (radius ∝ θ, φ counterclockwise from
//! the right) and the map's raster drawn through it.

use super::PolarPanel;
use crate::render::Raster;

/// Where a map's disk lies in the figure, in pixels (y downward).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Disk {
    /// Centre, x.
    pub cx: f64,
    /// Centre, y.
    pub cy: f64,
    /// Radius (θ = 90°).
    pub r: f64,
}

impl Disk {
    /// Pixel position of the direction `(theta, phi)` in degrees: radius ∝ θ, φ
    /// counterclockwise from the +x axis (to the right).
    pub fn position(&self, theta_deg: f64, phi_deg: f64) -> (f64, f64) {
        let rho = self.r * theta_deg / 90.0;
        let (s, c) = phi_deg.to_radians().sin_cos();
        (self.cx + rho * c, self.cy - rho * s)
    }

    /// The direction `(theta, phi)` in degrees (φ in `[0, 360)`) at a pixel position, or `None`
    /// outside the disk.
    pub fn direction(&self, x: f64, y: f64) -> Option<(f64, f64)> {
        let (dx, dy) = (x - self.cx, self.cy - y);
        let rho = dx.hypot(dy);
        if rho > self.r {
            return None;
        }
        Some((
            90.0 * rho / self.r,
            dy.atan2(dx).to_degrees().rem_euclid(360.0),
        ))
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
