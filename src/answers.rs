//! The printed answers of one question: the type every question's `answers()` returns and
//! `hw3 answers` prints.
//!
//! It lives in the core, below the question modules, so that a question names it without importing
//! the crate root (which imports every question back).

/// One question's printed answers, as `hw3 answers` shows them.
///
/// # Examples
/// ```
/// let q2 = hw3::q2_ray_sphere::answers();
/// assert_eq!(q2.question, "q2");
/// assert!(q2.text.lines().count() > 1);
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Answers {
    /// The question id (`"q2"`).
    pub question: &'static str,
    /// The homework's title for it.
    pub title: &'static str,
    /// The answers, as plain text with one claim per line.
    pub text: String,
}
