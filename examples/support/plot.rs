#![allow(dead_code)]
//! A small, dependency-free SVG plotting module for the host-side examples and benches.
//!
//! Include it with `#[path = "../support/plot.rs"] mod plot;` from `examples/<name>/main.rs`
//! or `#[path = "../examples/support/plot.rs"] mod plot;` from `benches/`.
//!
//! ```ignore
//! let p = plot::Plot::new("Step response")
//!     .x_label("time [s]")
//!     .y_label("position")
//!     .series(plot::Series::line("f32", points))
//!     .hline(1.0, "target");
//! p.write(std::path::Path::new("target/plots/step.svg"))?;
//! ```
//!
//! Output is a standalone SVG 1.1 document: nice 1-2-5 ticks on linear axes, decades on log
//! axes, light grid, a legend in the emptiest corner, data clipped to the plot area, and
//! points that cannot be drawn (non-finite, or non-positive on a log axis) skipped.

use std::fmt::Write as _;
use std::path::Path;

/// Okabe–Ito colour-blind-safe palette, in the order series get them (yellow last: it is
/// faint on white).
pub const PALETTE: [&str; 8] = [
    "#0072B2", // blue
    "#D55E00", // vermillion
    "#009E73", // bluish green
    "#E69F00", // orange
    "#56B4E9", // sky blue
    "#CC79A7", // reddish purple
    "#000000", // black
    "#F0E442", // yellow
];

const FONT: &str = "Helvetica, Arial, 'DejaVu Sans', 'Liberation Sans', sans-serif";
const TITLE_SIZE: f64 = 15.0;
const LABEL_SIZE: f64 = 12.5;
const TICK_SIZE: f64 = 11.0;
const LEGEND_SIZE: f64 = 11.0;
const LINE_WIDTH: f64 = 1.5;
const GRID_COLOR: &str = "#e4e4e4";
const MINOR_GRID_COLOR: &str = "#f2f2f2";
const AXIS_COLOR: &str = "#a0a0a0";
const TEXT_COLOR: &str = "#333333";

/// How a series is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Style {
    /// A 1.5 px polyline through the points.
    Line,
    /// A dot at each point.
    Markers,
    /// A polyline with a dot at each point.
    LineAndMarkers,
}

/// One named data series.
#[derive(Clone, Debug)]
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
    pub style: Style,
    /// Draw the line dashed.
    pub dashed: bool,
    /// Override the automatic palette colour (any SVG colour, e.g. `"#000000"`).
    pub color: Option<String>,
    /// A short text beside each point (empty: none), in the series' colour.
    pub labels: Vec<String>,
}

impl Series {
    pub fn new(
        name: impl Into<String>,
        points: impl IntoIterator<Item = (f64, f64)>,
        style: Style,
    ) -> Self {
        Series {
            name: name.into(),
            points: points.into_iter().collect(),
            style,
            dashed: false,
            color: None,
            labels: Vec::new(),
        }
    }
    pub fn line(name: impl Into<String>, points: impl IntoIterator<Item = (f64, f64)>) -> Self {
        Self::new(name, points, Style::Line)
    }
    pub fn markers(name: impl Into<String>, points: impl IntoIterator<Item = (f64, f64)>) -> Self {
        Self::new(name, points, Style::Markers)
    }
    pub fn line_markers(
        name: impl Into<String>,
        points: impl IntoIterator<Item = (f64, f64)>,
    ) -> Self {
        Self::new(name, points, Style::LineAndMarkers)
    }
    pub fn dashed(mut self) -> Self {
        self.dashed = true;
        self
    }
    pub fn color(mut self, color: impl Into<String>) -> Self {
        self.color = Some(color.into());
        self
    }
    /// Labels the points, one text per point in order (a scatter plot of named things).
    pub fn labels(mut self, labels: impl IntoIterator<Item = impl Into<String>>) -> Self {
        self.labels = labels.into_iter().map(Into::into).collect();
        self
    }
}

/// A 2D plot of one or more series.
#[derive(Clone, Debug)]
pub struct Plot {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub x_log: bool,
    pub y_log: bool,
    pub series: Vec<Series>,
    pub width: f64,
    pub height: f64,
    /// Horizontal reference lines (a target, a tolerance), drawn dashed with their label.
    pub hlines: Vec<(f64, String)>,
    /// Fixed axis ranges; `None` fits the data (rounded out to ticks).
    pub x_range: Option<(f64, f64)>,
    pub y_range: Option<(f64, f64)>,
}

impl Plot {
    pub fn new(title: impl Into<String>) -> Self {
        Plot {
            title: title.into(),
            x_label: String::new(),
            y_label: String::new(),
            x_log: false,
            y_log: false,
            series: Vec::new(),
            width: 640.0,
            height: 400.0,
            hlines: Vec::new(),
            x_range: None,
            y_range: None,
        }
    }
    pub fn x_label(mut self, label: impl Into<String>) -> Self {
        self.x_label = label.into();
        self
    }
    pub fn y_label(mut self, label: impl Into<String>) -> Self {
        self.y_label = label.into();
        self
    }
    pub fn log_x(mut self) -> Self {
        self.x_log = true;
        self
    }
    pub fn log_y(mut self) -> Self {
        self.y_log = true;
        self
    }
    pub fn series(mut self, series: Series) -> Self {
        self.series.push(series);
        self
    }
    pub fn hline(mut self, y: f64, label: impl Into<String>) -> Self {
        self.hlines.push((y, label.into()));
        self
    }
    pub fn size(mut self, width: f64, height: f64) -> Self {
        self.width = width;
        self.height = height;
        self
    }
    pub fn x_range(mut self, lo: f64, hi: f64) -> Self {
        self.x_range = Some((lo, hi));
        self
    }
    pub fn y_range(mut self, lo: f64, hi: f64) -> Self {
        self.y_range = Some((lo, hi));
        self
    }

    /// A standalone SVG document.
    pub fn render(&self) -> String {
        let mut out = String::new();
        svg_open(&mut out, self.width, self.height, &self.title);
        self.render_into(&mut out, "p0");
        out.push_str("</svg>\n");
        out
    }

    /// Render to `path`, creating its parent directories.
    pub fn write(&self, path: &Path) -> std::io::Result<()> {
        write_file(path, &self.render())
    }

    fn valid(&self, (x, y): (f64, f64)) -> bool {
        x.is_finite() && y.is_finite() && (!self.x_log || x > 0.0) && (!self.y_log || y > 0.0)
    }

    /// Draws the plot into `out` in its own coordinates (0..width, 0..height); `id` makes
    /// the clip-path id unique within a document.
    fn render_into(&self, out: &mut String, id: &str) {
        let (w, h) = (self.width, self.height);
        let mut xr: Option<(f64, f64)> = None;
        let mut yr: Option<(f64, f64)> = None;
        for s in &self.series {
            for &p in s.points.iter().filter(|&&p| self.valid(p)) {
                extend(&mut xr, p.0);
                extend(&mut yr, p.1);
            }
        }
        for &(y, _) in &self.hlines {
            if y.is_finite() && (!self.y_log || y > 0.0) {
                extend(&mut yr, y);
            }
        }

        let has_title = !self.title.is_empty();
        let top = if has_title { 38.0 } else { 14.0 };
        let bottom = if self.x_label.is_empty() { 28.0 } else { 48.0 };
        let ph = (h - top - bottom).max(20.0);
        let y_target = ((ph / 45.0) as usize).clamp(3, 10);
        let ya = Axis::build(self.y_log, yr, self.y_range, y_target);
        let left = left_margin(&ya, !self.y_label.is_empty());
        // The right margin leaves room for half of the last x tick label.
        let fit =
            |right: f64| x_axis_fitting(self.x_log, xr, self.x_range, (w - left - right).max(20.0));
        let right = fit(18.0).major.last().map_or(18.0, |t| {
            f64::max(18.0, label_width(&t.1, TICK_SIZE) / 2.0 + 6.0)
        });
        let xa = fit(right);
        let rect = Rect {
            x: left,
            y: top,
            w: (w - left - right).max(20.0),
            h: ph,
        };

        out.push_str("<g>\n");
        draw_grid(out, &rect, &xa, &ya);
        draw_axes(out, &rect, &xa, &ya);
        draw_labels(out, &rect, w, &self.title, &self.x_label, &self.y_label);

        // Data, clipped to the plot area.
        let clip = format!("{id}-clip");
        let _ = writeln!(
            out,
            r#"<clipPath id="{clip}"><rect x="{:.1}" y="{:.1}" width="{:.1}" height="{:.1}"/></clipPath>"#,
            rect.x, rect.y, rect.w, rect.h
        );
        let _ = writeln!(out, r#"<g clip-path="url(#{clip})">"#);
        let to_px = |p: (f64, f64)| -> Option<(f64, f64)> {
            if !self.valid(p) {
                return None;
            }
            let q = (rect.px(xa.frac(p.0)?), rect.py(ya.frac(p.1)?));
            (q.0.is_finite() && q.1.is_finite()).then_some(q)
        };
        let mut placed: Vec<(f64, f64, f64, f64)> = Vec::new(); // label boxes: x0, x1, y0, y1
        let line_ys: Vec<f64> = self
            .hlines
            .iter()
            .filter_map(|(y, _)| ya.frac(*y).map(|f| rect.py(f)))
            .collect();
        for (y, label) in &self.hlines {
            let Some(fy) = ya.frac(*y) else { continue };
            let py = rect.py(fy);
            if !(rect.y - 0.5..=rect.y + rect.h + 0.5).contains(&py) {
                continue;
            }
            let _ = writeln!(
                out,
                r##"<line x1="{:.1}" y1="{py:.1}" x2="{:.1}" y2="{py:.1}" stroke="#555555" stroke-width="1" stroke-dasharray="5 3"/>"##,
                rect.x,
                rect.x + rect.w
            );
            if !label.is_empty() {
                // Right-aligned above the line; below it, or further left, if that would
                // run into the top edge or an earlier label.
                let tw = text_width(label, 10.5);
                let mut right = rect.x + rect.w - 5.0;
                let (ty, tx) = 'place: loop {
                    let mut shift = f64::INFINITY;
                    // Above the line, unless another line is too close above and there
                    // is room below.
                    let gap = |below: bool| {
                        line_ys
                            .iter()
                            .map(|&o| if below { o - py } else { py - o })
                            .filter(|&d| d > 0.5)
                            .fold(f64::INFINITY, f64::min)
                    };
                    let order = if gap(false) < 15.0 && gap(true) >= 15.0 {
                        [py + 13.0, py - 5.0]
                    } else {
                        [py - 5.0, py + 13.0]
                    };
                    for ty in order {
                        if ty - 10.0 < rect.y || ty > rect.y + rect.h - 2.0 {
                            continue;
                        }
                        let hit = placed.iter().find(|b: &&(f64, f64, f64, f64)| {
                            b.0 < right && right - tw < b.1 && b.2 < ty + 2.0 && ty - 10.0 < b.3
                        });
                        match hit {
                            None => break 'place (ty, right),
                            Some(b) => shift = shift.min(b.0 - 8.0),
                        }
                    }
                    if !shift.is_finite() || shift - tw < rect.x {
                        break (
                            if py - 15.0 < rect.y {
                                py + 13.0
                            } else {
                                py - 5.0
                            },
                            right,
                        );
                    }
                    right = shift;
                };
                placed.push((tx - tw, tx, ty - 10.0, ty + 2.0));
                let _ = writeln!(
                    out,
                    r##"<text x="{tx:.1}" y="{ty:.1}" font-size="10.5" fill="#444444" text-anchor="end" stroke="white" stroke-width="3" stroke-linejoin="round" paint-order="stroke">{}</text>"##,
                    escape(label)
                );
            }
        }

        let mut occupied: Vec<(f64, f64)> = Vec::new();
        let mut legend: Vec<LegendEntry> = Vec::new();
        let mut auto = 0;
        for s in &self.series {
            let color = match &s.color {
                Some(c) => c.clone(),
                None => {
                    auto += 1;
                    PALETTE[(auto - 1) % PALETTE.len()].to_string()
                }
            };
            let pts: Vec<Option<(f64, f64)>> = s.points.iter().map(|&p| to_px(p)).collect();
            let line = s.style != Style::Markers;
            let marker = s.style != Style::Line;
            if line {
                let d = polyline_path(&pts, &rect.inflate(2.0), &mut occupied);
                if !d.is_empty() {
                    let _ = writeln!(
                        out,
                        r#"<path d="{d}" fill="none" stroke="{}" stroke-width="{LINE_WIDTH}" stroke-linejoin="round" stroke-linecap="round"{}/>"#,
                        escape(&color),
                        if s.dashed {
                            r#" stroke-dasharray="6 4""#
                        } else {
                            ""
                        }
                    );
                }
            }
            if marker {
                draw_markers(out, &pts, &rect, &color, line, &mut occupied);
            }
            for (p, label) in pts.iter().zip(&s.labels) {
                let Some(p) = p.filter(|p| rect.contains(*p)) else {
                    continue;
                };
                if label.is_empty() {
                    continue;
                }
                let _ = writeln!(
                    out,
                    r##"<text x="{:.1}" y="{:.1}" font-size="9.5" fill="{}" stroke="white" stroke-width="2.5" stroke-linejoin="round" paint-order="stroke">{}</text>"##,
                    p.0 + 4.5,
                    p.1 - 4.0,
                    escape(&color),
                    escape(label)
                );
                occupied.push((p.0 + 4.5 + text_width(label, 9.5) / 2.0, p.1 - 7.0));
            }
            if !s.name.is_empty() {
                legend.push(LegendEntry {
                    label: s.name.clone(),
                    color,
                    opacity: 1.0,
                    line,
                    marker,
                    dashed: s.dashed,
                });
            }
        }
        out.push_str("</g>\n");
        draw_legend(out, &rect, &legend, &occupied);
        out.push_str("</g>\n");
    }
}

/// Several plots in one SVG (small multiples), `columns` per row.
#[derive(Clone, Debug)]
pub struct Grid {
    pub title: String,
    pub plots: Vec<Plot>,
    pub columns: usize,
}

impl Grid {
    pub fn new(title: impl Into<String>) -> Self {
        Grid {
            title: title.into(),
            plots: Vec::new(),
            columns: 2,
        }
    }
    pub fn columns(mut self, columns: usize) -> Self {
        self.columns = columns;
        self
    }
    pub fn plot(mut self, plot: Plot) -> Self {
        self.plots.push(plot);
        self
    }
    pub fn render(&self) -> String {
        grid_svg(&self.title, &self.plots, self.columns)
    }
    pub fn write(&self, path: &Path) -> std::io::Result<()> {
        write_file(path, &self.render())
    }
}

/// Several plots in one SVG, `columns` per row, without an overall title. Each cell is as
/// large as the largest plot; use [`Plot::size`] for smaller panels.
pub fn render_grid(plots: &[Plot], columns: usize) -> String {
    grid_svg("", plots, columns)
}

fn grid_svg(title: &str, plots: &[Plot], columns: usize) -> String {
    let cols = columns.clamp(1, plots.len().max(1));
    let rows = plots.len().div_ceil(cols).max(1);
    let cw = plots.iter().map(|p| p.width).fold(0.0, f64::max).max(1.0);
    let ch = plots.iter().map(|p| p.height).fold(0.0, f64::max).max(1.0);
    let top = if title.is_empty() { 0.0 } else { 34.0 };
    let (w, h) = (cw * cols as f64, top + ch * rows as f64);
    let mut out = String::new();
    svg_open(&mut out, w, h, title);
    if !title.is_empty() {
        let _ = writeln!(
            out,
            r#"<text x="{:.1}" y="24" font-size="17" font-weight="bold" fill="{TEXT_COLOR}" text-anchor="middle">{}</text>"#,
            w / 2.0,
            escape(title)
        );
    }
    for (i, p) in plots.iter().enumerate() {
        let (c, r) = (i % cols, i / cols);
        let _ = writeln!(
            out,
            r#"<g transform="translate({:.1},{:.1})">"#,
            c as f64 * cw + (cw - p.width) / 2.0,
            top + r as f64 * ch + (ch - p.height) / 2.0
        );
        p.render_into(&mut out, &format!("p{i}"));
        out.push_str("</g>\n");
    }
    out.push_str("</svg>\n");
    out
}

/// Draws a 2D particle network (a rope, a jelly mesh) at a few snapshot times, overlaid:
/// the last frame opaque, earlier ones fainter. Each frame draws `edges` (index pairs into
/// the frame's points) as springs and its points as particles. Axes have equal scale, y
/// up. `times` (may be empty) labels the frames in a legend as "t = … s".
pub fn render_frames(
    title: &str,
    frames: &[Vec<(f64, f64)>],
    edges: &[(usize, usize)],
    times: &[f64],
) -> String {
    let fin = |p: &(f64, f64)| p.0.is_finite() && p.1.is_finite();
    let mut xr: Option<(f64, f64)> = None;
    let mut yr: Option<(f64, f64)> = None;
    for p in frames.iter().flatten().filter(|p| fin(p)) {
        extend(&mut xr, p.0);
        extend(&mut yr, p.1);
    }
    let (mut x0, mut x1) = xr.unwrap_or((-1.0, 1.0));
    let (mut y0, mut y1) = yr.unwrap_or((-1.0, 1.0));
    let span = f64::max(x1 - x0, y1 - y0);
    let span = if span > 0.0 {
        span
    } else {
        x0.abs().max(y0.abs()).max(1.0)
    };
    let pad = 0.06 * span;
    (x0, x1, y0, y1) = (x0 - pad, x1 + pad, y0 - pad, y1 + pad);
    // Equal scale: fit the world box into at most 560 x 480 px, but never narrower than
    // 260 x 200 px (the world range widens to fill instead).
    let scale = f64::min(560.0 / (x1 - x0), 480.0 / (y1 - y0));
    let pw = ((x1 - x0) * scale).clamp(260.0, 560.0);
    let ph = ((y1 - y0) * scale).clamp(200.0, 480.0);
    let (cx, cy) = ((x0 + x1) / 2.0, (y0 + y1) / 2.0);
    let (hw, hh) = (pw / scale / 2.0, ph / scale / 2.0);
    let ya = Axis::build(
        false,
        None,
        Some((cy - hh, cy + hh)),
        ((ph / 50.0) as usize).clamp(3, 10),
    );
    let xa = Axis::build(
        false,
        None,
        Some((cx - hw, cx + hw)),
        ((pw / 80.0) as usize).clamp(3, 8),
    );
    let top = if title.is_empty() { 14.0 } else { 38.0 };
    let left = left_margin(&ya, false);
    let rect = Rect {
        x: left,
        y: top,
        w: pw,
        h: ph,
    };
    let (w, h) = (left + pw + 20.0, top + ph + 28.0);

    let mut out = String::new();
    svg_open(&mut out, w, h, title);
    draw_grid(&mut out, &rect, &xa, &ya);
    draw_axes(&mut out, &rect, &xa, &ya);
    draw_labels(&mut out, &rect, w, title, "", "");
    let _ = writeln!(
        out,
        r#"<clipPath id="frames-clip"><rect x="{:.1}" y="{:.1}" width="{:.1}" height="{:.1}"/></clipPath>"#,
        rect.x, rect.y, rect.w, rect.h
    );
    out.push_str("<g clip-path=\"url(#frames-clip)\">\n");
    let color = PALETTE[0];
    let n = frames.len();
    let mut occupied = Vec::new();
    let mut legend = Vec::new();
    for (i, frame) in frames.iter().enumerate() {
        let opacity = if n <= 1 {
            1.0
        } else {
            0.18 + 0.82 * i as f64 / (n - 1) as f64
        };
        let px: Vec<Option<(f64, f64)>> = frame
            .iter()
            .map(|p| {
                fin(p).then(|| {
                    (
                        rect.px(xa.frac(p.0).unwrap_or(0.0)),
                        rect.py(ya.frac(p.1).unwrap_or(0.0)),
                    )
                })
            })
            .collect();
        let _ = writeln!(out, r#"<g opacity="{opacity:.2}">"#);
        let mut d = String::new();
        for &(a, b) in edges {
            if let (Some(Some(p)), Some(Some(q))) = (px.get(a), px.get(b)) {
                let _ = write!(d, "M{:.1},{:.1}L{:.1},{:.1}", p.0, p.1, q.0, q.1);
                occupied.push(((p.0 + q.0) / 2.0, (p.1 + q.1) / 2.0));
            }
        }
        if !d.is_empty() {
            let _ = writeln!(
                out,
                r#"<path d="{d}" fill="none" stroke="{color}" stroke-width="{LINE_WIDTH}" stroke-linecap="round"/>"#
            );
        }
        let _ = write!(
            out,
            r#"<g fill="{color}" stroke="white" stroke-width="0.8">"#
        );
        for p in px.iter().flatten() {
            let _ = write!(out, r#"<circle cx="{:.1}" cy="{:.1}" r="3.2"/>"#, p.0, p.1);
            occupied.push(*p);
        }
        out.push_str("</g>\n</g>\n");
        if let Some(t) = times.get(i) {
            legend.push(LegendEntry {
                label: format!("t = {} s", fmt_num(*t)),
                color: color.to_string(),
                opacity,
                line: !edges.is_empty(),
                marker: true,
                dashed: false,
            });
        }
    }
    out.push_str("</g>\n");
    draw_legend(&mut out, &rect, &legend, &occupied);
    out.push_str("</svg>\n");
    out
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
        return sci(v, 3);
    }
    let s = format!("{:.*}", (3 - e).clamp(0, 10) as usize, v);
    let s = trim_zeros(&s);
    if s == "-0" { "0".into() } else { s }
}

// ---------------------------------------------------------------------------------------
// Internals.

fn write_file(path: &Path, svg: &str) -> std::io::Result<()> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)?;
    }
    std::fs::write(path, svg)
}

fn svg_open(out: &mut String, w: f64, h: f64, title: &str) {
    let _ = writeln!(
        out,
        r#"<?xml version="1.0" encoding="UTF-8" standalone="no"?>"#
    );
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" version="1.1" width="{w:.0}" height="{h:.0}" viewBox="0 0 {w:.0} {h:.0}" font-family="{FONT}">"#
    );
    if !title.is_empty() {
        let _ = writeln!(out, "<title>{}</title>", escape(title));
    }
    out.push_str("<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n");
}

/// Escapes text for XML content and attribute values.
fn escape(s: &str) -> String {
    let mut r = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => r.push_str("&amp;"),
            '<' => r.push_str("&lt;"),
            '>' => r.push_str("&gt;"),
            '"' => r.push_str("&quot;"),
            '\'' => r.push_str("&apos;"),
            c => r.push(c),
        }
    }
    r
}

fn trim_zeros(s: &str) -> String {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s.to_string()
    }
}

/// Scientific notation with at most `digits` decimals in the mantissa, trailing zeros
/// removed: `2.5e-7`, `1e6`.
fn sci(v: f64, digits: usize) -> String {
    let s = format!("{:.*e}", digits, v);
    match s.split_once('e') {
        Some((m, e)) => format!("{}e{}", trim_zeros(m), e),
        None => s,
    }
}

fn extend(r: &mut Option<(f64, f64)>, v: f64) {
    *r = Some(match *r {
        None => (v, v),
        Some((lo, hi)) => (lo.min(v), hi.max(v)),
    });
}

#[derive(Clone, Copy, Debug)]
struct Rect {
    x: f64,
    y: f64,
    w: f64,
    h: f64,
}

impl Rect {
    fn px(&self, fx: f64) -> f64 {
        self.x + fx * self.w
    }
    fn py(&self, fy: f64) -> f64 {
        self.y + (1.0 - fy) * self.h
    }
    fn inflate(&self, d: f64) -> Rect {
        Rect {
            x: self.x - d,
            y: self.y - d,
            w: self.w + 2.0 * d,
            h: self.h + 2.0 * d,
        }
    }
    fn contains(&self, (x, y): (f64, f64)) -> bool {
        x >= self.x && x <= self.x + self.w && y >= self.y && y <= self.y + self.h
    }
}

#[derive(Clone, Debug, PartialEq)]
enum TickLabel {
    Text(String),
    /// `10^k`, drawn with a superscript.
    Pow10(i32),
}

/// One axis. `lo`/`hi` and tick positions are in axis units: the value on a linear axis,
/// its log10 on a log axis.
#[derive(Clone, Debug)]
struct Axis {
    log: bool,
    lo: f64,
    hi: f64,
    major: Vec<(f64, TickLabel)>,
    minor: Vec<f64>,
}

/// The 1-2-5 step near `raw` as (mantissa, exponent): step = m * 10^e.
fn nice_step(raw: f64) -> (i64, i32) {
    let raw = if raw.is_finite() && raw > 0.0 {
        raw
    } else {
        1.0
    };
    let e = raw.log10().floor() as i32;
    let f = raw / 10f64.powi(e);
    match f {
        f if f < 1.5 => (1, e),
        f if f < 3.5 => (2, e),
        f if f < 7.5 => (5, e),
        _ => (1, e + 1),
    }
}

/// `k * 10^e`, computed so that e.g. 3 * 10^-1 is exactly the double nearest 0.3.
fn scaled(k: i64, e: i32) -> f64 {
    if e < 0 {
        k as f64 / 10f64.powi(-e)
    } else {
        k as f64 * 10f64.powi(e)
    }
}

/// Tick label for `v` on a grid of step `m * 10^e`.
fn fmt_tick(v: f64, m: i64, e: i32) -> String {
    let step = scaled(m, e);
    if v.abs() < step * 1e-6 {
        return if (-4..0).contains(&e) {
            format!("{:.*}", (-e) as usize, 0.0)
        } else {
            "0".into()
        };
    }
    if !(-4..6).contains(&e) {
        let ve = v.abs().log10().floor() as i32;
        return sci(v, (ve - e).max(0) as usize);
    }
    format!("{:.*}", (-e).max(0) as usize, v)
}

/// Linear ticks: (lo, hi, ticks). With `loose`, lo and hi are rounded out to ticks.
fn linear_ticks(lo: f64, hi: f64, target: usize, loose: bool) -> (f64, f64, Vec<(f64, String)>) {
    let (mut lo, mut hi) = if lo <= hi { (lo, hi) } else { (hi, lo) };
    if hi - lo <= 1e-12 * lo.abs().max(hi.abs()).max(1e-300) {
        let d = if lo == 0.0 { 1.0 } else { lo.abs() * 0.1 };
        (lo, hi) = (lo - d, hi + d);
    }
    let (m, e) = nice_step((hi - lo) / target.max(1) as f64);
    let step = scaled(m, e);
    let k = |v: f64| v / step;
    if loose {
        lo = scaled(((k(lo) + 1e-9).floor() as i64) * m, e);
        hi = scaled(((k(hi) - 1e-9).ceil() as i64) * m, e);
    }
    let (k0, k1) = ((k(lo) - 1e-9).ceil() as i64, (k(hi) + 1e-9).floor() as i64);
    let ticks = (k0..=k1)
        .map(|i| {
            let v = scaled(i * m, e);
            (v, fmt_tick(v, m, e))
        })
        .collect();
    (lo, hi, ticks)
}

/// Log ticks in decades: (lo, hi, major decades, minor positions), all in log10 units.
/// With `loose`, lo and hi are rounded out to decades.
fn log_ticks(lo: f64, hi: f64, target: usize, loose: bool) -> (f64, f64, Vec<i32>, Vec<f64>) {
    let (mut lo, mut hi) = if lo <= hi { (lo, hi) } else { (hi, lo) };
    if loose {
        lo = (lo + 1e-9).floor();
        hi = (hi - 1e-9).ceil();
    }
    if hi - lo < 1e-9 {
        if loose {
            hi = lo + 1.0;
        } else {
            (lo, hi) = (lo - 0.5, hi + 0.5);
        }
    }
    let n = (hi - lo).ceil() as i32;
    let dstep = (n as f64 / target.max(1) as f64).ceil().max(1.0) as i32;
    let (d0, d1) = ((lo - 1e-9).ceil() as i32, (hi + 1e-9).floor() as i32);
    let major: Vec<i32> = (d0..=d1).filter(|d| d.rem_euclid(dstep) == 0).collect();
    let mut minor = Vec::new();
    if dstep == 1 {
        if n <= 12 {
            for d in (lo.floor() as i32)..=(hi.ceil() as i32) {
                for j in 2..=9 {
                    let t = d as f64 + (j as f64).log10();
                    if t > lo && t < hi {
                        minor.push(t);
                    }
                }
            }
        }
    } else {
        minor.extend(
            (d0..=d1)
                .filter(|d| d.rem_euclid(dstep) != 0)
                .map(f64::from),
        );
    }
    (lo, hi, major, minor)
}

impl Axis {
    /// `data` and `fixed` are in data units; a fixed range wins when it is usable.
    fn build(
        log: bool,
        data: Option<(f64, f64)>,
        fixed: Option<(f64, f64)>,
        target: usize,
    ) -> Axis {
        let usable = |r: (f64, f64)| {
            r.0.is_finite() && r.1.is_finite() && r.0 != r.1 && (!log || (r.0 > 0.0 && r.1 > 0.0))
        };
        let (range, loose) = match (fixed.filter(|&r| usable(r)), data) {
            (Some(r), _) => (r, false),
            (None, Some(r)) => (r, true),
            (None, None) => (if log { (1.0, 10.0) } else { (0.0, 1.0) }, true),
        };
        if !log {
            let (lo, hi, ticks) = linear_ticks(range.0, range.1, target, loose);
            return Axis {
                log,
                lo,
                hi,
                major: ticks
                    .into_iter()
                    .map(|(v, s)| (v, TickLabel::Text(s)))
                    .collect(),
                minor: Vec::new(),
            };
        }
        let (lo, hi, decades, mut minor) =
            log_ticks(range.0.log10(), range.1.log10(), target, loose);
        let mut major: Vec<(f64, TickLabel)> = decades
            .iter()
            .map(|&d| (d as f64, TickLabel::Pow10(d)))
            .collect();
        if major.len() < 2 {
            // A narrow fixed range: label 2 and 5 times the decades as well.
            for d in (lo.floor() as i32)..=(hi.ceil() as i32) {
                for j in [2.0, 5.0] {
                    let t = d as f64 + f64::log10(j);
                    if t >= lo - 1e-9 && t <= hi + 1e-9 {
                        major.push((t, TickLabel::Text(fmt_num(j * 10f64.powi(d)))));
                        minor.retain(|&m| (m - t).abs() > 1e-9);
                    }
                }
            }
            major.sort_by(|a, b| a.0.total_cmp(&b.0));
        }
        Axis {
            log,
            lo,
            hi,
            major,
            minor,
        }
    }

    /// Position of a data value as a fraction of the axis (0 = lo, 1 = hi).
    fn frac(&self, v: f64) -> Option<f64> {
        let t = if self.log {
            if v > 0.0 { v.log10() } else { return None }
        } else {
            v
        };
        t.is_finite().then(|| (t - self.lo) / (self.hi - self.lo))
    }

    fn tick_frac(&self, t: f64) -> f64 {
        (t - self.lo) / (self.hi - self.lo)
    }
}

/// An x axis with as many ticks as fit the width without labels colliding.
fn x_axis_fitting(log: bool, data: Option<(f64, f64)>, fixed: Option<(f64, f64)>, pw: f64) -> Axis {
    let mut target = ((pw / 85.0) as usize).clamp(2, 10);
    loop {
        let a = Axis::build(log, data, fixed, target);
        let widths: f64 = a
            .major
            .iter()
            .map(|t| label_width(&t.1, TICK_SIZE) + 14.0)
            .sum();
        if widths <= pw || target <= 2 {
            return a;
        }
        target -= 1;
    }
}

fn text_width(s: &str, size: f64) -> f64 {
    s.chars().count() as f64 * size * 0.58
}

fn label_width(l: &TickLabel, size: f64) -> f64 {
    match l {
        TickLabel::Text(s) => text_width(s, size),
        TickLabel::Pow10(k) => text_width("10", size) + text_width(&k.to_string(), size * 0.75),
    }
}

fn left_margin(ya: &Axis, y_label: bool) -> f64 {
    let w = ya
        .major
        .iter()
        .map(|t| label_width(&t.1, TICK_SIZE))
        .fold(0.0, f64::max);
    w + 12.0 + if y_label { 26.0 } else { 8.0 }
}

/// A tick label as SVG text content: a proper minus sign, `10` with a superscript.
fn tick_text(l: &TickLabel) -> String {
    match l {
        TickLabel::Text(s) => escape(&s.replace('-', "\u{2212}")),
        TickLabel::Pow10(k) => format!(
            r#"10<tspan dy="-0.45em" font-size="{:.2}">{}</tspan>"#,
            TICK_SIZE * 0.75,
            k.to_string().replace('-', "\u{2212}")
        ),
    }
}

fn draw_grid(out: &mut String, r: &Rect, xa: &Axis, ya: &Axis) {
    let _ = writeln!(
        out,
        r#"<g stroke-width="1" shape-rendering="crispEdges" fill="none">"#
    );
    let vline = |out: &mut String, f: f64, color: &str| {
        let x = r.px(f);
        let _ = writeln!(
            out,
            r#"<line x1="{x:.1}" y1="{:.1}" x2="{x:.1}" y2="{:.1}" stroke="{color}"/>"#,
            r.y,
            r.y + r.h
        );
    };
    let hline = |out: &mut String, f: f64, color: &str| {
        let y = r.py(f);
        let _ = writeln!(
            out,
            r#"<line x1="{:.1}" y1="{y:.1}" x2="{:.1}" y2="{y:.1}" stroke="{color}"/>"#,
            r.x,
            r.x + r.w
        );
    };
    for &t in &xa.minor {
        vline(out, xa.tick_frac(t), MINOR_GRID_COLOR);
    }
    for &t in &ya.minor {
        hline(out, ya.tick_frac(t), MINOR_GRID_COLOR);
    }
    for (t, _) in &xa.major {
        vline(out, xa.tick_frac(*t), GRID_COLOR);
    }
    for (t, _) in &ya.major {
        hline(out, ya.tick_frac(*t), GRID_COLOR);
    }
    // A slightly darker zero line on linear axes that span zero.
    if !ya.log && ya.lo < 0.0 && ya.hi > 0.0 {
        hline(out, ya.tick_frac(0.0), "#c4c4c4");
    }
    if !xa.log && xa.lo < 0.0 && xa.hi > 0.0 {
        vline(out, xa.tick_frac(0.0), "#c4c4c4");
    }
    out.push_str("</g>\n");
}

fn draw_axes(out: &mut String, r: &Rect, xa: &Axis, ya: &Axis) {
    let _ = writeln!(
        out,
        r#"<rect x="{:.1}" y="{:.1}" width="{:.1}" height="{:.1}" fill="none" stroke="{AXIS_COLOR}" stroke-width="1" shape-rendering="crispEdges"/>"#,
        r.x, r.y, r.w, r.h
    );
    let mut ticks = String::new();
    let bottom = r.y + r.h;
    for (t, _) in &xa.major {
        let x = r.px(xa.tick_frac(*t));
        let _ = write!(ticks, "M{x:.1},{bottom:.1}v4");
    }
    for (t, _) in &ya.major {
        let y = r.py(ya.tick_frac(*t));
        let _ = write!(ticks, "M{:.1},{y:.1}h-4", r.x);
    }
    let _ = writeln!(
        out,
        r#"<path d="{ticks}" stroke="{AXIS_COLOR}" stroke-width="1" shape-rendering="crispEdges"/>"#
    );
    let _ = writeln!(out, r##"<g font-size="{TICK_SIZE}" fill="#555555">"##);
    for (t, l) in &xa.major {
        let x = r.px(xa.tick_frac(*t));
        let _ = writeln!(
            out,
            r#"<text x="{x:.1}" y="{:.1}" text-anchor="middle">{}</text>"#,
            bottom + 17.0,
            tick_text(l)
        );
    }
    for (t, l) in &ya.major {
        let y = r.py(ya.tick_frac(*t));
        let _ = writeln!(
            out,
            r#"<text x="{:.1}" y="{:.1}" text-anchor="end">{}</text>"#,
            r.x - 7.0,
            y + TICK_SIZE * 0.35,
            tick_text(l)
        );
    }
    out.push_str("</g>\n");
}

fn draw_labels(out: &mut String, r: &Rect, width: f64, title: &str, x_label: &str, y_label: &str) {
    if !title.is_empty() {
        // Centred over the plot area unless that would push it off the image.
        let tw = text_width(title, TITLE_SIZE);
        let cx =
            (r.x + r.w / 2.0).clamp(tw / 2.0 + 6.0, (width - tw / 2.0 - 6.0).max(tw / 2.0 + 6.0));
        let _ = writeln!(
            out,
            r#"<text x="{cx:.1}" y="24" font-size="{TITLE_SIZE}" font-weight="bold" fill="{TEXT_COLOR}" text-anchor="middle">{}</text>"#,
            escape(title)
        );
    }
    if !x_label.is_empty() {
        let _ = writeln!(
            out,
            r#"<text x="{:.1}" y="{:.1}" font-size="{LABEL_SIZE}" fill="{TEXT_COLOR}" text-anchor="middle">{}</text>"#,
            r.x + r.w / 2.0,
            r.y + r.h + 38.0,
            escape(x_label)
        );
    }
    if !y_label.is_empty() {
        let _ = writeln!(
            out,
            r#"<text transform="translate(17,{:.1}) rotate(-90)" font-size="{LABEL_SIZE}" fill="{TEXT_COLOR}" text-anchor="middle">{}</text>"#,
            r.y + r.h / 2.0,
            escape(y_label)
        );
    }
}

/// A clipped segment: its two ends, and whether each end was cut off.
type Clipped = ((f64, f64), (f64, f64), bool, bool);

/// Liang–Barsky: the part of segment p-q inside `r`, and whether p or q were cut off.
fn clip_segment(p: (f64, f64), q: (f64, f64), r: &Rect) -> Option<Clipped> {
    let (dx, dy) = (q.0 - p.0, q.1 - p.1);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (den, num) in [
        (-dx, p.0 - r.x),
        (dx, r.x + r.w - p.0),
        (-dy, p.1 - r.y),
        (dy, r.y + r.h - p.1),
    ] {
        if den == 0.0 {
            if num < 0.0 {
                return None;
            }
        } else {
            let t = num / den;
            if den < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
        }
    }
    if t0 > t1 {
        return None;
    }
    let at = |t: f64| (p.0 + t * dx, p.1 + t * dy);
    Some((
        if t0 > 0.0 { at(t0) } else { p },
        if t1 < 1.0 { at(t1) } else { q },
        t0 > 0.0,
        t1 < 1.0,
    ))
}

/// Path data through the pixel points, broken at `None`s, clipped to `r`, and thinned so
/// that no vertex is within a third of a pixel of the previous one. Samples of the drawn
/// line go to `occupied` (for placing the legend).
fn polyline_path(pts: &[Option<(f64, f64)>], r: &Rect, occupied: &mut Vec<(f64, f64)>) -> String {
    let mut d = String::new();
    let mut last: Option<(f64, f64)> = None; // last vertex written in the open subpath
    let mut pending: Option<(f64, f64)> = None; // a vertex skipped for being too close
    let mut prev: Option<(f64, f64)> = None;
    let close =
        |d: &mut String, last: &mut Option<(f64, f64)>, pending: &mut Option<(f64, f64)>| {
            if let (Some(p), Some(_)) = (pending.take(), *last) {
                let _ = write!(d, " {:.1},{:.1}", p.0, p.1);
            }
            *last = None;
        };
    let mut budget = 20_000usize;
    for &pt in pts {
        let Some(q) = pt else {
            close(&mut d, &mut last, &mut pending);
            prev = None;
            continue;
        };
        if let Some((a, b, cut_a, cut_b)) = prev.and_then(|p| clip_segment(p, q, r)) {
            if cut_a || last.is_none() {
                close(&mut d, &mut last, &mut pending);
                let _ = write!(d, "M{:.1},{:.1}L", a.0, a.1);
                last = Some(a);
            }
            let l = last.unwrap_or(a);
            if (b.0 - l.0).abs() < 0.34 && (b.1 - l.1).abs() < 0.34 {
                pending = Some(b);
            } else {
                let _ = write!(d, " {:.1},{:.1}", b.0, b.1);
                // Samples every ~6 px along the segment, for legend placement.
                let len = ((b.0 - l.0).hypot(b.1 - l.1) / 6.0).ceil().min(200.0) as usize;
                if budget > 0 {
                    for i in 0..len.max(1) {
                        let t = i as f64 / len.max(1) as f64;
                        occupied.push((l.0 + t * (b.0 - l.0), l.1 + t * (b.1 - l.1)));
                    }
                    budget = budget.saturating_sub(len.max(1));
                }
                last = Some(b);
                pending = None;
            }
            if cut_b {
                close(&mut d, &mut last, &mut pending);
            }
        }
        prev = Some(q);
    }
    close(&mut d, &mut last, &mut pending);
    d.replace("L ", "L")
}

fn draw_markers(
    out: &mut String,
    pts: &[Option<(f64, f64)>],
    r: &Rect,
    color: &str,
    with_line: bool,
    occupied: &mut Vec<(f64, f64)>,
) {
    let (radius, extra) = if with_line {
        (2.6, r#" stroke="white" stroke-width="0.8""#)
    } else {
        (2.8, r#" fill-opacity="0.85""#)
    };
    let _ = write!(out, r#"<g fill="{}"{extra}>"#, escape(color));
    let box_ = r.inflate(radius);
    let mut last: Option<(f64, f64)> = None;
    for p in pts.iter().flatten().filter(|p| box_.contains(**p)) {
        // Skip dots that would land exactly on the previous one.
        if last.is_some_and(|l| (l.0 - p.0).abs() < 0.25 && (l.1 - p.1).abs() < 0.25) {
            continue;
        }
        let _ = write!(
            out,
            r#"<circle cx="{:.1}" cy="{:.1}" r="{radius}"/>"#,
            p.0, p.1
        );
        occupied.push(*p);
        last = Some(*p);
    }
    out.push_str("</g>\n");
}

struct LegendEntry {
    label: String,
    color: String,
    opacity: f64,
    line: bool,
    marker: bool,
    dashed: bool,
}

/// A legend box in whichever inside corner of `r` covers the fewest `occupied` points.
fn draw_legend(out: &mut String, r: &Rect, entries: &[LegendEntry], occupied: &[(f64, f64)]) {
    if entries.is_empty() {
        return;
    }
    let row = 17.0;
    let text_w = entries
        .iter()
        .map(|e| text_width(&e.label, LEGEND_SIZE))
        .fold(0.0, f64::max);
    let (lw, lh) = (
        10.0 + 24.0 + 7.0 + text_w + 10.0,
        8.0 + row * entries.len() as f64,
    );
    let inset = 8.0;
    let corners = [
        (r.x + r.w - inset - lw, r.y + inset),            // top right
        (r.x + inset, r.y + inset),                       // top left
        (r.x + r.w - inset - lw, r.y + r.h - inset - lh), // bottom right
        (r.x + inset, r.y + r.h - inset - lh),            // bottom left
    ];
    let mut best = corners[0];
    let mut best_count = usize::MAX;
    for c in corners {
        let b = Rect {
            x: c.0,
            y: c.1,
            w: lw,
            h: lh,
        }
        .inflate(3.0);
        let count = occupied.iter().filter(|p| b.contains(**p)).count();
        if count < best_count {
            (best, best_count) = (c, count);
        }
    }
    let (x, y) = best;
    let _ = writeln!(
        out,
        r##"<g font-size="{LEGEND_SIZE}" fill="{TEXT_COLOR}"><rect x="{x:.1}" y="{y:.1}" width="{lw:.1}" height="{lh:.1}" rx="3" fill="white" fill-opacity="0.88" stroke="#cccccc" stroke-width="0.8"/>"##
    );
    for (i, e) in entries.iter().enumerate() {
        let cy = y + 4.0 + row * (i as f64 + 0.5);
        let (x0, x1) = (x + 10.0, x + 34.0);
        let color = escape(&e.color);
        let _ = write!(out, r#"<g opacity="{:.2}">"#, e.opacity);
        if e.line {
            let _ = write!(
                out,
                r#"<line x1="{x0:.1}" y1="{cy:.1}" x2="{x1:.1}" y2="{cy:.1}" stroke="{color}" stroke-width="{LINE_WIDTH}" stroke-linecap="round"{}/>"#,
                if e.dashed {
                    r#" stroke-dasharray="6 4""#
                } else {
                    ""
                }
            );
        }
        if e.marker {
            let _ = write!(
                out,
                r#"<circle cx="{:.1}" cy="{cy:.1}" r="2.8" fill="{color}"{}/>"#,
                (x0 + x1) / 2.0,
                if e.line {
                    r#" stroke="white" stroke-width="0.8""#
                } else {
                    ""
                }
            );
        }
        out.push_str("</g>");
        let _ = writeln!(
            out,
            r#"<text x="{:.1}" y="{:.1}">{}</text>"#,
            x1 + 7.0,
            cy + LEGEND_SIZE * 0.35,
            escape(&e.label)
        );
    }
    out.push_str("</g>\n");
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small well-formedness check: balanced tags, quoted attributes, only known
    /// entities, one root element.
    fn assert_well_formed(svg: &str) {
        let mut stack: Vec<&str> = Vec::new();
        let mut roots = 0;
        let mut rest = svg;
        while let Some(i) = rest.find('<') {
            check_text(&rest[..i]);
            let end = rest[i..].find('>').expect("unterminated tag") + i;
            let tag = &rest[i + 1..end];
            rest = &rest[end + 1..];
            if tag.starts_with('?') || tag.starts_with('!') {
                continue;
            }
            assert_eq!(
                tag.matches('"').count() % 2,
                0,
                "unbalanced quotes in <{tag}>"
            );
            if let Some(name) = tag.strip_prefix('/') {
                assert_eq!(stack.pop(), Some(name.trim()), "mismatched </{name}>");
                continue;
            }
            let name = tag
                .split(|c: char| c.is_whitespace() || c == '/')
                .next()
                .unwrap();
            assert!(!name.is_empty(), "empty tag name");
            check_text(tag);
            if stack.is_empty() {
                roots += 1;
            }
            if !tag.ends_with('/') {
                stack.push(name);
            }
        }
        check_text(rest);
        assert!(stack.is_empty(), "unclosed: {stack:?}");
        assert_eq!(roots, 1, "exactly one root element");
    }

    fn check_text(s: &str) {
        for (i, _) in s.match_indices('&') {
            let ok = ["&amp;", "&lt;", "&gt;", "&quot;", "&apos;", "&#"]
                .iter()
                .any(|e| s[i..].starts_with(e));
            assert!(ok, "bare & in {s:?}");
        }
    }

    fn labels(a: &Axis) -> Vec<String> {
        a.major
            .iter()
            .map(|(_, l)| match l {
                TickLabel::Text(s) => s.clone(),
                TickLabel::Pow10(k) => format!("10^{k}"),
            })
            .collect()
    }

    #[test]
    fn number_formatting_is_compact() {
        assert_eq!(fmt_num(0.1 + 0.2), "0.3");
        assert_eq!(fmt_num(0.0), "0");
        assert_eq!(fmt_num(-0.0), "0");
        assert_eq!(fmt_num(-1.5), "-1.5");
        assert_eq!(fmt_num(100.0), "100");
        assert_eq!(fmt_num(1234.5678), "1235");
        assert_eq!(fmt_num(0.012345), "0.01235");
        assert_eq!(fmt_num(2.5e-7), "2.5e-7");
        assert_eq!(fmt_num(3.0e6), "3e6");
        assert_eq!(fmt_num(-1.0e-9), "-1e-9");
        assert_eq!(fmt_num(9.99996), "10");
        assert_eq!(fmt_num(-0.00001), "-1e-5");
        assert_eq!(fmt_num(f64::NAN), "NaN");
    }

    #[test]
    fn linear_ticks_use_1_2_5_steps_and_round_out() {
        let a = Axis::build(false, Some((0.0, 1.0)), None, 5);
        assert_eq!(
            labels(&a),
            ["0.0", "0.2", "0.4", "0.6", "0.8", "1.0"].map(String::from)
        );
        assert_eq!((a.lo, a.hi), (0.0, 1.0));

        let a = Axis::build(false, Some((-0.83, 1.02)), None, 5);
        assert_eq!(
            labels(&a),
            ["-1.0", "-0.5", "0.0", "0.5", "1.0", "1.5"].map(String::from)
        );
        assert_eq!((a.lo, a.hi), (-1.0, 1.5));

        // No float noise in labels, nor spurious ticks from it.
        let a = Axis::build(false, Some((0.3, 0.9)), None, 6);
        assert_eq!(
            labels(&a),
            ["0.3", "0.4", "0.5", "0.6", "0.7", "0.8", "0.9"].map(String::from)
        );

        let a = Axis::build(false, Some((0.0, 2.0e-5)), None, 4);
        assert_eq!(
            labels(&a),
            ["0", "5e-6", "1e-5", "1.5e-5", "2e-5"].map(String::from)
        );

        let a = Axis::build(false, Some((0.0, 3.0e6)), None, 3);
        assert_eq!(labels(&a), ["0", "1e6", "2e6", "3e6"].map(String::from));

        let a = Axis::build(false, Some((12.0, 730.0)), None, 6);
        assert_eq!(
            labels(&a),
            ["0", "100", "200", "300", "400", "500", "600", "700", "800"].map(String::from)
        );
    }

    #[test]
    fn fixed_and_degenerate_linear_ranges() {
        // A fixed range is kept as is, with ticks inside it.
        let a = Axis::build(false, Some((0.0, 100.0)), Some((0.05, 0.95)), 5);
        assert_eq!((a.lo, a.hi), (0.05, 0.95));
        assert_eq!(labels(&a), ["0.2", "0.4", "0.6", "0.8"].map(String::from));
        // A single value still makes a usable axis around it.
        let a = Axis::build(false, Some((5.0, 5.0)), None, 5);
        assert!(a.lo < 5.0 && a.hi > 5.0 && a.major.len() >= 2);
        let a = Axis::build(false, Some((0.0, 0.0)), None, 5);
        assert!(a.lo < 0.0 && a.hi > 0.0);
        // No data at all.
        let a = Axis::build(false, None, None, 5);
        assert_eq!((a.lo, a.hi), (0.0, 1.0));
    }

    #[test]
    fn log_ticks_are_decades() {
        let a = Axis::build(true, Some((0.003, 250.0)), None, 8);
        assert_eq!(
            labels(&a),
            ["10^-3", "10^-2", "10^-1", "10^0", "10^1", "10^2", "10^3"].map(String::from)
        );
        assert_eq!((a.lo, a.hi), (-3.0, 3.0));
        assert_eq!(a.minor.len(), 6 * 8);
        // Exact decades are not rounded out further.
        let a = Axis::build(true, Some((1.0, 1000.0)), None, 8);
        assert_eq!((a.lo, a.hi), (0.0, 3.0));
        // Many decades: every k-th decade labelled, the others minor.
        let a = Axis::build(true, Some((1e-12, 1e12)), None, 6);
        assert_eq!(
            labels(&a),
            ["10^-12", "10^-8", "10^-4", "10^0", "10^4", "10^8", "10^12"].map(String::from)
        );
        assert_eq!(a.minor.len(), 25 - 7);
        // Within one decade: the enclosing decades.
        let a = Axis::build(true, Some((2.0, 8.0)), None, 6);
        assert_eq!(labels(&a), ["10^0", "10^1"].map(String::from));
        // A narrow fixed range gets 2 and 5 labels.
        let a = Axis::build(true, None, Some((1.5, 8.0)), 6);
        assert_eq!(labels(&a), ["2", "5"].map(String::from));
        assert_eq!(a.frac(-1.0), None);
        assert_eq!(a.frac(0.0), None);
    }

    fn sample_plot() -> Plot {
        let osc: Vec<(f64, f64)> = (0..=400)
            .map(|i| {
                let t = i as f64 * 0.005;
                (t, 1.0 - (-3.0 * t).exp() * (12.0 * t).cos())
            })
            .collect();
        Plot::new("Step <response> & \"friends\"")
            .x_label("time [s]")
            .y_label("x")
            .series(Series::line("f32 & f64", osc.clone()))
            .series(Series::markers(
                "bad",
                vec![(f64::NAN, 1.0), (0.5, f64::INFINITY), (1.0, 1.0)],
            ))
            .series(Series::line_markers("coarse", osc.iter().step_by(40).copied()).dashed())
            .hline(1.0, "target < 1%")
    }

    #[test]
    fn render_is_well_formed_and_escaped() {
        let svg = sample_plot().render();
        assert_well_formed(&svg);
        assert!(svg.starts_with("<?xml"));
        assert!(svg.contains("Step &lt;response&gt; &amp; &quot;friends&quot;"));
        assert!(svg.contains("target &lt; 1%"));
        assert!(!svg.contains("NaN") && !svg.contains("inf"));
        assert!(svg.contains(PALETTE[0]) && svg.contains(PALETTE[1]) && svg.contains(PALETTE[2]));
    }

    #[test]
    fn log_plot_skips_non_positive_points() {
        let p = Plot::new("log")
            .log_x()
            .log_y()
            .series(Series::markers(
                "s",
                vec![
                    (0.0, 1.0),
                    (-1.0, 2.0),
                    (10.0, -3.0),
                    (10.0, 100.0),
                    (1e3, 1e-2),
                ],
            ))
            .hline(0.0, "not drawn");
        let svg = p.render();
        assert_well_formed(&svg);
        assert_eq!(svg.matches("<circle").count(), 2 + 1); // two points and the legend dot
        assert!(!svg.contains("not drawn") && !svg.contains("NaN"));
        // An empty plot still renders.
        assert_well_formed(&Plot::new("").log_y().render());
    }

    #[test]
    fn grid_and_frames_are_well_formed() {
        let plots = vec![
            sample_plot().size(400.0, 300.0),
            sample_plot().log_y(),
            Plot::new("empty"),
        ];
        let svg = render_grid(&plots, 2);
        assert_well_formed(&svg);
        for i in 0..3 {
            assert_eq!(svg.matches(&format!("id=\"p{i}-clip\"")).count(), 1);
        }
        assert_well_formed(
            &Grid::new("All & more")
                .columns(3)
                .plot(sample_plot())
                .render(),
        );

        let frames: Vec<Vec<(f64, f64)>> = (0..4)
            .map(|f| {
                (0..6)
                    .map(|i| (i as f64 * 0.1 * (f as f64 * 0.3).cos(), -(i as f64) * 0.1))
                    .collect()
            })
            .collect();
        let edges: Vec<(usize, usize)> = (0..5).map(|i| (i, i + 1)).chain([(9, 10)]).collect();
        let svg = render_frames("rope", &frames, &edges, &[0.0, 0.1, 0.2, 0.3]);
        assert_well_formed(&svg);
        assert!(svg.contains("t = 0.3 s"));
        assert_well_formed(&render_frames("", &[], &[], &[]));
    }

    #[test]
    fn close_reference_lines_get_separate_labels() {
        let svg = Plot::new("")
            .series(Series::line("", vec![(0.0, 0.0), (1.0, 1.2)]))
            .hline(1.0, "target")
            .hline(1.02, "upper")
            .render();
        let y_of = |label: &str| -> f64 {
            let end = svg.find(&format!(">{label}</text>")).unwrap();
            let start = svg[..end].rfind(" y=\"").unwrap() + 4;
            svg[start..].split('"').next().unwrap().parse().unwrap()
        };
        // The upper line's label above the lower one's, with no overlap.
        assert!(y_of("target") - y_of("upper") >= 12.0);
    }

    #[test]
    fn lines_are_clipped_and_broken_at_gaps() {
        let r = Rect {
            x: 0.0,
            y: 0.0,
            w: 100.0,
            h: 100.0,
        };
        let mut occ = Vec::new();
        let d = polyline_path(
            &[
                Some((-50.0, 50.0)),
                Some((50.0, 50.0)),
                None,
                Some((60.0, 10.0)),
                Some((60.0, 500.0)),
            ],
            &r,
            &mut occ,
        );
        assert_eq!(d, "M0.0,50.0L50.0,50.0M60.0,10.0L60.0,100.0");
        assert!(clip_segment((-1.0, -1.0), (-5.0, 50.0), &r).is_none());
    }
}
