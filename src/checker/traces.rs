//! Grading a kd-tree traversal: its leaves and every descent with its interval, each up to the
//! first divergence (with the error carried forward), and the planes met, node by node; the
//! feedback names the first divergence and why.

use super::key::{ExpectedLeaf, ExpectedPlane};
use super::policy::Rule;

/// Whether a student's bound `a` is the key's `b`: within 10⁻⁶ relative, and `inf` only as `inf`
/// (a finite bound where the ray never leaves the cell is wrong, however large).
pub(super) fn same_bound(a: f64, b: f64) -> bool {
    a == b || (a.is_finite() && b.is_finite() && (a - b).abs() <= 1e-6 * (1.0 + b.abs()))
}

/// A trace's bound as the answers file writes it: `inf`, or the number as [`echo_number`] prints it.
pub(super) fn show_bound(t: f64) -> String {
    if t.is_infinite() { "inf".into() } else { echo_number(t) }
}

/// A number as written: its shortest exact form, with an exponent when very small or large
/// (`5.29862e-12`, not `0.00000000000529862`), and `-0` as `0`, as the answers write it.
pub(super) fn echo_number(x: f64) -> String {
    let x = x + 0.0;
    if x != 0.0 && x.is_finite() && !(1e-4..1e15).contains(&x.abs()) { format!("{x:e}") } else { format!("{x}") }
}

pub(super) fn show_leaf(leaf: &ExpectedLeaf) -> String {
    format!("[{}] t in [{}, {}]", leaf.path.join(", "), show_bound(leaf.t_min), show_bound(leaf.t_max))
}

/// A graded trace: its credit, the feedback, and how many entries earned credit by following
/// from an earlier wrong bound.
pub(super) struct TraceGrade {
    /// Share of the entries right or carried forward, times their rules' credit.
    pub credit: f64,
    /// Every entry right.
    pub exact: bool,
    /// Entries that follow from the student's own earlier wrong plane parameter.
    pub carried: usize,
    /// The first divergence and why.
    pub words: String,
}

fn agree(e: &ExpectedLeaf, g: &ExpectedLeaf) -> bool {
    e.path == g.path && same_bound(g.t_min, e.t_min) && same_bound(g.t_max, e.t_max)
}

/// The entries of the key and of the answer that name the same cell, paired in order so that an
/// extra or a missing entry puts no later one out of step: first the most pairs that agree
/// entirely, then the most that share their cell (a weighted longest common subsequence). So a
/// zero-length piece listed before the right entry of the same cell is the extra one, not the
/// right entry.
fn aligned(expected: &[ExpectedLeaf], given: &[ExpectedLeaf]) -> Vec<(usize, usize)> {
    let (n, m) = (expected.len(), given.len());
    // An agreeing pair outweighs every same-cell pair the trace could hold.
    let whole = n.max(m) + 1;
    let weight = |i: usize, j: usize| match (&expected[i], &given[j]) {
        (e, g) if agree(e, g) => Some(whole + 1),
        (e, g) if e.path == g.path => Some(1),
        _ => None,
    };
    // best[i][j]: the heaviest pairing of expected[i..] with given[j..].
    let mut best = vec![vec![0usize; m + 1]; n + 1];
    for i in (0..n).rev() {
        for j in (0..m).rev() {
            let paired = weight(i, j).map_or(0, |w| w + best[i + 1][j + 1]);
            best[i][j] = paired.max(best[i + 1][j]).max(best[i][j + 1]);
        }
    }
    let (mut i, mut j, mut pairs) = (0, 0, Vec::new());
    while i < n && j < m {
        if weight(i, j).is_some_and(|w| best[i][j] == w + best[i + 1][j + 1]) {
            pairs.push((i, j));
            (i, j) = (i + 1, j + 1);
        } else if best[i][j] == best[i + 1][j] {
            i += 1;
        } else {
            j += 1;
        }
    }
    pairs
}

/// Where the answer first leaves the key, walking the pairing of [`aligned`]: how many entries
/// agree before it (so the divergence is entry `k + 1` of both), and the key's entry and the
/// answer's entry there, either absent when the other is missing or extra.
fn first_divergence<'a>(
    expected: &'a [ExpectedLeaf],
    given: &'a [ExpectedLeaf],
    pairs: &[(usize, usize)],
) -> (usize, Option<&'a ExpectedLeaf>, Option<&'a ExpectedLeaf>) {
    let (mut i, mut j) = (0, 0);
    for &(pi, pj) in pairs {
        if pi > i || pj > j || !agree(&expected[pi], &given[pj]) {
            break;
        }
        (i, j) = (pi + 1, pj + 1);
    }
    // i == j here: the loop advances both together, over agreeing pairs only.
    let (e, g) = match pairs.iter().find(|&&(pi, _)| pi >= i) {
        // The next pair skips a key entry only: that entry is missing.
        Some(&(pi, pj)) if pi > i && pj == j => (expected.get(i), None),
        // It skips an answer entry only: that entry is extra.
        Some(&(pi, pj)) if pi == i && pj > j => (None, given.get(j)),
        // The pair itself disagrees, or both sides skip an entry (a wrong cell), or no pair is
        // left (then what remains on either side).
        _ => (expected.get(i), given.get(j)),
    };
    (i, e, g)
}

/// Whether `given` follows the traversal's method: the key's cells in the key's order, and every
/// bound the key's, or carried from one wrong plane parameter, or that slip itself (a finite value
/// of the same sign where the key's bound is a plane crossing). A wrong, missing or extra cell, a
/// bound kept at 0 or left at infinity where the ray crosses a plane, or two or more wrong
/// crossings (bounds made up to fit) is a mistake of method.
pub(super) fn method_followed(expected: &[ExpectedLeaf], planes: &[(String, f64)], given: &[ExpectedLeaf]) -> bool {
    if expected.len() != given.len() || expected.iter().zip(given).any(|(e, g)| e.path != g.path) {
        return false;
    }
    let is_crossing = |t: f64| planes.iter().any(|(_, pt)| same_bound(t, *pt));
    let mut substituted: Vec<(f64, f64)> = Vec::new();
    for (e, g) in expected.iter().zip(given) {
        for (key, student) in [(e.t_min, g.t_min), (e.t_max, g.t_max)] {
            let carried = substituted.iter().find(|(k, _)| same_bound(key, *k)).map_or(key, |&(_, s)| s);
            if same_bound(student, carried) {
                continue;
            }
            let slip = student.is_finite()
                && (student > 0.0) == (key > 0.0)
                && is_crossing(key)
                && carried == key
                && substituted.is_empty();
            if !slip {
                return false;
            }
            substituted.push((key, student));
        }
    }
    true
}

/// Grades a trace (its leaves, or every descent) entry by entry.
///
/// An entry is right when its cell and bounds are the key's. A wrong *plane parameter* is carried
/// forward: once an entry has a wrong finite, non-zero bound where the key's bound is a plane
/// crossing, later entries are expected with that crossing at the student's value, and an entry
/// that follows earns [`Rule::CarriedForward`]'s credit. A bound kept at 0 or left at `inf` is a
/// mistake of method, not of arithmetic, and is not carried. Entries are paired by cell, in order
/// ([`aligned`]): an extra or a missing cell costs its own share (of the larger of the two counts),
/// not the credit of the entries after it.
pub(super) fn grade_trace(
    expected: &[ExpectedLeaf],
    planes: &[(String, f64)],
    given: &[ExpectedLeaf],
    descents: bool,
) -> TraceGrade {
    let (one, many) = if descents { ("descent", "descents") } else { ("leaf", "leaves") };
    let entries = expected.len().max(given.len()).max(1);
    if expected.len() == given.len() && expected.iter().zip(given).all(|(e, g)| agree(e, g)) {
        return TraceGrade { credit: 1.0, exact: true, carried: 0, words: format!("all {} {many} right", given.len()) };
    }
    let pairs = aligned(expected, given);
    let is_crossing = |t: f64| planes.iter().any(|(_, pt)| same_bound(t, *pt));
    // Key crossing → the student's value for it.
    let mut substituted: Vec<(f64, f64)> = Vec::new();
    let (mut right, mut carried) = (0, 0);
    for (e, g) in pairs.iter().map(|&(i, j)| (&expected[i], &given[j])) {
        if agree(e, g) {
            right += 1;
            continue;
        }
        let carry = |t: f64| substituted.iter().find(|(key, _)| same_bound(t, *key)).map_or(t, |&(_, s)| s);
        if !substituted.is_empty() && same_bound(g.t_min, carry(e.t_min)) && same_bound(g.t_max, carry(e.t_max)) {
            carried += 1;
            continue;
        }
        for (key, student) in [(e.t_min, g.t_min), (e.t_max, g.t_max)] {
            let slip = student.is_finite() && student != 0.0 && !same_bound(student, key);
            if slip && is_crossing(key) && !substituted.iter().any(|(k, _)| same_bound(*k, key)) {
                substituted.push((key, student));
            }
        }
    }
    let credit = (right as f64 + carried as f64 * Rule::CarriedForward.credit()) / entries as f64;
    let plane_at = |t: f64| planes.iter().find(|(_, pt)| same_bound(t, *pt)).map(|(name, _)| name.clone());
    let (prefix, key_entry, answer_entry) = first_divergence(expected, given, &pairs);
    let reason = match (key_entry, answer_entry) {
        (Some(e), None) if given[prefix..].iter().any(|g| g.path == e.path) => format!(
            "{one} {} out of order: the ray enters {} here, and your list has that cell later",
            prefix + 1,
            show_leaf(e)
        ),
        (Some(e), None) => format!("{one} {} missing: the ray goes on into {}", prefix + 1, show_leaf(e)),
        (None, Some(g)) if g.t_min == g.t_max => format!(
            "{one} {} is extra: {} has no length, and a piece of zero length is not entered",
            prefix + 1,
            show_leaf(g)
        ),
        (None, Some(g)) if prefix == expected.len() => {
            format!("{one} {} is extra: the ray has left the tree's last cell ({})", prefix + 1, show_leaf(g))
        }
        (None, Some(g)) => format!("{one} {} is extra: the ray does not enter {} there", prefix + 1, show_leaf(g)),
        (Some(e), Some(g)) if e.path != g.path => {
            format!("{one} {}: wrong cell: the ray is in {}, not [{}]", prefix + 1, show_leaf(e), g.path.join(", "))
        }
        (Some(e), Some(g)) if !same_bound(g.t_min, e.t_min) => {
            let why = if g.t_min == 0.0 {
                "you kept tmin at 0 after crossing the plane".to_string()
            } else if let Some(name) = plane_at(g.t_min) {
                format!("t = {} is where the ray crosses {name}, not where it enters this cell", g.t_min)
            } else {
                "tmin is where the ray enters this cell".to_string()
            };
            format!("{one} {} [{}]: tmin should be {}: {why}", prefix + 1, e.path.join(", "), show_bound(e.t_min))
        }
        (Some(e), Some(g)) => {
            let why = if g.t_max.is_infinite() {
                "the interval was not clipped at the plane the ray leaves by".to_string()
            } else if e.t_max.is_infinite() {
                "the ray does not leave this cell by any plane".to_string()
            } else if let Some(name) = plane_at(g.t_max) {
                format!("t = {} is where the ray crosses {name}, not where it leaves this cell", g.t_max)
            } else {
                "tmax is where the ray leaves this cell".to_string()
            };
            format!("{one} {} [{}]: tmax should be {}: {why}", prefix + 1, e.path.join(", "), show_bound(e.t_max))
        }
        (None, None) => unreachable!("a divergence exists when the lengths or a leaf differ"),
    };
    let follow = match carried {
        0 => String::new(),
        1 => format!("; 1 later {one} follows from that bound (error carried forward)"),
        n => format!("; {n} later {many} follow from that bound (error carried forward)"),
    };
    TraceGrade { credit, exact: false, carried, words: format!("first {prefix} {many} right; {reason}{follow}") }
}

fn show_t(t: Option<f64>) -> String {
    t.map_or_else(|| "parallel".to_string(), show_bound)
}

pub(super) fn show_plane(step: &ExpectedPlane) -> String {
    let node = if step.node.is_empty() { "root".to_string() } else { step.node.join(", ") };
    format!("[{node}] t = {} first {}", show_t(step.t), step.first)
}

/// The key's planes in the depth-first order the answer's own `first`s give: at each node the
/// child the answer names first (the key's first where the answer lists no such node) comes with
/// its whole subtree before its sibling. With the answer's firsts right, this is the key's order.
fn order_by_answer<'a>(expected: &'a [ExpectedPlane], given: &[ExpectedPlane]) -> Vec<&'a ExpectedPlane> {
    let first_at =
        |node: &[String]| given.iter().chain(expected).find(|p| p.node.as_slice() == node).map(|p| p.first.as_str());
    // A node's place in the order: at each level of its path, 0 for the first child, 1 for the second.
    let rank = |plane: &ExpectedPlane| -> Vec<u8> {
        (0..plane.node.len())
            .map(|level| u8::from(first_at(&plane.node[..level]) != Some(&plane.node[level])))
            .collect()
    };
    let mut order: Vec<&ExpectedPlane> = expected.iter().collect();
    order.sort_by_key(|p| rank(p));
    order
}

/// How many of `given`'s entries are right and stand in the order `order`: the largest number of
/// entries, each the same node as an entry of `order` with the same `t` and the same first child,
/// that appear in both lists in the same order.
fn right_in_order(
    order: &[&ExpectedPlane],
    given: &[ExpectedPlane],
    right: impl Fn(&ExpectedPlane, &ExpectedPlane) -> bool,
) -> usize {
    // best[j]: the most right entries matched among the key's entries so far and given[..j].
    let mut best = vec![0usize; given.len() + 1];
    for e in order {
        let mut next = vec![0usize; given.len() + 1];
        for (j, g) in given.iter().enumerate() {
            let matched = if right(e, g) { best[j] + 1 } else { 0 };
            next[j + 1] = next[j].max(best[j + 1]).max(matched);
        }
        best = next;
    }
    best[given.len()]
}

/// Credit for the planes of a trace, and the feedback: the first divergence and why.
///
/// Each plane is a node the ray meets, with its own `t` and its own first child, so each is graded
/// on its own: an entry earns its share (of the larger of the key's and the answer's counts) when
/// it names a node the ray meets, with that node's `t` and first child, in depth-first order. The
/// order is the key's, or the one the answer's own firsts give: a wrong `first` changes the order
/// of the nodes after it, and it is charged once, at its node. An extra node, a missing one or one
/// out of order earns nothing. `why_first` holds the reason each key step's first child is first
/// (the question's rule in that node's numbers), for the feedback on a wrong `first`.
///
/// A wrong `t` is charged at its node only: `followed` holds the planes as they follow from the
/// answer's own plane parameters (each node with its right `t`), and when they earn more, the
/// nodes and first children the slip changed below it are graded against them; the third value
/// says so (error carried forward).
pub(super) fn grade_planes(
    expected: &[ExpectedPlane],
    why_first: &[String],
    given: &[ExpectedPlane],
    followed: &[ExpectedPlane],
) -> (f64, String, bool) {
    let same_t = |a: Option<f64>, b: Option<f64>| match (a, b) {
        (None, None) => true,
        (Some(a), Some(b)) => same_bound(a, b),
        _ => false,
    };
    let agree = |e: &ExpectedPlane, g: &ExpectedPlane| e.node == g.node && same_t(g.t, e.t) && e.first == g.first;
    let prefix = expected.iter().zip(given).take_while(|(e, g)| agree(e, g)).count();
    if prefix == expected.len() && prefix == given.len() {
        return (1.0, format!("all {prefix} planes right"), false);
    }
    let key_order: Vec<&ExpectedPlane> = expected.iter().collect();
    let right = [key_order, order_by_answer(expected, given)]
        .iter()
        .map(|order| right_in_order(order, given, agree))
        .max()
        .unwrap_or(0);
    let shares = expected.len().max(given.len()).max(1);
    let followed_order: Vec<&ExpectedPlane> = followed.iter().collect();
    let right_followed = right_in_order(&followed_order, given, agree);
    // A slip that cuts a branch off leaves fewer nodes to list: each wrong entry still costs one
    // share of the longest of the three lists, as a node of the key would.
    let wrong_followed = followed.len().max(given.len()) - right_followed;
    let shares_followed = shares.max(followed.len());
    // Kept only when it earns more, compared as fractions: right/shares against
    // (shares_followed − wrong_followed)/shares_followed.
    let carried = (shares_followed - wrong_followed) * shares > right * shares_followed;
    let (right, credit) = if carried {
        (right_followed, (shares_followed - wrong_followed) as f64 / shares_followed as f64)
    } else {
        (right, right as f64 / shares as f64)
    };
    let n = prefix + 1;
    let reason = match (expected.get(prefix), given.get(prefix)) {
        (Some(e), None) => format!("plane {n} missing: the traversal goes on to {}", show_plane(e)),
        (None, Some(g)) => format!("plane {n} is extra: the traversal has no more nodes ({})", show_plane(g)),
        (Some(e), Some(g)) if e.node != g.node => {
            format!("plane {n}: the traversal splits at {} next, not at [{}]", show_plane(e), g.node.join(", "))
        }
        (Some(e), Some(g)) if !same_t(g.t, e.t) => match (e.t, g.t) {
            (None, _) => format!(
                "plane {n}: the ray is parallel to this plane, so there is no t (write \"parallel\"): it stays on its origin's side"
            ),
            (Some(t), None) => {
                format!("plane {n}: the ray is not parallel to this plane: t = (s - e_a)/d_a = {}", show_bound(t))
            }
            (Some(t), Some(given_t)) if same_bound(-given_t, t) => {
                format!("plane {n}: sign error: t = (s - e_a)/d_a = {}, not (e_a - s)/d_a", show_bound(t))
            }
            (Some(t), Some(_)) => format!("plane {n}: t = (s - e_a)/d_a = {}", show_bound(t)),
        },
        (Some(e), Some(_)) => match why_first.get(prefix) {
            Some(why) => format!("plane {n}: {why}"),
            None => format!("plane {n}: {} comes first: it is the child the ray is in just after tmin", e.first),
        },
        (None, None) => unreachable!("a divergence exists when the lengths or a step differ"),
    };
    let more = match (right.saturating_sub(prefix), carried) {
        (0, _) => String::new(),
        (1, false) => "; 1 more plane right (each node met earns its own share)".to_string(),
        (k, false) => format!("; {k} more planes right (each node met earns its own share)"),
        (1, true) => "; 1 more plane right as it follows from your t (error carried forward)".to_string(),
        (k, true) => format!("; {k} more planes right as they follow from your t (error carried forward)"),
    };
    (credit, format!("first {prefix} planes right; {reason}{more}"), carried)
}
