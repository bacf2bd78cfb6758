//! Reading Radiance `.hdr` files: Ward's RGBE pixels (G. Ward, "Real Pixels", *Graphics Gems II*,
//! 1991, pp. 80–83), the format of every light probe here.
//!
//! A file is a text header (`#?RADIANCE`, `NAME=value` lines, an empty line), a resolution line
//! (`-Y height +X width`: rows from the top, pixels left to right, the only orientation read
//! here) and one scanline per row. A pixel is four bytes `(r, g, b, e)`: a shared exponent `e`
//! and three 8-bit mantissas, so the value of a channel is `c · 2^(e − 136)` (`e − 128` for the
//! exponent, `− 8` for the mantissa's eight bits), and `e = 0` is black. This is the rule of
//! Ward's reference code (`rgbe.c`): no half-step is added to the mantissa. Scanlines are stored
//! flat, in the old run-length form (a pixel `(1, 1, 1, n)` repeats the previous pixel `n` times,
//! `n · 256` for a second marker in a row), or in the newer form marked by the bytes `2, 2` and a
//! width below 2¹⁵: the four channels of the row one after another, each as runs (a count byte
//! above 128 repeats the next byte `count − 128` times) and literals (a count byte up to 128 is
//! followed by that many bytes).
//!
//! Why here and not a crate: `image` 0.25 reads this format but compiles a colour-management
//! library with it that nothing here uses;
//! `zune-hdr` 0.5.2 computes `2^(e − 128)` with a shift masked to 5 bits, so an exponent below
//! 2⁻³¹ or above 2³¹ comes out wrong; `radiant` 0.3 divides the mantissa by 255 instead of 256.
//! The header's `EXPOSURE` is not applied (as `image` did not): every map here is stored in
//! radiance units already.

use std::io::{BufRead, Read};

/// Why a Radiance file could not be read.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum RadianceError {
    /// Reading failed (the operating system's message, or "unexpected end of file").
    #[error("{0}")]
    Io(String),
    /// The file does not start with `#?RADIANCE` (or `#?RGBE`, which some writers use).
    #[error("not a Radiance HDR file (no #?RADIANCE signature)")]
    Signature,
    /// The header ends before its empty line, or has a `FORMAT` other than RGBE.
    #[error("bad Radiance header: {0}")]
    Header(String),
    /// The resolution line is not `-Y height +X width` with 32-bit sizes.
    #[error("unsupported or unreadable resolution line `{0}` (expected `-Y height +X width`)")]
    Resolution(String),
    /// A scanline's runs do not add up to the width.
    #[error("scanline {row} has {got} pixels, expected {width}")]
    Scanline {
        /// Row of the scanline, from the top.
        row: usize,
        /// Pixels its runs would give.
        got: usize,
        /// The image's width.
        width: usize,
    },
}

impl From<std::io::Error> for RadianceError {
    fn from(e: std::io::Error) -> Self {
        if e.kind() == std::io::ErrorKind::UnexpectedEof {
            Self::Io("unexpected end of file".into())
        } else {
            Self::Io(e.to_string())
        }
    }
}

/// The longest header line read (Radiance writers keep them far shorter); a longer one is refused
/// rather than buffered without bound.
const MAX_LINE: usize = 4096;

fn read_line<R: BufRead>(reader: &mut R) -> Result<Option<Vec<u8>>, RadianceError> {
    let mut line = Vec::new();
    let read = reader.take(MAX_LINE as u64 + 1).read_until(b'\n', &mut line)?;
    if read == 0 {
        return Ok(None);
    }
    if line.last() == Some(&b'\n') {
        line.pop();
    } else if line.len() > MAX_LINE {
        return Err(RadianceError::Header(format!("a line is longer than {MAX_LINE} bytes")));
    }
    Ok(Some(line))
}

/// Reads the header and resolution line; returns `(width, height)` and leaves `reader` at the
/// first scanline.
///
/// # Errors
/// [`RadianceError::Signature`], [`RadianceError::Header`], [`RadianceError::Resolution`], or
/// [`RadianceError::Io`] if the file ends or cannot be read.
pub fn read_header<R: BufRead>(reader: &mut R) -> Result<(u32, u32), RadianceError> {
    let first = read_line(reader)?.ok_or(RadianceError::Signature)?;
    if !(first.starts_with(b"#?RADIANCE") || first.starts_with(b"#?RGBE")) {
        return Err(RadianceError::Signature);
    }
    loop {
        let Some(line) = read_line(reader)? else {
            return Err(RadianceError::Header("the file ends inside its header".into()));
        };
        if line.is_empty() {
            break;
        }
        let text = String::from_utf8_lossy(&line);
        if let Some((key, value)) = text.split_once('=')
            && key.trim() == "FORMAT"
            && value.trim() != "32-bit_rle_rgbe"
        {
            let shown: String = value.trim().chars().take(20).collect();
            return Err(RadianceError::Header(format!("FORMAT={shown} is not 32-bit_rle_rgbe")));
        }
    }
    let line = read_line(reader)?.ok_or_else(|| RadianceError::Resolution(String::new()))?;
    let text = String::from_utf8_lossy(&line).into_owned();
    let words: Vec<&str> = text.split_whitespace().collect();
    let refused = || RadianceError::Resolution(text.chars().take(40).collect());
    match words[..] {
        ["-Y", height, "+X", width] => {
            Ok((width.parse().map_err(|_| refused())?, height.parse().map_err(|_| refused())?))
        }
        _ => Err(refused()),
    }
}

/// The linear value of an RGBE pixel's channels, `c · 2^(e − 136)`, exactly: every such value
/// is an `f32` (the smallest, `2⁻¹³⁵`, is subnormal but representable, with room for the
/// mantissa's eight bits), and products and quotients of powers of two are exact in range.
#[must_use]
pub(crate) fn rgbe_to_rgb([r, g, b, e]: [u8; 4]) -> [f32; 3] {
    if e == 0 {
        return [0.0; 3];
    }
    // 2^(e − 128) spans 2⁻¹²⁷…2¹²⁷, inside f32's range, so the power and the division are
    // exact (the tests check every exponent against f64).
    let scale = 2f32.powi(i32::from(e) - 128) / 256.0;
    [f32::from(r) * scale, f32::from(g) * scale, f32::from(b) * scale]
}

fn read_pixel<R: Read>(reader: &mut R) -> Result<[u8; 4], RadianceError> {
    let mut pixel = [0; 4];
    reader.read_exact(&mut pixel)?;
    Ok(pixel)
}

/// Reads `height` scanlines of `width` pixels (after [`read_header`]) as linear RGB, row by row.
///
/// # Errors
/// [`RadianceError::Scanline`] when a scanline's runs overrun its width, [`RadianceError::Io`]
/// when the file ends early.
pub(crate) fn read_pixels<R: Read>(reader: &mut R, width: u32, height: u32) -> Result<Vec<[f32; 3]>, RadianceError> {
    let (width, height) = (width as usize, height as usize);
    let mut rgb = Vec::with_capacity(width.saturating_mul(height));
    let mut row = vec![[0u8; 4]; width];
    for y in 0..height {
        read_scanline(reader, &mut row, y)?;
        rgb.extend(row.iter().map(|&p| rgbe_to_rgb(p)));
    }
    Ok(rgb)
}

fn read_scanline<R: Read>(reader: &mut R, row: &mut [[u8; 4]], y: usize) -> Result<(), RadianceError> {
    let width = row.len();
    if width == 0 {
        return Ok(());
    }
    let first = read_pixel(reader)?;
    // The newer run-length form: (2, 2, high byte of the width, low byte), width < 2¹⁵.
    if first[0] == 2 && first[1] == 2 && first[2] < 128 {
        for channel in 0..4 {
            let mut x = 0;
            while x < width {
                let mut count = [0u8];
                reader.read_exact(&mut count)?;
                let (run, literal) =
                    if count[0] > 128 { (usize::from(count[0] - 128), false) } else { (usize::from(count[0]), true) };
                if x + run > width {
                    return Err(RadianceError::Scanline { row: y, got: x + run, width });
                }
                if literal {
                    let mut bytes = [0u8; 128];
                    reader.read_exact(&mut bytes[..run])?;
                    for (pixel, byte) in row[x..x + run].iter_mut().zip(&bytes[..run]) {
                        pixel[channel] = *byte;
                    }
                } else {
                    let mut value = [0u8];
                    reader.read_exact(&mut value)?;
                    row[x..x + run].iter_mut().for_each(|pixel| pixel[channel] = value[0]);
                }
                // A zero count adds nothing; the file then ends or overruns, both refused.
                x += run;
            }
        }
        return Ok(());
    }
    // Flat pixels, or the old run-length form.
    let is_marker = |p: [u8; 4]| p[..3] == [1, 1, 1];
    if is_marker(first) {
        return Err(RadianceError::Scanline { row: y, got: 0, width });
    }
    row[0] = first;
    let (mut x, mut multiplier) = (1, 1usize);
    while x < width {
        let pixel = read_pixel(reader)?;
        if is_marker(pixel) {
            // Consecutive markers multiply by 256 each; an overflow can only overrun the row.
            let run = usize::from(pixel[3]).saturating_mul(multiplier);
            let end = x.saturating_add(run);
            if end > width {
                return Err(RadianceError::Scanline { row: y, got: end, width });
            }
            let previous = row[x - 1];
            row[x..end].iter_mut().for_each(|p| *p = previous);
            x = end;
            multiplier = multiplier.saturating_mul(256);
        } else {
            row[x] = pixel;
            x += 1;
            multiplier = 1;
        }
    }
    Ok(())
}

/// A flat (uncompressed) Radiance file of `width` × `height` pixels, for tests: each value
/// rounded down to 8 mantissa bits, as Ward's `float2rgbe`.
#[cfg(test)]
pub(crate) fn flat_file(width: u32, height: u32, rgb: &[[f32; 3]]) -> Vec<u8> {
    let mut bytes = format!("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y {height} +X {width}\n").into_bytes();
    for &[r, g, b] in rgb {
        let largest = r.max(g).max(b);
        if largest < 1e-32 {
            bytes.extend([0; 4]);
            continue;
        }
        // largest = m · 2^e with m in [0.5, 1): the mantissas are c · 256 / 2^e.
        let e = largest.log2().floor() as i32 + 1;
        let scale = 256.0 / 2f32.powi(e);
        bytes.extend([(r * scale) as u8, (g * scale) as u8, (b * scale) as u8, (e + 128) as u8]);
    }
    bytes
}

#[cfg(test)]
mod tests {
    use super::*;

    fn decode(bytes: &[u8]) -> Result<(u32, u32, Vec<[f32; 3]>), RadianceError> {
        let mut reader = bytes;
        let (w, h) = read_header(&mut reader)?;
        Ok((w, h, read_pixels(&mut reader, w, h)?))
    }

    /// Test vectors worked by hand from the rule `c · 2^(e − 136)`.
    #[test]
    fn rgbe_values_follow_wards_rule_at_both_ends_of_the_exponent() {
        assert_eq!(rgbe_to_rgb([128, 64, 255, 129]), [1.0, 0.5, 255.0 / 128.0]);
        assert_eq!(rgbe_to_rgb([200, 1, 0, 0]), [0.0; 3], "e = 0 is black whatever the mantissas");
        // The expected values are computed in f64 and rounded once: `2f32.powi(-135)` overflows its
        // intermediate 2¹³⁵ at run time (0), while an optimised build folds it to the exact value.
        assert_eq!(rgbe_to_rgb([1, 0, 0, 1])[0], 2f64.powi(-135) as f32);
        assert_eq!(rgbe_to_rgb([255, 0, 0, 255])[0], 255.0 * 2f32.powi(119));
        assert_eq!(rgbe_to_rgb([128, 0, 0, 96])[0], 2f32.powi(-33), "beyond 2⁻³¹: zune-hdr's wrap");
        for e in 1..=255u8 {
            for c in [1u8, 17, 128, 255] {
                let exact = f64::from(c) * 2f64.powi(i32::from(e) - 136);
                assert_eq!(f64::from(rgbe_to_rgb([c, 0, 0, e])[0]), exact, "c = {c}, e = {e}");
            }
        }
    }

    #[test]
    fn the_three_scanline_forms_decode_to_the_same_pixels() {
        let header = b"#?RADIANCE\n# a comment\nFORMAT=32-bit_rle_rgbe\nEXPOSURE=2\n\n-Y 1 +X 4\n".to_vec();
        let (a, b) = ([128u8, 128, 128, 129], [64u8, 0, 255, 130]);
        let flat = [header.clone(), [a, a, a, b].concat()].concat();
        let old = [header.clone(), [a, [1, 1, 1, 2], b].concat()].concat();
        // New form: per channel, a run of three then a literal of one.
        let mut new = [header, vec![2, 2, 0, 4]].concat();
        for c in 0..4 {
            new.extend([128 + 3, a[c], 1, b[c]]);
        }
        let expected = vec![[1.0; 3], [1.0; 3], [1.0; 3], [1.0, 0.0, 255.0 / 64.0]];
        for bytes in [flat, old, new] {
            assert_eq!(decode(&bytes), Ok((4, 1, expected.clone())));
        }
    }

    #[test]
    fn broken_files_are_refused_with_a_reason() {
        type Check = fn(&RadianceError) -> bool;
        let cases: [(&[u8], Check); 8] = [
            (b"", |e| *e == RadianceError::Signature),
            (b"\x89PNG\r\n", |e| *e == RadianceError::Signature),
            (b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n", |e| matches!(e, RadianceError::Header(_))),
            (b"#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 1 +X 1\n", |e| matches!(e, RadianceError::Header(_))),
            (b"#?RADIANCE\n\n+X 1 -Y 1\n", |e| matches!(e, RadianceError::Resolution(_))),
            (b"#?RADIANCE\n\n-Y 1 +X 4294967296\n", |e| matches!(e, RadianceError::Resolution(_))),
            (b"#?RADIANCE\n\n-Y 4 +X 8\n\x02\x02", |e| matches!(e, RadianceError::Io(_))),
            (b"#?RADIANCE\n\n-Y 1 +X 2\n\x02\x02\x00\x02\xff\x00", |e| matches!(e, RadianceError::Scanline { .. })),
        ];
        for (bytes, expected) in cases {
            let error = decode(bytes).unwrap_err();
            assert!(expected(&error), "{:?}: {error}", String::from_utf8_lossy(bytes));
        }
        let mut markers = b"#?RADIANCE\n\n-Y 1 +X 3\n".to_vec();
        markers.extend([5, 5, 5, 130]);
        markers.extend([1, 1, 1, 255].repeat(12));
        assert!(matches!(decode(&markers), Err(RadianceError::Scanline { .. })), "chained markers overrun");
    }

    #[test]
    fn the_test_writer_round_trips_representable_values() {
        let rgb = [[0.25, 1.0, 2.0], [1.75, 0.0, 0.5], [0.0; 3], [3.0, 96.0, 1e-3]];
        let (w, h, back) = decode(&flat_file(2, 2, &rgb)).unwrap();
        assert_eq!((w, h), (2, 2));
        assert_eq!(&back[..3], &rgb[..3]);
        // Eight mantissa bits shared by the three channels: an error below 2⁻⁷ of the largest.
        for (got, want) in back[3].iter().zip(rgb[3]) {
            assert!((got - want).abs() <= 96.0 / 128.0, "{:?}", back[3]);
        }
    }
}
