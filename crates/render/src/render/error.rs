//! Why a render was refused: the limits a render's settings must keep, and one error type for
//! the renderer's entry points.

use super::photon::PhotonError;
use hw3_core::geometry::InputError;

/// Largest accepted image side, in pixels.
pub const MAX_SIDE: u32 = 8192;
/// Largest accepted pixel count (a 4096² image).
pub const MAX_PIXELS: u64 = 1 << 24;
/// Largest accepted number of samples per pixel.
pub const MAX_SPP: u32 = 1 << 16;

/// Why a render was refused. Nothing is rendered or written when one is returned.
///
/// # Examples
/// ```
/// use hw3_render::render::{RenderError, catalogue};
/// let err = catalogue::by_name("nope").unwrap_err();
/// assert!(matches!(err, RenderError::UnknownScene { .. }) && err.to_string().contains("mirrors"));
/// ```
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RenderError {
    /// The scene or a camera setting is invalid.
    #[error(transparent)]
    Input(#[from] InputError),
    /// The image is empty or too large.
    #[error("image size {width}×{height} refused: each side must be 1…{MAX_SIDE} and the pixel count ≤ {MAX_PIXELS}")]
    ImageSize {
        /// Requested width.
        width: u32,
        /// Requested height.
        height: u32,
    },
    /// Zero or too many samples per pixel.
    #[error("samples per pixel must be 1…{MAX_SPP}, got {0}")]
    SamplesPerPixel(u32),
    /// A scene's environment map could not be read (a missing file, a NaN texel, …).
    #[error("environment map: {0}")]
    Environment(String),
    /// Caustic settings out of range (photon count).
    #[error("caustic pass: {0}")]
    Caustics(#[from] PhotonError),
    /// A scene name that is not built in.
    #[error("unknown scene `{name}`; known: {known}")]
    UnknownScene {
        /// The name given.
        name: String,
        /// The built-in names, comma-separated.
        known: String,
    },
}
