//! The font of every figure: DejaVu Sans, embedded in the library (`assets/DejaVuSans.ttf`, license
//! in `assets/DejaVu-LICENSE.txt`) and registered with plotters' `ab_glyph` text renderer, so that
//! text is measured and rasterised the same way on every machine, with no system font installed.

use std::sync::OnceLock;

use plotters::style::{FontStyle, register_font};

/// The family name the figures' text uses. SVG files name it (`font-family="sans-serif"`), so an
/// SVG viewer draws the text with its own sans-serif font; PNG and GIF images are rasterised with
/// the embedded DejaVu Sans.
pub const FONT_FAMILY: &str = "sans-serif";

/// DejaVu Sans 2.37 (Bitstream Vera license with the DejaVu and Arev additions).
static DEJAVU_SANS: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");

/// Registers the embedded font with plotters (once per process; later calls do nothing).
pub(crate) fn ensure_registered() {
    static REGISTERED: OnceLock<()> = OnceLock::new();
    REGISTERED.get_or_init(|| {
        // The embedded file is a valid TrueType font: failing to parse it is a build defect.
        if register_font(FONT_FAMILY, FontStyle::Normal, DEJAVU_SANS).is_err() {
            panic!("the embedded DejaVu Sans font does not parse");
        }
    });
}
