//! Q4 variants: irradiance from an analytic sky with a closed form, the mirror ball's blind spot,
//! and Q4 as the homework asks it: lighting a surface from a small probe image, texel by texel.

use super::formula::{Kind, Point, Value};
use super::key::{Derivation, Expected, Follows, MalRule, Part, Q4Image, Q4Setting, Setting, Variant, formula_part};
use super::policy::Rule;
use crate::envmap::{Probe, ProbeFormat, Texel, horizontal_camera};
use crate::plot::markdown_table;
use crate::q4_light_probe::blind_spot;
use crate::q4_light_probe::irradiance::{centre_texels, equal_weight, unweighted_sum, weighted_sum};
use crate::q4_light_probe::maps::{AnalyticMap, Term};
use crate::rng;
use glam::{DVec2, DVec3};
use rand_core::Rng;
use std::f64::consts::PI;

/// The RNG stream of Q4 variants.
const STREAM: u64 = 4;

/// The chapter's sections each part is explained in.
const IRRADIANCE_NOTES: &str = "hw3/q4_light_probe/index.html#part-q4a-the-irradiance-of-a-linear-sky";
const BLIND_NOTES: &str = "hw3/q4_light_probe/index.html#part-q4b-the-blind-cone-and-the-light-it-loses";

pub(super) fn variant(seed: u64) -> Variant {
    let mut g = rng::seeded(seed, STREAM);
    // Seed 0: a sky of radiance 1 + 1·ω_z, a normal tilted 60° from up, a ball seen from 3 radii.
    let (a, b, tilt_deg, distance_over_radius) = if seed == 0 {
        (1.0, 1.0, 60.0, 3.0)
    } else {
        let mut pick = |n: u64| g.next_u64() % n;
        let a = 1.0 + pick(4) as f64;
        let b = [-1.0, 1.0, 2.0][pick(3) as usize];
        // Radiance is never negative: with A ≥ |B| the sky is ≥ 0 straight down too, so the
        // closed form (which integrates L as given) is the irradiance of a physical sky.
        let a = a.max(f64::abs(b));
        let tilt = [0.0, 30.0, 45.0, 60.0, 90.0, 120.0][pick(6) as usize];
        let d = [2.0, 3.0, 4.0, 5.0, 10.0][pick(5) as usize];
        (a, b, tilt, d)
    };
    let tilt = f64::to_radians(tilt_deg);
    let normal = DVec3::new(tilt.sin(), 0.0, tilt.cos());
    let map = AnalyticMap::new(vec![Term::Linear { a, b, axis: DVec3::Z }]);
    let irradiance = map.irradiance(normal);
    let gamma = blind_spot::half_angle(distance_over_radius).expect("variant distances exceed one radius");
    let lost = blind_spot::lost_fraction(distance_over_radius, 0.0).expect("variant distances exceed one radius");
    let (sign, b_abs) = if b < 0.0 { ('-', -b) } else { ('+', b) };
    let statement = format!(
        "Q4 (variant {seed}). An environment of radiance L(w) = {a} {sign} {b_abs} w_z (z up) lights a diffuse surface.\n\
         (a) the irradiance E(n) at a surface whose unit normal n is tilted {tilt_deg} degrees from up towards +x;\n\
         (b) a mirrored ball of radius R photographed from distance D = {distance_over_radius} R: the half-angle, \
         in degrees, of the cone of directions the ball cannot show, and the fraction of a uniform environment's \
         irradiance lost for a normal pointing straight into that cone."
    );
    let image = ProbeImage::draw(seed, a, b, &mut g);
    let statement = format!("{statement}\n{}", image.statement());
    // Without the cosine: ∫ over the hemisphere of L alone, 2πA + πB n_z.
    let no_cosine = 2.0 * PI * a + PI * b * normal.z;
    let parts = vec![
        Part {
            key: "q4a.irradiance",
            prompt: "irradiance E(n)",
            points: 3.0,
            expected: Expected::number(irradiance, 1e-3),
            mal_rules: vec![
                MalRule {
                    value: Expected::number(no_cosine, 1e-3),
                    message: "the cosine factor max(0, n . w) is missing: that is the integral of L alone",
                    rule: Rule::OtherQuantity,
                },
                MalRule {
                    value: Expected::number(irradiance / PI, 1e-3),
                    message: "that is E/π, the outgoing radiance of a white diffuse surface, not the irradiance",
                    rule: Rule::Factor,
                },
            ],
            explained_in: IRRADIANCE_NOTES,
            method: "Integrate L(w) max(0, n . w) over the sphere: a constant A gives pi A, a linear B w_z gives (2 pi/3) B n_z.",
        },
        Part {
            key: "q4b.blind_half_angle_deg",
            prompt: "half-angle of the blind cone, in degrees",
            points: 2.0,
            expected: Expected::number(gamma.to_degrees(), 1e-3),
            mal_rules: vec![
                MalRule {
                    value: Expected::number(gamma, 1e-3),
                    message: "that is the angle in radians; degrees are asked",
                    rule: Rule::Unit,
                },
                MalRule {
                    value: Expected::number(2.0 * gamma.to_degrees(), 1e-3),
                    message: "that is the full cone angle; the half-angle is arcsin(R/D)",
                    rule: Rule::FullForHalfAngle,
                },
            ],
            explained_in: BLIND_NOTES,
            method: "The camera's rays graze the ball where they are tangent to it: the hidden cone behind the ball has half-angle arcsin(R/D).",
        },
        Part {
            key: "q4b.lost_fraction",
            prompt: "fraction of a uniform map's irradiance lost, normal into the cone",
            points: 2.0,
            expected: Expected::number(lost, 1e-3),
            mal_rules: vec![MalRule {
                value: Expected::number(
                    blind_spot::solid_angle(distance_over_radius).expect("D > R") / (4.0 * PI),
                    1e-3,
                ),
                message: "that is the cone's share of the sphere of directions; irradiance weights by the cosine",
                rule: Rule::OtherQuantity,
            }],
            explained_in: BLIND_NOTES,
            method: "Weight the hidden cone by the cosine: for a normal along its axis the lost share of pi is sin^2 of the half-angle, (R/D)^2.",
        },
    ];
    let follows = vec![Follows {
        key: "q4b.lost_fraction",
        from: "q4b.blind_half_angle_deg",
        derivation: Derivation::LostFromHalfAngle,
    }];
    let mut parts = parts;
    parts.extend(image.parts(normal));
    let setting = Setting::Q4(Q4Setting { a, b, tilt_deg, distance_over_radius, image: image.setting() });
    Variant { question: "q4", seed, setting, statement, parts, follows }
}

/// Where the notes work a probe image by hand.
const PROBE_NOTES: &str = "hw3/q4_light_probe/index.html#part-q4c-a-small-mirror-ball-image-texel-by-texel";
const DIRECTION_METHOD: &str =
    "Reflect the view ray about the ball's normal at the texel's centre: w = 2(n . v)n - v, with v toward the camera.";
const SOLID_ANGLE_METHOD: &str =
    "On the orthographic ball dw = 4 dA for the part of the texel inside the disc (image units of the ball's radius).";
const WEIGHTED_METHOD: &str =
    "Add L max(0, n . w) dw over every texel inside the disc, each weighted by its own solid angle.";
const UNWEIGHTED_METHOD: &str =
    "Add L max(0, n . w) over the N texels inside the disc and multiply by the equal share 4 pi/N.";
const RATIO_METHOD: &str = "Divide the unweighted sum by the weighted one: a ratio above 1 means the equal share overweights the texels that light the surface.";
const MASKED_METHOD: &str = "Subtract the used texels' solid angles from 4 pi: what is left is held by the texels whose centre falls outside the disc.";
const BLIND_DIRECTION_METHOD: &str = "Every point of the rim reflects the view ray straight on, so the direction behind the ball is the one the image cannot show.";
const TERM_METHOD: &str = "One texel adds its radiance times the clamped cosine times its solid angle.";

/// Texels across the probe image of part (c): seed 0 has 5 × 5, other seeds draw one of these.
const IMAGE_SIZES: [usize; 2] = [4, 5];

/// The radiances a drawn image's texels take (never negative, never 0: a texel sum of zeros has
/// no bias ratio).
const RADIANCES: [f64; 6] = [0.5, 1.0, 1.5, 2.0, 3.0, 4.0];

/// Angular tolerance of a texel's direction, radians: three decimals per component pass; the
/// direction of a texel's corner (a tenth of a radian or more away) does not.
const DIRECTION_TOL: f64 = 5e-3;

/// Relative tolerance of the probe's solid angles and sums: four significant digits worked by
/// hand pass; every slip below moves the answer by more.
const PROBE_RTOL: f64 = 1e-2;

/// Relative tolerance of the bias ratio, tighter than the sums': the ratio is within a few percent
/// of 1, so a 1 % tolerance would accept "no bias".
const RATIO_RTOL: f64 = 2e-3;

/// The listed texels' parts: the direction and the solid angle of each.
const LISTED: [(&str, &str, &str, &str); 3] = [
    (
        "q4c.texel1_direction",
        "world direction w of the first listed texel's centre",
        "q4c.texel1_solid_angle",
        "solid angle dw of the first listed texel, steradians",
    ),
    (
        "q4c.texel2_direction",
        "world direction w of the second listed texel's centre",
        "q4c.texel2_solid_angle",
        "solid angle dw of the second listed texel, steradians",
    ),
    (
        "q4c.texel3_direction",
        "world direction w of the third listed texel's centre",
        "q4c.texel3_solid_angle",
        "solid angle dw of the third listed texel, steradians",
    ),
];

/// The symbols of the texel-term formula: radiance, normal, direction, solid angle.
const TERM_SYMBOLS: [(&str, Kind); 4] =
    [("L", Kind::Scalar), ("n", Kind::Vector), ("w", Kind::Vector), ("dw", Kind::Scalar)];

/// Part (c): a small mirror-ball probe image, every texel's radiance given, three texels listed.
#[derive(Debug, Clone)]
struct ProbeImage {
    /// Texels across and down.
    size: usize,
    /// The image as an orthographic mirror-ball probe seen from the `+x` horizon; texels whose
    /// centre is outside the disc hold 0.
    probe: Probe,
    /// The listed texels (row-major indices): two wholly inside the disc, then one on its rim.
    listed: [usize; 3],
}

/// The mistakes a grader can tell apart: a slip whose value falls within its tolerance of the
/// key (a rim texel's share when no rim texel lights the surface, say; the ball's normal at the
/// texel that looks back at the camera) is the key there, and of two slips that land on one value
/// only the first is named.
fn distinct(rules: Vec<MalRule>, key: &Expected) -> Vec<MalRule> {
    let mut seen = vec![key.clone()];
    rules
        .into_iter()
        .filter(|rule| {
            let new = seen.iter().all(|earlier| apart(&rule.value, earlier));
            seen.push(rule.value.clone());
            new
        })
        .collect()
}

/// Whether the slip `value` lies outside its own tolerance of `other`: numbers relative to
/// `other` (`|v − w| > rtol·|w|`), directions by angle; values of other kinds are always apart.
fn apart(value: &Expected, other: &Expected) -> bool {
    match (value, other) {
        (Expected::Number { value, rtol, .. }, Expected::Number { value: other, .. }) => {
            (value - other).abs() > rtol * other.abs()
        }
        (Expected::Direction { value, angle_tol }, Expected::Direction { value: other, .. }) => {
            DVec3::from_array(*other).angle_between(DVec3::from_array(*value)) > *angle_tol
        }
        _ => true,
    }
}

fn direction(value: DVec3) -> Expected {
    Expected::Direction { value: value.to_array(), angle_tol: DIRECTION_TOL }
}

fn probe_number(value: f64) -> Expected {
    Expected::number(value, PROBE_RTOL)
}

impl ProbeImage {
    /// Seed 0 photographs the sky of part (a), each texel its centre's radiance to one decimal;
    /// other seeds draw 4 × 4 or 5 × 5 texels from [`RADIANCES`] and which texels are listed.
    fn draw(seed: u64, a: f64, b: f64, g: &mut rng::Generator) -> Self {
        let size = if seed == 0 { 5 } else { IMAGE_SIZES[(g.next_u64() % 2) as usize] };
        let format = ProbeFormat::MirrorBall;
        let blank = Probe::from_fn(format, size, size, horizontal_camera(), |_| DVec3::ZERO)
            .expect("a 4 × 4 or 5 × 5 probe of zeros is valid");
        let centres = centre_texels(&blank);
        let radiance: Vec<DVec3> = centres
            .iter()
            .map(|t| match (t.centre_inside, seed) {
                (false, _) => DVec3::ZERO,
                (true, 0) => DVec3::splat(((a + b * t.direction.z) * 10.0).round().max(0.0) / 10.0),
                (true, _) => DVec3::splat(RADIANCES[(g.next_u64() % RADIANCES.len() as u64) as usize]),
            })
            .collect();
        let probe = Probe::from_radiance(format, size, size, horizontal_camera(), radiance)
            .expect("the radiances are finite and ≥ 0");
        let full = (2.0 / size as f64).powi(2);
        let (interior, rim): (Vec<usize>, Vec<usize>) = (0..centres.len())
            .filter(|&i| centres[i].centre_inside)
            .partition(|&i| (centres[i].area - full).abs() < 1e-12 * full);
        let listed = if seed == 0 {
            // Row 1 column 2 (straight above the middle), row 1 column 3, and the top rim texel.
            [7, 8, 2]
        } else {
            let first = interior[(g.next_u64() % interior.len() as u64) as usize];
            let others: Vec<usize> = interior.iter().copied().filter(|&i| i != first).collect();
            let second = others[(g.next_u64() % others.len() as u64) as usize];
            [first, second, rim[(g.next_u64() % rim.len() as u64) as usize]]
        };
        Self { size, probe, listed }
    }

    /// `(row, column)` of texel `index`.
    fn place(&self, index: usize) -> (usize, usize) {
        (index / self.size, index % self.size)
    }

    /// The image as a variant's setting states it: each texel's radiance (`None` where masked)
    /// and the listed texels.
    fn setting(&self) -> Q4Image {
        let radiance = self.probe.texels().iter().map(|t| t.centre_inside.then_some(t.radiance.x)).collect::<Vec<_>>();
        Q4Image { size: self.size, radiance, listed: self.listed.map(|i| self.place(i)) }
    }

    /// Part (c)'s statement, with the image as a table.
    fn statement(&self) -> String {
        let n = self.size;
        let mut header = vec!["row".to_string()];
        header.extend((0..n).map(|c| c.to_string()));
        let header: Vec<&str> = header.iter().map(String::as_str).collect();
        let rows = (0..n).map(|row| {
            let mut cells = vec![row.to_string()];
            cells.extend((0..n).map(|column| {
                let texel = self.probe.texels()[row * n + column];
                if texel.centre_inside { format!("{}", texel.radiance.x) } else { "-".into() }
            }));
            cells
        });
        let table = markdown_table(&header, rows);
        let listed: Vec<String> = self.listed.iter().map(|&i| format!("{:?}", self.place(i))).collect();
        format!(
            "(c) Q4 as asked: the ball photographed from far away (an orthographic camera on the +x horizon) as a \
             {n} x {n} image, the ball's disc of radius 1 inscribed in it; image right = world +y, image up = world +z, \
             toward the camera = world +x. Each texel records the radiance L below (row 0 at the top, column 0 at the \
             left; \"-\" marks a texel whose centre is outside the disc: masked, not used):\n\n{table}\n\
             For texels {} (row, column): the world direction w of the texel's centre (unit, from the ball toward the \
             light it shows) and the texel's solid angle dw. Over every texel used, for the normal n of (a): the \
             weighted texel sum of the irradiance E (each texel used weighted by its own solid angle); the unweighted \
             texel sum (every texel used given the same share of the sphere, as the Q4 chapter defines it); the \
             unweighted sum's bias as the ratio unweighted/weighted; the solid angle the masked texels hold; the one \
             direction the image cannot show; and, as a formula in L, n, w \
             and dw, the term one texel adds to E.",
            listed.join(", ")
        )
    }

    /// Part (c)'s parts for surface normal `normal`.
    fn parts(&self, normal: DVec3) -> Vec<Part> {
        let texels = centre_texels(&self.probe);
        let camera = horizontal_camera();
        let toward_camera = camera * DVec3::Z;
        let used = texels.iter().filter(|t| t.centre_inside).count();
        let share = 4.0 * PI / used as f64;
        let full_area = (2.0 / self.size as f64).powi(2);
        let mut parts = Vec::new();
        for (&index, (direction_key, direction_prompt, solid_angle_key, solid_angle_prompt)) in
            self.listed.iter().zip(LISTED)
        {
            let texel = texels[index];
            let rect = self.probe.texel_rect(index);
            let corners = [rect.min, DVec2::new(rect.max.x, rect.min.y), rect.max, DVec2::new(rect.min.x, rect.max.y)];
            let mut mal_rules = vec![
                MalRule {
                    value: direction(camera.transpose() * texel.direction),
                    message: "that is the direction in the camera's frame (x right, y up, z toward the camera); in \
                              the world image right is +y, image up +z, toward the camera +x",
                    rule: Rule::Convention,
                },
                MalRule {
                    value: direction(-texel.direction),
                    message: "that is -w, the way the light travels; w points from the ball toward the light it shows",
                    rule: Rule::Sign,
                },
                MalRule {
                    // The ball's normal halves the angle between the view ray back to the camera
                    // and the reflected one.
                    value: direction((texel.direction + toward_camera).normalize()),
                    message: "that is the ball's normal at the texel; the light comes along the view ray reflected \
                              about it, at twice its angle from the camera",
                    rule: Rule::OtherQuantity,
                },
            ];
            mal_rules.extend(corners.iter().filter_map(|&c| self.probe.image_to_world(c)).map(|(w, _)| MalRule {
                value: direction(w),
                message: "that is the direction of a corner of the texel; the texel looks along its centre's",
                rule: Rule::WrongTerm,
            }));
            parts.push(Part {
                key: direction_key,
                prompt: direction_prompt,
                points: 1.0,
                expected: direction(texel.direction),
                mal_rules: distinct(mal_rules, &direction(texel.direction)),
                explained_in: PROBE_NOTES,
                method: DIRECTION_METHOD,
            });
            parts.push(Part {
                key: solid_angle_key,
                prompt: solid_angle_prompt,
                points: 1.0,
                expected: probe_number(texel.solid_angle),
                mal_rules: {
                    // A texel wholly inside the disc has its whole area's solid angle: that slip
                    // is the key there, and only a rim texel can make it.
                    let mut rules = vec![
                        MalRule {
                            value: probe_number(4.0 * full_area),
                            message: "that is 4 x the whole texel's area; only the part inside the disc sees the sky",
                            rule: Rule::WrongTerm,
                        },
                        MalRule {
                            value: probe_number(texel.area),
                            message: "that is the texel's area in the image; on the orthographic ball dw = 4 dA",
                            rule: Rule::OtherQuantity,
                        },
                        MalRule {
                            value: probe_number(share),
                            message: "that is 4 pi/N, the equal share the unweighted sum gives every texel",
                            rule: Rule::OtherQuantity,
                        },
                    ];
                    // Compared with the key only, not with each other as `distinct` would:
                    // that is what this part has always named, and the variants' snapshots pin it.
                    rules.retain(|rule| apart(&rule.value, &probe_number(texel.solid_angle)));
                    rules
                },
                explained_in: PROBE_NOTES,
                method: SOLID_ANGLE_METHOD,
            });
        }
        let weight = equal_weight(&texels);
        let weighted = weighted_sum(normal, &texels).x;
        let unweighted = unweighted_sum(normal, &texels, weight).x;
        // max(0, x) − max(0, −x) = x: the sums without the clamp, from the clamped ones.
        let unclamped = weighted - weighted_sum(-normal, &texels).x;
        let whole: Vec<Texel> = texels
            .iter()
            .map(|t| Texel { solid_angle: if t.centre_inside { 4.0 * full_area } else { 0.0 }, ..*t })
            .collect();
        parts.push(Part {
            key: "q4c.weighted_sum",
            prompt: "the weighted texel sum of E over the texels used",
            points: 2.0,
            expected: probe_number(weighted),
            mal_rules: distinct(
                vec![
                MalRule {
                    value: probe_number(unweighted_sum(normal, &texels, 1.0).x),
                    message: "the solid angle dw is missing: that sum counts texels, not steradians",
                    rule: Rule::WrongTerm,
                },
                MalRule {
                    value: probe_number(unclamped),
                    message: "the clamp max(0, .) is missing: texels below the surface's horizon subtract light",
                    rule: Rule::WrongTerm,
                },
                MalRule {
                    value: probe_number(weighted_sum(-normal, &texels).x),
                    message: "that uses -w, the way the light travels; n . w needs w from the surface toward the light",
                    rule: Rule::Sign,
                },
                MalRule {
                    value: probe_number(weighted_sum(normal, &whole).x),
                    message: "the rim texels are counted whole; only their part inside the disc sees the sky",
                    rule: Rule::WrongTerm,
                },
                MalRule {
                    value: probe_number(unweighted),
                    message: "that is the unweighted sum; weight each texel by its own solid angle",
                    rule: Rule::OtherQuantity,
                },
            ],
                &probe_number(weighted),
            ),
            explained_in: PROBE_NOTES,
            method: WEIGHTED_METHOD,
        });
        parts.push(Part {
            key: "q4c.unweighted_sum",
            prompt: "the unweighted texel sum of E over the texels used",
            points: 1.0,
            expected: probe_number(unweighted),
            mal_rules: distinct(
                vec![
                    MalRule {
                        value: probe_number(unweighted_sum(normal, &texels, 1.0).x),
                        message: "that is the literal sum of L max(0, n . w): give each texel the equal share 4 pi/N",
                        rule: Rule::OtherQuantity,
                    },
                    MalRule {
                        value: probe_number(unweighted - unweighted_sum(-normal, &texels, weight).x),
                        message: "the clamp max(0, .) is missing: texels below the surface's horizon subtract light",
                        rule: Rule::WrongTerm,
                    },
                    MalRule {
                        value: probe_number(weighted),
                        message: "that is the weighted sum; the unweighted one gives every texel 4 pi/N",
                        rule: Rule::OtherQuantity,
                    },
                ],
                &probe_number(unweighted),
            ),
            explained_in: PROBE_NOTES,
            method: UNWEIGHTED_METHOD,
        });
        let ratio = |value| Expected::number(value, RATIO_RTOL);
        parts.push(Part {
            key: "q4c.bias_ratio",
            prompt: "bias of the unweighted sum, as the ratio unweighted/weighted",
            points: 1.0,
            expected: ratio(unweighted / weighted),
            mal_rules: distinct(
                vec![
                MalRule {
                    value: ratio(weighted / unweighted),
                    message: "that is weighted/unweighted; the ratio asked is unweighted/weighted",
                    rule: Rule::Convention,
                },
                MalRule {
                    value: ratio(1.0),
                    message: "the unweighted sum is not exact here: a texel wholly inside the disc covers 4(2/N)^2 and a rim texel less, and neither is the equal share 4 pi/N",
                    rule: Rule::OtherQuantity,
                },
            ],
                &ratio(unweighted / weighted),
            ),
            explained_in: PROBE_NOTES,
                method: RATIO_METHOD,
        });
        let masked: f64 = texels.iter().filter(|t| !t.centre_inside).map(|t| t.solid_angle).sum();
        parts.push(Part {
            key: "q4c.masked_solid_angle",
            prompt: "solid angle held by the masked texels, steradians",
            points: 0.5,
            expected: probe_number(masked),
            mal_rules: vec![MalRule {
                value: Expected::Number { value: 0.0, rtol: 0.0, atol: 1e-3 },
                message: "the ball shows every direction but one, yet the masked corner texels drop the part of \
                          the disc they hold",
                rule: Rule::WrongTerm,
            }],
            explained_in: PROBE_NOTES,
            method: MASKED_METHOD,
        });
        // The rim of the disc: every point of it sees straight behind the ball.
        let rim = self.probe.image_to_world(DVec2::X).map_or(-toward_camera, |(w, _)| w);
        parts.push(Part {
            key: "q4c.blind_direction",
            prompt: "the one world direction the image cannot show",
            points: 0.5,
            expected: direction(rim),
            mal_rules: vec![MalRule {
                value: direction(toward_camera),
                message: "that is the direction back to the camera, seen at the ball's centre; the blind \
                          direction is straight behind the ball, where the rim points",
                rule: Rule::Sign,
            }],
            explained_in: PROBE_NOTES,
            method: BLIND_DIRECTION_METHOD,
        });
        parts.push(formula_part(
            "q4c.term_formula",
            "the term one texel adds to E, as a formula",
            1.0,
            "L*max(0, dot(n, w))*dw",
            &TERM_SYMBOLS,
            &term_points(),
            &[
                (
                    "L*dot(n, w)",
                    "the solid angle dw and the clamp max(0, .) are missing (the student's K_d L (n . l))",
                    Rule::WrongTerm,
                ),
                (
                    "L*dot(n, w)*dw",
                    "the clamp max(0, .) is missing: light from below the surface's horizon subtracts",
                    Rule::WrongTerm,
                ),
                (
                    "L*max(0, dot(n, w))",
                    "the solid angle dw is missing: the sum would count texels, not steradians",
                    Rule::WrongTerm,
                ),
                (
                    "L*max(0, -dot(n, w))*dw",
                    "that uses -w, the way the light travels; w points toward the light",
                    Rule::Sign,
                ),
            ],
            PROBE_NOTES,
            TERM_METHOD,
        ));
        parts
    }
}

/// Where the texel-term formula is compared: 40 random radiances, unit normals, unit directions
/// (half of them below the normal's horizon, where the clamp matters) and solid angles.
fn term_points() -> Vec<Point> {
    let mut g = rng::seeded(0, STREAM + 100);
    let unit = |g: &mut rng::Generator| {
        let z = rng::uniform_in(g, -1.0, 1.0);
        let phi = rng::uniform_in(g, 0.0, 2.0 * PI);
        let s = (1.0 - z * z).sqrt();
        DVec3::new(s * phi.cos(), s * phi.sin(), z)
    };
    (0..40)
        .map(|_| {
            let (n, w) = (unit(&mut g), unit(&mut g));
            let values = [
                ("L", Value::Scalar(rng::uniform_in(&mut g, 0.5, 4.0))),
                ("n", Value::Vector(n)),
                ("w", Value::Vector(w)),
                ("dw", Value::Scalar(rng::uniform_in(&mut g, 0.05, 1.0))),
            ];
            values.into_iter().collect()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seed_zero_by_hand() {
        // E = πA + (2π/3) B cos 60° = π + π/3; γ = arcsin(1/3) = 19.47°; lost = (R/D)² = 1/9.
        let v = variant(0);
        let value = |key| match v.parts.iter().find(|p| p.key == key).unwrap().expected {
            Expected::Number { value, .. } => value,
            _ => unreachable!(),
        };
        assert!((value("q4a.irradiance") - 4.0 * PI / 3.0).abs() < 1e-12);
        assert!((value("q4b.blind_half_angle_deg") - 19.471_220_634_490_69).abs() < 1e-9);
        assert!((value("q4b.lost_fraction") - 1.0 / 9.0).abs() < 1e-12);
    }

    /// E(n) by midpoint quadrature over the sphere of the sky clamped at 0, written out here
    /// without the crate's maps: if a variant's sky went negative anywhere, its closed-form key
    /// would differ from this.
    fn clamped_quadrature(a: f64, b: f64, normal: DVec3) -> f64 {
        let (n_theta, n_phi) = (400, 800);
        let (d_theta, d_phi) = (PI / f64::from(n_theta), 2.0 * PI / f64::from(n_phi));
        let mut sum = 0.0;
        for i in 0..n_theta {
            let theta = (f64::from(i) + 0.5) * d_theta;
            for j in 0..n_phi {
                let phi = (f64::from(j) + 0.5) * d_phi;
                let w = DVec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos());
                sum += (a + b * w.z).max(0.0) * normal.dot(w).max(0.0) * theta.sin() * d_theta * d_phi;
            }
        }
        sum
    }

    /// Images drawn from 60 generator states are physical and well posed: radiances ≥ 0 inside the
    /// disc and 0 outside, two listed texels wholly inside the disc and one cut by its rim; and
    /// every variant's weighted sum is positive.
    #[test]
    fn every_probe_image_is_physical_and_lists_interior_and_rim_texels() {
        for seed in 0..60 {
            let mut g = rng::seeded(seed, STREAM);
            let image = ProbeImage::draw(seed, 1.0, 1.0, &mut g);
            let full = (2.0 / image.size as f64).powi(2);
            for texel in image.probe.texels() {
                assert!(texel.radiance.x >= 0.0);
                assert!(texel.centre_inside || texel.radiance.x == 0.0);
            }
            let area = |i: usize| image.probe.texels()[i].area;
            let [first, second, rim] = image.listed;
            assert!(first != second && (area(first) - full).abs() < 1e-12 && (area(second) - full).abs() < 1e-12);
            assert!(area(rim) < full && image.probe.texels()[rim].centre_inside, "seed {seed}");
            let v = variant(seed);
            let weighted = v.parts.iter().find(|p| p.key == "q4c.weighted_sum").unwrap();
            assert!(matches!(weighted.expected, Expected::Number { value, .. } if value > 0.0));
        }
    }

    #[test]
    fn every_variant_sky_is_physical_and_its_key_matches_the_clamped_integral() {
        for seed in 0..60 {
            let v = variant(seed);
            // The statement names the sky and the tilt; read them back rather than re-drawing.
            let words: Vec<&str> = v.statement.split_whitespace().collect();
            let at = words.iter().position(|w| *w == "L(w)").unwrap();
            let a: f64 = words[at + 2].parse().unwrap();
            let sign = if words[at + 3] == "-" { -1.0 } else { 1.0 };
            let b = sign * words[at + 4].parse::<f64>().unwrap();
            assert!(a >= b.abs(), "seed {seed}: L = {a} + {b} w_z goes negative");
            let tilt_at = words.iter().position(|w| *w == "tilted").unwrap();
            let tilt = words[tilt_at + 1].parse::<f64>().unwrap().to_radians();
            let normal = DVec3::new(tilt.sin(), 0.0, tilt.cos());
            let Expected::Number { value, .. } = v.parts[0].expected else { unreachable!() };
            let brute = clamped_quadrature(a, b, normal);
            assert!((value - brute).abs() < 1e-4 * value, "seed {seed}: key {value}, clamped integral {brute}");
        }
    }
}
