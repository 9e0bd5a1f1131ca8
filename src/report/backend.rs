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
    Ok(out)
}

/// Renders a drawing routine into an RGB bitmap of `size` and encodes it as PNG.
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
        enc.set_compression(png::Compression::Fast);
        let mut writer = enc.write_header().map_err(present_err)?;
        writer.write_image_data(rgb).map_err(present_err)?;
        writer.finish().map_err(present_err)?;
    }
    Ok(out)
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
