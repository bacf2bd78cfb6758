//! How grainy a render is: the RMS noise of one image in display levels, measured from two
//! renders that differ only in their random seed.
//!
//! Two independent estimates `a = I + n₁`, `b = I + n₂` of the same image `I` with noise of equal
//! spread differ by `n₁ − n₂`, whose RMS is `√2` times the noise of either, so
//! `rms(a − b) / √2` is the noise a reader sees at 100 % zoom, with no reference image needed
//! (bias, such as Whitted's missing indirect light, is not noise and does not show in it). The
//! figures choose their samples per pixel by it.

use super::scene::Scene;
use super::{RenderError, Settings, render};

/// The RMS noise of one render of `scene` with `settings`, in display levels (0 … 255 per
/// channel, the bytes of the PNG): the RMS difference between the renders with seeds
/// `settings.seed` and `settings.seed + 1`, over `√2`. Falls as `1/√spp` where the estimator is
/// unbiased and the 8-bit rounding (about 0.3 levels) is below it.
///
/// # Errors
/// [`RenderError`] when the settings are out of range ([`render`]).
///
/// # Examples
/// ```
/// use hw3::render::{Settings, analysis::analyze, catalogue, noise::noise_level};
/// let scene = catalogue::by_name("caustic").unwrap();
/// let at = |spp| noise_level(&scene, &Settings::whitted(40, 30, spp, analyze(&scene).plan)).unwrap();
/// let (coarse, fine) = (at(1), at(16));
/// assert!(fine < coarse / 2.0, "16× the samples, about a quarter of the noise: {coarse} → {fine}");
/// ```
pub fn noise_level(scene: &Scene, settings: &Settings) -> Result<f64, RenderError> {
    let draw = |seed| -> Result<crate::plot::RgbImage, RenderError> {
        Ok(render(scene, &Settings { seed, ..*settings }, &|_| {})?.to_rgb8())
    };
    let (a, b) = (draw(settings.seed)?, draw(settings.seed.wrapping_add(1))?);
    Ok(noise_between(&a, &b))
}

/// `rms(a − b) / √2` in display levels: the noise of one of two renders of the same image that
/// differ only in their seed (see the module docs).
///
/// # Panics
/// If the images differ in size.
#[must_use]
pub fn noise_between(a: &crate::plot::RgbImage, b: &crate::plot::RgbImage) -> f64 {
    crate::plot::rms_difference(a, b) / std::f64::consts::SQRT_2
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::{analysis::analyze, catalogue};

    /// The numbers the figures' samples were chosen by (not a check: slow, run by hand with
    /// `cargo test --release --test unit figure_scene_noise -- --ignored --nocapture`): each figure
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
}
