//! An 8-bit RGB picture ([`RgbImage`]) and its PNG encoding: what a render becomes before it is
//! shown, and what every PNG figure is drawn into.
//!
//! The crate needs a pixel buffer, a PNG encoder and (for its tests and examples) a PNG decoder,
//! and nothing else of an image library: the `png` crate does the format, this file the buffer.
//! (The `image` crate would do both, but compiles a colour-management library, moxcms, that
//! nothing here uses.) The encoder settings are `image` 0.25's defaults (fast deflate, adaptive
//! filtering), so the PNG figures are the bytes that crate would write.

use std::io::Cursor;

/// One pixel: red, green, blue in display levels 0 … 255.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Rgb(pub [u8; 3]);

/// A `width` × `height` picture of [`Rgb`] pixels, stored row by row from the top left, three
/// bytes a pixel.
///
/// # Examples
/// ```
/// use hw3_core::plot::{Rgb, RgbImage};
/// let mut image = RgbImage::from_pixel(3, 2, Rgb([10, 20, 30]));
/// image.put_pixel(2, 1, Rgb([255, 0, 0]));
/// assert_eq!(image.dimensions(), (3, 2));
/// assert_eq!(image.get_pixel(2, 1), Rgb([255, 0, 0]));
/// assert_eq!(&image.as_raw()[..3], &[10, 20, 30]);
/// ```
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct RgbImage {
    width: u32,
    height: u32,
    bytes: Vec<u8>,
}

/// Bytes of a `width` × `height` RGB picture, or `None` past `usize`.
fn checked_byte_count(width: u32, height: u32) -> Option<usize> {
    (width as usize).checked_mul(height as usize)?.checked_mul(3)
}

/// [`checked_byte_count`] of a picture this crate makes.
///
/// # Panics
/// If the count overflows `usize` (2⁶⁴ bytes: never a picture this crate makes).
fn byte_count(width: u32, height: u32) -> usize {
    checked_byte_count(width, height).expect("picture size fits in memory")
}

impl RgbImage {
    /// A black picture.
    ///
    /// # Examples
    /// ```
    /// assert_eq!(hw3_core::plot::RgbImage::new(2, 2).get_pixel(1, 1), hw3_core::plot::Rgb([0, 0, 0]));
    /// ```
    #[must_use]
    pub fn new(width: u32, height: u32) -> Self {
        Self { width, height, bytes: vec![0; byte_count(width, height)] }
    }

    /// A picture of one colour.
    ///
    /// # Examples
    /// ```
    /// use hw3_core::plot::{Rgb, RgbImage};
    /// assert!(RgbImage::from_pixel(4, 1, Rgb([7; 3])).pixels().all(|p| p == Rgb([7; 3])));
    /// ```
    #[must_use]
    pub fn from_pixel(width: u32, height: u32, pixel: Rgb) -> Self {
        Self { width, height, bytes: pixel.0.repeat(byte_count(width, height) / 3) }
    }

    /// The picture whose rows are `bytes` (three a pixel, from the top left), or `None` when
    /// `bytes` is not exactly `3 × width × height` long.
    ///
    /// # Examples
    /// ```
    /// use hw3_core::plot::RgbImage;
    /// assert!(RgbImage::from_raw(2, 1, vec![0; 6]).is_some());
    /// assert!(RgbImage::from_raw(2, 1, vec![0; 5]).is_none());
    /// ```
    #[must_use]
    pub fn from_raw(width: u32, height: u32, bytes: Vec<u8>) -> Option<Self> {
        (Some(bytes.len()) == checked_byte_count(width, height)).then_some(Self { width, height, bytes })
    }

    /// Width in pixels.
    ///
    /// # Examples
    /// ```
    /// assert_eq!(hw3_core::plot::RgbImage::new(5, 2).width(), 5);
    /// ```
    #[must_use]
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    ///
    /// # Examples
    /// ```
    /// assert_eq!(hw3_core::plot::RgbImage::new(5, 2).height(), 2);
    /// ```
    #[must_use]
    pub fn height(&self) -> u32 {
        self.height
    }

    /// `(width, height)` in pixels.
    ///
    /// # Examples
    /// ```
    /// assert_eq!(hw3_core::plot::RgbImage::new(5, 2).dimensions(), (5, 2));
    /// ```
    #[must_use]
    pub fn dimensions(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    fn offset(&self, x: u32, y: u32) -> usize {
        assert!(x < self.width && y < self.height, "pixel ({x}, {y}) outside a {}×{} picture", self.width, self.height);
        (y as usize * self.width as usize + x as usize) * 3
    }

    /// The pixel in column `x`, row `y` (from the top).
    ///
    /// # Panics
    /// If `(x, y)` is outside the picture.
    ///
    /// # Examples
    /// ```
    /// use hw3_core::plot::{Rgb, RgbImage};
    /// let image = RgbImage::from_raw(2, 1, vec![1, 2, 3, 4, 5, 6]).unwrap();
    /// assert_eq!(image.get_pixel(1, 0), Rgb([4, 5, 6]));
    /// ```
    #[must_use]
    pub fn get_pixel(&self, x: u32, y: u32) -> Rgb {
        let i = self.offset(x, y);
        Rgb([self.bytes[i], self.bytes[i + 1], self.bytes[i + 2]])
    }

    /// Sets the pixel in column `x`, row `y`.
    ///
    /// # Panics
    /// If `(x, y)` is outside the picture.
    ///
    /// # Examples
    /// ```
    /// use hw3_core::plot::{Rgb, RgbImage};
    /// let mut image = RgbImage::new(2, 2);
    /// image.put_pixel(0, 1, Rgb([9, 9, 9]));
    /// assert_eq!(image.as_raw()[6..9], [9, 9, 9]);
    /// ```
    pub fn put_pixel(&mut self, x: u32, y: u32, pixel: Rgb) {
        let i = self.offset(x, y);
        self.bytes[i..i + 3].copy_from_slice(&pixel.0);
    }

    /// Every pixel, row by row from the top left.
    ///
    /// # Examples
    /// ```
    /// assert_eq!(hw3_core::plot::RgbImage::new(3, 2).pixels().count(), 6);
    /// ```
    pub fn pixels(&self) -> impl Iterator<Item = Rgb> + '_ {
        self.bytes.chunks_exact(3).map(|p| Rgb([p[0], p[1], p[2]]))
    }

    /// The bytes, three a pixel, row by row from the top left.
    ///
    /// # Examples
    /// ```
    /// assert_eq!(hw3_core::plot::RgbImage::new(3, 2).as_raw().len(), 18);
    /// ```
    #[must_use]
    pub fn as_raw(&self) -> &[u8] {
        &self.bytes
    }

    /// The bytes, three a pixel, row by row from the top left.
    ///
    /// # Examples
    /// ```
    /// assert_eq!(hw3_core::plot::RgbImage::new(1, 1).into_raw(), vec![0, 0, 0]);
    /// ```
    #[must_use]
    pub fn into_raw(self) -> Vec<u8> {
        self.bytes
    }

    /// Copies `other` onto this picture with its top-left corner at `(x, y)`; what falls outside
    /// is cut off.
    ///
    /// # Examples
    /// ```
    /// use hw3_core::plot::{Rgb, RgbImage};
    /// let mut canvas = RgbImage::new(4, 2);
    /// canvas.paste(&RgbImage::from_pixel(2, 2, Rgb([5; 3])), 3, 1);
    /// assert_eq!(canvas.get_pixel(3, 1), Rgb([5; 3]));
    /// assert_eq!(canvas.get_pixel(2, 1), Rgb([0; 3]));
    /// ```
    pub fn paste(&mut self, other: &Self, x: u32, y: u32) {
        let columns = other.width.min(self.width.saturating_sub(x)) as usize;
        if columns == 0 {
            return;
        }
        for row in 0..other.height.min(self.height.saturating_sub(y)) {
            let from = row as usize * other.width as usize * 3;
            let to = self.offset(x, y + row);
            self.bytes[to..to + 3 * columns].copy_from_slice(&other.bytes[from..from + 3 * columns]);
        }
    }
}

/// Why a PNG could not be written or read.
#[derive(Debug, thiserror::Error)]
pub enum PngError {
    /// The encoder failed (the `png` crate's message).
    #[error("PNG encoding failed: {0}")]
    Encode(#[from] png::EncodingError),
    /// The bytes are not a PNG this crate reads (the `png` crate's message, or the colour type).
    #[error("PNG decoding failed: {0}")]
    Decode(String),
}

/// Encodes `image` as a PNG: 8-bit RGB, no metadata, the same bytes for the same pixels.
///
/// # Errors
/// [`PngError::Encode`] if the encoder fails (it does not on an in-memory buffer).
///
/// # Examples
/// ```
/// use hw3_core::plot::{Rgb, RgbImage, decode_png, encode_png};
/// let image = RgbImage::from_pixel(3, 2, Rgb([200, 100, 0]));
/// let bytes = encode_png(&image).unwrap();
/// assert!(bytes.starts_with(b"\x89PNG"));
/// assert_eq!(decode_png(&bytes).unwrap(), image);
/// ```
pub fn encode_png(image: &RgbImage) -> Result<Vec<u8>, PngError> {
    let mut bytes = Vec::new();
    {
        let mut encoder = png::Encoder::new(&mut bytes, image.width, image.height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_compression(png::Compression::Fast);
        encoder.set_filter(png::Filter::Adaptive);
        encoder.write_header()?.write_image_data(&image.bytes)?;
    }
    Ok(bytes)
}

/// Decodes a PNG of 8-bit RGB or RGBA pixels (alpha dropped), such as every PNG figure here.
///
/// # Errors
/// [`PngError::Decode`] for bytes that are not a PNG, a truncated one, or another colour type
/// or depth.
///
/// # Examples
/// ```
/// assert!(hw3_core::plot::decode_png(b"not a png").is_err());
/// ```
pub fn decode_png(bytes: &[u8]) -> Result<RgbImage, PngError> {
    let error = |e: png::DecodingError| PngError::Decode(e.to_string());
    let mut reader = png::Decoder::new(Cursor::new(bytes)).read_info().map_err(error)?;
    let mut buffer = vec![0; reader.output_buffer_size().ok_or_else(|| PngError::Decode("too large".into()))?];
    let info = reader.next_frame(&mut buffer).map_err(error)?;
    let channels = match (info.color_type, info.bit_depth) {
        (png::ColorType::Rgb, png::BitDepth::Eight) => 3,
        (png::ColorType::Rgba, png::BitDepth::Eight) => 4,
        (color, depth) => return Err(PngError::Decode(format!("{color:?} at {depth:?} is not 8-bit RGB"))),
    };
    let rows = buffer[..info.buffer_size()].chunks_exact(info.line_size);
    let rgb = rows.flat_map(|row| row.chunks_exact(channels).flat_map(|p| [p[0], p[1], p[2]])).collect();
    RgbImage::from_raw(info.width, info.height, rgb).ok_or_else(|| PngError::Decode("wrong buffer size".into()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paste_cuts_at_the_edges_and_round_trips_through_png() {
        let mut canvas = RgbImage::from_pixel(5, 4, Rgb([1, 2, 3]));
        let patch = RgbImage::from_raw(2, 2, (0..12).collect()).unwrap();
        canvas.paste(&patch, 4, 3);
        assert_eq!(canvas.get_pixel(4, 3), Rgb([0, 1, 2]));
        assert_eq!(canvas.get_pixel(3, 3), Rgb([1, 2, 3]));
        canvas.paste(&patch, 9, 9);
        let bytes = encode_png(&canvas).unwrap();
        assert_eq!(bytes, encode_png(&canvas).unwrap());
        assert_eq!(decode_png(&bytes).unwrap(), canvas);
        assert!(matches!(decode_png(&bytes[..bytes.len() / 2]), Err(PngError::Decode(_))));
    }
}
