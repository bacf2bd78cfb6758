//! Why an answers file cannot be graded at all.

/// Why an answers file could not be graded at all (exit status 2; nothing graded).
///
/// # Examples
/// ```
/// use hw3::checker::{CheckError, check};
/// assert!(matches!(check("[meta]\nseed = -1", None), Err(CheckError::BadSeed(_))));
/// assert!(matches!(check("[q2a]\nt = \"three\"", None), Err(CheckError::BadValue { .. })));
/// ```
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
    #[error("unknown question `{0}`; known: q1, q2, q3, q4, q5")]
    UnknownQuestion(String),
}
