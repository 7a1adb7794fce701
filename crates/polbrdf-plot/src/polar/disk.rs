//! The projection of the viewing hemisphere onto a disk (radius ∝ θ, φ counterclockwise from
//! the right).

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
