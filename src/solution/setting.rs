//! A variant's setting, read back from the checker's statement of it.
//!
//! The checker draws each variant's numbers and states them; it keeps the drawn values to itself.
//! Reading them back from the statement (rather than drawing them again) means a solution can never
//! solve a different problem from the one the student was given: the statement is the problem. A
//! change of wording fails here, loudly, and the tests run every variant 0–20 through it.

use super::SolutionError;
use crate::checker::{Q1Numbers, Variant};
use crate::geometry::{Ray, Sphere, parse_vec3};
use crate::q3_kd_traversal::{Ray2, parse_vec2};

/// Q4's setting: the sky `L(ω) = a + b ω_z`, the normal's tilt from up towards +x, and the
/// ball's distance in radii.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Q4Setting {
    pub a: f64,
    pub b: f64,
    pub tilt_deg: f64,
    pub distance_over_radius: f64,
}

fn error(variant: &Variant, what: &'static str) -> SolutionError {
    SolutionError::Statement { question: variant.question, seed: variant.seed, what }
}

/// The text right after the first `marker`.
fn after<'a>(text: &'a str, marker: &str) -> Option<&'a str> {
    text.find(marker).map(|i| &text[i + marker.len()..])
}

/// The text inside the parentheses right after `marker` (`e = (` → `-5, 1, 0`), for the CLI's
/// vector parsers to read: a statement writes a vector as a user types it.
fn inside<'a>(text: &'a str, marker: &str) -> Option<&'a str> {
    after(text, marker)?.split(')').next()
}

/// The number right after `marker`.
fn number(text: &str, marker: &str) -> Option<f64> {
    let rest = after(text, marker)?;
    let end = rest.find(|c: char| !(c.is_ascii_digit() || matches!(c, '.' | '-' | '+' | 'e'))).unwrap_or(rest.len());
    // A sentence's full stop is not part of the number.
    rest[..end].trim_end_matches('.').parse().ok()
}

/// Q1: the numbers of each difficulty.
pub(super) fn q1(variant: &Variant) -> Result<Q1Numbers, SolutionError> {
    let s = &variant.statement;
    let read = |marker: &str, what: &'static str| number(s, marker).ok_or_else(|| error(variant, what));
    Ok(Q1Numbers {
        count: read("(a) ", "the number of spheres")?,
        side: read("front face is a ", "the slab's side")?,
        radius: read("radius a = ", "the spheres' radius")?,
        sigma_t: read("sigma_t = ", "the fog's sigma_t")?,
        path: read("path of length ", "the fog path's length")?,
        mirror_radius: read("radius R = ", "the mirror's radius")?,
        step: read("steps sideways by ", "the camera step")?,
        speed: read("moving at ", "the object's speed")?,
        fps: read("filmed at ", "the frame rate")?,
        depth: read("across the view, ", "the object's distance")?,
        fov_deg: read("field of view of ", "the field of view")?,
        height: read("an image ", "the image height")?,
    })
}

/// Q2: the ray and the sphere.
pub(super) fn q2(variant: &Variant) -> Result<(Ray<f64>, Sphere<f64>), SolutionError> {
    let s = &variant.statement;
    let vector =
        |marker, what| inside(s, marker).and_then(|t| parse_vec3(what, t).ok()).ok_or_else(|| error(variant, what));
    let origin = vector("with e = (", "the eye e")?;
    let dir = vector(", d = (", "the direction d")?;
    let center = vector("centre o = (", "the centre o")?;
    let radius = number(s, "radius r = ").ok_or_else(|| error(variant, "the radius r"))?;
    let ray = Ray::new(origin, dir).map_err(|_| error(variant, "a valid ray"))?;
    let sphere = Sphere::new(center, radius).map_err(|_| error(variant, "a valid sphere"))?;
    Ok((ray, sphere))
}

/// Q3: the ray of part `label` (`'d'` or `'e'`).
pub(super) fn q3(variant: &Variant, label: char) -> Result<Ray2, SolutionError> {
    let line = variant
        .statement
        .lines()
        .find(|l| l.starts_with(&format!("({label}) ")))
        .ok_or_else(|| error(variant, "a ray's line"))?;
    let pair =
        |marker, what| inside(line, marker).and_then(|t| parse_vec2(what, t).ok()).ok_or_else(|| error(variant, what));
    let origin = pair("e = (", "a ray's origin")?;
    let dir = pair("d = (", "a ray's direction")?;
    Ray2::new(origin, dir).map_err(|_| error(variant, "a valid 2-D ray"))
}

/// Q4: the sky, the tilt and the ball's distance.
pub(super) fn q4(variant: &Variant) -> Result<Q4Setting, SolutionError> {
    let s = &variant.statement;
    let sky = after(s, "L(w) = ").ok_or_else(|| error(variant, "the sky"))?;
    let words: Vec<&str> = sky.split_whitespace().take(4).collect();
    let (a, b) = match words[..] {
        [a, sign, b, "w_z"] => {
            let a: f64 = a.parse().map_err(|_| error(variant, "the sky's constant"))?;
            let b: f64 = b.parse().map_err(|_| error(variant, "the sky's gradient"))?;
            match sign {
                "+" => (a, b),
                "-" => (a, -b),
                _ => return Err(error(variant, "the sky's sign")),
            }
        }
        _ => return Err(error(variant, "the sky")),
    };
    let tilt_deg = number(s, "tilted ").ok_or_else(|| error(variant, "the normal's tilt"))?;
    let distance_over_radius = number(s, "distance D = ").ok_or_else(|| error(variant, "the ball's distance"))?;
    Ok(Q4Setting { a, b, tilt_deg, distance_over_radius })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::checker::variant;

    #[test]
    fn seed_zero_reads_back_the_homeworks_numbers() {
        let (ray, sphere) = q2(&variant("q2", 0).unwrap()).unwrap();
        assert_eq!((ray, sphere), crate::q2_ray_sphere::worked_example());
        let q3_variant = variant("q3", 0).unwrap();
        let cases = crate::q3_kd_traversal::student::cases();
        assert_eq!([q3(&q3_variant, 'd').unwrap(), q3(&q3_variant, 'e').unwrap()], [cases[0].ray, cases[1].ray]);
        let setting = q4(&variant("q4", 0).unwrap()).unwrap();
        assert_eq!(setting, Q4Setting { a: 1.0, b: 1.0, tilt_deg: 60.0, distance_over_radius: 3.0 });
    }

    #[test]
    fn q1_reads_back_the_drawn_numbers() {
        for seed in 0..=20 {
            let numbers = q1(&variant("q1", seed).unwrap()).unwrap();
            assert_eq!(numbers, crate::checker::q1_numbers(seed), "seed {seed}");
        }
    }

    #[test]
    fn a_changed_statement_is_an_error_not_a_guess() {
        let mut v = variant("q2", 1).unwrap();
        v.statement = v.statement.replace("radius r", "size");
        assert_eq!(q2(&v), Err(SolutionError::Statement { question: "q2", seed: 1, what: "the radius r" }));
    }

    #[test]
    fn negative_gradients_read_with_their_sign() {
        let negative = (1..=200).map(|s| variant("q4", s).unwrap()).find(|v| v.statement.contains(" - 1 w_z"));
        let v = negative.expect("some variant has a sky darkening upwards");
        assert_eq!(q4(&v).unwrap().b, -1.0);
    }
}
