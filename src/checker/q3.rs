//! Q3 variants: rays through the homework's kd-tree, graded leaf by leaf (path and t-interval).

use super::key::{Expected, ExpectedLeaf, Part, Variant};
use crate::q3_kd_traversal::seed::cases;
use crate::q3_kd_traversal::{Node2, Ray2, Step, traverse};
use crate::rng;
use rand_core::Rng;

/// The RNG stream of Q3 variants.
const STREAM: u64 = 3;

const NOTES: &str = "hw3/q3_kd_traversal/index.html";

/// The expected leaves of `ray`, and the plane crossings of its trace (for feedback).
fn expected(ray: &Ray2) -> (Vec<ExpectedLeaf>, Vec<(String, f64)>) {
    let trace = traverse(&Node2::homework(), ray);
    let leaves = trace
        .leaves()
        .iter()
        .map(|leaf| ExpectedLeaf {
            path: leaf.path.iter().map(ToString::to_string).collect(),
            t_min: leaf.interval.t_min,
            t_max: leaf.interval.t_max,
        })
        .collect();
    let planes = trace
        .steps
        .iter()
        .filter_map(|step| match step {
            Step::Plane { axis, split, t: Some(t), .. } => Some((format!("{axis} = {split}"), *t)),
            _ => None,
        })
        .collect();
    (leaves, planes)
}

/// A ray with integer origin in [0, 6]² and a small integer direction that visits at least two
/// leaves and never starts on a split plane (those ties are the notes' subject, not a drill's).
fn random_ray(g: &mut rng::Generator) -> Ray2 {
    loop {
        let mut draw = |low: i64, high: i64| (low + (g.next_u64() % (high - low + 1) as u64) as i64) as f64;
        let origin = [draw(0, 6), draw(0, 5)];
        let dir = [draw(-2, 2), draw(-2, 2)];
        let on_plane = origin[0] == 3.0 || origin[1] == 1.0 || origin[1] == 3.0;
        let Ok(ray) = Ray2::new(origin, dir) else { continue };
        if !on_plane && expected(&ray).0.len() >= 2 {
            return ray;
        }
    }
}

pub(super) fn variant(seed: u64) -> Variant {
    let [d, e] = if seed == 0 {
        let seed_cases = cases();
        [seed_cases[0].ray, seed_cases[1].ray]
    } else {
        let mut g = rng::seeded(seed, STREAM);
        [random_ray(&mut g), random_ray(&mut g)]
    };
    let show = |r: &Ray2| format!("e = ({}, {}), d = ({}, {})", r.origin[0], r.origin[1], r.dir[0], r.dir[1]);
    let statement = format!(
        "Q3 (variant {seed}). The homework's 2-D kd-tree: the root splits x = 3; its child x < 3 splits y = 1,\n\
         its child x >= 3 splits y = 3. Traverse it front to back, keeping the ray's interval [tmin, tmax].\n\
         For each ray, list the leaves reached in order, each as {{ path = [\"x>=3\", \"y<3\"], tmin = 0, tmax = 2 }}\n\
         (write an infinite bound as \"inf\").\n\
         (d) {}\n\
         (e) {}",
        show(&d),
        show(&e)
    );
    let part = |key, ray: &Ray2, points| {
        let (leaves, planes) = expected(ray);
        Part {
            key,
            prompt: "leaves reached, in order, with their t-intervals",
            points,
            expected: Expected::Trace { leaves, planes },
            mal_rules: vec![],
            explained_in: NOTES,
        }
    };
    Variant { question: "q3", seed, statement, parts: vec![part("q3d.leaves", &d, 3.0), part("q3e.leaves", &e, 2.0)] }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seed_zero_is_the_homeworks_cases() {
        let v = variant(0);
        assert!(v.statement.contains("(d) e = (5, 0), d = (-1, 1)"), "{}", v.statement);
        assert!(v.statement.contains("(e) e = (2, 0), d = (-1, -1)"), "{}", v.statement);
    }
}
