//! The bundled font of the figures (DejaVu Sans, compiled into the binary
//! from `fonts/DejaVuSans.ttf`) and its one-time registration with plotters;
//! see [`super::plot`] for how text is laid out. A leaf of the report module,
//! used by the drawing backend and by the plotting helpers alike.

use super::error::ReportError;
use plotters::style::FontStyle;
use std::sync::OnceLock;

/// The bundled font (DejaVu Sans, Bitstream Vera licence).
pub static FONT_DATA: &[u8] = include_bytes!("fonts/DejaVuSans.ttf");
/// The family name the bundled font is registered under.
pub const FONT_FAMILY: &str = "sans-serif";

/// Registers the bundled font with plotters (once per process).
pub fn ensure_font() -> Result<(), ReportError> {
    static DONE: OnceLock<bool> = OnceLock::new();
    let ok = *DONE.get_or_init(|| {
        [
            FontStyle::Normal,
            FontStyle::Bold,
            FontStyle::Italic,
            FontStyle::Oblique,
        ]
        .into_iter()
        .all(|s| plotters::style::register_font(FONT_FAMILY, s, FONT_DATA).is_ok())
    });
    if ok {
        Ok(())
    } else {
        Err(ReportError::Font)
    }
}
