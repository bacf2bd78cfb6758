//! Q3 variants: rays through the homework's kd-tree, graded leaf by leaf (path and t-interval).

use super::formula::{Kind, Point, Value};
use super::key::{Derivation, Expected, ExpectedLeaf, ExpectedPlane, Follows, Part, Setting, Variant, formula_part};
use super::policy::Rule;
use super::traces::show_bound;
use crate::q3_kd_traversal::student::cases;
use crate::q3_kd_traversal::{Axis2, Branch, Interval, Node2, Ray2, Step, traverse};
use crate::rng;
use glam::DVec3;
use rand_core::Rng;

/// The RNG stream of Q3 variants.
const STREAM: u64 = 3;

/// The chapter's sections on the graded parts: the plane parameters (b) and (c), and the traces.
const ROOT_PLANE_NOTES: &str = "hw3/q3_kd_traversal/index.html#part-q3b-the-root-planes-parameter";
const CHILD_PLANE_NOTES: &str = "hw3/q3_kd_traversal/index.html#part-q3c-the-plane-parameter-in-the-left-child";
const TRACE_NOTES: &str = "hw3/q3_kd_traversal/index.html#parts-q3d-and-q3e-tracing-a-ray-through-the-tree";
const TRAVERSAL_METHOD: &str = "At each node cut [tmin, tmax] at the plane's t = (s - e_a)/d_a. The first child is the one the ray is in just after tmin (for a parallel ray its origin's side; for a ray on the plane at tmin the side it moves into). If tmin < t < tmax, the first child gets [tmin, t] and the second child [t, tmax]; otherwise (a parallel ray, t <= tmin or t >= tmax) only the first child is visited, with the whole [tmin, tmax], since the second child's piece would be empty or of zero length.";
/// The method of the `planes` parts.
const PLANES_METHOD: &str = "At each node reached, t = (s - e_a)/d_a (none for a parallel ray), and first the child the ray is in just after tmin: for a parallel ray its origin's side, for a ray on the plane at tmin the side it moves into.";

/// The key of one ray: its leaves, every descent, its planes with why each plane's first child is
/// first, and the plane crossings (for the feedback on a wrong bound).
struct Key {
    leaves: Vec<ExpectedLeaf>,
    descents: Vec<ExpectedLeaf>,
    planes: Vec<ExpectedPlane>,
    why_first: Vec<String>,
    crossings: Vec<(String, f64)>,
}

/// Why `first` is the first child visited at the plane `axis = split` of a node that holds the ray
/// over `interval`, by the question's rule and in this node's numbers: the child the ray is in just
/// after tmin; for a parallel ray its origin's side (the >= side when it lies in the plane); for a
/// ray on the plane at tmin, the side it moves into.
fn why_first(ray: &Ray2, axis: Axis2, split: f64, t: Option<f64>, interval: Interval, first: Branch) -> String {
    let a = axis.index();
    let (e, d) = (ray.origin[a], ray.dir[a]);
    let other = Branch { side: first.side.opposite(), ..first };
    let plane = format!("the plane {axis} = {split}");
    let (t_min, t_max) = (show_bound(interval.t_min), show_bound(interval.t_max));
    let Some(t) = t else {
        return if e == split {
            format!(
                "{first} comes first: the ray lies in {plane} (d_{axis} = 0, e_{axis} = {}), and a point on the \
                 plane belongs to the >= side; {first} is the only child visited",
                show_bound(e)
            )
        } else {
            format!(
                "{first} comes first: the ray is parallel to {plane} (d_{axis} = 0) and stays on its origin's side \
                 (e_{axis} = {}) for every t; {first} is the only child visited",
                show_bound(e)
            )
        };
    };
    let t_text = show_bound(t);
    if t == interval.t_min {
        format!(
            "{first} comes first: at tmin = {t_min} the ray is on {plane} and moves into {first} (d_{axis} = {}), \
             the side it moves into; {other} would get a piece of zero length, so {first} is the only child visited",
            show_bound(d)
        )
    } else if t < interval.t_min {
        format!(
            "{first} comes first: it is the child the ray is in just after tmin = {t_min}; the ray crossed {plane} \
             at t = {t_text}, before tmin, so {first} is the only child visited (the sign of d_{axis} alone would \
             point to {other}, whose piece here is empty)"
        )
    } else if t >= interval.t_max {
        format!(
            "{first} comes first: it is the child the ray is in just after tmin = {t_min}; the ray would reach \
             {plane} only at t = {t_text}, not before this node's tmax = {t_max}, so {first} is the only child visited"
        )
    } else {
        format!(
            "{first} comes first: it is the child the ray is in just after tmin = {t_min}; the ray reaches {plane} \
             only at t = {t_text}, so it is in {first} until then and in {other}, the second child, after"
        )
    }
}

fn key(ray: &Ray2) -> Key {
    let trace = traverse(&Node2::homework(), ray);
    let names = |path: &[Branch]| path.iter().map(ToString::to_string).collect::<Vec<_>>();
    let leaves = trace
        .leaves()
        .iter()
        .map(|leaf| ExpectedLeaf { path: names(&leaf.path), t_min: leaf.interval.t_min, t_max: leaf.interval.t_max })
        .collect();
    let root = Interval { t_min: 0.0, t_max: f64::INFINITY };
    // The piece of the ray each node descended into holds.
    let mut entered: Vec<(&[Branch], Interval)> = Vec::new();
    let mut descents = Vec::new();
    let mut planes = Vec::new();
    let mut why = Vec::new();
    let mut crossings = Vec::new();
    for (i, step) in trace.steps.iter().enumerate() {
        match step {
            Step::Plane { path, axis, split, t } => {
                if let Some(t) = t {
                    crossings.push((format!("{axis} = {split}"), *t));
                }
                // The walk records a plane, then descends into its first child at once.
                let Some(Step::Descend { path: child, .. }) = trace.steps.get(i + 1) else {
                    unreachable!("a plane is followed by the descent into its first child")
                };
                let first = *child.last().expect("a child's path is not empty");
                let interval = entered.iter().rev().find(|(p, _)| *p == path.as_slice()).map_or(root, |(_, i)| *i);
                why.push(why_first(ray, *axis, *split, *t, interval, first));
                planes.push(ExpectedPlane { node: names(path), t: *t, first: first.to_string() });
            }
            Step::Descend { path, interval } => {
                entered.push((path, *interval));
                descents.push(ExpectedLeaf { path: names(path), t_min: interval.t_min, t_max: interval.t_max });
            }
            Step::Leaf { .. } => {}
        }
    }
    Key { leaves, descents, planes, why_first: why, crossings }
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
            expected: Expected::Planes { steps: key.planes, why_first: key.why_first, ray: (ray.origin, ray.dir) },
            mal_rules: vec![],
            explained_in: TRACE_NOTES,
            method: PLANES_METHOD,
        });
        let key_descents = key.descents.clone();
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
        // Planes before descents before leaves: a slip is carried down the chain in one pass.
        follows.push(Follows {
            key: name("descents"),
            from: name("planes"),
            derivation: Derivation::DescentsFromPlanes { origin: ray.origin, dir: ray.dir },
        });
        follows.push(Follows {
            key: name("leaves"),
            from: name("descents"),
            derivation: Derivation::LeavesFromDescents { descents: key_descents, origin: ray.origin, dir: ray.dir },
        });
        follows.push(Follows {
            key: name("leaves"),
            from: name("planes"),
            derivation: Derivation::LeavesFromPlanes { origin: ray.origin, dir: ray.dir },
        });
    }
    Variant { question: "q3", seed, setting: Setting::Q3 { d, e }, statement, parts, follows }
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
            let Expected::Planes { steps, .. } = &v.parts.iter().find(|p| p.key == "q3e.planes").unwrap().expected
            else {
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

    /// The planes of part `part` of `seed`'s variant, with the reasons, and the feedback and credit
    /// for the key's planes with `edit` applied.
    fn graded(seed: u64, part: &str, edit: impl Fn(&mut Vec<ExpectedPlane>)) -> (f64, String) {
        let v = variant(seed);
        let Expected::Planes { steps, why_first, .. } = &v.parts.iter().find(|p| p.key == part).unwrap().expected
        else {
            unreachable!()
        };
        let mut given = steps.clone();
        edit(&mut given);
        // Nothing followed: these tests are about the firsts, charged against the key.
        let (credit, words, _) = super::super::traces::grade_planes(steps, why_first, &given, &[]);
        (credit, words)
    }

    /// The other child of a node: `"y<3"` for `"y>=3"` and back.
    fn flip(first: &mut String) {
        *first = if first.contains(">=") { first.replace(">=", "<") } else { first.replace('<', ">=") };
    }

    /// Seed 7, (d): at x >= 3 the plane y = 3 lies behind the eye (t = -1 <= tmin = 0) and d_y < 0.
    /// The child the ray is in just after tmin, y<3, comes first, not the side the sign of d_y
    /// points to; the feedback says so with the node's numbers, and never "near" or "far".
    #[test]
    fn seed_7_first_feedback_states_the_questions_rule() {
        let v = variant(7);
        assert!(v.statement.contains("(d) e = (6, 2), d = (-1, -1)"), "{}", v.statement);
        let (credit, words) = graded(7, "q3d.planes", |g| flip(&mut g[1].first));
        assert!(
            words.contains(
                "plane 2: y<3 comes first: it is the child the ray is in just after tmin = 0; the ray crossed the plane \
                 y = 3 at t = -1, before tmin, so y<3 is the only child visited"
            ),
            "{words}"
        );
        assert!(!words.contains("near") && !words.contains("far") && !words.contains("d_a < 0: the upper"), "{words}");
        // The two other planes are right: each earns its share.
        assert!((credit - 2.0 / 3.0).abs() < 1e-12, "{credit}");
    }

    /// Seed 12, (d): at x >= 3 (entered at tmin = 3) the plane y = 3 was crossed at t = 0.5 with
    /// d_y = 2 > 0: y>=3 comes first, because the ray is already above the plane.
    #[test]
    fn seed_12_first_feedback_states_the_questions_rule() {
        let v = variant(12);
        assert!(v.statement.contains("(d) e = (0, 2), d = (1, 2)"), "{}", v.statement);
        let (_, words) = graded(12, "q3d.planes", |g| flip(&mut g[2].first));
        assert!(
            words.contains(
                "plane 3: y>=3 comes first: it is the child the ray is in just after tmin = 3; the ray crossed the \
                 plane y = 3 at t = 0.5, before tmin, so y>=3 is the only child visited"
            ),
            "{words}"
        );
        assert!(!words.contains("d_a > 0: the lower side"), "{words}");
        // And at x < 3 (tmin = 0) the plane y = 1 lies behind the eye, at t = -0.5.
        let (_, words) = graded(12, "q3d.planes", |g| flip(&mut g[1].first));
        assert!(words.contains("plane 2: y>=1 comes first: it is the child the ray is in just after tmin = 0; the ray crossed the plane y = 1 at t = -0.5, before tmin"), "{words}");
    }

    /// Each case of the question's rule has its own reason: a crossing inside the node's piece, one
    /// beyond it, a parallel ray off and in the plane, and a ray on the plane at tmin.
    #[test]
    fn every_case_of_the_rule_has_its_reason() {
        let why = |origin: [f64; 2], dir: [f64; 2]| key(&Ray2::new(origin, dir).unwrap()).why_first;
        // Crosses x = 3 at t = 1.25 inside [0, inf]; at x >= 3 y = 3 lies behind (t = -1 < 1.25).
        let general = why([0.5, 2.0], [2.0, -1.0]);
        assert!(general[0].starts_with("x<3 comes first: it is the child the ray is in just after tmin = 0; the ray reaches the plane x = 3 only at t = 1.25, so it is in x<3 until then and in x>=3, the second child, after"), "{general:?}");
        // Parallel to both child planes, below both.
        let parallel = why([4.5, 0.5], [-1.5, 0.0]);
        assert!(parallel[1].starts_with("y<3 comes first: the ray is parallel to the plane y = 3 (d_y = 0) and stays on its origin's side (e_y = 0.5)"), "{parallel:?}");
        // Lying in the root's plane x = 3.
        let lying = why([3.0, 0.5], [0.0, 2.5]);
        assert!(lying[0].starts_with("x>=3 comes first: the ray lies in the plane x = 3 (d_x = 0, e_x = 3), and a point on the plane belongs to the >= side"), "{lying:?}");
        // Starting on x = 3 and moving left: t = -0 = tmin.
        let on_plane = why([3.0, 2.5], [-0.5, -1.0]);
        assert!(on_plane[0].starts_with("x<3 comes first: at tmin = 0 the ray is on the plane x = 3 and moves into x<3 (d_x = -0.5), the side it moves into"), "{on_plane:?}");
        // The homework's (d): at x >= 3 ([0, 2]) the plane y = 3 is met only at t = 3.
        let beyond = why([5.0, 0.0], [-1.0, 1.0]);
        assert!(beyond[1].starts_with("y<3 comes first: it is the child the ray is in just after tmin = 0; the ray would reach the plane y = 3 only at t = 3, not before this node's tmax = 2"), "{beyond:?}");
        for reasons in [general, parallel, lying, on_plane, beyond] {
            assert!(reasons.iter().all(|r| !r.contains("near") && !r.contains("far")), "{reasons:?}");
        }
    }

    /// The descents' method speaks of the first and the second child, by the question's rule.
    #[test]
    fn the_descents_method_speaks_of_first_and_second_children() {
        assert!(TRAVERSAL_METHOD.contains("The first child is the one the ray is in just after tmin"));
        assert!(TRAVERSAL_METHOD.contains("the first child gets [tmin, t] and the second child [t, tmax]"));
        assert!(!TRAVERSAL_METHOD.contains("near") && !TRAVERSAL_METHOD.contains("far"));
    }

    /// Planes are graded node by node. Seed 7, (e): the ray is parallel to the root's plane and
    /// crosses y = 3 at t = 1.5 in x >= 3. A wrong first at the root and a right second plane earn
    /// the second plane's share, as a right root and a wrong second plane earn the root's (under the
    /// old prefix rule the first answer earned nothing).
    #[test]
    fn seed_7_planes_after_a_wrong_first_earn_their_share() {
        let v = variant(7);
        assert!(v.statement.contains("(e) e = (5, 0), d = (0, 2)"), "{}", v.statement);
        let (root_wrong, words) = graded(7, "q3e.planes", |g| flip(&mut g[0].first));
        assert_eq!(root_wrong, 0.5, "{words}");
        assert!(words.contains("first 0 planes right; plane 1: x>=3 comes first: the ray is parallel to the plane x = 3 (d_x = 0) and stays on its origin's side (e_x = 5)"), "{words}");
        assert!(words.ends_with("1 more plane right (each node met earns its own share)"), "{words}");
        let (second_wrong, _) = graded(7, "q3e.planes", |g| flip(&mut g[1].first));
        assert_eq!(second_wrong, 0.5);
    }

    /// A wrong first changes the order of the nodes after it: the order the answer's own firsts
    /// give is accepted, and so is the key's; an extra node, a missing one or one out of both
    /// orders earns nothing, and an extra node costs its share through the count.
    #[test]
    fn planes_order_follows_the_answers_own_firsts() {
        // Seed 7, (d): root (first x>=3), then x>=3, then x<3.
        let (credit, _) = graded(7, "q3d.planes", |g| {
            flip(&mut g[0].first);
            g.swap(1, 2);
        });
        assert!((credit - 2.0 / 3.0).abs() < 1e-12, "the order of the answer's own first: {credit}");
        let (credit, _) = graded(7, "q3d.planes", |g| flip(&mut g[0].first));
        assert!((credit - 2.0 / 3.0).abs() < 1e-12, "the key's order: {credit}");
        let (credit, words) = graded(7, "q3d.planes", |g| g.swap(1, 2));
        assert!((credit - 2.0 / 3.0).abs() < 1e-12, "out of order, firsts right: {credit}");
        assert!(words.contains("plane 2: the traversal splits at [x>=3]"), "{words}");
        let (credit, _) = graded(7, "q3d.planes", |g| {
            g.remove(1);
        });
        assert!((credit - 2.0 / 3.0).abs() < 1e-12, "one missing: {credit}");
        let (credit, _) = graded(7, "q3e.planes", |g| {
            let extra = ExpectedPlane { node: vec!["x<3".into()], t: None, first: "y<1".into() };
            g.insert(1, extra);
        });
        assert!((credit - 2.0 / 3.0).abs() < 1e-12, "one extra: {credit}");
    }
}
