//! Colour: the renderer's linear RGB and the one scalar it is judged by, the relative luminance
//! `Y` (what the renderer compares images by and weighs lights' powers by; linear, no transfer
//! curve). Defined once, beside the environment map's sampling distribution that also follows it
//! ([`crate::envmap`] sits below the renderer, so the renderer names its copy).

pub use crate::envmap::{LUMINANCE_WEIGHTS, luminance};
