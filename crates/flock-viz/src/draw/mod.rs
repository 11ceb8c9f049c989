//! What every figure is drawn with: colours and sizes ([`style`]), the embedded font, number
//! formats, plane geometry and the SVG/PNG backends.

pub mod font;
pub(crate) mod format;
pub(crate) mod geometry;
pub(crate) mod marks;
pub(crate) mod palette;
pub(crate) mod render;
pub mod style;
