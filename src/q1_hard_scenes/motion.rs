//! Q1(d) change over time: a moving ball changes the image every frame, and its motion blur
//! needs more samples per pixel than the still scene for the same noise.

use super::metric::{METRIC_SIZE, render_metric};
use crate::geometry::InputError;
use crate::plot::markdown_table;
use crate::render::Image;
use crate::render::catalogue;
use glam::DVec3;
use std::fmt::Write as _;

/// The focal length of a pinhole camera in pixels, `(H/2)/tan(fov/2)`, for an image `height`
/// pixels high and a vertical field of view of `vfov_degrees`: half the image over the tangent of
/// half the angle.
///
/// # Examples
/// ```
/// use hw3::q1_hard_scenes::focal_length_pixels;
/// // 480 pixels over 60°: 240/tan 30° = 415.7 px.
/// assert!((focal_length_pixels(480.0, 60.0) - 240.0 * 3f64.sqrt()).abs() < 1e-9);
/// ```
#[must_use]
pub fn focal_length_pixels(height: f64, vfov_degrees: f64) -> f64 {
    height / 2.0 / (vfov_degrees.to_radians() / 2.0).tan()
}

/// The image shift, in pixels per frame, of an object that moves `movement` units per frame across
/// the view at `depth` units from a camera of focal length `focal_pixels`
/// ([`focal_length_pixels`]): the pinhole projection `x f / z`.
///
/// # Examples
/// ```
/// use hw3::q1_hard_scenes::{focal_length_pixels, pixels_per_frame};
/// // 2 units/s at 24 frames/s, 5 units away, 480 px over 60°: 6.9 px per frame.
/// let shift = pixels_per_frame(2.0 / 24.0, 5.0, focal_length_pixels(480.0, 60.0));
/// assert!((shift - 6.928_203).abs() < 1e-6);
/// ```
#[must_use]
pub fn pixels_per_frame(movement: f64, depth: f64, focal_pixels: f64) -> f64 {
    movement * focal_pixels / depth
}

/// Speed of the moving ball (units per unit time) and number of instantaneous frames.
pub(super) const MOTION_SPEED: f64 = 2.0;
const MOTION_FRAMES: usize = 10;
/// Samples per pixel of the noise measurement and of its reference.
///
/// # Examples
/// ```
/// use hw3::q1_hard_scenes::MOTION_SPP;
/// // Doubling sample counts: evenly spaced on the log-log chart the slope is fitted on.
/// assert!(MOTION_SPP.windows(2).all(|w| w[1] == 2 * w[0]));
/// ```
pub const MOTION_SPP: [u32; 6] = [1, 2, 4, 8, 16, 32];
/// Samples per pixel of the noise measurement's reference (rendered from another seed).
///
/// # Examples
/// ```
/// use hw3::q1_hard_scenes::{MOTION_REFERENCE_SPP, MOTION_SPP};
/// // Eight times the largest measured count: its own noise adds 1/8 to the last RMSE², which the
/// // fit of `motion_noise` takes out.
/// assert_eq!(MOTION_REFERENCE_SPP, 8 * MOTION_SPP[MOTION_SPP.len() - 1]);
/// ```
pub const MOTION_REFERENCE_SPP: u32 = 256;
/// The noise level for which the needed spp is reported (RMS luminance error).
///
/// # Examples
/// ```
/// use hw3::q1_hard_scenes::{MotionNoise, NOISE_TARGET};
/// // A noise constant of 0.05 needs (0.05/0.005)² = 100 samples per pixel for this target.
/// assert_eq!(MotionNoise::spp_needed(0.05, NOISE_TARGET), 100.0);
/// ```
pub const NOISE_TARGET: f64 = 0.005;

/// Image change between consecutive instantaneous frames of the moving ball.
///
/// # Examples
/// ```
/// use hw3::q1_hard_scenes::{MotionChange, motion_change};
/// let change: MotionChange = motion_change().unwrap();
/// // Every step between frames changes some pixels by more than 0.05.
/// assert!(change.changed_fraction.iter().all(|&f| f > 0.0));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct MotionChange {
    /// Mean absolute luminance change per frame (time step `1/MOTION_FRAMES`).
    pub mean_change: Vec<f64>,
    /// Fraction of pixels whose luminance changes by more than 0.05 per frame.
    pub changed_fraction: Vec<f64>,
    /// The ball's image speed, in pixels per frame, at the image centre's depth.
    pub pixels_per_frame: f64,
}

/// Renders instantaneous frames `t = k/10`, `k = 0…10`, and measures the change per step.
///
/// # Errors
/// [`InputError`] never for the built-in numbers.
///
/// # Examples
/// ```
/// let change = hw3::q1_hard_scenes::motion_change().unwrap();
/// assert_eq!(change.mean_change.len(), 10);
/// assert!(change.mean_change.iter().all(|&c| c > 0.0) && change.pixels_per_frame > 0.5);
/// ```
pub fn motion_change() -> Result<MotionChange, InputError> {
    let frames: Vec<Image> = (0..=MOTION_FRAMES)
        .map(|k| {
            let t = k as f64 / MOTION_FRAMES as f64;
            let scene = catalogue::moving_ball_with_shutter(MOTION_SPEED, (t, t))?;
            render_metric(&scene, 1, 1)
        })
        .collect::<Result<_, _>>()?;
    let mut mean_change = Vec::new();
    let mut changed_fraction = Vec::new();
    for pair in frames.windows(2) {
        mean_change.push(pair[1].mean_abs_difference(&pair[0]));
        let (a, b) = (pair[0].luminance(), pair[1].luminance());
        let changed = a.iter().zip(&b).filter(|(x, y)| (*x - *y).abs() > 0.05).count();
        changed_fraction.push(changed as f64 / a.len() as f64);
    }
    Ok(MotionChange { mean_change, changed_fraction, pixels_per_frame: ball_pixels_per_frame()? })
}

/// The ball's image speed in pixels per frame at the metric size, at the depth of the image
/// centre: geometry only, no rendering.
pub(super) fn ball_pixels_per_frame() -> Result<f64, InputError> {
    let camera = catalogue::moving_ball(MOTION_SPEED)?.camera().to_owned();
    let depth = (DVec3::new(0.0, 0.5, -3.0) - camera.eye).length();
    let focal_pixels = focal_length_pixels(f64::from(METRIC_SIZE.1), camera.vfov_degrees);
    Ok(pixels_per_frame(MOTION_SPEED / MOTION_FRAMES as f64, depth, focal_pixels))
}

/// RMS error against a 256-spp reference (another seed) versus spp, for the moving and the
/// resting ball; the free log-log slope, the constant `c` of `RMSE² ≈ c² (1/spp + 1/256)` (the
/// second term is the reference's own noise), and from it the spp needed for [`NOISE_TARGET`].
///
/// # Examples
/// ```
/// use hw3::q1_hard_scenes::MotionNoise;
/// // A measurement as `motion_noise` returns it (numbers rounded from the chapter's table).
/// let noise = MotionNoise {
///     rows: vec![(1, 0.1, 0.05), (4, 0.05, 0.025)],
///     slope_moving: -0.5,
///     slope_resting: -0.5,
///     constant_moving: 0.1,
///     constant_resting: 0.05,
/// };
/// assert!(MotionNoise::spp_needed(noise.constant_moving, 0.01) > MotionNoise::spp_needed(noise.constant_resting, 0.01));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct MotionNoise {
    /// `(spp, RMSE moving, RMSE resting)`.
    pub rows: Vec<(u32, f64, f64)>,
    /// Fitted log-log slope for the moving ball (free fit).
    pub slope_moving: f64,
    /// Fitted log-log slope for the resting ball.
    pub slope_resting: f64,
    /// `c` for the moving ball.
    pub constant_moving: f64,
    /// `c` for the resting ball.
    pub constant_resting: f64,
}

impl MotionNoise {
    /// Samples per pixel needed for RMSE ≤ `target`: `(c / target)²`, rounded up.
    ///
    /// # Examples
    /// ```
    /// use hw3::q1_hard_scenes::MotionNoise;
    /// assert_eq!(MotionNoise::spp_needed(0.5, 0.125), 16.0);
    /// assert_eq!(MotionNoise::spp_needed(0.5, 0.2), 7.0); // 6.25, rounded up
    /// ```
    #[must_use]
    pub fn spp_needed(constant: f64, target: f64) -> f64 {
        (constant / target).powi(2).ceil()
    }
}

/// Measures [`MotionNoise`]: one row per sample count of `spp` (at least two, for the fitted
/// slope), against a `reference_spp` reference, for the moving and the resting ball. The chapter's
/// table is [`MOTION_SPP`] against [`MOTION_REFERENCE_SPP`] (two 256-spp references;
/// `motion::tests` pins it).
///
/// # Errors
/// [`InputError::OutOfRange`] unless `spp` holds at least two counts, increasing (the slope is
/// fitted to them), every count and `reference_spp` at least 1, found before any render; or for
/// a count the renderer refuses (past its work bound). Never for the built-in numbers.
///
/// # Examples
/// ```
/// use hw3::q1_hard_scenes::motion_noise;
/// assert!(motion_noise(&[4], 16).is_err() && motion_noise(&[0, 1], 16).is_err() && motion_noise(&[1, 2], 0).is_err());
/// // Three sample counts against a 16-spp reference: a fraction of the chapter's work.
/// let noise = motion_noise(&[1, 2, 4], 16).unwrap();
/// assert_eq!(noise.rows.iter().map(|r| r.0).collect::<Vec<_>>(), [1, 2, 4]);
/// // Motion blur is noise: the moving ball needs more samples for the same error.
/// assert!(noise.constant_moving > noise.constant_resting);
/// ```
pub fn motion_noise(spp: &[u32], reference_spp: u32) -> Result<MotionNoise, InputError> {
    if spp.len() < 2 || !spp.windows(2).all(|w| w[0] < w[1]) || spp[0] == 0 {
        return Err(InputError::OutOfRange {
            name: "samples per pixel",
            value: format!("{spp:?}"),
            expected: "at least two counts, increasing, from 1",
        });
    }
    if reference_spp == 0 {
        return Err(InputError::OutOfRange {
            name: "reference samples per pixel",
            value: "0".into(),
            expected: "at least 1",
        });
    }
    let curve = |speed: f64| -> Result<Vec<f64>, InputError> {
        let scene = catalogue::moving_ball(speed)?;
        let reference = render_metric(&scene, reference_spp, 1_000_003)?;
        spp.iter().map(|&n| Ok(render_metric(&scene, n, 1)?.rms_difference(&reference))).collect()
    };
    let (moving, resting) = (curve(MOTION_SPEED)?, curve(0.0)?);
    let fit = |errors: &[f64]| {
        let xs: Vec<f64> = spp.iter().map(|&s| f64::from(s).ln()).collect();
        let ys: Vec<f64> = errors.iter().map(|e| e.ln()).collect();
        let n = xs.len() as f64;
        let (mx, my) = (xs.iter().sum::<f64>() / n, ys.iter().sum::<f64>() / n);
        let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
        let sxx: f64 = xs.iter().map(|x| (x - mx).powi(2)).sum();
        // The reference has noise of its own: E[RMSE²] = c² (1/spp + 1/reference_spp), so c² is
        // the mean of RMSE² / (1/spp + 1/reference_spp).
        let c_squared = spp
            .iter()
            .zip(errors)
            .map(|(&n, e)| e * e / (1.0 / f64::from(n) + 1.0 / f64::from(reference_spp)))
            .sum::<f64>()
            / n;
        (sxy / sxx, c_squared.sqrt())
    };
    let ((slope_moving, constant_moving), (slope_resting, constant_resting)) = (fit(&moving), fit(&resting));
    Ok(MotionNoise {
        rows: spp.iter().zip(moving.iter().zip(&resting)).map(|(&s, (&m, &r))| (s, m, r)).collect(),
        slope_moving,
        slope_resting,
        constant_moving,
        constant_resting,
    })
}

pub(super) fn motion_tables(change: &MotionChange, noise: &MotionNoise) -> String {
    let changes = markdown_table(
        &["step", "mean abs change", "pixels changed > 0.05"],
        change
            .mean_change
            .iter()
            .zip(&change.changed_fraction)
            .enumerate()
            .map(|(k, (m, f))| [format!("{} → {}", k, k + 1), format!("{m:.4e}"), format!("{f:.4}")]),
    );
    let noise_rows = markdown_table(
        &["spp", "RMSE moving", "RMSE resting"],
        noise.rows.iter().map(|(spp, m, r)| [spp.to_string(), format!("{m:.4e}"), format!("{r:.4e}")]),
    );
    let mut text =
        format!("image speed of the ball: {:.3} px/frame\n\n{changes}\n{noise_rows}", change.pixels_per_frame);
    let _ = writeln!(
        text,
        "\nslope moving {:.3}, resting {:.3}; c moving {:.4e}, resting {:.4e}; spp for RMSE {NOISE_TARGET}: moving {}, resting {}",
        noise.slope_moving,
        noise.slope_resting,
        noise.constant_moving,
        noise.constant_resting,
        MotionNoise::spp_needed(noise.constant_moving, NOISE_TARGET),
        MotionNoise::spp_needed(noise.constant_resting, NOISE_TARGET)
    );
    text
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::q1_hard_scenes::metric::snapshot;

    /// The projection against the numbers it has always given (the checker's seeds 0 and 1, as
    /// worked by `tests/answers/fixtures/keys.py`), and against the moving ball's own camera.
    #[test]
    fn image_shift_is_the_numbers_it_was() {
        let shift = pixels_per_frame(2.0 / 24.0, 5.0, focal_length_pixels(480.0, 60.0));
        assert!((shift - 6.928_203_230_275_509).abs() < 1e-12);
        let shift = pixels_per_frame(2.0 / 24.0, 10.0, focal_length_pixels(1080.0, 90.0));
        assert!((shift - 4.5).abs() < 1e-12);
        let camera = catalogue::moving_ball(MOTION_SPEED).unwrap().camera().to_owned();
        let depth = (DVec3::new(0.0, 0.5, -3.0) - camera.eye).length();
        let half_height = f64::from(METRIC_SIZE.1) / 2.0;
        let by_hand =
            MOTION_SPEED / MOTION_FRAMES as f64 * half_height / (camera.vfov_degrees.to_radians() / 2.0).tan() / depth;
        assert!((ball_pixels_per_frame().unwrap() / by_hand - 1.0).abs() < 1e-12);
    }

    #[test]
    fn motion_changes_every_frame_and_blur_costs_samples() {
        let change = motion_change().unwrap();
        assert!(change.mean_change.iter().all(|&c| c > 0.0));
        assert!(change.pixels_per_frame > 0.5, "faster than the 0.5 px/frame limit");
        let noise = motion_noise(&MOTION_SPP, MOTION_REFERENCE_SPP).unwrap();
        for slope in [noise.slope_moving, noise.slope_resting] {
            assert!((slope + 0.5).abs() < 0.05, "slope {slope}");
        }
        assert!(noise.constant_moving > noise.constant_resting);
        snapshot("q1_motion_metrics", &motion_tables(&change, &noise));
    }

    #[test]
    fn still_frames_do_not_change() {
        let frames: Vec<Image> = [0.0, 0.5]
            .iter()
            .map(|&t| render_metric(&catalogue::moving_ball_with_shutter(0.0, (t, t)).unwrap(), 1, 1).unwrap())
            .collect();
        assert_eq!(frames[0], frames[1]);
    }
}
