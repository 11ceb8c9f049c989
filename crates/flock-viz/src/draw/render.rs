//! Backends: a figure drawn once with generic plotters code, written as SVG text, an RGB buffer
//! (plotters' `BitMapBackend::with_buffer`, its combining marks centred by [`CentredMarks`]) or a
//! PNG (encoded with the `png` crate).

use plotters::coord::Shift;
use plotters::prelude::{BitMapBackend, DrawingArea, DrawingBackend, IntoDrawingArea, SVGBackend};

use crate::draw::font;
use crate::draw::marks::CentredMarks;
use crate::draw::style::{self, BACKGROUND};
use crate::error::VizError;

/// Something drawn on a plotters drawing area of any backend.
pub(crate) trait Figure {
    /// The image size in pixels (width, height).
    fn size(&self) -> (u32, u32);

    /// Draws the figure on `root` (already filled with the background).
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), VizError>;
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
        figure.draw(&root)?;
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
        let root =
            CentredMarks(BitMapBackend::with_buffer(&mut buffer, (w, h))).into_drawing_area();
        root.fill(&style::rgb(BACKGROUND)).map_err(VizError::draw)?;
        figure.draw(&root)?;
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
