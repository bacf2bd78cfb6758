//! Q3 variants: rays through the homework's kd-tree, graded leaf by leaf (path and t-interval).

use super::formula::{Kind, Point, Value};
use super::key::{Derivation, Expected, ExpectedLeaf, ExpectedPlane, Follows, Part, Variant, formula_part};
use super::policy::Rule;
use crate::q3_kd_traversal::student::cases;
use crate::q3_kd_traversal::{Node2, Ray2, Step, traverse};
use crate::rng;
use glam::DVec3;
use rand_core::Rng;

/// The RNG stream of Q3 variants.
const STREAM: u64 = 3;

/// The chapter's sections each part is explained in.
/// The chapter's sections on the graded parts: the plane parameters (b) and (c), and the traces.
const ROOT_PLANE_NOTES: &str = "hw3/q3_kd_traversal/index.html#part-q3b-the-root-planes-parameter";
const CHILD_PLANE_NOTES: &str = "hw3/q3_kd_traversal/index.html#part-q3c-the-plane-parameter-in-the-left-child";
const TRACE_NOTES: &str = "hw3/q3_kd_traversal/index.html#parts-q3d-and-q3e-tracing-a-ray-through-the-tree";
const TRAVERSAL_METHOD: &str = "At each node cut [tmin, tmax] at the plane's t = (s - e_a)/d_a: the near child gets [tmin, min(t, tmax)], the far child [max(t, tmin), tmax], and a piece of zero length is not visited.";

/// The key of one ray: its leaves, every descent, its planes, and the plane crossings (for the
/// feedback on a wrong bound).
struct Key {
    leaves: Vec<ExpectedLeaf>,
    descents: Vec<ExpectedLeaf>,
    planes: Vec<ExpectedPlane>,
    crossings: Vec<(String, f64)>,
}

fn key(ray: &Ray2) -> Key {
    let trace = traverse(&Node2::homework(), ray);
    let names = |path: &[crate::q3_kd_traversal::Branch]| path.iter().map(ToString::to_string).collect::<Vec<_>>();
    let leaves = trace
        .leaves()
        .iter()
        .map(|leaf| ExpectedLeaf { path: names(&leaf.path), t_min: leaf.interval.t_min, t_max: leaf.interval.t_max })
        .collect();
    let mut descents = Vec::new();
    let mut planes = Vec::new();
    let mut crossings = Vec::new();
    for (i, step) in trace.steps.iter().enumerate() {
        match step {
            Step::Plane { path, axis, split, t } => {
                if let Some(t) = t {
                    crossings.push((format!("{axis} = {split}"), *t));
                }
                // The walk records a plane, then descends into its first child at once.
                let first = match trace.steps.get(i + 1) {
                    Some(Step::Descend { path: child, .. }) => {
                        child.last().map(ToString::to_string).unwrap_or_default()
                    }
                    _ => String::new(),
                };
                planes.push(ExpectedPlane { node: names(path), t: *t, first });
            }
            Step::Descend { path, interval } => {
                descents.push(ExpectedLeaf { path: names(path), t_min: interval.t_min, t_max: interval.t_max });
            }
            Step::Leaf { .. } => {}
        }
    }
    Key { leaves, descents, planes, crossings }
}

/// The expected leaves of `ray`, and the plane crossings of its trace (for feedback).
fn expected(ray: &Ray2) -> (Vec<ExpectedLeaf>, Vec<(String, f64)>) {
    let key = key(ray);
    (key.leaves, key.crossings)
}

/// The kinds of second ray, by `seed mod 3`: a general ray, one parallel to a split, one that
/// starts on a split plane (the tie rules).
pub(super) const SECOND_RAY: [&str; 3] = ["general", "parallel", "on_plane"];

/// A ray of the given kind: integer origin in [0, 6] × [0, 5], small integer direction.
fn special_ray(g: &mut rng::Generator, kind: &str) -> Ray2 {
    loop {
        let mut draw = |low: i64, high: i64| (low + (g.next_u64() % (high - low + 1) as u64) as i64) as f64;
        let (origin, dir) = match kind {
            "parallel" => {
                let along = draw(1, 2) * if draw(0, 1) == 0.0 { -1.0 } else { 1.0 };
                let dir = if draw(0, 1) == 0.0 { [along, 0.0] } else { [0.0, along] };
                ([draw(0, 6), draw(0, 5)], dir)
            }
            _ => {
                let origin = match draw(0, 2) {
                    0.0 => [3.0, draw(0, 5)],
                    1.0 => [draw(0, 2), 1.0],
                    _ => [draw(4, 6), 3.0],
                };
                (origin, [draw(-2, 2), draw(-2, 2)])
            }
        };
        if let Ok(ray) = Ray2::new(origin, dir) {
            return ray;
        }
    }
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

const RAY_2D: [(&str, Kind); 2] = [("e", Kind::Vector), ("d", Kind::Vector)];

/// Where the plane-parameter formulas are compared: 40 rays with real coordinates, none parallel
/// to an axis.
fn formula_points() -> Vec<Point> {
    let mut g = rng::seeded(0, STREAM + 100);
    let mut points = Vec::new();
    while points.len() < 40 {
        let mut c = || rng::uniform_in(&mut g, -6.0, 6.0);
        let (e, d) = (DVec3::new(c(), c(), 0.0), DVec3::new(c(), c(), 0.0));
        if d.x.abs() > 0.2 && d.y.abs() > 0.2 {
            points.push([("e", Value::Vector(e)), ("d", Value::Vector(d))].into_iter().collect());
        }
    }
    points
}

pub(super) fn variant(seed: u64) -> Variant {
    let [d, e] = if seed == 0 {
        let student_cases = cases();
        [student_cases[0].ray, student_cases[1].ray]
    } else {
        let mut g = rng::seeded(seed, STREAM);
        let d = random_ray(&mut g);
        let e = match SECOND_RAY[(seed % 3) as usize] {
            "general" => random_ray(&mut g),
            kind => special_ray(&mut g, kind),
        };
        [d, e]
    };
    let show = |r: &Ray2| format!("e = ({}, {}), d = ({}, {})", r.origin[0], r.origin[1], r.dir[0], r.dir[1]);
    let statement = format!(
        "Q3 (variant {seed}). The homework's 2-D kd-tree: the root splits x = 3; its child x < 3 splits y = 1,\n\
         its child x >= 3 splits y = 3. Traverse it front to back, keeping the ray's interval [tmin, tmax].\n\
         Ties: a point on a split plane belongs to the >= side. At a node, the child the ray is in just after tmin \
         comes first; a ray starting on the plane (t = 0) goes only into the side it moves into; a ray parallel to \
         the plane has no t (write \"parallel\") and stays on its origin's side; a piece of zero length is not visited.\n\
         (b) the plane parameter t of the root's plane x = 3, as a formula in e and d (components e_x, d_x);\n\
         (c) the same for the plane y = 1 of the x < 3 child;\n\
         for each ray below: the planes met in order, each as {{ node = [\"x>=3\"], t = 3, first = \"y<3\" }} \
         (node = [] is the root); every descent into a child in order, each as {{ path = [\"x>=3\", \"y<3\"], \
         tmin = 0, tmax = 2 }}; and the leaves reached in order, in the same form (write an infinite bound as \"inf\").\n\
         (d) {}\n\
         (e) {}",
        show(&d),
        show(&e)
    );
    let points = formula_points();
    let mut follows = Vec::new();
    let mut parts = vec![
        formula_part(
            "q3b.t_formula",
            "t at the plane x = 3, in e, d",
            1.0,
            "(3 - e_x)/d_x",
            &RAY_2D,
            &points,
            &[
                ("(e_x - 3)/d_x", "sign error: e_x + d_x t = 3 gives t = (3 - e_x)/d_x", Rule::Sign),
                ("3/d_x", "the origin is missing: t = (3 - e_x)/d_x", Rule::WrongTerm),
            ],
            ROOT_PLANE_NOTES,
            "The ray's x is e_x + d_x t; it equals 3 at t = (3 - e_x)/d_x.",
        ),
        formula_part(
            "q3c.t_formula",
            "t at the plane y = 1, in e, d",
            1.0,
            "(1 - e_y)/d_y",
            &RAY_2D,
            &points,
            &[
                ("(e_y - 1)/d_y", "sign error: e_y + d_y t = 1 gives t = (1 - e_y)/d_y", Rule::Sign),
                ("(1 - e_x)/d_x", "that is the x-axis: the plane y = 1 uses e_y and d_y", Rule::WrongTerm),
            ],
            CHILD_PLANE_NOTES,
            "The ray's y is e_y + d_y t; it equals 1 at t = (1 - e_y)/d_y.",
        ),
    ];
    for (table, ray, leaf_points) in [("q3d", &d, 3.0), ("q3e", &e, 2.0)] {
        let key = key(ray);
        let name = |part: &str| -> &'static str {
            match (table, part) {
                ("q3d", "planes") => "q3d.planes",
                ("q3d", "descents") => "q3d.descents",
                ("q3d", _) => "q3d.leaves",
                (_, "planes") => "q3e.planes",
                (_, "descents") => "q3e.descents",
                _ => "q3e.leaves",
            }
        };
        parts.push(Part {
            key: name("planes"),
            prompt: "the planes met, in order: node, t (or \"parallel\"), the child first",
            points: 1.5,
            expected: Expected::Planes { steps: key.planes },
            mal_rules: vec![],
            explained_in: TRACE_NOTES,
            method: "At each node reached, t = (s - e_a)/d_a (none for a parallel ray), and first the child the ray is in just after tmin.",
        });
        parts.push(Part {
            key: name("descents"),
            prompt: "every descent into a child, in order, with its t-interval",
            points: 1.5,
            expected: Expected::Trace { leaves: key.descents, planes: key.crossings.clone(), descents: true },
            mal_rules: vec![],
            explained_in: TRACE_NOTES,
            method: TRAVERSAL_METHOD,
        });
        parts.push(Part {
            key: name("leaves"),
            prompt: "leaves reached, in order, with their t-intervals",
            points: leaf_points,
            expected: Expected::Trace { leaves: key.leaves, planes: key.crossings, descents: false },
            mal_rules: vec![],
            explained_in: TRACE_NOTES,
            method: TRAVERSAL_METHOD,
        });
        follows.push(Follows {
            key: name("leaves"),
            from: name("descents"),
            derivation: Derivation::LeavesFromDescents,
        });
    }
    Variant { question: "q3", seed, statement, parts, follows }
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

    #[test]
    fn second_rays_cover_the_tie_cases() {
        for seed in 1..60 {
            let v = variant(seed);
            let kind = SECOND_RAY[(seed % 3) as usize];
            let Expected::Planes { steps } = &v.parts.iter().find(|p| p.key == "q3e.planes").unwrap().expected else {
                unreachable!()
            };
            match kind {
                "parallel" => assert!(steps.iter().any(|s| s.t.is_none()), "seed {seed}: {steps:?}"),
                // Starting on a plane: t = 0 there, or no t when the ray also lies in it.
                "on_plane" => {
                    assert!(steps.iter().any(|s| s.t == Some(0.0) || s.t.is_none()), "seed {seed}: {steps:?}")
                }
                _ => {}
            }
        }
    }
}
