//! Error carried forward: a later part's key recomputed from the student's own earlier answer.

use super::key::{Derivation, Expected, ExpectedLeaf, ExpectedPlane};
use super::reading::Given;
use super::traces::{method_followed, same_bound};
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
            Derivation::DescentsFromPlanes { planes: key },
            Given::Planes(given),
            Expected::Trace { leaves: descents, planes: crossings, descents: true },
        ) => descents_with(key, given, descents).map(|leaves| Expected::Trace {
            leaves,
            planes: crossings.clone(),
            descents: true,
        }),
        (Derivation::LeavesFromDescents { descents: key }, Given::Trace(descents), Expected::Trace { planes, .. }) => {
            method_followed(key, planes, descents).then(|| Expected::Trace {
                leaves: leaves_of(descents),
                planes: planes.clone(),
                descents: false,
            })
        }
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

/// The key's descents with each plane parameter the student got wrong replaced by the student's
/// value, where the student's planes are the key's nodes and first children in the key's order
/// and differ only in finite, non-zero values of `t`; `None` when they differ in anything else.
fn descents_with(
    key: &[ExpectedPlane],
    given: &[ExpectedPlane],
    descents: &[ExpectedLeaf],
) -> Option<Vec<ExpectedLeaf>> {
    if key.len() != given.len() {
        return None;
    }
    let mut substituted: Vec<(f64, f64)> = Vec::new();
    for (k, g) in key.iter().zip(given) {
        if k.node != g.node || k.first != g.first {
            return None;
        }
        match (k.t, g.t) {
            (None, None) => {}
            (Some(kt), Some(gt)) if same_bound(gt, kt) => {}
            (Some(kt), Some(gt)) if gt.is_finite() && gt != 0.0 => substituted.push((kt, gt)),
            _ => return None,
        }
    }
    let with = |t: f64| substituted.iter().find(|(k, _)| same_bound(t, *k)).map_or(t, |&(_, g)| g);
    Some(
        descents
            .iter()
            .map(|d| ExpectedLeaf { path: d.path.clone(), t_min: with(d.t_min), t_max: with(d.t_max) })
            .collect(),
    )
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
