//! Grading: each part's answer against its key, with partial credit and feedback.

use super::carried::{planes_following, recompute};
use super::error::CheckError;
use super::formula::compare_formulas;
use super::key::{Derivation, Expected, Follows, Part, Variant};
use super::paths::compare_paths;
use super::policy::Rule;
use super::reading::{Given, lookup, read_seed, read_value, require_tables};
use super::suggest::unknown_keys;
use super::traces::{echo_number, grade_planes, grade_trace, show_leaf, show_plane};
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
    /// `"correct"` (full points: the key's answer, or one a full-credit rule accepts),
    /// `"partial"`, `"wrong"` or `"missing"`.
    pub status: &'static str,
    /// The answer given, as text.
    pub given: Option<String>,
    /// The key's answer, as text.
    pub expected: String,
    /// One-line feedback: the error, the tolerance in words, a mal-rule message, the first wrong
    /// step, and for a wrong answer one sentence on the method.
    pub feedback: String,
    /// The recognised mistake's rule id, if a rule matched.
    pub mistake: Option<&'static str>,
    /// Where the notes explain it: the chapter's page and the section's anchor.
    pub explained_in: &'static str,
}

/// The graded file.
///
/// # Examples
/// ```
/// let report = hw3::checker::check("[meta]\nseed = 4", None).unwrap();
/// assert_eq!((report.seed, report.score), (4, 0.0));
/// assert!(report.unknown_keys.is_empty() && report.warnings.is_empty());
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
    /// Misspelt keys graded under the one unanswered part they are close to
    /// (``"graded `q2a.t` for `q2a.tt`"``).
    pub warnings: Vec<String>,
}

impl Report {
    /// True when every part earned full marks.
    ///
    /// # Examples
    /// ```
    /// let key = hw3::checker::answer_key(2).unwrap();
    /// assert!(hw3::checker::check(&key, None).unwrap().all_correct());
    /// assert!(!hw3::checker::check("", None).unwrap().all_correct());
    /// ```
    #[must_use]
    pub fn all_correct(&self) -> bool {
        self.parts.iter().all(|p| p.status == "correct")
    }
}

/// Grades an answers file (TOML text). The seed comes from `seed_override`, else `[meta] seed`,
/// else 0, with a warning in the report.
///
/// Each part earns the best of: the key's answer (full points), a step that follows from the
/// student's own wrong answer to the part it depends on ([`Rule::CarriedForward`]), a trace's
/// share of right entries, or a recognised mistake's [`Rule`] credit. A key no part asks for but
/// within two edits of exactly one unanswered part is graded under that part, with a warning.
///
/// # Errors
/// [`CheckError`] when the file is not valid TOML, a value has the wrong type or is not finite,
/// or the seed is invalid. A missing answer is not an error: it scores 0 with status `missing`.
///
/// # Examples
/// ```
/// let template = hw3::checker::answer_key(0).unwrap();
/// let report = hw3::checker::check(&template, None).unwrap();
/// assert!(report.all_correct());
/// assert!(hw3::checker::check("q2a = [", None).is_err());
/// ```
pub fn check(text: &str, seed_override: Option<u64>) -> Result<Report, CheckError> {
    let table: toml::Table = toml::from_str(text).map_err(|e| CheckError::Syntax(toml_reason(text, &e)))?;
    require_tables(&table)?;
    let seed = match seed_override {
        Some(seed) => seed,
        None => read_seed(&table)?,
    };
    let variants: Vec<Variant> = QUESTIONS.iter().map(|q| variant(q, seed)).collect::<Result<_, _>>()?;
    let parts: Vec<&Part> = variants.iter().flat_map(|v| &v.parts).collect();
    let follows: Vec<&Follows> = variants.iter().flat_map(|v| &v.follows).collect();
    let mut unknown = unknown_keys(&table, &parts);
    let mut givens = Vec::new();
    for part in &parts {
        let given = lookup(&table, part.key).map(|v| read_value(part.key, v, &part.expected)).transpose()?;
        givens.push(given);
    }
    // A misspelt key is graded under its part only when its value has that part's shape.
    let mut warnings = Vec::new();
    // A file without its seed is graded as variant 0, which is right only for that variant: said
    // so, so that a class's grader sees it.
    if seed_override.is_none() && table.get("meta").and_then(|m| m.get("seed")).is_none() {
        warnings.push("no `[meta] seed` in the file and no --seed: graded as variant 0".to_string());
    }
    let mut renamed = vec![None; parts.len()];
    for u in &mut unknown {
        let (Some(target), Some(key)) = (u.graded_as, u.key.as_deref()) else { continue };
        let at = parts.iter().position(|p| p.key == target).expect("suggestions are part keys");
        let value = lookup(&table, key).expect("an unknown key is in the file");
        if let Ok(given) = read_value(target, value, &parts[at].expected) {
            givens[at] = Some(given);
            let warning = format!("graded `{target}` for `{key}`");
            renamed[at] = Some(warning.clone());
            warnings.push(warning);
            u.graded_as = None;
            u.described.clear();
        }
    }
    let unknown_keys = unknown.into_iter().map(|u| u.described).filter(|d| !d.is_empty()).collect();
    let mut results: Vec<PartResult> =
        parts.iter().zip(&givens).map(|(part, given)| grade(part, given.as_ref())).collect();
    carry_forward(&parts, &givens, &follows, &mut results);
    for ((result, part), warning) in results.iter_mut().zip(&parts).zip(renamed) {
        if result.score < part.points && result.status != "missing" {
            result.feedback = format!("{} — {}", result.feedback, part.method);
        }
        if let Some(warning) = warning {
            result.feedback = format!("{warning}: {}", result.feedback);
        }
    }
    let score = round2(results.iter().map(|r| r.score).sum());
    let max_score = round2(results.iter().map(|r| r.max_score).sum());
    Ok(Report { seed, score, max_score, parts: results, unknown_keys, warnings })
}

/// Error carried forward: a later part that follows correctly from the student's own wrong
/// answer to the part it depends on earns [`Rule::CarriedForward`]'s credit; a later part that is
/// wrong anyway is told the first wrong step of its chain.
fn carry_forward(parts: &[&Part], givens: &[Option<Given>], follows: &[&Follows], results: &mut [PartResult]) {
    let at = |key: &str| parts.iter().position(|p| p.key == key);
    // Dependencies come in order (t before the point before the normal), so one pass suffices.
    for f in follows {
        let (Some(later), Some(earlier)) = (at(f.key), at(f.from)) else { continue };
        if results[earlier].status == "missing"
            || results[earlier].mistake.is_none() && results[earlier].status == "correct"
        {
            continue;
        }
        // The first wrong step of the chain: the earlier part, or the step it carried its error from.
        let root = match results[earlier].mistake {
            Some(id) if id == Rule::CarriedForward.id() => {
                first_wrong_step(&results[earlier].feedback).unwrap_or(f.from).to_string()
            }
            _ => f.from.to_string(),
        };
        let part = parts[later];
        if results[later].score >= part.points {
            continue;
        }
        let (Some(given), Some(from)) = (&givens[later], &givens[earlier]) else { continue };
        let Some(expected) = recompute(&f.derivation, from, &part.expected) else {
            results[later].feedback =
                format!("{}; `{}` is wrong too: {}", results[later].feedback, f.from, unfollowable(&f.derivation));
            continue;
        };
        // An earlier slip this step does not depend on (an inward normal reflects the same way)
        // leaves the step's own mistake as its first.
        if as_given(&expected).is_some_and(|g| compare(&part.expected, &g).0) {
            continue;
        }
        let (credit, words) = match (&expected, given) {
            (Expected::Trace { leaves, planes, descents }, Given::Trace(g)) => {
                let graded = grade_trace(leaves, planes, g, *descents);
                (graded.credit, graded.words)
            }
            _ => (f64::from(u8::from(compare(&expected, given).0)), String::new()),
        };
        let credit = credit * Rule::CarriedForward.credit();
        let score = round2(part.points * credit);
        if score > results[later].score {
            let result = &mut results[later];
            result.score = score;
            result.status = status(score, part.points);
            result.mistake = Some(Rule::CarriedForward.id());
            result.feedback = if credit < 1.0 {
                // Part of it follows: what is still wrong against the student's own values.
                format!(
                    "{:.0} % of it follows from your `{}` (error carried forward); against the values you had: {words}; first wrong step: `{root}`",
                    100.0 * credit,
                    f.from
                )
            } else {
                format!(
                    "follows from your `{}`: right for the value you had (error carried forward); first wrong step: `{root}`",
                    f.from
                )
            };
        } else {
            // Wrong both against the key and against the student's own earlier answer: naming the
            // earlier part as the first wrong step would say that fixing it fixes this.
            results[later].feedback = format!(
                "{}; `{}` is wrong too, but this answer does not follow from it either",
                results[later].feedback, f.from
            );
        }
    }
}

/// Why a later part was not recomputed from the student's earlier answer.
fn unfollowable(derivation: &Derivation) -> &'static str {
    match derivation {
        Derivation::DescentsFromPlanes { .. } => {
            "your planes are not the traversal's with one slip of arithmetic (two or more wrong t, a t of the wrong sign or another plane's t, a wrong node or first child, or a parallel plane), so the descents are graded against the key"
        }
        Derivation::LeavesFromPlanes { .. } => {
            "your planes are not the traversal's with one slip of arithmetic (two or more wrong t, a t of the wrong sign or another plane's t, a wrong node or first child, or a parallel plane), so the leaves are graded against the key"
        }
        Derivation::LeavesFromDescents { .. } => {
            "your descents do not follow the traversal from the plane parameters they show (a wrong, missing or extra cell, a wrong first child, or a bound kept at 0 or left unclipped), so the leaves are graded against the key"
        }
        _ => "there is nothing in it to follow from",
    }
}

/// A recomputed key as if it were an answer, to compare with the key itself.
fn as_given(expected: &Expected) -> Option<Given> {
    match expected {
        Expected::Number { value, .. } => Some(Given::Number(*value)),
        Expected::Vector { value, .. } | Expected::Direction { value, .. } => Some(Given::Vector(*value)),
        Expected::Trace { leaves, .. } => Some(Given::Trace(leaves.clone())),
        Expected::Paths { value } => Some(Given::Paths(value.clone())),
        _ => None,
    }
}

/// The part a carried-forward feedback names as the first wrong step.
fn first_wrong_step(feedback: &str) -> Option<&str> {
    let (_, rest) = feedback.rsplit_once("first wrong step: `")?;
    rest.split('`').next()
}

fn status(score: f64, points: f64) -> &'static str {
    if score >= points {
        "correct"
    } else if score > 0.0 {
        "partial"
    } else {
        "wrong"
    }
}

/// The Euclidean length, scaled by the largest component first so that it overflows only when
/// the length itself does (a point at t = 10¹⁵⁵ has a finite length, though its square does not).
fn norm(v: [f64; 3]) -> f64 {
    let scale = v.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    if scale == 0.0 || !scale.is_finite() {
        return scale;
    }
    scale * v.iter().map(|x| (x / scale) * (x / scale)).sum::<f64>().sqrt()
}

/// Whether an error is within the allowed one: the allowed error must be finite (an infinite one
/// would accept anything), and a few units of rounding in computing the two are forgiven, so that a
/// decimal answer at the printed end of the range (2 − 0.02 = 1.98) is accepted.
fn within(error: f64, allowed: f64, scale: f64) -> bool {
    allowed.is_finite() && error <= allowed + 4.0 * f64::EPSILON * scale
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
            let range = format!(
                "accepted: {} to {}",
                show_bound_of_range(value - allowed, true),
                show_bound_of_range(value + allowed, false)
            );
            (
                within(error, allowed, value.abs() + x.abs()),
                if *value == 0.0 {
                    format!("off by {error:.3e}; {range}")
                } else {
                    format!("off by {error:.3e} (relative {:.3e}); {range}", error / value.abs())
                },
            )
        }
        (Expected::Vector { value, rtol, atol }, Given::Vector(v)) => {
            let allowed = rtol * norm(*value) + atol;
            let error = norm(difference(*v, *value));
            (
                within(error, allowed, norm(*value) + norm(*v)),
                format!("off by {error:.3e}; accepted within {allowed:.1e} of the key"),
            )
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
            let graded = grade_trace(leaves, planes, given, *descents);
            (graded.exact, graded.words)
        }
        (Expected::Planes { steps, why_first, ray }, Given::Planes(given)) => {
            let (credit, words, _) = grade_planes(steps, why_first, given, &planes_following(ray.0, ray.1, given));
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

/// A key's number in the feedback: at least six significant digits
/// ([`crate::plot::significant`]), so that an accepted range is never rounded onto a wrong
/// answer and a dense slab's gap fraction of 10⁻¹² is not printed as 0.
fn show_number(x: f64) -> String {
    crate::plot::significant(x)
}

/// An end of an accepted range as [`show_number`] prints it, rounded inwards (the low end up, the
/// high end down), so that a number written with no more digits than the range shows is accepted
/// exactly when it lies within the printed range.
fn show_bound_of_range(x: f64, low: bool) -> String {
    let text = show_number(x);
    let shown: f64 = text.parse().unwrap_or(x);
    if !x.is_finite() || (low && shown >= x) || (!low && shown <= x) {
        return text;
    }
    // One unit in the last digit shown: the exponent's for `1.23456e-7`, the decimals' otherwise.
    let unit = match text.split_once('e') {
        Some((_, exponent)) => 10f64.powi(exponent.parse::<i32>().unwrap_or(0) - 5),
        None => 10f64.powi(-(text.split_once('.').map_or(0, |(_, d)| d.len()) as i32)),
    };
    show_number(if low { shown + unit } else { shown - unit })
}

fn show_expected(expected: &Expected) -> String {
    match expected {
        Expected::Number { value, .. } => show_number(*value),
        Expected::Vector { value, .. } | Expected::Direction { value, .. } | Expected::Parallel { value, .. } => {
            show_vector(*value)
        }
        Expected::Trace { leaves, .. } => leaves.iter().map(show_leaf).collect::<Vec<_>>().join("; "),
        Expected::Planes { steps, .. } => steps.iter().map(show_plane).collect::<Vec<_>>().join("; "),
        Expected::Choice { value, .. } => (*value).to_string(),
        Expected::Flag { value } => value.to_string(),
        Expected::Formula { source, .. } => (*source).to_string(),
        Expected::Paths { value } => value.clone(),
        Expected::OrNone { none: true, .. } => "none".into(),
        Expected::OrNone { value, .. } => show_expected(value),
    }
}

/// A vector in the feedback: each component as [`show_number`] prints it, and a component below
/// 10⁻¹² as 0 (the rounding of a rotation in a key, not part of the answer).
fn show_vector(v: [f64; 3]) -> String {
    let [x, y, z] = v.map(|c| show_number(if c.abs() < 1e-12 { 0.0 } else { c }));
    format!("[{x}, {y}, {z}]")
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
            mistake: None,
            explained_in: part.explained_in,
        };
    };
    let shown = match given {
        Given::Number(x) => echo_number(*x),
        Given::Vector(v) => show_vector(*v),
        Given::Trace(leaves) => leaves.iter().map(show_leaf).collect::<Vec<_>>().join("; "),
        Given::Planes(steps) => steps.iter().map(show_plane).collect::<Vec<_>>().join("; "),
        Given::Choice { answer, .. } => answer.clone(),
        Given::Flag(flag) => flag.to_string(),
        Given::Formula { source, .. } | Given::Paths(source) | Given::Something(source) => source.clone(),
        Given::None => "none".into(),
    };
    // A list (a trace or its planes) is graded once: whether it is right, the words, its share of
    // right entries, and whether some of them carried an earlier value forward.
    let list = match (&part.expected, given) {
        (Expected::Trace { leaves, planes, descents }, Given::Trace(g)) => {
            let graded = grade_trace(leaves, planes, g, *descents);
            Some((graded.exact, graded.words, graded.credit, graded.carried > 0))
        }
        (Expected::Planes { steps, why_first, ray }, Given::Planes(g)) => {
            let (credit, words, carried) = grade_planes(steps, why_first, g, &planes_following(ray.0, ray.1, g));
            Some((credit == 1.0, words, credit, carried))
        }
        _ => None,
    };
    let (ok, words, trace) = match list {
        Some((ok, words, credit, carried)) => (ok, words, Some((credit, carried.then_some(Rule::CarriedForward)))),
        None => {
            let (ok, words) = compare(&part.expected, given);
            (ok, words, None)
        }
    };
    let mal_rule = part.mal_rules.iter().find(|rule| compare(&rule.value, given).0);
    let (credit, feedback, mistake) = if ok {
        (1.0, words, None)
    } else {
        match (trace, mal_rule) {
            (Some((share, rule)), _) if mal_rule.is_none_or(|m| share >= m.credit()) => (share, words, rule),
            (_, Some(m)) => (m.credit(), format!("{} ({words})", m.message), Some(m.rule)),
            _ => (0.0, words, None),
        }
    };
    let score = round2(part.points * credit);
    PartResult {
        key: part.key,
        score,
        max_score: part.points,
        status: status(score, part.points),
        given: Some(shown),
        expected,
        feedback,
        mistake: mistake.map(Rule::id),
        explained_in: part.explained_in,
    }
}

fn round2(x: f64) -> f64 {
    (x * 100.0).round() / 100.0
}

/// A TOML error as "line L, column C: reason", without the parser's excerpt of the line (which
/// can be as long as the file, and would push the reason out of a one-line message).
fn toml_reason(text: &str, error: &toml::de::Error) -> String {
    let reason = error.message().trim_end_matches('\n');
    match error.span() {
        Some(span) => {
            let before = &text[..span.start.min(text.len())];
            let line = before.matches('\n').count() + 1;
            let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
            format!("line {line}, column {column}: {reason}")
        }
        None => reason.to_owned(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::checker::{Kind, answer_key};
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
        let key = answer_key(0).unwrap();
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
        // An unclipped interval: the first leaf is wrong (a mistake of method, not carried
        // forward), the second is right on its own.
        let unclipped = in_leaves("tmax = 2.0", "tmax = \"inf\"");
        let d = check(&unclipped, None).unwrap().parts.into_iter().find(|p| p.key == "q3d.leaves").unwrap();
        assert_eq!((d.score, d.mistake), (1.5, None));
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
            let report = check(&answer_key(seed).unwrap(), None).unwrap();
            prop_assert!(report.all_correct(), "{:?}", report);
            prop_assert_eq!(report.score, report.max_score);
        }

        /// Perturbing one answer beyond its tolerance loses exactly that part's points.
        #[test]
        fn perturbing_one_part_loses_exactly_its_points(seed in 0u64..1_000_000, question in 0usize..QUESTIONS.len(), which in 0usize..64) {
            let variant = variant(QUESTIONS[question], seed).unwrap();
            let part = &variant.parts[which % variant.parts.len()];
            let key = answer_key(seed).unwrap();
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
            prop_assert_eq!(wrong.len(), 1, "{:?}", report);
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
