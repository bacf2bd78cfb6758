//! What the `hw3` command line accepts: the bound of every count it takes, the parsers that
//! enforce them, and the cleaning every message goes through before it reaches a terminal.
//!
//! The bounds keep one command's work and memory within what a laptop does in seconds (the
//! README's table "Exit statuses and limits" lists each with its measured worst case);
//! `--allow-large` raises them to what the program can still do without overflowing.

use crate::envmap::radiance::RadianceError;
use crate::fsio::io_reason;
use std::path::{Path, PathBuf};

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

/// A count outside its [`Limit`] ([`Limit::check`]): which count, its value and the bound it
/// crosses.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum LimitError {
    /// The value is below the limit's minimum.
    #[error("{name} must be at least {min}, got {value}")]
    TooSmall {
        /// The count as the message names it (`--size`, or a description).
        name: String,
        /// The value given.
        value: u64,
        /// [`Limit::min`].
        min: u64,
    },
    /// The value is over the default maximum, and `--allow-large` would accept it.
    #[error("{name} = {value} is over the limit of {max}; pass --allow-large to allow up to {max_large}")]
    NeedsAllowLarge {
        /// The count as the message names it.
        name: String,
        /// The value given.
        value: u64,
        /// [`Limit::max`].
        max: u64,
        /// [`Limit::max_large`].
        max_large: u64,
    },
    /// The value is over the largest value accepted even with `--allow-large`.
    #[error("{name} = {value} is over the limit of {max_large}, even with --allow-large")]
    TooLarge {
        /// The count as the message names it.
        name: String,
        /// The value given.
        value: u64,
        /// [`Limit::max_large`].
        max_large: u64,
    },
}

impl Limit {
    /// Checks `value` (named `name` in the message) against the limit.
    ///
    /// # Errors
    /// [`LimitError::TooSmall`] below [`Limit::min`], [`LimitError::NeedsAllowLarge`] over
    /// [`Limit::max`] when `--allow-large` would help (it is not given and the value is within
    /// [`Limit::max_large`]), [`LimitError::TooLarge`] over [`Limit::max_large`]: each names
    /// `name`, the value and the bound.
    ///
    /// # Examples
    /// ```
    /// use hw3::cli::{LimitError, PROBE_SIZE};
    /// assert!(PROBE_SIZE.check("--size", 256, false).is_ok());
    /// let error = PROBE_SIZE.check("--size", 2048, false).unwrap_err();
    /// assert!(matches!(error, LimitError::NeedsAllowLarge { value: 2048, max: 1024, .. }));
    /// assert!(error.to_string().contains("--allow-large"));
    /// assert!(PROBE_SIZE.check("--size", 2048, true).is_ok());
    /// assert!(matches!(PROBE_SIZE.check("--size", 1 << 20, true), Err(LimitError::TooLarge { .. })));
    /// ```
    pub fn check(&self, name: &str, value: u64, allow_large: bool) -> Result<u64, LimitError> {
        let max = if allow_large { self.max_large } else { self.max };
        let name = name.to_owned();
        if value < self.min {
            Err(LimitError::TooSmall { name, value, min: self.min })
        } else if value <= max {
            Ok(value)
        } else if !allow_large && value <= self.max_large {
            Err(LimitError::NeedsAllowLarge { name, value, max, max_large: self.max_large })
        } else {
            Err(LimitError::TooLarge { name, value, max_large: self.max_large })
        }
    }
}

/// A command-line value that does not parse ([`parse_unsigned`], [`parse_seed`],
/// [`parse_size`]): the text given and the range it should be in. The text is shown
/// [`quote`]d.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ArgError {
    /// Not a whole number from 0 to `max` (a sign, a non-digit, an empty text, a larger value).
    #[error("expected a whole number 0 … {max}, got `{}`", quote(.text))]
    NotAWholeNumber {
        /// The text given.
        text: String,
        /// The largest value accepted.
        max: u64,
    },
    /// Not a seed an answers file can store: a whole number from 0 to [`MAX_SEED`].
    #[error(
        "expected a whole number 0 … {MAX_SEED}, got `{}` (2^63 − 1 is the largest seed an answers file stores)",
        quote(.text)
    )]
    Seed {
        /// The text given.
        text: String,
    },
    /// `--size` is not `WIDTHxHEIGHT` with each side from 1 to `max_side`.
    #[error("--size: expected WIDTHxHEIGHT, each side 1 … {max_side}, got `{}`", quote(.text))]
    Size {
        /// The text given.
        text: String,
        /// The largest side accepted.
        max_side: u32,
    },
}

/// Parses a non-negative integer of at most `max`, in decimal, with a message that says the range.
///
/// # Errors
/// [`ArgError::NotAWholeNumber`] for a sign, a non-digit, an empty string or a value over `max`.
///
/// # Examples
/// ```
/// use hw3::cli::{ArgError, parse_unsigned};
/// assert_eq!(parse_unsigned("42", 100), Ok(42));
/// let error = parse_unsigned("-1", 100).unwrap_err();
/// assert_eq!(error, ArgError::NotAWholeNumber { text: "-1".into(), max: 100 });
/// assert!(error.to_string().contains("0 … 100"));
/// assert!(parse_unsigned("101", 100).is_err());
/// ```
pub fn parse_unsigned(text: &str, max: u64) -> Result<u64, ArgError> {
    let range = || ArgError::NotAWholeNumber { text: text.to_owned(), max };
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
/// [`ArgError::Seed`] where [`parse_unsigned`] fails.
///
/// # Examples
/// ```
/// use hw3::cli::{ArgError, parse_seed};
/// assert_eq!(parse_seed("9223372036854775807"), Ok(i64::MAX as u64));
/// assert_eq!(parse_seed("9223372036854775808"), Err(ArgError::Seed { text: "9223372036854775808".into() }));
/// ```
pub fn parse_seed(text: &str) -> Result<u64, ArgError> {
    parse_unsigned(text, MAX_SEED).map_err(|_| ArgError::Seed { text: text.to_owned() })
}

/// Parses `WIDTHxHEIGHT`, each side a whole number 1 … `max_side`.
///
/// # Errors
/// [`ArgError::Size`], whose message names `--size`.
///
/// # Examples
/// ```
/// use hw3::cli::{ArgError, parse_size};
/// assert_eq!(parse_size("320x240", 8192), Ok((320, 240)));
/// assert_eq!(parse_size("0x5", 8192), Err(ArgError::Size { text: "0x5".into(), max_side: 8192 }));
/// assert!(parse_size("-3x5", 8192).is_err());
/// ```
pub fn parse_size(text: &str, max_side: u32) -> Result<(u32, u32), ArgError> {
    let side = |s: &str| parse_unsigned(s.trim(), u64::from(max_side)).ok().filter(|&v| v >= 1);
    text.split_once(['x', 'X'])
        .and_then(|(w, h)| Some((u32::try_from(side(w)?).ok()?, u32::try_from(side(h)?).ok()?)))
        .ok_or_else(|| ArgError::Size { text: text.to_owned(), max_side })
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
    quote_within(text, QUOTE_CHARS)
}

/// [`quote`] with a limit of `max` characters.
fn quote_within(text: &str, max: usize) -> String {
    // Cut before escaping, so that the limit counts the user's characters.
    let kept = cut(text, max);
    let (head, tail) = kept.split_at(kept.char_indices().nth(max).map_or(kept.len(), |(i, _)| i));
    escape(head) + tail
}

/// A message made safe for one line of a terminal: line breaks become spaces, other control
/// characters (terminal escapes and bidirectional overrides among them) are shown as `\u{…}`, every
/// backtick-quoted span is cut to [`QUOTE_CHARS`] characters, and a line still longer than
/// [`MESSAGE_CHARS`] loses characters from its middle, so that its start (what failed) and its
/// end (why) are both kept.
///
/// # Examples
/// ```
/// let message = format!("bad value `{}`\nsecond line", "9".repeat(5000));
/// let line = hw3::cli::one_line(&message);
/// assert!(!line.contains('\n'));
/// assert!(line.chars().count() <= hw3::cli::MESSAGE_CHARS);
/// let long = format!("{}: No such file or directory", "d/".repeat(400));
/// assert!(hw3::cli::one_line(&long).ends_with(": No such file or directory"));
/// ```
#[must_use]
pub fn one_line(message: &str) -> String {
    let flat: String = message.chars().map(|c| if matches!(c, '\n' | '\r' | '\t') { ' ' } else { c }).collect();
    // Odd pieces between backticks are quoted input: quoted shorter while the line is too long.
    let clipped = |quote_chars: usize| -> String {
        let pieces: Vec<String> = flat
            .split('`')
            .enumerate()
            .map(|(i, piece)| if i % 2 == 1 { quote_within(piece, quote_chars) } else { escape(piece) })
            .collect();
        pieces.join("`")
    };
    let line = [QUOTE_CHARS, 60, 30, 12]
        .into_iter()
        .map(clipped)
        .find(|line| line.chars().count() <= MESSAGE_CHARS)
        .unwrap_or_else(|| clipped(12));
    cut_middle(&line, MESSAGE_CHARS)
}

/// Characters kept from the end of a message cut by [`cut_middle`]: room for its reason.
const MESSAGE_TAIL_CHARS: usize = 120;

/// `text` in at most `max` characters: unchanged if it fits, else its start and its last
/// [`MESSAGE_TAIL_CHARS`] characters around a mark saying how many were cut.
fn cut_middle(text: &str, max: usize) -> String {
    let chars: Vec<char> = text.chars().collect();
    if chars.len() <= max {
        return text.to_owned();
    }
    let mark = |n: usize| format!(" …({n} characters cut)… ");
    // The mark's length depends on the count it shows; the widest count is the whole length.
    let head = max - MESSAGE_TAIL_CHARS - mark(chars.len()).chars().count();
    let tail_start = chars.len() - MESSAGE_TAIL_CHARS;
    let head_text: String = chars[..head].iter().collect();
    let tail_text: String = chars[tail_start..].iter().collect();
    format!("{head_text}{}{tail_text}", mark(tail_start - head))
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
    let lines: Vec<String> = text.split('\n').map(|line| cut(&escape(line), REPORT_LINE_CHARS)).collect();
    lines.join("\n")
}

/// A report as pretty JSON that is also safe on a terminal: every character [`escape`] would
/// show escaped is written as a JSON `\uXXXX` escape (serde escapes C0 controls already, but not
/// DEL, C1 controls or the bidirectional ones). The value is unchanged for any JSON reader: such
/// characters occur only inside strings.
///
/// # Errors
/// Serialisation's, which a report's types never produce.
///
/// # Examples
/// ```
/// let text = hw3::cli::json_text(&serde_json::json!({ "given": "n\u{202e}o" })).unwrap();
/// assert!(text.contains(r"n\u202eo"));
/// let back: serde_json::Value = serde_json::from_str(&text).unwrap();
/// assert_eq!(back["given"], "n\u{202e}o");
/// ```
pub fn json_text<T: serde::Serialize + ?Sized>(value: &T) -> serde_json::Result<String> {
    let text = serde_json::to_string_pretty(value)?;
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        if c != '\n' && reaches_terminal_escaped(c) {
            let mut units = [0u16; 2];
            use std::fmt::Write as _;
            for unit in c.encode_utf16(&mut units) {
                let _ = write!(out, "\\u{unit:04x}");
            }
        } else {
            out.push(c);
        }
    }
    Ok(out)
}

/// Whether [`escape`] shows `c` escaped.
fn reaches_terminal_escaped(c: char) -> bool {
    c.is_control()
        || matches!(c, '\u{200e}' | '\u{200f}' | '\u{061c}' | '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}')
}

/// Replaces C0, DEL and C1 control characters, and the invisible characters that reorder text
/// (bidirectional embeddings, overrides, isolates and marks, Unicode TR9 §2), by a visible
/// `\u{…}`: nothing a user typed can move the cursor, recolour the terminal or make text read
/// backwards.
///
/// # Examples
/// ```
/// assert_eq!(hw3::cli::escape("a\u{202e}b\n"), "a\\u{202e}b\\u{a}");
/// ```
#[must_use]
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        let reorders =
            matches!(c, '\u{200e}' | '\u{200f}' | '\u{061c}' | '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}');
        if c.is_control() || reorders {
            out.push_str(&format!("\\u{{{:x}}}", u32::from(c)));
        } else {
            out.push(c);
        }
    }
    out
}

/// A path as a message shows it: [`quote`]d.
fn shown(path: &Path) -> String {
    quote(&path.display().to_string())
}

/// Why a text file could not be read ([`read_text_bounded`]): which file, and what is wrong.
///
/// # Examples
/// ```
/// use hw3::cli::{ReadError, read_text_bounded};
/// let error = read_text_bounded(std::path::Path::new("/dev/zero"), 1024).unwrap_err();
/// assert!(matches!(error, ReadError::NotAFile { kind: "a device", .. }));
/// assert_eq!(error.to_string(), "cannot read /dev/zero: it is a device, not a regular file");
/// ```
#[derive(Debug, thiserror::Error)]
pub enum ReadError {
    /// The file cannot be opened or read.
    #[error("cannot read {}: {}", shown(.path), io_reason(.source))]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// The path is a folder, a named pipe, a device or a socket (refused before reading, so that
    /// a pipe with no writer cannot make the command wait forever).
    #[error("cannot read {}: it is {kind}, not a regular file", shown(.path))]
    NotAFile {
        /// The path.
        path: PathBuf,
        /// What it is ([`crate::fsio::kind_of`]).
        kind: &'static str,
    },
    /// The file holds more than `limit` bytes.
    #[error("{} is longer than the limit of {limit} bytes", shown(.path))]
    TooLong {
        /// The file.
        path: PathBuf,
        /// The most bytes read.
        limit: u64,
    },
    /// The file is not UTF-8 text.
    #[error("{} is not UTF-8 text (byte {})", shown(.path), .source.valid_up_to())]
    NotUtf8 {
        /// The file.
        path: PathBuf,
        /// The decoder's error, which says where the first bad byte is.
        source: std::str::Utf8Error,
    },
}

/// Reads at most `limit` bytes of `path` as UTF-8 text: a device that never ends (`/dev/zero`) or a
/// huge file is refused after `limit + 1` bytes, without reading the rest.
///
/// # Errors
/// A [`ReadError`] naming the file: [`ReadError::Io`] when it cannot be read,
/// [`ReadError::NotAFile`] for a folder, a pipe or a device, [`ReadError::TooLong`] over the limit,
/// [`ReadError::NotUtf8`] when it is not UTF-8.
///
/// # Examples
/// ```
/// let path = std::env::temp_dir().join(format!("hw3-bounded-doc-{}.toml", std::process::id()));
/// std::fs::write(&path, "x".repeat(2000)).unwrap();
/// assert!(hw3::cli::read_text_bounded(&path, 1024).unwrap_err().to_string().contains("limit of 1024 bytes"));
/// assert_eq!(hw3::cli::read_text_bounded(&path, 2000).unwrap().len(), 2000);
/// std::fs::remove_file(&path).unwrap();
/// ```
pub fn read_text_bounded(path: &Path, limit: u64) -> Result<String, ReadError> {
    use std::io::Read as _;
    let io = |source| ReadError::Io { path: path.to_path_buf(), source };
    let (file, _) = crate::fsio::open_regular(path).map_err(|e| match e {
        crate::fsio::OpenError::Io(source) => io(source),
        crate::fsio::OpenError::NotAFile(kind) => ReadError::NotAFile { path: path.to_path_buf(), kind },
    })?;
    let mut bytes = Vec::new();
    file.take(limit + 1).read_to_end(&mut bytes).map_err(io)?;
    if bytes.len() as u64 > limit {
        return Err(ReadError::TooLong { path: path.to_path_buf(), limit });
    }
    String::from_utf8(bytes).map_err(|e| ReadError::NotUtf8 { path: path.to_path_buf(), source: e.utf8_error() })
}

/// Why a Radiance `.hdr` file given to `--env` was refused before decoding ([`check_hdr_file`]):
/// which file, and what is wrong with it.
#[derive(Debug, thiserror::Error)]
pub enum HdrFileError {
    /// The file cannot be opened, or its metadata read.
    #[error("--env: cannot read {}: {}", shown(.path), io_reason(.source))]
    Unreadable {
        /// The file.
        path: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// The path is not a regular file (a folder, a named pipe, a device), refused before reading.
    #[error("--env: {} is {kind}, not a regular file", shown(.path))]
    NotAFile {
        /// The path.
        path: PathBuf,
        /// What it is ([`crate::fsio::kind_of`]).
        kind: &'static str,
    },
    /// The file is larger than [`MAP_FILE_BYTES`].
    #[error("--env: {} has {bytes} bytes, over the limit of {limit}", shown(.path))]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// Its size in bytes.
        bytes: u64,
        /// [`MAP_FILE_BYTES`].
        limit: u64,
    },
    /// The file does not start with `#?RADIANCE`.
    #[error("--env: {} is not a Radiance .hdr file (it does not start with #?RADIANCE)", shown(.path))]
    NotRadiance {
        /// The file.
        path: PathBuf,
    },
    /// The resolution line cannot be read.
    #[error("--env: {} has an unreadable resolution line `{}`", shown(.path), quote(.line))]
    Resolution {
        /// The file.
        path: PathBuf,
        /// The line as read.
        line: String,
    },
    /// Another fault of the header (its `FORMAT`, its length, a read error).
    #[error("--env: {}: {source}", shown(.path))]
    Header {
        /// The file.
        path: PathBuf,
        /// The header reader's error.
        source: RadianceError,
    },
    /// The map is smaller than [`MAP_MIN_SIDES`].
    #[error(
        "--env: {} is {width}×{height}; a map needs at least {}×{} texels for the estimators to agree",
        shown(.path),
        .min.0,
        .min.1
    )]
    TooSmall {
        /// The file.
        path: PathBuf,
        /// The width its header declares.
        width: u64,
        /// The height its header declares.
        height: u64,
        /// [`MAP_MIN_SIDES`].
        min: (u64, u64),
    },
    /// The map has more texels than [`MAP_TEXELS`] allows (the limit's name says the file and
    /// its resolution).
    #[error(transparent)]
    Texels(LimitError),
}

/// Checks a Radiance `.hdr` file before it is decoded: its size in bytes, its header (read by the
/// decoder's own header reader: signature, `FORMAT`, resolution line), and the resolution it
/// declares, against [`MAP_TEXELS`] and [`MAP_MIN_SIDES`].
///
/// # Errors
/// A [`HdrFileError`] naming the file and what is wrong: [`HdrFileError::Unreadable`],
/// [`HdrFileError::NotAFile`], [`HdrFileError::TooLarge`] (bytes), [`HdrFileError::NotRadiance`],
/// [`HdrFileError::Resolution`], [`HdrFileError::Header`], [`HdrFileError::TooSmall`] or
/// [`HdrFileError::Texels`].
///
/// # Examples
/// ```
/// use hw3::cli::{HdrFileError, check_hdr_file};
/// let path = std::env::temp_dir().join(format!("hw3-cli-doc-{}.hdr", std::process::id()));
/// std::fs::write(&path, b"\x89PNG\r\n\x1a\n").unwrap();
/// let error = check_hdr_file(&path, false).unwrap_err();
/// assert!(matches!(error, HdrFileError::NotRadiance { .. }));
/// assert!(error.to_string().contains("not a Radiance"));
/// std::fs::remove_file(&path).unwrap();
/// ```
pub fn check_hdr_file(path: &Path, allow_large: bool) -> Result<(), HdrFileError> {
    use std::io::Read as _;
    let unreadable = |source| HdrFileError::Unreadable { path: path.to_path_buf(), source };
    let (file, meta) = crate::fsio::open_regular(path).map_err(|e| match e {
        crate::fsio::OpenError::Io(source) => unreadable(source),
        crate::fsio::OpenError::NotAFile(kind) => HdrFileError::NotAFile { path: path.to_path_buf(), kind },
    })?;
    if meta.len() > MAP_FILE_BYTES {
        return Err(HdrFileError::TooLarge { path: path.to_path_buf(), bytes: meta.len(), limit: MAP_FILE_BYTES });
    }
    // The decoder's own header reader, on at most 64 KiB: what passes here is what it will read.
    let mut reader = std::io::BufReader::new(file.take(64 * 1024));
    let (width, height) = crate::envmap::radiance::read_header(&mut reader).map_err(|e| match e {
        RadianceError::Signature => HdrFileError::NotRadiance { path: path.to_path_buf() },
        RadianceError::Resolution(line) => HdrFileError::Resolution { path: path.to_path_buf(), line },
        source => HdrFileError::Header { path: path.to_path_buf(), source },
    })?;
    let (width, height) = (u64::from(width), u64::from(height));
    if width < MAP_MIN_SIDES.0 || height < MAP_MIN_SIDES.1 {
        return Err(HdrFileError::TooSmall { path: path.to_path_buf(), width, height, min: MAP_MIN_SIDES });
    }
    MAP_TEXELS
        .check(&format!("--env: {}: texels ({width}×{height})", shown(path)), width.saturating_mul(height), allow_large)
        .map_err(HdrFileError::Texels)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn limits_name_the_flag_that_lifts_them() {
        let message = RENDER_SAMPLES.check("--spp", RENDER_SAMPLES.max + 1, false).unwrap_err().to_string();
        assert!(message.contains("--allow-large"), "{message}");
        let over = RENDER_SAMPLES.check("--spp", u64::MAX, true).unwrap_err();
        assert!(matches!(over, LimitError::TooLarge { value: u64::MAX, .. }));
        assert!(!over.to_string().contains("pass --allow-large"));
        let under = PROBE_SIZE.check("--size", 1, false).unwrap_err();
        assert_eq!(under, LimitError::TooSmall { name: "--size".into(), value: 1, min: 16 });
        assert_eq!(under.to_string(), "--size must be at least 16, got 1");
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
