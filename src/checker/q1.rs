//! Q1 variants: a number for each difficulty's metric (the gap fraction of a cluttered slab, fog
//! transmittance and visual range, the turn of a mirror reflection per camera step, the image
//! shift of a moving object per frame), and the built-in scenes matched to the difficulties.

use super::key::{Expected, MalRule, Part, Q1Setting, Setting, Variant};
use super::policy::Rule;
use crate::q1_hard_scenes::{
    block_probability, focal_length_pixels, gap_fraction, pixels_per_frame, reflection_turn, transmittance,
    visual_range,
};
use crate::render::catalogue::{CLUTTER_COUNT, CLUTTER_HALF_WIDTH, CLUTTER_RADIUS};
use crate::rng;
use rand_core::Rng;

/// The RNG stream of Q1 variants.
const STREAM: u64 = 1;

/// The chapter's sections each part is explained in.
const CLUTTER_NOTES: &str = "hw3/q1_hard_scenes/index.html#part-q1a-the-gap-fraction-of-a-slab-of-spheres";
const FOG_NOTES: &str = "hw3/q1_hard_scenes/index.html#part-q1b-transmittance-and-visual-range";
const MIRROR_NOTES: &str = "hw3/q1_hard_scenes/index.html#part-q1c-how-far-a-mirror-balls-reflection-turns";
const MOTION_NOTES: &str = "hw3/q1_hard_scenes/index.html#part-q1d-image-shift-per-frame";
const ANSWER_NOTES: &str = "hw3/q1_hard_scenes/index.html#part-q1match-which-scene-shows-which-difficulty";

/// The difficulties of Q1, by the homework's letters.
const DIFFICULTIES: [&str; 4] = ["a", "b", "c", "d"];

/// The four hard scenes of the renderer, by name, with the part that matches each and the
/// difficulty it shows. The letters live here, with the key, and not in the scene catalogue,
/// which `hw3 scenes` prints to students.
pub(crate) const SCENES: [(&str, &str, &str); 4] = [
    ("clutter", "q1match.clutter", "a"),
    ("fog", "q1match.fog", "b"),
    ("mirrors", "q1match.mirrors", "c"),
    ("motion", "q1match.motion", "d"),
];

/// Seed 0 is the renderer's clutter scene (1500 spheres of radius 0.5 over a 40 × 40 face) and
/// its fog street (σ_t = 0.08); other seeds draw from small grids of nice numbers.
pub(crate) fn numbers(seed: u64) -> Q1Setting {
    if seed == 0 {
        return Q1Setting {
            count: CLUTTER_COUNT as f64,
            side: 2.0 * CLUTTER_HALF_WIDTH,
            radius: CLUTTER_RADIUS,
            sigma_t: 0.08,
            path: 10.0,
            mirror_radius: 1.0,
            step: 0.01,
            speed: 2.0,
            fps: 24.0,
            depth: 5.0,
            fov_deg: 60.0,
            height: 480.0,
        };
    }
    let mut g = rng::seeded(seed, STREAM);
    let mut pick = |values: &[f64]| values[(g.next_u64() % values.len() as u64) as usize];
    Q1Setting {
        count: pick(&[500.0, 1000.0, 1500.0, 2000.0, 4000.0]),
        side: pick(&[20.0, 30.0, 40.0]),
        radius: pick(&[0.25, 0.5, 1.0]),
        sigma_t: pick(&[0.05, 0.1, 0.2, 0.5]),
        path: pick(&[1.0, 2.0, 5.0, 10.0]),
        mirror_radius: pick(&[0.5, 1.0, 2.0]),
        step: pick(&[0.01, 0.02, 0.05]),
        speed: pick(&[1.0, 2.0, 5.0]),
        fps: pick(&[24.0, 30.0, 60.0]),
        depth: pick(&[2.0, 5.0, 10.0]),
        fov_deg: pick(&[40.0, 60.0, 90.0]),
        height: pick(&[480.0, 720.0, 1080.0]),
    }
}

/// The difficulty one of the four hard [`SCENES`] shows, by the homework's letter.
///
/// # Panics
/// If `scene` is not one of them.
pub(crate) fn difficulty_of(scene: &str) -> &'static str {
    SCENES.iter().find(|(name, ..)| *name == scene).map(|&(.., letter)| letter).expect("one of the four hard scenes")
}

/// The key's numbers of a variant, with the intermediate values the worked solution shows and
/// the wrong answers the mal-rules recognise.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Key {
    /// `(W + 2a)²`: the face a sphere's centre falls in, widened by `a` on each side.
    pub widened_area: f64,
    /// One sphere's chance of blocking a ray, `πa²/(W + 2a)²`.
    pub p: f64,
    /// `(1 − p)^N`.
    pub gap: f64,
    /// The Boolean-model limit `e^(−Np)`: larger than the key by about `Np²/2`, relatively, so
    /// within the part's 1 % only while `Np²/2` stays below about 0.01.
    pub boolean: f64,
    /// The first-order term `1 − Np` (a recognised mistake).
    pub first_order: f64,
    /// The optical depth `σ_t ℓ`.
    pub optical_depth: f64,
    /// `e^(−σ_t ℓ)`.
    pub transmittance: f64,
    /// `ln 50/σ_t`.
    pub visual_range: f64,
    /// The mean free path `1/σ_t` (a recognised mistake).
    pub mean_free_path: f64,
    /// The normal's turn `δ/R`, radians.
    pub normal_turn: f64,
    /// The reflected ray's turn `2δ/R`, degrees.
    pub turn_deg: f64,
    /// The focal length in pixels, `(H/2)/tan(fov/2)`.
    pub focal_pixels: f64,
    /// The object's move per frame, `v/fps`.
    pub per_frame: f64,
    /// The image shift per frame, pixels.
    pub shift: f64,
}

/// The key of a variant's numbers.
pub(crate) fn key(n: &Q1Setting) -> Key {
    // One sphere blocks a ray with probability p = πa²/(W + 2a)² (its centre must fall in the
    // disc of radius a around the ray, out of a face widened by a on each side); misses multiply.
    let widened_area = (n.side + 2.0 * n.radius).powi(2);
    // The laws are the Q1 chapter's, called rather than restated, so the two cannot drift.
    let p = block_probability(n.radius, n.side);
    let optical_depth = n.sigma_t * n.path;
    // A sideways step δ moves where a pixel's ray meets the ball by δ; near the centre of the
    // ball the normal turns by δ/R and the reflected ray by twice that.
    let normal_turn = n.step / n.mirror_radius;
    let focal_pixels = focal_length_pixels(n.height, n.fov_deg);
    let per_frame = n.speed / n.fps;
    Key {
        widened_area,
        p,
        gap: gap_fraction(n.count, n.radius, n.side),
        boolean: (-n.count * p).exp(),
        first_order: 1.0 - n.count * p,
        optical_depth,
        transmittance: transmittance(n.sigma_t, n.path),
        visual_range: visual_range(n.sigma_t),
        mean_free_path: 1.0 / n.sigma_t,
        normal_turn,
        turn_deg: reflection_turn(n.step, n.mirror_radius).to_degrees(),
        focal_pixels,
        per_frame,
        shift: pixels_per_frame(per_frame, n.depth, focal_pixels),
    }
}

pub(super) fn variant(seed: u64) -> Variant {
    let n = numbers(seed);
    let k = key(&n);
    let (gap, transmittance, visual_range, turn, shift) = (k.gap, k.transmittance, k.visual_range, k.turn_deg, k.shift);
    let statement = format!(
        "Q1 (variant {seed}). What makes each scene hard, in numbers.\n\
         (a) {count} spheres of radius a = {a}, centres uniform over a slab whose front face is a {w} x {w} square \
         (widened by a on each side): the fraction of rays perpendicular to the face that cross the slab without a hit;\n\
         (b) fog of extinction coefficient sigma_t = {s}: the transmittance along a path of length {l}, and the visual \
         range (the distance at which an object's contrast falls to 2 %);\n\
         (c) a camera looking straight at a mirror sphere of radius R = {r} steps sideways by {step}: the angle, in \
         degrees, by which the reflected ray of the pixel at the ball's centre turns;\n\
         (d) an object moving at {v} units/s across the view, {z} units away, filmed at {fps} frames/s with a vertical \
         field of view of {fov} degrees and an image {h} pixels high: its image shift per frame, in pixels.\n\
         Match each built-in scene to the difficulty it shows (a, b, c or d): {}.",
        SCENES.map(|(name, ..)| name).join(", "),
        count = n.count,
        a = n.radius,
        w = n.side,
        s = n.sigma_t,
        l = n.path,
        r = n.mirror_radius,
        step = n.step,
        v = n.speed,
        z = n.depth,
        fps = n.fps,
        fov = n.fov_deg,
        h = n.height,
    );
    let mut parts = vec![
        Part {
            key: "q1a.gap_fraction",
            prompt: "fraction of rays crossing the slab without a hit",
            points: 2.0,
            // The exact (1 − p)^N, within 1 %. The Boolean-model limit e^(−Np) is larger by about
            // N p²/2, relatively: it passes only where that is below about 0.01 (the chapter says so).
            expected: Expected::number(gap, 1e-2),
            mal_rules: {
                let mut rules = vec![MalRule {
                    value: Expected::number(k.first_order, 1e-2),
                    message: "that is the first-order term 1 - N p; the misses multiply: (1 - p)^N",
                    rule: Rule::OtherQuantity,
                }];
                // Named only where it is wrong: for a sparse slab the limit is within 1 % and right.
                if (k.boolean / gap - 1.0).abs() > 1e-2 {
                    rules.push(MalRule {
                        value: Expected::number(k.boolean, 1e-2),
                        message: "that is the Boolean-model limit e^(-N p), larger than (1 - p)^N by about N p^2/2; for this slab that is more than 1 %: the product (1 - p)^N is the answer",
                        rule: Rule::OtherQuantity,
                    });
                }
                rules
            },
            explained_in: CLUTTER_NOTES,
            method: "One sphere blocks a ray with probability p = pi a^2/(W + 2a)^2; the N spheres miss independently: (1 - p)^N.",
        },
        Part {
            key: "q1b.transmittance",
            prompt: "transmittance along the path",
            points: 1.0,
            expected: Expected::number(transmittance, 1e-3),
            mal_rules: vec![MalRule {
                value: Expected::number(1.0 - k.optical_depth, 1e-3),
                message: "that is the first-order term 1 - sigma_t l; the transmittance is e^(-sigma_t l)",
                rule: Rule::OtherQuantity,
            }],
            explained_in: FOG_NOTES,
            method: "Each length dl removes the fraction sigma_t dl: the transmittance is e^(-sigma_t l) (Beer-Lambert).",
        },
        Part {
            key: "q1b.visual_range",
            prompt: "visual range (the distance at which contrast falls to 2 %)",
            points: 1.0,
            expected: Expected::number(visual_range, 1e-3),
            mal_rules: vec![MalRule {
                value: Expected::number(k.mean_free_path, 1e-3),
                message: "that is the mean free path 1/sigma_t; the visual range is where e^(-sigma_t d) = 2 %: ln 50/sigma_t",
                rule: Rule::OtherQuantity,
            }],
            explained_in: FOG_NOTES,
            method: "Contrast falls as e^(-sigma_t d); it reaches 2 % at d = ln 50/sigma_t (Koschmieder).",
        },
        Part {
            key: "q1c.reflection_turn_deg",
            prompt: "turn of the reflected ray, degrees",
            points: 1.0,
            expected: Expected::number(turn, 1e-2),
            mal_rules: vec![
                MalRule {
                    value: Expected::number(turn / 2.0, 1e-2),
                    message: "that is the turn of the normal, step/R; the reflected ray turns twice as much",
                    rule: Rule::OtherQuantity,
                },
                MalRule {
                    value: Expected::number(turn.to_radians(), 1e-2),
                    message: "that is the angle in radians; degrees are asked",
                    rule: Rule::Unit,
                },
            ],
            explained_in: MIRROR_NOTES,
            method: "A sideways step turns the normal at the ball's centre by step/R, and a reflection turns by twice its normal: 2 step/R radians, in degrees.",
        },
        Part {
            key: "q1d.pixels_per_frame",
            prompt: "image shift per frame, pixels",
            points: 1.0,
            expected: Expected::number(shift, 1e-2),
            mal_rules: vec![MalRule {
                value: Expected::number(n.speed / n.fps * n.height / n.fov_deg.to_radians().tan() / n.depth, 1e-2),
                message: "the focal length in pixels is (H/2)/tan(fov/2): half the image over the tangent of half the angle",
                rule: Rule::WrongTerm,
            }],
            explained_in: MOTION_NOTES,
            method: "The object moves v/fps per frame; at depth z the image moves that times the focal length in pixels, (H/2)/tan(fov/2), over z.",
        },
    ];
    for (scene, key, _) in SCENES {
        parts.push(Part {
            key,
            prompt: "which difficulty the scene shows",
            points: 0.5,
            expected: Expected::Choice { value: difficulty_of(scene), options: &DIFFICULTIES },
            mal_rules: vec![],
            explained_in: ANSWER_NOTES,
            method: "Look at the scene's picture in the chapter and ask what makes it hard: many objects hiding one another, a medium that dims and glows, mirrors, or motion.",
        });
    }
    Variant { question: "q1", seed, setting: Setting::Q1(n), statement, parts, follows: vec![] }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn value(v: &Variant, key: &str) -> f64 {
        match v.parts.iter().find(|p| p.key == key).unwrap().expected {
            Expected::Number { value, .. } => value,
            _ => unreachable!(),
        }
    }

    #[test]
    fn seed_zero_is_the_renderers_scenes() {
        let v = variant(0);
        assert!(v.statement.contains("1500 spheres of radius a = 0.5"), "{}", v.statement);
        // The clutter chapter's exact law for the same slab: p = π/4 / 41², (1 − p)^1500.
        let p = PI * 0.25 / 41.0f64.powi(2);
        assert!((value(&v, "q1a.gap_fraction") - (1.0 - p).powi(1500)).abs() < 1e-12);
        assert!((value(&v, "q1b.visual_range") - 48.9).abs() < 0.01);
    }

    #[test]
    fn the_four_scenes_are_the_four_difficulties() {
        let v = variant(0);
        let letters: Vec<&str> = SCENES
            .iter()
            .map(|(_, key, _)| match v.parts.iter().find(|p| p.key == *key).unwrap().expected {
                Expected::Choice { value, .. } => value,
                _ => unreachable!(),
            })
            .collect();
        assert_eq!(letters, ["a", "b", "c", "d"]);
    }

    /// `hw3 scenes` prints the catalogue to students: its lines name no question part and no
    /// difficulty, so they do not answer q1match.
    #[test]
    fn the_scene_catalogue_does_not_answer_q1match() {
        for (name, description) in crate::render::catalogue::CATALOGUE {
            for giveaway in ["Q1", "Q4", "motion blur", "medium", "hide one another", "change over time", "difficulty"]
            {
                assert!(!description.contains(giveaway), "{name}: {description:?} says {giveaway:?}");
            }
        }
    }

    /// The renderer's fog follows the transmittance law the key uses (measured by the Q1 code).
    #[test]
    fn the_renderers_fog_has_the_keys_transmittance() {
        let row = crate::q1_hard_scenes::fog_row(0.1, 5.0).unwrap();
        assert!((row.transmittance - row.law).abs() < 1e-9, "{row:?}");
    }
}
