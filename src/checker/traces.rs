//! Grading a kd-tree traversal: its leaves, every descent with its interval, and the planes met,
//! each up to the first divergence, with the reason it diverged.

use super::key::{ExpectedLeaf, ExpectedPlane};

pub(super) fn same_bound(a: f64, b: f64) -> bool {
    a == b || (a - b).abs() <= 1e-6 * (1.0 + b.abs())
}

pub(super) fn show_bound(t: f64) -> String {
    if t.is_infinite() { "inf".into() } else { format!("{t}") }
}

pub(super) fn show_leaf(leaf: &ExpectedLeaf) -> String {
    format!("[{}] t in [{}, {}]", leaf.path.join(", "), show_bound(leaf.t_min), show_bound(leaf.t_max))
}

/// Credit for a trace (its leaves, or every descent): the share of entries right before the first divergence, and why it diverged.
pub(super) fn grade_trace(
    expected: &[ExpectedLeaf],
    planes: &[(String, f64)],
    given: &[ExpectedLeaf],
    descents: bool,
) -> (f64, String) {
    let (one, many) = if descents { ("descent", "descents") } else { ("leaf", "leaves") };
    let agree = |e: &ExpectedLeaf, g: &ExpectedLeaf| {
        e.path == g.path && same_bound(g.t_min, e.t_min) && same_bound(g.t_max, e.t_max)
    };
    let prefix = expected.iter().zip(given).take_while(|(e, g)| agree(e, g)).count();
    let credit = prefix as f64 / expected.len().max(given.len()).max(1) as f64;
    if prefix == expected.len() && prefix == given.len() {
        return (1.0, format!("all {prefix} {many} right"));
    }
    let plane_at = |t: f64| planes.iter().find(|(_, pt)| same_bound(t, *pt)).map(|(name, _)| name.clone());
    let reason = match (expected.get(prefix), given.get(prefix)) {
        (Some(e), None) => format!("{one} {} missing: the ray goes on into {}", prefix + 1, show_leaf(e)),
        (None, Some(g)) => {
            format!("{one} {} is extra: the ray has left the tree's last cell ({})", prefix + 1, show_leaf(g))
        }
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
            } else if let Some(name) = plane_at(g.t_max) {
                format!("t = {} is where the ray crosses {name}, not where it leaves this cell", g.t_max)
            } else {
                "tmax is where the ray leaves this cell".to_string()
            };
            format!("{one} {} [{}]: tmax should be {}: {why}", prefix + 1, e.path.join(", "), show_bound(e.t_max))
        }
        (None, None) => unreachable!("a divergence exists when the lengths or a leaf differ"),
    };
    (credit, format!("first {prefix} {many} right; {reason}"))
}

fn show_t(t: Option<f64>) -> String {
    t.map_or_else(|| "parallel".to_string(), show_bound)
}

pub(super) fn show_plane(step: &ExpectedPlane) -> String {
    let node = if step.node.is_empty() { "root".to_string() } else { step.node.join(", ") };
    format!("[{node}] t = {} first {}", show_t(step.t), step.first)
}

/// Credit for the planes of a trace: the share right before the first divergence, and why.
pub(super) fn grade_planes(expected: &[ExpectedPlane], given: &[ExpectedPlane]) -> (f64, String) {
    let same_t = |a: Option<f64>, b: Option<f64>| match (a, b) {
        (None, None) => true,
        (Some(a), Some(b)) => same_bound(a, b),
        _ => false,
    };
    let agree = |e: &ExpectedPlane, g: &ExpectedPlane| e.node == g.node && same_t(g.t, e.t) && e.first == g.first;
    let prefix = expected.iter().zip(given).take_while(|(e, g)| agree(e, g)).count();
    let credit = prefix as f64 / expected.len().max(given.len()).max(1) as f64;
    if prefix == expected.len() && prefix == given.len() {
        return (1.0, format!("all {prefix} planes right"));
    }
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
        (Some(e), Some(_)) => format!(
            "plane {n}: {} comes first: the child the ray is in just after tmin (d_a > 0: the lower side; d_a < 0: the \
             upper; a ray starting on the plane goes where it moves; a parallel ray stays on its origin's side, >= on the plane)",
            e.first
        ),
        (None, None) => unreachable!("a divergence exists when the lengths or a step differ"),
    };
    (credit, format!("first {prefix} planes right; {reason}"))
}
