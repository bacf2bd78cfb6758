#![doc = include_str!(concat!(env!("OUT_DIR"), "/q1_hard_scenes.md"))]

mod accuracy;
mod chart;
mod clutter;
mod figures;
mod fog;
mod metric;
mod mirrors;
mod motion;

pub use clutter::{CLUTTER_COUNTS, CLUTTER_SEEDS, ClutterRow, block_probability, clutter_row, gap_fraction};
pub use figures::{Budget, RENDER_SPP, figure_jobs, figures, render_jobs, renders};
pub use fog::{
    FOG_DISTANCES, FOG_SIGMAS, FogRow, airlight_rows, airlight_traced, fog_row, transmittance, visual_range,
};
pub use mirrors::{
    DIVERGENCE_TRIALS, MIRROR_SPP, MIRROR_STEPS, MirrorDivergence, mirror_divergence, mirror_sensitivity,
    reflection_turn,
};
pub use motion::{
    MOTION_REFERENCE_SPP, MOTION_SPP, MotionChange, MotionNoise, NOISE_TARGET, focal_length_pixels, motion_change,
    motion_noise, pixels_per_frame,
};

use crate::answers::Answers;

/// Median growth of a ray pair's separation per bounce between the four mirror spheres
/// ([`mirror_divergence`] at [`DIVERGENCE_TRIALS`]), as [`answers`] prints it. Measured, not
/// computed by `answers` (which renders and traces nothing); pinned by
/// `tests::printed_measurements_are_what_the_code_measures`.
const MIRROR_GROWTH: &str = "2.55";
/// Lowest and highest ratio of the mirror to the diffuse image sensitivity over [`MIRROR_STEPS`]
/// ([`mirror_sensitivity`]), cut to one decimal (1.155 and 1.690 print 1.1 and 1.6); pinned by the
/// same test.
const SENSITIVITY_RATIOS: (&str, &str) = ("1.1", "1.6");
/// The clutter rows' gap fractions are within this many standard errors of the exact law
/// ([`clutter_row`]); pinned by the same test.
const CLUTTER_STANDARD_ERRORS: f64 = 2.0;

/// The Q1 answers: the four hard scenes and what makes each hard, with the law each obeys.
/// Cheap (no rendering); the measured tables are in the chapter and in `hw3 figures`.
///
/// The sphere counts, fog densities, tolerances, image size and the ball's image speed are
/// computed from the code that measures them; the three numbers only a measurement gives are
/// constants pinned by a test.
///
/// # Panics
/// Never: the built-in moving-ball scene is valid.
///
/// # Examples
/// ```
/// let answers = hw3::q1_hard_scenes::answers();
/// assert_eq!(answers.question, "q1");
/// assert!(answers.text.contains("e^(−σ_t d)"));
/// ```
#[must_use]
pub fn answers() -> Answers {
    let [first_count, .., last_count] = CLUTTER_COUNTS;
    let sigmas = FOG_SIGMAS.map(|s| s.to_string()).join(" / ");
    let ranges = FOG_SIGMAS.map(|s| format!("{:.1}", visual_range(s))).join(" / ");
    let (coarse, fine) = fog::AIRLIGHT_TOLERANCES;
    let (width, height) = metric::METRIC_SIZE;
    let (low, high) = SENSITIVITY_RATIOS;
    let pixels_per_frame = motion::ball_pixels_per_frame().expect("the built-in moving-ball scene is valid");
    let text = format!(
        "(a) clutter: the gap fraction of a random forest falls as (1−p)^N ≈ e^(−nπa²Z) and the depth complexity grows as nπa²Z; measured within {CLUTTER_STANDARD_ERRORS} standard errors over N = {first_count}…{last_count} (table q1_clutter_table).\n\
         (b) fog: contrast to an object falls as e^(−σ_t d) (the renderer reproduces it to rounding, below {:e}), visual range ln 50/σ_t = {ranges} units for σ_t = {sigmas}, and the lamp's glow adds airlight that matches Sun et al.'s closed form ({coarse:e} at {} steps, < {fine:e} at 4096).\n\
         (c) mirrors: nearby rays separate ×{MIRROR_GROWTH} per bounce between four mirror spheres (an independent implementation: ×2.45) but only linearly between flat mirrors; over the pixels that see the spheres, the image changes {low}–{high}× faster per unit camera move than the same spheres made diffuse (Whitted, {width}×{height}).\n\
         (d) change over time: the moving ball shifts {pixels_per_frame:.1} px per frame (above the 0.5 px/frame limit for a 1-px feature), and its motion blur needs more samples per pixel than the still scene for the same noise (table q1_motion_table).",
        fog::ROUNDING_LEVEL,
        crate::render::integrator::IN_SCATTER_STEPS,
    );
    Answers { question: "q1", title: "Four scenes that are hard to render, and why (measured)", text }
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[unit_test]
    fn chapter_includes_every_generated_table() {
        let chapter = include_str!("../docs/q1_hard_scenes.md");
        for table in [
            "q1_clutter_table.md",
            "q1_fog_table.md",
            "q1_airlight_table.md",
            "q1_mirror_table.md",
            "q1_mirror_divergence_table.md",
            "q1_motion_table.md",
        ] {
            assert!(chapter.contains(&format!("{{{{include:figures/{table}}}}}")), "{table}");
        }
    }

    /// The numbers [`answers`] prints from measurements are what the measurements give today.
    #[unit_test]
    fn printed_measurements_are_what_the_code_measures() {
        let divergence = mirror_divergence(DIVERGENCE_TRIALS).unwrap();
        assert_eq!(format!("{:.2}", divergence.median_factor), MIRROR_GROWTH);
        let ratios: Vec<f64> =
            mirror_sensitivity(&MIRROR_STEPS, MIRROR_SPP).unwrap().iter().map(|&(_, m, d)| m / d).collect();
        let cut = |r: f64| format!("{:.1}", (r * 10.0).floor() / 10.0);
        let (low, high) = ratios.iter().fold((f64::INFINITY, 0.0f64), |(l, h), &r| (l.min(r), h.max(r)));
        assert_eq!((cut(low).as_str(), cut(high).as_str()), SENSITIVITY_RATIOS);
        for n in CLUTTER_COUNTS {
            let row = clutter_row(n).unwrap();
            let z = (row.gap_fraction - row.gap_exact) / row.gap_standard_error;
            assert!(z.abs() < CLUTTER_STANDARD_ERRORS, "N = {n}: z = {z:.2}");
        }
        for row in fog::fog_rows().unwrap() {
            assert!((row.transmittance / row.law - 1.0).abs() < fog::ROUNDING_LEVEL, "{row:?}");
        }
        let text = answers().text;
        assert!(text.contains(&format!("{:.1} px per frame", motion_change().unwrap().pixels_per_frame)));
    }
}
