//! Q2 variants: a ray and a sphere with small integer coordinates, and the parts a–c.

use super::key::{Expected, MalRule, Part, Variant};
use crate::geometry::sphere::{closest_approach_t, first_hit_stable, roots_stable, surface_hit};
use crate::geometry::{Ray, Sphere};
use crate::q2_ray_sphere::worked_example;
use crate::rng;
use glam::DVec3;
use rand_core::Rng;

/// The RNG stream of Q2 variants: changing another question's generator never changes Q2's.
const STREAM: u64 = 2;

const NOTES: &str = "hw3/q2_ray_sphere/index.html";

/// Draws an integer in `low..=high` from 64 random bits (a tiny modulo bias is irrelevant here,
/// and integer draws keep variants identical on every platform).
fn integer(g: &mut rng::Generator, low: i64, high: i64) -> f64 {
    (low + (g.next_u64() % (high - low + 1) as u64) as i64) as f64
}

/// A ray/sphere pair for `seed`: seed 0 is the notes' worked example; others are drawn with
/// integer coordinates until the ray starts outside and meets the sphere at two distinct
/// positive roots, with a discriminant large enough that hand arithmetic is not a lottery.
pub(super) fn scene(seed: u64) -> (Ray<f64>, Sphere<f64>) {
    if seed == 0 {
        return worked_example();
    }
    let mut g = rng::seeded(seed, STREAM);
    loop {
        let origin = DVec3::new(integer(&mut g, -6, 6), integer(&mut g, -6, 6), integer(&mut g, -6, 6));
        let dir = DVec3::new(integer(&mut g, -3, 3), integer(&mut g, -3, 3), integer(&mut g, -3, 3));
        let center = DVec3::new(integer(&mut g, -6, 6), integer(&mut g, -6, 6), integer(&mut g, -6, 6));
        let radius = integer(&mut g, 1, 4);
        let Ok(ray) = Ray::new(origin, dir) else {
            continue;
        };
        let Ok(sphere) = Sphere::new(center, radius) else {
            continue;
        };
        let outside = (origin - center).length_squared() > radius * radius;
        let roots = roots_stable(&ray, &sphere);
        if outside && roots.is_some_and(|r| r.near > 0.0 && r.far - r.near > 0.25 * radius / dir.length()) {
            return (ray, sphere);
        }
    }
}

fn number(value: f64) -> Expected {
    Expected::Number { value, rtol: 1e-3, atol: 1e-9 }
}

fn vector(value: DVec3) -> Expected {
    Expected::Vector { value: value.to_array(), rtol: 1e-3, atol: 1e-6 }
}

fn direction(value: DVec3) -> Expected {
    Expected::Direction { value: value.normalize().to_array(), angle_tol: 1e-3 }
}

fn parallel(value: DVec3) -> Expected {
    Expected::Parallel { value: value.normalize().to_array(), angle_tol: 1e-3 }
}

pub(super) fn variant(seed: u64) -> Variant {
    let (ray, sphere) = scene(seed);
    let roots = roots_stable(&ray, &sphere).expect("variants are drawn to hit");
    let t = first_hit_stable(&ray, &sphere).expect("variants are drawn to hit");
    let hit = surface_hit(&ray, &sphere, t);
    let d_hat = ray.dir.normalize();
    let reflected = d_hat - hit.normal * (2.0 * hit.normal.dot(d_hat));
    let t_closest = closest_approach_t(&ray, sphere.center);
    let length = ray.dir.length();
    let v = |v: DVec3| format!("({}, {}, {})", v.x, v.y, v.z);
    let statement = format!(
        "Q2 (variant {seed}). Ray e + d t with e = {}, d = {}; sphere with centre o = {}, radius r = {}.\n\
         (a) the parameter t of the first intersection, and the intersection point;\n\
         (b) the unit normal there, and the unit reflected direction;\n\
         (c) the parameter t of the ray's closest approach to the centre.",
        v(ray.origin),
        v(ray.dir),
        v(sphere.center),
        sphere.radius
    );
    let mut parts = vec![
        Part {
            key: "q2a.t",
            prompt: "first intersection parameter t",
            points: 2.0,
            expected: number(t),
            mal_rules: vec![MalRule {
                value: number(roots.far),
                message: "that is the larger root: the first hit is the smallest positive root",
                credit: 0.0,
            }],
            explained_in: NOTES,
        },
        Part {
            key: "q2a.point",
            prompt: "intersection point e + d t",
            points: 1.0,
            expected: vector(hit.point),
            mal_rules: vec![MalRule {
                value: vector(ray.at(roots.far)),
                message: "that is the far intersection: use the smallest positive root",
                credit: 0.0,
            }],
            explained_in: NOTES,
        },
        Part {
            key: "q2b.normal",
            prompt: "unit normal (p - o)/r at the hit",
            points: 1.0,
            expected: direction(hit.normal),
            mal_rules: vec![MalRule {
                value: parallel(-hit.normal),
                message: "the normal points inward: use p - o, not o - p",
                credit: 0.0,
            }],
            explained_in: NOTES,
        },
        Part {
            key: "q2b.reflected_dir",
            prompt: "unit reflected direction d^ - 2 (n . d^) n",
            points: 2.0,
            expected: direction(reflected),
            mal_rules: vec![MalRule {
                value: parallel(d_hat + hit.normal * (2.0 * hit.normal.dot(d_hat))),
                message: "sign error: r = d - 2 (n . d) n (the normal component flips)",
                credit: 0.0,
            }],
            explained_in: NOTES,
        },
        Part {
            key: "q2c.t_closest",
            prompt: "closest-approach parameter -(e - o) . d / |d|^2",
            points: 2.0,
            expected: number(t_closest),
            mal_rules: vec![],
            explained_in: NOTES,
        },
    ];
    if (length - 1.0).abs() > 1e-3 {
        // Mal-rules that only differ from the key when |d| ≠ 1.
        parts[0].mal_rules.push(MalRule {
            value: number(t * length),
            message: "that is the distance to the hit; t is the distance divided by |d|",
            credit: 0.0,
        });
        parts[4].mal_rules.push(MalRule {
            value: number(t_closest * length),
            message: "that is the distance along the ray, (o - e) . d^; divide by |d| once more for t",
            credit: 0.5,
        });
        let unnormalised = ray.dir - hit.normal * (2.0 * hit.normal.dot(ray.dir));
        parts[3].mal_rules.push(MalRule {
            value: Expected::Vector { value: unnormalised.to_array(), rtol: 1e-3, atol: 1e-6 },
            message: "right direction, but not unit length: normalise d first",
            credit: 0.5,
        });
    }
    Variant { question: "q2", seed, statement, parts }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seed_zero_is_the_worked_example() {
        let variant = variant(0);
        assert!(variant.statement.contains("e = (-5, 1, 0)"), "{}", variant.statement);
    }

    #[test]
    fn variants_start_outside_and_hit_twice() {
        for seed in 1..200 {
            let (ray, sphere) = scene(seed);
            assert!((ray.origin - sphere.center).length() > sphere.radius);
            let roots = roots_stable(&ray, &sphere).unwrap();
            assert!(roots.near > 0.0 && roots.far > roots.near, "seed {seed}");
        }
    }
}
