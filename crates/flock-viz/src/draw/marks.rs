//! [`CentredMarks`]: a raster backend that draws a combining mark (U+0300–U+036F, the tilde of K̃)
//! centred over its base letter.
//!
//! plotters' `ab_glyph` renderer puts each glyph's ink at the pen and ignores its side bearing,
//! so a combining mark (no advance, its ink left of the pen in the font) lands after its base
//! letter. This backend draws such a text as the text without its marks, then each mark with
//! the centre of its ink on the centre of its base letter's ink, at the height the font gives
//! it. Every other call goes to the wrapped backend unchanged. SVG needs none of this: the
//! viewer lays the text out.

use plotters_backend::text_anchor::{HPos, VPos};
use plotters_backend::{
    BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingBackend, DrawingErrorKind,
};

/// A raster backend whose texts have their combining marks centred over their base letters.
pub(crate) struct CentredMarks<B>(pub(crate) B);

/// Whether `c` is a combining diacritical mark (U+0300–U+036F).
fn is_mark(c: char) -> bool {
    ('\u{300}'..='\u{36F}').contains(&c)
}

/// The pieces `text` is drawn as, each with its x offset in the text's own frame: the text
/// without its marks at 0, then each mark centred on the ink of the letter before it.
fn pieces<S: BackendTextStyle>(text: &str, style: &S) -> Result<Vec<(String, i32)>, S::FontError> {
    let mut bare = String::with_capacity(text.len());
    let mut marks = Vec::new();
    // the base letter of the marks that follow, and where its pen starts
    let mut base: Option<(char, i32)> = None;
    for c in text.chars() {
        match base {
            Some((letter, pen)) if is_mark(c) => {
                let letter = ink_centre_twice(style, letter)?;
                let mark = ink_centre_twice(style, c)?;
                if let (Some(letter), Some(mark)) = (letter, mark) {
                    marks.push((c.to_string(), pen + (letter - mark) / 2));
                }
            }
            _ => {
                let ((x0, _), (x1, _)) = style.layout_box(&bare)?;
                base = Some((c, x1 - x0));
                bare.push(c);
            }
        }
    }
    let mut out = vec![(bare, 0)];
    out.extend(marks);
    Ok(out)
}

/// Twice the x centre of the ink of `c` drawn alone at the pen (the left plus the right edge of
/// its pixels), or `None` for a glyph with no ink.
fn ink_centre_twice<S: BackendTextStyle>(style: &S, c: char) -> Result<Option<i32>, S::FontError> {
    let mut span: Option<(i32, i32)> = None;
    style
        .draw(&c.to_string(), (0, 0), |x, _, colour| {
            if colour.alpha > 0.0 {
                span = Some(span.map_or((x, x), |(a, b)| (a.min(x), b.max(x))));
            }
            Ok::<(), ()>(())
        })?
        .ok();
    Ok(span.map(|(left, right)| left + right))
}

impl<B: DrawingBackend> DrawingBackend for CentredMarks<B> {
    type ErrorType = B::ErrorType;

    fn get_size(&self) -> (u32, u32) {
        self.0.get_size()
    }

    fn ensure_prepared(&mut self) -> Result<(), DrawingErrorKind<B::ErrorType>> {
        self.0.ensure_prepared()
    }

    fn present(&mut self) -> Result<(), DrawingErrorKind<B::ErrorType>> {
        self.0.present()
    }

    fn draw_pixel(
        &mut self,
        point: BackendCoord,
        color: BackendColor,
    ) -> Result<(), DrawingErrorKind<B::ErrorType>> {
        self.0.draw_pixel(point, color)
    }

    fn draw_line<S: BackendStyle>(
        &mut self,
        from: BackendCoord,
        to: BackendCoord,
        style: &S,
    ) -> Result<(), DrawingErrorKind<B::ErrorType>> {
        self.0.draw_line(from, to, style)
    }

    fn draw_rect<S: BackendStyle>(
        &mut self,
        upper_left: BackendCoord,
        bottom_right: BackendCoord,
        style: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<B::ErrorType>> {
        self.0.draw_rect(upper_left, bottom_right, style, fill)
    }

    fn draw_path<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        style: &S,
    ) -> Result<(), DrawingErrorKind<B::ErrorType>> {
        self.0.draw_path(path, style)
    }

    fn draw_circle<S: BackendStyle>(
        &mut self,
        center: BackendCoord,
        radius: u32,
        style: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<B::ErrorType>> {
        self.0.draw_circle(center, radius, style, fill)
    }

    fn fill_polygon<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        vert: I,
        style: &S,
    ) -> Result<(), DrawingErrorKind<B::ErrorType>> {
        self.0.fill_polygon(vert, style)
    }

    fn blit_bitmap(
        &mut self,
        pos: BackendCoord,
        size: (u32, u32),
        src: &[u8],
    ) -> Result<(), DrawingErrorKind<B::ErrorType>> {
        self.0.blit_bitmap(pos, size, src)
    }

    /// As plotters' default `draw_text` (the anchor and the rotation applied to every pixel),
    /// each piece of [`pieces`] at its offset.
    fn draw_text<S: BackendTextStyle>(
        &mut self,
        text: &str,
        style: &S,
        pos: BackendCoord,
    ) -> Result<(), DrawingErrorKind<B::ErrorType>> {
        if !text.chars().any(is_mark) {
            return self.0.draw_text(text, style, pos);
        }
        if style.color().alpha == 0.0 {
            return Ok(());
        }
        let font_error = |e: S::FontError| DrawingErrorKind::FontError(Box::new(e));
        let ((min_x, min_y), (max_x, max_y)) = style.layout_box(text).map_err(font_error)?;
        let (width, height) = (max_x - min_x, max_y - min_y);
        let dx = match style.anchor().h_pos {
            HPos::Left => 0,
            HPos::Right => -width,
            HPos::Center => -width / 2,
        };
        let dy = match style.anchor().v_pos {
            VPos::Top => 0,
            VPos::Center => -height / 2,
            VPos::Bottom => -height,
        };
        let transform = style.transform();
        let (w, h) = self.get_size();
        for (piece, offset) in pieces(text, style).map_err(font_error)? {
            style
                .draw(&piece, (offset, 0), |x, y, colour| {
                    let (x, y) = transform.transform(x + dx - min_x, y + dy - min_y);
                    let (x, y) = (pos.0 + x, pos.1 + y);
                    if (0..w as i32).contains(&x) && (0..h as i32).contains(&y) {
                        self.0.draw_pixel((x, y), colour)
                    } else {
                        Ok(())
                    }
                })
                .map_err(font_error)??;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use plotters::prelude::{BitMapBackend, IntoDrawingArea, IntoFont, WHITE};
    use plotters::style::{BLACK, TextStyle};

    use super::*;
    use crate::draw::font::{self, FONT_FAMILY};

    const W: usize = 200;
    const H: usize = 80;

    /// Whether each pixel of a W × H white image is inked once `text` (48 px, at (40, 10)) is
    /// drawn on it through [`CentredMarks`].
    fn inked(text: &str) -> Vec<bool> {
        font::ensure_registered();
        let mut buffer = vec![255u8; W * H * 3];
        {
            let root = CentredMarks(BitMapBackend::with_buffer(
                &mut buffer,
                (W as u32, H as u32),
            ))
            .into_drawing_area();
            root.fill(&WHITE).unwrap();
            let style = TextStyle::from((FONT_FAMILY, 48).into_font()).color(&BLACK);
            root.draw_text(text, &style, (40, 10)).unwrap();
            root.present().unwrap();
        }
        buffer.chunks_exact(3).map(|p| p != [255; 3]).collect()
    }

    /// The first and last columns inked in `rows`.
    fn extent(ink: &[bool], rows: std::ops::Range<usize>) -> Option<(usize, usize)> {
        let columns: Vec<usize> = (0..W)
            .filter(|&x| rows.clone().any(|y| ink[y * W + x]))
            .collect();
        Some((*columns.first()?, *columns.last()?))
    }

    #[test]
    fn the_tilde_of_k_is_centred_over_the_k() {
        let k = inked("K");
        let top = (0..H).find(|&y| (0..W).any(|x| k[y * W + x])).unwrap();
        let k_extent = extent(&k, 0..H).unwrap();
        let k_tilde = inked("K\u{303}");
        assert_eq!(
            extent(&k_tilde, top..H),
            Some(k_extent),
            "the K is drawn where it is without its tilde"
        );
        let (left, right) = extent(&k_tilde, 0..top).expect("a tilde above the K");
        let centre = |(a, b): (usize, usize)| (a + b) as f64 / 2.0;
        let (mark, letter) = (centre((left, right)), centre(k_extent));
        assert!(
            (mark - letter).abs() <= 1.5,
            "the tilde centred at x = {mark}, the K at x = {letter}"
        );
        assert!(
            left > k_extent.0 && right < k_extent.1,
            "the tilde within the K"
        );
    }
}
