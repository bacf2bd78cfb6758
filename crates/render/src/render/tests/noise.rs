//! Tests of `render::noise`.

use crate::render::Settings;
use crate::render::noise::*;
use crate::render::{analysis::analyze, catalogue};

/// The numbers the figures' samples were chosen by (not a check: slow, run by hand with
/// `cargo test --release -p hw3-render --lib figure_scene_noise -- --ignored --nocapture`): each figure
/// scene's noise at half its figure's width and height (the noise per pixel does not depend
/// on the image size) for the given samples per pixel, Whitted with the scene's plan.
#[test]
#[ignore = "slow: prints the figures' noise for choosing their samples"]
fn figure_scene_noise() {
    let sizes = [
        ("clutter", (320, 240)),
        ("clear-street", (160, 120)),
        ("fog", (160, 120)),
        ("mirrors", (160, 120)),
        ("diffuse-spheres", (160, 120)),
        ("motion", (160, 120)),
        ("still", (160, 120)),
        ("probe-lit", (320, 240)),
        ("fog-panel", (320, 240)),
        ("caustic", (160, 120)),
    ];
    let spps: Vec<u32> = std::env::var("HW3_NOISE_SPP")
        .map_or_else(|_| vec![16, 64], |v| v.split(',').map(|s| s.parse().unwrap()).collect());
    for (name, (width, height)) in sizes {
        let scene = catalogue::by_name(name).unwrap();
        let plan = analyze(&scene).plan;
        let line: Vec<String> = spps
            .iter()
            .map(|&spp| {
                let noise = noise_level(&scene, &Settings::whitted(width, height, spp, plan)).unwrap();
                format!("{spp} spp: {noise:.2}")
            })
            .collect();
        println!("{name:16} {}", line.join("   "));
    }
}
