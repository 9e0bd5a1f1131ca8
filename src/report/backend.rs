//! One drawing backend type for both output formats, and the in-memory
//! renderers (SVG into a `String`, PNG into a byte vector).
//!
//! Figures draw on a [`DrawingArea`] of [`AnyBackend`], so a figure's drawing
//! code is written once and runs against the SVG and the bitmap backend alike.
//! Text is laid out with the bundled DejaVu Sans font (see [`super::plot`]);
//! nothing here touches the file system or the system fonts.

use super::error::ReportError;
use super::font::ensure_font;
use plotters::coord::Shift;
use plotters::prelude::{BitMapBackend, DrawingArea, IntoDrawingArea, SVGBackend};
use plotters_backend::{
    BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingBackend, DrawingErrorKind,
};
use std::error::Error as StdError;
use std::fmt;

/// The drawing area every figure renders on.
pub type Area<'a> = DrawingArea<AnyBackend<'a>, Shift>;

/// Either an SVG or an RGB bitmap backend (both in memory).
pub enum AnyBackend<'a> {
    /// Vector output into a string.
    Svg(SVGBackend<'a>),
    /// Raster output into an RGB buffer.
    Bitmap(BitMapBackend<'a>),
}

/// A backend error of either kind, as text.
#[derive(Debug)]
pub struct AnyBackendError(String);

impl fmt::Display for AnyBackendError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl StdError for AnyBackendError {}

fn conv<E: StdError + Send + Sync>(e: DrawingErrorKind<E>) -> DrawingErrorKind<AnyBackendError> {
    match e {
        DrawingErrorKind::DrawingError(e) => {
            DrawingErrorKind::DrawingError(AnyBackendError(e.to_string()))
        }
        DrawingErrorKind::FontError(e) => DrawingErrorKind::FontError(e),
    }
}

macro_rules! dispatch {
    ($self:expr, $b:ident => $body:expr) => {
        match $self {
            AnyBackend::Svg($b) => $body.map_err(conv),
            AnyBackend::Bitmap($b) => $body.map_err(conv),
        }
    };
}

type R<T = ()> = Result<T, DrawingErrorKind<AnyBackendError>>;

impl DrawingBackend for AnyBackend<'_> {
    type ErrorType = AnyBackendError;

    fn get_size(&self) -> (u32, u32) {
        match self {
            AnyBackend::Svg(b) => b.get_size(),
            AnyBackend::Bitmap(b) => b.get_size(),
        }
    }
    fn ensure_prepared(&mut self) -> R {
        dispatch!(self, b => b.ensure_prepared())
    }
    fn present(&mut self) -> R {
        dispatch!(self, b => b.present())
    }
    fn draw_pixel(&mut self, point: BackendCoord, color: BackendColor) -> R {
        dispatch!(self, b => b.draw_pixel(point, color))
    }
    fn draw_line<S: BackendStyle>(&mut self, from: BackendCoord, to: BackendCoord, style: &S) -> R {
        dispatch!(self, b => b.draw_line(from, to, style))
    }
    fn draw_rect<S: BackendStyle>(
        &mut self,
        upper_left: BackendCoord,
        bottom_right: BackendCoord,
        style: &S,
        fill: bool,
    ) -> R {
        dispatch!(self, b => b.draw_rect(upper_left, bottom_right, style, fill))
    }
    fn draw_path<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        style: &S,
    ) -> R {
        dispatch!(self, b => b.draw_path(path, style))
    }
    fn draw_circle<S: BackendStyle>(
        &mut self,
        center: BackendCoord,
        radius: u32,
        style: &S,
        fill: bool,
    ) -> R {
        dispatch!(self, b => b.draw_circle(center, radius, style, fill))
    }
    fn fill_polygon<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        vert: I,
        style: &S,
    ) -> R {
        dispatch!(self, b => b.fill_polygon(vert, style))
    }
    fn draw_text<T: BackendTextStyle>(&mut self, text: &str, style: &T, pos: BackendCoord) -> R {
        dispatch!(self, b => b.draw_text(text, style, pos))
    }
    fn estimate_text_size<T: BackendTextStyle>(&self, text: &str, style: &T) -> R<(u32, u32)> {
        match self {
            AnyBackend::Svg(b) => b.estimate_text_size(text, style).map_err(conv),
            AnyBackend::Bitmap(b) => b.estimate_text_size(text, style).map_err(conv),
        }
    }
    fn blit_bitmap(&mut self, pos: BackendCoord, size: (u32, u32), src: &[u8]) -> R {
        dispatch!(self, b => b.blit_bitmap(pos, size, src))
    }
}

/// A drawing routine: draws one figure on the given area.
pub type DrawFn<'f> = dyn Fn(&Area<'_>) -> Result<(), ReportError> + 'f;

fn present_err(e: impl fmt::Display) -> ReportError {
    ReportError::Render {
        figure: String::new(),
        message: e.to_string(),
    }
}

/// Renders a drawing routine into an SVG document of `size` (pixels).
pub fn render_svg(size: (u32, u32), draw: &DrawFn<'_>) -> Result<String, ReportError> {
    ensure_font()?;
    let mut out = String::new();
    {
        let area = AnyBackend::Svg(SVGBackend::with_string(&mut out, size)).into_drawing_area();
        draw(&area)?;
        area.present().map_err(present_err)?;
    }
    Ok(thin_svg(&out))
}

/// Renders a drawing routine into an RGB bitmap of `size` and encodes it as PNG
/// (8-bit RGB at the figure's full pixel size: paper resolution is kept; only
/// the deflate level trades time for size).
pub fn render_png(size: (u32, u32), draw: &DrawFn<'_>) -> Result<Vec<u8>, ReportError> {
    ensure_font()?;
    let (w, h) = size;
    let mut rgb = vec![255u8; w as usize * h as usize * 3];
    {
        let area =
            AnyBackend::Bitmap(BitMapBackend::with_buffer(&mut rgb, size)).into_drawing_area();
        draw(&area)?;
        area.present().map_err(present_err)?;
    }
    encode_png(&rgb, size)
}

/// Encodes an 8-bit RGB buffer as PNG.
pub fn encode_png(rgb: &[u8], (w, h): (u32, u32)) -> Result<Vec<u8>, ReportError> {
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, w, h);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        // Deflate level 6 (flate2's default): about 2.7x smaller than the
        // `Fast` encoder on the report's figures, at about 0.1 s per
        // 1800 x 1200 figure (measured, see docs of [`render_png`]).
        enc.set_compression(png::Compression::Default);
        let mut writer = enc.write_header().map_err(present_err)?;
        writer.write_image_data(rgb).map_err(present_err)?;
        writer.finish().map_err(present_err)?;
    }
    Ok(out)
}

/// Most decimals kept in a number of an SVG attribute value: 2 (pixel
/// coordinates are integers already; font sizes and opacities need no more
/// than 1/100 pixel or 1/100 of full opacity).
pub const SVG_DECIMALS: usize = 2;

/// Thins an SVG written by plotters without changing what it shows:
///
/// * elements drawn with `opacity="0"` (invisible) and text elements without
///   text are dropped;
/// * the default attributes `opacity="1"` and, on `<rect>`, `stroke="none"` are dropped;
/// * numbers in attribute values keep at most [`SVG_DECIMALS`] decimals;
/// * a run of consecutive filled `<rect>`s (a heat map, drawn cell row by
///   cell row) whose pixel boxes do not overlap is written as one `<path>` per
///   fill colour (painting order within the run cannot matter when no pixel is
///   painted twice).
///
/// Text content is never changed.
pub fn thin_svg(svg: &str) -> String {
    let mut out = String::with_capacity(svg.len() / 2);
    let mut run: Vec<RectBox> = Vec::new();
    // An open text element: its opening tag (thinned) and content lines.
    let mut text: Option<(String, Vec<&str>, bool)> = None;
    for line in svg.lines() {
        if let Some((tag, content, visible)) = text.as_mut() {
            if line.starts_with("</text>") {
                // Empty or invisible text elements are dropped.
                if *visible && content.iter().any(|c| !c.trim().is_empty()) {
                    out.push_str(tag);
                    out.push('\n');
                    for c in content.iter() {
                        out.push_str(c);
                        out.push('\n');
                    }
                    out.push_str(line);
                    out.push('\n');
                }
                text = None;
            } else {
                content.push(line);
            }
            continue;
        }
        let invisible = line.starts_with('<') && line.contains(" opacity=\"0\"");
        if line.starts_with("<text") && !line.contains("</text>") {
            flush_rects(&mut run, &mut out);
            text = Some((thin_attributes(line), Vec::new(), !invisible));
            continue;
        }
        if invisible {
            continue;
        }
        if let Some(r) = RectBox::parse(line) {
            run.push(r);
            continue;
        }
        flush_rects(&mut run, &mut out);
        out.push_str(&thin_attributes(line));
        out.push('\n');
    }
    flush_rects(&mut run, &mut out);
    out
}

/// A filled, fully opaque `<rect>` of plotters' SVG output.
struct RectBox {
    x: i64,
    y: i64,
    w: i64,
    h: i64,
    fill: String,
    line: String,
}

impl RectBox {
    fn parse(line: &str) -> Option<RectBox> {
        let body = line.strip_prefix("<rect ")?.strip_suffix("/>")?;
        let mut x = None;
        let mut y = None;
        let mut w = None;
        let mut h = None;
        let mut fill = None;
        for part in body.split_whitespace() {
            let (k, v) = part.split_once('=')?;
            let v = v.strip_prefix('"')?.strip_suffix('"')?;
            match k {
                "x" => x = v.parse().ok(),
                "y" => y = v.parse().ok(),
                "width" => w = v.parse().ok(),
                "height" => h = v.parse().ok(),
                "fill" if v.starts_with('#') => fill = Some(v.to_owned()),
                "opacity" if v == "1" => {}
                "stroke" if v == "none" => {}
                _ => return None,
            }
        }
        Some(RectBox {
            x: x?,
            y: y?,
            w: w?,
            h: h?,
            fill: fill?,
            line: line.to_owned(),
        })
    }
}

/// Writes a run of filled rectangles: one `<path>` per colour if no two of
/// them overlap (and the run has more than one), else each as it was (thinned).
fn flush_rects(run: &mut Vec<RectBox>, out: &mut String) {
    use std::fmt::Write as _;
    if run.is_empty() {
        return;
    }
    if run.len() > 1 && !rects_overlap(run) {
        let mut colours: Vec<&str> = Vec::new();
        for r in run.iter() {
            if !colours.contains(&r.fill.as_str()) {
                colours.push(&r.fill);
            }
        }
        for c in colours {
            let _ = write!(out, "<path fill=\"{c}\" d=\"");
            for r in run.iter().filter(|r| r.fill == c) {
                let _ = write!(out, "M{} {}h{}v{}h{}z", r.x, r.y, r.w, r.h, -r.w);
            }
            out.push_str("\"/>\n");
        }
    } else {
        for r in run.iter() {
            out.push_str(&thin_attributes(&r.line));
            out.push('\n');
        }
    }
    run.clear();
}

/// Whether two rectangles of the run share a pixel (sweep over rows of a
/// bounding-box bitmap; the run is small next to the canvas).
fn rects_overlap(run: &[RectBox]) -> bool {
    let x0 = run.iter().map(|r| r.x).min().unwrap_or(0);
    let y0 = run.iter().map(|r| r.y).min().unwrap_or(0);
    let x1 = run.iter().map(|r| r.x + r.w.max(0)).max().unwrap_or(0);
    let y1 = run.iter().map(|r| r.y + r.h.max(0)).max().unwrap_or(0);
    let (w, h) = ((x1 - x0).max(0) as usize, (y1 - y0).max(0) as usize);
    if w.saturating_mul(h) > 64_000_000 {
        return true; // too large to check: keep the order
    }
    let mut seen = vec![false; w * h];
    for r in run {
        for yy in (r.y - y0)..(r.y - y0 + r.h.max(0)) {
            let row = yy as usize * w;
            for xx in (r.x - x0)..(r.x - x0 + r.w.max(0)) {
                let i = row + xx as usize;
                if seen[i] {
                    return true;
                }
                seen[i] = true;
            }
        }
    }
    false
}

/// Drops default attributes and shortens long decimals in one tag line.
fn thin_attributes(line: &str) -> String {
    if !line.starts_with('<') || line.starts_with("</") {
        return line.to_owned();
    }
    let mut s = line.replace(" opacity=\"1\"", "");
    if s.starts_with("<rect") {
        s = s.replace(" stroke=\"none\"", "");
    }
    shorten_numbers(&s)
}

/// Rounds every decimal number with more than [`SVG_DECIMALS`] decimals inside
/// double quotes to that many (trailing zeros removed).
fn shorten_numbers(s: &str) -> String {
    let b = s.as_bytes();
    let mut out: Vec<u8> = Vec::with_capacity(s.len());
    let mut i = 0;
    let mut in_quotes = false;
    while i < b.len() {
        let c = b[i];
        if c == b'"' {
            in_quotes = !in_quotes;
        }
        if in_quotes && c.is_ascii_digit() && (i == 0 || !b[i - 1].is_ascii_alphanumeric()) {
            let start = i;
            while i < b.len() && b[i].is_ascii_digit() {
                i += 1;
            }
            if i < b.len() && b[i] == b'.' {
                let dot = i;
                i += 1;
                while i < b.len() && b[i].is_ascii_digit() {
                    i += 1;
                }
                let text = &s[start..i];
                if i - dot - 1 > SVG_DECIMALS {
                    if let Ok(v) = text.parse::<f64>() {
                        let r = format!("{v:.SVG_DECIMALS$}");
                        let r = r.trim_end_matches('0').trim_end_matches('.');
                        out.extend_from_slice(r.as_bytes());
                        continue;
                    }
                }
                out.extend_from_slice(text.as_bytes());
            } else {
                out.extend_from_slice(&b[start..i]);
            }
            continue;
        }
        out.push(c);
        i += 1;
    }
    // Only ASCII digit runs were replaced, so the bytes stay valid UTF-8.
    String::from_utf8(out).unwrap_or_else(|_| s.to_owned())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::font::FONT_FAMILY;
    use plotters::prelude::*;

    fn draw_text(area: &Area<'_>) -> Result<(), ReportError> {
        area.fill(&WHITE).map_err(present_err)?;
        area.draw(&Text::new(
            "λ₁ = 3/4",
            (10, 30),
            (FONT_FAMILY, 40).into_font(),
        ))
        .map_err(present_err)
    }

    #[test]
    fn png_has_size_and_rasterised_text() {
        let png_bytes = render_png((200, 100), &draw_text).unwrap();
        let mut reader = png::Decoder::new(&png_bytes[..]).read_info().unwrap();
        let mut buf = vec![0; reader.output_buffer_size()];
        let info = reader.next_frame(&mut buf).unwrap();
        assert_eq!((info.width, info.height), (200, 100));
        // The bundled font drew glyphs: dark pixels exist.
        let dark = buf[..info.buffer_size()]
            .chunks(3)
            .filter(|p| p[0] < 100)
            .count();
        assert!(dark > 50, "{dark}");
    }

    #[test]
    fn svg_has_size_and_text_element() {
        let svg = render_svg((200, 100), &draw_text).unwrap();
        assert!(svg.contains("width=\"200\"") && svg.contains("height=\"100\""));
        assert!(svg.contains("<text") && svg.contains("λ₁ = 3/4"));
    }
}

#[cfg(test)]
mod doc_examples {
    //! The examples of this private module's items (not doctests: the module is
    //! not public).
    use super::*;

    #[test]
    fn thin_svg_example() {
        let svg = "<svg>\n<rect x=\"0\" y=\"0\" width=\"2\" height=\"2\" opacity=\"1\" fill=\"#FF0000\" stroke=\"none\"/>\n<rect x=\"2\" y=\"0\" width=\"2\" height=\"2\" opacity=\"1\" fill=\"#FF0000\" stroke=\"none\"/>\n<text font-size=\"40.32258064516129\" opacity=\"1\">\n0.5\n</text>\n<line x1=\"0\" opacity=\"0\"/>\n</svg>\n";
        let thin = thin_svg(svg);
        assert!(thin.contains("<path fill=\"#FF0000\" d=\"M0 0h2v2h-2zM2 0h2v2h-2z\"/>"));
        assert!(thin.contains("font-size=\"40.32\"") && thin.contains("\n0.5\n"));
        assert!(!thin.contains("opacity") && !thin.contains("<line"));
    }
}
