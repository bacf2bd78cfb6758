//! The questions the checker knows, and their variants by seed.

use super::error::CheckError;
use super::key::Variant;
use super::{q1, q2, q3, q4, q5};

/// The questions the checker grades, in order.
///
/// # Examples
/// ```
/// for question in hw3::checker::QUESTIONS {
///     assert!(hw3::checker::variant(question, 1).is_ok());
/// }
/// ```
pub const QUESTIONS: [&str; 5] = ["q1", "q2", "q3", "q4", "q5"];

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
        "q1" => Ok(q1::variant(seed)),
        "q2" => Ok(q2::variant(seed)),
        "q3" => Ok(q3::variant(seed)),
        "q4" => Ok(q4::variant(seed)),
        "q5" => Ok(q5::variant(seed)),
        other => Err(CheckError::UnknownQuestion(other.to_string())),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::checker::answers_key_for;

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
}
