//! Plotting helpers shared by the figure kinds: the bundled font, sizes that
//! stay readable at paper size, greyscale-safe colours, marker shapes and a
//! colour bar.
//!
//! Fonts: DejaVu Sans is compiled into the binary (`fonts/DejaVuSans.ttf`,
//! licence in `fonts/LICENSE-DejaVu.txt`) and registered with plotters under
//! the family name `sans-serif`; plotters' `ab_glyph` feature then lays out
//! and rasterises all text with it. System fonts and fontconfig are never
//! consulted. (SVG files name the family `sans-serif`; SVG viewers draw the
//! text with their own sans-serif font, which is what SVG text is for.)
//!
//! Colours: series colours are samples of viridis, whose lightness increases
//! monotonically, so series stay distinguishable in greyscale; every series
//! also gets its own marker shape (and reference lines their own dash
//! pattern), so nothing depends on colour alone.

use super::backend::Area;
use super::error::ReportError;
use plotters::element::{Drawable, PointCollection};
use plotters::prelude::*;
use plotters::style::colors::colormaps::ViridisRGB;
use plotters_backend::{BackendCoord, DrawingErrorKind};

pub use super::font::FONT_FAMILY;

/// Text and line sizes for a figure of a given pixel size.
///
/// Sizes scale with the smaller side (but at least 62% of the width), so a
/// 1600 x 1000 figure printed 16 cm wide (about 250 dpi) has 8-11 pt text.
#[derive(Clone, Copy, Debug)]
pub struct Theme {
    /// Figure title.
    pub title: u32,
    /// Panel titles and axis descriptions.
    pub label: u32,
    /// Tick labels.
    pub tick: u32,
    /// Legend text.
    pub legend: u32,
    /// Data line width.
    pub line: u32,
    /// Marker size (radius-like, pixels).
    pub marker: i32,
}

impl Theme {
    /// The theme for a figure of `(width, height)` pixels.
    pub fn for_size((w, h): (u32, u32)) -> Self {
        let b = (w.min(h) as f64).max(w as f64 * 0.62);
        Theme {
            title: (b * 0.045).round() as u32,
            label: (b * 0.036).round() as u32,
            tick: (b * 0.031).round() as u32,
            legend: (b * 0.028).round() as u32,
            line: ((b / 420.0).round() as u32).max(1),
            marker: ((b / 160.0).round() as i32).max(3),
        }
    }

    /// Width of legend glyphs (pixels).
    pub fn glyph(&self) -> i32 {
        self.legend as i32 * 2
    }

    /// `legend_area_size` for plotters' series labels: glyph plus a gap.
    pub fn legend_area(&self) -> u32 {
        self.legend * 2 + self.legend / 2
    }

    /// A text style of `size` pixels in the bundled font.
    pub fn font(&self, size: u32) -> TextStyle<'static> {
        (FONT_FAMILY, size).into_font().color(&BLACK)
    }
}

/// Converts a plotters drawing error into a report error.
pub fn draw_err<E: std::fmt::Display>(e: E) -> ReportError {
    ReportError::Render {
        figure: String::new(),
        message: e.to_string(),
    }
}

/// Fills the area white and draws the figure title; returns the area below it.
pub fn titled<'a>(area: &Area<'a>, title: &str, theme: &Theme) -> Result<Area<'a>, ReportError> {
    area.fill(&WHITE).map_err(draw_err)?;
    area.margin(theme.title / 3, 0, 0, 0)
        .titled(title, theme.font(theme.title))
        .map_err(draw_err)
}

/// `c` blended with white: `alpha` = 1 gives `c`, 0 gives white (opaque, so
/// it prints the same in every format).
pub fn mix_white(c: RGBColor, alpha: f64) -> RGBColor {
    let m = |x: u8| (255.0 - (255.0 - x as f64) * alpha).round() as u8;
    RGBColor(m(c.0), m(c.1), m(c.2))
}

/// Viridis at `t` in [0, 1].
pub fn viridis(t: f64) -> RGBColor {
    ViridisRGB::get_color(t.clamp(0.0, 1.0))
}

/// Colour of series `i` of `count`: viridis between 0 and 0.82 (the lightest
/// yellows are avoided on white paper).
pub fn series_color(i: usize, count: usize) -> RGBColor {
    if count <= 1 {
        return viridis(0.0);
    }
    viridis(0.82 * i as f64 / (count - 1) as f64)
}

/// Marker shapes, cycled through by series index.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Marker {
    /// Filled circle.
    Circle,
    /// Filled square.
    Square,
    /// Filled upward triangle.
    Triangle,
    /// Filled diamond.
    Diamond,
    /// Filled downward triangle.
    TriangleDown,
    /// Diagonal cross (unfilled).
    Cross,
    /// Open circle.
    Ring,
    /// Plus sign (unfilled).
    Plus,
}

impl Marker {
    /// All markers, in cycling order.
    pub const ALL: [Marker; 8] = [
        Marker::Circle,
        Marker::Square,
        Marker::Triangle,
        Marker::Diamond,
        Marker::TriangleDown,
        Marker::Cross,
        Marker::Ring,
        Marker::Plus,
    ];

    /// The marker of series `i`.
    pub fn nth(i: usize) -> Marker {
        Marker::ALL[i % Marker::ALL.len()]
    }

    /// A drawable marker centred at `at` (data or pixel coordinates) with half-size `s` pixels.
    pub fn at<C>(self, at: C, s: i32, color: RGBColor) -> MarkerElement<C> {
        MarkerElement {
            at,
            shape: self,
            size: s,
            color,
        }
    }
}

/// A marker as a plotters element (works on every backend).
#[derive(Clone, Debug)]
pub struct MarkerElement<C> {
    at: C,
    shape: Marker,
    size: i32,
    color: RGBColor,
}

impl<'a, C: 'a> PointCollection<'a, C> for &'a MarkerElement<C> {
    type Point = &'a C;
    type IntoIter = std::iter::Once<&'a C>;
    fn point_iter(self) -> Self::IntoIter {
        std::iter::once(&self.at)
    }
}

impl<C, DB: DrawingBackend> Drawable<DB> for MarkerElement<C> {
    fn draw<I: Iterator<Item = BackendCoord>>(
        &self,
        mut points: I,
        backend: &mut DB,
        _: (u32, u32),
    ) -> Result<(), DrawingErrorKind<DB::ErrorType>> {
        let Some((x, y)) = points.next() else {
            return Ok(());
        };
        let s = self.size;
        let fill = ShapeStyle::from(&self.color).filled();
        let stroke = ShapeStyle::from(&self.color).stroke_width((s as u32 / 3).max(2));
        let poly = |pts: &[(i32, i32)]| -> Vec<BackendCoord> {
            pts.iter().map(|&(dx, dy)| (x + dx, y + dy)).collect()
        };
        match self.shape {
            Marker::Circle => backend.draw_circle((x, y), s as u32, &fill, true),
            Marker::Ring => backend.draw_circle((x, y), s as u32, &stroke, false),
            Marker::Square => {
                let t = (s as f64 * 0.85) as i32;
                backend.draw_rect((x - t, y - t), (x + t, y + t), &fill, true)
            }
            Marker::Triangle => {
                let t = (s as f64 * 1.15) as i32;
                backend.fill_polygon(poly(&[(0, -t), (t, t * 3 / 4), (-t, t * 3 / 4)]), &fill)
            }
            Marker::TriangleDown => {
                let t = (s as f64 * 1.15) as i32;
                backend.fill_polygon(poly(&[(0, t), (t, -t * 3 / 4), (-t, -t * 3 / 4)]), &fill)
            }
            Marker::Diamond => {
                let t = (s as f64 * 1.2) as i32;
                backend.fill_polygon(poly(&[(0, -t), (t, 0), (0, t), (-t, 0)]), &fill)
            }
            Marker::Cross => {
                backend.draw_line((x - s, y - s), (x + s, y + s), &stroke)?;
                backend.draw_line((x - s, y + s), (x + s, y - s), &stroke)
            }
            Marker::Plus => {
                backend.draw_line((x - s, y), (x + s, y), &stroke)?;
                backend.draw_line((x, y - s), (x, y + s), &stroke)
            }
        }
    }
}

/// A legend glyph: a (dashed) line, a marker, or a filled box, `width` pixels wide,
/// starting at the legend anchor. Use [`Theme::glyph`] as width and
/// [`Theme::legend_area`] for `legend_area_size` so text never overlaps it.
#[derive(Clone, Copy, Debug)]
pub struct LegendGlyph {
    at: BackendCoord,
    width: i32,
    color: RGBColor,
    line: u32,
    dash: Option<(u32, u32)>,
    marker: Option<(Marker, i32)>,
    boxed: bool,
}

impl LegendGlyph {
    /// A solid line.
    pub fn line(at: BackendCoord, th: &Theme, color: RGBColor, line: u32) -> Self {
        LegendGlyph {
            at,
            width: th.glyph(),
            color,
            line,
            dash: None,
            marker: None,
            boxed: false,
        }
    }
    /// A dashed line with (dash, gap) lengths.
    pub fn dashed(mut self, dash: (u32, u32)) -> Self {
        self.dash = Some(dash);
        self
    }
    /// A marker in the middle (and no line if `line` was 0).
    pub fn marker(mut self, m: Marker, size: i32) -> Self {
        self.marker = Some((m, size));
        self
    }
    /// A filled box instead of a line.
    pub fn boxed(mut self) -> Self {
        self.boxed = true;
        self
    }
}

impl<'a> PointCollection<'a, BackendCoord> for &'a LegendGlyph {
    type Point = &'a BackendCoord;
    type IntoIter = std::iter::Once<&'a BackendCoord>;
    fn point_iter(self) -> Self::IntoIter {
        std::iter::once(&self.at)
    }
}

impl<DB: DrawingBackend> Drawable<DB> for LegendGlyph {
    fn draw<I: Iterator<Item = BackendCoord>>(
        &self,
        mut points: I,
        backend: &mut DB,
        size: (u32, u32),
    ) -> Result<(), DrawingErrorKind<DB::ErrorType>> {
        let Some((x, y)) = points.next() else {
            return Ok(());
        };
        let w = self.width;
        if self.boxed {
            let h = w / 3;
            backend.draw_rect(
                (x, y - h),
                (x + w, y + h),
                &ShapeStyle::from(&self.color).filled(),
                true,
            )?;
            backend.draw_rect(
                (x, y - h),
                (x + w, y + h),
                &ShapeStyle::from(&BLACK.mix(0.5)),
                false,
            )?;
        } else if self.line > 0 {
            let style = ShapeStyle::from(&self.color).stroke_width(self.line);
            match self.dash {
                None => backend.draw_line((x, y), (x + w, y), &style)?,
                Some((d, g)) => {
                    let (d, g) = (d.max(1) as i32, g as i32);
                    let mut a = x;
                    while a < x + w {
                        backend.draw_line((a, y), ((a + d).min(x + w), y), &style)?;
                        a += d + g;
                    }
                }
            }
        }
        if let Some((m, s)) = self.marker {
            if self.boxed {
                // On a box of its own colour: a white halo, as on the maps.
                m.at((), s + 2, WHITE)
                    .draw(std::iter::once((x + w / 2, y)), backend, size)?;
            }
            m.at((), s, self.color)
                .draw(std::iter::once((x + w / 2, y)), backend, size)?;
        }
        Ok(())
    }
}

/// Draws a legend in its own area (beside a chart rather than over its data):
/// one glyph per entry, followed by one or more text lines. The glyphs must
/// have been made with anchor `(0, 0)`; they are moved into place here.
pub fn side_legend(
    area: &Area<'_>,
    entries: &[(LegendGlyph, Vec<String>)],
    theme: &Theme,
) -> Result<(), ReportError> {
    let x = theme.tick as i32;
    let line_h = theme.legend as i32 * 5 / 4;
    let mut y = theme.label as i32 * 2;
    let (w, _) = area.dim_in_pixel();
    let font = theme.font(theme.legend);
    for (glyph, lines) in entries {
        let mut g = *glyph;
        g.at = (x, y + theme.legend as i32 / 2);
        area.draw(&g).map_err(draw_err)?;
        // Text that would leave the area is wrapped at its separators.
        let room = (w as i32 - x - g.width - theme.legend as i32).max(1) as u32;
        let lines: Vec<String> = lines
            .iter()
            .flat_map(|t| {
                wrap_text(t, room, |s| {
                    area.estimate_text_size(s, &font).map_or(0, |d| d.0)
                })
            })
            .collect();
        for (k, text) in lines.iter().enumerate() {
            area.draw(&Text::new(
                text.clone(),
                (x + g.width + theme.legend as i32 / 2, y + k as i32 * line_h),
                theme.font(theme.legend),
            ))
            .map_err(draw_err)?;
        }
        y += line_h * lines.len().max(1) as i32 + theme.legend as i32 / 2;
    }
    Ok(())
}

/// Splits `text` into lines no wider than `room` pixels (by `width`), breaking
/// after a space, `:`, `/`, `,` or `_`; a piece without a break point that is
/// still too wide stays whole. Text that fits is one line.
pub fn wrap_text(text: &str, room: u32, width: impl Fn(&str) -> u32) -> Vec<String> {
    if width(text) <= room {
        return vec![text.to_owned()];
    }
    // Pieces ending at a break character (kept with the piece before it).
    let mut pieces = Vec::new();
    let mut start = 0;
    for (i, c) in text.char_indices() {
        if matches!(c, ' ' | ':' | '/' | ',' | '_') {
            pieces.push(&text[start..i + c.len_utf8()]);
            start = i + c.len_utf8();
        }
    }
    if start < text.len() {
        pieces.push(&text[start..]);
    }
    let mut out: Vec<String> = Vec::new();
    let mut cur = String::new();
    for p in pieces {
        let joined = format!("{cur}{p}");
        if !cur.is_empty() && width(joined.trim_end()) > room {
            out.push(cur.trim_end().to_owned());
            cur = p.to_owned();
        } else {
            cur = joined;
        }
    }
    if !cur.trim_end().is_empty() {
        out.push(cur.trim_end().to_owned());
    }
    out
}

/// A tick label of a log axis: the decimal form from 0.01 to below 10^4
/// (`0.1`, `1`, `10`), the power of ten outside (`1e-5`, `1e5`); never
/// `1e0`.
pub fn log_tick(y: f64) -> String {
    if (0.01..1e4).contains(&y.abs()) {
        tick((y * 1e6).round() / 1e6)
    } else {
        format!("{y:.0e}")
    }
}

/// Dash patterns for reference lines: (dash length, gap) in pixels, scaled by the line width.
pub fn dash(i: usize, theme: &Theme) -> (u32, u32) {
    let w = theme.line.max(1);
    match i % 3 {
        0 => (8 * w, 5 * w),
        1 => (2 * w, 4 * w),
        _ => (14 * w, 5 * w),
    }
}

/// `r` with the index `k` as Unicode subscript digits (`r₁₂`).
pub fn subscript(base: &str, k: usize) -> String {
    const SUB: [char; 10] = ['₀', '₁', '₂', '₃', '₄', '₅', '₆', '₇', '₈', '₉'];
    let digits: String = k
        .to_string()
        .chars()
        .map(|c| SUB[c.to_digit(10).unwrap_or(0) as usize])
        .collect();
    format!("{base}{digits}")
}

/// Points of the circle |z| = r, for drawing in the complex plane.
pub fn circle_points(r: f64, samples: usize) -> Vec<(f64, f64)> {
    (0..=samples)
        .map(|k| {
            let t = std::f64::consts::TAU * k as f64 / samples as f64;
            (r * t.cos(), r * t.sin())
        })
        .collect()
}

/// Draws a vertical colour bar for `color(t)`, t in [0, 1], spanning the values
/// [vmin, vmax]: the bar at the left of `area`, tick labels to its right, and
/// `label` written vertically at the right edge.
pub fn colorbar(
    area: &Area<'_>,
    vmin: f64,
    vmax: f64,
    label: &str,
    theme: &Theme,
    color: &dyn Fn(f64) -> RGBColor,
) -> Result<(), ReportError> {
    let (w, h) = area.dim_in_pixel();
    let bar = theme.label as i32 * 2;
    let ticks = theme.tick * 4;
    let left = theme.tick as i32;
    let right = (w as i32 - left - bar - ticks as i32).max(0);
    let mut chart = ChartBuilder::on(area)
        .margin_top(theme.label as i32 * 2)
        .margin_bottom(theme.label as i32 * 4)
        .margin_left(left)
        .margin_right(right)
        .right_y_label_area_size(ticks)
        .build_cartesian_2d(0.0..1.0, vmin..vmax)
        .map_err(draw_err)?
        .set_secondary_coord(0.0..1.0, vmin..vmax);
    chart
        .configure_secondary_axes()
        .y_labels(6)
        .label_style(theme.font(theme.tick))
        .draw()
        .map_err(draw_err)?;
    let steps = 200;
    chart
        .draw_series((0..steps).map(|k| {
            let a = vmin + (vmax - vmin) * k as f64 / steps as f64;
            let b = vmin + (vmax - vmin) * (k + 1) as f64 / steps as f64;
            Rectangle::new(
                [(0.0, a), (1.0, b)],
                color(k as f64 / (steps - 1) as f64).filled(),
            )
        }))
        .map_err(draw_err)?;
    let x = (w as i32 - theme.label as i32 / 2 - 2).max(0);
    area.draw(&Text::new(
        label.to_owned(),
        (x, h as i32 / 2),
        theme
            .font(theme.label)
            .transform(FontTransform::Rotate270)
            .pos(plotters::style::text_anchor::Pos::new(
                plotters::style::text_anchor::HPos::Center,
                plotters::style::text_anchor::VPos::Bottom,
            )),
    ))
    .map_err(draw_err)?;
    Ok(())
}

/// Draws the series legend inside the plot area at `position`, in the report's
/// style (legend font, translucent white box, thin border).
pub fn inner_legend<'a, DB, CT>(
    chart: &mut ChartContext<'a, DB, CT>,
    position: SeriesLabelPosition,
    th: &Theme,
) -> Result<(), ReportError>
where
    DB: DrawingBackend + 'a,
    CT: CoordTranslate,
{
    chart
        .configure_series_labels()
        .position(position)
        .label_font(th.font(th.legend))
        .legend_area_size(th.legend_area())
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK.mix(0.5))
        .margin(th.legend as i32 / 2)
        .draw()
        .map_err(draw_err)
}

/// Colour of a subdominant class (math doc section 7) in class maps: the
/// common classes get well-separated viridis samples, the rare ones dark or
/// grey fills; unknown names get a light grey.
pub fn class_color(class: &str) -> RGBColor {
    match class {
        "standard" => RGBColor(20, 20, 20),
        "real_distinct" => viridis(0.35),
        "complex_pair" => viridis(0.9),
        "defective" => RGBColor(110, 110, 110),
        "not_separated" => RGBColor(160, 160, 160),
        // the class-free verdict of `verify --property g1`: a hue apart
        // from the viridis classes, since its cells hold either class
        "g1" => RGBColor(230, 145, 56),
        _ => RGBColor(215, 215, 215),
    }
}

/// A class's legend swatch: the `2s x 2s` box with top-left corner `(x, y)`,
/// filled with [`class_color`] and outlined in black.
pub fn class_swatch(
    side: &Area<'_>,
    (x, y): (i32, i32),
    s: i32,
    class: &str,
) -> Result<(), ReportError> {
    let bx = [(x, y), (x + s * 2, y + s * 2)];
    side.draw(&Rectangle::new(bx, class_color(class).filled()))
        .map_err(draw_err)?;
    side.draw(&Rectangle::new(bx, BLACK.stroke_width(1)))
        .map_err(draw_err)
}

/// A tick label: at most 6 decimals with trailing zeros removed, scientific
/// notation below 1e-4 and from 1e6 on, and never a negative zero: a value
/// below [`TICK_ZERO`] in modulus (a rounding residue of the tick arithmetic
/// on linear axes, e.g. `-0.85 + 5 * 0.17`) is written `0`.
pub fn tick(v: f64) -> String {
    let a = v.abs();
    if a < TICK_ZERO {
        return "0".to_owned();
    }
    if !(1e-4..1e6).contains(&a) {
        return format!("{v:e}");
    }
    let s = format!("{v:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".to_owned()
    } else {
        s.to_owned()
    }
}

/// Tick values below this modulus are written `0` by [`tick`]: 1e-12 is far
/// below any tick step of the figures (the smallest axis span is ~1e-7, on
/// log axes, which format their own ticks).
pub const TICK_ZERO: f64 = 1e-12;

/// Clips a polyline to the box `[x0, x1] x [y0, y1]`: the pieces inside, each
/// a polyline of its own, with the crossing points interpolated on the box
/// edge (plotters would otherwise draw points outside the plot area along its
/// frame).
pub fn clip_polyline(
    points: &[(f64, f64)],
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
) -> Vec<Vec<(f64, f64)>> {
    let inside = |p: (f64, f64)| x0 <= p.0 && p.0 <= x1 && y0 <= p.1 && p.1 <= y1;
    // Liang-Barsky clip of the segment a-b; None if it misses the box.
    let clip = |a: (f64, f64), b: (f64, f64)| -> Option<((f64, f64), (f64, f64))> {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let (mut t0, mut t1) = (0.0f64, 1.0f64);
        for (p, q) in [
            (-dx, a.0 - x0),
            (dx, x1 - a.0),
            (-dy, a.1 - y0),
            (dy, y1 - a.1),
        ] {
            if p == 0.0 {
                if q < 0.0 {
                    return None;
                }
            } else {
                let r = q / p;
                if p < 0.0 {
                    t0 = t0.max(r);
                } else {
                    t1 = t1.min(r);
                }
            }
        }
        (t0 <= t1).then_some((
            (a.0 + t0 * dx, a.1 + t0 * dy),
            (a.0 + t1 * dx, a.1 + t1 * dy),
        ))
    };
    let mut out: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut cur: Vec<(f64, f64)> = Vec::new();
    for w in points.windows(2) {
        match clip(w[0], w[1]) {
            Some((p, q)) => {
                if cur.is_empty() {
                    cur.push(p);
                }
                cur.push(q);
                if !inside(w[1]) {
                    out.push(std::mem::take(&mut cur));
                }
            }
            None => {
                if !cur.is_empty() {
                    out.push(std::mem::take(&mut cur));
                }
            }
        }
    }
    if !cur.is_empty() {
        out.push(cur);
    }
    out.retain(|p| p.len() > 1);
    out
}

/// Axis ranges with equal scale on both axes (a circle stays round) for a
/// plot area of `(w, h)` pixels that must show the box `[x0, x1] x [y0, y1]`:
/// the box is centred and the axis with room to spare is widened.
pub fn equal_aspect(
    (w, h): (u32, u32),
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
) -> ((f64, f64), (f64, f64)) {
    let (w, h) = (w.max(1) as f64, h.max(1) as f64);
    let scale = (w / (x1 - x0)).min(h / (y1 - y0));
    let (cx, cy) = ((x0 + x1) / 2.0, (y0 + y1) / 2.0);
    let (hx, hy) = (w / scale / 2.0, h / scale / 2.0);
    ((cx - hx, cx + hx), (cy - hy, cy + hy))
}

/// Draws a legend as rows of entries (glyph and one line of text) across
/// `area`, wrapping to a new row when an entry does not fit; returns the
/// height used. The glyphs must have been made with anchor `(0, 0)`.
pub fn legend_rows(
    area: &Area<'_>,
    entries: &[(LegendGlyph, String)],
    theme: &Theme,
) -> Result<u32, ReportError> {
    let (w, _) = area.dim_in_pixel();
    let font = theme.font(theme.legend);
    let gap = theme.legend as i32 * 2;
    let row_h = theme.legend as i32 * 3 / 2;
    let (mut x, mut y) = (gap / 2, 0);
    let widths: Vec<i32> = entries
        .iter()
        .map(|(g, text)| {
            let tw = area.estimate_text_size(text, &font).map_or(0, |s| s.0) as i32;
            g.width + theme.legend as i32 / 2 + tw
        })
        .collect();
    for ((glyph, text), ew) in entries.iter().zip(widths) {
        if x > gap / 2 && x + ew > w as i32 {
            x = gap / 2;
            y += row_h;
        }
        let mut g = *glyph;
        g.at = (x, y + theme.legend as i32 / 2);
        area.draw(&g).map_err(draw_err)?;
        area.draw(&Text::new(
            text.clone(),
            (x + g.width + theme.legend as i32 / 2, y),
            font.clone(),
        ))
        .map_err(draw_err)?;
        x += ew + gap;
    }
    Ok((y + row_h) as u32)
}

/// The height [`legend_rows`] will use for `entries` on an area `width` wide.
pub fn legend_rows_height(
    area: &Area<'_>,
    width: u32,
    entries: &[(LegendGlyph, String)],
    theme: &Theme,
) -> u32 {
    let font = theme.font(theme.legend);
    let gap = theme.legend as i32 * 2;
    let row_h = theme.legend as i32 * 3 / 2;
    let (mut x, mut rows) = (gap / 2, 1);
    for (g, text) in entries {
        let tw = area.estimate_text_size(text, &font).map_or(0, |s| s.0) as i32;
        let ew = g.width + theme.legend as i32 / 2 + tw;
        if x > gap / 2 && x + ew > width as i32 {
            x = gap / 2;
            rows += 1;
        }
        x += ew + gap;
    }
    (rows * row_h) as u32
}

/// The chart of a knot-space map panel ([`square_ratio_panel`]).
pub type RatioChart<'a> = ChartContext<
    'a,
    super::backend::AnyBackend<'a>,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;

/// A square chart over `[lo, hi]^2` with axes `r₀`, `r₁` (the knot-space
/// maps: `knot-map` and `certified-map`), inside the panel `pa` under the
/// caption `caption`. The panel is first centred vertically for an
/// estimated caption height, the caption drawn, then the longer side padded
/// so that the plot area is exactly square (equal aspect on the square).
/// `y_tick` formats the `r₁` tick labels. Returns the chart and the side of
/// its plot area in pixels.
pub fn square_ratio_panel<'a>(
    pa: &Area<'a>,
    caption: &str,
    th: &Theme,
    [lo, hi]: [f64; 2],
    y_tick: &dyn Fn(&f64) -> String,
) -> Result<(RatioChart<'a>, u32), ReportError> {
    let (pw, ph) = pa.dim_in_pixel();
    let xl = th.label * 3;
    let yl = th.label * 3;
    let (ml, mr) = (th.tick / 2, th.tick);
    let cap = th.label * 2;
    let est = pw
        .saturating_sub(yl + ml + mr)
        .min(ph.saturating_sub(xl + cap));
    let pad0 = ph.saturating_sub(xl + cap + est) / 2;
    let pa = pa.margin(pad0, pad0, 0, 0);
    let pa = pa.titled(caption, th.font(th.label)).map_err(draw_err)?;
    let (pw, ph) = pa.dim_in_pixel();
    let avail_w = pw.saturating_sub(yl + ml + mr);
    let avail_h = ph.saturating_sub(xl);
    let plot_w = avail_w.min(avail_h).max(1);
    let pad_h = avail_w.saturating_sub(plot_w) / 2;
    let pad_v = avail_h.saturating_sub(plot_w);
    let mut chart = ChartBuilder::on(&pa)
        .margin_left((ml + pad_h) as i32)
        .margin_right((mr + avail_w.saturating_sub(plot_w + pad_h)) as i32)
        .margin_top((pad_v / 2) as i32)
        .margin_bottom((pad_v - pad_v / 2) as i32)
        .x_label_area_size(xl)
        .y_label_area_size(yl)
        .build_cartesian_2d(lo..hi, lo..hi)
        .map_err(draw_err)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc("r₀")
        .y_desc("r₁")
        .x_labels(3)
        .y_labels(3)
        .label_style(th.font(th.tick))
        .axis_desc_style(th.font(th.label))
        .x_label_formatter(&|x| tick(*x))
        .y_label_formatter(y_tick)
        .draw()
        .map_err(draw_err)?;
    Ok((chart, plot_w))
}

/// The cells of a `grid x grid` map as filled rectangles, the runs of equal
/// colour along each row merged into one rectangle (fewer SVG elements):
/// `color(i, j)` is the colour of cell `i` of row `j` (`r₁` cell `j`), and
/// cell boundary `k` lies at `at(k)` on both axes.
pub fn row_runs(
    grid: usize,
    at: impl Fn(usize) -> f64,
    color: impl Fn(usize, usize) -> RGBColor,
) -> Vec<Rectangle<(f64, f64)>> {
    let mut rects = Vec::new();
    for j in 0..grid {
        let mut start = 0;
        while start < grid {
            let col = color(start, j);
            let mut end = start + 1;
            while end < grid && color(end, j) == col {
                end += 1;
            }
            rects.push(Rectangle::new(
                [(at(start), at(j)), (at(end), at(j + 1))],
                col.filled(),
            ));
            start = end;
        }
    }
    rects
}

#[cfg(test)]
mod doc_examples {
    //! The examples of this private module's items (not doctests: the module is
    //! not public).
    use super::*;

    #[test]
    fn log_ticks_are_decimal_near_one() {
        assert_eq!(log_tick(1.0), "1");
        assert_eq!(log_tick(10.0), "10");
        assert_eq!(log_tick(0.01), "0.01");
        assert_eq!(log_tick(1e-3), "1e-3");
        assert_eq!(log_tick(1e5), "1e5");
    }

    #[test]
    fn wrap_text_breaks_at_separators_only_when_needed() {
        let w = |s: &str| 10 * s.chars().count() as u32;
        assert_eq!(wrap_text("standard", 80, w), ["standard"]);
        assert_eq!(
            wrap_text("indeterminate:standard/defective", 200, w),
            ["indeterminate:", "standard/defective"]
        );
        assert_eq!(
            wrap_text("indeterminate:standard/defective", 100, w),
            ["indeterminate:", "standard/", "defective"]
        );
        assert_eq!(
            wrap_text("unbreakablelongword", 50, w),
            ["unbreakablelongword"]
        );
    }

    #[test]
    fn tick_examples() {
        assert_eq!(tick(-0.0), "0");
        assert_eq!(tick(-1e-17), "0");
        assert_eq!(tick(0.30000000000000004), "0.3");
        assert_eq!(tick(2.0), "2");
        assert_eq!(tick(1e-5), "1e-5");
    }

    #[test]
    fn clip_polyline_example() {
        let p = clip_polyline(
            &[(-1.0, 0.5), (0.5, 0.5), (2.0, 0.5)],
            (0.0, 1.0),
            (0.0, 1.0),
        );
        assert_eq!(p, vec![vec![(0.0, 0.5), (0.5, 0.5), (1.0, 0.5)]]);
    }

    #[test]
    fn equal_aspect_example() {
        let ((a, b), (c, d)) = equal_aspect((400, 200), (0.0, 1.0), (0.0, 1.0));
        assert_eq!(((a, b), (c, d)), ((-0.5, 1.5), (0.0, 1.0)));
    }
}
