//! The numerical core of `hw3`, the layer every other crate of the workspace builds on: the two
//! floating-point precisions the notes compare ([`real`]), rays, spheres and the stable
//! ray/sphere solver ([`geometry`]), seeded and portable random numbers ([`rng`]), sample
//! statistics ([`stats`]), deterministic figures, charts and tables ([`plot`]), and files written
//! so that a reader never sees half of one ([`fsio`]).
//!
//! It depends on no other crate of the workspace: the renderer (`hw3-render`) and the homework's
//! questions (`hw3`) sit above it, and Cargo refuses an import the other way.

#![warn(missing_docs)]
#![allow(
    clippy::neg_cmp_op_on_partial_ord,
    reason = "`!(x >= 0)` is how the numerics say 'negative or NaN': NaN must fail every test"
)]

pub mod fsio;
pub mod geometry;
pub mod plot;
pub mod real;
pub mod rng;
pub mod stats;

/// The workspace's snapshot folder (`snapshots/` at the top of the repository), where every
/// crate's snapshot tests keep their snapshots, named by the snapshot's name alone.
#[doc(hidden)]
pub const SNAPSHOTS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../snapshots");
