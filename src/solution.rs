//! Worked solutions: every intermediate number of a checker variant, in the order a student writes
//! it, ending in the final answers the checker grades.
//!
//! A solution is computed, never typed: the variant's setting comes from
//! [`checker::variant`], every step from the functions the checker's key
//! is built from (Q1's laws of clutter, fog, mirrors and motion, the stable ray/sphere solver and the homework's own `A, B, C` algorithm for Q2,
//! the kd-tree traversal and its interval rule for Q3, the analytic sky and the blind-spot
//! formulas for Q4, the light-path decision of each table cell for Q5). The tests check, for
//! seeds 0 to 20, that every final number equals the key, and that the solution written as an
//! answers file, with the digits it prints, grades full marks.
//!
//! `hw3 solution --seed S [--question qN] [--format text|markdown]` prints it; seed 0 is the
//! homework's own numbers where it has them (Q3), and fixed numbers elsewhere (Q1: the renderer's
//! scenes; Q2: e = (−5, 1, 0), d = (1, 0, 0), a sphere of radius 2 at the origin; Q4: L = 1 + ω_z,
//! a 60° tilt, D = 3R). The printable answer key of the notes, [`crate::notes::answer_key`], is
//! drawn from the same solutions.
//!
//! # Examples
//! ```
//! use hw3::solution::{Format, Value, solution};
//! let q2 = solution("q2", 0).unwrap();
//! let t = q2.answers().find(|a| a.key == "q2a.t").unwrap();
//! assert!(matches!(t.value, Value::Number(t) if (t - (5.0 - 3f64.sqrt())).abs() < 1e-12));
//! assert!(q2.render(Format::Text).contains("B = 2 f·d = -10"));
//! ```

mod answer_key;
mod q1;
mod q2;
mod q3;
mod q4;
mod q5;
mod text;

pub use answer_key::{answer_key_table, figures};

use crate::checker::{self, CheckError, ExpectedLeaf, ExpectedPlane, Setting};

/// The questions a solution can be asked for, in homework order.
pub const QUESTIONS: [&str; 5] = ["q1", "q2", "q3", "q4", "q5"];

/// How a solution is printed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Plain text for a terminal: one step a line, sections indented.
    Text,
    /// Markdown for a hand-out: a heading per question and per part, a list item per step.
    Markdown,
}

impl std::str::FromStr for Format {
    type Err = SolutionError;

    /// `text` or `markdown`.
    ///
    /// # Examples
    /// ```
    /// use hw3::solution::Format;
    /// assert_eq!("markdown".parse::<Format>().unwrap(), Format::Markdown);
    /// assert!("html".parse::<Format>().is_err());
    /// ```
    fn from_str(text: &str) -> Result<Self, Self::Err> {
        match text {
            "text" => Ok(Self::Text),
            "markdown" => Ok(Self::Markdown),
            other => Err(SolutionError::UnknownFormat(other.to_owned())),
        }
    }
}

/// Why a solution could not be written.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SolutionError {
    /// A question id outside [`QUESTIONS`].
    #[error("unknown question `{0}`; known: q1, q2, q3, q4, q5")]
    UnknownQuestion(String),
    /// A format other than `text` or `markdown`.
    #[error("unknown format `{0}`; known: text, markdown")]
    UnknownFormat(String),
}

/// A final answer's value, as the checker compares it.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// A number.
    Number(f64),
    /// A point or a direction.
    Vector([f64; 3]),
    /// The leaves of a kd-tree traversal, in order.
    Leaves(Vec<ExpectedLeaf>),
    /// One word: `yes`, `no` or `impractical`; Q2's case.
    Word(String),
    /// `true` or `false` (does the ray hit?).
    Flag(bool),
    /// No such value (a ray that does not hit has no first intersection): written `"none"`.
    None,
    /// A formula in the checker's syntax (`2*dot(e - o, d)`).
    Formula(String),
    /// A class of light paths in Heckbert's notation (`LD+E`, or `none`).
    Paths(String),
    /// The planes met in a kd-tree traversal, in order.
    Planes(Vec<ExpectedPlane>),
}

/// A final answer: the part's key in the answers file (`q2a.t`) and its value.
#[derive(Debug, Clone, PartialEq)]
pub struct Answer {
    /// TOML path of the part (`"q2a.t"`).
    pub key: &'static str,
    /// The value the step arrives at.
    pub value: Value,
}

/// One line of working, and the final answer it arrives at, if any.
#[derive(Debug, Clone, PartialEq)]
pub struct Step {
    /// The working, with its numbers (`B = 2 f·d = -10`).
    pub text: String,
    /// The part this step answers.
    pub answer: Option<Answer>,
    /// Nesting depth (0 for a top-level step; a kd-tree node's depth for Q3).
    pub depth: usize,
}

impl Step {
    fn work(text: impl Into<String>) -> Self {
        Self { text: text.into(), answer: None, depth: 0 }
    }

    fn answer(text: impl Into<String>, key: &'static str, value: Value) -> Self {
        Self { text: text.into(), answer: Some(Answer { key, value }), depth: 0 }
    }

    fn at(mut self, depth: usize) -> Self {
        self.depth = depth;
        self
    }
}

/// One part of a question's solution (`(a) the first intersection`).
#[derive(Debug, Clone, PartialEq)]
pub struct Section {
    /// The part's title.
    pub title: String,
    /// The working, in order.
    pub steps: Vec<Step>,
}

/// A question's worked solution for one variant.
#[derive(Debug, Clone, PartialEq)]
pub struct Solution {
    /// The question id (`"q2"`).
    pub question: &'static str,
    /// The variant's seed.
    pub seed: u64,
    /// The question with its numbers, as the checker states it.
    pub statement: String,
    /// Its parts, in order.
    pub sections: Vec<Section>,
}

impl Solution {
    /// Every final answer, in the order the working reaches them.
    pub fn answers(&self) -> impl Iterator<Item = &Answer> {
        self.sections.iter().flat_map(|s| &s.steps).filter_map(|step| step.answer.as_ref())
    }

    /// The solution printed as text or markdown.
    ///
    /// # Examples
    /// ```
    /// use hw3::solution::{Format, solution};
    /// let q4 = solution("q4", 0).unwrap();
    /// assert!(q4.render(Format::Markdown).starts_with("## Q4"));
    /// ```
    #[must_use]
    pub fn render(&self, format: Format) -> String {
        text::solution(self, format)
    }

    /// The final answers as an answers file (`hw3 check` reads it), with the digits the solution
    /// prints: what a student who copies the solution would hand in.
    ///
    /// # Examples
    /// ```
    /// let q3 = hw3::solution::solution("q3", 0).unwrap();
    /// let file = format!("[meta]\nseed = 0\n{}", q3.answers_toml());
    /// let report = hw3::checker::check(&file, None).unwrap();
    /// assert!(report.parts.iter().filter(|p| p.key.starts_with("q3")).all(|p| p.status == "correct"));
    /// ```
    #[must_use]
    pub fn answers_toml(&self) -> String {
        text::answers_toml(self)
    }
}

/// The worked solution of `question` for variant `seed`.
///
/// # Errors
/// [`SolutionError::UnknownQuestion`] for a question outside [`QUESTIONS`].
///
/// # Examples
/// ```
/// let q5 = hw3::solution::solution("q5", 0).unwrap();
/// // 12 table cells, each with its reason, and the 6 effects' path classes.
/// assert_eq!(q5.answers().count(), 12 + 12 + 6);
/// assert!(hw3::solution::solution("q7", 0).is_err());
/// ```
pub fn solution(question: &str, seed: u64) -> Result<Solution, SolutionError> {
    let variant = checker::variant(question, seed).map_err(|e| match e {
        CheckError::UnknownQuestion(q) => SolutionError::UnknownQuestion(q),
        other => SolutionError::UnknownQuestion(other.to_string()),
    })?;
    let sections = match &variant.setting {
        Setting::Q1(numbers) => q1::sections(numbers),
        Setting::Q2 { ray, sphere } => q2::sections(ray, sphere),
        Setting::Q3 { d, e } => q3::sections(*d, *e),
        Setting::Q4(setting) => q4::sections(setting),
        Setting::Q5 => q5::sections(&variant),
    };
    Ok(Solution { question: variant.question, seed, statement: variant.statement, sections })
}

/// What `hw3 solution` prints: one question's solution, or every question's in order.
///
/// # Errors
/// As [`solution`].
///
/// # Examples
/// ```
/// use hw3::solution::{Format, command};
/// let all = command(None, 3, Format::Text).unwrap();
/// assert!(all.contains("Q2 (variant 3)") && all.contains("Q5"));
/// ```
pub fn command(question: Option<&str>, seed: u64, format: Format) -> Result<String, SolutionError> {
    let questions: Vec<&str> = question.map_or_else(|| QUESTIONS.to_vec(), |q| vec![q]);
    let texts: Vec<String> =
        questions.iter().map(|q| solution(q, seed).map(|s| s.render(format))).collect::<Result<_, _>>()?;
    Ok(texts.join("\n").trim_end().to_owned())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_question_has_a_solution() {
        for question in QUESTIONS {
            let s = solution(question, 0).unwrap();
            assert!(!s.sections.is_empty(), "{question}");
        }
    }

    #[test]
    fn unknown_question_is_an_error_naming_it() {
        assert_eq!(solution("q9", 0), Err(SolutionError::UnknownQuestion("q9".into())));
        assert!(command(Some("Q2"), 0, Format::Text).unwrap_err().to_string().contains("`Q2`"));
    }

    /// Seed 0 of every question, as text and as markdown, pinned (a change here changes the
    /// printed key).
    #[test]
    fn seed_zero_solutions_are_pinned() {
        let text = command(None, 0, Format::Text).unwrap();
        let markdown = command(None, 0, Format::Markdown).unwrap();
        crate::testing::insta_settings().bind(|| {
            insta::assert_snapshot!("solution_seed0_text", text);
            insta::assert_snapshot!("solution_seed0_markdown", markdown);
        });
    }
}
