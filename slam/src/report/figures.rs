//! The figures of `rusoar slam`, drawn with plotters onto any backend and saved twice: SVG
//! (text stays text, no fonts needed) and PNG (text in our own pixel font, [`super::pixfont`]).
//!
//! Each figure is a value implementing [`Figure`]; [`save`] renders it to `<stem>.svg` and
//! `<stem>.png`. The figures answer the thesis's plots (Experiment and Result):
//!
//! - [`TimeBands`]: a quantity against time, median and 10–90 % band across seeds per condition
//!   (position error: Figure 30; walls in memory: Figure 28 as a count), or a paired difference
//!   with its confidence band, with dashed lines at targets;
//! - [`MapFigure`]: true walls, true and believed paths, and walls of a map, in one or more
//!   panels (Figures 26 and 29; snapshots over time: Figure 28);
//! - [`HoughFigure`]: one voted Hough space with its zones (Figure 20, 21) beside the returns and
//!   the walls extracted from them (Figure 22);
//! - [`Histogram`]: counts in bins, two colours (sizes of the `setOdometry` corrections);
//! - [`PairedScatter`]: one point per seed, off against on, with the diagonal.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use super::super::geom::{Point, Segment};
use super::super::pipeline::Extraction;
use super::pixfont::{write_png, PixelTextBackend};

/// Colour of the SLAM-off condition.
pub const OFF: RGBColor = RGBColor(205, 65, 40);
/// Colour of the SLAM-on condition.
pub const ON: RGBColor = RGBColor(35, 95, 200);
/// Grey of the true path.
pub const TRUE_PATH: RGBColor = RGBColor(150, 150, 150);
/// Walls the agent believes in.
pub const MAP_WALL: RGBColor = RGBColor(35, 95, 200);
/// Believed path.
pub const BELIEVED_PATH: RGBColor = RGBColor(215, 90, 30);

const FONT: &str = "sans-serif";

/// A figure that can draw itself on any plotters backend.
pub trait Figure {
    /// Size in pixels.
    fn size(&self) -> (u32, u32);
    /// Draws the whole figure onto `root`.
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String>;
}

fn err<E: std::fmt::Display>(e: E) -> String {
    format!("plotting failed: {e}")
}

/// Renders `fig` to `dir/<stem>.svg` and `dir/<stem>.png`; returns the two file names.
pub fn save(fig: &impl Figure, dir: &Path, stem: &str) -> Result<[String; 2], String> {
    let size = fig.size();
    let svg_name = format!("{stem}.svg");
    let png_name = format!("{stem}.png");
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        fig.draw(&root)?;
        root.present().map_err(err)?;
    }
    let path = dir.join(&svg_name);
    crate::output_file::write(&path, svg)?;
    let mut rgb = vec![255u8; size.0 as usize * size.1 as usize * 3];
    {
        let root = PixelTextBackend::with_buffer(&mut rgb, size).into_drawing_area();
        fig.draw(&root)?;
        root.present().map_err(err)?;
    }
    write_png(&dir.join(&png_name), &rgb, size)?;
    Ok([svg_name, png_name])
}

/// Median and band of a quantity over time.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Band {
    /// Times, s.
    pub t: Vec<f64>,
    pub median: Vec<f64>,
    /// Lower and upper edge (10 % and 90 % quantiles); empty for a single run.
    pub lo: Vec<f64>,
    pub hi: Vec<f64>,
}

impl Band {
    fn y_max(&self) -> f64 {
        self.median
            .iter()
            .chain(&self.hi)
            .copied()
            .filter(|v| v.is_finite())
            .fold(0.0, f64::max)
    }

    /// The lowest value drawn, 0 when none is negative.
    fn y_min(&self) -> f64 {
        self.median
            .iter()
            .chain(&self.lo)
            .copied()
            .filter(|v| v.is_finite())
            .fold(0.0, f64::min)
    }
}

/// A dashed horizontal line across a [`TimeBands`] figure, with a legend entry: a target.
pub struct HLine {
    pub label: String,
    pub value: f64,
    pub color: RGBColor,
}

/// One line of a [`TimeBands`] figure.
pub struct BandSeries<'a> {
    pub label: String,
    pub color: RGBColor,
    pub band: &'a Band,
    /// Dashed median line (for a second quantity of the same condition).
    pub dashed: bool,
}

/// Quantities against time: a median line and a shaded band per series.
pub struct TimeBands<'a> {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub series: Vec<BandSeries<'a>>,
    /// Targets, drawn dashed across the whole time axis.
    pub hlines: Vec<HLine>,
}

impl Figure for TimeBands<'_> {
    fn size(&self) -> (u32, u32) {
        (960, 560)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        root.fill(&WHITE).map_err(err)?;
        let x_max = self
            .series
            .iter()
            .flat_map(|s| s.band.t.last().copied())
            .fold(0.0, f64::max)
            .max(1e-3);
        let lines = self
            .hlines
            .iter()
            .map(|h| h.value)
            .filter(|v| v.is_finite());
        let top = self
            .series
            .iter()
            .map(|s| s.band.y_max())
            .chain(lines.clone())
            .fold(0.0, f64::max);
        let bottom = self
            .series
            .iter()
            .map(|s| s.band.y_min())
            .chain(lines)
            .fold(0.0, f64::min);
        // A margin of 8 % of the span beyond each end that holds data; 0 stays the edge when
        // nothing is negative, as an error's axis should.
        let span = (top - bottom).max(1e-3);
        let y_max = if top > 0.0 { top + 0.08 * span } else { 0.0 };
        let y_min = if bottom < 0.0 {
            bottom - 0.08 * span
        } else {
            0.0
        };
        let y_max = y_max.max(y_min + 1e-3);
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, (FONT, 22))
            .margin(15)
            .x_label_area_size(50)
            // Room for a minus sign before the tick labels.
            .y_label_area_size(if y_min < 0.0 { 88 } else { 75 })
            .build_cartesian_2d(0.0..x_max, y_min..y_max)
            .map_err(err)?;
        let (fx, fy) = (tick_format(x_max), tick_format(y_max - y_min));
        chart
            .configure_mesh()
            .x_desc(&self.x_label)
            .y_desc(&self.y_label)
            .x_label_formatter(&fx)
            .y_label_formatter(&fy)
            .label_style((FONT, 15))
            .axis_desc_style((FONT, 16))
            .light_line_style(RGBColor(235, 235, 235))
            .draw()
            .map_err(err)?;
        if y_min < 0.0 {
            // A difference's axis: the line of no difference.
            chart
                .draw_series(LineSeries::new(
                    [(0.0, 0.0), (x_max, 0.0)],
                    BLACK.stroke_width(1),
                ))
                .map_err(err)?;
        }
        for h in &self.hlines {
            chart
                .draw_series(DashedLineSeries::new(
                    [(0.0, h.value), (x_max, h.value)],
                    10,
                    6,
                    h.color.stroke_width(2),
                ))
                .map_err(err)?;
        }
        for s in &self.series {
            let b = s.band;
            if !b.lo.is_empty() && b.lo.len() == b.t.len() && b.hi.len() == b.t.len() {
                let mut poly: Vec<(f64, f64)> =
                    b.t.iter().copied().zip(b.hi.iter().copied()).collect();
                poly.extend(b.t.iter().copied().zip(b.lo.iter().copied()).rev());
                chart
                    .draw_series(std::iter::once(Polygon::new(
                        poly,
                        s.color.mix(0.16).filled(),
                    )))
                    .map_err(err)?;
            }
        }
        for s in &self.series {
            let b = s.band;
            let pts: Vec<(f64, f64)> = b.t.iter().copied().zip(b.median.iter().copied()).collect();
            let style = s.color.stroke_width(2);
            if s.dashed {
                chart
                    .draw_series(DashedLineSeries::new(pts, 8, 5, style))
                    .map_err(err)?;
            } else {
                chart
                    .draw_series(LineSeries::new(pts, style))
                    .map_err(err)?;
            }
        }
        let items: Vec<(String, Swatch)> = self
            .series
            .iter()
            .map(|s| {
                let sw = if s.dashed {
                    Swatch::Dashed(s.color)
                } else {
                    Swatch::Line(s.color)
                };
                (s.label.clone(), sw)
            })
            .chain(
                self.hlines
                    .iter()
                    .map(|h| (h.label.clone(), Swatch::Dashed(h.color))),
            )
            .collect();
        legend_box(
            &chart.plotting_area().strip_coord_spec(),
            &items,
            Corner::UpperLeft,
        )
    }
}

/// One map panel: the true walls, the true and believed paths, and a set of walls.
pub struct MapPanel<'a> {
    pub title: String,
    pub truth: &'a [Segment],
    pub true_path: &'a [Point],
    pub believed_path: &'a [Point],
    /// Walls to draw over the room, m.
    pub walls: Vec<(Point, Point)>,
}

/// Map panels in a grid with a common legend.
pub struct MapFigure<'a> {
    pub title: String,
    pub panels: Vec<MapPanel<'a>>,
    pub columns: usize,
    /// What the blue walls are.
    pub walls_label: String,
    /// The view, m: (x0, x1, y0, y1).
    pub view: (f64, f64, f64, f64),
}

/// A view around the true walls: their bounding box grown by `grow` of its size on every side.
pub fn view_around(truth: &[Segment], grow: f64) -> (f64, f64, f64, f64) {
    let pts = truth.iter().flat_map(|s| [s.a, s.b]);
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for p in pts {
        x0 = x0.min(p.x);
        x1 = x1.max(p.x);
        y0 = y0.min(p.y);
        y1 = y1.max(p.y);
    }
    if x0 > x1 {
        return (-5.0, 5.0, -5.0, 5.0);
    }
    let pad = |size: f64| if size > 0.0 { size * grow } else { 0.5 };
    let (gx, gy) = (pad(x1 - x0), pad(y1 - y0));
    (x0 - gx, x1 + gx, y0 - gy, y1 + gy)
}

/// Clips segment p–q to the box (Liang–Barsky); `None` when it lies outside.
pub fn clip_segment(p: Point, q: Point, v: (f64, f64, f64, f64)) -> Option<(Point, Point)> {
    if ![p.x, p.y, q.x, q.y].iter().all(|c| c.is_finite()) {
        return None;
    }
    let (dx, dy) = (q.x - p.x, q.y - p.y);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (pk, qk) in [
        (-dx, p.x - v.0),
        (dx, v.1 - p.x),
        (-dy, p.y - v.2),
        (dy, v.3 - p.y),
    ] {
        if pk == 0.0 {
            if qk < 0.0 {
                return None;
            }
        } else {
            let r = qk / pk;
            if pk < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
        }
    }
    (t0 <= t1).then(|| {
        (
            Point::new(p.x + t0 * dx, p.y + t0 * dy),
            Point::new(p.x + t1 * dx, p.y + t1 * dy),
        )
    })
}

/// A path cut into the runs of consecutive points inside the view.
fn visible_runs(path: &[Point], v: (f64, f64, f64, f64)) -> Vec<Vec<(f64, f64)>> {
    let inside = |p: &Point| p.x >= v.0 && p.x <= v.1 && p.y >= v.2 && p.y <= v.3;
    let mut runs = Vec::new();
    let mut cur = Vec::new();
    for p in path {
        if inside(p) {
            cur.push((p.x, p.y));
        } else if !cur.is_empty() {
            runs.push(std::mem::take(&mut cur));
        }
    }
    if !cur.is_empty() {
        runs.push(cur);
    }
    runs
}

/// At most `n` points of `path`, evenly spaced, plus its last point.
fn thin(path: &[Point], n: usize) -> Vec<Point> {
    if path.len() <= n || n < 2 {
        return path.to_vec();
    }
    let stride = path.len().div_ceil(n);
    let mut out: Vec<Point> = path.iter().step_by(stride).copied().collect();
    if let Some(last) = path.last() {
        out.push(*last);
    }
    out
}

/// A row of legend entries (a short line in a colour, then its text) across `area`.
fn legend_row<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    items: &[(&str, RGBColor, u32)],
) -> Result<(), String> {
    let style = TextStyle::from((FONT, 15).into_font()).color(&BLACK);
    let mut x = 20i32;
    let y = 14i32;
    for (text, color, width) in items {
        area.draw(&PathElement::new(
            vec![(x, y), (x + 28, y)],
            color.stroke_width(*width),
        ))
        .map_err(err)?;
        x += 36;
        area.draw(&Text::new(text.to_string(), (x, y - 7), style.clone()))
            .map_err(err)?;
        let (w, _) = area.estimate_text_size(text, &style).map_err(err)?;
        x += w as i32 + 30;
    }
    Ok(())
}

/// What a legend entry shows before its text.
#[derive(Debug, Clone, Copy)]
pub enum Swatch {
    Line(RGBColor),
    Dashed(RGBColor),
    Block(RGBColor),
}

/// Which corner of the plotting area a legend sits in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Corner {
    UpperLeft,
    UpperRight,
}

/// A framed legend in a corner of `area`, measured with the backend's own text metrics (so that
/// the PNG's pixel font and the SVG's text both fit the box).
fn legend_box<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    items: &[(String, Swatch)],
    corner: Corner,
) -> Result<(), String> {
    if items.is_empty() {
        return Ok(());
    }
    let style = TextStyle::from((FONT, 15).into_font()).color(&BLACK);
    let mut text_w = 0i32;
    let mut text_h = 0i32;
    for (t, _) in items {
        let (w, h) = area.estimate_text_size(t, &style).map_err(err)?;
        text_w = text_w.max(w as i32);
        text_h = text_h.max(h as i32);
    }
    let line_h = text_h + 8;
    let (box_w, box_h) = (12 + 30 + 8 + text_w + 12, items.len() as i32 * line_h + 10);
    let (aw, _) = area.dim_in_pixel();
    let x0 = match corner {
        Corner::UpperLeft => 12,
        Corner::UpperRight => aw as i32 - box_w - 12,
    };
    let y0 = 12;
    area.draw(&Rectangle::new(
        [(x0, y0), (x0 + box_w, y0 + box_h)],
        WHITE.mix(0.9).filled(),
    ))
    .map_err(err)?;
    area.draw(&Rectangle::new(
        [(x0, y0), (x0 + box_w, y0 + box_h)],
        BLACK.stroke_width(1),
    ))
    .map_err(err)?;
    for (i, (text, swatch)) in items.iter().enumerate() {
        let top = y0 + 5 + i as i32 * line_h;
        let mid = top + line_h / 2;
        let (sx0, sx1) = (x0 + 12, x0 + 42);
        match swatch {
            Swatch::Line(c) => area
                .draw(&PathElement::new(
                    vec![(sx0, mid), (sx1, mid)],
                    c.stroke_width(3),
                ))
                .map_err(err)?,
            Swatch::Dashed(c) => {
                for x in (sx0..sx1).step_by(10) {
                    area.draw(&PathElement::new(
                        vec![(x, mid), ((x + 6).min(sx1), mid)],
                        c.stroke_width(3),
                    ))
                    .map_err(err)?;
                }
            }
            Swatch::Block(c) => area
                .draw(&Rectangle::new(
                    [(sx0 + 7, mid - 6), (sx0 + 23, mid + 6)],
                    c.filled(),
                ))
                .map_err(err)?,
        }
        area.draw(&Text::new(text.clone(), (sx1 + 8, top + 4), style.clone()))
            .map_err(err)?;
    }
    Ok(())
}

/// Tick labels with as many decimals as a span of `span` needs.
fn tick_format(span: f64) -> impl Fn(&f64) -> String {
    let decimals = if span >= 20.0 {
        0
    } else if span >= 2.0 {
        1
    } else {
        2
    };
    move |v: &f64| format!("{v:.decimals$}")
}

/// Draws the room view into `area` with equal scales on both axes; returns the chart's ranges.
fn equal_axes<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    v: (f64, f64, f64, f64),
    label_x: u32,
    label_y: u32,
    margin: u32,
) -> (f64, f64, f64, f64) {
    let (w, h) = area.dim_in_pixel();
    let pw = (w as f64 - label_y as f64 - 2.0 * margin as f64).max(10.0);
    let ph = (h as f64 - label_x as f64 - 2.0 * margin as f64).max(10.0);
    let (mut x0, mut x1, mut y0, mut y1) = v;
    let (sx, sy) = ((x1 - x0) / pw, (y1 - y0) / ph);
    if sx > sy {
        let grow = (sx * ph - (y1 - y0)) / 2.0;
        y0 -= grow;
        y1 += grow;
    } else {
        let grow = (sy * pw - (x1 - x0)) / 2.0;
        x0 -= grow;
        x1 += grow;
    }
    (x0, x1, y0, y1)
}

impl MapFigure<'_> {
    fn panel<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        p: &MapPanel<'_>,
    ) -> Result<(), String> {
        let area = area.titled(&p.title, (FONT, 17)).map_err(err)?;
        let v = equal_axes(&area, self.view, 52, 72, 8);
        let mut chart = ChartBuilder::on(&area)
            .margin(8)
            .x_label_area_size(52)
            .y_label_area_size(72)
            .build_cartesian_2d(v.0..v.1, v.2..v.3)
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc("x, m")
            .y_desc("y, m")
            .label_style((FONT, 14))
            .axis_desc_style((FONT, 14))
            .light_line_style(RGBColor(240, 240, 240))
            .draw()
            .map_err(err)?;
        for run in visible_runs(&thin(p.true_path, 3000), v) {
            chart
                .draw_series(LineSeries::new(run, TRUE_PATH.stroke_width(2)))
                .map_err(err)?;
        }
        for run in visible_runs(&thin(p.believed_path, 3000), v) {
            chart
                .draw_series(LineSeries::new(run, BELIEVED_PATH.stroke_width(2)))
                .map_err(err)?;
        }
        for s in p.truth {
            if let Some((a, b)) = clip_segment(s.a, s.b, v) {
                chart
                    .draw_series(LineSeries::new(
                        [(a.x, a.y), (b.x, b.y)],
                        BLACK.stroke_width(3),
                    ))
                    .map_err(err)?;
            }
        }
        for (a, b) in &p.walls {
            if let Some((a, b)) = clip_segment(*a, *b, v) {
                chart
                    .draw_series(LineSeries::new(
                        [(a.x, a.y), (b.x, b.y)],
                        MAP_WALL.stroke_width(2),
                    ))
                    .map_err(err)?;
            }
        }
        for (path, color) in [(p.true_path, TRUE_PATH), (p.believed_path, BELIEVED_PATH)] {
            if let Some(end) = path
                .last()
                .filter(|e| e.x >= v.0 && e.x <= v.1 && e.y >= v.2 && e.y <= v.3)
            {
                chart
                    .draw_series(std::iter::once(Circle::new(
                        (end.x, end.y),
                        5,
                        color.filled(),
                    )))
                    .map_err(err)?;
            }
        }
        Ok(())
    }
}

impl Figure for MapFigure<'_> {
    fn size(&self) -> (u32, u32) {
        let cols = self.columns.max(1) as u32;
        let rows = (self.panels.len() as u32).div_ceil(cols).max(1);
        (cols * 620, rows * 500 + 80)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        root.fill(&WHITE).map_err(err)?;
        let root = root.titled(&self.title, (FONT, 22)).map_err(err)?;
        let (_, h) = root.dim_in_pixel();
        let (body, legend) = root.split_vertically(h.saturating_sub(34));
        let cols = self.columns.max(1);
        let rows = self.panels.len().div_ceil(cols).max(1);
        let cells = body.split_evenly((rows, cols));
        for (p, cell) in self.panels.iter().zip(cells.iter()) {
            self.panel(cell, p)?;
        }
        legend_row(
            &legend,
            &[
                ("true walls", BLACK, 3),
                ("true path", TRUE_PATH, 2),
                ("believed path", BELIEVED_PATH, 2),
                (&self.walls_label, MAP_WALL, 2),
            ],
        )
    }
}

/// One voted Hough space (left) and the returns and walls of the same extraction (right).
pub struct HoughFigure<'a> {
    pub title: String,
    pub extraction: &'a Extraction,
    /// The critical value k.
    pub k: u32,
    pub truth: &'a [Segment],
}

impl HoughFigure<'_> {
    /// Run-length rectangles of the accumulator: (θ0, θ1, r0, r1 in m, shade level 1..=levels).
    pub fn cells(&self, levels: u32) -> Vec<(f64, f64, f64, f64, u32)> {
        let acc = &self.extraction.accumulator;
        let max = acc.max_votes();
        let mut out = Vec::new();
        if max == 0 {
            return out;
        }
        let step = acc.theta_step_deg() as f64;
        let bin = acc.r_bin_mm() / 1000.0;
        let level = |v: u32| -> u32 {
            if v == 0 {
                0
            } else {
                // Square root: the weak votes of the sinusoids' tails stay visible beside peaks.
                ((v as f64 / max as f64).sqrt() * levels as f64)
                    .ceil()
                    .clamp(1.0, levels as f64) as u32
            }
        };
        for t in 0..acc.n_theta() {
            let th = acc.theta_deg(t);
            let mut ri = 0;
            while ri < acc.n_r() {
                let l = level(acc.get(t, ri));
                let mut end = ri + 1;
                while end < acc.n_r() && level(acc.get(t, end)) == l {
                    end += 1;
                }
                if l > 0 {
                    let r0 = acc.r_mm(ri) / 1000.0 - bin / 2.0;
                    out.push((th, th + step, r0, r0 + bin * (end - ri) as f64, l));
                }
                ri = end;
            }
        }
        out
    }
}

impl Figure for HoughFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (1240, 600)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        root.fill(&WHITE).map_err(err)?;
        let root = root.titled(&self.title, (FONT, 20)).map_err(err)?;
        let (left, right) = root.split_horizontally(640);
        let acc = &self.extraction.accumulator;
        let levels = 12;
        let cells = self.cells(levels);
        let r_top = cells.iter().map(|c| c.3).fold(0.5, f64::max);
        let left = left
            .titled(
                &format!(
                    "Hough space: peak {} votes, k = {}, {} zones",
                    acc.max_votes(),
                    self.k,
                    self.extraction.zones.len()
                ),
                (FONT, 15),
            )
            .map_err(err)?;
        let mut chart = ChartBuilder::on(&left)
            .margin(10)
            .x_label_area_size(52)
            .y_label_area_size(72)
            .build_cartesian_2d(0.0..360.0, (acc.r_min_mm() / 1000.0)..r_top)
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc("θ, degrees")
            .y_desc("r, m")
            .label_style((FONT, 14))
            .axis_desc_style((FONT, 14))
            .disable_mesh()
            .draw()
            .map_err(err)?;
        chart
            .draw_series(cells.iter().map(|&(t0, t1, r0, r1, l)| {
                let g = (245.0 - 225.0 * l as f64 / levels as f64).round() as u8;
                Rectangle::new([(t0, r0), (t1, r1)], RGBColor(g, g, g).filled())
            }))
            .map_err(err)?;
        for z in &self.extraction.zones {
            if let Some(p) = z.peaks.first() {
                chart
                    .draw_series(std::iter::once(Circle::new(
                        (p.theta_deg, p.r_mm / 1000.0),
                        7,
                        RED.stroke_width(2),
                    )))
                    .map_err(err)?;
            }
        }
        // Right: the returns and the walls, in the believed frame.
        let right = right
            .titled(
                &format!(
                    "{} returns, {} kept, {} wall(s)",
                    self.extraction.points.len(),
                    self.extraction.filtered.len(),
                    self.extraction.walls.len()
                ),
                (FONT, 15),
            )
            .map_err(err)?;
        let mut view = view_around(self.truth, 0.08);
        for p in &self.extraction.points {
            let (x, y) = (p.x / 1000.0, p.y / 1000.0);
            if x.is_finite() && y.is_finite() {
                view = (view.0.min(x), view.1.max(x), view.2.min(y), view.3.max(y));
            }
        }
        let v = equal_axes(&right, view, 52, 72, 10);
        let mut chart = ChartBuilder::on(&right)
            .margin(10)
            .x_label_area_size(52)
            .y_label_area_size(72)
            .build_cartesian_2d(v.0..v.1, v.2..v.3)
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc("x, m (believed frame)")
            .y_desc("y, m")
            .label_style((FONT, 14))
            .axis_desc_style((FONT, 14))
            .light_line_style(RGBColor(240, 240, 240))
            .draw()
            .map_err(err)?;
        for s in self.truth {
            chart
                .draw_series(DashedLineSeries::new(
                    [(s.a.x, s.a.y), (s.b.x, s.b.y)],
                    8,
                    6,
                    RGBColor(110, 110, 110).stroke_width(2),
                ))
                .map_err(err)?;
        }
        chart
            .draw_series(self.extraction.points.iter().map(|p| {
                Circle::new(
                    (p.x / 1000.0, p.y / 1000.0),
                    2,
                    RGBColor(185, 185, 185).filled(),
                )
            }))
            .map_err(err)?;
        chart
            .draw_series(
                self.extraction
                    .filtered
                    .iter()
                    .map(|p| Circle::new((p.x / 1000.0, p.y / 1000.0), 2, BLACK.filled())),
            )
            .map_err(err)?;
        for w in &self.extraction.walls {
            chart
                .draw_series(LineSeries::new(
                    [
                        (w.start.x as f64 / 1000.0, w.start.y as f64 / 1000.0),
                        (w.end.x as f64 / 1000.0, w.end.y as f64 / 1000.0),
                    ],
                    RED.stroke_width(3),
                ))
                .map_err(err)?;
        }
        if let Some(w) = self.extraction.walls.first() {
            let (x, y) = (w.reference.x as f64 / 1000.0, w.reference.y as f64 / 1000.0);
            let th = (w.reference.th as f64).to_radians();
            chart
                .draw_series(std::iter::once(Circle::new((x, y), 6, ON.filled())))
                .map_err(err)?;
            chart
                .draw_series(LineSeries::new(
                    [(x, y), (x + 0.4 * th.cos(), y + 0.4 * th.sin())],
                    ON.stroke_width(2),
                ))
                .map_err(err)?;
        }
        Ok(())
    }
}

/// Counts in bins, each bar in one of two colours.
pub struct Histogram {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    /// (bin start, bin end, count, second colour?)
    pub bars: Vec<(f64, f64, u32, bool)>,
    pub labels: [(String, RGBColor); 2],
}

impl Figure for Histogram {
    fn size(&self) -> (u32, u32) {
        (960, 520)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        root.fill(&WHITE).map_err(err)?;
        let x0 = self.bars.iter().map(|b| b.0).fold(f64::MAX, f64::min);
        let x1 = self.bars.iter().map(|b| b.1).fold(f64::MIN, f64::max);
        let (x0, x1) = if x0 < x1 { (x0, x1) } else { (-1.0, 1.0) };
        let y1 = self.bars.iter().map(|b| b.2).max().unwrap_or(0).max(1) as f64 * 1.1;
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, (FONT, 20))
            .margin(15)
            .x_label_area_size(50)
            .y_label_area_size(65)
            .build_cartesian_2d(x0..x1, 0.0..y1)
            .map_err(err)?;
        let (fx, fy) = (tick_format(x1 - x0), |v: &f64| format!("{v:.0}"));
        chart
            .configure_mesh()
            .x_desc(&self.x_label)
            .y_desc(&self.y_label)
            .x_label_formatter(&fx)
            .y_label_formatter(&fy)
            .label_style((FONT, 15))
            .axis_desc_style((FONT, 16))
            .light_line_style(RGBColor(235, 235, 235))
            .draw()
            .map_err(err)?;
        for (i, (_, color)) in self.labels.iter().enumerate() {
            let second = i == 1;
            chart
                .draw_series(
                    self.bars
                        .iter()
                        .filter(|b| b.3 == second && b.2 > 0)
                        .map(|b| Rectangle::new([(b.0, 0.0), (b.1, b.2 as f64)], color.filled())),
                )
                .map_err(err)?;
        }
        let items: Vec<(String, Swatch)> = self
            .labels
            .iter()
            .map(|(l, c)| (l.clone(), Swatch::Block(*c)))
            .collect();
        legend_box(
            &chart.plotting_area().strip_coord_spec(),
            &items,
            Corner::UpperRight,
        )
    }
}

/// One panel of a [`PairedScatter`]: title, axis unit, points (seed, off, on).
pub type ScatterPanel = (String, String, Vec<(u64, f64, f64)>);

/// One point per seed: a measure without (x) and with (y) the SLAM rules, in panels.
pub struct PairedScatter {
    pub title: String,
    pub panels: Vec<ScatterPanel>,
}

impl Figure for PairedScatter {
    fn size(&self) -> (u32, u32) {
        (560 * self.panels.len().max(1) as u32, 580)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        root.fill(&WHITE).map_err(err)?;
        let root = root.titled(&self.title, (FONT, 20)).map_err(err)?;
        let cells = root.split_evenly((1, self.panels.len().max(1)));
        for ((title, unit, pts), cell) in self.panels.iter().zip(cells.iter()) {
            let m = pts
                .iter()
                .flat_map(|p| [p.1, p.2])
                .filter(|v| v.is_finite())
                .fold(0.0, f64::max)
                .max(1e-3)
                * 1.08;
            let below = pts.iter().filter(|p| p.2 < p.1).count();
            let cell = cell
                .titled(
                    &format!("{title}: {below} of {} seeds lower with SLAM", pts.len()),
                    (FONT, 14),
                )
                .map_err(err)?;
            let mut chart = ChartBuilder::on(&cell)
                .margin(12)
                .x_label_area_size(45)
                .y_label_area_size(65)
                .build_cartesian_2d(0.0..m, 0.0..m)
                .map_err(err)?;
            chart
                .configure_mesh()
                .x_desc(format!("SLAM off, {unit}"))
                .y_desc(format!("SLAM on, {unit}"))
                .label_style((FONT, 14))
                .axis_desc_style((FONT, 14))
                .light_line_style(RGBColor(240, 240, 240))
                .draw()
                .map_err(err)?;
            chart
                .draw_series(DashedLineSeries::new(
                    [(0.0, 0.0), (m, m)],
                    6,
                    5,
                    BLACK.stroke_width(1),
                ))
                .map_err(err)?;
            chart
                .draw_series(
                    pts.iter()
                        .filter(|p| p.1.is_finite() && p.2.is_finite())
                        .map(|p| Circle::new((p.1, p.2), 5, ON.filled())),
                )
                .map_err(err)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segments_are_clipped_to_the_view() {
        let v = (0.0, 10.0, 0.0, 5.0);
        let (a, b) = clip_segment(Point::new(-5.0, 1.0), Point::new(5.0, 1.0), v).unwrap();
        assert_eq!((a.x, a.y, b.x, b.y), (0.0, 1.0, 5.0, 1.0));
        assert!(clip_segment(Point::new(-5.0, 6.0), Point::new(5.0, 6.0), v).is_none());
        assert!(clip_segment(Point::new(f64::NAN, 0.0), Point::new(1.0, 1.0), v).is_none());
        let (a, b) = clip_segment(Point::new(1.0, 1.0), Point::new(2.0, 2.0), v).unwrap();
        assert_eq!((a.x, b.y), (1.0, 2.0));
    }

    #[test]
    fn paths_split_where_they_leave_the_view() {
        let v = (0.0, 1.0, 0.0, 1.0);
        let path = [
            Point::new(0.5, 0.5),
            Point::new(0.6, 0.5),
            Point::new(2.0, 0.5),
            Point::new(0.7, 0.5),
        ];
        assert_eq!(
            visible_runs(&path, v),
            vec![vec![(0.5, 0.5), (0.6, 0.5)], vec![(0.7, 0.5)]]
        );
        assert_eq!(thin(&path, 2).len(), 3);
    }

    #[test]
    fn the_view_keeps_equal_scales() {
        let truth = [Segment::new(-4.0, -3.0, 4.0, 3.0)];
        let v = view_around(&truth, 0.0);
        assert_eq!(v, (-4.0, 4.0, -3.0, 3.0));
    }
}
