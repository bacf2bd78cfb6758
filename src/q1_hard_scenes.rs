#![doc = include_str!(concat!(env!("OUT_DIR"), "/q1_hard_scenes.md"))]

mod accuracy;
mod chart;
mod clutter;
mod figures;
mod findings;
mod fog;
mod metric;
mod mirrors;
mod motion;

pub use clutter::{
    CLUTTER_CAMERA_STEP, CLUTTER_COUNTS, CLUTTER_SEEDS, ClutterRow, block_probability, clutter_row, gap_fraction,
};
pub use figures::{Budget, RENDER_SPP, figure_jobs, figures, render_jobs, renders};
pub use findings::{Findings, findings};
pub use fog::{
    AIRLIGHT_CONVERGENCE_LAMPS, AIRLIGHT_STEPS, FOG_DISTANCES, FOG_SIGMAS, FogRow, airlight_convergence, airlight_rows,
    airlight_traced, fog_path_factor, fog_row, transmittance, visual_range,
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

/// The Q1 answers: the four hard scenes and what makes each hard, with the law each obeys.
/// Cheap (no rendering): the measured numbers are [`findings`], read from the committed tables
/// that the engineering notes include, in the words the chapter prints them, so the two say the
/// same (every number printed here is one the chapter prints; `tests/chapters_q1_q2.rs` checks).
///
/// # Examples
/// ```
/// let answers = hw3::q1_hard_scenes::answers();
/// assert_eq!(answers.question, "q1");
/// assert!(answers.text.contains("e^(−σ_t ℓ)"));
/// // Every shared number is printed as the chapter prints it.
/// for phrase in hw3::q1_hard_scenes::findings().shared_phrases() {
///     assert!(answers.text.contains(&phrase), "{phrase}");
/// }
/// ```
#[must_use]
pub fn answers() -> Answers {
    let found = findings();
    let (first_count, last_count) = found.clutter_counts;
    let sigmas = FOG_SIGMAS.map(|s| s.to_string()).join(" / ");
    let [within, changed, kd_tests, airlight_turn, ranges, sensitivity, growth, ball_speed, constant_ratio, spp_ratio] =
        <[String; 10]>::try_from(found.shared_phrases()).expect("ten shared phrases");
    let (_, passed_most) = found.spheres_passed;
    let (coarse, fine) = found.airlight_errors;
    let text = format!(
        "(a) clutter: one sphere of radius a over a W × W face (widened by a on each side) blocks a \
         perpendicular ray with probability p = πa²/(W + 2a)², so the gap fraction is (1 − p)^N; its limit \
         e^(−Np) is larger by about Np²/2, relatively. Over forests of {first_count} to {last_count} spheres \
         every measured gap fraction lies {within} of the law. What makes it hard is visibility: at N = \
         {last_count} a ray passes through {passed_most:.3} spheres on average but sees at most one; a \
         sideways camera step of {CLUTTER_CAMERA_STEP} changes which sphere {changed} of the pixels see; \
         the kd-tree of Q3 cuts the ray/sphere tests from all N to {kd_tests}.\n\
         (b) fog: a target's light arrives dimmed by the transmittance e^(−σ_t ℓ) over a path of length \
         ℓ (the renderer matches it to rounding, below {:e}); a dark object seen against the horizon sky \
         keeps the contrast e^(−σ_t d) (Koschmieder), so the visual range is ln 50/σ_t = {ranges} units \
         for σ_t = {sigmas}. A lamp adds its glow (airlight), which the renderer adds up in {} steps along \
         every view ray, at most {coarse:.1e} from Sun et al.'s closed form ({fine:.1e} with 4096 steps); \
         under a lamp the contrast falls faster than T where the glow grows with distance, and slower \
         where it falls ({airlight_turn}).\n\
         (c) mirrors: a sideways camera step δ turns the reflection at a mirror ball's centre by 2δ/R; \
         between four mirror spheres nearby rays separate {growth}, between flat mirrors only linearly; \
         over the pixels that see the spheres, the image changes {sensitivity} faster per unit camera \
         move than the same spheres made diffuse.\n\
         (d) change over time: an object moving v/fps per frame at depth z shifts \
         (v/fps)·(H/2)/tan(fov/2)/z pixels per frame; the moving ball shifts {ball_speed}, and its motion \
         blur costs {constant_ratio}, {spp_ratio} of the still scene for the same noise.",
        fog::ROUNDING_LEVEL,
        crate::render::integrator::IN_SCATTER_STEPS,
    );
    Answers { question: "q1", title: "Four scenes that are hard to render, and why", text }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The chapter's lessons rest on the generated tables, which the engineering notes include in
    /// full (the chapter itself keeps the charts and the lessons in words).
    #[test]
    fn engineering_notes_include_every_generated_table() {
        let notes = include_str!("../docs/engineering_q1.md");
        for table in [
            "q1_clutter_table.md",
            "q1_clutter_hardness.md",
            "q1_fog_table.md",
            "q1_airlight_table.md",
            "q1_airlight_steps.md",
            "q1_mirror_table.md",
            "q1_mirror_divergence_table.md",
            "q1_motion_table.md",
        ] {
            assert!(notes.contains(&format!("{{{{include:figures/{table}}}}}")), "{table}");
        }
    }

    /// The numbers [`answers`] prints are the findings the chapter prints (the tables they are
    /// read from are compared with the code's own measurements by `tests/docs.rs`).
    #[test]
    fn answers_print_the_shared_findings() {
        let text = answers().text;
        for phrase in findings().shared_phrases() {
            assert!(text.contains(&phrase), "{phrase}");
        }
    }
}
