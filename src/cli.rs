//! What the `hw3` command line accepts: the bound of every count it takes, the parsers that
//! enforce them, and the cleaning every message goes through before it reaches a terminal.
//!
//! The bounds keep one command's work and memory within what a laptop does in seconds (the
//! README's table "Exit statuses and limits" lists each with its measured worst case);
//! `--allow-large` raises them to what the program can still do without overflowing.

use crate::fsio::io_reason;

/// Largest variant seed: answers files store it as a TOML integer, which is an `i64`.
pub const MAX_SEED: u64 = i64::MAX as u64;

/// `hw3 irradiance --size`: texels across the probe an analytic map is rasterised into.
pub const PROBE_SIZE: Limit = Limit { min: 16, max: 1024, max_large: 4096 };

/// `hw3 irradiance --samples`: Monte Carlo samples.
pub const IRRADIANCE_SAMPLES: Limit = Limit { min: 1, max: 1 << 20, max_large: 1 << 30 };

/// Texels of a lat-long `.hdr` map given to `hw3 irradiance --env` (width × height).
pub const MAP_TEXELS: Limit = Limit { min: 16 * 8, max: 2048 * 1024, max_large: crate::envmap::Probe::MAX_READ_TEXELS };

/// Smallest width and height of a lat-long map: below 16 texels across, the texel-sum estimators
/// of a constant map are off by more than 1 % (3.5 % at 8, 100 % at 1).
pub const MAP_MIN_SIDES: (u64, u64) = (16, 8);

/// Bytes of a `.hdr` file read by `hw3 irradiance` (RGBE is 4 bytes a texel, before run-length
/// encoding).
pub const MAP_FILE_BYTES: u64 = 4 * (1 << 24) + 4096;

/// Camera samples (width × height × spp) of one `hw3 render`.
pub const RENDER_SAMPLES: Limit = Limit { min: 1, max: 1 << 22, max_large: 1 << 40 };

/// Bytes of an answers file read by `hw3 check` (a complete answers file is about 3 KB).
pub const ANSWERS_FILE_BYTES: u64 = 256 * 1024;

/// Characters of user input a message may quote: the rest is cut, and the message says how much.
pub const QUOTE_CHARS: usize = 100;

/// Characters of one message line on stderr.
pub const MESSAGE_CHARS: usize = 240;

/// A count's accepted range: `min..=max`, or `min..=max_large` with `--allow-large`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limit {
    /// The smallest value accepted.
    pub min: u64,
    /// The largest value accepted by default.
    pub max: u64,
    /// The largest value accepted with `--allow-large`.
    pub max_large: u64,
}

impl Limit {
    /// Checks `value` (named `name` in the message) against the limit.
    ///
    /// # Errors
    /// A one-line message naming `name`, the range, and whether `--allow-large` would help.
    ///
    /// # Examples
    /// ```
    /// use hw3::cli::PROBE_SIZE;
    /// assert!(PROBE_SIZE.check("--size", 256, false).is_ok());
    /// assert!(PROBE_SIZE.check("--size", 2048, false).unwrap_err().contains("--allow-large"));
    /// assert!(PROBE_SIZE.check("--size", 2048, true).is_ok());
    /// assert!(PROBE_SIZE.check("--size", 1 << 20, true).is_err());
    /// ```
    pub fn check(&self, name: &str, value: u64, allow_large: bool) -> Result<u64, String> {
        let max = if allow_large { self.max_large } else { self.max };
        if value < self.min {
            Err(format!("{name} must be at least {}, got {value}", self.min))
        } else if value <= max {
            Ok(value)
        } else if !allow_large && value <= self.max_large {
            Err(format!(
                "{name} = {value} is over the limit of {max}; pass --allow-large to allow up to {}",
                self.max_large
            ))
        } else {
            Err(format!("{name} = {value} is over the limit of {}, even with --allow-large", self.max_large))
        }
    }
}

/// Parses a non-negative integer of at most `max`, in decimal, with a message that says the range.
///
/// # Errors
/// A one-line message for a sign, a non-digit, an empty string or a value over `max`.
///
/// # Examples
/// ```
/// assert_eq!(hw3::cli::parse_unsigned("42", 100), Ok(42));
/// assert!(hw3::cli::parse_unsigned("-1", 100).unwrap_err().contains("0 … 100"));
/// assert!(hw3::cli::parse_unsigned("101", 100).is_err());
/// ```
pub fn parse_unsigned(text: &str, max: u64) -> Result<u64, String> {
    let range = || format!("expected a whole number 0 … {max}, got `{}`", quote(text));
    if text.is_empty() || !text.bytes().all(|b| b.is_ascii_digit()) {
        return Err(range());
    }
    match text.parse::<u64>() {
        Ok(value) if value <= max => Ok(value),
        _ => Err(range()),
    }
}

/// The `--seed` parser of `template`, `check` and `variant`: 0 … 2⁶³ − 1, the seeds an answers
/// file can store, so that every template written can be checked.
///
/// # Errors
/// As [`parse_unsigned`].
///
/// # Examples
/// ```
/// assert_eq!(hw3::cli::parse_seed("9223372036854775807"), Ok(i64::MAX as u64));
/// assert!(hw3::cli::parse_seed("9223372036854775808").is_err());
/// ```
pub fn parse_seed(text: &str) -> Result<u64, String> {
    parse_unsigned(text, MAX_SEED).map_err(|e| format!("{e} (2^63 − 1 is the largest seed an answers file stores)"))
}

/// Parses `WIDTHxHEIGHT`, each side a whole number 1 … `max_side`.
///
/// # Errors
/// A one-line message naming `--size`.
///
/// # Examples
/// ```
/// assert_eq!(hw3::cli::parse_size("320x240", 8192), Ok((320, 240)));
/// assert!(hw3::cli::parse_size("0x5", 8192).is_err());
/// assert!(hw3::cli::parse_size("-3x5", 8192).is_err());
/// ```
pub fn parse_size(text: &str, max_side: u32) -> Result<(u32, u32), String> {
    let side = |s: &str| parse_unsigned(s.trim(), u64::from(max_side)).ok().filter(|&v| v >= 1);
    text.split_once(['x', 'X'])
        .and_then(|(w, h)| Some((u32::try_from(side(w)?).ok()?, u32::try_from(side(h)?).ok()?)))
        .ok_or_else(|| format!("--size: expected WIDTHxHEIGHT, each side 1 … {max_side}, got `{}`", quote(text)))
}

/// `text` cut to [`QUOTE_CHARS`] characters (with how many were cut), control characters escaped:
/// what a message may show of a user's input.
///
/// # Examples
/// ```
/// assert_eq!(hw3::cli::quote("a\u{1b}[2J"), "a\\u{1b}[2J");
/// let long = "x".repeat(1000);
/// assert!(hw3::cli::quote(&long).ends_with("… (900 more characters)"));
/// ```
#[must_use]
pub fn quote(text: &str) -> String {
    // Cut before escaping, so that the limit counts the user's characters.
    let kept = cut(text, QUOTE_CHARS);
    let (head, tail) = kept.split_at(kept.char_indices().nth(QUOTE_CHARS).map_or(kept.len(), |(i, _)| i));
    escape_controls(head) + tail
}

/// A message made safe for one line of a terminal: line breaks become spaces, other control
/// characters (terminal escapes among them) are shown as `\u{…}`, every backtick-quoted span is cut
/// to [`QUOTE_CHARS`] characters and the whole line to [`MESSAGE_CHARS`].
///
/// # Examples
/// ```
/// let message = format!("bad value `{}`\nsecond line", "9".repeat(5000));
/// let line = hw3::cli::one_line(&message);
/// assert!(!line.contains('\n'));
/// assert!(line.chars().count() <= hw3::cli::MESSAGE_CHARS + 30);
/// ```
#[must_use]
pub fn one_line(message: &str) -> String {
    let flat: String = message.chars().map(|c| if matches!(c, '\n' | '\r' | '\t') { ' ' } else { c }).collect();
    // Odd pieces between backticks are quoted input.
    let clipped: Vec<String> = flat
        .split('`')
        .enumerate()
        .map(|(i, piece)| if i % 2 == 1 { quote(piece) } else { escape_controls(piece) })
        .collect();
    cut(&clipped.join("`"), MESSAGE_CHARS)
}

/// `text` cut to `max` characters, saying how many were cut.
fn cut(text: &str, max: usize) -> String {
    let total = text.chars().count();
    if total <= max {
        return text.to_owned();
    }
    let mut kept: String = text.chars().take(max).collect();
    kept.push_str(&format!("… ({} more characters)", total - max));
    kept
}

/// Longest line of a report on stdout ([`terminal_text`]). A report's feedback teaches, so it is cut
/// far later than an error message; the answers file behind it is bounded anyway (256 KiB).
pub const REPORT_LINE_CHARS: usize = 2000;

/// Multi-line text for a terminal (a report on stdout): control characters other than line breaks
/// are shown as `\u{…}`, and each line longer than [`REPORT_LINE_CHARS`] is cut.
///
/// # Examples
/// ```
/// assert_eq!(hw3::cli::terminal_text("ok\n\u{1b}[31mred"), "ok\n\\u{1b}[31mred");
/// ```
#[must_use]
pub fn terminal_text(text: &str) -> String {
    let lines: Vec<String> = text.split('\n').map(|line| cut(&escape_controls(line), REPORT_LINE_CHARS)).collect();
    lines.join("\n")
}

/// Replaces C0, DEL and C1 control characters by a visible `\u{…}`.
fn escape_controls(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        if c.is_control() {
            out.push_str(&format!("\\u{{{:x}}}", u32::from(c)));
        } else {
            out.push(c);
        }
    }
    out
}

/// Reads at most `limit` bytes of `path` as UTF-8 text: a device that never ends (`/dev/zero`) or a
/// huge file is refused after `limit + 1` bytes, without reading the rest.
///
/// # Errors
/// A one-line message naming the file: unreadable, over the limit, or not UTF-8.
///
/// # Examples
/// ```
/// assert!(hw3::cli::read_text_bounded(std::path::Path::new("/dev/zero"), 1024).unwrap_err().contains("1024"));
/// ```
pub fn read_text_bounded(path: &std::path::Path, limit: u64) -> Result<String, String> {
    use std::io::Read as _;
    let name = quote(&path.display().to_string());
    let file = std::fs::File::open(path).map_err(|e| format!("cannot read {name}: {}", io_reason(&e)))?;
    if file.metadata().is_ok_and(|m| m.is_dir()) {
        return Err(format!("cannot read {name}: it is a directory"));
    }
    let mut bytes = Vec::new();
    file.take(limit + 1).read_to_end(&mut bytes).map_err(|e| format!("cannot read {name}: {}", io_reason(&e)))?;
    if bytes.len() as u64 > limit {
        return Err(format!("{name} is longer than the limit of {limit} bytes"));
    }
    String::from_utf8(bytes).map_err(|e| format!("{name} is not UTF-8 text (byte {})", e.utf8_error().valid_up_to()))
}

/// Checks a Radiance `.hdr` file before it is decoded: its size in bytes, its header (read by the
/// decoder's own header reader: signature, `FORMAT`, resolution line), and the resolution it
/// declares, against [`MAP_TEXELS`] and [`MAP_MIN_SIDES`].
///
/// # Errors
/// A one-line message naming the file and what is wrong (not a Radiance file, too large, too small).
///
/// # Examples
/// ```
/// let path = std::env::temp_dir().join(format!("hw3-cli-doc-{}.hdr", std::process::id()));
/// std::fs::write(&path, b"\x89PNG\r\n\x1a\n").unwrap();
/// assert!(hw3::cli::check_hdr_file(&path, false).unwrap_err().contains("not a Radiance"));
/// std::fs::remove_file(&path).unwrap();
/// ```
pub fn check_hdr_file(path: &std::path::Path, allow_large: bool) -> Result<(), String> {
    use std::io::Read as _;
    let name = quote(&path.display().to_string());
    let file = std::fs::File::open(path).map_err(|e| format!("--env: cannot read {name}: {}", io_reason(&e)))?;
    let meta = file.metadata().map_err(|e| format!("--env: cannot read {name}: {}", io_reason(&e)))?;
    if !meta.is_file() {
        return Err(format!("--env: {name} is not a regular file"));
    }
    if meta.len() > MAP_FILE_BYTES {
        return Err(format!("--env: {name} has {} bytes, over the limit of {MAP_FILE_BYTES}", meta.len()));
    }
    // The decoder's own header reader, on at most 64 KiB: what passes here is what it will read.
    use crate::envmap::radiance::{RadianceError, read_header};
    let mut reader = std::io::BufReader::new(file.take(64 * 1024));
    let (width, height) = read_header(&mut reader).map_err(|e| match e {
        RadianceError::Signature => {
            format!("--env: {name} is not a Radiance .hdr file (it does not start with #?RADIANCE)")
        }
        RadianceError::Resolution(line) => {
            format!("--env: {name} has an unreadable resolution line `{}`", quote(&line))
        }
        other => format!("--env: {name}: {other}"),
    })?;
    let (width, height) = (u64::from(width), u64::from(height));
    if width < MAP_MIN_SIDES.0 || height < MAP_MIN_SIDES.1 {
        return Err(format!(
            "--env: {name} is {width}×{height}; a map needs at least {}×{} texels for the estimators to agree",
            MAP_MIN_SIDES.0, MAP_MIN_SIDES.1
        ));
    }
    MAP_TEXELS.check(
        &format!("--env: {name}: texels ({width}×{height})"),
        width.saturating_mul(height),
        allow_large,
    )?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn limits_name_the_flag_that_lifts_them() {
        let message = RENDER_SAMPLES.check("--spp", RENDER_SAMPLES.max + 1, false).unwrap_err();
        assert!(message.contains("--allow-large"), "{message}");
        assert!(!RENDER_SAMPLES.check("--spp", u64::MAX, true).unwrap_err().contains("pass --allow-large"));
        assert!(PROBE_SIZE.check("--size", 1, false).unwrap_err().contains("at least 16"));
    }

    #[test]
    fn parse_unsigned_refuses_signs_spaces_and_overflow() {
        for bad in ["", "+1", "-0", " 1", "1e3", "0x10", "18446744073709551616", "١"] {
            assert!(parse_unsigned(bad, u64::MAX).is_err(), "{bad:?}");
        }
        assert_eq!(parse_unsigned("18446744073709551615", u64::MAX), Ok(u64::MAX));
        assert_eq!(parse_unsigned("007", 10), Ok(7));
    }

    #[test]
    fn one_line_never_carries_a_control_character() {
        let line = one_line("a\u{7}b\u{9b}c\u{7f}d\r\ne");
        assert!(!line.chars().any(char::is_control), "{line:?}");
        assert_eq!(line, "a\\u{7}b\\u{9b}c\\u{7f}d  e");
    }
}
