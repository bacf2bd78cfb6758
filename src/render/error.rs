//! Why a render was refused: one error type for the renderer's entry points.

use super::photon::PhotonError;
use super::{MAX_PIXELS, MAX_SIDE, MAX_SPP};
use crate::geometry::InputError;

/// Why a render was refused. Nothing is rendered or written when one is returned.
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
