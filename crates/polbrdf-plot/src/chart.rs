//! Line charts: a small declarative layer over `plotters` (moved here from `polbrdf-reproduce`),
//! drawn once into a PNG (bitmap backend, text rendered with the embedded DejaVu Sans through
//! `ab_glyph`) and once into an SVG.

use crate::encode::{draw_err, encode_png};
use crate::error::Result;
use crate::font::FAMILY;
use plotters::coord::Shift;
use plotters::prelude::*;

/// The result of drawing (`T`: what a step reports besides success).
type PlotResult<T = ()> = std::result::Result<T, Box<dyn std::error::Error + Send + Sync>>;

/// Distinct colours (Matplotlib's "tab10").
pub const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

/// One line.
#[derive(Debug, Clone)]
pub struct Line {
    /// Legend text (empty: no legend entry).
    pub label: String,
    /// Points in data coordinates.
    pub points: Vec<(f64, f64)>,
    /// Colour.
    pub color: RGBColor,
    /// Dashed instead of solid.
    pub dashed: bool,
    /// Stroke width in pixels.
    pub width: u32,
}

/// Marker shapes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Marker {
    /// Filled disc.
    Disc,
    /// Open square (drawn around a coinciding disc, so both stay visible).
    Square,
}

/// A set of markers.
#[derive(Debug, Clone)]
pub struct Markers {
    /// Legend text (empty: no legend entry).
    pub label: String,
    /// Points in data coordinates.
    pub points: Vec<(f64, f64)>,
    /// Colour of each point (one per point).
    pub colors: Vec<RGBColor>,
    /// Colour of the legend sample.
    pub legend_color: RGBColor,
    /// Shape.
    pub marker: Marker,
}

/// Where the legend goes.
#[derive(Debug, Clone, Copy)]
pub enum LegendAt {
    /// Upper left corner.
    UpperLeft,
    /// Upper right corner.
    UpperRight,
    /// Lower left corner.
    LowerLeft,
    /// Right edge, half way up.
    MiddleRight,
}

/// One chart.
#[derive(Debug, Clone)]
pub struct Panel {
    /// Caption above the chart.
    pub title: String,
    /// x axis description (with unit).
    pub x_desc: String,
    /// y axis description (with unit).
    pub y_desc: String,
    /// x range.
    pub x_range: (f64, f64),
    /// y range (in log10 units when `log_y`).
    pub y_range: (f64, f64),
    /// y data are log10 of the quantity; ticks are labelled as powers of ten.
    pub log_y: bool,
    /// A logarithmic x axis (data and range as they are, > 0), e.g. wavelength; labels at 1, 2
    /// and 5 times the powers of ten.
    pub log_x: bool,
    /// Approximate number of x tick labels.
    pub x_ticks: usize,
    /// Approximate number of y tick labels.
    pub y_ticks: usize,
    /// Lines.
    pub lines: Vec<Line>,
    /// Marker sets.
    pub markers: Vec<Markers>,
    /// Vertical reference lines: x, label.
    pub vlines: Vec<(f64, String)>,
    /// Legend position.
    pub legend: LegendAt,
}

/// A figure of one or more panels side by side.
#[derive(Debug, Clone)]
pub struct Figure {
    /// Pixel size of the PNG (the SVG uses the same user units).
    pub size: (u32, u32),
    /// Panels, left to right.
    pub panels: Vec<Panel>,
}

/// `10ⁿ` with Unicode superscripts.
pub fn power_of_ten(k: i32) -> String {
    const SUP: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let mut s = String::from("10");
    if k < 0 {
        s.push('⁻');
    }
    for c in k.unsigned_abs().to_string().chars() {
        s.push(SUP[c.to_digit(10).unwrap_or(0) as usize]);
    }
    s
}

/// Lines are drawn through at most this many points: wide strokes through one point per pixel
/// come out jagged in the bitmap backend. The CSV files keep every point.
const MAX_LINE_POINTS: usize = 200;

/// Every k-th point (and the last), keeping at most about `max` points.
fn decimate(points: &[(f64, f64)], max: usize) -> Vec<(f64, f64)> {
    if points.len() <= max {
        return points.to_vec();
    }
    let k = points.len().div_ceil(max);
    let mut out: Vec<(f64, f64)> = points.iter().step_by(k).copied().collect();
    if let Some(&last) = points.last() {
        if out.last() != Some(&last) {
            out.push(last);
        }
    }
    out
}

fn draw_panel<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, p: &Panel) -> PlotResult
where
    DB::ErrorType: 'static,
{
    let mut builder = ChartBuilder::on(area);
    builder
        .caption(&p.title, (FAMILY, 24))
        .margin(14)
        .margin_right(28)
        .x_label_area_size(62)
        .y_label_area_size(if p.log_y { 92 } else { 82 });
    let (x, y) = (p.x_range.0..p.x_range.1, p.y_range.0..p.y_range.1);
    if p.log_x {
        draw_chart(builder.build_cartesian_2d(LogAxis(x), y)?, p)
    } else {
        draw_chart(builder.build_cartesian_2d(x, y)?, p)
    }
}

/// A logarithmic axis with labels at 1, 2 and 5 times the powers of ten and light grid lines at
/// every integer multiple, over the whole range (plotters' own log axis starts its ticks at the
/// first power of ten inside the range, leaving e.g. 0.4–1 µm bare).
struct LogAxis(std::ops::Range<f64>);

impl Ranged for LogAxis {
    type FormatOption = plotters::coord::ranged1d::DefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        let (lo, hi) = (self.0.start.ln(), self.0.end.ln());
        let t = (value.ln() - lo) / (hi - lo);
        limit.0 + (t * f64::from(limit.1 - limit.0)).round() as i32
    }

    fn key_points<H: plotters::coord::ranged1d::KeyPointHint>(&self, hint: H) -> Vec<f64> {
        let mantissas: &[f64] = if hint.weight().allow_light_points() {
            &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0]
        } else {
            &[1.0, 2.0, 5.0]
        };
        let (lo, hi) = (self.0.start, self.0.end);
        let mut out = Vec::new();
        for d in lo.log10().floor() as i32..=hi.log10().ceil() as i32 {
            for m in mantissas {
                let v = m * 10f64.powi(d);
                if v >= lo * (1.0 - 1e-12) && v <= hi * (1.0 + 1e-12) {
                    out.push(v);
                }
            }
        }
        if out.len() > hint.max_num_points() {
            out.retain(|v| (v.log10() - v.log10().round()).abs() < 1e-9);
        }
        out
    }

    fn range(&self) -> std::ops::Range<f64> {
        self.0.clone()
    }
}

/// The chart type both axes' constructions give: any x axis over `f64`, a linear y axis.
type Chart<'a, DB, X> =
    ChartContext<'a, DB, Cartesian2d<X, plotters::coord::types::RangedCoordf64>>;

/// Everything but the axes' construction: the same for a linear and a logarithmic x axis. The
/// layers in drawing order: the mesh, the vertical reference lines, the lines, the markers and
/// the legend (when any line or marker set has a label).
fn draw_chart<'a, DB: DrawingBackend + 'a, X>(mut chart: Chart<'a, DB, X>, p: &Panel) -> PlotResult
where
    DB::ErrorType: 'static,
    X: Ranged<ValueType = f64> + plotters::coord::ranged1d::ValueFormatter<f64>,
{
    draw_mesh(&mut chart, p)?;
    draw_vlines(&mut chart, p)?;
    let lines_labelled = draw_lines(&mut chart, p)?;
    let markers_labelled = draw_markers(&mut chart, p)?;
    if lines_labelled || markers_labelled {
        draw_legend(&mut chart, p.legend)?;
    }
    Ok(())
}

/// The y tick label of `v`: a power of ten at the integers of a log axis (none between them),
/// else the value with at most three decimals and no trailing zeros (never "-0").
fn y_tick_label(v: f64, log_y: bool) -> String {
    if log_y {
        let k = v.round();
        if (v - k).abs() < 1e-9 {
            power_of_ten(k as i32)
        } else {
            String::new()
        }
    } else {
        let s = format!("{v:.3}");
        let s = s.trim_end_matches('0').trim_end_matches('.').to_string();
        if s == "-0" {
            "0".into()
        } else {
            s
        }
    }
}

/// The x tick label of `v`: at most two decimals, no trailing zeros.
fn x_tick_label(v: f64) -> String {
    let s = format!("{v:.2}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// The axes, their descriptions and tick labels, and the light and bold grid lines.
fn draw_mesh<'a, DB: DrawingBackend + 'a, X>(chart: &mut Chart<'a, DB, X>, p: &Panel) -> PlotResult
where
    DB::ErrorType: 'static,
    X: Ranged<ValueType = f64> + plotters::coord::ranged1d::ValueFormatter<f64>,
{
    let y_fmt = |v: &f64| y_tick_label(*v, p.log_y);
    let x_fmt = |v: &f64| x_tick_label(*v);
    chart
        .configure_mesh()
        .x_desc(&p.x_desc)
        .y_desc(&p.y_desc)
        .x_labels(p.x_ticks)
        .y_labels(p.y_ticks)
        .x_label_formatter(&x_fmt)
        .y_label_formatter(&y_fmt)
        .axis_desc_style((FAMILY, 22))
        .label_style((FAMILY, 18))
        .light_line_style(RGBColor(235, 235, 235))
        .bold_line_style(RGBColor(200, 200, 200))
        .draw()?;
    Ok(())
}

/// The vertical reference lines (dashed, over the whole y range), each with its label near the
/// top.
fn draw_vlines<'a, DB: DrawingBackend + 'a, X>(
    chart: &mut Chart<'a, DB, X>,
    p: &Panel,
) -> PlotResult
where
    DB::ErrorType: 'static,
    X: Ranged<ValueType = f64> + plotters::coord::ranged1d::ValueFormatter<f64>,
{
    for (x, label) in &p.vlines {
        let (y0, y1) = p.y_range;
        chart.draw_series(DashedLineSeries::new(
            [(*x, y0), (*x, y1)],
            8,
            6,
            ShapeStyle::from(&BLACK.mix(0.6)).stroke_width(2),
        ))?;
        chart.draw_series(std::iter::once(Text::new(
            label.clone(),
            (*x, y1 - 0.03 * (y1 - y0)),
            (FAMILY, 18).into_font().color(&BLACK.mix(0.8)),
        )))?;
    }
    Ok(())
}

/// The lines (decimated to [`MAX_LINE_POINTS`]), solid or dashed, with a legend sample for each
/// labelled one; whether any line has a label.
fn draw_lines<'a, DB: DrawingBackend + 'a, X>(
    chart: &mut Chart<'a, DB, X>,
    p: &Panel,
) -> PlotResult<bool>
where
    DB::ErrorType: 'static,
    X: Ranged<ValueType = f64> + plotters::coord::ranged1d::ValueFormatter<f64>,
{
    let mut any_label = false;
    for l in &p.lines {
        let style = ShapeStyle::from(&l.color).stroke_width(l.width);
        let points = decimate(&l.points, MAX_LINE_POINTS);
        let anno = if l.dashed {
            chart.draw_series(DashedLineSeries::new(points, 10, 6, style))?
        } else {
            chart.draw_series(LineSeries::new(points, style))?
        };
        if !l.label.is_empty() {
            any_label = true;
            let dashed = l.dashed;
            anno.label(&l.label).legend(move |(x, y)| {
                if dashed {
                    EmptyElement::at((x, y))
                        + PathElement::new(vec![(0, 0), (9, 0)], style)
                        + PathElement::new(vec![(14, 0), (24, 0)], style)
                } else {
                    // Same element type as the dashed branch: a full segment plus an empty one.
                    EmptyElement::at((x, y))
                        + PathElement::new(vec![(0, 0), (24, 0)], style)
                        + PathElement::new(vec![(24, 0), (24, 0)], style)
                }
            });
        }
    }
    Ok(any_label)
}

/// The marker sets (discs or open squares, one colour per point), with a legend sample for
/// each labelled set; whether any set has a label.
fn draw_markers<'a, DB: DrawingBackend + 'a, X>(
    chart: &mut Chart<'a, DB, X>,
    p: &Panel,
) -> PlotResult<bool>
where
    DB::ErrorType: 'static,
    X: Ranged<ValueType = f64> + plotters::coord::ranged1d::ValueFormatter<f64>,
{
    let mut any_label = false;
    for m in &p.markers {
        let shape = m.marker;
        let pts = m.points.iter().zip(&m.colors);
        let anno = match shape {
            Marker::Disc => {
                chart.draw_series(pts.map(|(&(x, y), &c)| Circle::new((x, y), 5, c.filled())))?
            }
            Marker::Square => chart.draw_series(pts.map(|(&(x, y), &c)| {
                EmptyElement::at((x, y))
                    + Rectangle::new([(-8, -8), (8, 8)], ShapeStyle::from(&c).stroke_width(2))
            }))?,
        };
        if !m.label.is_empty() {
            any_label = true;
            let c = m.legend_color;
            let anno = anno.label(&m.label);
            match shape {
                Marker::Disc => {
                    anno.legend(move |(x, y)| {
                        EmptyElement::at((x + 12, y)) + Circle::new((0, 0), 5, c.filled())
                    });
                }
                Marker::Square => {
                    anno.legend(move |(x, y)| {
                        EmptyElement::at((x + 12, y))
                            + Rectangle::new(
                                [(-8, -8), (8, 8)],
                                ShapeStyle::from(&c).stroke_width(2),
                            )
                    });
                }
            }
        }
    }
    Ok(any_label)
}

/// The legend of the labelled lines and marker sets, on a light box at `at`.
fn draw_legend<'a, DB: DrawingBackend + 'a, X>(
    chart: &mut Chart<'a, DB, X>,
    at: LegendAt,
) -> PlotResult
where
    DB::ErrorType: 'static,
    X: Ranged<ValueType = f64> + plotters::coord::ranged1d::ValueFormatter<f64>,
{
    let pos = match at {
        LegendAt::UpperLeft => SeriesLabelPosition::UpperLeft,
        LegendAt::UpperRight => SeriesLabelPosition::UpperRight,
        LegendAt::LowerLeft => SeriesLabelPosition::LowerLeft,
        LegendAt::MiddleRight => SeriesLabelPosition::MiddleRight,
    };
    chart
        .configure_series_labels()
        .position(pos)
        .margin(12)
        .legend_area_size(34)
        .label_font((FAMILY, 18))
        .background_style(WHITE.mix(0.88))
        .border_style(RGBColor(120, 120, 120))
        .draw()?;
    Ok(())
}

fn draw_figure<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, fig: &Figure) -> PlotResult
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE)?;
    let areas = root.split_evenly((1, fig.panels.len().max(1)));
    for (area, panel) in areas.iter().zip(&fig.panels) {
        draw_panel(area, panel)?;
    }
    root.present()?;
    Ok(())
}

impl Figure {
    /// The figure as a PNG file (RGB, drawn in memory).
    ///
    /// # Errors
    /// [`crate::Error::Font`], [`crate::Error::Draw`] or [`crate::Error::Encode`].
    pub fn png(&self) -> Result<Vec<u8>> {
        crate::font::register()?;
        let (w, h) = self.size;
        let mut rgb = vec![0u8; (w as usize) * (h as usize) * 3];
        {
            let root = BitMapBackend::with_buffer(&mut rgb, self.size).into_drawing_area();
            draw_figure(&root, self).map_err(draw_err)?;
        }
        encode_png(&rgb, w, h)
    }

    /// The figure as an SVG document.
    ///
    /// # Errors
    /// [`crate::Error::Font`] or [`crate::Error::Draw`].
    pub fn svg(&self) -> Result<String> {
        crate::font::register()?;
        let mut text = String::new();
        {
            let root = SVGBackend::with_string(&mut text, self.size).into_drawing_area();
            draw_figure(&root, self).map_err(draw_err)?;
        }
        Ok(text)
    }
}
