//! Q3 worked: at every split the plane's `t`, which child comes first and why, every interval
//! descended, and the leaves reached.
//!
//! The steps are the traversal's own trace ([`traverse`], as `hw3 kd-trace` prints it); at each
//! plane the visit is explained by the same interval rule the traversal applied
//! ([`split_interval`]).

use super::text::{num, operand};
use super::{Section, Step, Value};
use crate::checker::{ExpectedLeaf, ExpectedPlane};
use crate::kdtree::{QuotientAxis, Visit, split_interval};
use crate::q3_kd_traversal::{Branch, Interval, Node2, Ray2, Step as TraceStep, traverse};

/// The parts, each with the statement's label of its ray: its planes, descents and leaves.
const PARTS: [(char, [&str; 3]); 2] =
    [('d', ["q3d.planes", "q3d.descents", "q3d.leaves"]), ('e', ["q3e.planes", "q3e.descents", "q3e.leaves"])];

fn path_text(path: &[Branch]) -> String {
    if path.is_empty() { "root".into() } else { path.iter().map(ToString::to_string).collect::<Vec<_>>().join(", ") }
}

fn interval_text(i: Interval) -> String {
    format!("[{}, {}]", num(i.t_min), num(i.t_max))
}

/// Why the traversal visits what it visits at the plane `axis = split` of a node whose ray
/// interval is `interval`.
fn visit_text(ray: &Ray2, axis: crate::q3_kd_traversal::Axis2, split: f64, interval: Interval) -> String {
    let a = axis.index();
    let (e, d) = (ray.origin[a], ray.dir[a]);
    let decision = split_interval(QuotientAxis::new(e, d), split, interval.t_min, interval.t_max);
    let child = |side| Branch { axis, side, split }.to_string();
    let Some(t) = decision.t_plane else {
        let Visit::Only(side) = decision.visit else { unreachable!("a parallel ray visits one child") };
        return format!(
            "d_{axis} = 0: the ray is parallel to the plane (no division); e_{axis} = {} puts it in {} only",
            num(e),
            child(side)
        );
    };
    let plane = format!(
        "t = ({} - e_{axis})/d_{axis} = ({} - {})/{} = {}",
        num(split),
        num(split),
        operand(e),
        operand(d),
        num(t)
    );
    let near = if d > 0.0 { format!("d_{axis} > 0") } else { format!("d_{axis} < 0") };
    let why = match decision.visit {
        Visit::NearThenFar { near: side, .. } => format!(
            "{near}, so {} is near; tmin {} < t < tmax {}: {} first on {}, then {} on {}",
            child(side),
            num(interval.t_min),
            num(interval.t_max),
            child(side),
            interval_text(Interval { t_min: interval.t_min, t_max: t }),
            child(side.opposite()),
            interval_text(Interval { t_min: t, t_max: interval.t_max }),
        ),
        Visit::Only(side) if t <= interval.t_min => format!(
            "{near}; t ≤ tmin = {}: the ray has already crossed the plane, only the far child {} on {}",
            num(interval.t_min),
            child(side),
            interval_text(interval)
        ),
        Visit::Only(side) => format!(
            "{near}; t ≥ tmax = {}: the ray leaves before the plane, only the near child {} on {}",
            num(interval.t_max),
            child(side),
            interval_text(interval)
        ),
    };
    format!("{plane}; {why}")
}

fn names(path: &[Branch]) -> Vec<String> {
    path.iter().map(ToString::to_string).collect()
}

fn part(ray: &Ray2, [planes_key, descents_key, key]: [&'static str; 3], label: char) -> Section {
    let trace = traverse(&Node2::homework(), ray);
    let root = Interval { t_min: 0.0, t_max: f64::INFINITY };
    let mut intervals: Vec<(Vec<Branch>, Interval)> = vec![(Vec::new(), root)];
    let mut steps = vec![Step::work(format!("start at the root with t in {}", interval_text(root)))];
    let mut planes = Vec::new();
    let mut descents = Vec::new();
    for (i, step) in trace.steps.iter().enumerate() {
        match step {
            TraceStep::Plane { path, axis, split, t } => {
                // The walk descends into the child it visits first right after meeting the plane.
                let first = match trace.steps.get(i + 1) {
                    Some(TraceStep::Descend { path: child, .. }) => {
                        child.last().map(ToString::to_string).unwrap_or_default()
                    }
                    _ => String::new(),
                };
                planes.push(ExpectedPlane { node: names(path), t: *t, first });
                let interval = intervals.iter().rev().find(|(p, _)| p == path).map_or(root, |(_, i)| *i);
                let text = format!(
                    "at {}: plane {axis} = {split}: {}",
                    path_text(path),
                    visit_text(ray, *axis, *split, interval)
                );
                steps.push(Step::work(text).at(path.len()));
            }
            TraceStep::Descend { path, interval } => {
                intervals.push((path.clone(), *interval));
                descents.push(ExpectedLeaf { path: names(path), t_min: interval.t_min, t_max: interval.t_max });
            }
            TraceStep::Leaf { path, interval } => {
                steps.push(
                    Step::work(format!("leaf {} reached with t in {}", path_text(path), interval_text(*interval)))
                        .at(path.len()),
                );
            }
        }
    }
    let leaves: Vec<ExpectedLeaf> = trace
        .leaves()
        .iter()
        .map(|l| ExpectedLeaf {
            path: l.path.iter().map(ToString::to_string).collect(),
            t_min: l.interval.t_min,
            t_max: l.interval.t_max,
        })
        .collect();
    steps.push(Step::answer(
        format!("planes met in order: {}", super::text::value(&Value::Planes(planes.clone()))),
        planes_key,
        Value::Planes(planes),
    ));
    let listed = descents.iter().map(super::text::leaf).collect::<Vec<_>>().join("; then ");
    steps.push(Step::answer(format!("descents in order: {listed}"), descents_key, Value::Leaves(descents)));
    let listed = leaves.iter().map(super::text::leaf).collect::<Vec<_>>().join("; then ");
    steps.push(Step::answer(format!("leaves in order: {listed}"), key, Value::Leaves(leaves)));
    let title = format!(
        "({label}) e = ({}, {}), d = ({}, {})",
        num(ray.origin[0]),
        num(ray.origin[1]),
        num(ray.dir[0]),
        num(ray.dir[1])
    );
    Section { title, steps }
}

pub(super) fn sections(d: Ray2, e: Ray2) -> Vec<Section> {
    // (b) and (c) in symbols: the plane `axis = s` is met where `e_axis + d_axis t = s`.
    let formulas = Section {
        title: "(b), (c) the plane parameter in symbols".into(),
        steps: vec![
            Step::answer(
                "x = 3: e_x + d_x t = 3, so t = (3 - e_x)/d_x",
                "q3b.t_formula",
                Value::Formula("(3 - e_x)/d_x".into()),
            ),
            Step::answer(
                "y = 1: e_y + d_y t = 1, so t = (1 - e_y)/d_y",
                "q3c.t_formula",
                Value::Formula("(1 - e_y)/d_y".into()),
            ),
        ],
    };
    let mut sections = vec![formulas];
    for (&(label, keys), ray) in PARTS.iter().zip([d, e]) {
        sections.push(part(&ray, keys, label));
    }
    sections
}
