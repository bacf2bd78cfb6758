//! Why an experiment could not run.

use super::radiosity::RadiosityError;
use crate::geometry::InputError;
use crate::render::photon::PhotonError;

/// Why an experiment could not run.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::{error::ExperimentError, radiosity::RadiosityError};
/// let error: ExperimentError = RadiosityError::NoPatches.into();
/// assert_eq!(error.to_string(), "the scene has no diffuse or emitting quad to mesh");
/// ```
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ExperimentError {
    /// The radiosity system could not be built.
    #[error(transparent)]
    Radiosity(#[from] RadiosityError),
    /// Photon tracing or a photon-map estimate failed.
    #[error(transparent)]
    Photon(#[from] PhotonError),
    /// A scene failed validation (never for the built-in scenes).
    #[error(transparent)]
    Scene(#[from] InputError),
    /// A figure could not be rendered or encoded.
    #[error("rendering a figure failed: {0}")]
    Render(String),
    /// Committed data (a CSV under `docs/data/`) is malformed.
    #[error("committed data: {0}")]
    Data(String),
    /// A table row or column id that [`EFFECTS`](crate::q5_effect_tables::EFFECTS) or
    /// [`ALGORITHMS`](crate::q5_effect_tables::ALGORITHMS) does not list.
    #[error("no effect or method with id {0:?}")]
    UnknownId(&'static str),
}
