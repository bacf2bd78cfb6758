//! Grading: each part's answer against its key, with partial credit and feedback.

use super::error::CheckError;
use super::key::{Expected, ExpectedLeaf, Part, Variant};
use super::reading::{Given, lookup, read_seed, read_value};
use super::suggest::unknown_keys;
use super::variants::{QUESTIONS, variant};
use serde::Serialize;

/// Verdict on one part.
///
/// # Examples
/// ```
/// let report = hw3::checker::check("[q2c]\nt_closest = 5.0", None).unwrap();
/// let part = report.parts.iter().find(|p| p.key == "q2c.t_closest").unwrap();
/// assert_eq!((part.status, part.score, part.max_score), ("correct", 2.0, 2.0));
/// ```
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PartResult {
    /// TOML path.
    pub key: &'static str,
    /// Points earned (rounded to 0.01).
    pub score: f64,
    /// Points available.
    pub max_score: f64,
    /// `"correct"`, `"partial"`, `"wrong"` or `"missing"`.
    pub status: &'static str,
    /// The answer given, as text.
    pub given: Option<String>,
    /// The key's answer, as text.
    pub expected: String,
    /// One-line feedback: the error, the tolerance in words, a mal-rule message.
    pub feedback: String,
    /// Where the notes explain it.
    pub explained_in: &'static str,
}

/// The graded file.
///
/// # Examples
/// ```
/// let report = hw3::checker::check("[meta]\nseed = 4", None).unwrap();
/// assert_eq!((report.seed, report.score), (4, 0.0));
/// assert!(report.unknown_keys.is_empty());
/// ```
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// The variant seed graded against.
    pub seed: u64,
    /// Total points earned (rounded to 0.01).
    pub score: f64,
    /// Total points available.
    pub max_score: f64,
    /// One result per part, in question order.
    pub parts: Vec<PartResult>,
    /// Keys in the file that no part asks for (with a suggestion when one is close).
    pub unknown_keys: Vec<String>,
}

impl Report {
    /// True when every part earned full marks.
    ///
    /// # Examples
    /// ```
    /// let key = hw3::checker::answers_key(2).unwrap();
    /// assert!(hw3::checker::check(&key, None).unwrap().all_correct());
    /// assert!(!hw3::checker::check("", None).unwrap().all_correct());
    /// ```
    #[must_use]
    pub fn all_correct(&self) -> bool {
        self.parts.iter().all(|p| p.status == "correct")
    }
}

/// Grades an answers file (TOML text). The seed comes from `seed_override`, else `[meta] seed`,
/// else 0.
///
/// # Errors
/// [`CheckError`] when the file is not valid TOML, a value has the wrong type or is not finite,
/// or the seed is invalid. A missing answer is not an error: it scores 0 with status `missing`.
///
/// # Examples
/// ```
/// let template = hw3::checker::answers_key(0).unwrap();
/// let report = hw3::checker::check(&template, None).unwrap();
/// assert!(report.all_correct());
/// assert!(hw3::checker::check("q2a = [", None).is_err());
/// ```
pub fn check(text: &str, seed_override: Option<u64>) -> Result<Report, CheckError> {
    let table: toml::Table = toml::from_str(text).map_err(|e| CheckError::Syntax(e.to_string()))?;
    let seed = match seed_override {
        Some(seed) => seed,
        None => read_seed(&table)?,
    };
    let variants: Vec<Variant> = QUESTIONS.iter().map(|q| variant(q, seed)).collect::<Result<_, _>>()?;
    let parts: Vec<&Part> = variants.iter().flat_map(|v| &v.parts).collect();
    let unknown_keys = unknown_keys(&table, &parts);
    let mut results = Vec::new();
    for part in parts {
        let given = lookup(&table, part.key).map(|v| read_value(part.key, v, &part.expected)).transpose()?;
        results.push(grade(part, given.as_ref()));
    }
    let score = round2(results.iter().map(|r| r.score).sum());
    let max_score = round2(results.iter().map(|r| r.max_score).sum());
    Ok(Report { seed, score, max_score, parts: results, unknown_keys })
}
fn same_bound(a: f64, b: f64) -> bool {
    a == b || (a - b).abs() <= 1e-6 * (1.0 + b.abs())
}

fn show_bound(t: f64) -> String {
    if t.is_infinite() { "inf".into() } else { format!("{t}") }
}

fn show_leaf(leaf: &ExpectedLeaf) -> String {
    format!("[{}] t in [{}, {}]", leaf.path.join(", "), show_bound(leaf.t_min), show_bound(leaf.t_max))
}

/// Credit for a trace: the share of leaves right before the first divergence, and why it diverged.
fn grade_trace(expected: &[ExpectedLeaf], planes: &[(String, f64)], given: &[ExpectedLeaf]) -> (f64, String) {
    let agree = |e: &ExpectedLeaf, g: &ExpectedLeaf| {
        e.path == g.path && same_bound(g.t_min, e.t_min) && same_bound(g.t_max, e.t_max)
    };
    let prefix = expected.iter().zip(given).take_while(|(e, g)| agree(e, g)).count();
    let credit = prefix as f64 / expected.len().max(given.len()).max(1) as f64;
    if prefix == expected.len() && prefix == given.len() {
        return (1.0, format!("all {prefix} leaves right"));
    }
    let plane_at = |t: f64| planes.iter().find(|(_, pt)| same_bound(t, *pt)).map(|(name, _)| name.clone());
    let reason = match (expected.get(prefix), given.get(prefix)) {
        (Some(e), None) => format!("leaf {} missing: the ray goes on into {}", prefix + 1, show_leaf(e)),
        (None, Some(g)) => {
            format!("leaf {} is extra: the ray has left the tree's last cell ({})", prefix + 1, show_leaf(g))
        }
        (Some(e), Some(g)) if e.path != g.path => {
            format!("leaf {}: wrong cell: the ray is in {}, not [{}]", prefix + 1, show_leaf(e), g.path.join(", "))
        }
        (Some(e), Some(g)) if !same_bound(g.t_min, e.t_min) => {
            let why = if g.t_min == 0.0 {
                "you kept tmin at 0 after crossing the plane".to_string()
            } else if let Some(name) = plane_at(g.t_min) {
                format!("t = {} is where the ray crosses {name}, not where it enters this cell", g.t_min)
            } else {
                "tmin is where the ray enters this cell".to_string()
            };
            format!("leaf {} [{}]: tmin should be {}: {why}", prefix + 1, e.path.join(", "), show_bound(e.t_min))
        }
        (Some(e), Some(g)) => {
            let why = if g.t_max.is_infinite() {
                "the interval was not clipped at the plane the ray leaves by".to_string()
            } else if let Some(name) = plane_at(g.t_max) {
                format!("t = {} is where the ray crosses {name}, not where it leaves this cell", g.t_max)
            } else {
                "tmax is where the ray leaves this cell".to_string()
            };
            format!("leaf {} [{}]: tmax should be {}: {why}", prefix + 1, e.path.join(", "), show_bound(e.t_max))
        }
        (None, None) => unreachable!("a divergence exists when the lengths or a leaf differ"),
    };
    (credit, format!("first {prefix} leaves right; {reason}"))
}

fn norm(v: [f64; 3]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

fn difference(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// Whether `given` matches `expected` within its tolerance, and the error in words.
fn compare(expected: &Expected, given: &Given) -> (bool, String) {
    match (expected, given) {
        (Expected::Number { value, rtol, atol }, Given::Number(x)) => {
            let allowed = rtol * value.abs() + atol;
            let error = (x - value).abs();
            let range = format!("accepted: {:.6} to {:.6}", value - allowed, value + allowed);
            (
                error <= allowed,
                format!("off by {error:.3e} (relative {:.1e}); {range}", error / value.abs().max(1e-300)),
            )
        }
        (Expected::Vector { value, rtol, atol }, Given::Vector(v)) => {
            let allowed = rtol * norm(*value) + atol;
            let error = norm(difference(*v, *value));
            (error <= allowed, format!("off by {error:.3e}; accepted within {allowed:.1e} of the key"))
        }
        (Expected::Direction { value, angle_tol } | Expected::Parallel { value, angle_tol }, Given::Vector(v)) => {
            let length = norm(*v);
            if length == 0.0 {
                return (false, "the zero vector is not a direction".into());
            }
            let cos = (value.iter().zip(v).map(|(a, b)| a * b).sum::<f64>() / length).clamp(-1.0, 1.0);
            let angle = cos.acos();
            let unit = matches!(expected, Expected::Parallel { .. }) || (length - 1.0).abs() <= 1e-3;
            let words = format!("angle {angle:.2e} rad (accepted ≤ {angle_tol:.0e}), length {length:.4}");
            (angle <= *angle_tol && unit, words)
        }
        (Expected::Trace { leaves, planes }, Given::Trace(given)) => {
            let (credit, words) = grade_trace(leaves, planes, given);
            (credit == 1.0, words)
        }
        (Expected::Choice { value }, Given::Choice { answer, why }) => {
            let echo = why.as_ref().map_or(String::new(), |w| format!(" (your reason, not graded: {w})"));
            (answer == value, format!("the key says {value}{echo}"))
        }
        _ => (false, "answer has the wrong shape".into()),
    }
}

fn show_expected(expected: &Expected) -> String {
    match expected {
        Expected::Number { value, .. } => format!("{value:.6}"),
        Expected::Vector { value, .. } | Expected::Direction { value, .. } | Expected::Parallel { value, .. } => {
            show_vector(*value)
        }
        Expected::Trace { leaves, .. } => leaves.iter().map(show_leaf).collect::<Vec<_>>().join("; "),
        Expected::Choice { value } => (*value).to_string(),
    }
}

fn show_vector(v: [f64; 3]) -> String {
    format!("[{:.6}, {:.6}, {:.6}]", v[0], v[1], v[2])
}

fn grade(part: &Part, given: Option<&Given>) -> PartResult {
    let expected = show_expected(&part.expected);
    let Some(given) = given else {
        return PartResult {
            key: part.key,
            score: 0.0,
            max_score: part.points,
            status: "missing",
            given: None,
            expected,
            feedback: format!("no answer for `{}`", part.key),
            explained_in: part.explained_in,
        };
    };
    let shown = match given {
        Given::Number(x) => format!("{x}"),
        Given::Vector(v) => show_vector(*v),
        Given::Trace(leaves) => leaves.iter().map(show_leaf).collect::<Vec<_>>().join("; "),
        Given::Choice { answer, .. } => answer.clone(),
    };
    let (ok, words) = compare(&part.expected, given);
    let trace_credit = match (&part.expected, given) {
        (Expected::Trace { leaves, planes }, Given::Trace(g)) => Some(grade_trace(leaves, planes, g).0),
        _ => None,
    };
    let (score, status, feedback) = if ok {
        (part.points, "correct", words)
    } else if let Some(credit) = trace_credit.filter(|&c| c > 0.0) {
        (part.points * credit, "partial", words)
    } else if let Some(rule) = part.mal_rules.iter().find(|rule| compare(&rule.value, given).0) {
        let status = if rule.credit > 0.0 { "partial" } else { "wrong" };
        (part.points * rule.credit, status, format!("{} ({words})", rule.message))
    } else {
        (0.0, "wrong", words)
    };
    PartResult {
        key: part.key,
        score: round2(score),
        max_score: part.points,
        status,
        given: Some(shown),
        expected,
        feedback,
        explained_in: part.explained_in,
    }
}

fn round2(x: f64) -> f64 {
    (x * 100.0).round() / 100.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::checker::{answers_key, report_text};
    use proptest::prelude::*;

    #[test]
    fn blank_file_scores_zero_with_every_part_missing() {
        let report = check("", None).unwrap();
        assert_eq!(report.score, 0.0);
        assert!(report.parts.iter().all(|p| p.status == "missing"));
    }

    #[test]
    fn malformed_and_hostile_files_are_errors_not_panics() {
        let deep = format!("x = {}1{}", "[".repeat(10_000), "]".repeat(10_000));
        for text in [
            "q2a = [",
            "[q2a]\nt = \"three\"",
            "[q2a]\nt = nan",
            "[q2a]\nt = inf",
            "[q2a]\nt = 1e400",
            "[q2a]\npoint = [1, 2]",
            "[q2a]\npoint = [1, 2, \"x\"]",
            "[meta]\nseed = -1",
            "[meta]\nseed = \"zero\"",
            deep.as_str(),
            "\u{0}\u{1}binary",
        ] {
            assert!(check(text, None).is_err(), "{text:.40}");
        }
    }

    #[test]
    fn trace_feedback_names_the_first_divergence() {
        let key = answers_key(0).unwrap();
        // Case (d) with tmin kept at 0 in the second leaf.
        let wrong = key.replacen("tmin = 2.0", "tmin = 0.0", 1);
        let report = check(&wrong, None).unwrap();
        let d = report.parts.iter().find(|p| p.key == "q3d.leaves").unwrap();
        assert_eq!((d.status, d.score), ("partial", 1.5));
        assert!(d.feedback.contains("you kept tmin at 0 after crossing the plane"), "{}", d.feedback);
        // An unclipped interval.
        let unclipped = key.replacen("tmax = 2.0", "tmax = \"inf\"", 1);
        let d = check(&unclipped, None).unwrap().parts.into_iter().find(|p| p.key == "q3d.leaves").unwrap();
        assert_eq!(d.score, 0.0);
        assert!(d.feedback.contains("not clipped"), "{}", d.feedback);
        // A missing leaf.
        let short = "[q3d]\nleaves = [{ path = [\"x>=3\", \"y<3\"], tmin = 0, tmax = 2 }]";
        let d = check(short, None).unwrap().parts.into_iter().find(|p| p.key == "q3d.leaves").unwrap();
        assert_eq!(d.score, 1.5);
        assert!(d.feedback.contains("leaf 2 missing"), "{}", d.feedback);
    }

    #[test]
    fn malformed_traces_are_errors() {
        for text in [
            "[q3d]\nleaves = 3",
            "[q3d]\nleaves = [1, 2]",
            "[q3d]\nleaves = [{ path = \"x>=3\", tmin = 0, tmax = 1 }]",
            "[q3d]\nleaves = [{ path = [\"x>=3\"], tmin = 0 }]",
            "[q3d]\nleaves = [{ path = [\"x>=3\"], tmin = \"zero\", tmax = 1 }]",
        ] {
            assert!(check(text, None).is_err(), "{text}");
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// The key of any variant scores 100 %.
        #[test]
        fn key_scores_full_marks(seed in 0u64..1_000_000) {
            let report = check(&answers_key(seed).unwrap(), None).unwrap();
            prop_assert!(report.all_correct(), "{}", report_text(&report));
            prop_assert_eq!(report.score, report.max_score);
        }

        /// Perturbing one answer beyond its tolerance loses exactly that part's points.
        #[test]
        fn perturbing_one_part_loses_exactly_its_points(seed in 0u64..1_000_000, question in 0usize..4, which in 0usize..12) {
            let variant = variant(QUESTIONS[question], seed).unwrap();
            let part = &variant.parts[which % variant.parts.len()];
            let key = answers_key(seed).unwrap();
            let (table, name) = part.key.split_once('.').unwrap();
            let mut doc: toml::Table = toml::from_str(&key).unwrap();
            let entry = doc.get_mut(table).unwrap().as_table_mut().unwrap().get_mut(name).unwrap();
            *entry = match entry.clone() {
                toml::Value::Float(x) => toml::Value::Float(x * 1.5 + 1.0),
                toml::Value::String(word) => toml::Value::String(if word == "yes" { "no" } else { "yes" }.into()),
                toml::Value::Array(mut items) if items[0].is_table() => {
                    // A trace: move where the ray enters its last leaf.
                    let last = items.last_mut().unwrap().as_table_mut().unwrap();
                    let t_min = last["tmin"].as_float().unwrap();
                    last.insert("tmin".into(), toml::Value::Float(t_min + 0.25));
                    toml::Value::Array(items)
                }
                toml::Value::Array(mut items) => {
                    // Rotate the components: a different vector of the same length.
                    items.rotate_left(1);
                    let x = items[0].as_float().unwrap();
                    items[0] = toml::Value::Float(x + 0.5);
                    toml::Value::Array(items)
                }
                other => other,
            };
            let report = check(&toml::to_string(&doc).unwrap(), None).unwrap();
            let lost = report.max_score - report.score;
            let wrong: Vec<_> = report.parts.iter().filter(|p| p.status != "correct").collect();
            prop_assert_eq!(wrong.len(), 1, "{}", report_text(&report));
            prop_assert_eq!(wrong[0].key, part.key);
            prop_assert!(wrong[0].score < part.points);
            prop_assert!((lost - (part.points - wrong[0].score)).abs() < 1e-9);
        }

        /// Arbitrary text never panics the checker.
        #[test]
        fn arbitrary_text_never_panics(text in ".{0,200}") {
            let _ = check(&text, None);
        }
    }
}
