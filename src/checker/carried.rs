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
        // A half-angle of 0 (no blind spot) or of 90° or more is not a cone to lose light in.
        (Derivation::LostFromHalfAngle, Given::Number(degrees), Expected::Number { rtol, atol, .. })
            if *degrees > 0.0 && *degrees < 90.0 =>
        {
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
/// who takes `given_t` at a node instead of computing it: its planes (each with the `t` used, and
/// the node's right `t`) and its descents.
fn traversal_with(
    origin: [f64; 2],
    dir: [f64; 2],
    given_t: &dyn Fn(&[Branch]) -> Option<f64>,
) -> (Vec<(ExpectedPlane, Option<f64>)>, Vec<ExpectedLeaf>) {
    let names = |path: &[Branch]| path.iter().map(ToString::to_string).collect::<Vec<_>>();
    let ray = Ray2 { origin, dir };
    let trace = traverse_with(&Node2::homework(), &ray, given_t);
    let (mut planes, mut descents) = (Vec::new(), Vec::new());
    for (i, step) in trace.steps.iter().enumerate() {
        match step {
            Step::Plane { path, axis, split, t } => {
                let Some(Step::Descend { path: child, .. }) = trace.steps.get(i + 1) else { continue };
                let first = child.last().map(ToString::to_string).unwrap_or_default();
                let right_t = plane_t(origin, dir, axis.index(), *split);
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
/// first children of the traversal taken with the student's slip (see [`Slips`]), each node with
/// its right `t` (or none for a parallel ray), so that grading against them charges a wrong `t`
/// at its node and nowhere below it.
pub(super) fn planes_following(origin: [f64; 2], dir: [f64; 2], given: &[ExpectedPlane]) -> Vec<ExpectedPlane> {
    let slips = Slips::of_planes(origin, dir, given);
    let (planes, _) = traversal_with(origin, dir, &|path| slips.at(path));
    planes.into_iter().map(|(plane, right_t)| ExpectedPlane { t: right_t, ..plane }).collect()
}

/// The wrong plane parameters of an answer that are followed as a slip of arithmetic: one at
/// most, and only a value a slip can give. A `t` of the other sign than the right one (the crossing
/// put on the wrong side of the eye, as the flipped formula `(e_a − s)/d_a` does), or the `t` of
/// another plane or axis of the tree (the wrong term), is a mistake of method; two or more wrong
/// values are no longer a slip (a trace made up to fit invented values would otherwise follow).
/// What is not followed is graded against the key.
struct Slips {
    /// The followed slip: the node (its branch names) and the student's `t` there.
    slip: Option<(Vec<String>, f64)>,
}

impl Slips {
    /// The slip among an answer's planes, if exactly one of its plane parameters is wrong and it is
    /// a slip.
    fn of_planes(origin: [f64; 2], dir: [f64; 2], given: &[ExpectedPlane]) -> Self {
        let wrong: Vec<(Vec<String>, f64)> = given
            .iter()
            .filter_map(|p| {
                let right = right_t_named(origin, dir, &p.node)?;
                let t = p.t?;
                (!same_bound(t, right)).then(|| (p.node.clone(), t))
            })
            .collect();
        Self::of(origin, dir, wrong)
    }

    fn of(origin: [f64; 2], dir: [f64; 2], wrong: Vec<(Vec<String>, f64)>) -> Self {
        let slip = match wrong.as_slice() {
            [(node, t)] if is_slip(origin, dir, node, *t) => Some((node.clone(), *t)),
            _ => None,
        };
        Self { slip }
    }

    /// The `t` the followed traversal takes at the node `path`: the slip there; `None` elsewhere,
    /// where the traversal computes the right one.
    fn at(&self, path: &[Branch]) -> Option<f64> {
        let (slipped, t) = self.slip.as_ref()?;
        (slipped.len() == path.len() && slipped.iter().zip(path).all(|(name, b)| *name == b.to_string())).then_some(*t)
    }
}

/// Where the ray `origin + t dir` meets the plane `p_axis = split`, by the homework's arithmetic
/// (`(s − e_a)/d_a`); `None` for a ray parallel to it.
fn plane_t(origin: [f64; 2], dir: [f64; 2], axis: usize, split: f64) -> Option<f64> {
    let line = QuotientAxis::new(origin[axis], dir[axis]);
    (!line.is_parallel()).then(|| line.plane_t(split))
}

/// Whether the wrong value `t` at `node` can be a slip of arithmetic: finite, of the right value's
/// sign, and neither another node's plane parameter nor this node's split taken on the other axis
/// (the wrong term).
fn is_slip(origin: [f64; 2], dir: [f64; 2], node: &[String], t: f64) -> bool {
    let Some((axis, split)) = split_named(node) else { return false };
    let Some(right) = plane_t(origin, dir, axis, split) else { return false };
    let mut wrong_terms: Vec<f64> = tree_planes().into_iter().filter_map(|(a, s)| plane_t(origin, dir, a, s)).collect();
    wrong_terms.extend(plane_t(origin, dir, 1 - axis, split));
    let wrong_term = wrong_terms.iter().any(|&other| same_bound(t, other) && !same_bound(other, right));
    t.is_finite() && (t > 0.0) == (right > 0.0) && !wrong_term
}

/// The planes of the homework's tree: each split's axis index and value.
fn tree_planes() -> Vec<(usize, f64)> {
    fn walk(node: &Node2, out: &mut Vec<(usize, f64)>) {
        if let Node2::Split { axis, split, lower, upper } = node {
            out.push((axis.index(), *split));
            walk(lower, out);
            walk(upper, out);
        }
    }
    let mut out = Vec::new();
    walk(&Node2::homework(), &mut out);
    out
}

/// The axis index and split value of the homework tree's node named by its branches.
fn split_named(node: &[String]) -> Option<(usize, f64)> {
    let tree = Node2::homework();
    let mut at = &tree;
    for name in node {
        let Node2::Split { axis, split, lower, upper } = at else { return None };
        at = if *name == (Branch { axis: *axis, side: Side::Lower, split: *split }).to_string() {
            lower
        } else if *name == (Branch { axis: *axis, side: Side::Upper, split: *split }).to_string() {
            upper
        } else {
            return None;
        };
    }
    match at {
        Node2::Split { axis, split, .. } => Some((axis.index(), *split)),
        Node2::Leaf => None,
    }
}

/// The right plane parameter of the homework tree's node named by its branches (`["x<3"]`):
/// `(s − e_a)/d_a`, or `None` for a parallel ray, a leaf or a name the tree does not have.
fn right_t_named(origin: [f64; 2], dir: [f64; 2], node: &[String]) -> Option<f64> {
    let (axis, split) = split_named(node)?;
    plane_t(origin, dir, axis, split)
}

/// The descents as they follow from the student's planes: the traversal taken with the student's
/// slip (see [`Slips`]), when the student's planes are that traversal's, node for node and first
/// child for first child. A slip may change which children are visited and which comes first below
/// it; all of that follows. `None` when the planes are not that traversal's (a wrong value that is
/// not a slip, a wrong node or first child, a missing or extra plane, a parallel plane given a `t`
/// or a crossing called parallel): a mistake of method.
fn descents_following(origin: [f64; 2], dir: [f64; 2], given: &[ExpectedPlane]) -> Option<Vec<ExpectedLeaf>> {
    let slips = Slips::of_planes(origin, dir, given);
    let (planes, descents) = traversal_with(origin, dir, &|path| slips.at(path));
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
    // The plane parameters the descents show: the bound between a node's two children.
    let shown: Vec<(Vec<String>, f64)> = given
        .iter()
        .filter_map(|g| {
            let (_, parent) = g.path.split_last()?;
            let second = given
                .iter()
                .find(|h| h.path.len() == g.path.len() && h.path.starts_with(parent) && h.path != g.path)?;
            let first_here = given.iter().position(|h| h == g) < given.iter().position(|h| h == second);
            first_here.then(|| (parent.to_vec(), g.t_max))
        })
        .collect();
    let wrong: Vec<(Vec<String>, f64)> = shown
        .into_iter()
        .filter(|(node, t)| right_t_named(origin, dir, node).is_some_and(|right| !same_bound(*t, right)))
        .collect();
    if wrong.len() > 1 {
        return false;
    }
    let slips = Slips::of(origin, dir, wrong);
    let (_, descents) = traversal_with(origin, dir, &|path| slips.at(path));
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
