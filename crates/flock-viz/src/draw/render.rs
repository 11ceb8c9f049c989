//! Backends: a figure drawn once with generic plotters code, written as SVG text, an RGB buffer
//! (plotters' `BitMapBackend::with_buffer`) or a PNG (encoded with the `png` crate).

use plotters::coord::Shift;
use plotters::prelude::{BitMapBackend, DrawingArea, DrawingBackend, IntoDrawingArea, SVGBackend};

use crate::draw::font;
use crate::draw::style::{self, BACKGROUND};
use crate::error::VizError;

/// Something drawn on a plotters drawing area of any backend.
pub(crate) trait Figure {
    /// The image size in pixels (width, height).
    fn size(&self) -> (u32, u32);

    /// Draws the figure on `root` (already filled with the background), its text passed through
    /// `text`.
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        text: TextMode,
    ) -> Result<(), VizError>;
}

/// How text reaches the backend.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum TextMode {
    /// As written: an SVG viewer lays it out.
    Svg,
    /// Rasterised by plotters' `ab_glyph` renderer, which places every glyph at the pen position
    /// and ignores its side bearing: a combining mark (U+0300–U+036F, the tilde of K̃) would land
    /// after its base letter. Each mark is moved before its base, where it is drawn over the
    /// letter's left part.
    Bitmap,
}

impl TextMode {
    /// `text` as this backend should receive it.
    pub(crate) fn text(self, text: &str) -> String {
        if self == Self::Svg {
            return text.to_owned();
        }
        let mut out: Vec<char> = Vec::with_capacity(text.len());
        for c in text.chars() {
            if ('\u{300}'..='\u{36F}').contains(&c) && !out.is_empty() {
                let base = out.len() - 1;
                out.insert(base, c);
            } else {
                out.push(c);
            }
        }
        out.into_iter().collect()
    }
}

/// Checks an image size: both sides at least 16 pixels, at most 16384.
fn check_size((w, h): (u32, u32)) -> Result<(), VizError> {
    if !(16..=16384).contains(&w) || !(16..=16384).contains(&h) {
        return Err(VizError::invalid(format!(
            "an image of {w} × {h} pixels: each side must be between 16 and 16384"
        )));
    }
    Ok(())
}

/// The figure as an SVG document.
pub(crate) fn svg(figure: &impl Figure) -> Result<String, VizError> {
    check_size(figure.size())?;
    font::ensure_registered();
    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, figure.size()).into_drawing_area();
        root.fill(&style::rgb(BACKGROUND)).map_err(VizError::draw)?;
        figure.draw(&root, TextMode::Svg)?;
        root.present().map_err(VizError::draw)?;
    }
    Ok(out)
}

/// The figure as an RGB buffer, 3 bytes per pixel, rows top to bottom.
pub(crate) fn rgb(figure: &impl Figure) -> Result<Vec<u8>, VizError> {
    check_size(figure.size())?;
    font::ensure_registered();
    let (w, h) = figure.size();
    let mut buffer = vec![0u8; w as usize * h as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut buffer, (w, h)).into_drawing_area();
        root.fill(&style::rgb(BACKGROUND)).map_err(VizError::draw)?;
        figure.draw(&root, TextMode::Bitmap)?;
        root.present().map_err(VizError::draw)?;
    }
    Ok(buffer)
}

/// The figure as a PNG file's bytes.
pub(crate) fn png(figure: &impl Figure) -> Result<Vec<u8>, VizError> {
    let (w, h) = figure.size();
    let buffer = rgb(figure)?;
    encode_png(&buffer, w, h)
}

/// An RGB buffer as PNG bytes.
pub(crate) fn encode_png(rgb: &[u8], w: u32, h: u32) -> Result<Vec<u8>, VizError> {
    let mut out = Vec::new();
    let mut encoder = png::Encoder::new(&mut out, w, h);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header().map_err(VizError::encode)?;
    writer.write_image_data(rgb).map_err(VizError::encode)?;
    writer.finish().map_err(VizError::encode)?;
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bitmap_text_moves_combining_marks_before_their_base() {
        assert_eq!(TextMode::Bitmap.text("K\u{303} (m)"), "\u{303}K (m)");
        assert_eq!(TextMode::Svg.text("K\u{303}"), "K\u{303}");
        assert_eq!(TextMode::Bitmap.text("\u{303}"), "\u{303}");
    }
}
