//! Helpers shared by the integration tests.
#![allow(dead_code)]

/// insta settings: snapshots in the top-level `snapshots/`, named by the snapshot name alone.
pub fn insta_settings() -> insta::Settings {
    let mut settings = insta::Settings::clone_current();
    settings.set_snapshot_path(concat!(env!("CARGO_MANIFEST_DIR"), "/snapshots"));
    settings.set_prepend_module_to_snapshot(false);
    settings
}
