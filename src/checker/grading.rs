//! Grading: each part's answer against its key, with partial credit and feedback.

use super::error::CheckError;
use super::formula::compare_formulas;
use super::key::{Expected, Part, Variant};
use super::paths::compare_paths;
use super::reading::{Given, lookup, read_seed, read_value, require_tables};
use super::suggest::unknown_keys;
use super::traces::{grade_planes, grade_trace, show_leaf, show_plane};
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
    require_tables(&table)?;
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
        (Expected::Trace { leaves, planes, descents }, Given::Trace(given)) => {
            let (credit, words) = grade_trace(leaves, planes, given, *descents);
            (credit == 1.0, words)
        }
        (Expected::Planes { steps }, Given::Planes(given)) => {
            let (credit, words) = grade_planes(steps, given);
            (credit == 1.0, words)
        }
        (Expected::Choice { value, options }, Given::Choice { answer, why }) => {
            let echo = why.as_ref().map_or(String::new(), |w| format!(" (your reason, not graded: {w})"));
            let listed = if options.contains(&answer.as_str()) {
                String::new()
            } else {
                format!("; `{answer}` is not one of {}", options.join(", "))
            };
            (answer == value, format!("the key says {value}{echo}{listed}"))
        }
        (Expected::Flag { value }, Given::Flag(flag)) => (flag == value, format!("the key says {value}")),
        (Expected::Formula { key, symbols, points, .. }, Given::Formula { formula, .. }) => {
            compare_formulas(key, formula, symbols, points)
        }
        (Expected::Paths { value }, Given::Paths(given)) => compare_paths(value, given),
        (Expected::OrNone { none: true, .. }, Given::None) => (true, "right: there is none".into()),
        (Expected::OrNone { none: true, .. }, _) => (false, "there is none: write \"none\"".into()),
        (Expected::OrNone { none: false, .. }, Given::None) => {
            (false, "there is one: the key is a value, not none".into())
        }
        (Expected::OrNone { value, none: false }, given) => compare(value, given),
        (_, Given::None) => {
            (false, "this part always has an answer: \"none\" is accepted only where the template offers it".into())
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
        Expected::Planes { steps } => steps.iter().map(show_plane).collect::<Vec<_>>().join("; "),
        Expected::Choice { value, .. } => (*value).to_string(),
        Expected::Flag { value } => value.to_string(),
        Expected::Formula { source, .. } => (*source).to_string(),
        Expected::Paths { value } => value.clone(),
        Expected::OrNone { none: true, .. } => "none".into(),
        Expected::OrNone { value, .. } => show_expected(value),
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
        Given::Planes(steps) => steps.iter().map(show_plane).collect::<Vec<_>>().join("; "),
        Given::Choice { answer, .. } => answer.clone(),
        Given::Flag(flag) => flag.to_string(),
        Given::Formula { source, .. } | Given::Paths(source) | Given::Something(source) => source.clone(),
        Given::None => "none".into(),
    };
    let (ok, words) = compare(&part.expected, given);
    let trace_credit = match (&part.expected, given) {
        (Expected::Trace { leaves, planes, descents }, Given::Trace(g)) => {
            Some(grade_trace(leaves, planes, g, *descents).0)
        }
        (Expected::Planes { steps }, Given::Planes(g)) => Some(grade_planes(steps, g).0),
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
    use crate::checker::{Kind, answers_key, report_text};
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
        // Edit case (d)'s leaves only (its descents come first and hold the same intervals).
        let at = key.find("[q3d]").unwrap();
        let at = at + key[at..].find("\nleaves").unwrap();
        let in_leaves = |from: &str, to: &str| format!("{}{}", &key[..at], key[at..].replacen(from, to, 1));
        // Case (d) with tmin kept at 0 in the second leaf.
        let wrong = in_leaves("tmin = 2.0", "tmin = 0.0");
        let report = check(&wrong, None).unwrap();
        let d = report.parts.iter().find(|p| p.key == "q3d.leaves").unwrap();
        assert_eq!((d.status, d.score), ("partial", 1.5));
        assert!(d.feedback.contains("you kept tmin at 0 after crossing the plane"), "{}", d.feedback);
        // An unclipped interval.
        let unclipped = in_leaves("tmax = 2.0", "tmax = \"inf\"");
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
        fn perturbing_one_part_loses_exactly_its_points(seed in 0u64..1_000_000, question in 0usize..QUESTIONS.len(), which in 0usize..64) {
            let variant = variant(QUESTIONS[question], seed).unwrap();
            let part = &variant.parts[which % variant.parts.len()];
            let key = answers_key(seed).unwrap();
            let (table, name) = part.key.split_once('.').unwrap();
            let mut doc: toml::Table = toml::from_str(&key).unwrap();
            let entry = doc.get_mut(table).unwrap().as_table_mut().unwrap().get_mut(name).unwrap();
            let or_none = matches!(part.expected, Expected::OrNone { .. });
            *entry = match entry.clone() {
                toml::Value::String(word) if or_none && word == "none" => toml::Value::Float(1.0),
                _ if or_none && matches!(part.expected, Expected::OrNone { none: false, .. }) => {
                    toml::Value::String("none".into())
                }
                toml::Value::Float(x) => toml::Value::Float(x * 1.5 + 1.0),
                toml::Value::Boolean(b) => toml::Value::Boolean(!b),
                toml::Value::String(word) => toml::Value::String(match &part.expected {
                    Expected::Choice { options, .. } => options.iter().find(|o| **o != word).unwrap().to_string(),
                    Expected::Formula { key, .. } if key.kind() == Kind::Vector => format!("2*({word})"),
                    Expected::Formula { .. } => format!("({word}) + 1"),
                    Expected::Paths { .. } if word == "none" => "LGE".into(),
                    Expected::Paths { .. } => "none".into(),
                    other => unreachable!("a string answer for {other:?}"),
                }),
                toml::Value::Array(mut items) if items[0].is_table() => {
                    let last = items.last_mut().unwrap().as_table_mut().unwrap();
                    if let Some(t_min) = last.get("tmin").and_then(toml::Value::as_float) {
                        // A trace: move where the ray enters its last leaf.
                        last.insert("tmin".into(), toml::Value::Float(t_min + 0.25));
                    } else if let Some(t) = last.get("t").and_then(toml::Value::as_float) {
                        // Planes: move the last plane's parameter.
                        last.insert("t".into(), toml::Value::Float(t + 0.25));
                    } else {
                        last.insert("t".into(), toml::Value::Float(1.0));
                    }
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
