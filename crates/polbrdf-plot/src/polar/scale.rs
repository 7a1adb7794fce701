//! Colour scales: how values map to colours (linear, log10 or periodic) and the ticks and
//! labels of the colour bar.

use crate::colormap::Colormap;
use plotters::style::RGBColor;

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
    pub(super) fn tick_marks(&self) -> Vec<(f64, String)> {
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

/// The smallest gap between consecutive `ticks` (how many decimals their labels need).
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

/// The superscript digits 0–9.
/// The label of the log-scale tick `m·10^k`: a plain number for |k| ≤ 2, else a power of ten
/// with superscripts (`m×` in front unless `m` = 1).
fn log_label(m: f64, k: i32) -> String {
    if (-2..=2).contains(&k) {
        let v = m * 10f64.powi(k);
        return format_number(v, 10f64.powi(k.min(0)));
    }
    let p = crate::chart::power_of_ten(k);
    if m == 1.0 {
        p
    } else {
        format!("{m}×{p}")
    }
}
