//! Why an experiment could not run, and why a table of `hw3 effect-tables` could not be made.

use super::radiosity::RadiosityError;
use crate::data::DataError;
use crate::geometry::InputError;
use crate::render::RenderError;
use crate::render::analysis::grammar::GrammarError;
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
    /// A render was refused.
    #[error("rendering a figure failed: {0}")]
    Render(#[from] RenderError),
    /// A render of the mean of two halves was asked for a sample count that does not split into
    /// two equal halves (odd, or zero).
    #[error("rendering a figure failed: {0} samples per pixel do not split into two equal halves")]
    UnevenSamples(u32),
    /// Committed data (a CSV under `docs/data/`) is malformed.
    #[error("committed data: {0}")]
    Data(#[from] DataError),
    /// A table row or column id that [`EFFECTS`](crate::q5_effect_tables::EFFECTS) or
    /// [`ALGORITHMS`](crate::q5_effect_tables::ALGORITHMS) does not list.
    #[error("no effect or method with id {0:?}")]
    UnknownId(&'static str),
    /// The measured table has no cell for an effect and a method a figure shows.
    #[error("the measured table has no such cell")]
    MissingCell {
        /// The effect's id.
        effect: &'static str,
        /// The method's id.
        algorithm: &'static str,
    },
}

/// Why a table of `hw3 effect-tables` could not be made.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::error::TablesError;
/// use hw3::render::analysis::grammar::GrammarError;
/// let error: TablesError = GrammarError::TooManyStates(50_000).into();
/// assert_eq!(error.to_string(), "comparing these classes needs more than 50000 automaton states; write the class more simply");
/// ```
#[derive(Debug, thiserror::Error)]
pub enum TablesError {
    /// The grammar's table could not be built (a search past its state limit; never for the
    /// built-in tables).
    #[error(transparent)]
    Grammar(#[from] GrammarError),
    /// The JSON output could not be serialised.
    #[error(transparent)]
    Json(#[from] serde_json::Error),
}
