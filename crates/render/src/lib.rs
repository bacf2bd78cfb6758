//! The renderer of `hw3` and what it is built from: the SAH kd-tree over spheres ([`kdtree`]),
//! environment maps and mirror-ball light probes ([`envmap`]), and a small physically based
//! renderer ([`render`]: Whitted and path tracing, fog, motion blur, photon maps, and passes
//! planned from the light paths a scene can carry).
//!
//! It builds on `hw3-core` and never on the homework's questions (`hw3`), which sit above it.

#![warn(missing_docs)]
#![allow(
    clippy::neg_cmp_op_on_partial_ord,
    reason = "`!(x >= 0)` is how the numerics say 'negative or NaN': NaN must fail every test"
)]

pub mod envmap;
pub mod kdtree;
pub mod render;

/// What the unit tests share: snapshot settings.
#[cfg(test)]
mod testing {
    /// insta settings of the workspace's snapshot tests: the top-level `snapshots/` folder,
    /// snapshots named by their name alone.
    pub(crate) fn insta_settings() -> insta::Settings {
        let mut settings = insta::Settings::clone_current();
        settings.set_snapshot_path(hw3_core::SNAPSHOTS);
        settings.set_prepend_module_to_snapshot(false);
        settings
    }
}
