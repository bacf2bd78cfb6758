//! Q2 variants: a ray and a sphere with small integer coordinates, and the parts a–c.

use super::formula::{Kind, Point, Value};
use super::key::{Derivation, Expected, Follows, MalRule, Part, Setting, Variant, formula_part};
use super::policy::Rule;
use crate::geometry::sphere::{Roots, closest_approach_t, first_hit_stable, roots_stable, surface_hit};
use crate::geometry::{Ray, Sphere};
use crate::q2_ray_sphere::worked_example;
use crate::rng;
use glam::DVec3;
use rand_core::Rng;

/// The RNG stream of Q2 variants: changing another question's generator never changes Q2's.
const STREAM: u64 = 2;

/// The chapter's sections each part is explained in.
const DERIVATION: &str = "hw3/q2_ray_sphere/index.html#part-q2a-the-case-the-first-hit-and-its-point";
const REFLECTION_NOTES: &str = "hw3/q2_ray_sphere/index.html#part-q2b-the-normal-and-the-reflected-direction";
const CLOSEST_NOTES: &str = "hw3/q2_ray_sphere/index.html#part-q2c-the-closest-approach";

const T_METHOD: &str = "Solve A t^2 + B t + C = 0 and take the smallest positive root (t = 0 is the eye, not a hit).";
const POINT_METHOD: &str = "Put the first hit's t into the ray: p = e + d t.";
const NORMAL_METHOD: &str =
    "The outward normal at p is (p - o)/r: from the centre to the hit, of unit length on the sphere.";
const REFLECTED_METHOD: &str = "With dhat = d/|d|, flip the normal component: dhat - 2 (n . dhat) n.";

/// Draws an integer in `low..=high` from 64 random bits (a tiny modulo bias is irrelevant here,
/// and integer draws keep variants identical on every platform).
fn integer(g: &mut rng::Generator, low: i64, high: i64) -> f64 {
    (low + (g.next_u64() % (high - low + 1) as u64) as i64) as f64
}

/// The cases of the homework's analysis of Q2(a), in the order seeds cycle through them
/// (`(seed − 1) mod 6`, so seeds 1, 7, 13, … are "outside"; seed 0 is a fixed ray with the eye outside,
/// [`crate::q2_ray_sphere::worked_example`], not the chapter's worked example).
pub(super) const CASES: [&str; 6] = ["outside", "inside", "behind", "tangent", "miss", "on_surface"];

/// Why each case is what it is, for the feedback on a wrong `case` or `hit`.
fn case_reason(case: &str) -> &'static str {
    match case {
        "outside" => {
            "C = |e - o|^2 - r^2 > 0 (eye outside) and B^2 - 4AC > 0 with both roots positive: the hit is the smaller root"
        }
        "inside" => "C = |e - o|^2 - r^2 < 0: the eye is inside, one root is negative and the hit is the larger root",
        "behind" => "C > 0 and B^2 - 4AC > 0, but both roots are negative: the sphere is behind the eye, no hit",
        "tangent" => "B^2 - 4AC = 0: one double root t = -B/2A > 0, the ray grazes the sphere (a hit)",
        "miss" => "B^2 - 4AC < 0: no real root, the ray's line misses the sphere",
        _ => {
            "C = 0: the eye is on the sphere, one root is t = 0 (the eye itself, not a hit); the other, -B/A, is the hit if positive"
        }
    }
}

/// An axis-aligned unit vector drawn from the six.
fn axis(g: &mut rng::Generator) -> DVec3 {
    let sign = if g.next_u64().is_multiple_of(2) { 1.0 } else { -1.0 };
    [DVec3::X, DVec3::Y, DVec3::Z][(g.next_u64() % 3) as usize] * sign
}

/// A ray/sphere pair for `seed` and its case: seed 0 is a fixed ray and sphere (eye `(−5, 1, 0)`,
/// direction `(1, 0, 0)`, radius 2 at the origin: an eye outside), not the chapter's worked example
/// ([`crate::q2_ray_sphere::notes_example`], which no variant draws); others are
/// drawn with integer coordinates in the case `CASES[(seed − 1) mod 6]`. "outside" redraws until the
/// ray meets the sphere at two well-separated positive roots (a discriminant large enough that
/// hand arithmetic is not a lottery); the tangent and on-surface cases are built exactly (a
/// tangent point or an eye at `o ± r` along an axis), so their discriminant or `C` is exactly 0.
pub(super) fn scene(seed: u64) -> (Ray<f64>, Sphere<f64>, &'static str) {
    if seed == 0 {
        let (ray, sphere) = worked_example();
        return (ray, sphere, "outside");
    }
    let case = CASES[((seed - 1) % 6) as usize];
    let mut g = rng::seeded(seed, STREAM);
    loop {
        let origin = DVec3::new(integer(&mut g, -6, 6), integer(&mut g, -6, 6), integer(&mut g, -6, 6));
        let dir = DVec3::new(integer(&mut g, -3, 3), integer(&mut g, -3, 3), integer(&mut g, -3, 3));
        let center = DVec3::new(integer(&mut g, -6, 6), integer(&mut g, -6, 6), integer(&mut g, -6, 6));
        let radius = integer(&mut g, 1, 4);
        let (origin, dir) = match case {
            "tangent" => {
                // Touch at p = o + r n; d ⟂ n; the eye k steps back along d.
                let n = axis(&mut g);
                let dir = dir - n * dir.dot(n);
                (center + n * radius - dir * integer(&mut g, 1, 3), dir)
            }
            "on_surface" => (center + axis(&mut g) * radius, dir),
            _ => (origin, dir),
        };
        let (Ok(ray), Ok(sphere)) = (Ray::new(origin, dir), Sphere::new(center, radius)) else {
            continue;
        };
        let c = (origin - center).length_squared() - radius * radius;
        let roots = roots_stable(&ray, &sphere);
        let separated = |r: &Roots<f64>| r.far - r.near > 0.25 * radius / dir.length();
        let wanted = match case {
            "outside" => c > 0.0 && roots.is_some_and(|r| r.near > 0.0 && separated(&r)),
            "inside" => c < 0.0,
            "behind" => c > 0.0 && roots.is_some_and(|r| r.far < 0.0 && separated(&r)),
            "tangent" => roots.is_some_and(|r| r.near == r.far && r.near > 0.0),
            // A clear miss: the line passes at least half a radius outside.
            "miss" => (origin - center).cross(dir).length() > 1.5 * radius * dir.length(),
            _ => c == 0.0 && (origin - center).dot(dir) != 0.0,
        };
        if wanted {
            return (ray, sphere, case);
        }
    }
}

fn vector(value: DVec3) -> Expected {
    Expected::Vector { value: value.to_array(), rtol: 1e-3, atol: 1e-6 }
}

fn direction(value: DVec3) -> Expected {
    Expected::Direction { value: value.normalize().to_array(), angle_tol: 1e-3 }
}

/// A value that a ray which misses does not have.
fn or_none(value: Expected) -> Expected {
    Expected::OrNone { value: Box::new(value), none: false }
}

fn parallel(value: DVec3) -> Expected {
    Expected::Parallel { value: value.normalize().to_array(), angle_tol: 1e-3 }
}

/// Symbols of the formula parts.
const RAY_SPHERE: [(&str, Kind); 4] =
    [("e", Kind::Vector), ("d", Kind::Vector), ("o", Kind::Vector), ("r", Kind::Scalar)];
const QUADRATIC: [(&str, Kind); 3] = [("A", Kind::Scalar), ("B", Kind::Scalar), ("C", Kind::Scalar)];
const AT_HIT: [(&str, Kind); 3] = [("p", Kind::Vector), ("o", Kind::Vector), ("r", Kind::Scalar)];
const REFLECTION: [(&str, Kind); 3] = [("d", Kind::Vector), ("dhat", Kind::Vector), ("n", Kind::Vector)];
const RAY_CENTRE: [(&str, Kind); 3] = [("e", Kind::Vector), ("d", Kind::Vector), ("o", Kind::Vector)];

/// Where formulas are compared: 40 rays that hit a sphere, real numbers (not the variant's
/// integers, so a formula cannot agree by coincidence), every symbol consistent with the others
/// (`A = d·d`, `t` the first hit, `p = e + d t`, `n = (p − o)/r`, `dhat = d/|d|`). With `inside`,
/// every second eye is inside the sphere (`C < 0`, the larger root, `n · d > 0`), so that a formula
/// right only from outside (`abs(C)`, a reflection with `abs(n · d)`) is not accepted; without,
/// every eye is outside (the root formula asked is the first hit from outside).
pub(super) fn formula_points(inside: bool) -> Vec<Point> {
    let mut g = rng::seeded(0, STREAM + 100);
    let mut points = Vec::new();
    while points.len() < 40 {
        let want_inside = inside && points.len() % 2 == 1;
        let mut v = || {
            DVec3::new(
                rng::uniform_in(&mut g, -4.0, 4.0),
                rng::uniform_in(&mut g, -4.0, 4.0),
                rng::uniform_in(&mut g, -4.0, 4.0),
            )
        };
        let (e, d, o) = (v(), v(), v());
        let r = 0.5 + 2.0 * rng::uniform(&mut g);
        let (a, b, c) = (d.dot(d), 2.0 * (e - o).dot(d), (e - o).length_squared() - r * r);
        let disc = b * b - 4.0 * a * c;
        let separated = if want_inside { c < -0.1 } else { c > 0.1 };
        if !separated || disc <= 0.1 * a || a < 0.1 {
            continue;
        }
        let t = if want_inside { (-b + disc.sqrt()) / (2.0 * a) } else { (-b - disc.sqrt()) / (2.0 * a) };
        let p = e + d * t;
        let n = (p - o) / r;
        let values = [
            ("e", Value::Vector(e)),
            ("d", Value::Vector(d)),
            ("o", Value::Vector(o)),
            ("r", Value::Scalar(r)),
            ("A", Value::Scalar(a)),
            ("B", Value::Scalar(b)),
            ("C", Value::Scalar(c)),
            ("t", Value::Scalar(t)),
            ("p", Value::Vector(p)),
            ("n", Value::Vector(n)),
            ("dhat", Value::Vector(d.normalize())),
        ];
        points.push(values.into_iter().collect());
    }
    points
}

fn formula_parts(points: &[Point], outside: &[Point]) -> [Part; 7] {
    let part = |key, prompt, source, symbols, slips, notes, method| {
        formula_part(key, prompt, 1.0, source, symbols, points, slips, notes, method)
    };
    [
        part(
            "q2a.A",
            "A of A t^2 + B t + C = 0, in e, d, o, r",
            "dot(d, d)",
            &RAY_SPHERE,
            &[("norm(d)", "|d| for |d|^2: A = d . d", Rule::Power)],
            DERIVATION,
            "Put e + d t into |p - o|^2 = r^2 and collect the powers of t: A = d . d.",
        ),
        part(
            "q2a.B",
            "B, in e, d, o, r",
            "2*dot(e - o, d)",
            &RAY_SPHERE,
            &[
                ("dot(e - o, d)", "the factor 2 is missing: B = 2 (e - o) . d", Rule::Factor),
                ("2*dot(o - e, d)", "sign error: B = 2 (e - o) . d", Rule::Sign),
                ("2*dot(e, d)", "the centre is missing: (e - o), not e", Rule::WrongTerm),
            ],
            DERIVATION,
            "Expand |(e - o) + d t|^2: the cross term is 2 (e - o) . d t, so B = 2 (e - o) . d.",
        ),
        part(
            "q2a.C",
            "C, in e, d, o, r",
            "dot(e - o, e - o) - r^2",
            &RAY_SPHERE,
            &[
                ("dot(e - o, e - o) - r", "r for r^2: C = |e - o|^2 - r^2", Rule::Power),
                ("dot(e, e) - r^2", "the centre is missing: C = |e - o|^2 - r^2", Rule::WrongTerm),
                ("r^2 - dot(e - o, e - o)", "sign error: C = |e - o|^2 - r^2", Rule::Sign),
            ],
            DERIVATION,
            "The terms without t: C = |e - o|^2 - r^2 (its sign says whether the eye is outside).",
        ),
        formula_part(
            "q2a.t_formula",
            "the first hit from outside, in A, B, C",
            1.0,
            "(-B - sqrt(B^2 - 4*A*C))/(2*A)",
            &QUADRATIC,
            outside,
            &[
                (
                    "(-B + sqrt(B^2 - 4*A*C))/(2*A)",
                    "that is the larger root: from outside, the first hit is the smaller",
                    Rule::WrongRoot,
                ),
                ("(-B - sqrt(B^2 - 4*A*C))/A", "the factor 2 is missing: divide by 2A", Rule::Factor),
                ("(B - sqrt(B^2 - 4*A*C))/(2*A)", "sign error: the roots are (-B ± sqrt(B^2 - 4AC))/2A", Rule::Sign),
                ("(-B - sqrt(B^2 - A*C))/(2*A)", "the factor 4 is missing: B^2 - 4AC", Rule::Factor),
            ],
            DERIVATION,
            "The roots are (-B ± sqrt(B^2 - 4AC))/2A; from outside both are positive and the first hit is the smaller.",
        ),
        part(
            "q2b.normal_formula",
            "the unit normal at the hit, in p, o, r",
            "(p - o)/r",
            &AT_HIT,
            &[
                ("(o - p)/r", "the normal points inward: p - o, not o - p", Rule::Sign),
                ("p - o", "not unit length: divide by r", Rule::NotNormalised),
            ],
            REFLECTION_NOTES,
            "The outward normal points from the centre to the hit, and |p - o| = r on the sphere: n = (p - o)/r.",
        ),
        part(
            "q2b.reflected_formula",
            "the unit reflected direction, in d, dhat, n",
            "dhat - 2*dot(n, dhat)*n",
            &REFLECTION,
            &[
                ("dhat + 2*dot(n, dhat)*n", "sign error: r = d - 2 (n . d) n (the normal component flips)", Rule::Sign),
                (
                    "dhat - dot(n, dhat)*n",
                    "that is the projection onto the tangent plane: removing the normal component once does not reflect, flipping it (twice) does",
                    Rule::OtherQuantity,
                ),
                (
                    "d - 2*dot(n, d)*n",
                    "right direction, but not unit length: use dhat = d/norm(d)",
                    Rule::NotNormalised,
                ),
            ],
            REFLECTION_NOTES,
            "Split dhat into its parts along n and along the surface, and flip the normal part: dhat - 2 (n . dhat) n.",
        ),
        part(
            "q2c.t_formula",
            "the closest-approach parameter, in e, d, o",
            "-dot(e - o, d)/dot(d, d)",
            &RAY_CENTRE,
            &[
                (
                    "-dot(e - o, d)/norm(d)",
                    "|d| for |d|^2: that is the distance along the ray; divide by |d| once more for t",
                    Rule::DistanceForParameter,
                ),
                ("dot(e - o, d)/dot(d, d)", "sign error: t = -(e - o) . d / |d|^2", Rule::Sign),
                ("-dot(e - o, d)", "divide by |d|^2 (t is in units of d)", Rule::WrongTerm),
            ],
            CLOSEST_NOTES,
            "At the closest approach e + d t - o is perpendicular to d: (e - o + d t) . d = 0 gives t = -(e - o) . d / (d . d).",
        ),
    ]
}

pub(super) fn variant(seed: u64) -> Variant {
    let (ray, sphere, case) = scene(seed);
    let roots = roots_stable(&ray, &sphere);
    let first = first_hit_stable(&ray, &sphere);
    let t_closest = closest_approach_t(&ray, sphere.center);
    let length = ray.dir.length();
    let v = |v: DVec3| format!("({}, {}, {})", v.x, v.y, v.z);
    let statement = format!(
        "Q2 (variant {seed}). Ray e + d t with e = {}, d = {}; sphere with centre o = {}, radius r = {}.\n\
         (a) which case of the analysis applies (case = one of {}), whether the ray hits the sphere at some t > 0 \
         (hit = true or false; t = 0 is the eye itself, not a hit), the parameter t of the first intersection and \
         the intersection point (\"none\" for each if it does not hit);\n\
         (b) the unit normal there, and the unit reflected direction (\"none\" if it does not hit);\n\
         (c) the parameter t of the ray's closest approach to the centre.\n\
         Also as formulas (the same for every variant): A, B, C of A t^2 + B t + C = 0 in e, d, o, r; the first hit \
         from outside in A, B, C; the unit normal in p, o, r; the unit reflected direction in d, dhat = d/|d|, n; the \
         closest-approach parameter in e, d, o.",
        v(ray.origin),
        v(ray.dir),
        v(sphere.center),
        sphere.radius,
        CASES.join(", ")
    );
    let reason = case_reason(case);
    let wrong_cases: Vec<MalRule> = CASES
        .iter()
        .filter(|c| **c != case)
        .map(|c| MalRule {
            value: Expected::Choice { value: c, options: &CASES },
            message: reason,
            rule: Rule::WrongCase,
        })
        .collect();
    let mut follows = Vec::new();
    let mut parts = vec![
        Part {
            key: "q2a.case",
            prompt: "which case of the analysis applies",
            points: 1.0,
            expected: Expected::Choice { value: case, options: &CASES },
            mal_rules: wrong_cases,
            explained_in: DERIVATION,
            method: "Decide by signs, in order: the discriminant B^2 - 4AC (no real root: miss; zero: tangent), then C (eye outside, inside or on the sphere), then the signs of the roots.",
        },
        Part {
            key: "q2a.hit",
            prompt: "does the ray hit the sphere at some t > 0",
            points: 1.0,
            expected: Expected::Flag { value: first.is_some() },
            mal_rules: vec![MalRule {
                value: Expected::Flag { value: first.is_none() },
                message: reason,
                rule: Rule::WrongCase,
            }],
            explained_in: DERIVATION,
            method: "The ray hits when the quadratic has a root t > 0 (t = 0 is the eye itself).",
        },
    ];
    let (points, outside) = (formula_points(true), formula_points(false));
    let [a, b, c, t_formula, normal_formula, reflected_formula, t_closest_formula] = formula_parts(&points, &outside);
    if let (Some(t), Some(roots)) = (first, roots) {
        let hit = surface_hit(&ray, &sphere, t);
        let d_hat = ray.dir.normalize();
        let reflected = d_hat - hit.normal * (2.0 * hit.normal.dot(d_hat));
        let other = if t == roots.far { roots.near } else { roots.far };
        let other_message = match case {
            "inside" => "that root is negative (behind the eye): from inside, the first hit is the larger root",
            "on_surface" => "t = 0 is the eye itself on the sphere, not a hit: the first hit is the other root",
            _ => "that is the larger root: the first hit is the smallest positive root",
        };
        let mut t_part = Part {
            key: "q2a.t",
            prompt: "first intersection parameter t",
            points: 2.0,
            expected: or_none(Expected::number(t, 1e-3)),
            mal_rules: vec![],
            explained_in: DERIVATION,
            method: T_METHOD,
        };
        if other != t {
            t_part.mal_rules.push(MalRule {
                value: Expected::number(other, 1e-3),
                message: other_message,
                rule: Rule::WrongRoot,
            });
        }
        let mut point_part = Part {
            key: "q2a.point",
            prompt: "the first intersection point",
            points: 1.0,
            expected: or_none(vector(hit.point)),
            mal_rules: vec![],
            explained_in: DERIVATION,
            method: POINT_METHOD,
        };
        if other != t {
            point_part.mal_rules.push(MalRule {
                value: vector(ray.at(other)),
                message: "that is the other intersection: use the smallest positive root",
                rule: Rule::WrongRoot,
            });
        }
        let mut reflected_part = Part {
            key: "q2b.reflected_dir",
            prompt: "unit reflected direction at the hit",
            points: 2.0,
            expected: or_none(direction(reflected)),
            mal_rules: vec![],
            explained_in: REFLECTION_NOTES,
            method: REFLECTED_METHOD,
        };
        if case != "tangent" {
            // At a grazing hit n . d = 0: the sign slip gives the same direction.
            reflected_part.mal_rules.push(MalRule {
                value: parallel(d_hat + hit.normal * (2.0 * hit.normal.dot(d_hat))),
                message: "sign error: r = d - 2 (n . d) n (the normal component flips)",
                rule: Rule::Sign,
            });
        }
        if (length - 1.0).abs() > 1e-3 {
            // Mal-rules that only differ from the key when |d| ≠ 1.
            t_part.mal_rules.push(MalRule {
                value: Expected::number(t * length, 1e-3),
                message: "that is the distance to the hit; t is the distance divided by |d|",
                rule: Rule::DistanceForParameter,
            });
            let unnormalised = ray.dir - hit.normal * (2.0 * hit.normal.dot(ray.dir));
            reflected_part.mal_rules.push(MalRule {
                value: Expected::Vector { value: unnormalised.to_array(), rtol: 1e-3, atol: 1e-6 },
                message: "right direction, but not unit length: normalise d first",
                rule: Rule::NotNormalised,
            });
        }
        let (origin, dir, center) = (ray.origin.to_array(), ray.dir.to_array(), sphere.center.to_array());
        follows.extend([
            Follows { key: "q2a.point", from: "q2a.t", derivation: Derivation::PointFromT { origin, dir } },
            Follows { key: "q2b.normal", from: "q2a.point", derivation: Derivation::NormalFromPoint { center } },
            Follows {
                key: "q2b.reflected_dir",
                from: "q2b.normal",
                derivation: Derivation::ReflectionFromNormal { dir },
            },
        ]);
        parts.extend([t_part, point_part]);
        parts.extend([a, b, c, t_formula]);
        parts.extend([
            Part {
                key: "q2b.normal",
                prompt: "unit outward normal at the hit",
                points: 1.0,
                expected: or_none(direction(hit.normal)),
                mal_rules: vec![MalRule {
                    value: parallel(-hit.normal),
                    message: "the normal points inward: use p - o, not o - p",
                    rule: Rule::Sign,
                }],
                explained_in: REFLECTION_NOTES,
                method: NORMAL_METHOD,
            },
            reflected_part,
        ]);
    } else {
        // No hit: the same parts, each answered "none", so the template does not give it away.
        let none = |key, prompt, points, like, explained_in, method| Part {
            key,
            prompt,
            points,
            expected: Expected::OrNone { value: Box::new(like), none: true },
            mal_rules: vec![],
            explained_in,
            method,
        };
        let zero = DVec3::X;
        parts.extend([
            none("q2a.t", "first intersection parameter t", 2.0, Expected::number(0.0, 1e-3), DERIVATION, T_METHOD),
            none("q2a.point", "the first intersection point", 1.0, vector(zero), DERIVATION, POINT_METHOD),
            a,
            b,
            c,
            t_formula,
            none("q2b.normal", "unit outward normal at the hit", 1.0, direction(zero), REFLECTION_NOTES, NORMAL_METHOD),
            none(
                "q2b.reflected_dir",
                "unit reflected direction at the hit",
                2.0,
                direction(zero),
                REFLECTION_NOTES,
                REFLECTED_METHOD,
            ),
        ]);
    }
    parts.extend([normal_formula, reflected_formula]);
    let mut closest = Part {
        key: "q2c.t_closest",
        prompt: "parameter t of the ray's closest approach to the centre",
        points: 2.0,
        expected: Expected::number(t_closest, 1e-3),
        mal_rules: vec![],
        explained_in: CLOSEST_NOTES,
        method: "At the closest approach e + d t - o is perpendicular to d: t = -(e - o) . d / |d|^2.",
    };
    if (length - 1.0).abs() > 1e-3 {
        closest.mal_rules.push(MalRule {
            value: Expected::number(t_closest * length, 1e-3),
            message: "that is the distance along the ray, (o - e) . d^; divide by |d| once more for t",
            rule: Rule::DistanceForParameter,
        });
    }
    parts.extend([closest, t_closest_formula]);
    Variant { question: "q2", seed, setting: Setting::Q2 { ray, sphere }, statement, parts, follows }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Seed 0 is the fixed ray the grader's manual describes, not the chapter's worked example.
    #[test]
    fn seed_zero_is_the_fixed_ray_not_the_chapters_example() {
        let variant = variant(0);
        assert!(variant.statement.contains("e = (-5, 1, 0)"), "{}", variant.statement);
        assert_ne!(scene(0).1, crate::q2_ray_sphere::notes_example().1);
    }

    #[test]
    fn every_seed_is_in_its_case() {
        for seed in 1..300 {
            let (ray, sphere, case) = scene(seed);
            assert_eq!(case, CASES[((seed - 1) % 6) as usize]);
            let c = (ray.origin - sphere.center).length_squared() - sphere.radius * sphere.radius;
            let roots = roots_stable(&ray, &sphere);
            let hit = first_hit_stable(&ray, &sphere);
            match case {
                "outside" => assert!(c > 0.0 && roots.unwrap().near > 0.0 && roots.unwrap().far > roots.unwrap().near),
                "inside" => assert!(c < 0.0 && hit == Some(roots.unwrap().far)),
                "behind" => assert!(c > 0.0 && roots.unwrap().far < 0.0 && hit.is_none()),
                "tangent" => assert!(roots.unwrap().near == roots.unwrap().far && hit.is_some()),
                "miss" => assert!(roots.is_none() && hit.is_none()),
                _ => assert_eq!(c, 0.0),
            }
        }
    }
}
