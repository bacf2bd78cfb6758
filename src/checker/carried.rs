//! Error carried forward: a later part's key recomputed from the student's own earlier answer.

use super::key::{Derivation, Expected, ExpectedLeaf, ExpectedPlane};
use super::reading::Given;
use super::traces::{method_followed, same_bound};
use crate::kdtree::{AxisLine, QuotientAxis, Side};
use crate::q3_kd_traversal::{Branch, Node2, Ray2, Step, traverse_with};
use glam::DVec3;

/// The later part's key as it would be from `earlier` (the student's answer to the part it
/// follows from), compared with the later part's own tolerance; `None` when the earlier answer
/// gives nothing to compute from (missing, "none", a zero vector).
pub(super) fn recompute(derivation: &Derivation, earlier: &Given, later: &Expected) -> Option<Expected> {
    let later = match later {
        Expected::OrNone { value, none: false } => value.as_ref(),
        other => other,
    };
    match (derivation, earlier, later) {
        (Derivation::PointFromT { origin, dir }, Given::Number(t), Expected::Vector { rtol, atol, .. }) => {
            let point = DVec3::from_array(*origin) + DVec3::from_array(*dir) * *t;
            Some(Expected::Vector { value: point.to_array(), rtol: *rtol, atol: *atol })
        }
        (Derivation::NormalFromPoint { center }, Given::Vector(point), Expected::Direction { angle_tol, .. }) => {
            let normal = (DVec3::from_array(*point) - DVec3::from_array(*center)).try_normalize()?;
            Some(Expected::Direction { value: normal.to_array(), angle_tol: *angle_tol })
        }
        (Derivation::ReflectionFromNormal { dir }, Given::Vector(normal), Expected::Direction { angle_tol, .. }) => {
            let n = DVec3::from_array(*normal).try_normalize()?;
            let d = DVec3::from_array(*dir).normalize();
            let reflected = d - n * (2.0 * n.dot(d));
            Some(Expected::Direction { value: reflected.to_array(), angle_tol: *angle_tol })
        }
        (Derivation::LostFromHalfAngle, Given::Number(degrees), Expected::Number { rtol, atol, .. }) => {
            let lost = degrees.to_radians().sin().powi(2);
            Some(Expected::Number { value: lost, rtol: *rtol, atol: *atol })
        }
        (
            Derivation::DescentsFromPlanes { origin, dir },
            Given::Planes(given),
            Expected::Trace { planes: crossings, descents: true, .. },
        ) => descents_following(*origin, *dir, given).map(|leaves| Expected::Trace {
            leaves,
            planes: crossings.clone(),
            descents: true,
        }),
        (
            Derivation::LeavesFromPlanes { origin, dir },
            Given::Planes(given),
            Expected::Trace { planes: crossings, descents: false, .. },
        ) => descents_following(*origin, *dir, given).map(|descents| Expected::Trace {
            leaves: leaves_of(&descents),
            planes: crossings.clone(),
            descents: false,
        }),
        (
            Derivation::LeavesFromDescents { descents: key, origin, dir },
            Given::Trace(descents),
            Expected::Trace { planes, .. },
        ) => (method_followed(key, planes, descents) || is_a_traversal(*origin, *dir, descents))
            .then(|| Expected::Trace { leaves: leaves_of(descents), planes: planes.clone(), descents: false }),
        (Derivation::MissedFromVerdict { effect }, Given::Choice { answer, .. }, Expected::Paths { .. }) => {
            match answer.as_str() {
                "yes" => Some(Expected::Paths { value: "none".into() }),
                "no" | "impractical" => Some(Expected::Paths { value: (*effect).to_string() }),
                _ => None,
            }
        }
        _ => None,
    }
}

/// The traversal of the ray `origin + t dir` through the homework's tree as a student makes it
/// who takes `plane_t` at a node instead of computing it: its planes (each with the `t` used, and
/// the node's right `t`) and its descents.
fn traversal_with(
    origin: [f64; 2],
    dir: [f64; 2],
    plane_t: &dyn Fn(&[Branch]) -> Option<f64>,
) -> (Vec<(ExpectedPlane, Option<f64>)>, Vec<ExpectedLeaf>) {
    let names = |path: &[Branch]| path.iter().map(ToString::to_string).collect::<Vec<_>>();
    let ray = Ray2 { origin, dir };
    let trace = traverse_with(&Node2::homework(), &ray, plane_t);
    let (mut planes, mut descents) = (Vec::new(), Vec::new());
    for (i, step) in trace.steps.iter().enumerate() {
        match step {
            Step::Plane { path, axis, split, t } => {
                let Some(Step::Descend { path: child, .. }) = trace.steps.get(i + 1) else { continue };
                let first = child.last().map(ToString::to_string).unwrap_or_default();
                let a = axis.index();
                let right_t = t.map(|_| QuotientAxis::new(origin[a], dir[a]).plane_t(*split));
                planes.push((ExpectedPlane { node: names(path), t: *t, first }, right_t));
            }
            Step::Descend { path, interval } => {
                descents.push(ExpectedLeaf { path: names(path), t_min: interval.t_min, t_max: interval.t_max });
            }
            Step::Leaf { .. } => {}
        }
    }
    (planes, descents)
}

/// The planes as they follow from the student's own plane parameters: the nodes met and the
/// first children of the traversal taken with every finite `t` the student gives (at its node),
/// each node with its right `t` (or none for a parallel ray), so that grading against them charges
/// a wrong `t` at its node and nowhere below it.
pub(super) fn planes_following(origin: [f64; 2], dir: [f64; 2], given: &[ExpectedPlane]) -> Vec<ExpectedPlane> {
    let (planes, _) = traversal_with(origin, dir, &|path| given_t(origin, dir, given, path));
    planes.into_iter().map(|(plane, right_t)| ExpectedPlane { t: right_t, ..plane }).collect()
}

/// The student's finite `t` at the node `path`, if the student's planes name that node, unless it
/// is the right `t` with its sign flipped: `(e_a − s)/d_a` is a wrong formula, a mistake of
/// method, and what follows from it is not carried.
fn given_t(origin: [f64; 2], dir: [f64; 2], given: &[ExpectedPlane], path: &[Branch]) -> Option<f64> {
    let node: Vec<String> = path.iter().map(ToString::to_string).collect();
    let t = given.iter().find(|p| p.node == node).and_then(|p| p.t).filter(|t| t.is_finite())?;
    (!flipped_sign(origin, dir, path, t)).then_some(t)
}

/// Whether `t` is the negative of the right plane parameter at the node `path` (and not the right
/// one itself, as 0 is).
fn flipped_sign(origin: [f64; 2], dir: [f64; 2], path: &[Branch], t: f64) -> bool {
    let Some(right) = right_t(origin, dir, path) else { return false };
    same_bound(-t, right) && !same_bound(t, right)
}

/// The right plane parameter of the homework tree's node at `path`: `(s − e_a)/d_a`, or `None`
/// for a parallel ray or a leaf.
fn right_t(origin: [f64; 2], dir: [f64; 2], path: &[Branch]) -> Option<f64> {
    let tree = Node2::homework();
    let node = path.iter().fold(&tree, |node, branch| match (node, branch.side) {
        (Node2::Split { lower, .. }, Side::Lower) => lower,
        (Node2::Split { upper, .. }, Side::Upper) => upper,
        (leaf, _) => leaf,
    });
    let Node2::Split { axis, split, .. } = node else { return None };
    let line = QuotientAxis::new(origin[axis.index()], dir[axis.index()]);
    (!line.is_parallel()).then(|| line.plane_t(*split))
}

/// The descents as they follow from the student's planes: the traversal taken with the student's
/// plane parameters (every finite one, at its node), when the student's planes are that
/// traversal's, node for node and first child for first child. A wrong `t` may change which
/// children are visited and which comes first below it; all of that follows. `None` when the
/// planes are not that traversal's (a wrong node or first child, a missing or extra plane, a
/// parallel plane given a `t` or a crossing called parallel): a mistake of method.
fn descents_following(origin: [f64; 2], dir: [f64; 2], given: &[ExpectedPlane]) -> Option<Vec<ExpectedLeaf>> {
    let (planes, descents) = traversal_with(origin, dir, &|path| given_t(origin, dir, given, path));
    let same = planes.len() == given.len()
        && planes.iter().map(|(p, _)| p).zip(given).all(|(p, g)| {
            p.node == g.node
                && p.first == g.first
                && match (p.t, g.t) {
                    (None, None) => true,
                    (Some(a), Some(b)) => same_bound(a, b),
                    _ => false,
                }
        });
    same.then_some(descents)
}

/// Whether `given` is the traversal's list of descents for the plane parameters it shows: at each
/// node where both children are entered, the bound between them; at every other node, the right
/// `t`. The traversal taken with those values must give exactly `given`; a wrong first child, a
/// missing or extra descent, or a bound kept at 0 or left unclipped gives a list it does not.
fn is_a_traversal(origin: [f64; 2], dir: [f64; 2], given: &[ExpectedLeaf]) -> bool {
    let inferred = |path: &[Branch]| -> Option<f64> {
        right_t(origin, dir, path)?;
        let parent: Vec<String> = path.iter().map(ToString::to_string).collect();
        let children: Vec<&ExpectedLeaf> =
            given.iter().filter(|g| g.path.len() == parent.len() + 1 && g.path[..parent.len()] == parent[..]).collect();
        match children.as_slice() {
            [first, _] if !flipped_sign(origin, dir, path, first.t_max) => Some(first.t_max),
            _ => None,
        }
    };
    let (_, descents) = traversal_with(origin, dir, &inferred);
    descents.len() == given.len()
        && descents
            .iter()
            .zip(given)
            .all(|(e, g)| e.path == g.path && same_bound(e.t_min, g.t_min) && same_bound(e.t_max, g.t_max))
}

/// The descents into cells the trace does not split further: a descent is a leaf unless the next
/// descent goes into one of its children.
fn leaves_of(descents: &[ExpectedLeaf]) -> Vec<ExpectedLeaf> {
    descents
        .iter()
        .enumerate()
        .filter(|(i, d)| descents.get(i + 1).is_none_or(|next| !next.path.starts_with(&d.path)))
        .map(|(_, d)| d.clone())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::checker::variant;

    /// Each derivation applied to the key's own earlier answer gives the key's later answer: the
    /// dependency is the one the key itself is computed by.
    #[test]
    fn derivations_reproduce_the_key_from_the_keys_own_answers() {
        let mut checked = 0;
        for question in ["q2", "q3", "q4", "q5"] {
            for seed in 0..40 {
                let v = variant(question, seed).unwrap();
                for follows in &v.follows {
                    let part = |key| v.parts.iter().find(|p| p.key == key).unwrap();
                    let (later, earlier) = (part(follows.key), part(follows.from));
                    let inner = |e: &Expected| match e {
                        Expected::OrNone { value, none: false } => value.as_ref().clone(),
                        other => other.clone(),
                    };
                    let given = match inner(&earlier.expected) {
                        Expected::Number { value, .. } => Given::Number(value),
                        Expected::Vector { value, .. } | Expected::Direction { value, .. } => Given::Vector(value),
                        Expected::Trace { leaves, .. } => Given::Trace(leaves),
                        Expected::Planes { steps, .. } => Given::Planes(steps),
                        Expected::Choice { value, .. } => Given::Choice { answer: value.to_string(), why: None },
                        other => panic!("{question} {seed} {}: {other:?}", follows.from),
                    };
                    let recomputed = recompute(&follows.derivation, &given, &later.expected).unwrap();
                    let key = inner(&later.expected);
                    let close = |a: &[f64; 3], b: &[f64; 3]| a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-9);
                    match (&recomputed, &key) {
                        (Expected::Number { value: a, .. }, Expected::Number { value: b, .. }) => {
                            assert!((a - b).abs() < 1e-9 * b.abs().max(1.0), "{question} {seed}: {a} vs {b}")
                        }
                        (Expected::Vector { value: a, .. }, Expected::Vector { value: b, .. })
                        | (Expected::Direction { value: a, .. }, Expected::Direction { value: b, .. }) => {
                            assert!(close(a, b), "{question} {seed} {}: {a:?} vs {b:?}", follows.key)
                        }
                        (Expected::Trace { leaves: a, .. }, Expected::Trace { leaves: b, .. }) => {
                            assert_eq!(a, b, "{question} {seed}")
                        }
                        (Expected::Paths { value: a }, Expected::Paths { value: b }) => {
                            assert_eq!(a, b, "{question} {seed} {}", follows.key)
                        }
                        other => panic!("{other:?}"),
                    }
                    checked += 1;
                }
            }
        }
        assert!(checked > 100, "{checked}");
    }
}
