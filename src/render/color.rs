//! Colour: the renderer's linear RGB and the one scalar it is judged by.

use glam::DVec3;

/// Rec. 709 / sRGB primaries' luminance weights `(0.2126, 0.7152, 0.0722)` (ITU-R BT.709-6,
/// item 3.2): the relative luminance `Y` of a linear RGB colour.
pub const LUMINANCE_WEIGHTS: DVec3 = DVec3::new(0.2126, 0.7152, 0.0722);

/// The relative luminance `Y` of linear RGB `rgb` (the dot product with [`LUMINANCE_WEIGHTS`]):
/// what the renderer compares images by and weighs lights' powers by. Linear: no transfer curve.
///
/// # Examples
/// ```
/// use glam::DVec3;
/// use hw3::render::color::luminance;
/// assert!((luminance(DVec3::ONE) - 1.0).abs() < 1e-15); // the weights sum to 1
/// assert_eq!(luminance(DVec3::Y), 0.7152);
/// ```
#[must_use]
pub fn luminance(rgb: DVec3) -> f64 {
    rgb.dot(LUMINANCE_WEIGHTS)
}
