//! Environment maps: radiance arriving from infinitely far away, stored as an image.
//!
//! Shared by the homework's light-probe question (Q4, in `hw3`, which adds analytic maps,
//! irradiance estimators and the accuracy study) and the renderer
//! ([`crate::render::environment`], which lights scenes with a map).
//!
//! - [`format`](mod@format): how a probe image encodes directions ([`ProbeFormat`]: mirror ball, perspective
//!   ball, angular map, latitude-longitude), the Jacobian `dω/dA` and exact texel solid angles.
//! - [`probe`]: a [`Probe`], an image in one format with the direction, solid angle and radiance
//!   of every texel, built from a function, a radiance buffer or a Radiance `.hdr` file.
//! - [`distribution`]: [`MapDistribution`], importance sampling of a probe's directions in
//!   proportion to [`luminance`] × solid angle, with its exact solid-angle pdf.
//! - `filter`: [`Probe::radiance_bilinear`], the bilinear lookup that pictures of a map use.
//! - [`builtin`]: the two CC0 maps compiled into the binary ([`BuiltinMap`]), so that nothing
//!   is read from the source tree at run time.

pub mod builtin;
pub mod distribution;
mod filter;
pub mod format;
pub mod probe;
pub mod radiance;

pub use builtin::BuiltinMap;
pub use distribution::{LUMINANCE_WEIGHTS, MapDistribution, MapSample, luminance};
pub use format::ProbeFormat;
pub use probe::{Probe, ProbeError, Texel, horizontal_camera};
