//! PNG figures without fonts: a plotters bitmap backend whose text comes from a small 5 × 7 pixel
//! font of our own, and the PNG encoding of its buffer.
//!
//! plotters draws text into bitmaps through a font library (`ttf`: font-kit and fontconfig, or
//! `ab_glyph`: a font file we would have to ship). A fresh Debian machine with only cargo has
//! neither system fonts nor fontconfig, so [`PixelTextBackend`] wraps plotters'
//! [`BitMapBackend`] and draws every string itself, glyph by glyph, scaled to the requested size
//! in whole pixels. The SVG figures do not need this: SVG keeps text as text.

use std::path::Path;

use plotters::backend::{BitMapBackend, DrawingBackend};
use plotters_backend::text_anchor::{HPos, VPos};
use plotters_backend::{
    BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingErrorKind,
};

/// Glyph rows (5 columns each, `#` = ink), 7 per glyph, for printable ASCII and a few symbols
/// the figures use. Drawn for this project.
const GLYPHS: &[(char, &str)] = &[
    (' ', "..... ..... ..... ..... ..... ..... ....."),
    ('!', "..#.. ..#.. ..#.. ..#.. ..#.. ..... ..#.."),
    ('"', ".#.#. .#.#. ..... ..... ..... ..... ....."),
    ('#', ".#.#. .#.#. ##### .#.#. ##### .#.#. .#.#."),
    ('$', "..#.. .#### #.#.. .###. ..#.# ####. ..#.."),
    ('%', "##... ##..# ...#. ..#.. .#... #..## ...##"),
    ('&', ".##.. #..#. #.#.. .#... #.#.# #..#. .##.#"),
    ('\'', "..#.. ..#.. ..... ..... ..... ..... ....."),
    ('(', "...#. ..#.. .#... .#... .#... ..#.. ...#."),
    (')', ".#... ..#.. ...#. ...#. ...#. ..#.. .#..."),
    ('*', "..... ..#.. #.#.# .###. #.#.# ..#.. ....."),
    ('+', "..... ..#.. ..#.. ##### ..#.. ..#.. ....."),
    (',', "..... ..... ..... ..... .##.. ..#.. .#..."),
    ('-', "..... ..... ..... ##### ..... ..... ....."),
    ('.', "..... ..... ..... ..... ..... .##.. .##.."),
    ('/', "..... ....# ...#. ..#.. .#... #.... ....."),
    ('0', ".###. #...# #..## #.#.# ##..# #...# .###."),
    ('1', "..#.. .##.. ..#.. ..#.. ..#.. ..#.. .###."),
    ('2', ".###. #...# ....# ...#. ..#.. .#... #####"),
    ('3', "##### ...#. ..#.. ...#. ....# #...# .###."),
    ('4', "...#. ..##. .#.#. #..#. ##### ...#. ...#."),
    ('5', "##### #.... ####. ....# ....# #...# .###."),
    ('6', "..##. .#... #.... ####. #...# #...# .###."),
    ('7', "##### ....# ...#. ..#.. .#... .#... .#..."),
    ('8', ".###. #...# #...# .###. #...# #...# .###."),
    ('9', ".###. #...# #...# .#### ....# ...#. .##.."),
    (':', "..... .##.. .##.. ..... .##.. .##.. ....."),
    (';', "..... .##.. .##.. ..... .##.. ..#.. .#..."),
    ('<', "...#. ..#.. .#... #.... .#... ..#.. ...#."),
    ('=', "..... ..... ##### ..... ##### ..... ....."),
    ('>', ".#... ..#.. ...#. ....# ...#. ..#.. .#..."),
    ('?', ".###. #...# ....# ...#. ..#.. ..... ..#.."),
    ('@', ".###. #...# ....# .##.# #.#.# #.#.# .###."),
    ('A', ".###. #...# #...# ##### #...# #...# #...#"),
    ('B', "####. #...# #...# ####. #...# #...# ####."),
    ('C', ".###. #...# #.... #.... #.... #...# .###."),
    ('D', "###.. #..#. #...# #...# #...# #..#. ###.."),
    ('E', "##### #.... #.... ####. #.... #.... #####"),
    ('F', "##### #.... #.... ####. #.... #.... #...."),
    ('G', ".###. #...# #.... #.### #...# #...# .####"),
    ('H', "#...# #...# #...# ##### #...# #...# #...#"),
    ('I', ".###. ..#.. ..#.. ..#.. ..#.. ..#.. .###."),
    ('J', "..### ...#. ...#. ...#. ...#. #..#. .##.."),
    ('K', "#...# #..#. #.#.. ##... #.#.. #..#. #...#"),
    ('L', "#.... #.... #.... #.... #.... #.... #####"),
    ('M', "#...# ##.## #.#.# #.#.# #...# #...# #...#"),
    ('N', "#...# #...# ##..# #.#.# #..## #...# #...#"),
    ('O', ".###. #...# #...# #...# #...# #...# .###."),
    ('P', "####. #...# #...# ####. #.... #.... #...."),
    ('Q', ".###. #...# #...# #...# #.#.# #..#. .##.#"),
    ('R', "####. #...# #...# ####. #.#.. #..#. #...#"),
    ('S', ".#### #.... #.... .###. ....# ....# ####."),
    ('T', "##### ..#.. ..#.. ..#.. ..#.. ..#.. ..#.."),
    ('U', "#...# #...# #...# #...# #...# #...# .###."),
    ('V', "#...# #...# #...# #...# #...# .#.#. ..#.."),
    ('W', "#...# #...# #...# #.#.# #.#.# #.#.# .#.#."),
    ('X', "#...# #...# .#.#. ..#.. .#.#. #...# #...#"),
    ('Y', "#...# #...# .#.#. ..#.. ..#.. ..#.. ..#.."),
    ('Z', "##### ....# ...#. ..#.. .#... #.... #####"),
    ('[', ".###. .#... .#... .#... .#... .#... .###."),
    ('\\', "..... #.... .#... ..#.. ...#. ....# ....."),
    (']', ".###. ...#. ...#. ...#. ...#. ...#. .###."),
    ('^', "..#.. .#.#. #...# ..... ..... ..... ....."),
    ('_', "..... ..... ..... ..... ..... ..... #####"),
    ('`', ".#... ..#.. ..... ..... ..... ..... ....."),
    ('a', "..... ..... .###. ....# .#### #...# .####"),
    ('b', "#.... #.... #.##. ##..# #...# #...# ####."),
    ('c', "..... ..... .###. #.... #.... #...# .###."),
    ('d', "....# ....# .##.# #..## #...# #...# .####"),
    ('e', "..... ..... .###. #...# ##### #.... .###."),
    ('f', "..##. .#..# .#... ###.. .#... .#... .#..."),
    ('g', "..... .#### #...# #...# .#### ....# .###."),
    ('h', "#.... #.... #.##. ##..# #...# #...# #...#"),
    ('i', "..#.. ..... .##.. ..#.. ..#.. ..#.. .###."),
    ('j', "...#. ..... ..##. ...#. ...#. #..#. .##.."),
    ('k', "#.... #.... #..#. #.#.. ##... #.#.. #..#."),
    ('l', ".##.. ..#.. ..#.. ..#.. ..#.. ..#.. .###."),
    ('m', "..... ..... ##.#. #.#.# #.#.# #...# #...#"),
    ('n', "..... ..... #.##. ##..# #...# #...# #...#"),
    ('o', "..... ..... .###. #...# #...# #...# .###."),
    ('p', "..... ..... ####. #...# ####. #.... #...."),
    ('q', "..... ..... .##.# #..## .#### ....# ....#"),
    ('r', "..... ..... #.##. ##..# #.... #.... #...."),
    ('s', "..... ..... .###. #.... .###. ....# ####."),
    ('t', ".#... .#... ###.. .#... .#... .#..# ..##."),
    ('u', "..... ..... #...# #...# #...# #..## .##.#"),
    ('v', "..... ..... #...# #...# #...# .#.#. ..#.."),
    ('w', "..... ..... #...# #...# #.#.# #.#.# .#.#."),
    ('x', "..... ..... #...# .#.#. ..#.. .#.#. #...#"),
    ('y', "..... ..... #...# #...# .#### ....# .###."),
    ('z', "..... ..... ##### ...#. ..#.. .#... #####"),
    ('{', "...#. ..#.. ..#.. .#... ..#.. ..#.. ...#."),
    ('|', "..#.. ..#.. ..#.. ..#.. ..#.. ..#.. ..#.."),
    ('}', ".#... ..#.. ..#.. ...#. ..#.. ..#.. .#..."),
    ('~', "..... ..... .#... #.#.# ...#. ..... ....."),
    ('°', ".##.. #..#. #..#. .##.. ..... ..... ....."),
    ('θ', ".###. #...# #...# ##### #...# #...# .###."),
    ('σ', "..... ..... .#### #..#. #...# #...# .###."),
    ('–', "..... ..... ..... ##### ..... ..... ....."),
    ('−', "..... ..... ..... ##### ..... ..... ....."),
    ('×', "..... #...# .#.#. ..#.. .#.#. #...# ....."),
    ('√', "..### ..#.. ..#.. ..#.. #.#.. .#... ....."),
    ('≤', "...#. ..#.. .#... ..#.. ...#. ..... #####"),
    ('≥', ".#... ..#.. ...#. ..#.. .#... ..... #####"),
];

/// Glyph width and height in font pixels, and the advance from one glyph to the next.
const GLYPH_W: i32 = 5;
const GLYPH_H: i32 = 7;
const ADVANCE: i32 = 6;

/// The rows of `c`'s glyph as bit masks (bit 4 = leftmost column); unknown characters get a
/// hollow box.
pub fn glyph(c: char) -> [u8; 7] {
    const BOX: [u8; 7] = [0x1f, 0x11, 0x11, 0x11, 0x11, 0x11, 0x1f];
    let Some((_, rows)) = GLYPHS.iter().find(|(g, _)| *g == c) else {
        return BOX;
    };
    let mut out = [0u8; 7];
    for (i, row) in rows.split(' ').take(7).enumerate() {
        out[i] = row
            .bytes()
            .fold(0u8, |acc, b| (acc << 1) | u8::from(b == b'#'));
    }
    out
}

/// Screen pixels per font pixel for a font of `size` (plotters' size in pixels).
pub fn scale_for(size: f64) -> i32 {
    if size.is_finite() {
        ((size / 9.0).round() as i32).clamp(1, 8)
    } else {
        1
    }
}

/// Width and height in screen pixels of `text` at `size`.
pub fn text_size(text: &str, size: f64) -> (u32, u32) {
    let s = scale_for(size);
    let n = text.chars().count() as i32;
    let w = if n == 0 { 0 } else { (n * ADVANCE - 1) * s };
    (w.max(0) as u32, (GLYPH_H * s) as u32)
}

/// The screen pixels of `text` at `size`, relative to its top-left corner, unrotated.
pub fn text_pixels(text: &str, size: f64) -> Vec<(i32, i32)> {
    let s = scale_for(size);
    let mut px = Vec::new();
    for (i, c) in text.chars().enumerate() {
        let x0 = i as i32 * ADVANCE * s;
        for (row, bits) in glyph(c).iter().enumerate() {
            for col in 0..GLYPH_W {
                if bits & (1 << (GLYPH_W - 1 - col)) != 0 {
                    for dy in 0..s {
                        for dx in 0..s {
                            px.push((x0 + col * s + dx, row as i32 * s + dy));
                        }
                    }
                }
            }
        }
    }
    px
}

/// plotters' [`BitMapBackend`] with text drawn in our pixel font.
pub struct PixelTextBackend<'a> {
    inner: BitMapBackend<'a>,
}

impl<'a> PixelTextBackend<'a> {
    /// A backend drawing into `buf`, RGB, `w × h` pixels.
    pub fn with_buffer(buf: &'a mut [u8], (w, h): (u32, u32)) -> Self {
        PixelTextBackend {
            inner: BitMapBackend::with_buffer(buf, (w, h)),
        }
    }
}

type Res<E> = Result<(), DrawingErrorKind<E>>;

impl DrawingBackend for PixelTextBackend<'_> {
    type ErrorType = <BitMapBackend<'static> as DrawingBackend>::ErrorType;

    fn get_size(&self) -> (u32, u32) {
        self.inner.get_size()
    }

    fn ensure_prepared(&mut self) -> Res<Self::ErrorType> {
        self.inner.ensure_prepared()
    }

    fn present(&mut self) -> Res<Self::ErrorType> {
        self.inner.present()
    }

    fn draw_pixel(&mut self, point: BackendCoord, color: BackendColor) -> Res<Self::ErrorType> {
        self.inner.draw_pixel(point, color)
    }

    fn draw_line<S: BackendStyle>(
        &mut self,
        from: BackendCoord,
        to: BackendCoord,
        style: &S,
    ) -> Res<Self::ErrorType> {
        self.inner.draw_line(from, to, style)
    }

    fn draw_rect<S: BackendStyle>(
        &mut self,
        upper_left: BackendCoord,
        bottom_right: BackendCoord,
        style: &S,
        fill: bool,
    ) -> Res<Self::ErrorType> {
        self.inner.draw_rect(upper_left, bottom_right, style, fill)
    }

    fn draw_path<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        style: &S,
    ) -> Res<Self::ErrorType> {
        self.inner.draw_path(path, style)
    }

    fn draw_circle<S: BackendStyle>(
        &mut self,
        center: BackendCoord,
        radius: u32,
        style: &S,
        fill: bool,
    ) -> Res<Self::ErrorType> {
        self.inner.draw_circle(center, radius, style, fill)
    }

    fn fill_polygon<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        vert: I,
        style: &S,
    ) -> Res<Self::ErrorType> {
        self.inner.fill_polygon(vert, style)
    }

    fn blit_bitmap(
        &mut self,
        pos: BackendCoord,
        size: (u32, u32),
        src: &[u8],
    ) -> Res<Self::ErrorType> {
        self.inner.blit_bitmap(pos, size, src)
    }

    fn draw_text<TStyle: BackendTextStyle>(
        &mut self,
        text: &str,
        style: &TStyle,
        pos: BackendCoord,
    ) -> Res<Self::ErrorType> {
        let color = style.color();
        if color.alpha == 0.0 {
            return Ok(());
        }
        let (w, h) = text_size(text, style.size());
        let (w, h) = (w as i32, h as i32);
        let anchor = style.anchor();
        let dx = match anchor.h_pos {
            HPos::Left => 0,
            HPos::Right => -w,
            HPos::Center => -w / 2,
        };
        let dy = match anchor.v_pos {
            VPos::Top => 0,
            VPos::Center => -h / 2,
            VPos::Bottom => -h,
        };
        let trans = style.transform();
        let (sw, sh) = self.get_size();
        for (x, y) in text_pixels(text, style.size()) {
            let (x, y) = trans.transform(x + dx, y + dy);
            let (x, y) = (pos.0 + x, pos.1 + y);
            if x >= 0 && y >= 0 && x < sw as i32 && y < sh as i32 {
                self.inner.draw_pixel((x, y), color)?;
            }
        }
        Ok(())
    }

    fn estimate_text_size<TStyle: BackendTextStyle>(
        &self,
        text: &str,
        style: &TStyle,
    ) -> Result<(u32, u32), DrawingErrorKind<Self::ErrorType>> {
        Ok(text_size(text, style.size()))
    }
}

/// Writes an RGB buffer of `w × h` pixels as a PNG file.
pub fn write_png(path: &Path, rgb: &[u8], (w, h): (u32, u32)) -> Result<(), String> {
    let err = |e: &dyn std::fmt::Display| format!("cannot write {}: {e}", path.display());
    if rgb.len() != (w as usize) * (h as usize) * 3 {
        return Err(err(&"the pixel buffer does not match the image size"));
    }
    let mut bytes = Vec::new();
    let mut enc = png::Encoder::new(&mut bytes, w, h);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    // Flat-coloured plots compress well with the fast encoder; the default one took a fifth
    // of a short experiment's time.
    enc.set_compression(png::Compression::Fast);
    let mut writer = enc.write_header().map_err(|e| err(&e))?;
    writer.write_image_data(rgb).map_err(|e| err(&e))?;
    writer.finish().map_err(|e| err(&e))?;
    crate::output_file::write(path, bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_glyph_has_seven_rows_of_five() {
        for (c, rows) in GLYPHS {
            let rows: Vec<&str> = rows.split(' ').collect();
            assert_eq!(rows.len(), 7, "{c:?}");
            assert!(
                rows.iter()
                    .all(|r| r.len() == 5 && r.bytes().all(|b| b == b'#' || b == b'.')),
                "{c:?}"
            );
        }
        let mut chars: Vec<char> = GLYPHS.iter().map(|(c, _)| *c).collect();
        chars.sort();
        let n = chars.len();
        chars.dedup();
        assert_eq!(chars.len(), n, "a glyph is defined twice");
        for c in ' '..='~' {
            assert!(GLYPHS.iter().any(|(g, _)| *g == c), "{c:?} has no glyph");
        }
    }

    #[test]
    fn glyphs_decode_to_bits() {
        assert_eq!(glyph('T'), [0x1f, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04]);
        assert_eq!(glyph(' '), [0; 7]);
        // Unknown: a box.
        assert_eq!(glyph('\u{2603}')[0], 0x1f);
    }

    #[test]
    fn text_is_scaled_in_whole_pixels() {
        assert_eq!(scale_for(9.0), 1);
        assert_eq!(scale_for(18.0), 2);
        assert_eq!(scale_for(f64::NAN), 1);
        assert_eq!(text_size("ab", 18.0), (22, 14));
        assert_eq!(text_size("", 18.0), (0, 14));
        // "-" at scale 1: one row of five pixels, the fourth row.
        let px = text_pixels("-", 9.0);
        assert_eq!(px, (0..5).map(|x| (x, 3)).collect::<Vec<_>>());
        // At scale 2 each font pixel becomes four.
        assert_eq!(text_pixels("-", 18.0).len(), 20);
    }

    #[test]
    fn the_backend_draws_text_where_asked_and_encodes_a_png() {
        use plotters::prelude::*;
        let (w, h) = (60u32, 30u32);
        let mut buf = vec![0u8; (w * h * 3) as usize];
        {
            let root = PixelTextBackend::with_buffer(&mut buf, (w, h)).into_drawing_area();
            root.fill(&WHITE).unwrap();
            let style = ("sans-serif", 9.0).into_font().color(&BLACK);
            root.draw_text("I", &style, (10, 5)).unwrap();
            root.present().unwrap();
        }
        let dark = |x: u32, y: u32| buf[((y * w + x) * 3) as usize] < 128;
        // "I": top bar from x 11 to 13 at row 5, stem at x 12.
        assert!(dark(11, 5) && dark(12, 5) && dark(13, 5) && !dark(10, 5));
        assert!(dark(12, 8) && !dark(11, 8));
        let inked = (0..w * h).filter(|i| buf[(*i * 3) as usize] < 128).count();
        assert_eq!(inked, 3 + 5 + 3);
        let path = std::env::temp_dir().join(format!("rusoar-pixfont-{}.png", std::process::id()));
        write_png(&path, &buf, (w, h)).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
        let dec = png::Decoder::new(std::io::Cursor::new(bytes));
        let info = dec.read_info().unwrap().info().clone();
        assert_eq!((info.width, info.height), (w, h));
        let _ = std::fs::remove_file(&path);
        assert!(write_png(&path, &buf[1..], (w, h)).is_err());
    }
}
