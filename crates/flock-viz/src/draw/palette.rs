//! [`Palette`]: the 256 colours of an animated GIF, chosen once for the whole animation.
//!
//! A figure drawn by plotters has more than 256 colours (the font's and the markers' edges are
//! blended with the background), so a GIF frame needs a palette. Choosing one per frame (the
//! `gif` crate's `Frame::from_rgb_speed`, a NeuQuant network trained on every frame) was 85 % of
//! the time of `flocking plot`, and let a colour shift from frame to frame. The palette here is
//! learned once, by the same NeuQuant network (`color_quant`, already the `gif` crate's), from the
//! pixels of a few frames spread over the animation that are not the background (which is a
//! colour of its own), or is the frames' exact colours when they have at most 256; each pixel is
//! then given its nearest palette colour.

use std::collections::BTreeSet;

use color_quant::NeuQuant;

/// NeuQuant's sampling factor: 1 trains on every pixel, 30 (fastest) on one in 30; 10 is the
/// `gif` crate's default speed.
const SAMPLE_FACTOR: i32 = 10;

/// The slots of the cache of [`Palette::indices`]: 2^CACHE_BITS.
const CACHE_BITS: u32 = 12;
const CACHE_SLOTS: usize = 1 << CACHE_BITS;

/// At most 256 colours, and which of them each pixel of a frame is drawn with.
#[derive(Clone, Debug)]
pub(crate) struct Palette {
    colours: Vec<[u8; 3]>,
}

impl Palette {
    /// The palette of `samples`, RGB buffers (3 bytes a pixel) drawn on `background`: their
    /// colours when there are at most 256, else `background` and the 255 colours a NeuQuant
    /// network learns from the samples' other pixels (most of a figure is background: learning
    /// from the rest is quicker and spends every colour on the drawing).
    pub(crate) fn learn(samples: &[Vec<u8>], background: [u8; 3]) -> Self {
        let drawn: Vec<[u8; 3]> = samples
            .iter()
            .flat_map(|rgb| rgb.chunks_exact(3))
            .map(|p| [p[0], p[1], p[2]])
            .filter(|&p| p != background)
            .collect();
        let mut exact = BTreeSet::from([background]);
        if drawn.iter().all(|&p| {
            exact.insert(p);
            exact.len() <= 256
        }) {
            return Self {
                colours: exact.into_iter().collect(),
            };
        }
        let rgba: Vec<u8> = drawn
            .iter()
            .flat_map(|p| [p[0], p[1], p[2], u8::MAX])
            .collect();
        let network = NeuQuant::new(SAMPLE_FACTOR, 255, &rgba);
        let learned = network.color_map_rgb();
        Self {
            colours: std::iter::once(background)
                .chain(learned.chunks_exact(3).map(|c| [c[0], c[1], c[2]]))
                .collect(),
        }
    }

    /// The palette as the GIF's colour table: red, green, blue of each colour.
    pub(crate) fn table(&self) -> Vec<u8> {
        self.colours.concat()
    }

    /// Each pixel of `rgb` as the index of its nearest colour (squared RGB distance, the first
    /// of equals).
    pub(crate) fn indices(&self, rgb: &[u8]) -> Vec<u8> {
        // the colours met and their indices, each in the slot its hash gives (a later colour of
        // the same slot takes it): a frame has a few hundred colours
        let mut known = vec![None; CACHE_SLOTS];
        let mut last: Option<([u8; 3], u8)> = None;
        rgb.chunks_exact(3)
            .map(|p| {
                let colour = [p[0], p[1], p[2]];
                match last {
                    // most pixels repeat their left neighbour (the background)
                    Some((c, index)) if c == colour => index,
                    _ => {
                        let key = u32::from_be_bytes([0, p[0], p[1], p[2]]);
                        // Fibonacci hashing: the top bits of the key times 2³² / φ
                        let slot = (key.wrapping_mul(0x9E37_79B9) >> (32 - CACHE_BITS)) as usize;
                        let index = match known[slot] {
                            Some((c, index)) if c == colour => index,
                            _ => {
                                let index = self.nearest(colour);
                                known[slot] = Some((colour, index));
                                index
                            }
                        };
                        last = Some((colour, index));
                        index
                    }
                }
            })
            .collect()
    }

    /// The index of the palette colour nearest `colour`.
    fn nearest(&self, colour: [u8; 3]) -> u8 {
        let distance = |c: &[u8; 3]| -> u32 {
            c.iter()
                .zip(colour)
                .map(|(&a, b)| (i32::from(a) - i32::from(b)).unsigned_abs().pow(2))
                .sum()
        };
        let (index, _) = self
            .colours
            .iter()
            .enumerate()
            .min_by_key(|&(k, c)| (distance(c), k))
            .unwrap_or((0, &[0; 3]));
        // at most 256 colours
        index as u8
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn few_colours_are_kept_exactly() {
        let rgb = [255, 255, 255, 0, 0, 0, 255, 255, 255, 10, 20, 30];
        let palette = Palette::learn(&[rgb.to_vec()], [255; 3]);
        assert_eq!(palette.table(), [0, 0, 0, 10, 20, 30, 255, 255, 255]);
        assert_eq!(palette.indices(&rgb), [2, 0, 2, 1]);
        // a colour not in the samples: its nearest
        assert_eq!(palette.indices(&[9, 21, 33, 250, 250, 250]), [1, 2]);
    }

    #[test]
    fn many_colours_are_learned_and_the_dominant_ones_kept() {
        // half the image white, half 1,000 shades (4 blues × 250 greys) of 100 pixels each
        let mut rgb = vec![255u8; 3 * 200_000];
        for k in 0..100_000usize {
            let shade = k / 100;
            let grey = (shade % 250) as u8;
            rgb[3 * k..3 * k + 3].copy_from_slice(&[grey, grey, (shade / 250) as u8 * 60]);
        }
        let palette = Palette::learn(&[rgb.clone()], [255; 3]);
        assert_eq!(palette.table().len(), 256 * 3);
        let indices = palette.indices(&rgb);
        let table = palette.table();
        let colour =
            |k: usize| &table[3 * usize::from(indices[k])..3 * usize::from(indices[k]) + 3];
        assert_eq!(colour(150_000), [255, 255, 255], "the background is exact");
        // every shade within a few levels of its own
        for k in (0..100_000).step_by(100) {
            let error: u32 = colour(k)
                .iter()
                .zip(&rgb[3 * k..3 * k + 3])
                .map(|(&a, &b)| u32::from(a.abs_diff(b)))
                .max()
                .unwrap();
            assert!(
                error <= 16,
                "pixel {k}: {:?} drawn as {:?}",
                &rgb[3 * k..3 * k + 3],
                colour(k)
            );
        }
    }
}
