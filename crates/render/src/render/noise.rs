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
/// use hw3_render::render::{Settings, analysis::analyze, catalogue, noise::noise_level};
/// let scene = catalogue::by_name("caustic").unwrap();
/// let at = |spp| noise_level(&scene, &Settings::whitted(40, 30, spp, analyze(&scene).plan)).unwrap();
/// let (coarse, fine) = (at(1), at(16));
/// assert!(fine < coarse / 2.0, "16× the samples, about a quarter of the noise: {coarse} → {fine}");
/// ```
pub fn noise_level(scene: &Scene, settings: &Settings) -> Result<f64, RenderError> {
    let draw = |seed| -> Result<hw3_core::plot::RgbImage, RenderError> {
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
pub fn noise_between(a: &hw3_core::plot::RgbImage, b: &hw3_core::plot::RgbImage) -> f64 {
    hw3_core::plot::rms_difference(a, b) / std::f64::consts::SQRT_2
}
