#![doc = include_str!(concat!(env!("OUT_DIR"), "/checker.md"))]

mod q2;
mod q3;
mod q4;
mod q5;

use serde::Serialize;
use std::fmt::Write as _;

/// The answer a part expects, with how it is compared.
#[derive(Debug, Clone, PartialEq)]
pub enum Expected {
    /// A number, accepted within `rtol·|value| + atol`.
    Number {
        /// The key's value.
        value: f64,
        /// Relative tolerance.
        rtol: f64,
        /// Absolute tolerance.
        atol: f64,
    },
    /// A point or vector, accepted when `|given − value| ≤ rtol·|value| + atol`.
    Vector {
        /// The key's value.
        value: [f64; 3],
        /// Relative tolerance on the norm of the difference.
        rtol: f64,
        /// Absolute tolerance on the norm of the difference.
        atol: f64,
    },
    /// A unit direction, accepted within `angle_tol` radians *and* within 10⁻³ of unit length.
    Direction {
        /// The key's unit vector.
        value: [f64; 3],
        /// Angular tolerance in radians.
        angle_tol: f64,
    },
    /// A kd-tree traversal: the leaves reached, in order, graded leaf by leaf up to the first
    /// divergence (numbers within 10⁻⁶, `inf` exactly).
    Trace {
        /// The key's leaves.
        leaves: Vec<ExpectedLeaf>,
        /// The plane crossings of the key's trace (`"y = 3"`, t), used to explain a wrong bound.
        planes: Vec<(String, f64)>,
    },
    /// One word out of a few (`"yes"`, `"no"`, `"impractical"`), compared case-insensitively.
    /// The file may give it as `a = "no"` or `a = { answer = "no", why = "..." }`; the `why` is
    /// echoed in the feedback, never graded.
    Choice {
        /// The key's word.
        value: &'static str,
    },
    /// Any vector pointing within `angle_tol` radians of `value`, whatever its length (for
    /// recognising wrong answers whose length is also off).
    Parallel {
        /// A unit vector along the direction.
        value: [f64; 3],
        /// Angular tolerance in radians.
        angle_tol: f64,
    },
}

/// One leaf of a traversal: its path from the root (`["x>=3", "y<3"]`) and its t-interval.
#[derive(Debug, Clone, PartialEq)]
pub struct ExpectedLeaf {
    /// Branch conditions from the root.
    pub path: Vec<String>,
    /// Where the ray enters the leaf.
    pub t_min: f64,
    /// Where it leaves (`+∞` for an unbounded cell).
    pub t_max: f64,
}

/// A wrong answer we expect students to give, with its own message and partial credit.
#[derive(Debug, Clone, PartialEq)]
pub struct MalRule {
    /// The wrong value it recognises (compared with the part's own tolerance).
    pub value: Expected,
    /// What went wrong, in one line.
    pub message: &'static str,
    /// Fraction of the part's points it still earns (0 to 1).
    pub credit: f64,
}

/// One gradable part of a question: `key` is the TOML path (`q2a.t`).
#[derive(Debug, Clone, PartialEq)]
pub struct Part {
    /// TOML path of the answer: table and key (`"q2a.t"`).
    pub key: &'static str,
    /// What the student is asked, in one line.
    pub prompt: &'static str,
    /// Points for a correct answer.
    pub points: f64,
    /// The key's answer and comparison.
    pub expected: Expected,
    /// Recognised wrong answers.
    pub mal_rules: Vec<MalRule>,
    /// Where the notes explain it (a path inside the rustdoc, e.g. `hw3/q2_ray_sphere/index.html`).
    pub explained_in: &'static str,
}

/// A question variant: its parameters in words and its parts.
#[derive(Debug, Clone, PartialEq)]
pub struct Variant {
    /// Question id (`"q2"`).
    pub question: &'static str,
    /// The seed it came from (0 = the homework's own numbers, or the notes' worked example).
    pub seed: u64,
    /// The question with its numbers, as markdown.
    pub statement: String,
    /// Its parts, in order.
    pub parts: Vec<Part>,
}

/// The questions the checker grades, in order.
pub const QUESTIONS: [&str; 4] = ["q2", "q3", "q4", "q5"];

/// The variant of `question` for `seed`.
///
/// # Errors
/// [`CheckError::UnknownQuestion`] for a question id not in [`QUESTIONS`].
///
/// # Examples
/// ```
/// let variant = hw3::checker::variant("q2", 0).unwrap();
/// assert!(variant.parts.iter().any(|p| p.key == "q2a.t"));
/// ```
pub fn variant(question: &str, seed: u64) -> Result<Variant, CheckError> {
    match question {
        "q2" => Ok(q2::variant(seed)),
        "q3" => Ok(q3::variant(seed)),
        "q4" => Ok(q4::variant(seed)),
        "q5" => Ok(q5::variant(seed)),
        other => Err(CheckError::UnknownQuestion(other.to_string())),
    }
}

/// Why an answers file could not be graded at all (exit status 2; nothing graded).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CheckError {
    /// Not valid TOML; the parser's message includes line and column.
    #[error("not valid TOML: {0}")]
    Syntax(String),
    /// A value has the wrong type or is not finite.
    #[error("`{key}`: {problem}")]
    BadValue {
        /// The TOML path.
        key: String,
        /// What is wrong with it.
        problem: String,
    },
    /// `[meta] seed` is not a non-negative integer.
    #[error("`meta.seed` must be an integer from 0 to 2^63, got {0}")]
    BadSeed(String),
    /// A question id the checker does not know.
    #[error("unknown question `{0}`; known: q2, q3, q4, q5")]
    UnknownQuestion(String),
}

/// Verdict on one part.
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

fn read_seed(table: &toml::Table) -> Result<u64, CheckError> {
    match table.get("meta").and_then(|m| m.get("seed")) {
        None => Ok(0),
        Some(toml::Value::Integer(i)) if *i >= 0 => Ok(*i as u64),
        Some(other) => Err(CheckError::BadSeed(other.to_string())),
    }
}

fn lookup<'a>(table: &'a toml::Table, key: &str) -> Option<&'a toml::Value> {
    let (section, name) = key.split_once('.')?;
    table.get(section)?.get(name)
}

/// An answer read from the file, shaped like the part's expected value.
#[derive(Debug, Clone, PartialEq)]
enum Given {
    Number(f64),
    Vector([f64; 3]),
    Trace(Vec<ExpectedLeaf>),
    Choice { answer: String, why: Option<String> },
}

fn read_choice(key: &str, value: &toml::Value) -> Result<Given, CheckError> {
    let bad = |problem: String| CheckError::BadValue { key: key.to_string(), problem };
    let text = |v: &toml::Value| v.as_str().map(|s| s.trim().to_lowercase());
    match value {
        toml::Value::String(_) => Ok(Given::Choice { answer: text(value).unwrap_or_default(), why: None }),
        toml::Value::Table(table) => {
            let answer =
                table.get("answer").and_then(text).ok_or_else(|| bad("needs answer = \"yes\" or \"no\"".into()))?;
            let why = match table.get("why") {
                None => None,
                Some(toml::Value::String(why)) => Some(why.clone()),
                Some(other) => return Err(bad(format!("`why` must be a string, got {}", other.type_str()))),
            };
            Ok(Given::Choice { answer, why })
        }
        other => Err(bad(format!("expected \"yes\", \"no\" or \"impractical\", got {} `{other}`", other.type_str()))),
    }
}

/// A t bound: a number, or the string `"inf"`.
fn bound(key: &str, value: Option<&toml::Value>) -> Result<f64, CheckError> {
    match value {
        Some(toml::Value::String(s)) if s == "inf" => Ok(f64::INFINITY),
        Some(other) => number(key, other),
        None => Err(CheckError::BadValue { key: key.to_string(), problem: "each leaf needs tmin and tmax".into() }),
    }
}

fn read_trace(key: &str, value: &toml::Value) -> Result<Vec<ExpectedLeaf>, CheckError> {
    let bad = |problem: String| CheckError::BadValue { key: key.to_string(), problem };
    let toml::Value::Array(items) = value else {
        return Err(bad(format!("expected an array of leaves, got {} `{value}`", value.type_str())));
    };
    items
        .iter()
        .map(|item| {
            let leaf = item.as_table().ok_or_else(|| bad("each leaf is a table { path, tmin, tmax }".into()))?;
            let path = leaf
                .get("path")
                .and_then(toml::Value::as_array)
                .ok_or_else(|| bad("each leaf needs path = [\"x>=3\", ...]".into()))?
                .iter()
                .map(|b| {
                    b.as_str().map(str::to_owned).ok_or_else(|| bad("path entries are strings like \"y<1\"".into()))
                })
                .collect::<Result<Vec<_>, _>>()?;
            Ok(ExpectedLeaf { path, t_min: bound(key, leaf.get("tmin"))?, t_max: bound(key, leaf.get("tmax"))? })
        })
        .collect()
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

fn number(key: &str, value: &toml::Value) -> Result<f64, CheckError> {
    let x = match value {
        toml::Value::Float(x) => *x,
        toml::Value::Integer(i) => *i as f64,
        other => {
            let problem = format!("expected a number, got {} `{other}`", other.type_str());
            return Err(CheckError::BadValue { key: key.to_string(), problem });
        }
    };
    if x.is_finite() {
        Ok(x)
    } else {
        Err(CheckError::BadValue { key: key.to_string(), problem: format!("must be finite, got {x}") })
    }
}

fn read_value(key: &str, value: &toml::Value, expected: &Expected) -> Result<Given, CheckError> {
    match expected {
        Expected::Number { .. } => number(key, value).map(Given::Number),
        Expected::Trace { .. } => read_trace(key, value).map(Given::Trace),
        Expected::Choice { .. } => read_choice(key, value),
        Expected::Vector { .. } | Expected::Direction { .. } | Expected::Parallel { .. } => {
            let bad = |problem: String| CheckError::BadValue { key: key.to_string(), problem };
            let toml::Value::Array(items) = value else {
                return Err(bad(format!("expected an array of 3 numbers, got {} `{value}`", value.type_str())));
            };
            if items.len() != 3 {
                return Err(bad(format!("expected 3 numbers, got {}", items.len())));
            }
            let mut out = [0.0; 3];
            for (slot, item) in out.iter_mut().zip(items) {
                *slot = number(key, item)?;
            }
            Ok(Given::Vector(out))
        }
    }
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

fn unknown_keys(table: &toml::Table, parts: &[&Part]) -> Vec<String> {
    let known: Vec<&str> = parts.iter().map(|p| p.key).collect();
    let mut unknown = Vec::new();
    for (section, value) in table {
        if section == "meta" {
            continue;
        }
        let Some(inner) = value.as_table() else {
            unknown.push(format!("`{section}` (answers go in tables such as [q2a])"));
            continue;
        };
        for name in inner.keys() {
            let key = format!("{section}.{name}");
            if known.contains(&key.as_str()) {
                continue;
            }
            let suggestion =
                known.iter().min_by_key(|k| edit_distance(k, &key)).filter(|k| edit_distance(k, &key) <= 3);
            unknown.push(match suggestion {
                Some(s) => format!("`{key}` (did you mean `{s}`?)"),
                None => format!("`{key}`"),
            });
        }
    }
    unknown
}

/// Levenshtein distance, for "did you mean" suggestions.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut previous = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let substitution = previous + usize::from(ca != cb);
            previous = row[j + 1];
            row[j + 1] = substitution.min(row[j] + 1).min(previous + 1);
        }
    }
    row[b.len()]
}

/// A blank answers file for `seed`: every question's statement as comments, every key present
/// but commented out, with its tolerance.
///
/// # Examples
/// ```
/// let blank = hw3::checker::template(0).unwrap();
/// assert!(blank.contains("# t = "));
/// let report = hw3::checker::check(&blank, None).unwrap();
/// assert_eq!(report.score, 0.0);
/// ```
///
/// # Errors
/// Never for the built-in questions; the `Result` covers future question ids.
pub fn template(seed: u64) -> Result<String, CheckError> {
    let mut out = format!("# hw3 answers file. Grade it with: hw3 check FILE\n[meta]\nseed = {seed}\n");
    for question in QUESTIONS {
        let variant = variant(question, seed)?;
        out.push('\n');
        for line in variant.statement.lines() {
            let _ = writeln!(out, "# {line}");
        }
        let mut section = "";
        for part in &variant.parts {
            let (table, name) = part.key.split_once('.').unwrap_or((part.key, ""));
            if table != section {
                let _ = writeln!(out, "\n[{table}]");
                section = table;
            }
            let shape = match part.expected {
                Expected::Number { rtol, .. } => format!("a number; relative tolerance {rtol:.0e}"),
                Expected::Vector { .. } => "[x, y, z]".to_string(),
                Expected::Direction { angle_tol, .. } | Expected::Parallel { angle_tol, .. } => {
                    format!("[x, y, z], unit length, within {angle_tol:.0e} rad")
                }
                Expected::Trace { .. } => "[{ path = [...], tmin = N, tmax = N or \"inf\" }, ...]".to_string(),
                Expected::Choice { .. } => {
                    "\"yes\", \"no\" or \"impractical\"; or { answer = ..., why = \"...\" }".to_string()
                }
            };
            let _ = writeln!(out, "# {} ({shape}, {} points)\n# {name} = ", part.prompt, part.points);
        }
    }
    Ok(out)
}

/// The key itself as an answers file (what a perfect student would submit).
///
/// # Errors
/// Never for the built-in questions.
///
/// # Examples
/// ```
/// assert!(hw3::checker::answers_key(3).unwrap().contains("seed = 3"));
/// ```
pub fn answers_key(seed: u64) -> Result<String, CheckError> {
    let mut out = format!("[meta]\nseed = {seed}\n");
    for question in QUESTIONS {
        out.push_str(&answers_key_for(question, seed)?);
    }
    Ok(out)
}

/// The key's tables for one question (no `[meta]`).
///
/// # Errors
/// [`CheckError::UnknownQuestion`] for an unknown question id.
///
/// # Examples
/// ```
/// assert!(hw3::checker::answers_key_for("q3", 0).unwrap().contains("[q3d]"));
/// ```
pub fn answers_key_for(question: &str, seed: u64) -> Result<String, CheckError> {
    let mut out = String::new();
    let mut section = "";
    for part in variant(question, seed)?.parts {
        let (table, name) = part.key.split_once('.').unwrap_or((part.key, ""));
        if table != section {
            let _ = writeln!(out, "\n[{table}]");
            section = table;
        }
        let value = match part.expected {
            Expected::Number { value, .. } => format!("{value:?}"),
            Expected::Vector { value, .. } | Expected::Direction { value, .. } | Expected::Parallel { value, .. } => {
                format!("[{:?}, {:?}, {:?}]", value[0], value[1], value[2])
            }
            Expected::Choice { value } => format!("{value:?}"),
            Expected::Trace { leaves, .. } => {
                let bound = |t: f64| if t.is_infinite() { "\"inf\"".to_string() } else { format!("{t:?}") };
                let rows: Vec<String> = leaves
                    .iter()
                    .map(|l| {
                        let path: Vec<String> = l.path.iter().map(|p| format!("{p:?}")).collect();
                        format!(
                            "  {{ path = [{}], tmin = {}, tmax = {} }},",
                            path.join(", "),
                            bound(l.t_min),
                            bound(l.t_max)
                        )
                    })
                    .collect();
                format!("[\n{}\n]", rows.join("\n"))
            }
        };
        let _ = writeln!(out, "{name} = {value}");
    }
    Ok(out)
}

/// The report as plain text: one line per part, then the total.
///
/// # Examples
/// ```
/// let report = hw3::checker::check("", None).unwrap();
/// assert!(hw3::checker::report_text(&report).contains("missing"));
/// ```
#[must_use]
pub fn report_text(report: &Report) -> String {
    let mut out = format!("variant seed {}\n", report.seed);
    for part in &report.parts {
        let mark = match part.status {
            "correct" => "✓",
            "partial" => "~",
            _ => "✗",
        };
        let _ = writeln!(out, "{mark} {:<26} {:>5.2}/{:<4} {}", part.key, part.score, part.max_score, part.status);
        if part.status != "correct" {
            let given = part.given.as_deref().unwrap_or("—");
            let _ = writeln!(out, "    given {given}, expected {}\n    {}", part.expected, part.feedback);
            let _ = writeln!(out, "    explained in {}", part.explained_in);
        }
    }
    for key in &report.unknown_keys {
        let _ = writeln!(out, "? unknown key {key}: not graded");
    }
    let _ = write!(out, "score {:.2} / {:.2} over {} parts", report.score, report.max_score, report.parts.len());
    out
}

/// The report in Gradescope's autograder `results.json` shape (one test per part).
///
/// # Examples
/// ```
/// let report = hw3::checker::check("", None).unwrap();
/// let json = hw3::checker::report_gradescope(&report);
/// assert_eq!(json["tests"][0]["name"], "q2a.t");
/// ```
#[must_use]
pub fn report_gradescope(report: &Report) -> serde_json::Value {
    let tests: Vec<serde_json::Value> = report
        .parts
        .iter()
        .map(|p| {
            serde_json::json!({
                "name": p.key,
                "score": p.score,
                "max_score": p.max_score,
                "status": if p.status == "correct" { "passed" } else { "failed" },
                "output": format!("{}: given {}, expected {}. {}", p.status, p.given.as_deref().unwrap_or("—"), p.expected, p.feedback),
                "visibility": "visible",
            })
        })
        .collect();
    serde_json::json!({ "score": report.score, "output": format!("variant seed {}", report.seed), "tests": tests })
}

#[cfg(test)]
mod tests {
    use super::*;
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
    fn misspelt_key_gets_a_suggestion() {
        let report = check("[q2a]\npiont = [1, 2, 3]\n[q2c]\nt_closet = 5.0\nwhatever = 1", None).unwrap();
        assert_eq!(
            report.unknown_keys,
            vec![
                "`q2a.piont` (did you mean `q2a.point`?)".to_string(),
                "`q2c.t_closet` (did you mean `q2c.t_closest`?)".to_string(),
                "`q2c.whatever`".to_string(),
            ]
        );
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

    /// Value stability: seeds 1–5 of every question, statement and key, pinned (a change here
    /// changes every student's variant).
    #[test]
    fn variants_are_pinned_for_seeds_1_to_5() {
        for question in QUESTIONS {
            let text: String = (1..=5)
                .map(|s| {
                    format!(
                        "{}\n-- key --\n{}\n",
                        variant(question, s).unwrap().statement,
                        answers_key_for(question, s).unwrap()
                    )
                })
                .collect();
            let name = format!("checker_{question}_variants");
            crate::test_support::insta_settings().bind(|| insta::assert_snapshot!(name, text));
        }
    }

    #[test]
    fn edit_distance_basics() {
        assert_eq!(edit_distance("kitten", "sitting"), 3);
        assert_eq!(edit_distance("", "abc"), 3);
        assert_eq!(edit_distance("same", "same"), 0);
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
