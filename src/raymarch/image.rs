//! Images: linear RGB while rendering, 8-bit sRGB PNG on disk.

use std::io::BufWriter;
use std::path::Path;

use glam::DVec3;

use crate::error::{Error, Result};

/// A rendered image in linear RGB, rows from the top.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width × height` linear RGB values, row by row from the top.
    pub pixels: Vec<DVec3>,
}

/// An 8-bit sRGB image as read from or written to PNG.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Rgb8 {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `3 × width × height` bytes, R G B, rows from the top.
    pub data: Vec<u8>,
}

impl Image {
    /// A black image.
    #[must_use]
    pub fn new(width: u32, height: u32) -> Image {
        Image {
            width,
            height,
            pixels: vec![DVec3::ZERO; width as usize * height as usize],
        }
    }

    /// The pixel at `(x, y)` from the top left.
    #[must_use]
    pub fn get(&self, x: u32, y: u32) -> DVec3 {
        self.pixels[(y * self.width + x) as usize]
    }

    /// Encodes to 8-bit sRGB (values clamped to 0..=1).
    #[must_use]
    pub fn to_rgb8(&self) -> Rgb8 {
        let mut data = Vec::with_capacity(self.pixels.len() * 3);
        for p in &self.pixels {
            for c in p.to_array() {
                data.push(encode_srgb(c));
            }
        }
        Rgb8 {
            width: self.width,
            height: self.height,
            data,
        }
    }

    /// Writes an 8-bit sRGB PNG; see [`Rgb8::write_png`].
    ///
    /// # Errors
    ///
    /// As [`Rgb8::write_png`].
    pub fn write_png(&self, path: impl AsRef<Path>) -> Result<()> {
        self.to_rgb8().write_png(path)
    }
}

impl Rgb8 {
    /// The pixel at `(x, y)`.
    #[must_use]
    pub fn get(&self, x: u32, y: u32) -> [u8; 3] {
        let i = 3 * (y * self.width + x) as usize;
        [self.data[i], self.data[i + 1], self.data[i + 2]]
    }

    /// Writes a PNG (sRGB chunk set). The file appears whole or not at all: the data goes to a
    /// sibling temporary file that is renamed over the target when complete.
    ///
    /// # Errors
    ///
    /// [`Error::Io`](crate::Error::Io) naming the file when it cannot be written or encoded;
    /// the target is then left as it was.
    pub fn write_png(&self, path: impl AsRef<Path>) -> Result<()> {
        let path = path.as_ref();
        crate::io::write_file_with(path, |file| {
            let mut enc = png::Encoder::new(BufWriter::new(file), self.width, self.height);
            enc.set_color(png::ColorType::Rgb);
            enc.set_depth(png::BitDepth::Eight);
            enc.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
            let mut w = enc.write_header().map_err(png_error)?;
            w.write_image_data(&self.data).map_err(png_error)?;
            w.finish().map_err(png_error)
        })
    }

    /// Reads an 8-bit RGB or RGBA PNG (alpha dropped).
    ///
    /// # Errors
    ///
    /// [`Error::Io`](crate::Error::Io) when the file cannot be opened,
    /// [`Error::Parse`](crate::Error::Parse) when it is not an 8-bit RGB or RGBA PNG.
    pub fn read_png(path: impl AsRef<Path>) -> Result<Rgb8> {
        let path = path.as_ref();
        let parse = |message: String| Error::Parse {
            path: path.to_path_buf(),
            line: None,
            message,
        };
        let file = std::fs::File::open(path).map_err(|source| Error::Io {
            path: path.to_path_buf(),
            source,
        })?;
        let mut dec = png::Decoder::new(std::io::BufReader::new(file));
        dec.set_transformations(png::Transformations::EXPAND | png::Transformations::STRIP_16);
        let mut reader = dec.read_info().map_err(|e| parse(e.to_string()))?;
        let size = reader
            .output_buffer_size()
            .ok_or_else(|| parse("image too large".into()))?;
        let mut buf = vec![0; size];
        let info = reader
            .next_frame(&mut buf)
            .map_err(|e| parse(e.to_string()))?;
        let channels = match info.color_type {
            png::ColorType::Rgb => 3,
            png::ColorType::Rgba => 4,
            other => return Err(parse(format!("expected RGB or RGBA, found {other:?}"))),
        };
        let data = buf[..info.buffer_size()]
            .chunks(channels)
            .flat_map(|c| [c[0], c[1], c[2]])
            .collect();
        Ok(Rgb8 {
            width: info.width,
            height: info.height,
            data,
        })
    }

    /// Mean and largest absolute difference per channel, in 8-bit steps; `None` when the sizes
    /// differ.
    #[must_use]
    pub fn difference(&self, other: &Rgb8) -> Option<(f64, u8)> {
        if (self.width, self.height) != (other.width, other.height) {
            return None;
        }
        let mut sum = 0u64;
        let mut max = 0u8;
        for (a, b) in self.data.iter().zip(&other.data) {
            let d = a.abs_diff(*b);
            sum += d as u64;
            max = max.max(d);
        }
        Some((sum as f64 / self.data.len().max(1) as f64, max))
    }
}

/// Linear → sRGB transfer, rounded to 8 bits.
pub(crate) fn encode_srgb(c: f64) -> u8 {
    let c = if c.is_nan() { 0.0 } else { c.clamp(0.0, 1.0) };
    let s = if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    };
    (s * 255.0).round() as u8
}

/// A PNG encoding fault as the I/O error the writer reports.
fn png_error(e: png::EncodingError) -> std::io::Error {
    std::io::Error::other(format!("PNG encoding failed: {e}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn png_round_trip_and_difference() {
        let mut img = Image::new(3, 2);
        img.pixels[1] = DVec3::new(1.0, 0.5, 0.0);
        img.pixels[5] = DVec3::splat(0.2);
        let dir = std::env::temp_dir().join(format!("bspcsg-png-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("t.png");
        img.write_png(&path).unwrap();
        let back = Rgb8::read_png(&path).unwrap();
        assert_eq!(back, img.to_rgb8());
        assert_eq!(back.get(1, 0), [255, 188, 0]);
        assert_eq!(back.difference(&back), Some((0.0, 0)));
        // No temporary file is left behind.
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
