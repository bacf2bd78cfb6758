//! The small renders the mirror and motion metrics are measured on: Whitted, 64×48 pixels.

use crate::geometry::InputError;
use crate::render::analysis::analyze;
use crate::render::scene::Scene;
use crate::render::{Image, Settings, render};

/// Image size of the mirror and motion measurements.
pub(super) const METRIC_SIZE: (u32, u32) = (64, 48);

/// Whitted render of `scene` at the metric size with its own plan.
pub(super) fn render_metric(scene: &Scene, spp: u32, seed: u64) -> Result<Image, InputError> {
    let (width, height) = METRIC_SIZE;
    let settings = Settings { seed, ..Settings::whitted(width, height, spp, analyze(scene).plan) };
    // The sample count comes from the public measurements' callers, so a count the renderer
    // refuses (0, or past its work bound) is an error, not a panic.
    // The size is fixed, so the sample count is the only setting the renderer can refuse.
    render(scene, &settings, &|_| {}).map_err(|_| InputError::OutOfRange {
        name: "samples per pixel",
        value: spp.to_string(),
        expected: if spp == 0 { "at least 1" } else { "within the renderer's work bound" },
    })
}

/// Pins `text` as the snapshot `name` in the crate's `snapshots/` folder.
#[cfg(test)]
pub(super) fn snapshot(name: &str, text: &str) {
    crate::testing::insta_settings().bind(|| insta::assert_snapshot!(name, text));
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::catalogue;
    use std::fmt::Write as _;

    #[test]
    fn render_thumbnails() {
        let mut text = String::new();
        for (name, scene) in [
            ("mirrors", catalogue::mirror_spheres(true).unwrap()),
            ("fog", catalogue::fog_street(0.08).unwrap()),
            ("motion", catalogue::moving_ball(2.0).unwrap()),
            ("clutter", catalogue::clutter_forest(300, 1).unwrap()),
        ] {
            let image = render_metric(&scene, 2, 1).unwrap();
            let _ = writeln!(text, "{name}:\n{}", image.thumbnail_text(8, 6));
        }
        snapshot("q1_render_thumbnails", &text);
    }
}
