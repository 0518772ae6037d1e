//! SVG charts for the tour, the examples and the pareto bench, drawn by plotters' SVG
//! backend: line and marker series with a legend, axis labels, linear or log axes,
//! labelled horizontal reference lines, small multiples on one page, and snapshots of a
//! 2D particle network.
//!
//! ```no_run
//! use lab::plot::{Plot, Series};
//! let points = (0..100).map(|n| (n as f64 * 0.01, (n as f64 * 0.1).sin()));
//! Plot::new("Step response")
//!     .x_label("time [s]")
//!     .y_label("position")
//!     .series(Series::line("f32", points))
//!     .hline(1.0, "target")
//!     .write(std::path::Path::new("target/plots/step.svg"))
//!     .expect("written");
//! ```
//!
//! Points that cannot be drawn (not finite, or not positive on a log axis) are left out.
//! Text goes into the SVG as `<text>` in a sans-serif font, laid out by the viewer: no
//! font is read when drawing, so nothing here needs fontconfig or freetype.

use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// The Okabe–Ito colour-blind-safe palette, in the order series get them (yellow, faint
/// on white, last).
pub const PALETTE: [RGBColor; 8] = [
    RGBColor(0x00, 0x72, 0xB2), // blue
    RGBColor(0xD5, 0x5E, 0x00), // vermillion
    RGBColor(0x00, 0x9E, 0x73), // bluish green
    RGBColor(0xE6, 0x9F, 0x00), // orange
    RGBColor(0x56, 0xB4, 0xE9), // sky blue
    RGBColor(0xCC, 0x79, 0xA7), // reddish purple
    RGBColor(0x00, 0x00, 0x00), // black
    RGBColor(0xF0, 0xE4, 0x42), // yellow
];

/// Sizes below are in plotters' points; the SVG gets pixels, `pt/1.24`.
const FONT: FontFamily<'static> = FontFamily::SansSerif;
const TEXT: RGBColor = RGBColor(0x33, 0x33, 0x33);
const GRID: RGBColor = RGBColor(0xE4, 0xE4, 0xE4);
const REFERENCE: RGBColor = RGBColor(0x70, 0x70, 0x70);

/// How a series is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Style {
    /// A line through the points.
    Line,
    /// A dot at each point.
    Markers,
}

/// One named data series.
#[derive(Clone, Debug)]
pub struct Series {
    /// The name in the legend.
    pub name: String,
    /// The points, in drawing order.
    pub points: Vec<(f64, f64)>,
    /// Line or markers.
    pub style: Style,
    /// Draw the line dashed.
    pub dashed: bool,
    /// A short text beside each point (empty: none), in the series' colour.
    pub labels: Vec<String>,
}

impl Series {
    fn new(
        name: impl Into<String>,
        points: impl IntoIterator<Item = (f64, f64)>,
        style: Style,
    ) -> Self {
        Series {
            name: name.into(),
            points: points.into_iter().collect(),
            style,
            dashed: false,
            labels: Vec::new(),
        }
    }

    /// A line through `points`.
    pub fn line(name: impl Into<String>, points: impl IntoIterator<Item = (f64, f64)>) -> Self {
        Self::new(name, points, Style::Line)
    }

    /// A dot at each of `points`.
    pub fn markers(name: impl Into<String>, points: impl IntoIterator<Item = (f64, f64)>) -> Self {
        Self::new(name, points, Style::Markers)
    }

    /// The line dashed.
    pub fn dashed(mut self) -> Self {
        self.dashed = true;
        self
    }

    /// Labels the points, one text per point in order (a scatter plot of named things).
    pub fn labels(mut self, labels: impl IntoIterator<Item = impl Into<String>>) -> Self {
        self.labels = labels.into_iter().map(Into::into).collect();
        self
    }
}

/// A chart of one or more series.
#[derive(Clone, Debug)]
pub struct Plot {
    /// The caption above the chart.
    pub title: String,
    /// The label under the x axis.
    pub x_label: String,
    /// The label beside the y axis.
    pub y_label: String,
    /// A logarithmic x axis.
    pub x_log: bool,
    /// A logarithmic y axis.
    pub y_log: bool,
    /// The series, drawn in order.
    pub series: Vec<Series>,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Horizontal reference lines (a target, a tolerance), drawn dashed, in the legend.
    pub hlines: Vec<(f64, String)>,
    /// A fixed y range; `None` fits the data.
    pub y_range: Option<(f64, f64)>,
}

impl Plot {
    /// An empty 640 × 400 chart.
    pub fn new(title: impl Into<String>) -> Self {
        Plot {
            title: title.into(),
            x_label: String::new(),
            y_label: String::new(),
            x_log: false,
            y_log: false,
            series: Vec::new(),
            width: 640,
            height: 400,
            hlines: Vec::new(),
            y_range: None,
        }
    }

    /// The x axis label.
    pub fn x_label(mut self, label: impl Into<String>) -> Self {
        self.x_label = label.into();
        self
    }

    /// The y axis label.
    pub fn y_label(mut self, label: impl Into<String>) -> Self {
        self.y_label = label.into();
        self
    }

    /// A logarithmic x axis.
    pub fn log_x(mut self) -> Self {
        self.x_log = true;
        self
    }

    /// A logarithmic y axis.
    pub fn log_y(mut self) -> Self {
        self.y_log = true;
        self
    }

    /// Adds a series.
    pub fn series(mut self, series: Series) -> Self {
        self.series.push(series);
        self
    }

    /// Adds a dashed horizontal line at `y`, named `label` in the legend.
    pub fn hline(mut self, y: f64, label: impl Into<String>) -> Self {
        self.hlines.push((y, label.into()));
        self
    }

    /// The size in pixels.
    pub fn size(mut self, width: u32, height: u32) -> Self {
        self.width = width;
        self.height = height;
        self
    }

    /// Fixes the y range (points outside it are clipped).
    pub fn y_range(mut self, lo: f64, hi: f64) -> Self {
        self.y_range = Some((lo, hi));
        self
    }

    /// A standalone SVG document.
    pub fn render(&self) -> String {
        svg(self.width, self.height, |root| self.draw(root))
    }

    /// Writes [`Plot::render`] to `path`, creating its parent directories.
    pub fn write(&self, path: &Path) -> std::io::Result<()> {
        write_file(path, &self.render())
    }

    fn drawable(&self, (x, y): (f64, f64)) -> bool {
        x.is_finite() && y.is_finite() && (!self.x_log || x > 0.0) && (!self.y_log || y > 0.0)
    }

    /// A point in the chart's coordinates: a log axis is drawn as `log₁₀` of the value,
    /// on a linear scale, so that its ticks can be whole decades.
    fn to_chart(&self, (x, y): (f64, f64)) -> (f64, f64) {
        (
            if self.x_log { x.log10() } else { x },
            if self.y_log { y.log10() } else { y },
        )
    }

    /// The drawable points of `series`, in chart coordinates, with their indices.
    fn chart_points<'a>(
        &'a self,
        series: &'a Series,
    ) -> impl Iterator<Item = (usize, (f64, f64))> + 'a {
        series
            .points
            .iter()
            .enumerate()
            .filter(|&(_, &p)| self.drawable(p))
            .map(|(k, &p)| (k, self.to_chart(p)))
    }

    /// The x and y ranges in chart coordinates: the data's (and the reference lines'),
    /// widened a little on a linear axis and out to whole decades on a log one.
    fn ranges(&self) -> ((f64, f64), (f64, f64)) {
        let (mut x, mut y) = (Span::default(), Span::default());
        for s in &self.series {
            for (_, (px, py)) in self.chart_points(s) {
                x.add(px);
                y.add(py);
            }
        }
        for &(h, _) in &self.hlines {
            if h.is_finite() && (!self.y_log || h > 0.0) {
                y.add(self.to_chart((1.0, h)).1);
            }
        }
        let x = x.axis(self.x_log);
        let y = match self.y_range {
            Some((lo, hi)) if self.y_log => (lo.log10(), hi.log10()),
            Some(r) => r,
            None => y.axis(self.y_log),
        };
        (x, y)
    }

    fn draw(&self, area: &DrawingArea<SVGBackend<'_>, Shift>) -> DrawResult {
        let ((x0, x1), (y0, y1)) = self.ranges();
        // Whole decades on a log axis: one label a decade up to ten, else a nice step of
        // decades (plotters picks 1-2-5 steps, whole numbers at these counts).
        let labels = |log: bool, lo: f64, hi: f64| {
            if log && hi - lo <= 10.0 {
                (hi - lo).round() as usize + 1
            } else {
                6
            }
        };
        let value = |log: bool, v: f64, span: f64| {
            if log {
                fmt_num(10f64.powf(v))
            } else {
                fmt_num(snap(v, span))
            }
        };
        let mut chart = ChartBuilder::on(area)
            .caption(&self.title, (FONT, 19).into_font().color(&TEXT))
            .margin(10)
            .x_label_area_size(if self.x_label.is_empty() { 24 } else { 40 })
            .y_label_area_size(if self.y_label.is_empty() { 48 } else { 64 })
            .build_cartesian_2d(x0..x1, y0..y1)?;
        chart
            .configure_mesh()
            .x_desc(&self.x_label)
            .y_desc(&self.y_label)
            .axis_desc_style((FONT, 16).into_font().color(&TEXT))
            .label_style((FONT, 14).into_font().color(&TEXT))
            .x_labels(labels(self.x_log, x0, x1))
            .y_labels(labels(self.y_log, y0, y1))
            .x_label_formatter(&|v| value(self.x_log, *v, x1 - x0))
            .y_label_formatter(&|v| value(self.y_log, *v, y1 - y0))
            .bold_line_style(GRID)
            .light_line_style(WHITE)
            .draw()?;
        for (i, s) in self.series.iter().enumerate() {
            let color = PALETTE[i % PALETTE.len()];
            let points: Vec<(f64, f64)> = self.chart_points(s).map(|(_, p)| p).collect();
            let name = s.name.as_str();
            match s.style {
                Style::Line => {
                    let style = color.stroke_width(2);
                    let drawn = if s.dashed {
                        chart.draw_series(DashedLineSeries::new(points, 6, 4, style))?
                    } else {
                        chart.draw_series(LineSeries::new(points, style))?
                    };
                    // A dashed series shows one dash in the legend.
                    let length = if s.dashed { 7 } else { 18 };
                    drawn.label(name).legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + length, y)], color.stroke_width(2))
                    });
                }
                Style::Markers => {
                    let labels = &s.labels;
                    let font = (FONT, 13).into_font().color(&color);
                    chart
                        .draw_series(self.chart_points(s).map(|(k, p)| {
                            let text = labels.get(k).cloned().unwrap_or_default();
                            EmptyElement::at(p)
                                + Circle::new((0, 0), 3, color.filled())
                                + Text::new(text, (5, -10), font.clone())
                        }))?
                        .label(name)
                        .legend(move |(x, y)| Circle::new((x + 9, y), 3, color.filled()));
                }
            }
        }
        for (h, label) in &self.hlines {
            let h = self.to_chart((1.0, *h)).1;
            let line = vec![(x0, h), (x1, h)];
            chart
                .draw_series(DashedLineSeries::new(line, 4, 4, REFERENCE.stroke_width(1)))?
                .label(label)
                .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 7, y)], REFERENCE));
        }
        let all: Vec<(f64, f64)> = self
            .series
            .iter()
            .flat_map(|s| self.chart_points(s).map(|(_, p)| p))
            .collect();
        chart
            .configure_series_labels()
            .position(emptiest_corner(&all, (x0, x1), (y0, y1)))
            .label_font((FONT, 14).into_font().color(&TEXT))
            .background_style(WHITE.mix(0.85))
            .border_style(GRID)
            .draw()?;
        Ok(())
    }
}

/// Several charts on one page (small multiples), `columns` per row, each in a cell as
/// large as the largest chart.
#[derive(Clone, Debug)]
pub struct Grid {
    /// The caption above the page (empty: none).
    pub title: String,
    /// The charts, row by row.
    pub plots: Vec<Plot>,
    /// Charts per row.
    pub columns: usize,
}

impl Grid {
    /// An empty page of two columns.
    pub fn new(title: impl Into<String>) -> Self {
        Grid {
            title: title.into(),
            plots: Vec::new(),
            columns: 2,
        }
    }

    /// Charts per row.
    pub fn columns(mut self, columns: usize) -> Self {
        self.columns = columns;
        self
    }

    /// Adds a chart.
    pub fn plot(mut self, plot: Plot) -> Self {
        self.plots.push(plot);
        self
    }

    /// A standalone SVG document.
    pub fn render(&self) -> String {
        let columns = self.columns.clamp(1, self.plots.len().max(1));
        let rows = self.plots.len().div_ceil(columns).max(1);
        let cell_w = self.plots.iter().map(|p| p.width).max().unwrap_or(640);
        let cell_h = self.plots.iter().map(|p| p.height).max().unwrap_or(400);
        let top = if self.title.is_empty() { 0 } else { 34 };
        let size = (cell_w * columns as u32, top + cell_h * rows as u32);
        svg(size.0, size.1, |root| {
            let body = if self.title.is_empty() {
                root.clone()
            } else {
                root.titled(
                    &self.title,
                    (FONT, 21).into_font().style(FontStyle::Bold).color(&TEXT),
                )?
            };
            for (plot, cell) in self.plots.iter().zip(body.split_evenly((rows, columns))) {
                // A smaller chart sits in the middle of its cell.
                let (w, h) = cell.dim_in_pixel();
                let (dx, dy) = (
                    w.saturating_sub(plot.width) / 2,
                    h.saturating_sub(plot.height) / 2,
                );
                let inner = cell.margin(dy, dy, dx, dx);
                plot.draw(&inner)?;
            }
            Ok(())
        })
    }

    /// Writes [`Grid::render`] to `path`, creating its parent directories.
    pub fn write(&self, path: &Path) -> std::io::Result<()> {
        write_file(path, &self.render())
    }
}

/// Draws a 2D particle network (a rope, a jelly mesh) at a few snapshot times, overlaid:
/// the last frame opaque, earlier ones fainter. Each frame draws `edges` (index pairs into
/// the frame's points) as springs and its points as particles, on axes of equal scale.
/// `times` (may be empty) labels the frames in the legend as "t = … s".
pub fn render_frames(
    title: &str,
    frames: &[Vec<(f64, f64)>],
    edges: &[(usize, usize)],
    times: &[f64],
) -> String {
    let finite = |p: &&(f64, f64)| p.0.is_finite() && p.1.is_finite();
    let (mut xs, mut ys) = (Span::default(), Span::default());
    for p in frames.iter().flatten().filter(finite) {
        xs.add(p.0);
        ys.add(p.1);
    }
    let (x0, x1) = xs.bounds().unwrap_or((-1.0, 1.0));
    let (y0, y1) = ys.bounds().unwrap_or((-1.0, 1.0));
    let span = f64::max(x1 - x0, y1 - y0);
    let span = if span > 0.0 { span } else { 1.0 };
    let pad = 0.06 * span;
    let (x0, x1, y0, y1) = (x0 - pad, x1 + pad, y0 - pad, y1 + pad);
    // Equal scale: fit the box into at most 560 × 480 px of plotting area, but never
    // narrower than 260 × 200 px (the range widens to fill instead).
    let scale = f64::min(560.0 / (x1 - x0), 480.0 / (y1 - y0));
    let (pw, ph) = (
        ((x1 - x0) * scale).clamp(260.0, 560.0),
        ((y1 - y0) * scale).clamp(200.0, 480.0),
    );
    let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
    let (hw, hh) = (0.5 * pw / scale, 0.5 * ph / scale);
    let (left, bottom, top, right) = (
        56u32,
        30u32,
        if title.is_empty() { 14u32 } else { 40 },
        16u32,
    );
    let size = (pw as u32 + left + right, ph as u32 + top + bottom);
    svg(size.0, size.1, |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(title, (FONT, 19).into_font().color(&TEXT))
            .margin_right(right)
            .x_label_area_size(bottom)
            .y_label_area_size(left)
            .build_cartesian_2d(cx - hw..cx + hw, cy - hh..cy + hh)?;
        chart
            .configure_mesh()
            .label_style((FONT, 14).into_font().color(&TEXT))
            .x_label_formatter(&|v| fmt_num(snap(*v, 2.0 * hw)))
            .y_label_formatter(&|v| fmt_num(snap(*v, 2.0 * hh)))
            .bold_line_style(GRID)
            .light_line_style(WHITE)
            .draw()?;
        let color = PALETTE[0];
        let n = frames.len();
        for (i, frame) in frames.iter().enumerate() {
            let opacity = if n <= 1 {
                1.0
            } else {
                0.18 + 0.82 * i as f64 / (n - 1) as f64
            };
            let faded = color.mix(opacity);
            let springs = edges.iter().filter_map(|&(a, b)| {
                let (p, q) = (frame.get(a)?, frame.get(b)?);
                (finite(&p) && finite(&q))
                    .then(|| PathElement::new(vec![*p, *q], faded.stroke_width(2)))
            });
            let drawn = chart.draw_series(springs)?;
            if let Some(t) = times.get(i) {
                drawn
                    .label(format!("t = {} s", fmt_num(*t)))
                    .legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 18, y)], faded.stroke_width(2))
                    });
            }
            chart.draw_series(
                frame
                    .iter()
                    .filter(finite)
                    .map(|p| Circle::new(*p, 3, faded.filled())),
            )?;
        }
        if !times.is_empty() {
            let all: Vec<(f64, f64)> = frames.iter().flatten().copied().collect();
            let corner = emptiest_corner(&all, (cx - hw, cx + hw), (cy - hh, cy + hh));
            chart
                .configure_series_labels()
                .position(corner)
                .label_font((FONT, 14).into_font().color(&TEXT))
                .background_style(WHITE.mix(0.85))
                .border_style(GRID)
                .draw()?;
        }
        Ok(())
    })
}

/// Formats a number compactly with at most 4 significant digits: `0.1 + 0.2` gives
/// `"0.3"`, `1234.567` gives `"1235"`, `2.5e-7` gives `"2.5e-7"`.
pub fn fmt_num(v: f64) -> String {
    if v.is_nan() {
        return "NaN".into();
    }
    if v.is_infinite() {
        return if v > 0.0 { "inf".into() } else { "-inf".into() };
    }
    if v == 0.0 {
        return "0".into();
    }
    let e = v.abs().log10().floor() as i32;
    if !(-4..6).contains(&e) {
        let s = format!("{v:.3e}");
        return match s.split_once('e') {
            Some((m, e)) => format!("{}e{e}", trim_zeros(m)),
            None => s,
        };
    }
    let s = trim_zeros(&format!("{:.*}", (3 - e).clamp(0, 10) as usize, v));
    if s == "-0" { "0".into() } else { s }
}

// ---------------------------------------------------------------------------------------
// Internals.

type DrawResult = Result<(), Box<dyn std::error::Error>>;

/// Renders `draw` on a white SVG page of `width × height` pixels. A drawing error (which
/// the SVG backend, writing to a string, does not produce) leaves the page as far as
/// it got.
fn svg(
    width: u32,
    height: u32,
    draw: impl FnOnce(&DrawingArea<SVGBackend<'_>, Shift>) -> DrawResult,
) -> String {
    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, (width, height)).into_drawing_area();
        let drawn = root
            .fill(&WHITE)
            .map_err(Into::into)
            .and_then(|()| draw(&root));
        if let Err(e) = drawn {
            eprintln!("plot: {e}");
        }
        let _ = root.present();
    }
    out
}

/// A tick value within rounding of zero (`−2.2e−16` for a tick meant at 0), as 0.
fn snap(v: f64, span: f64) -> f64 {
    if v.abs() < 1e-9 * span { 0.0 } else { v }
}

/// The corner of the plotting area with the fewest points in a box of a third of its
/// width and 40 % of its height, for the legend; upper right on a tie.
fn emptiest_corner(points: &[(f64, f64)], x: (f64, f64), y: (f64, f64)) -> SeriesLabelPosition {
    let (w, h) = ((x.1 - x.0) / 3.0, (y.1 - y.0) / 2.5);
    let count = |left: bool, top: bool| {
        points
            .iter()
            .filter(|p| {
                let in_x = if left { p.0 <= x.0 + w } else { p.0 >= x.1 - w };
                let in_y = if top { p.1 >= y.1 - h } else { p.1 <= y.0 + h };
                in_x && in_y
            })
            .count()
    };
    [
        (SeriesLabelPosition::UpperRight, count(false, true)),
        (SeriesLabelPosition::UpperLeft, count(true, true)),
        (SeriesLabelPosition::LowerRight, count(false, false)),
        (SeriesLabelPosition::LowerLeft, count(true, false)),
    ]
    .into_iter()
    .min_by_key(|(_, n)| *n)
    .map_or(SeriesLabelPosition::UpperRight, |(corner, _)| corner)
}

fn write_file(path: &Path, svg: &str) -> std::io::Result<()> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)?;
    }
    std::fs::write(path, svg)
}

fn trim_zeros(s: &str) -> String {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s.to_string()
    }
}

/// The extent of some values.
#[derive(Clone, Copy, Debug, Default)]
struct Span(Option<(f64, f64)>);

impl Span {
    fn add(&mut self, v: f64) {
        self.0 = Some(match self.0 {
            None => (v, v),
            Some((lo, hi)) => (lo.min(v), hi.max(v)),
        });
    }

    fn bounds(self) -> Option<(f64, f64)> {
        self.0
    }

    /// An axis range around the values: 5 % of the span added on a linear axis (a unit
    /// around a single value); on a log axis (values in decades) out to whole decades.
    fn axis(self, log: bool) -> (f64, f64) {
        match (self.0, log) {
            (None, false) => (0.0, 1.0),
            (None, true) => (-1.0, 0.0),
            (Some((lo, hi)), false) => {
                let pad = if hi > lo { 0.05 * (hi - lo) } else { 1.0 };
                (lo - pad, hi + pad)
            }
            // On a log axis the values are already decades.
            (Some((lo, hi)), true) => {
                let (lo, hi) = (lo.floor(), hi.ceil());
                (lo, if hi > lo { hi } else { lo + 1.0 })
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn is_svg(s: &str) -> bool {
        s.contains("<svg") && s.trim_end().ends_with("</svg>")
    }

    #[test]
    fn a_plot_has_its_title_labels_series_and_legend() {
        let svg = Plot::new("Step & response <1>")
            .x_label("time [s]")
            .y_label("offset [px]")
            .series(Series::line(
                "f32",
                (0..50).map(|n| (n as f64, (n as f64 * 0.2).sin())),
            ))
            .series(Series::markers("golden", [(1.0, 0.5), (2.0, f64::NAN)]).labels(["a", "b"]))
            .hline(0.0, "target")
            .render();
        assert!(is_svg(&svg));
        for text in [
            "Step &amp; response &lt;1&gt;",
            "time [s]",
            "offset [px]",
            "f32",
            "golden",
            "target",
        ] {
            assert!(svg.contains(text), "{text} missing");
        }
        // The NaN point is not drawn, so neither is its label.
        assert!(svg.contains("\na\n") && !svg.contains("\nb\n"));
    }

    #[test]
    fn log_axes_leave_out_what_they_cannot_draw() {
        let svg = Plot::new("errors")
            .log_x()
            .log_y()
            .series(Series::markers(
                "e",
                [(1.0, 1e-9), (10.0, 0.0), (-1.0, 1e-3), (100.0, 1e-3)],
            ))
            .render();
        assert!(is_svg(&svg));
        // Two of the four points can be drawn on log axes; the third dot is the legend's.
        assert_eq!(svg.matches("<circle").count(), 2 + 1, "{svg}");
        // Decade ticks: 1e-9 to 1e-3 on y, 1 to 100 on x.
        for tick in ["1e-9", "1e-6", "0.001", "\n1\n", "\n10\n", "\n100\n"] {
            assert!(svg.contains(tick), "{tick} missing");
        }
    }

    #[test]
    fn a_grid_and_frames_render() {
        let p = Plot::new("a")
            .series(Series::line("x", [(0.0, 0.0), (1.0, 1.0)]))
            .size(300, 200);
        let svg = Grid::new("page")
            .columns(2)
            .plot(p.clone())
            .plot(p)
            .render();
        assert!(is_svg(&svg) && svg.contains("page"));
        let frames = vec![vec![(0.0, 0.0), (1.0, 0.0)], vec![(0.0, 0.0), (0.7, -0.7)]];
        let svg = render_frames("rope", &frames, &[(0, 1)], &[0.0, 0.5]);
        assert!(is_svg(&svg) && svg.contains("t = 0.5 s"));
    }

    #[test]
    fn numbers_are_compact() {
        assert_eq!(fmt_num(0.1 + 0.2), "0.3");
        assert_eq!(fmt_num(1234.567), "1235");
        assert_eq!(fmt_num(2.5e-7), "2.5e-7");
        assert_eq!(fmt_num(0.0), "0");
    }
}
