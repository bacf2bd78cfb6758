//! Q1 worked: the number behind each difficulty (the gap fraction of a cluttered slab, fog
//! transmittance and visual range, the turn of a mirror reflection per camera step, the image
//! shift per frame of a moving object), then which built-in scene shows which difficulty.
//!
//! Every number is the checker's key ([`checker::q1_key`](crate::checker)) of the variant's
//! numbers; the working shows the intermediate values that key is built from.

use super::text::{final_number, num, operand};
use super::{Section, Step, Value};
use crate::checker::{Q1_SCENES, Q1Setting, difficulty_of, q1_key};
use crate::render::catalogue::CATALOGUE;

pub(super) fn sections(n: &Q1Setting) -> Vec<Section> {
    let k = q1_key(n);
    let a = vec![
        Step::work(format!(
            "a sphere blocks a ray perpendicular to the face when its centre is within a = {} of the ray; its \
             centre is uniform over the face widened by a on each side: (W + 2a)² = ({} + 2 · {})² = {}",
            num(n.radius),
            num(n.side),
            num(n.radius),
            num(k.widened_area)
        )),
        Step::work(format!(
            "p = πa²/(W + 2a)² = π · {}/{} = {}",
            num(n.radius * n.radius),
            num(k.widened_area),
            significant(k.p)
        )),
        Step::answer(
            format!(
                "the {} spheres are independent, so the misses multiply: (1 - p)^N = (1 - {})^{} = {}",
                num(n.count),
                significant(k.p),
                num(n.count),
                final_number(k.gap)
            ),
            "q1a.gap_fraction",
            Value::Number(k.gap),
        ),
        Step::work({
            // The limit is larger by about Np²/2, relatively: within the part's 1 % only for a
            // sparse slab.
            let excess = k.boolean / k.gap - 1.0;
            let limit = if excess < 0.01 {
                "agrees within 1 %".to_string()
            } else {
                format!(
                    "is {:.1} % larger (about Np²/2 = {}), outside the 1 % accepted: the product is the answer",
                    excess * 100.0,
                    significant(n.count * k.p * k.p / 2.0)
                )
            };
            // The first-order term is below the product by about (Np)²/2 in absolute terms: within
            // 1 % only for a very sparse slab.
            let first_order = if (k.first_order / k.gap - 1.0).abs() < 0.01 {
                "also agrees within 1 % here, for so sparse a slab, though it counts a ray that two spheres block as blocked twice"
            } else {
                "does not agree (it counts a ray that two spheres block as blocked twice)"
            };
            format!(
                "check: the Boolean-model limit e^(-Np) = e^(-{}) = {} {limit}; the first-order term \
                 1 - Np = {} {first_order}",
                num(n.count * k.p),
                significant(k.boolean),
                num(k.first_order)
            )
        }),
    ];
    let b = vec![
        Step::work(format!(
            "optical depth τ = σ_t ℓ = {} · {} = {}",
            num(n.sigma_t),
            num(n.path),
            num(k.optical_depth)
        )),
        Step::answer(
            format!("T = e^(-τ) = e^(-{}) = {}", num(k.optical_depth), final_number(k.transmittance)),
            "q1b.transmittance",
            Value::Number(k.transmittance),
        ),
        Step::work(
            "an object's contrast against the fog falls as e^(-σ_t d); it is 2 % where e^(-σ_t d) = 1/50, so \
             d = ln 50/σ_t (Koschmieder)",
        ),
        Step::answer(
            format!("d = ln 50/σ_t = {}/{} = {}", num(50f64.ln()), num(n.sigma_t), num(k.visual_range)),
            "q1b.visual_range",
            Value::Number(k.visual_range),
        ),
        Step::work(format!("(not the mean free path 1/σ_t = {}, where T is 1/e = 37 %)", num(k.mean_free_path))),
    ];
    let c = vec![
        Step::work(format!(
            "a sideways step δ = {} moves the point where the centre pixel's ray meets the ball by δ",
            num(n.step)
        )),
        Step::work(format!(
            "near the ball's centre the normal turns by δ/R = {}/{} = {} rad",
            num(n.step),
            num(n.mirror_radius),
            num(k.normal_turn)
        )),
        Step::work(format!(
            "the reflected ray turns by twice the normal's turn: 2δ/R = {} rad",
            num(2.0 * k.normal_turn)
        )),
        Step::answer(
            format!("in degrees: {} · 180/π = {}°", num(2.0 * k.normal_turn), num(k.turn_deg)),
            "q1c.reflection_turn_deg",
            Value::Number(k.turn_deg),
        ),
    ];
    let half_fov = n.fov_deg / 2.0;
    let d = vec![
        Step::work(format!(
            "focal length in pixels f = (H/2)/tan(fov/2) = {}/tan({}°) = {}/{} = {}",
            num(n.height / 2.0),
            num(half_fov),
            num(n.height / 2.0),
            num(half_fov.to_radians().tan()),
            num(k.focal_pixels)
        )),
        Step::work(format!(
            "the object moves v/fps = {}/{} = {} units a frame",
            num(n.speed),
            num(n.fps),
            num(k.per_frame)
        )),
        Step::answer(
            format!(
                "at depth z = {} its image moves (v/fps) f/z = {} · {}/{} = {} pixels a frame",
                num(n.depth),
                num(k.per_frame),
                num(k.focal_pixels),
                operand(n.depth),
                num(k.shift)
            ),
            "q1d.pixels_per_frame",
            Value::Number(k.shift),
        ),
    ];
    let matches = Q1_SCENES
        .iter()
        .map(|&(scene, key, _)| {
            let letter = difficulty_of(scene);
            let description = CATALOGUE.iter().find(|(name, _)| *name == scene).map_or("", |(_, d)| d);
            Step::answer(format!("{scene} ({description}): ({letter})"), key, Value::Word(letter.into()))
        })
        .collect();
    vec![
        Section { title: "(a) clutter: the gap fraction".into(), steps: a },
        Section { title: "(b) fog: transmittance and visual range".into(), steps: b },
        Section { title: "(c) mirrors: the turn of the reflected ray".into(), steps: c },
        Section { title: "(d) motion: the image shift per frame".into(), steps: d },
        Section { title: "which scene shows which difficulty".into(), steps: matches },
    ]
}

/// A probability that may be far below 1 (a sphere's `p`, the gap of a dense slab): six
/// significant digits, where [`num`]'s six decimals would keep only a few, or print 0.
fn significant(x: f64) -> String {
    if x == 0.0 || x.abs() >= 0.1 {
        return num(x);
    }
    if x.abs() < 1e-4 {
        return format!("{x:.5e}");
    }
    // 1e-4 ≤ |x| < 0.1: 5 − ⌊log₁₀|x|⌋ decimals are six significant digits.
    let decimals = (5.0 - x.abs().log10().floor()) as usize;
    let text = format!("{x:.decimals$}");
    text.trim_end_matches('0').to_owned()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_probabilities_keep_their_digits() {
        assert_eq!(significant(0.0017811224), "0.00178112");
        assert_eq!(significant(0.028295), "0.028295");
        assert_eq!(significant(4.67e-12), "4.67000e-12");
        assert_eq!(significant(0.449329), "0.449329");
        assert_eq!(significant(0.0), "0");
    }
}
