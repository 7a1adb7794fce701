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

use crate::colormap::Colormap;
use crate::error::{Error, Result};
use crate::font::FAMILY;
use crate::render::{layered_png, layered_svg, Layered, Raster};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

pub(crate) type DrawResult = std::result::Result<(), Box<dyn std::error::Error + Send + Sync>>;

/// Height of the title strip at the top of each panel, pixels.
const TITLE_H: f64 = 46.0;
/// Height of the legend strip at the bottom of each panel, pixels.
const LEGEND_H: f64 = 38.0;
/// Width of the colour bar area at the right of each panel, pixels.
const BAR_AREA_W: f64 = 128.0;
/// Room between the rim and the panel edge for the azimuth labels, pixels.
const LABEL_MARGIN: f64 = 38.0;

/// Values on a regular grid of viewing directions: rows of constant zenith angle θ
/// (ascending, in `[0°, 90°]`), each with the same uniformly spaced azimuths φ covering the
/// full circle.
#[derive(Debug, Clone, PartialEq)]
pub struct PolarGrid {
    theta_deg: Vec<f64>,
    phi0_deg: f64,
    phi_step_deg: f64,
    n_phi: usize,
    values: Vec<f64>,
}

impl PolarGrid {
    /// A grid from its axes (degrees) and `values[i·phi.len() + j]` at
    /// `(theta_deg[i], phi_deg[j])`.
    ///
    /// # Errors
    /// [`Error::Invalid`] when θ is not ascending within `[0, 90]`, φ is not uniformly spaced
    /// over exactly one turn (`n·Δφ = 360°`), there are fewer than 2 zenith or 3 azimuth values,
    /// or `values` has the wrong length.
    pub fn new(theta_deg: Vec<f64>, phi_deg: Vec<f64>, values: Vec<f64>) -> Result<Self> {
        let bad = |m: &str| Err(Error::Invalid(format!("polar grid: {m}")));
        if theta_deg.len() < 2 || phi_deg.len() < 3 {
            return bad("needs at least 2 zenith angles and 3 azimuths");
        }
        let ascending = theta_deg.windows(2).all(|w| w[0] < w[1]);
        if !(ascending && theta_deg[0] >= 0.0 && theta_deg[theta_deg.len() - 1] <= 90.0) {
            return bad("zenith angles must ascend within [0°, 90°]");
        }
        let n_phi = phi_deg.len();
        let step = 360.0 / n_phi as f64;
        let uniform = phi_deg
            .iter()
            .enumerate()
            .all(|(j, p)| (p - (phi_deg[0] + j as f64 * step)).abs() <= 1e-6 * step);
        if !uniform || !phi_deg[0].is_finite() {
            return bad("azimuths must be uniformly spaced over one full turn");
        }
        if values.len() != theta_deg.len() * n_phi {
            return bad("values must have one entry per (zenith, azimuth) pair");
        }
        Ok(Self {
            theta_deg,
            phi0_deg: phi_deg[0],
            phi_step_deg: step,
            n_phi,
            values,
        })
    }

    /// The zenith angles (degrees).
    pub fn theta_deg(&self) -> &[f64] {
        &self.theta_deg
    }

    /// Number of azimuths.
    pub fn n_phi(&self) -> usize {
        self.n_phi
    }

    /// The values, zenith-major.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// The value drawn at the direction `(theta, phi)` (degrees): bilinear interpolation of
    /// the grid, θ clamped to its range, φ wrapping around; with `period`, on the circle (the
    /// result then lies in `(−period/2, period/2]`).
    pub fn value_at(&self, theta_deg: f64, phi_deg: f64, period: Option<f64>) -> f64 {
        self.interpolate(&self.values, theta_deg, phi_deg, period)
    }

    /// Bilinear interpolation of `values` (laid out like the grid's) at `(theta, phi)` degrees;
    /// θ is clamped to the grid's range, φ wraps around. With `period`, values are angles
    /// interpolated on the circle (result in `(−period/2, period/2]`).
    fn interpolate(&self, values: &[f64], theta: f64, phi: f64, period: Option<f64>) -> f64 {
        let th = &self.theta_deg;
        let last = th.len() - 1;
        let (i0, i1, ft) = if theta <= th[0] {
            (0, 0, 0.0)
        } else if theta >= th[last] {
            (last, last, 0.0)
        } else {
            let i = th.partition_point(|&t| t <= theta) - 1;
            (i, i + 1, (theta - th[i]) / (th[i + 1] - th[i]))
        };
        let u = ((phi - self.phi0_deg) / self.phi_step_deg).rem_euclid(self.n_phi as f64);
        let j0 = (u.floor() as usize).min(self.n_phi - 1);
        let j1 = (j0 + 1) % self.n_phi;
        let fp = u - j0 as f64;
        let at = |i: usize, j: usize| values[i * self.n_phi + j];
        let corners = [
            (at(i0, j0), (1.0 - ft) * (1.0 - fp)),
            (at(i0, j1), (1.0 - ft) * fp),
            (at(i1, j0), ft * (1.0 - fp)),
            (at(i1, j1), ft * fp),
        ];
        match period {
            None => corners
                .iter()
                .filter(|(_, w)| *w > 0.0)
                .map(|(v, w)| v * w)
                .sum(),
            Some(p) => {
                let k = std::f64::consts::TAU / p;
                let (mut c, mut s) = (0.0, 0.0);
                for (v, w) in corners.iter().filter(|(_, w)| *w > 0.0) {
                    c += w * (k * v).cos();
                    s += w * (k * v).sin();
                }
                s.atan2(c) / k
            }
        }
    }
}

/// How values map to colours, and the colour bar's label.
#[derive(Debug, Clone, PartialEq)]
pub struct ColorScale {
    /// The colour map.
    pub colormap: Colormap,
    /// Value at the bottom of the colour bar (data units; > 0 for a log scale).
    pub min: f64,
    /// Value at the top of the colour bar.
    pub max: f64,
    /// Logarithmic (base 10) scale.
    pub log: bool,
    /// The values are angles with this period (e.g. 180 for AoLP in degrees): interpolated on
    /// the circle and wrapped into `(max − period, max]`.
    pub period: Option<f64>,
    /// Colour bar label, with the unit (e.g. `"DoLP"`, `"BRDF (sr⁻¹)"`, `"ΔAoLP (°)"`).
    pub label: String,
    /// Tick values; `None` for automatic ticks (1-2-5 steps, or decades on a log scale).
    pub ticks: Option<Vec<f64>>,
}

impl ColorScale {
    /// A linear scale over `[min, max]` with automatic ticks.
    pub fn linear(colormap: Colormap, min: f64, max: f64, label: impl Into<String>) -> Self {
        Self {
            colormap,
            min,
            max,
            log: false,
            period: None,
            label: label.into(),
            ticks: None,
        }
    }

    /// A log10 scale over `[min, max]` (both > 0) with ticks at decades.
    pub fn log10(colormap: Colormap, min: f64, max: f64, label: impl Into<String>) -> Self {
        Self {
            log: true,
            ..Self::linear(colormap, min, max, label)
        }
    }

    /// Maps a value to the data space where interpolation happens (log10 for a log scale;
    /// non-positive values go below the bottom of the bar).
    pub(crate) fn forward(&self, v: f64) -> f64 {
        if !self.log {
            return v;
        }
        if v > 0.0 {
            v.log10()
        } else if v.is_nan() {
            v
        } else {
            self.min.log10() - 1.0
        }
    }

    /// Position `t` on the colour bar (0 bottom, 1 top; outside for values beyond the limits)
    /// of a value in interpolation space.
    pub(crate) fn position(&self, x: f64) -> f64 {
        let (lo, hi) = (self.forward(self.min), self.forward(self.max));
        let x = match self.period {
            Some(p) => hi - (hi - x).rem_euclid(p),
            None => x,
        };
        (x - lo) / (hi - lo)
    }

    /// Position on the colour bar of a tick value (no wrapping).
    fn tick_position(&self, v: f64) -> f64 {
        let (lo, hi) = (self.forward(self.min), self.forward(self.max));
        (self.forward(v) - lo) / (hi - lo)
    }

    /// Position on the colour bar of a data value (0 bottom, 1 top; clamped when drawn).
    pub fn t(&self, v: f64) -> f64 {
        self.position(self.forward(v))
    }

    /// The colour a data value is drawn with.
    pub fn color(&self, v: f64) -> RGBColor {
        self.colormap.rgb(self.t(v))
    }

    /// Ticks as (position on the bar, label).
    fn tick_marks(&self) -> Vec<(f64, String)> {
        if let Some(ticks) = &self.ticks {
            return ticks
                .iter()
                .map(|&v| (self.tick_position(v), format_number(v, tick_step(ticks))))
                .filter(|(t, _)| (-1e-9..=1.0 + 1e-9).contains(t))
                .collect();
        }
        if self.log {
            let (lo, hi) = (self.min.log10(), self.max.log10());
            let (k0, k1) = (lo.ceil() as i32, hi.floor() as i32);
            let mut out = Vec::new();
            let mults: &[f64] = if k1 - k0 <= 2 {
                &[1.0, 2.0, 5.0]
            } else {
                &[1.0]
            };
            let stride = ((k1 - k0) / 6 + 1).max(1);
            for k in (k0 - 1)..=(k1 + 1) {
                for &m in mults {
                    if m == 1.0 && (k - k0).rem_euclid(stride) != 0 {
                        continue;
                    }
                    let v = m * 10f64.powi(k);
                    let x = v.log10();
                    if x >= lo - 1e-9 && x <= hi + 1e-9 {
                        out.push(((x - lo) / (hi - lo), log_label(m, k)));
                    }
                }
            }
            return out;
        }
        let step = nice_step((self.max - self.min) / 8.0);
        let first = (self.min / step - 1e-9).ceil() as i64;
        let last = (self.max / step + 1e-9).floor() as i64;
        (first..=last)
            .map(|k| {
                let v = k as f64 * step;
                (self.tick_position(v), format_number(v, step))
            })
            .collect()
    }
}

/// A 1-2-2.5-5 step at least `raw`.
fn nice_step(raw: f64) -> f64 {
    if !(raw.is_finite() && raw > 0.0) {
        return 1.0;
    }
    let mag = 10f64.powf(raw.log10().floor());
    for m in [1.0, 2.0, 2.5, 5.0, 10.0] {
        if m * mag >= raw * (1.0 - 1e-9) {
            return m * mag;
        }
    }
    10.0 * mag
}

/// The smallest of 1, 1.2, 1.5, 2, 2.5, 3, 4, 5, 6, 8, 10 times a power of ten that is ≥ `x`
/// (for colour limits); 1 for non-positive or non-finite `x`.
pub fn nice_ceil(x: f64) -> f64 {
    if !(x.is_finite() && x > 0.0) {
        return 1.0;
    }
    let mag = 10f64.powf(x.log10().floor());
    for m in [1.0, 1.2, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0] {
        if m * mag >= x * (1.0 - 1e-12) {
            return m * mag;
        }
    }
    10.0 * mag
}

fn tick_step(ticks: &[f64]) -> f64 {
    ticks
        .windows(2)
        .map(|w| (w[1] - w[0]).abs())
        .fold(f64::INFINITY, f64::min)
}

/// `v` with as many decimals as `step` needs, and a real minus sign.
fn format_number(v: f64, step: f64) -> String {
    let decimals = if step.is_finite() && step > 0.0 {
        let mut d = 0usize;
        while d < 6
            && ((step * 10f64.powi(d as i32)).round() - step * 10f64.powi(d as i32)).abs() > 1e-6
        {
            d += 1;
        }
        d
    } else {
        2
    };
    let s = format!("{:.*}", decimals, v + 0.0);
    if let Some(rest) = s.strip_prefix('-') {
        if rest.chars().all(|c| c == '0' || c == '.') {
            rest.to_string()
        } else {
            format!("−{rest}")
        }
    } else {
        s
    }
}

const SUPERSCRIPTS: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];

fn log_label(m: f64, k: i32) -> String {
    if (-2..=2).contains(&k) {
        let v = m * 10f64.powi(k);
        return format_number(v, 10f64.powi(k.min(0)));
    }
    let mut p = String::from("10");
    if k < 0 {
        p.push('⁻');
    }
    for c in k.unsigned_abs().to_string().chars() {
        p.push(SUPERSCRIPTS[c.to_digit(10).unwrap_or(0) as usize]);
    }
    if m == 1.0 {
        p
    } else {
        format!("{m}×{p}")
    }
}

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
fn raster(p: &PolarPanel, disk: &Disk) -> Raster {
    let x0 = (disk.cx - disk.r).floor() as i64 - 1;
    let y0 = (disk.cy - disk.r).floor() as i64 - 1;
    let side = (2.0 * disk.r).ceil() as u32 + 3;
    let values: Vec<f64> = p.grid.values.iter().map(|&v| p.scale.forward(v)).collect();
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

pub(crate) fn font(size: f64) -> TextStyle<'static> {
    TextStyle::from((FAMILY, size).into_font()).color(&BLACK)
}

pub(crate) fn centered(size: f64) -> TextStyle<'static> {
    font(size).pos(Pos::new(HPos::Center, VPos::Center))
}

pub(crate) fn pt(x: f64, y: f64) -> (i32, i32) {
    (x.round() as i32, y.round() as i32)
}

fn draw_mark<DB: DrawingBackend>(
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

/// Text on a white box, for labels drawn over the map.
fn boxed_text<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    text: &str,
    (x, y): (f64, f64),
    size: f64,
) -> DrawResult
where
    DB::ErrorType: 'static,
{
    let style = centered(size);
    let (tw, th) = root.estimate_text_size(text, &style)?;
    let (hw, hh) = (f64::from(tw) / 2.0 + 3.0, f64::from(th) / 2.0 + 1.0);
    root.draw(&Rectangle::new(
        [pt(x - hw, y - hh), pt(x + hw, y + hh)],
        WHITE.mix(0.8).filled(),
    ))?;
    root.draw(&Text::new(text.to_string(), pt(x, y), style))?;
    Ok(())
}

fn draw_panel_overlay<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    p: &PolarPanel,
    (ox, oy): (f64, f64),
    (w, h): (u32, u32),
    disk: &Disk,
) -> DrawResult
where
    DB::ErrorType: 'static,
{
    let (w, h) = (f64::from(w), f64::from(h));
    // Title.
    root.draw(&Text::new(
        p.title.clone(),
        pt(ox + w / 2.0, oy + TITLE_H / 2.0 + 2.0),
        centered(21.0),
    ))?;

    // Polar grid: circles at θ = 30°, 60°, spokes every 30°, the rim (θ = 90°).
    // Each grid line is a light halo under a dark line, so it shows on dark and light colours.
    let halo = ShapeStyle::from(&WHITE.mix(0.25)).stroke_width(3);
    let grid = ShapeStyle::from(&RGBColor(20, 20, 20).mix(0.55)).stroke_width(1);
    for style in [halo, grid] {
        for theta in [30.0, 60.0] {
            root.draw(&Circle::new(
                pt(disk.cx, disk.cy),
                (disk.r * theta / 90.0).round() as i32,
                style,
            ))?;
        }
        for k in 0..12 {
            let phi = 30.0 * f64::from(k);
            let (x0, y0) = disk.position(30.0 / 8.0, phi);
            let (x1, y1) = disk.position(90.0, phi);
            root.draw(&PathElement::new(vec![pt(x0, y0), pt(x1, y1)], style))?;
        }
    }
    for k in 0..12 {
        let phi = 30.0 * f64::from(k);
        let (lx, ly) = disk.position(90.0 * (disk.r + 20.0) / disk.r, phi);
        root.draw(&Text::new(format!("{phi:.0}°"), pt(lx, ly), centered(15.0)))?;
    }
    root.draw(&Circle::new(
        pt(disk.cx, disk.cy),
        disk.r.round() as i32,
        ShapeStyle::from(&BLACK).stroke_width(2),
    ))?;
    for theta in [30.0, 60.0] {
        let (x, y) = disk.position(theta, 285.0);
        boxed_text(root, &format!("{theta:.0}°"), (x, y), 13.0)?;
    }

    // Marks, then their labels.
    for m in &p.marks {
        draw_mark(root, m.shape, disk.position(m.theta_deg, m.phi_deg))?;
    }
    for m in &p.marks {
        if !m.label.is_empty() {
            let (x, y) = disk.position(m.theta_deg, m.phi_deg);
            boxed_text(root, &m.label, (x + 16.0, y - 14.0), 13.0)?;
        }
    }

    // Colour bar.
    let bx = ox + w - BAR_AREA_W + 8.0;
    draw_color_bar(
        root,
        &p.scale,
        bx,
        (disk.cy - disk.r, disk.cy + disk.r),
        ox + w - 12.0,
    )?;

    // Legend: one entry per distinct legend text, then how to read the axes.
    let ly = oy + h - LEGEND_H / 2.0 - 2.0;
    let mut x = ox + 14.0;
    let text_style = font(14.0).pos(Pos::new(HPos::Left, VPos::Center));
    let mut seen: Vec<&str> = Vec::new();
    for m in &p.marks {
        if m.legend.is_empty() || seen.contains(&m.legend.as_str()) {
            continue;
        }
        seen.push(&m.legend);
        draw_mark(root, m.shape, (x + 16.0, ly))?;
        root.draw(&Text::new(
            m.legend.clone(),
            pt(x + 36.0, ly),
            text_style.clone(),
        ))?;
        let (tw, _) = root.estimate_text_size(&m.legend, &text_style)?;
        x += 36.0 + f64::from(tw) + 16.0;
    }
    let axes = "radius θr, angle φr";
    let (tw, _) = root.estimate_text_size(axes, &text_style)?;
    let ax = ox + w - 10.0 - f64::from(tw);
    if ax < x {
        return Ok(()); // no room left beside the legend
    }
    root.draw(&Text::new(
        axes.to_string(),
        pt(ax, ly),
        font(14.0)
            .color(&RGBColor(90, 90, 90))
            .pos(Pos::new(HPos::Left, VPos::Center)),
    ))?;
    Ok(())
}

/// A vertical colour bar of `scale` with its ticks and its rotated label: the bar's left edge at
/// `bx`, spanning `top` to `bottom` (pixels, y downward); the label no further right than
/// `right_limit`. Shared by the polar maps and the images ([`crate::heatmap`]).
pub(crate) fn draw_color_bar<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    scale: &ColorScale,
    bx: f64,
    (top, bottom): (f64, f64),
    right_limit: f64,
) -> DrawResult
where
    DB::ErrorType: 'static,
{
    let bw = 20.0;
    let height = bottom - top;
    let (it, ib) = (top.round() as i32, bottom.round() as i32);
    for yy in it..ib {
        let t = 1.0 - (f64::from(yy - it) + 0.5) / f64::from(ib - it);
        root.draw(&Rectangle::new(
            [(bx as i32, yy), ((bx + bw) as i32, yy + 1)],
            scale.colormap.rgb(t).filled(),
        ))?;
    }
    root.draw(&Rectangle::new(
        [(bx as i32, it), ((bx + bw) as i32, ib)],
        ShapeStyle::from(&BLACK).stroke_width(1),
    ))?;
    let tick_style = font(14.0).pos(Pos::new(HPos::Left, VPos::Center));
    let mut widest = 0u32;
    for (t, label) in scale.tick_marks() {
        widest = widest.max(root.estimate_text_size(&label, &tick_style)?.0);
        let y = bottom - t.clamp(0.0, 1.0) * height;
        root.draw(&PathElement::new(
            vec![pt(bx + bw, y), pt(bx + bw + 5.0, y)],
            ShapeStyle::from(&BLACK).stroke_width(1),
        ))?;
        root.draw(&Text::new(label, pt(bx + bw + 8.0, y), tick_style.clone()))?;
    }
    let label_style = TextStyle::from(
        (FAMILY, 16.0)
            .into_font()
            .transform(FontTransform::Rotate270),
    )
    .color(&BLACK)
    .pos(Pos::new(HPos::Center, VPos::Center));
    root.draw(&Text::new(
        scale.label.clone(),
        pt(
            (bx + bw + 8.0 + f64::from(widest) + 14.0).min(right_limit),
            0.5 * (top + bottom),
        ),
        label_style,
    ))?;
    Ok(())
}
