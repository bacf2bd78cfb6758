//! The student's answers to Q3 encoded as data — the handwritten traces of cases (d) and (e) and a
//! literal transcription of its rules (b)/(c) — and the step-by-step comparison with ours.
//!
//! Nothing here is trusted: the tests in this file and in the chapter decide, by checking where
//! the ray really is, which side of every disagreement is right.

use super::{Axis2, Branch, Interval, LeafVisit, Ray2, Step};
use crate::kdtree::Side;
use std::fmt;

const INF: f64 = f64::INFINITY;

/// One of the student's worked cases: its label, its ray, and the student's handwritten steps.
///
/// # Examples
/// ```
/// let cases = hw3::q3_kd_traversal::student::cases();
/// assert_eq!(cases.iter().map(|c| c.label).collect::<Vec<_>>(), ["d", "e"]);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct StudentCase {
    /// The homework's sub-question (`"d"`, `"e"`).
    pub label: &'static str,
    /// The case's ray `e + d t`.
    pub ray: Ray2,
    /// The student's steps, in the student's order (planes and descents; the student names no leaves).
    pub handwritten: Vec<Step>,
}

fn branch(axis: Axis2, side: Side, split: f64) -> Branch {
    Branch { axis, side, split }
}

fn plane(path: &[Branch], axis: Axis2, split: f64, t: f64) -> Step {
    Step::Plane { path: path.to_vec(), axis, split, t: Some(t) }
}

fn descend(path: &[Branch], t_min: f64, t_max: f64) -> Step {
    Step::Descend { path: path.to_vec(), interval: Interval { t_min, t_max } }
}

/// The student's cases (d) and (e), with the handwritten traces transcribed step by step. The
/// student names each branch by its last condition only ("descend y<3 branch"); the full path is the one
/// its preceding steps lead to.
///
/// # Examples
/// ```
/// let cases = hw3::q3_kd_traversal::student::cases();
/// assert_eq!(cases[0].ray.origin, [5.0, 0.0]);
/// assert_eq!(cases[0].handwritten.len(), 7);
/// ```
#[must_use]
pub fn cases() -> Vec<StudentCase> {
    let x_lo = branch(Axis2::X, Side::Lower, 3.0);
    let x_hi = branch(Axis2::X, Side::Upper, 3.0);
    let d = StudentCase {
        label: "d",
        ray: Ray2 { origin: [5.0, 0.0], dir: [-1.0, 1.0] },
        handwritten: vec![
            plane(&[], Axis2::X, 3.0, 2.0),
            descend(&[x_hi], 0.0, 2.0),
            plane(&[x_hi], Axis2::Y, 3.0, 3.0),
            descend(&[x_hi, branch(Axis2::Y, Side::Lower, 3.0)], 0.0, 2.0),
            descend(&[x_lo], 3.0, INF),
            plane(&[x_lo], Axis2::Y, 1.0, 1.0),
            descend(&[x_lo, branch(Axis2::Y, Side::Upper, 1.0)], 3.0, INF),
        ],
    };
    let e = StudentCase {
        label: "e",
        ray: Ray2 { origin: [2.0, 0.0], dir: [-1.0, -1.0] },
        handwritten: vec![
            plane(&[], Axis2::X, 3.0, -1.0),
            descend(&[x_lo], 0.0, INF),
            plane(&[x_lo], Axis2::Y, 1.0, -1.0),
            descend(&[x_lo, branch(Axis2::Y, Side::Lower, 1.0)], 0.0, INF),
        ],
    };
    vec![d, e]
}

/// One row of the step-by-step comparison: our step and the student's at the same position
/// (leaf steps, which the student does not write, are left out of ours).
///
/// # Examples
/// ```
/// use hw3::q3_kd_traversal::{Node2, student, traverse};
/// let case = &student::cases()[0]; // (d)
/// let rows = student::compare(&traverse(&Node2::homework(), &case.ray), &case.handwritten);
/// assert_eq!(rows[0].index, 1);
/// assert!(rows[0].agrees()); // both start with the root plane at t = 2
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct StepComparison {
    /// 1-based position.
    pub index: usize,
    /// Our step, if the trace is that long.
    pub ours: Option<Step>,
    /// The student's step, if the student wrote that many.
    pub student: Option<Step>,
}

impl StepComparison {
    /// Whether both sides wrote the same step.
    ///
    /// # Examples
    /// ```
    /// use hw3::q3_kd_traversal::{Node2, student, traverse};
    /// let case = &student::cases()[0]; // (d)
    /// let rows = student::compare(&traverse(&Node2::homework(), &case.ray), &case.handwritten);
    /// assert!(!rows[4].agrees()); // step 5: [2, inf] vs the student's [3, inf]
    /// ```
    #[must_use]
    pub fn agrees(&self) -> bool {
        self.ours == self.student
    }
}

impl fmt::Display for StepComparison {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let show = |step: &Option<Step>| {
            step.as_ref().map_or_else(|| "(none)".to_owned(), |s| s.to_string().trim().to_owned())
        };
        let verdict = if self.agrees() { "agree" } else { "DIFFER" };
        write!(f, "step {}: {verdict}: ours `{}`, student `{}`", self.index, show(&self.ours), show(&self.student))
    }
}

/// Compares our trace with the student's handwritten steps position by position.
///
/// # Examples
/// ```
/// use hw3::q3_kd_traversal::{Node2, student, traverse};
/// let case = &student::cases()[1]; // (e)
/// let rows = student::compare(&traverse(&Node2::homework(), &case.ray), &case.handwritten);
/// assert!(rows.iter().all(|row| row.agrees()));
/// ```
#[must_use]
pub fn compare(ours: &super::Trace, handwritten: &[Step]) -> Vec<StepComparison> {
    let ours: Vec<&Step> = ours.steps.iter().filter(|s| !matches!(s, Step::Leaf { .. })).collect();
    (0..ours.len().max(handwritten.len()))
        .map(|i| StepComparison {
            index: i + 1,
            ours: ours.get(i).map(|s| (*s).clone()),
            student: handwritten.get(i).cloned(),
        })
        .collect()
}

/// The student's rules taken literally, on the homework tree: rule (b) at the root (near side by
/// `e_x ≥ 3`, crossing only if `t > 0`), rule (c) at both children ("the right branch is handled
/// similarly": the `y = 3` node uses (c) with 3 for 1), including its `else // dy < 0` branch
/// for `d_y = 0` and its strict `t < tmin` / `t > tmax` tests. Kept only to check the student's rules;
/// the crate traverses with [`crate::kdtree::split_interval`].
///
/// # Examples
/// ```
/// use hw3::q3_kd_traversal::{Ray2, student::literal_leaves};
/// let leaves = literal_leaves(&Ray2::new([2.0, 0.0], [-1.0, -1.0]).unwrap());
/// assert_eq!(leaves.len(), 1);
/// ```
#[must_use]
pub fn literal_leaves(ray: &Ray2) -> Vec<LeafVisit> {
    let [ex, ey] = ray.origin;
    let [dx, dy] = ray.dir;
    let t = (3.0 - ex) / dx;
    let x_children: Vec<(Side, f64, f64)> = match (ex >= 3.0, t > 0.0) {
        (true, true) => vec![(Side::Upper, 0.0, t), (Side::Lower, t, INF)],
        (true, false) => vec![(Side::Upper, 0.0, INF)],
        (false, true) => vec![(Side::Lower, 0.0, t), (Side::Upper, t, INF)],
        (false, false) => vec![(Side::Lower, 0.0, INF)],
    };
    let mut leaves = Vec::new();
    for (x_side, t_min, t_max) in x_children {
        let y_split = if x_side == Side::Lower { 1.0 } else { 3.0 };
        let t = (y_split - ey) / dy;
        let (first, second) = if dy > 0.0 { (Side::Lower, Side::Upper) } else { (Side::Upper, Side::Lower) };
        let y_children = if t < t_min {
            vec![(second, t_min, t_max)]
        } else if t > t_max {
            vec![(first, t_min, t_max)]
        } else {
            vec![(first, t_min, t), (second, t, t_max)]
        };
        for (y_side, t_min, t_max) in y_children {
            leaves.push(LeafVisit {
                path: vec![branch(Axis2::X, x_side, 3.0), branch(Axis2::Y, y_side, y_split)],
                interval: Interval { t_min, t_max },
            });
        }
    }
    leaves
}

#[cfg(test)]
mod tests {
    use super::super::{Cell, Node2, traverse};
    use super::*;

    /// Whether the ray really lies in the leaf's cell over the leaf's interval (sampled at the
    /// ends' neighbourhoods and inside; an empty interval holds nothing and fails).
    fn interval_holds_ray(ray: &Ray2, leaf: &LeafVisit) -> bool {
        let Interval { t_min, t_max } = leaf.interval;
        if !(t_min < t_max) {
            return false;
        }
        let cell = Cell { path: leaf.path.clone() };
        let end = if t_max.is_finite() { t_max } else { t_min + 64.0 };
        (0..64).all(|k| cell.contains(ray.at(t_min + (end - t_min) * (f64::from(k) + 0.5) / 64.0)))
    }

    #[test]
    fn comparison_tables_are_pinned() {
        let _guard = crate::testing::insta_settings().bind_to_scope();
        for case in cases() {
            let rows = compare(&traverse(&Node2::homework(), &case.ray), &case.handwritten);
            let text: Vec<String> = rows.iter().map(ToString::to_string).collect();
            insta::assert_snapshot!(format!("q3_compare_{}", case.label), text.join("\n"));
        }
    }

    #[test]
    fn case_d_differs_exactly_at_the_x_lower_branch_and_the_student_is_wrong_there() {
        let case = &cases()[0];
        let rows = compare(&traverse(&Node2::homework(), &case.ray), &case.handwritten);
        let differing: Vec<usize> = rows.iter().filter(|r| !r.agrees()).map(|r| r.index).collect();
        assert_eq!(differing, [5, 7]);
        // The student's [3, inf] for x<3 leaves t in (2, 3) in no leaf, yet the ray is then in the
        // x<3, y>=1 cell: at t = 2.5 it is at (2.5, 2.5).
        let cell = Cell { path: vec![branch(Axis2::X, Side::Lower, 3.0), branch(Axis2::Y, Side::Upper, 1.0)] };
        assert_eq!(case.ray.at(2.5), [2.5, 2.5]);
        assert!(cell.contains(case.ray.at(2.5)));
        // And that piece begins at t = 2, the root plane's t, not the y = 3 plane's t = 3: just after
        // t = 2 the ray is in the cell, just before it is not (at t = 2 it is on x = 3, which
        // belongs to x>=3).
        assert!(cell.contains(case.ray.at(2.0 + 1e-9)));
        assert!(!cell.contains(case.ray.at(2.0)));
        assert!(!cell.contains(case.ray.at(2.0 - 1e-9)));
    }

    #[test]
    fn case_e_agrees_step_by_step() {
        let case = &cases()[1];
        let rows = compare(&traverse(&Node2::homework(), &case.ray), &case.handwritten);
        assert_eq!(rows.len(), 4);
        assert!(rows.iter().all(StepComparison::agrees));
    }

    #[test]
    fn literal_rules_agree_with_ours_on_both_cases() {
        for case in cases() {
            assert_eq!(literal_leaves(&case.ray), traverse(&Node2::homework(), &case.ray).leaves());
        }
    }

    /// Origin on x = 3 heading to x < 3: rule (b) computes t = −0, fails `t > 0`, and sends the ray
    /// into x ≥ 3 for ever, though it is in x < 3 for every t > 0.
    #[test]
    fn literal_rule_b_misroutes_an_origin_on_the_root_plane() {
        let ray = Ray2::new([3.0, 0.0], [-1.0, 0.5]).unwrap();
        let literal = literal_leaves(&ray);
        assert!(literal.iter().any(|leaf| !interval_holds_ray(&ray, leaf)));
        let ours = traverse(&Node2::homework(), &ray).leaves();
        assert!(ours.iter().all(|leaf| interval_holds_ray(&ray, leaf)));
    }

    /// d_y = +0 under y = 3: rule (c)'s `else // dy < 0` branch gets t = +inf, which is neither
    /// `< tmin` nor `> tmax = inf`, so it descends y ≥ 3 over the whole interval — a cell the
    /// ray (at y = 0) never enters — and adds an empty [inf, inf] visit of y < 3.
    #[test]
    fn literal_rule_c_misroutes_a_horizontal_ray_with_positive_zero() {
        let ray = Ray2::new([5.0, 0.0], [1.0, 0.0]).unwrap();
        let literal = literal_leaves(&ray);
        assert!(literal.iter().any(|leaf| !interval_holds_ray(&ray, leaf)));
        assert_eq!(literal.len(), 2);
        // With −0 the same ray is routed correctly by the literal rule (t = −inf < tmin).
        let negative_zero = Ray2::new([5.0, 0.0], [1.0, -0.0]).unwrap();
        assert!(literal_leaves(&negative_zero).iter().all(|leaf| interval_holds_ray(&negative_zero, leaf)));
        let ours = traverse(&Node2::homework(), &ray).leaves();
        assert_eq!(ours.len(), 1);
        assert!(ours.iter().all(|leaf| interval_holds_ray(&ray, leaf)));
    }

    /// Away from ties (random real coordinates) the literal rules and ours agree exactly.
    #[test]
    fn literal_rules_agree_with_ours_on_generic_rays() {
        let mut rng = crate::rng::seeded(3, 0);
        let mut uniform = |lo: f64, hi: f64| crate::rng::uniform_in(&mut rng, lo, hi);
        for _ in 0..10_000 {
            let ray = Ray2::new([uniform(-5.0, 10.0), uniform(-5.0, 10.0)], [uniform(-1.0, 1.0), uniform(-1.0, 1.0)])
                .unwrap();
            assert_eq!(literal_leaves(&ray), traverse(&Node2::homework(), &ray).leaves());
        }
    }
}
